// What every rank must agree on before a step: the step's one reduction (a max over ranks). The
// stable step and the force bound limit the step; the rest are flags and measures that decide what
// the next steps do (a checkpoint, a reference update, a stop).
#pragma once
#include <limits>

#include "parallel/comm.hpp"

namespace rk {

struct StepLimits {
  double dt = 0;                  // the stable step, min over ranks (s)
  double penalty_dt = std::numeric_limits<double>::infinity();  // after a reference update, the contact's step, min over ranks (s; infinite: dt)
  double force_bound = 0;         // the largest force contribution to one particle (fixed-point scale)
  double contact_bound = 0;       // the largest contact force contribution (<= force_bound)
  bool unhealthy = false;         // a rank's stress update or forces are not physical
  bool checkpoint_clock = false;  // rank 0's wall clock says a checkpoint is due
  double strain_since_update = 0; // largest Green strain since the last reference update
  double symmetry_depth = 0;      // material past a symmetry plane, in smallest spacings
  double pressure_ratio = 0;      // largest |p| / (rho0 c_L v_max + sigma_y)
  bool interrupted = false;       // a rank received SIGINT or SIGTERM
  double reaction_bound = 0;      // the largest contribution to a press-driven die's reaction (its fixed-point scale)
  double cell_dt_ceiling = 0;     // multi-rate steps: at or above every cell's own stable step (s)

  // Collective: the limits of all ranks, in one reduction.
  void reduce(const Comm& comm) {
    double r[12] = {-dt, force_bound, unhealthy ? 1.0 : 0.0, checkpoint_clock ? 1.0 : 0.0, strain_since_update,
                    symmetry_depth, pressure_ratio, interrupted ? 1.0 : 0.0, reaction_bound, contact_bound, -penalty_dt,
                    cell_dt_ceiling};
    comm.max(r, 12);
    dt = -r[0], force_bound = r[1], unhealthy = r[2] > 0, checkpoint_clock = r[3] > 0;
    strain_since_update = r[4], symmetry_depth = r[5], pressure_ratio = r[6], interrupted = r[7] > 0;
    reaction_bound = r[8], contact_bound = r[9], penalty_dt = -r[10], cell_dt_ceiling = r[11];
  }
};

}  // namespace rk
