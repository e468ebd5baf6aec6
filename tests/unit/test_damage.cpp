// The ductile damage criteria as pure laws (solver/material/damage.hpp) against their closed forms:
// uniaxial tension gives dD = d ep for both (sigma_1 = sigma_eq, sigma_m = sigma_1 / 3), uniaxial
// compression and hydrostatic pressure 0, pure shear 1/sqrt 3 (Cockcroft-Latham) and 2/3 (Brozzo);
// the largest principal stress against Eigen's eigenvalues for rotated tensors; invariance to a
// rotation of the stress.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "material/damage.hpp"

namespace {

TEST(Damage, ClosedFormsOfTheCriteria) {
  const double tension[6] = {300e6, 0, 0, 0, 0, 0}, compression[6] = {0, 0, -300e6, 0, 0, 0};
  const double pressure[6] = {-1e9, -1e9, -1e9, 0, 0, 0}, shear[6] = {0, 0, 0, 0, 100e6, 0};
  const double dep = 0.01;
  rk::DamageIncrement d = rk::damage_increment(tension, dep);
  EXPECT_NEAR(d.cockcroft_latham, dep, 1e-15);
  EXPECT_NEAR(d.brozzo, dep, 1e-15);
  d = rk::damage_increment(compression, dep);  // sigma_1 = 0 up to the cubic's round-off
  EXPECT_NEAR(d.cockcroft_latham, 0.0, 1e-15);
  EXPECT_NEAR(d.brozzo, 0.0, 1e-15);
  d = rk::damage_increment(pressure, dep);
  EXPECT_EQ(d.cockcroft_latham, 0.0);
  const double confined[6] = {-100e6, -100e6, -400e6, 0, 0, 0};  // compression under a die's confinement
  d = rk::damage_increment(confined, dep);
  EXPECT_EQ(d.cockcroft_latham, 0.0);
  EXPECT_EQ(d.brozzo, 0.0);
  d = rk::damage_increment(shear, dep);
  EXPECT_NEAR(d.cockcroft_latham, dep / std::sqrt(3.0), 1e-15);
  EXPECT_NEAR(d.brozzo, 2 * dep / 3, 1e-15);
  EXPECT_EQ(rk::damage_increment(tension, 0).cockcroft_latham, 0.0);  // no plastic strain, no damage
}

// Oyane's normalized integrand max(sigma_m / sigma_eq + a, 0): tension 1/3 + a, pure shear a,
// uniaxial compression a - 1/3 where positive, none under a die's confinement (sigma_m / sigma_eq =
// -2 here) nor where the scene gives no constant (a = 0 in compression)
TEST(Damage, OyaneClosedForms) {
  const double tension[6] = {300e6, 0, 0, 0, 0, 0}, compression[6] = {0, 0, -300e6, 0, 0, 0};
  const double shear[6] = {0, 0, 0, 0, 100e6, 0}, confined[6] = {-100e6, -100e6, -400e6, 0, 0, 0};
  const double dep = 0.01, a = 0.45;
  EXPECT_NEAR(rk::damage_increment(tension, dep, a).oyane, (1.0 / 3 + a) * dep, 1e-15);
  EXPECT_NEAR(rk::damage_increment(shear, dep, a).oyane, a * dep, 1e-15);
  EXPECT_NEAR(rk::damage_increment(compression, dep, a).oyane, (a - 1.0 / 3) * dep, 1e-15);
  EXPECT_EQ(rk::damage_increment(compression, dep, 0.2).oyane, 0.0);
  EXPECT_EQ(rk::damage_increment(confined, dep, a).oyane, 0.0);
  EXPECT_EQ(rk::damage_increment(tension, 0, a).oyane, 0.0);
  // the other criteria do not depend on it
  EXPECT_EQ(rk::damage_increment(shear, dep, a).brozzo, rk::damage_increment(shear, dep).brozzo);
}

TEST(Damage, LargestPrincipalStressMatchesEigenAndIsRotationInvariant) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 2000; ++k) {
    const double s[6] = {u(rng), u(rng), u(rng), u(rng), u(rng), u(rng)};
    Eigen::Matrix3d m;
    m << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
    const double largest = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m).eigenvalues().maxCoeff();
    EXPECT_NEAR(rk::largest_principal(s), largest, 1e-12) << k;
  }
  // uniaxial tension along a rotated axis: still sigma_1 = sigma_eq
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix3d t = R * Eigen::Vector3d(250e6, 0, 0).asDiagonal() * R.transpose();
  const double s[6] = {t(0, 0), t(1, 1), t(2, 2), t(0, 1), t(1, 2), t(2, 0)};
  EXPECT_NEAR(rk::damage_increment(s, 0.02).cockcroft_latham, 0.02, 1e-12);
  EXPECT_NEAR(rk::damage_increment(s, 0.02).brozzo, 0.02, 1e-12);
  const double equal[6] = {5, 5, 5, 0, 0, 0};  // a repeated root: the mean
  EXPECT_DOUBLE_EQ(rk::largest_principal(equal), 5.0);
}

}  // namespace
