// Checkpoint and restart: each rank writes the STATE it needs to continue (never the offline data:
// neighbours and shape functions are rebuilt from the subdomain file) to CASE/checkpoint/rank_NNNN.h5,
// atomically (temporary name, fsync, rename), so a crash leaves the previous good checkpoint. A
// restarted run continues bitwise as the uninterrupted run would have. Each rank keeps its newest
// checkpoint and the one before (rank_NNNN.h5.previous): a job killed while its ranks were writing
// can leave one rank a checkpoint behind the others, and the restart takes the newest step that
// every rank holds.
#pragma once
#include <string>
#include <vector>

#include "contact/die_contact.hpp"
#include "model.hpp"
#include "parallel/comm.hpp"
#include "state.hpp"

namespace rk {

// The layout of the checkpoint files: a reader refuses another.
inline constexpr std::int64_t kCheckpointFormat = 10;

// What the time loop carries besides the State.
struct RunClock {
  double next_output = 0, next_history = 0, dt_stable = 0, kinetic0 = 0, last_error = 0, max_ke_ratio = 0;
  double max_error = 0;  // the largest energy error of the run so far
  double energy_scale = 0;  // the energy error's scale so far (energy_error)
  double max_ke_ratio_late = 0;  // the largest kinetic / internal energy over the run's second half
  double max_pressure_ratio = 0;  // the largest |p| / (rho0 c_L v_max + sigma_y) so far (PressureBound)
  // the smallest unclipped global stable step since the start or the last reference update (-1 just
  // after one: the next step's): sets the penalty stiffness
  double dt_penalty = 0;
  std::int64_t frames = 0;
};

std::string checkpoint_path(const std::string& case_dir, int rank);

// A new run (not a restart) removes this rank's checkpoints of an earlier run: a later --restart
// must not take the earlier run's newer step for this run's.
void remove_checkpoints(const std::string& case_dir, int rank);

// Collective: the file this rank restarts from, the newest checkpoint step held by every rank.
// One clear error on every rank when there is none.
std::string restart_checkpoint(const std::string& case_dir, const Comm& comm);

// `dies`: their totals (work, heat) and the die triangles this rank's material has touched.
void write_checkpoint(const std::string& case_dir, const Model& md, const State& st, const RunClock& clock,
                      const DieContact& dies);

// A stage of a chain (stage.hpp) reads the previous case's checkpoint, whose dies are not this
// case's: per die of this case the previous case's die it continues (-1: a new die, from rest and
// untouched), and the previous case's triangle count per die.
struct DieCarry {
  std::vector<int> continues;
  std::vector<std::size_t> previous_triangles;
};

// Reads a checkpoint of this rank into st/clock/dies; checks it belongs to this model. After reference
// updates it also sets md.point_X and st.u_ref, J_ref (the caller then rebuilds the model). With
// `stage`, the dies' totals and fill are carried by it, a die left out adds its contact work to the
// part's external work (the balance keeps it), and the presses start anew.
void read_checkpoint(const std::string& path, Model& md, State& st, RunClock& clock, DieContact& dies,
                     const DieCarry* stage = nullptr);

}  // namespace rk
