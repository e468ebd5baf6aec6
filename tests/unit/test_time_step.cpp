// The stable step is measured from the smallest principal stretch of F at the integration points.
#include <gtest/gtest.h>

#include <cmath>

#include "time_step.hpp"

namespace {

// F = R diag(a, b, c) Q: stretches a, b, c between two rotations
void stretch_between_rotations(double a, double b, double c, double F[9]) {
  const double s = std::sin(0.7), co = std::cos(0.7), s2 = std::sin(-1.1), c2 = std::cos(-1.1);
  const double R[9] = {co, -s, 0, s, co, 0, 0, 0, 1};      // about z
  const double Q[9] = {1, 0, 0, 0, c2, -s2, 0, s2, c2};    // about x
  const double D[3] = {a, b, c};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      F[3 * i + j] = 0;
      for (int k = 0; k < 3; ++k) F[3 * i + j] += R[3 * i + k] * D[k] * Q[3 * k + j];
    }
}

TEST(TimeStep, SmallestStretchIsTheSmallestSingularValue) {
  const double cases[][3] = {{1, 1, 1}, {2, 0.5, 1}, {0.05, 3, 3}, {1.2, 1.2, 0.3}, {0.7, 0.7, 0.7}, {1e-3, 1, 20}};
  for (const auto& k : cases) {
    double F[9];
    stretch_between_rotations(k[0], k[1], k[2], F);
    const double expected = std::min({k[0], k[1], k[2]});
    EXPECT_NEAR(rk::smallest_stretch(F, k[0] * k[1] * k[2]), expected, 1e-11 * expected) << k[0] << " " << k[1] << " " << k[2];
  }
  const double shear[9] = {1, 1, 0, 0, 1, 0, 0, 0, 1};  // simple shear, gamma = 1: (sqrt 5 - 1) / 2
  EXPECT_NEAR(rk::smallest_stretch(shear, 1.0), (std::sqrt(5.0) - 1) / 2, 1e-12);
}

TEST(TimeStep, GershgorinFloorBoundsTheSmallestEigenvalueFromBelow) {
  // a bound (never above lambda_min(C)), exact for a pure stretch, and close to it near F = I, where
  // the time step uses it to skip the eigenvalue formula
  const double cases[][3] = {{1, 1, 1}, {2, 0.5, 1}, {0.05, 3, 3}, {1.2, 1.2, 0.3}, {0.98, 1.01, 1.03}, {1e-3, 1, 20}};
  for (const auto& k : cases) {
    double F[9];
    stretch_between_rotations(k[0], k[1], k[2], F);
    const double lambda = std::pow(std::min({k[0], k[1], k[2]}), 2);
    EXPECT_LE(rk::gershgorin_floor(F), lambda * (1 + 1e-12)) << k[0] << " " << k[1] << " " << k[2];
  }
  const double D[9] = {0.9, 0, 0, 0, 1.3, 0, 0, 0, 1.1};
  EXPECT_DOUBLE_EQ(rk::gershgorin_floor(D), 0.81);
  double near[9] = {1.01, 0.02, -0.01, 0.0, 0.99, 0.015, 0.01, -0.02, 1.0};  // a small strain
  const double J = near[0] * (near[4] * near[8] - near[5] * near[7]) - near[1] * (near[3] * near[8] - near[5] * near[6]) +
                   near[2] * (near[3] * near[7] - near[4] * near[6]);
  const double exact = std::pow(rk::smallest_stretch(near, J), 2), floor = rk::gershgorin_floor(near);
  EXPECT_LE(floor, exact);
  EXPECT_GT(floor, 0.9 * exact) << "tight near F = I";
}

}  // namespace
