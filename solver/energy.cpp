#include "energy.hpp"

#include <algorithm>
#include <cmath>

namespace rk {

Energies rank_energies(const Model& md, const State& st, const std::vector<double>& v_old) {
  // kinetic (the owned particles), internal (the points' stored and plastic work, with the bulk
  // viscosity's dissipated work and the stress's work on the thermal strain), plastic work, external work
  Energies e;
  e.internal = st.viscous_work + st.thermal_work, e.external = st.external_work, e.thermal = st.thermal_work;
  for (std::size_t I = 0; I < md.n; ++I) {
    if (!md.owned[I]) continue;
    double v2 = 0, vv = 0;
    for (int i = 0; i < 3; ++i) {
      const double vb = 0.5 * (v_old[3 * I + i] + st.v[3 * I + i]);
      v2 += vb * vb;
      vv += v_old[3 * I + i] * st.v[3 * I + i];
    }
    e.kinetic += 0.5 * md.mass[I] * v2;
    e.kinetic_step += 0.5 * md.mass[I] * vv;
  }
  for (std::size_t g = 0; g < md.m; ++g) {
    e.internal += md.weight[g] * (st.psi[g] + st.wp[g]);
    e.plastic += md.weight[g] * st.wp[g];
  }
  return e;
}

Energies compute_energies(const Model& md, const State& st, const std::vector<double>& v_old, const Comm& comm) {
  Energies e = rank_energies(md, st, v_old);  // this rank's shares, summed in one reduction
  double sums[6] = {e.kinetic, e.kinetic_step, e.internal, e.plastic, e.external, e.thermal};
  comm.sum(sums, 6);
  e.kinetic = sums[0], e.kinetic_step = sums[1], e.internal = sums[2], e.plastic = sums[3], e.external = sums[4];
  e.thermal = sums[5];
  return e;
}

double energy_error(const Energies& e, double kinetic0, double& scale) {
  scale = std::max({scale, kinetic0, std::abs(e.external), std::abs(e.contact), std::abs(e.thermal)});
  if (!(scale > 0)) return 0.0;
  return std::abs(e.kinetic_step + e.internal - kinetic0 - e.external - e.contact) / scale;
}

}  // namespace rk
