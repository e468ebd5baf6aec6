#include "energy.hpp"

#include <algorithm>
#include <cmath>

namespace rk {

Energies compute_energies(const Model& md, const State& st, const std::vector<double>& v_old, const Comm& comm) {
  Energies e;  // this rank's shares: its owned particles' kinetic energy, its points' internal energy
  e.internal = st.viscous_work;  // the bulk viscosity's work is dissipated
  e.external = st.external_work;
  for (std::size_t I = 0; I < md.n; ++I) {
    if (!md.owned[I]) continue;
    double v2 = 0;
    for (int i = 0; i < 3; ++i) {
      const double vb = 0.5 * (v_old[3 * I + i] + st.v[3 * I + i]);
      v2 += vb * vb;
    }
    e.kinetic += 0.5 * md.mass[I] * v2;
  }
  for (std::size_t g = 0; g < md.m; ++g) {
    e.internal += md.weight[g] * (st.psi[g] + st.wp[g]);
    e.plastic += md.weight[g] * st.wp[g];
  }
  double sums[4] = {e.kinetic, e.internal, e.plastic, e.external};  // one reduction
  comm.sum(sums, 4);
  e.kinetic = sums[0], e.internal = sums[1], e.plastic = sums[2], e.external = sums[3];
  return e;
}

double energy_error(const Energies& e, double kinetic0) {
  const double scale = std::max({kinetic0, std::abs(e.external), std::abs(e.contact)});
  if (!(scale > 0)) return 0.0;
  return std::abs(e.kinetic + e.internal - kinetic0 - e.external - e.contact) / scale;
}

}  // namespace rk
