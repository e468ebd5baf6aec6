#include "flow_lines.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace rk {

FlowLineSet select_flow_lines(const Scene::Output::FlowLines& spec, const std::vector<double>& X, double h) {
  const Vec3& n = spec.normal;
  const Vec3& a = spec.direction;
  const Vec3 e = {n[1] * a[2] - n[2] * a[1], n[2] * a[0] - n[0] * a[2], n[0] * a[1] - n[1] * a[0]};  // across the lines
  struct Near {
    double along, miss, across;  // position along the line; distance from it; offset across it
    std::int64_t particle;
  };
  std::map<std::int64_t, std::vector<Near>> near;  // offset k: the particles within half a spacing
  for (std::size_t I = 0; I < X.size() / 3; ++I) {
    double d[3];
    for (int i = 0; i < 3; ++i) d[i] = X[3 * I + i] - spec.point[i];
    const double off_plane = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
    const double across = d[0] * e[0] + d[1] * e[1] + d[2] * e[2];
    const auto k = std::int64_t(std::llround(across / spec.spacing));
    const double off_line = across - double(k) * spec.spacing;
    if (std::abs(off_plane) > 0.5 * h || std::abs(off_line) > 0.5 * h) continue;
    near[k].push_back({d[0] * a[0] + d[1] * a[1] + d[2] * a[2], std::hypot(off_plane, off_line), off_line, std::int64_t(I)});
  }
  FlowLineSet set;
  for (auto& [k, candidates] : near) {
    // one particle per layer along the line, the nearest to it (ties: the same side every layer): where the
    // particles are finer than the spacing asked, two columns lie within half a spacing of a line between
    // them, and the line zigzagged from one to the other at t = 0
    std::sort(candidates.begin(), candidates.end(), [](const Near& p, const Near& q) { return p.along < q.along; });
    std::vector<std::pair<double, std::int64_t>> line;  // (position along, particle)
    for (std::size_t i = 0; i < candidates.size();) {
      std::size_t best = i, j = i;
      for (; j < candidates.size() && candidates[j].along - candidates[i].along < 0.25 * h; ++j) {
        const Near &p = candidates[j], &b = candidates[best];
        if (p.miss < b.miss - 1e-6 * h || (p.miss < b.miss + 1e-6 * h && p.across < b.across - 1e-6 * h)) best = j;
      }
      line.push_back({candidates[best].along, candidates[best].particle});
      i = j;
    }
    if (line.size() < 2) continue;
    const auto first = std::int64_t(set.particles.size()), number = first == 0 ? 0 : set.line.back() + 1;
    for (const auto& [along, I] : line) set.particles.push_back(I), set.line.push_back(number);
    for (auto p = first; p + 1 < std::int64_t(set.particles.size()); ++p) {
      const std::int64_t segment[2] = {p, p + 1};
      set.lines.add(segment, 2, 3);  // VTK_LINE
    }
  }
  return set;
}

}  // namespace rk
