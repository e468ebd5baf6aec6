// Stable time step from the CURRENT configuration (the Taylor bar's falls > 20x while it mushrooms):
// dt = CFL * min over cells of (shortest current cell edge) / (dilatational wave speed at the
// cell's current density), c^2 = (K + 4G/3) / rho, rho = rho0 / Jbar.
#pragma once
#include "model.hpp"
#include "state.hpp"

namespace rk {

struct StableStep {
  double dt;
  std::size_t cell;  // the cell that sets it
};

StableStep stable_time_step(const Model& md, const State& st, double cfl);

}  // namespace rk
