#include "energy.hpp"

#include <algorithm>
#include <cmath>

namespace rk {

Energies compute_energies(const Model& md, const State& st, const std::vector<double>& v_old, const Comm& comm) {
  // this rank's shares, summed in one reduction: kinetic (its owned particles), internal (its points'
  // stored and plastic work, with the bulk viscosity's dissipated work and the stress's work on the
  // thermal strain), plastic work, external work
  double e[6] = {0, st.viscous_work + st.thermal_work, 0, st.external_work, st.thermal_work, 0};
  for (std::size_t I = 0; I < md.n; ++I) {
    if (!md.owned[I]) continue;
    double v2 = 0, vv = 0;
    for (int i = 0; i < 3; ++i) {
      const double vb = 0.5 * (v_old[3 * I + i] + st.v[3 * I + i]);
      v2 += vb * vb;
      vv += v_old[3 * I + i] * st.v[3 * I + i];
    }
    e[0] += 0.5 * md.mass[I] * v2;
    e[5] += 0.5 * md.mass[I] * vv;
  }
  for (std::size_t g = 0; g < md.m; ++g) {
    e[1] += md.weight[g] * (st.psi[g] + st.wp[g]);
    e[2] += md.weight[g] * st.wp[g];
  }
  comm.sum(e, 6);
  Energies out;
  out.kinetic = e[0], out.internal = e[1], out.plastic = e[2], out.external = e[3], out.thermal = e[4];
  out.kinetic_step = e[5];
  return out;
}

double energy_error(const Energies& e, double kinetic0, double& scale) {
  scale = std::max({scale, kinetic0, std::abs(e.external), std::abs(e.contact), std::abs(e.thermal)});
  if (!(scale > 0)) return 0.0;
  return std::abs(e.kinetic_step + e.internal - kinetic0 - e.external - e.contact) / scale;
}

}  // namespace rk
