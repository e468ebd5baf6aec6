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

double stretch_ceiling(const double F[9]) {
  double least = std::numeric_limits<double>::infinity();  // lambda_min(C) <= C_ii (a Rayleigh quotient)
  for (int i = 0; i < 3; ++i) least = std::min(least, F[i] * F[i] + F[3 + i] * F[3 + i] + F[6 + i] * F[6 + i]);
  return std::sqrt(least);
}

namespace {

// the dilatational wave speed in cell c: a point's dt = h_c / this * its smallest stretch (with bulk
// viscosity, times the point's factor)
double wave_speed(const Model& md, const State& st, std::size_t c) {
  return std::sqrt(md.material_of_cell(c).wave_speed2(st.cell_J[c]));
}

}  // namespace

StableStep stable_time_step(const Model& md, const State& st, double cfl, bool damped, std::size_t first,
                            double* on_reference) {
  const bool both = on_reference && !md.cell_h_reference.empty();
  double dt = std::numeric_limits<double>::infinity(), dt_reference = dt;
  std::size_t which = 0;
  auto visit = [&](std::size_t c) {
    const double wave = wave_speed(md, st, c);
    const double scale0 = md.cell_h0[c] / wave, reference0 = both ? md.cell_h_reference[c] / wave : 0.0;
    for (auto g = md.cell_points[c]; g < md.cell_points[c + 1]; ++g) {
      const double* F = &st.F[9 * std::size_t(g)];
      const double factor = st.dt_factor.empty() || !damped ? 1.0 : st.dt_factor[std::size_t(g)];  // bulk viscosity
      const double scale = scale0 * factor, reference = reference0 * factor;
      // Cheap lower bounds first: lambda_min(C) >= det C / (lambda_mid lambda_max) >= 4 J^2 / (tr C)^2,
      // and Gershgorin's min_i (C_ii - sum_j!=i |C_ij|), the tight one near F = I (after a reference
      // update, where the first leaves most points to the eigenvalue formula's acos and cos); a point
      // is measured where it may set either least
      double trC = 0;
      for (int k = 0; k < 9; ++k) trC += F[k] * F[k];
      const double floor1 = 2 * std::abs(st.J[g]) / trC;
      bool step = scale * floor1 < dt, ref = both && reference * floor1 < dt_reference;
      if (!step && !ref) continue;  // cannot set either
      const double floor2 = std::sqrt(std::max(gershgorin_floor(F), 0.0));
      step = step && scale * floor2 < dt, ref = ref && reference * floor2 < dt_reference;
      if (!step && !ref) continue;
      const double stretch = smallest_stretch(F, st.J[g]);
      if (step && scale * stretch < dt) dt = scale * stretch, which = c;
      if (ref) dt_reference = std::min(dt_reference, reference * stretch);
    }
  };
  // the cell that set the last step first: its step, near the new one, lets the bounds skip the other
  // cells' points (a part compressed evenly otherwise sends many to the eigenvalue formula); the least
  // over the points does not depend on the order
  if (first < md.cells) visit(first);
  for (std::size_t c = 0; c < md.cells; ++c)
    if (c != first) visit(c);
  if (on_reference) *on_reference = cfl * dt_reference;
  return {cfl * dt, which};
}

void cell_time_steps(const Model& md, const State& st, double cfl, double dt, int levels, std::vector<double>& dt_cell) {
  const auto class_of = [&](double x) {  // as Subcycles::plan reads it
    int k = 0;
    while (k < levels && double(2 << k) * dt <= x) ++k;
    return k;
  };
  dt_cell.assign(md.cells, std::numeric_limits<double>::infinity());
  for (std::size_t c = 0; c < md.cells; ++c) {
    const double scale0 = md.cell_h0[c] / wave_speed(md, st, c);
    int least = levels;  // the class of dt_cell[c] so far
    for (auto g = md.cell_points[c]; g < md.cell_points[c + 1] && least > 0; ++g) {
      const double* F = &st.F[9 * std::size_t(g)];
      const double scale = st.dt_factor.empty() ? scale0 : scale0 * st.dt_factor[std::size_t(g)];
      double trC = 0;  // the cheap lower bounds of stable_time_step: where they hold the class, no more is needed
      for (int k = 0; k < 9; ++k) trC += F[k] * F[k];
      const double bound = cfl * (scale * std::max(2 * std::abs(st.J[g]) / trC, std::sqrt(std::max(gershgorin_floor(F), 0.0))));
      // and from above: where both bounds are in one class, so is the step
      const int below = class_of(bound);
      const bool held = below >= least || class_of(cfl * (scale * stretch_ceiling(F))) == below;
      // (CFL times the point's step, rounded as stable_time_step rounds the least)
      dt_cell[c] = std::min(dt_cell[c], held ? bound : cfl * (scale * smallest_stretch(F, st.J[g])));
      least = class_of(dt_cell[c]);
    }
  }
}

double cell_time_step_ceiling(const Model& md, const State& st, double cfl) {
  double most = 0;
  for (std::size_t c = 0; c < md.cells; ++c) {
    const auto g = std::size_t(md.cell_points[c]);
    if (g == std::size_t(md.cell_points[c + 1])) continue;
    const double factor = st.dt_factor.empty() ? 1.0 : st.dt_factor[g];
    most = std::max(most, cfl * (md.cell_h0[c] / wave_speed(md, st, c) * factor * stretch_ceiling(&st.F[9 * g])));
  }
  return most * (1 + 1e-12);  // (past the round-off of the cells' own steps)
}

}  // namespace rk
