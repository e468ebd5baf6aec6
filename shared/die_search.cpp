#include "die_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rk {
namespace {

inline double dot3(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// x as a float no larger (below) or no smaller (above): a float box that holds the double one
float float_below(double x) {
  const float f = float(x);
  return double(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}
float float_above(double x) {
  const float f = float(x);
  return double(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
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

DieSearch::DieSearch(const DieSurface& s, double search_margin, double skin) : s_(s) {
  const std::size_t nt = s.triangles.size() / 3;
  margin_ = search_margin, skin_ = skin;
  const double margin = search_margin + skin;  // the bins' reach
  box_.resize(6 * nt);  // per triangle: lo[3], hi[3]
  double hi[3], edges = 0;
  for (int d = 0; d < 3; ++d) lo_[d] = std::numeric_limits<double>::infinity(), hi[d] = -lo_[d];
  for (std::size_t t = 0; t < nt; ++t) {
    const double* v[3] = {&s.vertices[3 * s.triangles[3 * t]], &s.vertices[3 * s.triangles[3 * t + 1]],
                          &s.vertices[3 * s.triangles[3 * t + 2]]};
    for (int d = 0; d < 3; ++d) {
      box_[6 * t + d] = std::min({v[0][d], v[1][d], v[2][d]});
      box_[6 * t + 3 + d] = std::max({v[0][d], v[1][d], v[2][d]});
      lo_[d] = std::min(lo_[d], box_[6 * t + d] - margin);
      hi[d] = std::max(hi[d], box_[6 * t + 3 + d] + margin);
    }
    double e1[3], n[3];
    const double len = 2 * s.area_normal(t, n);  // |n| (the doubling is exact)
    for (int i = 0; i < 3; ++i) normal_.push_back(len > 0 ? n[i] / len : 0.0), e1[i] = v[1][i] - v[0][i];
    edges += std::sqrt(dot3(e1, e1));
    for (int k = 0; k < 3; ++k) {  // the angle at corner k between its two edges
      double p[3], q[3];
      for (int i = 0; i < 3; ++i) p[i] = v[(k + 1) % 3][i] - v[k][i], q[i] = v[(k + 2) % 3][i] - v[k][i];
      const double pq = std::sqrt(dot3(p, p) * dot3(q, q));
      angle_.push_back(pq > 0 ? std::acos(std::clamp(dot3(p, q) / pq, -1.0, 1.0)) : 0.0);
    }
  }
  if (nt == 0) {
    start_.assign(2, 0);
    return;
  }
  // Bin size: the mean edge or the margin, whichever is larger, with at most ~2^21 bins (8 MiB of bin
  // offsets), grown 1.25x until they fit.
  h_ = std::max(edges / double(nt), margin);
  for (;;) {
    for (int d = 0; d < 3; ++d) dims_[d] = std::max<std::int64_t>(1, std::int64_t((hi[d] - lo_[d]) / h_) + 1);
    if (dims_[0] * dims_[1] * dims_[2] <= (std::int64_t(1) << 21)) break;
    h_ *= 1.25;
  }
  start_.assign(dims_[0] * dims_[1] * dims_[2] + 1, 0);
  auto each_bin = [&](std::size_t t, auto fn) {  // the bins the triangle's box grown by the margin touches
    std::int64_t b0[3], b1[3];
    for (int d = 0; d < 3; ++d) {
      const double lo[3] = {box_[6 * t] - margin, box_[6 * t + 1] - margin, box_[6 * t + 2] - margin};
      const double hi[3] = {box_[6 * t + 3] + margin, box_[6 * t + 4] + margin, box_[6 * t + 5] + margin};
      b0[d] = bin(lo, d), b1[d] = bin(hi, d);
    }
    for (std::int64_t k = b0[2]; k <= b1[2]; ++k)
      for (std::int64_t j = b0[1]; j <= b1[1]; ++j)
        for (std::int64_t i = b0[0]; i <= b1[0]; ++i) fn((k * dims_[1] + j) * dims_[0] + i);
  };
  for (std::size_t t = 0; t < nt; ++t) each_bin(t, [&](std::int64_t b) { ++start_[b + 1]; });
  for (std::size_t b = 1; b < start_.size(); ++b) start_[b] += start_[b - 1];
  items_.resize(std::size_t(start_.back()));
  std::vector<std::int32_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t t = 0; t < nt; ++t) each_bin(t, [&](std::int64_t b) { items_[fill[b]++] = std::int32_t(t); });
}

std::int64_t DieSearch::bin(const double x[3], int d) const {
  return std::clamp<std::int64_t>(std::int64_t(std::floor((x[d] - lo_[d]) / h_)), 0, dims_[d] - 1);
}

std::int64_t DieSearch::bin_of(const double x[3]) const {
  for (int d = 0; d < 3; ++d)
    if (x[d] < lo_[d] || x[d] > lo_[d] + double(dims_[d]) * h_) return -1;
  return (bin(x, 2) * dims_[1] + bin(x, 1)) * dims_[0] + bin(x, 0);
}

DieHit DieSearch::nearest(const double x[3]) const { return nearest(x, -1); }

DieHit DieSearch::nearest(const double x[3], std::int32_t hint) const {
  const std::int64_t b = bin_of(x);
  if (b < 0) return DieHit{};
  return nearest_among(x, &items_[std::size_t(start_[b])], nullptr, start_[b + 1] - start_[b], hint);
}

int DieSearch::candidates(const double x[3], double skin, std::int32_t* out, float* boxes, int capacity) const {
  const std::int64_t b = bin_of(x);
  if (b < 0) return 0;
  // (the reach a little past margin + skin: a slave at the skin's distance stays covered through round-off)
  const double reach = (margin_ + skin) * (margin_ + skin) * (1 + 1e-9) + 1e-18;
  int count = 0;
  double c[3];
  for (std::int32_t k = start_[b]; k < start_[b + 1]; ++k)
    if (const std::int32_t t = items_[k]; box_distance2(&box_[6 * std::size_t(t)], x) <= reach && distance2(t, x, c) <= reach) {
      if (count == capacity) return -1;
      for (int d = 0; d < 3; ++d)
        boxes[6 * count + d] = float_below(box_[6 * t + d]), boxes[6 * count + 3 + d] = float_above(box_[6 * t + 3 + d]);
      out[count++] = t;
    }
  return count;
}

double DieSearch::distance2(std::int32_t t, const double x[3], double c[3]) const {
  closest_point_on_triangle(x, s_.corner(std::size_t(t), 0), s_.corner(std::size_t(t), 1), s_.corner(std::size_t(t), 2), c);
  return (x[0] - c[0]) * (x[0] - c[0]) + (x[1] - c[1]) * (x[1] - c[1]) + (x[2] - c[2]) * (x[2] - c[2]);
}

// The hint's distance bounds the nearest's: a triangle whose box is farther (by more than the ties'
// tolerance) would at most have been a best that a closer one then replaced, which changes nothing.
double DieSearch::hint_bound(const double x[3], std::int32_t hint) const {
  if (hint < 0) return std::numeric_limits<double>::infinity();
  double c[3];
  return distance2(hint, x, c) * (1 + 1e-9) + 1e-17;
}

DieHit DieSearch::nearest_among(const double x[3], const std::int32_t* triangles, const float* boxes, int count,
                                std::int32_t hint) const {
  return nearest_within(x, triangles, boxes, count, hint_bound(x, hint));
}

DieHit DieSearch::nearest_among(const double x[3], const std::int32_t* triangles, const float* boxes, int count,
                                std::int32_t hint, const std::int32_t* near, const float* near_boxes, int near_count,
                                double far2) const {
  const double bound = hint_bound(x, hint);
  // (the others' boxes lie at least sqrt(far2) from x: each box2 > bound, the loop's first rejection)
  return far2 > bound ? nearest_within(x, near, near_boxes, near_count, bound)
                      : nearest_within(x, triangles, boxes, count, bound);
}

DieHit DieSearch::nearest_within(const double x[3], const std::int32_t* triangles, const float* boxes, int count,
                                 double bound) const {
  DieHit hit;
  double best = std::numeric_limits<double>::infinity(), best_point[3] = {0, 0, 0};
  const double reach = margin_ * margin_;  // nothing beyond the margin counts
  double pseudo[3] = {0, 0, 0};
  // Squared distances within 1e-12 relative (1e-18 m^2 absolute) are equal to round-off: one point.
  for (int k = 0; k < count; ++k) {
    const std::int32_t t = triangles[k];
    // (a float box holds the triangle's: a triangle it keeps that the exact box would reject is farther
    // than the best so far and changes nothing)
    const double box2 = boxes ? box_distance2(&boxes[6 * k], x) : box_distance2(&box_[6 * std::size_t(t)], x);
    if (box2 > reach || box2 > bound || (std::isfinite(best) && box2 > best * (1 + 1e-12) + 1e-18)) continue;
    double c[3];
    const double d2 = distance2(t, x, c);
    if (d2 > reach) continue;
    const double tol = std::isfinite(best) ? 1e-18 + 1e-12 * best : 0.0;
    // the triangle's weight in the pseudo-normal: its angle where the closest point is one of its
    // corners (every triangle around that vertex finds it there), else 1 (its face, or an edge with
    // its neighbour)
    double weight = 1;
    for (int k = 0; k < 3; ++k) {
      const double* corner = s_.corner(std::size_t(t), k);
      if (c[0] == corner[0] && c[1] == corner[1] && c[2] == corner[2]) weight = angle_[3 * std::size_t(t) + std::size_t(k)];
    }
    if (!std::isfinite(best) || d2 < best - tol) {  // a strictly closer point: restart the pseudo-normal
      best = d2;
      hit.triangle = t;
      for (int i = 0; i < 3; ++i) best_point[i] = c[i], pseudo[i] = weight * normal_[3 * t + i];
    } else if (d2 <= best + tol) {  // the same point seen from a neighbouring triangle (edge, vertex)
      for (int i = 0; i < 3; ++i) pseudo[i] += weight * normal_[3 * t + i];
    }
  }
  if (!std::isfinite(best)) return hit;
  const double len = std::sqrt(dot3(pseudo, pseudo));
  if (!(len > 0)) return DieHit{};
  hit.found = true;
  double diff[3];
  for (int i = 0; i < 3; ++i) hit.normal[i] = pseudo[i] / len, diff[i] = x[i] - best_point[i];
  hit.gap = std::sqrt(best) * (dot3(diff, hit.normal) < 0 ? -1.0 : 1.0);
  return hit;
}

}  // namespace rk
