// Energy monitor (docs/scene.md, "Energy"): kinetic, internal (stored elastic + plastic work, from
// the material state, not from the forces, + the bulk viscosity's work + the stress's work on the
// thermal strain) and the work of the boundary forces; see energy_error().
#pragma once
#include <vector>

#include "model.hpp"
#include "parallel/comm.hpp"
#include "state.hpp"

namespace rk {

struct Energies {
  double kinetic = 0, internal = 0, plastic = 0, external = 0;
  // sum m v^{n-1/2} . v^{n+1/2} / 2: the kinetic part of the energy the central difference conserves
  // (with the strain energy, exactly for a linear system); the balance takes it (docs/decisions.md,
  // "The energy balance: the central difference's own kinetic energy, the largest scale so far")
  double kinetic_step = 0;
  double contact = 0;  // work of the contact forces on the material they hold (set by the caller)
  double thermal = 0;  // the stress's work on the thermal strain (in internal)
};

// This rank's shares at time t^n (its owned particles, its points); kinetic energy from
// vbar = (v^{n-1/2} + v^{n+1/2}) / 2, kinetic_step from v^{n-1/2} . v^{n+1/2}.
Energies rank_energies(const Model& md, const State& st, const std::vector<double>& v_old);

// Whole-model totals at time t^n: rank_energies summed over the ranks.
Energies compute_energies(const Model& md, const State& st, const std::vector<double>& v_old, const Comm& comm);

// |KE_step + E_int - KE0 - W_ext - W_contact| / scale, the scale the largest of KE0, |W_ext|, |W_contact|
// and |W_thermal| so far: the energy put in sets it (a thermal strain puts energy in as a load does), and
// it keeps its largest value, as a load that is taken off again leaves its error in the balance.
// `scale` carries it from row to row (0 at the start).
double energy_error(const Energies& e, double kinetic0, double& scale);

}  // namespace rk
