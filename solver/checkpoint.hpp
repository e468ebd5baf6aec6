// Checkpoint and restart: each rank writes the STATE it needs to continue (never the offline data:
// neighbours and shape functions are rebuilt from the subdomain file) to CASE/checkpoint/rank_NNNN.h5,
// atomically (temporary name, fsync, rename), so a crash leaves the previous good checkpoint. A
// restarted run continues bitwise as the uninterrupted run would have.
#pragma once
#include <string>
#include <vector>

#include "contact/die_contact.hpp"
#include "model.hpp"
#include "state.hpp"

namespace rk {

// What the time loop carries besides the State.
struct RunClock {
  double next_output = 0, next_history = 0, dt_stable = 0, kinetic0 = 0, last_error = 0, max_ke_ratio = 0;
  std::int64_t frames = 0;
};

std::string checkpoint_path(const std::string& case_dir, int rank);

void write_checkpoint(const std::string& case_dir, const Model& md, const State& st, const RunClock& clock,
                      const std::vector<DieTotals>& dies);

// Reads this rank's checkpoint into st/clock/dies; checks it belongs to this model. After reference
// updates it also sets md.point_X and st.u_ref, J_ref (the caller then rebuilds the model).
void read_checkpoint(const std::string& case_dir, Model& md, State& st, RunClock& clock,
                     std::vector<DieTotals>& dies);

}  // namespace rk
