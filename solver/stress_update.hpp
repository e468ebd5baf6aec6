// Pointwise material update at the integration points, with the F-bar treatment of the volumetric
// part (de Souza Neto et al. 1996): the material sees Fbar = (Jbar/J)^{1/3} F with Jbar the cell
// average of det F, which removes volumetric locking of isochoric plastic flow. The stress entering
// the internal force is the variationally consistent one,
//   tau_eff = dev(tau(Fbar)) + J p_c I,   p_c = sum_g w_g tr(tau_g)/3 / sum_g w_g J_g  (per cell),
//   P = tau_eff F^{-T},
// so that sum_g w_g P : dF equals the rate of the stored energy plus dissipation (energy closes).
// The points of a cell go through the material update kLanes at a time (material/lanes.hpp); without
// F-bar (volumetric: none, one point per cell, nodal integration) kLanes consecutive points at a time.
#pragma once
#include "model.hpp"
#include "state.hpp"

namespace rk {

// The material's volume ratio J below which (or above whose inverse) the state is not physical.
inline constexpr double kMinVolumeRatio = 0.5;

struct StressHealth {
  bool ok = true;
  std::size_t point = 0;  // first failing point
  double J = 1;
  std::size_t plastic = 0;  // points that returned to the yield surface (for the bench's flop count)
};

StressHealth update_stress(const Model& md, State& st);

}  // namespace rk
