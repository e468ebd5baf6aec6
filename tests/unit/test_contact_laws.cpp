// The pointwise contact laws (solver/contact/contact_laws.hpp) against their closed forms:
// - the penalty stiffness k = s m / dt^2 and force k d n (its spring's energy k d^2 / 2 is the work
//   of that force over the depth: checked by the trapezoid rule on a linear force, exact);
// - the dashpot of a spring held at its step's limit (k = m / dt^2): 2 xi m / dt there, none below it;
//   a slave loaded onto such a spring by a steady force settles at F / k as the central difference's
//   closed form says (its roots' modulus sqrt(1 - 2 xi) per step), where the undamped one rings on;
// - the tangential relative velocity is orthogonal to the normal and leaves the normal part out;
// - Coulomb with an elastic stick: the force grows as k times the slip while under mu f_n, then
//   slips at mu f_n, against v_t; the friction's work is the spring's energy plus mu f_n over the
//   slip beyond the spring's; sliding back unloads the spring first; the carried force leaves its
//   normal part and is capped by a falling mu f_n; no force with mu = 0 or without sliding and load.
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
  EXPECT_DOUBLE_EQ(rk::penalty_force(k, depth, 0.0, -1.0, n, f), k * depth);  // no dashpot: the spring alone
  for (int i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ(f[i], k * depth * n[i]);
  // the work of f along -n from 0 to d (linear in the depth: the trapezoid rule is exact) is k d^2 / 2
  double f0[3], work = 0;
  rk::penalty_force(k, 0.0, 0.0, 0.0, n, f0);
  for (int i = 0; i < 3; ++i) work += 0.5 * (f0[i] + f[i]) * depth * n[i];
  EXPECT_NEAR(work, 0.5 * k * depth * depth, 1e-12 * k * depth * depth);
}

TEST(ContactLaws, ASpringHeldAtItsStepsLimitIsDampedAndSettles) {
  const double s = 0.81, m = 2e-3, dt_min = 1e-7, xi = 0.2;
  // below the limit (dt^2 s <= dt_min^2) no dashpot; past it 2 xi m / dt, the spring at m / dt^2
  EXPECT_EQ(rk::penalty_damping(xi, s, m, dt_min, 1.1 * dt_min), 0.0);
  const double dt = 2 * dt_min, k = rk::penalty_stiffness(s, m, dt_min, dt);
  ASSERT_DOUBLE_EQ(k, m / (dt * dt));
  ASSERT_DOUBLE_EQ(rk::penalty_damping(xi, s, m, dt_min, dt), 2 * xi * m / dt);
  EXPECT_EQ(rk::penalty_damping(0.0, s, m, dt_min, dt), 0.0);
  // the dashpot resists the approach, and the spring with it never pulls on a slave leaving fast
  const double n[3] = {0, 0, 1};
  double f[3];
  rk::penalty_force(k, 1e-6, 2 * xi * m / dt, -0.1, n, f);
  EXPECT_DOUBLE_EQ(f[2], k * 1e-6 + 2 * xi * m / dt * 0.1);
  rk::penalty_force(k, 1e-6, 2 * xi * m / dt, 100.0, n, f);
  EXPECT_EQ(f[2], 0.0);
  // A slave pressed onto the obstacle by a steady force F from rest at zero depth, stepped as the
  // solver steps it (the force from the depth at t^n and the velocity v^{n-1/2}): with
  // omega dt = 1 the depth's error e obeys e'' = -e - 2 xi (e - e_prev), roots of
  // lambda^2 - (1 - 2 xi) lambda + (1 - 2 xi) = 0, of modulus r = sqrt(1 - 2 xi) = 0.775 at xi = 0.2:
  // the error after n steps is C r^n of F / k, C = 1.3 for these roots (1 / sin of their argument,
  // 50 degrees), bounded here by 2 r^n; undamped (r = 1) it keeps ringing at the amplitude F / k.
  const double F = 50.0;
  auto settle = [&](double damping, int steps, bool last_only) {
    double depth = 0, v = 0, worst = 0;  // v along -n: into the obstacle
    for (int i = 1; i <= steps; ++i) {
      rk::penalty_force(k, depth, rk::penalty_damping(damping, s, m, dt_min, dt), -v, n, f);
      v += dt * (F - f[2]) / m;
      depth = std::max(depth + dt * v, 0.0);
      if (i == steps || (!last_only && i > steps - 10)) worst = std::max(worst, std::abs(depth - F / k) / (F / k));
    }
    return worst;
  };
  for (const int steps : {20, 40, 60}) EXPECT_LT(settle(xi, steps, true), 2 * std::pow(std::sqrt(1 - 2 * xi), steps));
  EXPECT_GT(settle(0.0, 60, false), 0.5);
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

TEST(ContactLaws, CoulombsStickLoadsWithTheSlipUpToMuFnThenSlips) {
  const double n[3] = {0, 0, 1}, v[3] = {3.0, -4.0, 7.0}, none[3] = {0, 0, 0};
  double vt[3];
  ASSERT_DOUBLE_EQ(rk::tangential_velocity(v, n, vt), 5.0);  // (3, -4, 0)
  const double mu = 0.3, fn = 100.0, k = 1e3, dt = 1e-3;  // mu f_n = 30; each step slides 5 mm: k dt |v_t| = 5 N
  double f[3] = {0, 0, 0}, slid = 0, work = 0;
  for (int step = 1; step <= 8; ++step) {
    double next[3];
    rk::coulomb_friction(mu, fn, k, f, n, vt, dt, next);
    slid += 5e-3;
    const double magnitude = std::hypot(next[0], next[1], next[2]);
    // stuck: the spring's force k times the slip so far (6 steps reach mu f_n); then it slips at mu f_n
    EXPECT_NEAR(magnitude, std::min(k * slid, mu * fn), 1e-12) << "step " << step;
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(next[i], -magnitude * vt[i] / 5.0, 1e-12) << "against the sliding";
    work -= dt * (next[0] * vt[0] + next[1] * vt[1] + next[2] * vt[2]);
    for (int i = 0; i < 3; ++i) f[i] = next[i];
  }
  // what the friction took: the spring's energy at mu f_n plus mu f_n over the slip beyond the spring's
  const double stuck_slip = mu * fn / k;
  EXPECT_NEAR(work, rk::stick_energy(f, k) + mu * fn * (slid - stuck_slip) + 0.5 * 5.0 * 30e-3, 1e-9)
      << "the trapezoid's excess over the loading steps: 6 steps of 5 N x 5 mm / 2";
  EXPECT_DOUBLE_EQ(rk::stick_energy(f, k), 30.0 * 30.0 / 2e3);
  // sliding back, the spring unloads first: elastic, the force falls by k dt |v_t| a step
  const double back[3] = {-vt[0], -vt[1], -vt[2]};
  double after[3];
  rk::coulomb_friction(mu, fn, k, f, n, back, dt, after);
  EXPECT_NEAR(std::hypot(after[0], after[1], after[2]), 25.0, 1e-12);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(after[i], f[i] * 25.0 / 30.0, 1e-12);
  // the last force's part along the normal is not carried (the tangent plane it acts in); at rest it holds
  const double tilted[3] = {1.0, 2.0, 7.0};
  rk::coulomb_friction(mu, fn, k, tilted, n, none, dt, after);
  EXPECT_DOUBLE_EQ(after[0], 1.0);
  EXPECT_DOUBLE_EQ(after[1], 2.0);
  EXPECT_DOUBLE_EQ(after[2], 0.0);
  // a lower normal force caps a carried force at the new mu f_n, in its direction
  rk::coulomb_friction(mu, 10.0, k, f, n, none, dt, after);
  EXPECT_NEAR(std::hypot(after[0], after[1], after[2]), 3.0, 1e-12);
}

TEST(ContactLaws, NoFrictionWithoutMuOrSliding) {
  const double vt[3] = {1, 0, 0}, rest[3] = {0, 0, 0}, n[3] = {0, 0, 1}, carried[3] = {5, 0, 0};
  double f[3] = {7, 7, 7};
  rk::coulomb_friction(0.0, 100.0, 1e3, carried, n, vt, 1e-3, f);
  for (double fi : f) EXPECT_EQ(fi, 0.0);
  f[0] = f[1] = f[2] = 7;
  rk::coulomb_friction(0.5, 100.0, 1e3, rest, n, rest, 1e-3, f);
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

TEST(ShearFriction, TheForceIsTauTimesTheAreaAgainstTheSlidingBeyondTheStick) {
  const double vt[3] = {3, 4, 0}, n[3] = {0, 0, 1}, none[3] = {0, 0, 0};  // |vt| = 5
  double f[3];
  rk::interface_friction(2e6, 1e-4, 1e9, none, n, vt, 1e-3, f);  // slipping: the stick's 5e6 N past tau A = 200 N
  EXPECT_DOUBLE_EQ(f[0], -200 * 0.6);
  EXPECT_DOUBLE_EQ(f[1], -200 * 0.8);
  EXPECT_EQ(f[2], 0);
  rk::interface_friction(2e6, 1e-4, 1e4, none, n, vt, 1e-3, f);  // sticking: k dt |v_t| = 50 N, the spring's
  EXPECT_DOUBLE_EQ(std::hypot(f[0], f[1]), 50);
  const double carried[3] = {f[0], f[1], f[2]};
  rk::interface_friction(2e6, 1e-4, 1e4, carried, n, vt, 1e-3, f);  // loaded on: 100 N
  EXPECT_DOUBLE_EQ(std::hypot(f[0], f[1]), 100);
  rk::interface_friction(0.0, 1e-4, 1e4, carried, n, vt, 1e-3, f);  // no stress: no force
  EXPECT_EQ(f[0] * f[0] + f[1] * f[1] + f[2] * f[2], 0);
  rk::interface_friction(2e6, 1e-4, 1e9, none, n, none, 1e-3, f);
  EXPECT_EQ(f[0] * f[0] + f[1] * f[1] + f[2] * f[2], 0);
}

}  // namespace
