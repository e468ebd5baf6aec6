#include "die_search.hpp"

#include <cmath>
#include <limits>

namespace rk {
namespace {

inline double dot3(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

std::vector<double> centres(const DieSurface& s) {
  std::vector<double> c;
  for (std::size_t t = 0; t < s.triangles.size() / 3; ++t)
    for (int d = 0; d < 3; ++d) {
      double sum = 0;
      for (int k = 0; k < 3; ++k) sum += s.vertices[3 * s.triangles[3 * t + k] + d];
      c.push_back(sum / 3);
    }
  return c;
}

}  // namespace

void closest_point_on_triangle(const double p[3], const double a[3], const double b[3], const double c[3],
                               double out[3]) {
  double ab[3], ac[3], ap[3];
  for (int i = 0; i < 3; ++i) ab[i] = b[i] - a[i], ac[i] = c[i] - a[i], ap[i] = p[i] - a[i];
  const double d1 = dot3(ab, ap), d2 = dot3(ac, ap);
  auto set = [&](const double* q) { out[0] = q[0], out[1] = q[1], out[2] = q[2]; };
  if (d1 <= 0 && d2 <= 0) return set(a);
  double bp[3];
  for (int i = 0; i < 3; ++i) bp[i] = p[i] - b[i];
  const double d3 = dot3(ab, bp), d4 = dot3(ac, bp);
  if (d3 >= 0 && d4 <= d3) return set(b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    for (int i = 0; i < 3; ++i) out[i] = a[i] + v * ab[i];
    return;
  }
  double cp[3];
  for (int i = 0; i < 3; ++i) cp[i] = p[i] - c[i];
  const double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
  if (d6 >= 0 && d5 <= d6) return set(c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    for (int i = 0; i < 3; ++i) out[i] = a[i] + w * ac[i];
    return;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    for (int i = 0; i < 3; ++i) out[i] = b[i] + w * (c[i] - b[i]);
    return;
  }
  const double denom = 1 / (va + vb + vc), v = vb * denom, w = vc * denom;
  for (int i = 0; i < 3; ++i) out[i] = a[i] + ab[i] * v + ac[i] * w;
}

DieSearch::DieSearch(const DieSurface& s, double margin)
    : s_(s), centre_(centres(s)), grid_(nullptr, nullptr, 0) {
  const std::size_t nt = s.triangles.size() / 3;
  for (std::size_t t = 0; t < nt; ++t) {
    const double* v[3] = {&s.vertices[3 * s.triangles[3 * t]], &s.vertices[3 * s.triangles[3 * t + 1]],
                          &s.vertices[3 * s.triangles[3 * t + 2]]};
    double r = 0;
    for (int k = 0; k < 3; ++k) {
      double d2 = 0;
      for (int i = 0; i < 3; ++i) d2 += (v[k][i] - centre_[3 * t + i]) * (v[k][i] - centre_[3 * t + i]);
      r = std::max(r, std::sqrt(d2));
    }
    radius_.push_back(r + margin);
    double e1[3], e2[3], n[3];
    for (int i = 0; i < 3; ++i) e1[i] = v[1][i] - v[0][i], e2[i] = v[2][i] - v[0][i];
    n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    const double len = std::sqrt(dot3(n, n));
    for (int i = 0; i < 3; ++i) normal_.push_back(len > 0 ? n[i] / len : 0.0);
  }
  grid_ = NeighbourGrid(centre_.data(), radius_.data(), nt);
}

DieHit DieSearch::nearest(const double x[3], std::vector<std::int32_t>& scratch) const {
  scratch.clear();
  grid_.covering(x, scratch);
  DieHit hit;
  double best = std::numeric_limits<double>::infinity(), best_point[3] = {0, 0, 0};
  double pseudo[3] = {0, 0, 0};
  for (auto t : scratch) {
    double c[3];
    closest_point_on_triangle(x, &s_.vertices[3 * s_.triangles[3 * t]], &s_.vertices[3 * s_.triangles[3 * t + 1]],
                              &s_.vertices[3 * s_.triangles[3 * t + 2]], c);
    const double d2 = (x[0] - c[0]) * (x[0] - c[0]) + (x[1] - c[1]) * (x[1] - c[1]) + (x[2] - c[2]) * (x[2] - c[2]);
    const double tol = std::isfinite(best) ? 1e-18 + 1e-12 * best : 0.0;
    if (!std::isfinite(best) || d2 < best - tol) {  // a strictly closer point: restart the pseudo-normal
      best = d2;
      for (int i = 0; i < 3; ++i) best_point[i] = c[i], pseudo[i] = normal_[3 * t + i];
    } else if (d2 <= best + tol) {  // the same point seen from a neighbouring triangle (edge, vertex)
      for (int i = 0; i < 3; ++i) pseudo[i] += normal_[3 * t + i];
    }
  }
  if (scratch.empty() || !std::isfinite(best)) return hit;
  const double len = std::sqrt(dot3(pseudo, pseudo));
  if (!(len > 0)) return hit;
  hit.found = true;
  double diff[3];
  for (int i = 0; i < 3; ++i) hit.normal[i] = pseudo[i] / len, diff[i] = x[i] - best_point[i];
  hit.gap = std::sqrt(best) * (dot3(diff, hit.normal) < 0 ? -1.0 : 1.0);
  return hit;
}

}  // namespace rk
