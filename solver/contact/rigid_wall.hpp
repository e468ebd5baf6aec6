// A fixed, frictionless rigid plane met by the particles, imposed kinematically:
// a particle whose next position x + dt v would cross the plane gets the normal velocity that puts
// it exactly on the plane (no penetration, no stiffness, no effect on the stable step). Every copy
// of a shared particle applies the same constraint (identical data, identical result); only the
// owner counts the work of the impulse m dv . vbar, so it is counted once over all ranks.
#pragma once
#include "model.hpp"
#include "scene.hpp"
#include "state.hpp"

namespace rk {

struct WallResult {
  double work = 0;        // work of the wall on the owned particles this step (J)
  double normal_force = 0;  // force of the wall on the owned particles along its normal (N)
  std::int64_t contacts = 0;
};

// A reference update's new position x of a particle whose position is now c: one on the wall stays
// on it, one that would be behind it is put on it.
void project_onto_wall(const RigidWall& wall, const double* c, double* x);

// v_old: velocities before this step's update (for vbar = (v_old + v_new) / 2).
WallResult apply_rigid_wall(const Model& md, State& st, const RigidWall& wall, double dt_next, double dt_avg,
                            const std::vector<double>& v_old);

}  // namespace rk
