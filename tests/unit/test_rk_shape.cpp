// Reproducing conditions of the RK shape functions: regular, 20 %-jittered
// and near-boundary particles, a/h = 1.5 and 2 (linear), 2.5 (quadratic).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "local_particles.hpp"
#include "neighbour_grid.hpp"
#include "rk_shape.hpp"

namespace {

struct Cloud {
  std::vector<double> X, V, a;
};

Cloud lattice(int n, double h, double jitter, double dilation) {
  Cloud c;
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int idx[3] = {i, j, k};
        for (int d = 0; d < 3; ++d) c.X.push_back(h * idx[d] + jitter * h * u(rng));
        c.V.push_back(h * h * h);
        c.a.push_back(dilation * h);
      }
  return c;
}

struct Case {
  double jitter, dilation;
  rk::Basis basis;
};

class Reproducing : public ::testing::TestWithParam<Case> {};

TEST_P(Reproducing, PolynomialsAndGradientsToRoundOff) {
  const Case p = GetParam();
  const double h = 1e-3;  // millimetre spacing: the conditions must hold at the solver's scales
  Cloud c = lattice(8, h, p.jitter, p.dilation);
  rk::NeighbourGrid grid(c.X.data(), c.a.data(), c.a.size());
  const rk::RkParticles parts{c.X.data(), c.V.data(), c.a.data()};
  // interior, near a face, near an edge, at a corner
  const double points[4][3] = {{3.3 * h, 3.7 * h, 4.1 * h}, {0.1 * h, 3.2 * h, 3.9 * h}, {0.05 * h, 0.2 * h, 4 * h}, {0, 0, 0}};
  for (const auto& x : points) {
    std::vector<std::int32_t> nb;
    grid.covering(x, nb);
    std::vector<double> N(nb.size()), dN(3 * nb.size());
    const auto r = rk::rk_shape(x, nb, parts, rk::Kernel::cubic_bspline, p.basis, N.data(), dN.data());
    ASSERT_TRUE(r.regular) << "at " << x[0] << "," << x[1] << "," << x[2];
    // N alone (no dN: the material rows, the constraints' rows) is bit for bit the same N
    std::vector<double> N_alone(nb.size(), -1.0);
    const auto r_alone = rk::rk_shape(x, nb, parts, rk::Kernel::cubic_bspline, p.basis, N_alone.data(), nullptr);
    EXPECT_TRUE(r_alone.regular);
    EXPECT_EQ(r_alone.rcond, r.rcond);
    for (std::size_t k = 0; k < nb.size(); ++k) EXPECT_EQ(N_alone[k], N[k]) << "neighbour " << k;
    double sum = 0, first[3] = {0, 0, 0}, grad[3] = {0, 0, 0}, second[3][3] = {}, quad[6] = {};
    for (std::size_t k = 0; k < nb.size(); ++k) {
      const double* X = &c.X[3 * nb[k]];
      sum += N[k];
      for (int i = 0; i < 3; ++i) {
        first[i] += N[k] * X[i];
        grad[i] += dN[3 * k + i];
        for (int j = 0; j < 3; ++j) second[i][j] += X[i] * dN[3 * k + j];
      }
      for (int i = 0; i < 3; ++i) quad[i] += N[k] * X[i] * X[i];
      quad[3] += N[k] * X[0] * X[1], quad[4] += N[k] * X[1] * X[2], quad[5] += N[k] * X[2] * X[0];
    }
    EXPECT_NEAR(sum, 1.0, 1e-12);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(first[i] / h, x[i] / h, 1e-12) << "sum N_I X_I = X";
      EXPECT_NEAR(grad[i] * h, 0.0, 1e-12) << "sum grad N_I = 0";
      for (int j = 0; j < 3; ++j) EXPECT_NEAR(second[i][j], i == j ? 1.0 : 0.0, 1e-12) << "sum X_I (x) grad N_I = I";
    }
    if (p.basis == rk::Basis::quadratic) {
      const double exact[6] = {x[0] * x[0], x[1] * x[1], x[2] * x[2], x[0] * x[1], x[1] * x[2], x[2] * x[0]};
      for (int i = 0; i < 6; ++i) EXPECT_NEAR(quad[i] / (h * h), exact[i] / (h * h), 1e-12) << "quadratic term " << i;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Clouds, Reproducing,
                         ::testing::Values(Case{0.0, 1.5, rk::Basis::linear}, Case{0.0, 2.0, rk::Basis::linear},
                                           Case{0.2, 1.5, rk::Basis::linear}, Case{0.2, 2.0, rk::Basis::linear},
                                           Case{0.0, 2.5, rk::Basis::quadratic}, Case{0.2, 2.5, rk::Basis::quadratic}),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           const Case& c = info.param;
                           return std::string(c.basis == rk::Basis::linear ? "linear" : "quadratic") + "_jitter" +
                                  std::to_string(int(100 * c.jitter)) + "_dilation" + std::to_string(int(10 * c.dilation));
                         });

TEST(RkShape, TooFewNeighboursIsReportedSingular) {
  Cloud c = lattice(4, 1.0, 0.0, 0.9);  // support smaller than the spacing: one particle per point
  const rk::RkParticles parts{c.X.data(), c.V.data(), c.a.data()};
  std::vector<std::int32_t> nb{0};
  double N[1], dN[3];
  const double x[3] = {0.1, 0.1, 0.1};
  EXPECT_FALSE(rk::rk_shape(x, nb, parts, rk::Kernel::cubic_bspline, rk::Basis::linear, N, dN).regular);
}

}  // namespace

namespace {

double spread_at(const Cloud& c, const double x[3]) {
  rk::NeighbourGrid grid(c.X.data(), c.a.data(), c.a.size());
  const rk::RkParticles parts{c.X.data(), c.V.data(), c.a.data()};
  std::vector<std::int32_t> nb;
  grid.covering(x, nb);
  return rk::neighbour_spread(x, nb, parts, rk::Kernel::cubic_bspline);
}

// The placement measure the reference updates grow supports by (solver/rk/reference_update.cpp, kPoor
// 0.03) must stay well above it at every point of a fresh lattice, the faces, edges and corners
// included (a fresh prep never needs growing), and fall to zero where the particles around a point
// are flat (below).
TEST(RkShape, SpreadOfAFreshLatticeIsAboveAThird) {
  const double h = 1e-3;
  const Cloud c = lattice(8, h, 0.0, 2.0);
  const double points[4][3] = {{3.3 * h, 3.7 * h, 4.1 * h}, {0.1 * h, 3.2 * h, 3.9 * h}, {0.05 * h, 0.2 * h, 4 * h}, {0, 0, 0}};
  for (const auto& x : points)
    EXPECT_GT(spread_at(c, x), 0.3) << "at " << x[0] / h << ", " << x[1] / h << ", " << x[2] / h << " h";
}

TEST(RkShape, SpreadFallsForAFlatNeighbourhood) {
  const double h = 1e-3, x[3] = {3.3 * h, 3.7 * h, 0.0};
  Cloud c = lattice(8, h, 0.0, 2.0);
  for (std::size_t I = 0; I < c.a.size(); ++I) c.X[3 * I + 2] *= 1e-3;  // layers squeezed to a sheet
  EXPECT_LT(spread_at(c, x), 1e-4);
}

}  // namespace

// One search for a cell's points (near_group, then covering_among per point) gives each point exactly
// the columns of its own search, in the same order, whatever the supports' sizes: the grouped search
// picks the columns of the shape functions at the start and at every reference update, so the same
// columns give the same shape functions.
TEST(NeighbourGrid, AGroupsSearchGivesEachPointItsOwnColumns) {
  const double h = 1e-3;
  Cloud c = lattice(9, h, 0.3, 2.0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (auto& a : c.a) a *= 0.6 + 0.9 * u(rng);  // supports 1.2-3.0 spacings (grown ones beside t = 0 ones)
  const rk::NeighbourGrid grid(c.X.data(), c.a.data(), c.a.size());
  std::size_t points = 0, columns = 0;
  for (int cell = 0; cell < 200; ++cell) {
    // a sheared cell's 8 points, some cells reaching past the cloud's faces
    const double o[3] = {-h + 10 * h * u(rng), -h + 10 * h * u(rng), -h + 10 * h * u(rng)}, e = h * (0.2 + 1.5 * u(rng));
    std::vector<double> x;
    for (int q = 0; q < 8; ++q)
      for (int d = 0; d < 3; ++d) x.push_back(o[d] + ((q >> d) & 1) * e + (d == 0 ? 0.7 * e * ((q >> 2) & 1) : 0.0));
    std::vector<std::int32_t> candidates, among, own;
    grid.near_group(x.data(), 8, candidates);
    ASSERT_TRUE(std::is_sorted(candidates.begin(), candidates.end()));
    for (int q = 0; q < 8; ++q) {
      among.clear(), own.clear();
      grid.covering_among(&x[3 * q], candidates, among);
      grid.covering(&x[3 * q], own);
      ASSERT_EQ(among, own) << "cell " << cell << ", point " << q;
      ++points, columns += own.size();
    }
  }
  for (int q = 0; q < 50; ++q) {  // groups of one point (a particle's own search)
    const double x[3] = {10 * h * u(rng), 10 * h * u(rng), 10 * h * u(rng)};
    std::vector<std::int32_t> candidates, among, own;
    grid.near_group(x, 1, candidates);
    grid.covering_among(x, candidates, among);
    grid.covering(x, own);
    ASSERT_EQ(among, own) << "single point " << q;
  }
  EXPECT_GT(columns, 20 * points);  // the points sit among the particles, not beside them
}

// The local particles (rkprep's subdomains, the reference updates' halos) by one search per cell give
// the set that one search per point gives, a face point left ungrouped included.
TEST(LocalParticles, GroupedByCellTheSameSetAsPointByPoint) {
  const double h = 1e-3;
  Cloud c = lattice(9, h, 0.3, 2.0);
  const rk::NeighbourGrid grid(c.X.data(), c.a.data(), c.a.size());
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  rk::LocalParticleRequest single{grid, c.X.data(), {}, {}, {}, {}};
  std::vector<std::int32_t> groups;
  for (int cell = 0; cell < 12; ++cell) {  // a corner of the cloud: far particles stay out
    groups.push_back(std::int32_t(single.points.size() / 3));
    const double o[3] = {3 * h * u(rng), 3 * h * u(rng), 3 * h * u(rng)};
    for (int q = 0; q < 8; ++q)
      for (int d = 0; d < 3; ++d) single.points.push_back(o[d] + 0.8 * h * ((q >> d) & 1));
  }
  groups.push_back(std::int32_t(single.points.size() / 3));
  for (int d = 0; d < 3; ++d) single.points.push_back(7.5 * h);  // past the last group: searched alone
  single.owned = {0, 5};
  rk::LocalParticleRequest grouped = single;
  grouped.point_groups = groups;
  const auto by_point = rk::local_particles(single), by_cell = rk::local_particles(grouped);
  EXPECT_EQ(by_cell, by_point);
  EXPECT_GT(by_point.size(), 100u);
  EXPECT_LT(by_point.size(), c.a.size());
}
