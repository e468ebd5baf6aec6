// Contact geometry: closest point on a triangle (every Voronoi region) and the signed gap to a
// closed die surface (outside > 0, inside < 0, including near edges and corners).
#include <gtest/gtest.h>

#include <cmath>

#include "die_search.hpp"

namespace {

TEST(ClosestPoint, EveryRegionOfTheTriangle) {
  const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
  struct Case {
    double p[3], q[3];
  } cases[] = {
      {{0.2, 0.2, 1.0}, {0.2, 0.2, 0}},    // face interior: straight down
      {{-1, -1, 0.5}, {0, 0, 0}},          // vertex a
      {{2, -0.5, 0}, {1, 0, 0}},           // vertex b
      {{-0.2, 3, 0}, {0, 1, 0}},           // vertex c
      {{0.5, -1, 0}, {0.5, 0, 0}},         // edge ab
      {{-1, 0.5, 0.3}, {0, 0.5, 0}},       // edge ac
      {{1, 1, 0}, {0.5, 0.5, 0}},          // edge bc
  };
  for (const auto& k : cases) {
    double out[3];
    rk::closest_point_on_triangle(k.p, a, b, c, out);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(out[i], k.q[i], 1e-15) << "point " << k.p[0] << "," << k.p[1];
  }
}

rk::DieSurface unit_cube() {  // [0,1]^3, 12 triangles, counter-clockwise seen from outside
  rk::DieSurface s;
  for (int k = 0; k < 8; ++k) s.vertices.insert(s.vertices.end(), {double(k & 1), double((k >> 1) & 1), double((k >> 2) & 1)});
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) s.triangles.insert(s.triangles.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
  return s;
}

TEST(DieSearch, SignedGapOutsideInsideEdgesCorners) {
  const rk::DieSurface cube = unit_cube();
  const rk::DieSearch search(cube, 1.0);
  struct Case {
    double x[3], gap, n[3];
  } cases[] = {
      {{0.5, 0.5, 1.3}, 0.3, {0, 0, 1}},      // above the top face
      {{0.5, 0.5, 0.9}, -0.1, {0, 0, 1}},     // just inside under the top face
      {{0.5, -0.25, 0.5}, 0.25, {0, -1, 0}},  // in front of a side face
      {{0.3, 0.02, 0.5}, -0.02, {0, -1, 0}},  // inside near that face
      {{1.3, 0.5, 1.4}, 0.5, {0, 0, 0}},      // beyond an edge: distance to the edge
      {{1.2, 1.2, 1.2}, std::sqrt(0.12), {0, 0, 0}},  // beyond a corner
  };
  for (const auto& k : cases) {
    const rk::DieHit hit = search.nearest(k.x);
    ASSERT_TRUE(hit.found);
    EXPECT_NEAR(hit.gap, k.gap, 1e-12) << k.x[0] << "," << k.x[1] << "," << k.x[2];
    if (k.n[0] || k.n[1] || k.n[2]) {  // braces: EXPECT_NEAR expands to an if-else
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(hit.normal[i], k.n[i], 1e-12);
    }
  }
  const double far[3] = {5, 5, 5};
  EXPECT_FALSE(search.nearest(far).found) << "beyond the search margin";
}

}  // namespace
