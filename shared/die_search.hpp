// Closest-point queries against a rigid die surface (triangles with outward normals), in the die's
// own frame: the dies only translate, so the bucket grid is built once and never refreshed. Each
// triangle is listed in every bin its box (grown by the search margin and the skin) touches, so a
// query reads one bin however large the die's triangles are.
// Used by rkprep (a workpiece must not start inside a die) and rksolve (the contact of the material
// points, particles and integration points, with the die's triangles).
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "subdomain.hpp"

namespace rk {

struct DieHit {
  bool found = false;   // a triangle within the search margin
  double gap = 0;       // signed distance: < 0 inside the die
  // unit outward normal at the closest point: the triangle's; at an edge the sum of its two
  // triangles'; at a vertex the angle-weighted pseudo-normal (Baerentzen & Aanaes 2005: each
  // triangle's normal times its angle there), whose sign is right for any point near the vertex
  double normal[3] = {0, 0, 0};
  std::int32_t triangle = -1;    // the (first) triangle holding the closest point
};

// The squared distance from x to the box lo[3], hi[3]: a lower bound on its triangle's, cheap to reject with.
template <class Real>
inline double box_distance2(const Real* box, const double x[3]) {
  double box2 = 0;
  for (int d = 0; d < 3; ++d) {
    const double out = std::max({double(box[d]) - x[d], x[d] - double(box[3 + d]), 0.0});
    box2 += out * out;
  }
  return box2;
}

// Closest point to p on the triangle (a, b, c) (Ericson, Real-Time Collision Detection, 5.1.5).
void closest_point_on_triangle(const double p[3], const double a[3], const double b[3], const double c[3],
                               double out[3]);

class DieSearch {
 public:
  // skin: the farthest a point may move from where candidates() gathered its triangles (0: not used)
  DieSearch(const DieSurface& surface, double margin, double skin = 0);
  // The closest point among the triangles within the margin of x (no allocation).
  DieHit nearest(const double x[3]) const;
  // The triangles that can lie within the margin of any point within `skin` (<= skin()) of x (those
  // within margin + skin of x), ascending, into out; their count, or -1 where more than capacity.
  // Their boxes go to boxes (lo[3], hi[3] each, rounded outward to float): read with the triangles,
  // in one stream, instead of from the die's arrays.
  int candidates(const double x[3], double skin, std::int32_t* out, float* boxes, int capacity) const;
  // nearest(x) over the given triangles, ascending (boxes: candidates()', or null for the die's own):
  // bit for bit nearest(x)'s answer where they hold every triangle within the margin of x
  // (candidates() of a point within the skin of x). hint: a triangle likely the nearest (x's last
  // hit, or -1): its distance rejects the farther triangles before their closest points are sought.
  DieHit nearest_among(const double x[3], const std::int32_t* triangles, const float* boxes, int count,
                       std::int32_t hint = -1) const;
  // The same answer read from a part of them where it suffices: `near` (near_count, ascending, with
  // their boxes) holds every one of the triangles whose box may lie within sqrt(far2) of x; where the
  // hint is nearer than that, each of the others would be rejected by its box, so only `near` is read.
  DieHit nearest_among(const double x[3], const std::int32_t* triangles, const float* boxes, int count,
                       std::int32_t hint, const std::int32_t* near, const float* near_boxes, int near_count,
                       double far2) const;
  DieHit nearest(const double x[3], std::int32_t hint) const;  // nearest(x), with a hint
  std::size_t triangles() const { return normal_.size() / 3; }
  double margin() const { return margin_; }  // a point nearest() does not find is farther than this
  double skin() const { return skin_; }

 private:
  const DieSurface& s_;
  std::vector<double> normal_, box_;  // per triangle: unit normal; lo[3], hi[3]
  std::vector<double> angle_;         // per triangle: its angle at each corner (rad)
  double margin_ = 0, skin_ = 0;
  double lo_[3]{}, h_ = 1;
  std::int64_t dims_[3]{1, 1, 1};
  std::vector<std::int32_t> start_, items_;  // CSR: triangles per bin
  std::int64_t bin(const double x[3], int d) const;
  double distance2(std::int32_t t, const double x[3], double c[3]) const;  // to triangle t; c its closest point
  std::int64_t bin_of(const double x[3]) const;  // -1: x is beyond every triangle's margin and skin
  double hint_bound(const double x[3], std::int32_t hint) const;  // a bound on the nearest's squared distance
  DieHit nearest_within(const double x[3], const std::int32_t* triangles, const float* boxes, int count, double bound) const;
};

}  // namespace rk
