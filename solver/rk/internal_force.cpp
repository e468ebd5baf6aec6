#include "rk/internal_force.hpp"

#include <algorithm>

#include "parallel/overlap_exchange.hpp"
#include "rk/row3.hpp"

namespace rk {

int force_headroom(const Model& md, int per_column, int extra, const Comm& comm) {
  std::vector<Fixed> terms(md.n, 0);
  for (auto k = md.nbr_offsets.front(); k < md.nbr_offsets.back(); ++k) terms[std::size_t(md.nbr[k])] += per_column;
  OverlapExchange(md, 1).sum(terms);
  double most = terms.empty() ? 0.0 : double(*std::max_element(terms.begin(), terms.end()));
  comm.max(&most, 1);
  return headroom_bits(std::int64_t(most) + extra);
}

int row_headroom(int headroom) { return std::max(headroom, kRowHeadroom); }

ForceTerms force_terms(const Model& md, const DieContact& dies, const PartContact& parts, const Comm& comm) {
  std::vector<Fixed> internal(md.n, 0), contact(md.n, 0);
  for (auto k = md.nbr_offsets.front(); k < md.nbr_offsets.back(); ++k) ++internal[std::size_t(md.nbr[k])];
  dies.count_terms(md, contact);
  parts.count_terms(md, contact);
  OverlapExchange exchange(md, 1);  // the shared copies' counts summed: every rank's terms
  exchange.sum(internal);
  exchange.sum(contact);
  double most[2] = {0, 0};
  for (std::size_t I = 0; I < md.n; ++I)
    most[0] = std::max(most[0], double(internal[I])), most[1] = std::max(most[1], double(contact[I]));
  comm.max(most, 2);
  return {std::int64_t(most[0]), std::int64_t(most[1])};
}

void clear_internal_force(State& st) { std::fill(st.partial.begin(), st.partial.end(), Fixed(0)); }

void add_point_forces(const Model& md, const std::vector<double>& P_all, std::vector<Fixed>& partial,
                      const FixedScale& scale, std::span<const std::int32_t> points) {
  const double* dN = md.dN.data();
  const std::int32_t* nbr = md.nbr.data();
  for (const std::int32_t g : points) {
    // P's columns times w and the fixed-point scale (a power of two), once a point instead of once a term
    const double ws = md.weight[g] * scale.to_fixed;
    const double* P = &P_all[9 * std::size_t(g)];
    const Row3 column[3] = {ws * make_row3(P[0], P[3], P[6]), ws * make_row3(P[1], P[4], P[7]), ws * make_row3(P[2], P[5], P[8])};
    const std::int64_t k1 = md.nbr_offsets[g + 1];  // (held: the stores below may alias the offsets)
#pragma GCC unroll 2  // (two terms an iteration: half the loop's own increments and branches a term)
    for (auto k = md.nbr_offsets[g]; k < k1; ++k) {
      const Row3 d = load_row3(&dN[3 * std::size_t(k)]);
      const FixedRow3 f = round_row(column[0] * d[0] + column[1] * d[1] + column[2] * d[2]);
      add_row(&partial[kForceStride * std::size_t(nbr[k])], f);
    }
  }
}

void read_forces(const std::vector<Fixed>& partial, const FixedScale& scale, std::vector<double>& force) {
  for (std::size_t I = 0; I < force.size() / 3; ++I)
    for (int i = 0; i < 3; ++i) force[3 * I + i] = scale.real(partial[kForceStride * I + i]);
}

void add_internal_force(const Model& md, State& st, const FixedScale& scale, std::span<const std::int32_t> points) {
  add_point_forces(md, st.P, st.partial, scale, points);
}

}  // namespace rk
