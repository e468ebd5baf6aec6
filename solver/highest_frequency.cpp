#include "highest_frequency.hpp"

#include <algorithm>
#include <cmath>

#include "rk/internal_force.hpp"
#include "rk/row3.hpp"
#include "time_step.hpp"

namespace rk {
namespace {

// A value in [-1, 1) from an integer (splitmix64): the start vector, the same on every rank.
double scramble(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  x ^= x >> 31;
  return double(x >> 11) * 0x1.0p-52 - 1.0;
}

void inverse(const double F[9], double J, double Fi[9]) {
  Fi[0] = (F[4] * F[8] - F[5] * F[7]) / J, Fi[1] = (F[2] * F[7] - F[1] * F[8]) / J, Fi[2] = (F[1] * F[5] - F[2] * F[4]) / J;
  Fi[3] = (F[5] * F[6] - F[3] * F[8]) / J, Fi[4] = (F[0] * F[8] - F[2] * F[6]) / J, Fi[5] = (F[2] * F[3] - F[0] * F[5]) / J;
  Fi[6] = (F[3] * F[7] - F[4] * F[6]) / J, Fi[7] = (F[1] * F[6] - F[0] * F[7]) / J, Fi[8] = (F[0] * F[4] - F[1] * F[3]) / J;
}

}  // namespace

HighestFrequency::HighestFrequency(const Model& md, const Comm& comm)
    : exchange_(md, int(kForceStride)), headroom_(row_headroom(force_headroom(md, 1, 0, comm))), Kv_(3 * md.n), P_(9 * md.m), partial_(kForceStride * md.n) {
  double owned = 0;
  for (std::size_t I = 0; I < md.n; ++I) owned += md.owned[I];
  comm.sum(&owned, 1);
  sum_headroom_ = headroom_bits(std::int64_t(owned));
}

// f_I = sum_g w_g J sigma(v) F^-T grad_X N_I, sigma = K theta I + 2 G dev(sym(grad_x v)),
// theta = tr grad_x v (its cell's weighted mean with F-bar), J = det F (the cell's mean with F-bar)
void HighestFrequency::apply(const Model& md, const State& st, const Comm& comm) {
  const std::vector<double>& v = st.stiff_mode;
  double bound = 0;
  for (std::size_t c = 0; c < md.cells; ++c) {  // (every point lies in a cell: model.cpp)
    const auto g0 = std::size_t(md.cell_points[c]), g1 = std::size_t(md.cell_points[c + 1]);
    double wt = 0, w = 0;
    for (auto g = g0; g < g1; ++g) {
      Row3 row[3] = {make_row3(0, 0, 0), make_row3(0, 0, 0), make_row3(0, 0, 0)};  // grad_X v
      for (auto k = md.nbr_offsets[g]; k < md.nbr_offsets[g + 1]; ++k) {
        const std::size_t J = 3 * std::size_t(md.nbr[k]);
        const Row3 d = load_row3(&md.dN[3 * std::size_t(k)]);
        for (int i = 0; i < 3; ++i) row[i] += v[J + i] * d;
      }
      double Fi[9];
      inverse(&st.F[9 * g], st.J[g], Fi);
      double* L = &P_[9 * g];  // grad_x v = grad_X v F^-1, kept here until the stress replaces it
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) L[3 * i + j] = row[i][0] * Fi[j] + row[i][1] * Fi[3 + j] + row[i][2] * Fi[6 + j];
      wt += md.weight[g] * (L[0] + L[4] + L[8]), w += md.weight[g];
    }
    const double theta_cell = w > 0 ? wt / w : 0.0;  // the F-bar mean of tr grad_x v
    const double K = md.material_of_cell(c).law.bulk, G = md.material_of_cell(c).law.shear;
    for (auto g = g0; g < g1; ++g) {
      double* L = &P_[9 * g];
      const double tr = L[0] + L[4] + L[8], theta = md.fbar ? theta_cell : tr;
      const double J = md.fbar ? st.cell_J[c] : st.J[g];
      double s[9];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) s[3 * i + j] = J * G * (L[3 * i + j] + L[3 * j + i]);
      for (int i = 0; i < 3; ++i) s[4 * i] += J * (K * theta - 2 * G * tr / 3);
      double Fi[9];
      inverse(&st.F[9 * g], st.J[g], Fi);
      double norm2 = 0;
      for (int i = 0; i < 3; ++i)  // P = J sigma F^-T
        for (int A = 0; A < 3; ++A) {
          L[3 * i + A] = s[3 * i] * Fi[3 * A] + s[3 * i + 1] * Fi[3 * A + 1] + s[3 * i + 2] * Fi[3 * A + 2];
          norm2 += L[3 * i + A] * L[3 * i + A];
        }
      bound = std::max(bound, md.weight[g] * std::sqrt(norm2) * md.dN_max[g]);
    }
  }
  comm.max(&bound, 1);
  const FixedScale scale = FixedScale::for_bound(bound, headroom_);
  std::fill(partial_.begin(), partial_.end(), Fixed(0));
  add_point_forces(md, P_, partial_, scale, md.boundary_points);
  add_point_forces(md, P_, partial_, scale, md.interior_points);
  exchange_.sum(partial_);
  read_forces(partial_, scale, Kv_);
}

// sum over the owned particles of a_I . b_I (times m_I with by_mass), in fixed point over the ranks
double HighestFrequency::dot(const Model& md, const std::vector<double>& a, const std::vector<double>& b, bool by_mass,
                             const Comm& comm) const {
  double bound = 0;
  for (std::size_t I = 0; I < md.n; ++I)
    if (md.owned[I])
      for (int i = 0; i < 3; ++i) bound = std::max(bound, std::abs(a[3 * I + i] * b[3 * I + i] * (by_mass ? md.mass[I] : 1.0)));
  comm.max(&bound, 1);
  const FixedScale scale = FixedScale::for_bound(bound, sum_headroom_ + 2);
  std::int64_t sum = 0;
  for (std::size_t I = 0; I < md.n; ++I)
    if (md.owned[I])
      for (int i = 0; i < 3; ++i) sum += scale.fixed(a[3 * I + i] * b[3 * I + i] * (by_mass ? md.mass[I] : 1.0));
  comm.sum(&sum, 1);
  return scale.real(sum);
}

double HighestFrequency::iterate(const Model& md, State& st, const Comm& comm, int iterations) {
  std::vector<double>& v = st.stiff_mode;
  double lambda = 0;
  for (int it = 0; it < iterations; ++it) {
    apply(md, st, comm);
    lambda = dot(md, v, Kv_, false, comm) / dot(md, v, v, true, comm);  // the Rayleigh quotient
    double largest = 0;
    for (std::size_t I = 0; I < md.n; ++I)
      for (int i = 0; i < 3; ++i) largest = std::max(largest, std::abs(v[3 * I + i] = Kv_[3 * I + i] / md.mass[I]));
    comm.max(&largest, 1);
    if (!(largest > 0)) break;
    for (double& x : v) x /= largest;
  }
  return lambda;
}

double HighestFrequency::step_ratio(const Model& md, State& st, const Comm& comm) {
  if (st.stiff_mode.size() != 3 * md.n) {
    st.stiff_mode.resize(3 * md.n);
    for (std::size_t I = 0; I < md.n; ++I)
      for (int i = 0; i < 3; ++i) st.stiff_mode[3 * I + i] = scramble(3 * std::uint64_t(md.global_id[I]) + std::uint64_t(i));
    st.step_ratio = 0;
  }
  if (st.step_ratio > 0 && st.step % kEvery != 0) return st.step_ratio;
  const double omega2 = iterate(md, st, comm, st.step_ratio > 0 ? 1 : kStart);
  double cells = stable_time_step(md, st, 1.0, false).dt;
  comm.min(&cells, 1);
  // a part that does not deform (omega = 0) or cells without a step: the cells' estimate alone
  st.step_ratio = omega2 > 0 && std::isfinite(cells) ? 2 / std::sqrt(omega2) / cells : 1.0;
  return st.step_ratio;
}

}  // namespace rk
