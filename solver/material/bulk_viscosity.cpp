#include "material/bulk_viscosity.hpp"

#include <cmath>

namespace rk {

void init_bulk_viscosity(const Model& md, State& st, const Scene::BulkViscosity& k) {
  const std::size_t n = k.on() ? md.m : 0;
  st.q.assign(n, 0.0);
  st.dt_factor.assign(n, 1.0);
  st.J_last.assign(n, 0.0);  // 0: no step taken yet, no rate
}

namespace {

// Cell c's q and step factors from the volume change over dt (the span of its last increment); the work
// of q into `work`.
void cell_viscosity(const Model& md, State& st, const Scene::BulkViscosity& k, std::size_t c, double dt, double& work) {
  const auto g0 = std::size_t(md.cell_points[c]), g1 = std::size_t(md.cell_points[c + 1]);
  if (g0 == g1) return;  // (nodal integration leaves cells without points)
  const Solid& solid = md.material_of_cell(c);
  const double c_wave = std::sqrt(solid.wave_speed2(st.cell_J[c]));
  double h = 0;  // the particle spacing about the cell: the resolution a shock is spread over
  const auto n0 = md.cell_node_offsets[c], n1 = md.cell_node_offsets[c + 1];
  for (auto n = n0; n < n1; ++n) h += md.spacing0[std::size_t(md.cell_nodes[std::size_t(n)])];
  h /= std::max(1, int(n1 - n0));
  // q and the step's factor of the volume ratio J (from t = 0) after J_last
  auto at = [&](double J, double J_last, double& q, double& factor) {
    q = 0, factor = 1;
    if (!(J_last > 0 && dt > 0 && J > 0 && J < J_last)) return;
    const double e = std::log(J_last / J) / dt;  // |tr D|, compression
    const double l = h * std::cbrt(J);
    const double Q = k.linear * c_wave + k.quadratic * l * e;
    q = solid.density / J * l * e * Q;
    const double r = Q / c_wave;
    factor = 1 / (r + std::sqrt(1 + r * r));
  };
  double wJ = 0, w = 0, q = 0, factor = 1;
  if (md.fbar) {  // the cell's J: one q for its points, as its pressure
    for (auto g = g0; g < g1; ++g) wJ += md.weight[g] * st.total_J(g), w += md.weight[g];
    at(wJ / w, st.J_last[g0], q, factor);
  }
  for (auto g = g0; g < g1; ++g) {
    const double J = md.fbar ? wJ / w : st.total_J(g);
    if (!md.fbar) at(J, st.J_last[g], q, factor);
    if (st.J_last[g] > 0) work += md.weight[g] * 0.5 * (st.q[g] + q) * (st.J_last[g] - J);
    st.q[g] = q;
    st.dt_factor[g] = factor;
    st.J_last[g] = J;
  }
}

}  // namespace

void update_bulk_viscosity(const Model& md, State& st, const Scene::BulkViscosity& k) {
  if (st.q.empty()) return;
  double work = 0;
  for (std::size_t c = 0; c < md.cells; ++c) cell_viscosity(md, st, k, c, st.dt_half, work);
  st.viscous_work += work;
}

void update_bulk_viscosity(const Model& md, State& st, const Scene::BulkViscosity& k, std::span<const std::int32_t> cells) {
  if (st.q.empty()) return;
  double work = 0;
  for (const std::int32_t c : cells) cell_viscosity(md, st, k, std::size_t(c), st.t - st.cell_t_last[std::size_t(c)], work);
  st.viscous_work += work;
}

}  // namespace rk
