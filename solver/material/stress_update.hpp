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
#include <span>

#include "model.hpp"
#include "state.hpp"

namespace rk {

// The material's volume ratio J below which (or above whose inverse) the state is not physical.
inline constexpr double kMinVolumeRatio = 0.5;

// The most points an F-bar cell may hold (a hexahedron at gauss_order 3 holds 27): update_stress keeps
// a cell's batches, and the damage its plastic strain increments, on the stack. rksolve refuses a
// subdomain with more at the start.
inline constexpr std::size_t kMaxCellPoints = 32;

// The pressure's health bound. No metal under an impact at speed v or a tool pressing it carries a
// pressure many times p_ref = rho0 c_L v + sigma_y(ep): the acoustic (shock) pressure of the impact
// plus the flow stress a tool's constraint multiplies. `impact` is rho0 c_L v of the run's fastest
// start or tool (with mass scaling's density: it raises a start's pressure as well); `ratio` the
// multiple of p_ref past which the state is not physical (health.max_pressure_ratio; 0: no bound).
struct PressureBound {
  double impact = 0;  // Pa
  double ratio = 0;
};

struct StressHealth {
  bool ok = true;
  std::size_t point = 0;  // first failing point
  double J = 1;
  std::size_t plastic = 0;  // points that returned to the yield surface (for the bench's flop count)
  double pressure_ratio = 0;  // the largest |p| / p_ref (PressureBound) of the rank's points
  double pressure = 0;  // its pressure (Pa, compression positive, the bulk viscosity's q included)
  bool pressure_stop = false;  // not ok because a pressure passed the bound (point, pressure say where)
  // the largest |F^T F - I|^2 of the points updated (twice the Green strain's norm, squared), where
  // Model::green_strain asks: the reference update's measure, taken here while F is at hand instead of
  // in a pass of its own
  double green_strain2 = 0;
};

StressHealth update_stress(const Model& md, State& st, const PressureBound& bound);
// The same at the listed F-bar cells only (multi-rate steps: the cells due this step; none if empty).
StressHealth update_stress(const Model& md, State& st, const PressureBound& bound, std::span<const std::int32_t> cells);

// v_max: the largest of the initial speed over the part's box [lo, hi] and the speeds of the dies
// and prescribed faces (PressureBound::impact is rho c_L v_max).
double fastest_speed(const Scene& scene, const double lo[3], const double hi[3]);

}  // namespace rk
