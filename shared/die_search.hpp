// Closest-point queries against a rigid die surface (triangles with outward normals), in the die's
// own frame: the dies only translate, so the bucket grid is built once and never refreshed.
// Used by rkprep (a workpiece must not start inside a die) and rksolve (particle-to-segment contact).
#pragma once
#include <cstdint>
#include <vector>

#include "neighbour_grid.hpp"
#include "subdomain.hpp"

namespace rk {

struct DieHit {
  bool found = false;   // a triangle within the search margin
  double gap = 0;       // signed distance: < 0 inside the die
  double normal[3] = {0, 0, 0};  // unit outward normal at the closest point (pseudo-normal at edges)
};

// Closest point to p on the triangle (a, b, c) (Ericson, Real-Time Collision Detection, 5.1.5).
void closest_point_on_triangle(const double p[3], const double a[3], const double b[3], const double c[3],
                               double out[3]);

class DieSearch {
 public:
  DieSearch(const DieSurface& surface, double margin);
  // `scratch` holds candidate triangles (reserve it once: then no allocation per query).
  DieHit nearest(const double x[3], std::vector<std::int32_t>& scratch) const;
  std::size_t triangles() const { return normal_.size() / 3; }

 private:
  const DieSurface& s_;
  std::vector<double> centre_, radius_, normal_;
  NeighbourGrid grid_;
};

}  // namespace rk
