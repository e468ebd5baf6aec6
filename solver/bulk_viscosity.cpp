#include "bulk_viscosity.hpp"

#include <cmath>

namespace rk {

void init_bulk_viscosity(const Model& md, State& st, const BulkViscosityCoefficients& k) {
  const bool on = k.quadratic > 0 || k.linear > 0;
  st.q.assign(on ? md.m : 0, 0.0);
  st.dt_factor.assign(on ? md.m : 0, 1.0);
  st.J_last.assign(on ? md.m : 0, 0.0);  // 0: no step taken yet, no rate
}

void update_bulk_viscosity(const Model& md, State& st, const BulkViscosityCoefficients& k) {
  if (st.q.empty()) return;
  const double dt = st.dt_half;
  double work = 0;
  for (std::size_t c = 0; c < md.cells; ++c) {
    const auto g0 = std::size_t(md.cell_points[c]), g1 = std::size_t(md.cell_points[c + 1]);
    double wJ = 0, w = 0;
    if (md.fbar)
      for (auto g = g0; g < g1; ++g) wJ += md.weight[g] * st.total_J(g), w += md.weight[g];
    const double c_wave = std::sqrt(md.wave_modulus * std::max(st.cell_J[c], 1e-12) / md.density);
    double h = 0;  // the particle spacing about the cell: the resolution a shock is spread over
    const auto n0 = md.cell_node_offsets[c], n1 = md.cell_node_offsets[c + 1];
    for (auto k = n0; k < n1; ++k) h += md.spacing0[std::size_t(md.cell_nodes[std::size_t(k)])];
    h /= std::max(1, int(n1 - n0));
    for (auto g = g0; g < g1; ++g) {
      const double J = md.fbar ? wJ / w : st.total_J(g);
      double q = 0, factor = 1;
      if (st.J_last[g] > 0 && dt > 0 && J > 0 && J < st.J_last[g]) {
        const double e = std::log(st.J_last[g] / J) / dt;  // |tr D|, compression
        const double l = h * std::cbrt(J);
        const double Q = k.linear * c_wave + k.quadratic * l * e;
        q = md.density / J * l * e * Q;
        const double r = Q / c_wave;
        factor = 1 / (r + std::sqrt(1 + r * r));
      }
      if (st.J_last[g] > 0) work += md.weight[g] * 0.5 * (st.q[g] + q) * (st.J_last[g] - J);
      st.q[g] = q;
      st.dt_factor[g] = factor;
      st.J_last[g] = J;
    }
  }
  st.viscous_work += work;
}

}  // namespace rk
