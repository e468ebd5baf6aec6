// The pointwise contact laws (solver/contact/contact_laws.hpp) against their closed forms:
// - the penalty stiffness k = s m / dt^2 and force k d n (its spring's energy k d^2 / 2 is the work
//   of that force over the depth: checked by the trapezoid rule on a linear force, exact);
// - the tangential relative velocity is orthogonal to the normal and leaves the normal part out;
// - Coulomb: below mu f_n the slave sticks with the stick force, above it slips with mu f_n, both
//   against v_t; the force's magnitude is min(f_s, mu f_n) for every ratio; no force with mu = 0
//   or without sliding; the friction's power -f . v_t is never negative (it only dissipates).
#include <gtest/gtest.h>

#include <cmath>

#include "contact/contact_laws.hpp"

namespace {

TEST(ContactLaws, PenaltyIsKTimesDepthAlongTheNormal) {
  const double k = rk::penalty_stiffness(0.5, 2e-3, 1e-7, 1e-7);
  EXPECT_DOUBLE_EQ(k, 0.5 * 2e-3 / 1e-14);
  // from the smallest step so far, however the step moved since; at most m / dt^2
  EXPECT_DOUBLE_EQ(rk::penalty_stiffness(0.5, 2e-3, 1e-7, 1.2e-7), k);
  EXPECT_DOUBLE_EQ(rk::penalty_stiffness(0.5, 2e-3, 1e-7, 2e-7), 2e-3 / 4e-14);
  const double n[3] = {0.6, 0.0, -0.8}, depth = 3e-6;
  double f[3];
  rk::penalty_force(k, depth, n, f);
  for (int i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ(f[i], k * depth * n[i]);
  // the work of f along -n from 0 to d (linear in the depth: the trapezoid rule is exact) is k d^2 / 2
  double f0[3], work = 0;
  rk::penalty_force(k, 0.0, n, f0);
  for (int i = 0; i < 3; ++i) work += 0.5 * (f0[i] + f[i]) * depth * n[i];
  EXPECT_NEAR(work, 0.5 * k * depth * depth, 1e-12 * k * depth * depth);
}

TEST(ContactLaws, TangentialVelocityDropsTheNormalPart) {
  const double n[3] = {0.0, 0.6, 0.8}, v[3] = {1.0, -2.0, 3.0};
  double vt[3];
  const double norm = rk::tangential_velocity(v, n, vt);
  EXPECT_NEAR(vt[0] * n[0] + vt[1] * n[1] + vt[2] * n[2], 0.0, 1e-15);
  const double vn = v[1] * n[1] + v[2] * n[2];  // 1.2
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(vt[i], v[i] - vn * n[i], 1e-15);
  EXPECT_NEAR(norm * norm, 1 + 4 + 9 - vn * vn, 1e-13);
}

TEST(ContactLaws, CoulombSticksBelowMuFnAndSlipsAbove) {
  const double n[3] = {0, 0, 1}, v[3] = {3.0, -4.0, 7.0};
  double vt[3], f[3];
  const double vt_norm = rk::tangential_velocity(v, n, vt);  // (3, -4, 0), 5
  ASSERT_DOUBLE_EQ(vt_norm, 5.0);
  const double fn = 100.0;
  for (double stick : {1.0, 10.0, 29.9, 30.1, 80.0, 1e6}) {  // mu f_n = 30
    rk::coulomb_friction(0.3, fn, stick, vt, vt_norm, f);
    const double expected = std::min(stick, 0.3 * fn);  // stick below, slip above
    EXPECT_NEAR(std::hypot(f[0], f[1], f[2]), expected, 1e-12 * expected) << "stick force " << stick;
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(f[i], -expected * vt[i] / 5.0, 1e-12 * expected);
    EXPECT_GT(-(f[0] * vt[0] + f[1] * vt[1] + f[2] * vt[2]), 0.0);  // dissipates
  }
}

TEST(ContactLaws, NoFrictionWithoutMuOrSliding) {
  const double vt[3] = {1, 0, 0}, rest[3] = {0, 0, 0};
  double f[3] = {7, 7, 7};
  rk::coulomb_friction(0.0, 100.0, 50.0, vt, 1.0, f);
  for (double fi : f) EXPECT_EQ(fi, 0.0);
  f[0] = f[1] = f[2] = 7;
  rk::coulomb_friction(0.5, 100.0, 0.0, rest, 0.0, f);
  for (double fi : f) EXPECT_EQ(fi, 0.0);
}

}  // namespace

namespace {

TEST(ShearFriction, ShearFactorAndHybridStressesAreTheForgingLaws) {
  const double flow = 100e6, k = flow / std::sqrt(3.0);
  EXPECT_DOUBLE_EQ(rk::shear_factor_stress(1.0, flow), k);  // sticking: the material's shear yield stress
  EXPECT_DOUBLE_EQ(rk::shear_factor_stress(0.3, flow), 0.3 * k);
  EXPECT_EQ(rk::shear_factor_stress(0.0, flow), 0.0);
  // hybrid: Coulomb below the pressure where mu p reaches m k, m k above it
  const double m = 0.4, mu = 0.2, p_switch = m * k / mu;
  EXPECT_DOUBLE_EQ(rk::hybrid_friction_stress(mu, 0.5 * p_switch, m, flow), mu * 0.5 * p_switch);
  EXPECT_DOUBLE_EQ(rk::hybrid_friction_stress(mu, 2 * p_switch, m, flow), m * k);
  EXPECT_EQ(rk::hybrid_friction_stress(mu, -1e6, m, flow), 0.0);  // a face pulled off its die
}

TEST(ShearFriction, TheForceIsTauTimesTheAreaAgainstTheSlidingUpToTheStickForce) {
  const double vt[3] = {3, 4, 0};  // |vt| = 5
  double f[3];
  rk::interface_friction(2e6, 1e-4, 1e9, vt, 5, f);  // slipping: tau A = 200 N
  EXPECT_DOUBLE_EQ(f[0], -200 * 0.6);
  EXPECT_DOUBLE_EQ(f[1], -200 * 0.8);
  EXPECT_EQ(f[2], 0);
  rk::interface_friction(2e6, 1e-4, 50, vt, 5, f);  // sticking: the force that stops it in one step
  EXPECT_DOUBLE_EQ(std::hypot(f[0], f[1]), 50);
  const double at_rest[3] = {0, 0, 0};
  rk::interface_friction(2e6, 1e-4, 1e9, at_rest, 0, f);
  EXPECT_EQ(f[0] * f[0] + f[1] * f[1] + f[2] * f[2], 0);
}

}  // namespace
