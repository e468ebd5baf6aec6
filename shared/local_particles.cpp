#include "local_particles.hpp"

#include <algorithm>

namespace rk {

std::vector<std::int32_t> local_particles(const LocalParticleRequest& r) {
  // one mark per particle: linear in the points (docs/decisions.md, "Local particles by one mark per
  // particle")
  std::vector<std::uint8_t> mark(r.grid.size(), 0);
  std::vector<std::int32_t> found;
  for (auto I : r.cell_nodes) mark[I] = 1;
  auto mark_support = [&](const double* x) {
    found.clear();
    r.grid.covering(x, found);
    for (auto I : found) mark[I] = 1;
  };
  const std::size_t grouped = r.point_groups.empty() ? 0 : std::size_t(r.point_groups.back());
  for (std::size_t g = grouped; g < r.points.size() / 3; ++g) mark_support(&r.points[3 * g]);
  for (std::size_t c = 0; c + 1 < r.point_groups.size(); ++c) {
    const auto g0 = std::size_t(r.point_groups[c]), g1 = std::size_t(r.point_groups[c + 1]);
    found.clear();
    r.grid.near_group(&r.points[3 * g0], g1 - g0, found);
    for (auto I : found)
      for (auto g = g0; g < g1 && !mark[I]; ++g) mark[I] = r.grid.covers(&r.points[3 * g], I);
  }
  for (auto I : r.owned) mark_support(&r.X[3 * std::size_t(I)]);
  std::vector<std::int32_t> local;
  for (std::size_t I = 0; I < mark.size(); ++I)
    if (mark[I]) local.push_back(std::int32_t(I));
  return local;
}

void overlap_maps(const std::vector<std::vector<std::int32_t>>& local, int q, std::vector<std::int32_t>& neighbour_ranks,
                  std::vector<std::vector<std::int32_t>>& maps) {
  neighbour_ranks.clear();
  maps.clear();
  const auto& mine = local[q];
  for (int p = 0; p < int(local.size()); ++p) {
    if (p == q) continue;
    std::vector<std::int32_t> shared;  // a merge of two ascending lists
    auto a = mine.begin();
    auto b = local[p].begin();
    while (a != mine.end() && b != local[p].end()) {
      if (*a < *b) ++a;
      else if (*b < *a) ++b;
      else shared.push_back(std::int32_t(a - mine.begin())), ++a, ++b;
    }
    if (!shared.empty()) {
      neighbour_ranks.push_back(p);
      maps.push_back(std::move(shared));
    }
  }
}

}  // namespace rk
