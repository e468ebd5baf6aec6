#include "time_step.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rk {

double smallest_stretch(const double F[9], double detF) {
  double C[6];  // xx, yy, zz, xy, yz, zx
  const int a[6] = {0, 1, 2, 0, 1, 2}, b[6] = {0, 1, 2, 1, 2, 0};
  for (int k = 0; k < 6; ++k)
    C[k] = F[a[k]] * F[b[k]] + F[3 + a[k]] * F[3 + b[k]] + F[6 + a[k]] * F[6 + b[k]];
  // eigenvalues of a symmetric 3x3 matrix by the trigonometric method (Smith 1961)
  const double q = (C[0] + C[1] + C[2]) / 3;
  const double off = C[3] * C[3] + C[4] * C[4] + C[5] * C[5];
  const double d0 = C[0] - q, d1 = C[1] - q, d2 = C[2] - q;
  const double p = std::sqrt((d0 * d0 + d1 * d1 + d2 * d2 + 2 * off) / 6);
  // C isotropic to round-off (spread below 1e-14 of its mean): all three eigenvalues are q
  if (!(p > 1e-14 * q)) return std::sqrt(std::max(q, 0.0));
  const double B[6] = {d0 / p, d1 / p, d2 / p, C[3] / p, C[4] / p, C[5] / p};
  const double detB = B[0] * (B[1] * B[2] - B[4] * B[4]) - B[3] * (B[3] * B[2] - B[4] * B[5]) +
                      B[5] * (B[3] * B[4] - B[1] * B[5]);
  const double phi = std::acos(std::clamp(detB / 2, -1.0, 1.0)) / 3;
  const double largest = q + 2 * p * std::cos(phi), smallest = q + 2 * p * std::cos(phi + 2 * M_PI / 3);
  // q + 2p cos(...) cancels for the smallest when the stretches spread (1e-6 relative at 1e-3 vs 20);
  // det C / (product of the other two) keeps its digits, det C = (det F)^2
  const double others = largest * (3 * q - largest - smallest);
  return std::sqrt(others > 0 ? detF * detF / others : std::max(smallest, 0.0));
}

double gershgorin_floor(const double F[9]) {
  auto c = [&](int a, int b) { return F[a] * F[b] + F[3 + a] * F[3 + b] + F[6 + a] * F[6 + b]; };  // C = F^T F
  const double xy = std::abs(c(0, 1)), yz = std::abs(c(1, 2)), zx = std::abs(c(2, 0));
  return std::min({c(0, 0) - xy - zx, c(1, 1) - xy - yz, c(2, 2) - yz - zx});
}

namespace {

// dt of cell c's points = this * their smallest stretch (with bulk viscosity, times the point's factor)
double cell_scale(const Model& md, const State& st, std::size_t c, const std::vector<double>& h) {
  const double c2 = md.material_of_cell(c).wave_speed2(st.cell_J[c]);
  return h[c] / std::sqrt(c2);
}

}  // namespace

StableStep stable_time_step(const Model& md, const State& st, double cfl, bool damped, std::size_t first,
                            const std::vector<double>* edges) {
  const std::vector<double>& h = edges ? *edges : md.cell_h0;
  double dt = std::numeric_limits<double>::infinity();
  std::size_t which = 0;
  auto visit = [&](std::size_t c) {
    const double scale0 = cell_scale(md, st, c, h);
    for (auto g = md.cell_points[c]; g < md.cell_points[c + 1]; ++g) {
      const double* F = &st.F[9 * std::size_t(g)];
      const double scale = st.dt_factor.empty() || !damped ? scale0 : scale0 * st.dt_factor[std::size_t(g)];  // bulk viscosity
      // Cheap lower bounds first: lambda_min(C) >= det C / (lambda_mid lambda_max) >= 4 J^2 / (tr C)^2,
      // and Gershgorin's min_i (C_ii - sum_j!=i |C_ij|), the tight one near F = I (after a reference
      // update, where the first leaves most points to the eigenvalue formula's acos and cos)
      double trC = 0;
      for (int k = 0; k < 9; ++k) trC += F[k] * F[k];
      if (scale * 2 * std::abs(st.J[g]) / trC >= dt) continue;  // cannot set the step
      if (scale * std::sqrt(std::max(gershgorin_floor(F), 0.0)) >= dt) continue;
      const double dtg = scale * smallest_stretch(F, st.J[g]);
      if (dtg < dt) dt = dtg, which = c;
    }
  };
  // the cell that set the last step first: its step, near the new one, lets the bounds skip the other
  // cells' points (a part compressed evenly otherwise sends many to the eigenvalue formula); the least
  // over the points does not depend on the order
  if (first < md.cells) visit(first);
  for (std::size_t c = 0; c < md.cells; ++c)
    if (c != first) visit(c);
  return {cfl * dt, which};
}

void cell_time_steps(const Model& md, const State& st, double cfl, double enough, std::vector<double>& dt_cell) {
  dt_cell.assign(md.cells, std::numeric_limits<double>::infinity());
  for (std::size_t c = 0; c < md.cells; ++c) {
    const double scale0 = cell_scale(md, st, c, md.cell_h0);
    for (auto g = md.cell_points[c]; g < md.cell_points[c + 1]; ++g) {
      const double* F = &st.F[9 * std::size_t(g)];
      const double scale = st.dt_factor.empty() ? scale0 : scale0 * st.dt_factor[std::size_t(g)];
      double trC = 0;  // the cheap lower bounds of stable_time_step: past `enough`, no more is needed
      for (int k = 0; k < 9; ++k) trC += F[k] * F[k];
      const double bound = cfl * (scale * std::max(2 * std::abs(st.J[g]) / trC, std::sqrt(std::max(gershgorin_floor(F), 0.0))));
      // (CFL times the point's step, rounded as stable_time_step rounds the least)
      dt_cell[c] = std::min(dt_cell[c], bound >= enough ? bound : cfl * (scale * smallest_stretch(F, st.J[g])));
    }
  }
}

}  // namespace rk
