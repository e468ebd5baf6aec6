// Health checks: a state that is not physical, or a run that can never end, stops every rank at the
// step it is found, after a last frame on every rank, with one message that says where and what to
// change. After the step's reduction: a collapsed stable step, material past a symmetry plane, a
// volume ratio or pressure past its bound (material/stress_update.hpp), non-finite forces. At a history row:
// a particle outside the box of the part and the dies, an energy error past its bound (with the
// place of an unstable mode, when there is one).
#pragma once
#include <functional>
#include <string>

#include "contact/die_contact.hpp"
#include "material/stress_update.hpp"
#include "model.hpp"
#include "parallel/comm.hpp"
#include "scene.hpp"
#include "state.hpp"
#include "step_limits.hpp"
#include "time_step.hpp"

namespace rk {

// Collective: writes the last frame on every rank before the stop.
using WriteLastFrame = std::function<void()>;

// The scales the checks measure against, fixed at the start of the run.
struct HealthScales {
  double dt0 = 0;      // the initial stable step (s)
  double h_min = 0;    // the smallest particle spacing (m)
  double v_start = 0;  // the fastest start or tool (m/s)
  double part_lo[3] = {0, 0, 0}, part_hi[3] = {0, 0, 0};  // the part's initial box (m)
};

// "particle 12 at (x, y, z) m": where the material at a local particle is now, for messages.
std::string describe_particle(const Model& md, const State& st, std::int32_t I);

class HealthChecks {
 public:
  HealthChecks(const Scene& scene, const HealthScales& scales) : scene_(scene), scales_(scales) {}
  const HealthScales& scales() const { return scales_; }

  // After the step's reduction (limits are global; stable, stress and healthy, its stress and forces
  // finite, are this rank's).
  void after_reduction(const Model& md, const State& st, const DieContact& dies, const StepLimits& limits,
                       const StableStep& stable, const StressHealth& stress, bool healthy, const Comm& comm,
                       const WriteLastFrame& last_frame) const;
  // After a history row; `started`: past the start-up (the energy check's scale has formed).
  void after_history(const Model& md, const State& st, const DieContact& dies, double energy_error, bool started,
                     const Comm& comm, const WriteLastFrame& last_frame) const;

 private:
  void escaped_particle(const Model& md, const State& st, const DieContact& dies, const Comm& comm,
                        const WriteLastFrame& last_frame) const;
  void energy_runaway(const Model& md, const State& st, double energy_error, const Comm& comm,
                      const WriteLastFrame& last_frame) const;

  const Scene& scene_;
  HealthScales scales_;
};

}  // namespace rk
