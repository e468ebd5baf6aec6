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

}  // namespace
