// prep/jitter: irregular particle layouts for the stability study.
#include <gtest/gtest.h>

#include <cmath>

#include "jitter.hpp"

namespace {

rk::VolumeMesh lattice(int n) {  // (n+1)^3 nodes, unit spacing, surface flags on the cube's faces
  rk::VolumeMesh m;
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        m.X.insert(m.X.end(), {double(i), double(j), double(k)});
        m.surface.push_back(i == 0 || j == 0 || k == 0 || i == n || j == n || k == n);
      }
  return m;
}

TEST(Jitter, MovesOnlyInteriorParticlesWithinTheBound) {
  const rk::VolumeMesh m = lattice(6);
  const std::vector<double> spacing(m.node_count(), 2.0);
  rk::VolumeMesh j = m;
  rk::jitter_interior(j, spacing, 0.4);
  double largest = 0, moved = 0;
  for (std::size_t I = 0; I < m.node_count(); ++I)
    for (int d = 0; d < 3; ++d) {
      const double off = std::abs(j.X[3 * I + d] - m.X[3 * I + d]);
      if (m.surface[I]) {
        EXPECT_EQ(off, 0.0) << "surface node " << I;
      }
      largest = std::max(largest, off);
      moved += off > 0;
    }
  EXPECT_LT(largest, 0.4 * 2.0);   // up to fraction x spacing per axis
  EXPECT_GT(largest, 0.7 * 0.8);   // and the offsets span most of that range (125 x 3 draws)
  EXPECT_EQ(moved, 125 * 3);        // every interior coordinate moved
}

TEST(Jitter, IsDeterministicAndZeroIsTheIdentity) {
  const rk::VolumeMesh m = lattice(4);
  const std::vector<double> spacing(m.node_count(), 1.0);
  rk::VolumeMesh a = m, b = m, zero = m;
  rk::jitter_interior(a, spacing, 0.3);
  rk::jitter_interior(b, spacing, 0.3);
  rk::jitter_interior(zero, spacing, 0.0);
  EXPECT_EQ(a.X, b.X);
  EXPECT_NE(a.X, m.X);
  EXPECT_EQ(zero.X, m.X);
}

}  // namespace
