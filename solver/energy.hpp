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
  double contact = 0;  // work of the contact forces on the material they hold (set by the caller)
  double thermal = 0;  // the stress's work on the thermal strain (in internal)
};

// Whole-model totals at time t^n; kinetic energy from vbar = (v^{n-1/2} + v^{n+1/2}) / 2.
Energies compute_energies(const Model& md, const State& st, const std::vector<double>& v_old, const Comm& comm);

// |E(t) - E(0) - W_ext - W_contact| / max(KE0, |W_ext|, |W_contact|, |W_thermal|): the energy put in
// sets the scale (a thermal strain puts energy in as a load does).
double energy_error(const Energies& e, double kinetic0);

}  // namespace rk
