#include "local_particles.hpp"

#include <algorithm>

namespace rk {

std::vector<std::int32_t> local_particles(const LocalParticleRequest& r) {
  std::vector<std::int32_t> local(r.cell_nodes), found;
  for (std::size_t g = 0; g < r.points.size() / 3; ++g) {
    found.clear();
    r.grid.covering(&r.points[3 * g], found);
    local.insert(local.end(), found.begin(), found.end());
  }
  for (auto I : r.owned) {
    found.clear();
    r.grid.covering(&r.X[3 * std::size_t(I)], found);
    local.insert(local.end(), found.begin(), found.end());
  }
  std::sort(local.begin(), local.end());
  local.erase(std::unique(local.begin(), local.end()), local.end());
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
