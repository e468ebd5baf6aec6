#include "die_fill_regions.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

namespace rk {
namespace {

double triangle_area(const DieSurface& s, std::size_t t, double centre[3]) {
  double n[3];
  s.centre(t, centre);
  return s.area_normal(t, n);
}

std::size_t root(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

std::vector<UnfilledRegion> unfilled_regions(const DieSurface& die, const std::vector<double>& touched, const double shift[3]) {
  const std::size_t n = die.triangle_count(), vertices = die.vertices.size() / 3;
  std::vector<std::size_t> parent(n), first(vertices, n);  // first: a vertex's first untouched triangle
  std::iota(parent.begin(), parent.end(), 0);
  for (std::size_t t = 0; t < n; ++t) {
    if (touched[t] != 0) continue;
    for (int c = 0; c < 3; ++c) {  // join the untouched triangles that share a vertex
      const auto v = std::size_t(die.triangles[3 * t + std::size_t(c)]);
      if (first[v] == n) first[v] = t;
      else parent[root(parent, t)] = root(parent, first[v]);
    }
  }
  std::vector<UnfilledRegion> regions;
  std::vector<std::size_t> index(n, n);  // a root's region
  for (std::size_t t = 0; t < n; ++t) {
    if (touched[t] != 0) continue;
    const std::size_t r = root(parent, t);
    if (index[r] == n) {
      index[r] = regions.size();
      UnfilledRegion fresh;
      for (int i = 0; i < 3; ++i) fresh.lo[i] = 1e300, fresh.hi[i] = -1e300;
      regions.push_back(fresh);
    }
    UnfilledRegion& g = regions[index[r]];
    double c[3];
    const double a = triangle_area(die, t, c);
    g.area += a;
    for (int i = 0; i < 3; ++i) g.centre[i] += a * (c[i] + shift[i]);
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i) {
        const double x = die.corner(t, k)[i] + shift[i];
        g.lo[i] = std::min(g.lo[i], x), g.hi[i] = std::max(g.hi[i], x);
      }
  }
  for (auto& g : regions)
    for (double& c : g.centre) c /= g.area > 0 ? g.area : 1;
  std::sort(regions.begin(), regions.end(), [](const auto& a, const auto& b) { return a.area > b.area; });
  return regions;
}

std::string describe_fill(const std::string& name, const DieSurface& die, const std::vector<double>& touched,
                          const double shift[3], std::size_t most) {
  double working = 0, filled = 0, c[3];
  for (std::size_t t = 0; t < die.triangle_count(); ++t) {
    const double a = triangle_area(die, t, c);
    if (touched[t] >= 0) working += a;
    if (touched[t] > 0) filled += a;
  }
  const auto regions = unfilled_regions(die, touched, shift);
  char text[400];
  std::snprintf(text, sizeof text, "die '%s': %.3g %% of its working surface filled (%.4g of %.4g mm^2)", name.c_str(),
                working > 0 ? 100 * filled / working : 0.0, 1e6 * filled, 1e6 * working);
  std::string out = text;
  if (regions.empty()) return out + "; no unfilled region";
  std::snprintf(text, sizeof text, "; %zu unfilled region%s, the largest:", regions.size(), regions.size() > 1 ? "s" : "");
  out += text;
  for (std::size_t k = 0; k < std::min(most, regions.size()); ++k) {
    const auto& g = regions[k];
    std::snprintf(text, sizeof text, "%s %.3g mm^2 around (%.3g, %.3g, %.3g) mm, %.3g x %.3g x %.3g mm", k ? ";" : "",
                  1e6 * g.area, 1e3 * g.centre[0], 1e3 * g.centre[1], 1e3 * g.centre[2], 1e3 * (g.hi[0] - g.lo[0]),
                  1e3 * (g.hi[1] - g.lo[1]), 1e3 * (g.hi[2] - g.lo[2]));
    out += text;
  }
  return out;
}

}  // namespace rk
