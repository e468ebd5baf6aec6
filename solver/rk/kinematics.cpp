#include "rk/kinematics.hpp"

#include "rk/row3.hpp"

namespace rk {
namespace {

// F_g's columns F_.j = e_j + sum_I (d_I - d_I^ref) dN_I/dX_j: per term one load of the padded
// displacement and three multiply-adds by the gradient's components, the even and the odd terms in
// sums of their own (one chain of multiply-adds waits on each add's latency; two halve the wait)
inline void gather_point(const Model& md, State& st, std::size_t g) {
  const double* d = st.d_gather.data();
  const double* dN = md.dN.data();
  Row3 column[3] = {make_row3(1, 0, 0), make_row3(0, 1, 0), make_row3(0, 0, 1)};
  Row3 odd[3] = {make_row3(0, 0, 0), make_row3(0, 0, 0), make_row3(0, 0, 0)};
  const std::int64_t k1 = md.nbr_offsets[g + 1];
  auto k = md.nbr_offsets[g];
  for (; k + 1 < k1; k += 2) {
    const Row3 dI = load_row4(&d[4 * std::size_t(md.nbr[k])]), dJ = load_row4(&d[4 * std::size_t(md.nbr[k + 1])]);
    for (int j = 0; j < 3; ++j) column[j] += dN[3 * std::size_t(k) + j] * dI, odd[j] += dN[3 * std::size_t(k) + 3 + j] * dJ;
  }
  if (k < k1) {
    const Row3 dI = load_row4(&d[4 * std::size_t(md.nbr[k])]);
    for (int j = 0; j < 3; ++j) column[j] += dN[3 * std::size_t(k) + j] * dI;
  }
  for (int j = 0; j < 3; ++j) column[j] += odd[j];
  double* F = &st.F[9 * g];
  for (int i = 0; i < 9; ++i) F[i] = column[i % 3][i / 3];
  st.J[g] = F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) + F[2] * (F[3] * F[7] - F[4] * F[6]);
}

void copy_displacements(const Model& md, State& st) {
  if (st.d_gather.size() != 4 * md.n) st.d_gather.assign(4 * md.n, 0.0);  // (at the start and a reference update)
  const bool updated = !st.u_ref.empty();
  for (std::size_t I = 0; I < md.n; ++I)
    for (int i = 0; i < 3; ++i) st.d_gather[4 * I + i] = updated ? st.u[3 * I + i] - st.u_ref[3 * I + i] : st.u[3 * I + i];
}

void cell_average(const Model& md, State& st, std::size_t c) {
  double wJ = 0, w = 0;
  for (auto g = md.cell_points[c]; g < md.cell_points[c + 1]; ++g) wJ += md.weight[g] * st.J[g], w += md.weight[g];
  st.cell_J[c] = w > 0 ? wJ / w : 1.0;  // (nodal integration leaves cells without points)
}

}  // namespace

void compute_deformation_gradient(const Model& md, State& st) {
  copy_displacements(md, st);
  for (std::size_t g = 0; g < md.m; ++g) gather_point(md, st, g);
  for (std::size_t c = 0; c < md.cells; ++c) cell_average(md, st, c);
}

void compute_deformation_gradient(const Model& md, State& st, std::span<const std::int32_t> cells) {
  copy_displacements(md, st);
  for (const std::int32_t c : cells) {
    for (auto g = md.cell_points[std::size_t(c)]; g < md.cell_points[std::size_t(c) + 1]; ++g) gather_point(md, st, std::size_t(g));
    cell_average(md, st, std::size_t(c));
  }
}

namespace {

// x += sum_k N[k] (d_J - d_J^ref) over the row cols[k0 .. k1) (d^ref = 0 before the first update)
void add_row(const State& st, const std::int32_t* cols, const double* N, std::int64_t k0, std::int64_t k1, double x[3]) {
  const bool updated = !st.u_ref.empty();
  for (auto k = k0; k < k1; ++k) {
    const std::size_t J = 3 * std::size_t(cols[k]);
    for (int i = 0; i < 3; ++i) x[i] += N[k] * (updated ? st.u[J + i] - st.u_ref[J + i] : st.u[J + i]);
  }
}

// d_I^ref + sum_k N[k] (d_J - d_J^ref) over the row cols[k0 .. k1)
void row_displacement(const State& st, std::size_t I, const std::int32_t* cols, const double* N, std::int32_t k0,
                      std::int32_t k1, double uh[3]) {
  for (int i = 0; i < 3; ++i) uh[i] = st.u_ref.empty() ? 0.0 : st.u_ref[3 * I + i];
  add_row(st, cols, N, k0, k1, uh);
}

}  // namespace

void point_position(const Model& md, const State& st, std::size_t g, double x[3]) {
  for (int i = 0; i < 3; ++i) x[i] = md.point_X[3 * g + i];
  add_row(st, md.nbr.data(), md.N.data(), md.nbr_offsets[g], md.nbr_offsets[g + 1], x);
}

void material_position(const Model& md, const State& st, std::size_t I, double x[3]) {
  for (int i = 0; i < 3; ++i) x[i] = md.Xr[3 * I + i];
  add_row(st, md.material_cols.data(), md.material_N.data(), md.material_offsets[I], md.material_offsets[I + 1], x);
}

void material_velocity(const Model& md, const std::vector<double>& v, std::size_t I, double vh[3]) {
  vh[0] = vh[1] = vh[2] = 0;
  for (auto k = md.material_offsets[I]; k < md.material_offsets[I + 1]; ++k)
    for (int i = 0; i < 3; ++i) vh[i] += md.material_N[std::size_t(k)] * v[3 * std::size_t(md.material_cols[std::size_t(k)]) + i];
}

void constrained_displacement(const Model& md, const State& st, std::size_t q, double uh[3]) {
  row_displacement(st, std::size_t(md.ebc_particles[q]), md.ebc_cols.data(), md.ebc_N.data(), md.ebc_offsets[q],
                   md.ebc_offsets[q + 1], uh);
}

void material_displacement(const Model& md, const State& st, std::size_t I, double uh[3]) {
  row_displacement(st, I, md.material_cols.data(), md.material_N.data(), md.material_offsets[I],
                   md.material_offsets[I + 1], uh);
}

}  // namespace rk
