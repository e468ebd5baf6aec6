// Contact geometry: closest point on a triangle (every Voronoi region), the signed gap to a closed
// die surface (outside > 0, inside < 0, including near edges and corners), and the slaves' candidate
// lists against the bins.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "contact/die_candidates.hpp"
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

// A steep square pyramid (apex at the origin, base 2 x 2 at z = -3) whose +x face is a fan of three
// triangles at the apex. A point outside, nearest the apex, toward the -x face: the plain sum of the
// normals there, 3 n(+x) + n(-x) + n(+y) + n(-y), points away from it (the point would read inside, gap
// < 0); weighted by the triangles' angles at the apex, the fan counts as the one face it is.
TEST(DieSearch, PseudoNormalAtAVertexWeightedByAngles) {
  rk::DieSurface s;
  const double h = 3, a = 1;
  s.vertices = {0, 0, 0, a, -a, -h, a, a, -h, -a, a, -h, -a, -a, -h};  // apex 0, base 1..4 counter-clockwise
  const double fan[2][3] = {{a, -a / 3, -h}, {a, a / 3, -h}};  // the +x face's edge split in three
  for (const auto& v : fan) s.vertices.insert(s.vertices.end(), v, v + 3);
  s.triangles = {0, 1, 5, 0, 5, 6, 0, 6, 2,  // +x, fanned (counter-clockwise from outside)
                 0, 2, 3, 0, 3, 4, 0, 4, 1,  // +y, -x, -y
                 1, 4, 3, 1, 3, 2};          // the base
  const rk::DieSearch search(s, 1.0);
  const double c = a / std::sqrt(h * h + a * a), sn = h / std::sqrt(h * h + a * a);  // n(+x) = (sn, 0, c)
  const double nx[3] = {sn, 0, c}, mx[3] = {-sn, 0, c}, py[3] = {0, sn, c}, my[3] = {0, -sn, c};
  double x[3];
  for (int i = 0; i < 3; ++i) x[i] = 0.01 * (mx[i] + 0.2 * py[i] + 0.2 * my[i] + 0.05 * nx[i]);
  const double plain[3] = {3 * nx[0] + mx[0] + py[0] + my[0], 3 * nx[1] + mx[1] + py[1] + my[1], 3 * nx[2] + mx[2] + py[2] + my[2]};
  ASSERT_LT(x[0] * plain[0] + x[1] * plain[1] + x[2] * plain[2], 0.0);  // the plain sum would call it inside
  const rk::DieHit hit = search.nearest(x);
  ASSERT_TRUE(hit.found);
  EXPECT_NEAR(hit.gap, std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]), 1e-15);  // outside, at the apex
  EXPECT_NEAR(hit.normal[0], 0, 1e-12);  // the four faces' angles at the apex are equal: straight up
  EXPECT_NEAR(hit.normal[1], 0, 1e-12);
  EXPECT_NEAR(hit.normal[2], 1, 1e-12);
}

}  // namespace

// The unit cube with each face cut into n x n squares, two triangles each.
rk::DieSurface fine_cube(int n) {
  rk::DieSurface s;
  auto vertex = [&](double x, double y, double z) {
    s.vertices.insert(s.vertices.end(), {x, y, z});
    return int(s.vertices.size() / 3 - 1);
  };
  // each face: an origin, two edge directions (counter-clockwise seen from outside)
  const double faces[6][9] = {{0, 0, 0, 0, 1, 0, 1, 0, 0}, {0, 0, 1, 1, 0, 0, 0, 1, 0}, {0, 0, 0, 1, 0, 0, 0, 0, 1},
                              {0, 1, 0, 0, 0, 1, 1, 0, 0}, {0, 0, 0, 0, 0, 1, 0, 1, 0}, {1, 0, 0, 0, 1, 0, 0, 0, 1}};
  for (const auto& f : faces) {
    std::vector<int> id;
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const double a = double(i) / n, b = double(j) / n;
        id.push_back(vertex(f[0] + a * f[3] + b * f[6], f[1] + a * f[4] + b * f[7], f[2] + a * f[5] + b * f[8]));
      }
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int p = id[j * (n + 1) + i], q = id[j * (n + 1) + i + 1], r = id[(j + 1) * (n + 1) + i + 1],
                  t = id[(j + 1) * (n + 1) + i];
        s.triangles.insert(s.triangles.end(), {p, q, r, p, r, t});
      }
  }
  return s;
}

// A slave's candidate triangles answer as its bin does, bit for bit, whether the slave stays within the
// skin (the list kept) or leaves it (gathered again), inside the die or out, at faces, edges and
// corners, where a slave near the surface reads only its list's near part, and where a fine mesh puts
// more triangles near it than a list holds (the skin shrinks). Mutations caught (2026-12-05): the near
// part gathered half as far; the slave's move since the gathering not taken off the near part's reach.
TEST(DieCandidates, TheSameHitAsTheBinsAlongEveryPath) {
  for (int n : {4, 20}) {
    const rk::DieSurface cube = fine_cube(n);
    const rk::DieSearch search(cube, 0.1, 0.05);
    const int slaves = 300, steps = 200;
    rk::DieCandidates lists(slaves, 1);
    std::uint64_t seed = 12345;
    auto uniform = [&] {  // in [0, 1)
      seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
      return double(seed >> 11) * 0x1.0p-53;
    };
    std::vector<double> x(3 * slaves);
    for (double& v : x) v = -0.15 + 1.3 * uniform();
    int found = 0, inside = 0;
    for (int step = 0; step < steps; ++step)
      for (int s = 0; s < slaves; ++s) {
        double* y = &x[3 * std::size_t(s)];
        const double stride = step % 50 == 49 ? 0.2 : 0.004;  // now and then a jump past the skin
        for (int i = 0; i < 3; ++i) y[i] = std::clamp(y[i] + stride * (2 * uniform() - 1), -0.15, 1.15);
        const rk::DieHit a = search.nearest(y), b = lists.nearest(search, 0, std::size_t(s), y);
        ASSERT_EQ(a.found, b.found) << "slave " << s << " step " << step;
        if (!a.found) continue;
        ++found, inside += a.gap < 0;
        ASSERT_EQ(a.triangle, b.triangle) << "slave " << s << " step " << step;
        ASSERT_EQ(std::memcmp(&a.gap, &b.gap, sizeof a.gap), 0) << "slave " << s << " step " << step;
        ASSERT_EQ(std::memcmp(a.normal, b.normal, sizeof a.normal), 0) << "slave " << s << " step " << step;
      }
    EXPECT_GT(found, slaves * steps / 4) << n;  // the paths stay near the surface: most lookups find it
    EXPECT_GT(inside, slaves * steps / 20) << n;
  }
}
