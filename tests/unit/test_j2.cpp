// J2 return mapping: uniaxial stress-strain curve against the closed form,
// stress on the yield surface after plastic steps, objectivity under a rigid rotation.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "material/j2_point.hpp"
#include "return_check.hpp"

namespace {

const rk::J2Params kCopper = rk::J2Params::from(117e9, 0.35, 400e6, 100e6, true);

double von_mises(const Eigen::Matrix3d& tau) {
  const Eigen::Matrix3d s = tau - tau.trace() / 3 * Eigen::Matrix3d::Identity();
  return std::sqrt(1.5 * (s.array() * s.array()).sum());
}

// Uniaxial stress along x in log strain eps: the lateral stretch is found so that tau_yy = tau_zz = 0.
struct Uniaxial {
  double cp[6] = {1, 1, 1, 0, 0, 0};
  double ep = 0;
  rk::J2Update step(double eps) {
    double lam = std::exp(-0.35 * eps), lo = 0.2, hi = 1.5;
    rk::J2Update up;
    for (int it = 0; it < 200; ++it) {  // bisection on the lateral stretch
      lam = 0.5 * (lo + hi);
      double cp_try[6];
      std::copy(cp, cp + 6, cp_try);
      double ep_try = ep;
      up = rk::j2_update(Eigen::Vector3d(std::exp(eps), lam, lam).asDiagonal().toDenseMatrix(), kCopper, cp_try, ep_try);
      (up.tau(1, 1) > 0 ? hi : lo) = lam;
    }
    up = rk::j2_update(Eigen::Vector3d(std::exp(eps), lam, lam).asDiagonal().toDenseMatrix(), kCopper, cp, ep);
    return up;
  }
};

TEST(J2, UniaxialCurveMatchesClosedForm) {
  // Elastic: tau = E eps. Plastic (linear hardening, log strains): tau = (sy0 + H eps) / (1 + H/E).
  const double E = 117e9, sy0 = 400e6, H = 100e6;
  Uniaxial test;
  for (double eps = 0.0005; eps <= 0.5; eps += 0.0005) {
    const rk::J2Update up = test.step(eps);
    const double expected = eps < sy0 / E ? E * eps : (sy0 + H * eps) / (1 + H / E);
    ASSERT_NEAR(up.tau(0, 0), expected, 1e-6 * expected) << "eps = " << eps;
    ASSERT_NEAR(up.tau(1, 1), 0.0, 1e-3 * expected);
  }
  EXPECT_NEAR(test.ep, 0.5 - test.step(0.5).tau(0, 0) / E, 1e-6);
}

TEST(J2, PlasticStressStaysOnTheYieldSurface) {
  double cp[6] = {1, 1, 1, 0, 0, 0}, ep = 0;
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  for (int k = 1; k <= 50; ++k) {  // a non-proportional path: shear then stretch
    F(0, 1) = 0.01 * k;
    F(2, 2) = 1 + 0.004 * k;
    const rk::J2Update up = rk::j2_update(F, kCopper, cp, ep);
    if (ep > 0) {
      EXPECT_NEAR(von_mises(up.tau), 400e6 + 100e6 * ep, 1e-9 * 400e6) << "step " << k;
      EXPECT_GT(up.dissipation, 0.0);
    }
  }
  EXPECT_GT(ep, 0.1);
}

TEST(J2, RigidRotationRotatesTheStressAndChangesNothingElse) {
  double cp[6] = {1, 1, 1, 0, 0, 0}, ep = 0;
  Eigen::Matrix3d F;
  F << 1.08, 0.05, 0.0, 0.02, 0.95, 0.03, 0.0, 0.01, 0.99;
  const rk::J2Update first = rk::j2_update(F, kCopper, cp, ep);
  ASSERT_GT(ep, 0.0);
  // continue from the same plastic state once with F2 and once with R F2
  Eigen::Matrix3d F2 = F;
  F2(0, 0) += 0.01;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  double cpa[6], cpb[6], epa = ep, epb = ep;
  std::copy(cp, cp + 6, cpa), std::copy(cp, cp + 6, cpb);
  const rk::J2Update a = rk::j2_update(F2, kCopper, cpa, epa);
  const rk::J2Update b = rk::j2_update(R * F2, kCopper, cpb, epb);
  EXPECT_NEAR(epa, epb, 1e-14);
  EXPECT_NEAR(a.psi, b.psi, 1e-9 * std::abs(a.psi));
  EXPECT_LT((R * a.tau * R.transpose() - b.tau).norm(), 1e-9 * a.tau.norm());
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(cpa[i], cpb[i], 1e-12) << "plastic state is rotation invariant";
  (void)first;
}

TEST(J2, ElasticModelNeverYields) {
  const rk::J2Params elastic = rk::J2Params::from(71e9, 0.3, 0, 0, false);
  double cp[6] = {1, 1, 1, 0, 0, 0}, ep = 0;
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  F(0, 0) = 1.2;
  const rk::J2Update up = rk::j2_update(F, elastic, cp, ep);
  EXPECT_EQ(ep, 0.0);
  EXPECT_EQ(up.dissipation, 0.0);
  // Hencky: stored energy = K/2 vol^2 + G |dev eps|^2
  const double e = std::log(1.2), K = elastic.bulk, G = elastic.shear;
  EXPECT_NEAR(up.psi, 0.5 * K * e * e + G * (2.0 / 3.0) * e * e, 1e-9 * up.psi);
}

}  // namespace

TEST(J2, PowerLawHardeningFollowsTheCurve) {
  // aluminium of Table 4 of Wang et al. 2007: sigma = 576.79 (0.01658 + ep)^0.3593 MPa, initial yield 132.2 MPa
  const rk::J2Params al = rk::J2Params::power(71e9, 0.3, 576.79e6, 0.01658, 0.3593);
  EXPECT_NEAR(al.yield(0), 132.2e6, 0.05e6);
  double cp[6] = {1, 1, 1, 0, 0, 0}, ep = 0;
  for (int k = 1; k <= 40; ++k) {  // isochoric extension: plastic strain grows, q stays on the curve
    const double e = 0.01 * k;
    Eigen::Matrix3d F = Eigen::Vector3d(std::exp(e), std::exp(-e / 2), std::exp(-e / 2)).asDiagonal();
    const rk::J2Update up = rk::j2_update(F, al, cp, ep);
    EXPECT_NEAR(von_mises(up.tau), al.yield(ep), 1e-9 * al.yield(ep)) << "step " << k;
  }
  // isochoric path: equivalent strain 0.4 = ep + q / (3G)
  EXPECT_NEAR(ep, 0.4 - al.yield(ep) / (3 * al.shear), 1e-9);
}

// The stress update runs kLanes points at once (lanes.hpp). A point's result must not depend on the
// points that share its batch (or the answer would depend on the rank count): every lane, in any
// company, equals the point updated alone, bit for bit. The mix has elastic and plastic points,
// different series lengths, and one elastic stretch beyond the series' range (spectral path). A
// rate-dependent law takes each point at its own temperature T0 + k dT, increments of dt.
void each_lane_alone(const rk::J2Params& law, double T0 = 0, double dT = 0, double dt = 0, double ep0 = 0.01) {
  constexpr int kPoints = 11;
  Eigen::Matrix3d F[kPoints];
  for (int k = 0; k < kPoints; ++k) {
    F[k] = Eigen::Matrix3d::Identity();
    F[k](0, 0) += 0.0004 * k * k;            // elastic for small k, plastic beyond
    F[k](1, 2) += 0.001 * (k % 3);
    F[k](2, 0) -= 0.0007 * (k % 4);
  }
  F[5] *= 1.2;  // |b_e - I| > 0.1: spectral logarithm
  double cp0[6] = {1.001, 0.999, 1, 0.0005, 0, -0.0002};
  double alone_cp[kPoints][6], alone_ep[kPoints];
  Eigen::Matrix3d alone_tau[kPoints];
  int plastic = 0;
  for (int k = 0; k < kPoints; ++k) {
    std::copy(cp0, cp0 + 6, alone_cp[k]);
    alone_ep[k] = ep0;
    const rk::J2Update up = rk::j2_update(F[k], law, alone_cp[k], alone_ep[k], T0 + k * dT, dt);
    alone_tau[k] = up.tau;
    plastic += up.plastic;
  }
  EXPECT_GT(plastic, 0);
  EXPECT_LT(plastic, kPoints);
  for (int shift = 0; shift < rk::kLanes; ++shift) {  // every point in every lane, beside others
    rk::J2Batch b;
    for (int first = 0; first < kPoints; first += rk::kLanes) {
      for (int l = 0; l < rk::kLanes; ++l) {
        const int k = (first + l + shift) % kPoints;
        for (int i = 0; i < 9; ++i) b.F.v[i][l] = F[k](i / 3, i % 3);
        for (int i = 0; i < 6; ++i) b.cp_inv.v[i][l] = cp0[i];
        b.ep[l] = ep0, b.T[l] = T0 + k * dT;
      }
      b.dt = dt;
      rk::j2_update(law, b);
      for (int l = 0; l < rk::kLanes; ++l) {
        const int k = (first + l + shift) % kPoints;
        EXPECT_EQ(b.plastic[l] != 0, alone_ep[k] > ep0) << "point " << k << " lane " << l;
        EXPECT_EQ(b.ep[l], alone_ep[k]) << "point " << k << " in lane " << l;
        for (int i = 0; i < 6; ++i) EXPECT_EQ(b.cp_inv.v[i][l], alone_cp[k][i]) << "point " << k << " lane " << l;
        EXPECT_EQ(b.tau.v[0][l], alone_tau[k](0, 0)) << "point " << k << " lane " << l;
        EXPECT_EQ(b.tau.v[4][l], alone_tau[k](1, 2)) << "point " << k << " lane " << l;
      }
    }
  }
}

TEST(J2, EachLaneComputesWhatItWouldAlone) { each_lane_alone(kCopper); }

// The power law's return runs its Newton iterations across the lanes (the binomial series) and a lane
// whose increment is large on pow alone: here both (points 1-4 by the series, 5-10 by pow, at ep 0.01).
TEST(J2, EachLaneComputesWhatItWouldAloneOnThePowerLaw) {
  each_lane_alone(rk::J2Params::power(71e9, 0.3, 576.79e6, 0.01658, 0.3593));
}

// The power law's return by the binomial series lands on the curve K (eps0 + ep)^n as pow gives it, from
// increments of 1e-9 of the strain so far to past the series' range (u = dgamma / (eps0 + ep) > 1/4,
// where pow takes over). Measured 2026-12-04: the series within 4.4e-16 of sigma_y (2 ulp), pow's
// iterations (their step to 1e-14 of dgamma) within 5.6e-15: 1e-15 and 1e-14.
TEST(J2, PowerLawReturnLandsOnTheCurveOverTheIncrements) {
  const rk::J2Params al = rk::J2Params::power(71e9, 0.3, 576.79e6, 0.01658, 0.3593);
  for (double u : {1e-9, 1e-6, 1e-4, 1e-2, 0.1, 0.24, 0.3, 1.0}) {
    double cp[6] = {1, 1, 1, 0, 0, 0}, ep = 0.2;
    const double z0 = al.eps0 + ep, e = al.yield(ep) / (3 * al.shear) + u * z0;  // isochoric: dgamma ~ u z0
    const Eigen::Matrix3d F = Eigen::Vector3d(std::exp(e), std::exp(-e / 2), std::exp(-e / 2)).asDiagonal();
    const rk::J2Update up = rk::j2_update(F, al, cp, ep);
    ASSERT_TRUE(up.plastic) << u;
    EXPECT_NEAR((ep - 0.2) / (u * z0), 1.0, 0.05) << "the increment asked, u = " << u;
    EXPECT_NEAR(von_mises(up.tau) / al.yield(ep), 1.0, u < 0.25 ? 1e-15 : 1e-14) << "u = " << u;
    // the dissipation sigma_y dgamma, dgamma read back as ep - 0.2 (to the round-off of ep)
    EXPECT_NEAR(up.dissipation / (al.yield(ep) * (ep - 0.2)), 1.0, 1e-15 + 1.2e-16 / (ep - 0.2)) << "u = " << u;
  }
}

// The F-bar ratio's cube root (lanes.hpp) against libm: within 2 ulp near 1, libm's own value far out.
TEST(J2, CubeRootNearOneMatchesLibm) {
  for (double r = 0.85; r <= 1.15; r += 1.37e-4) {
    rk::Lane x = rk::splat(r);
    x[0] = 1 + (r - 1) * 1e-6;  // and very near 1
    const rk::Lane y = rk::cube_root_near_one(x);
    for (int l = 0; l < 2; ++l) {
      const double exact = std::cbrt(x[l]);
      EXPECT_LE(std::abs(y[l] - exact), 2 * std::numeric_limits<double>::epsilon() * exact) << "r = " << x[l];
    }
  }
  EXPECT_EQ(rk::cube_root_near_one(rk::splat(8.0))[1], 2.0);
  EXPECT_EQ(rk::cube_root_near_one(rk::splat(1.0))[0], 1.0);
}

// A batch's values read from and written to the points' rows (lanes.hpp's transposes and masked loads
// and stores): every component of each of the batch's n points to its lane and back, the lanes past n
// read as 0, and nothing outside the n points' rows written; n from one point to kLanes (a cell of
// four or six points fills part of a batch).
template <int stride>
void check_strided_round_trip(int n) {
  constexpr int size = stride * rk::kLanes + 2;
  double x[size], y[size];
  for (int k = 0; k < size; ++k) x[k] = 1.0 + k, y[k] = -1.0;
  rk::Lane v[stride];
  rk::strided_to_lanes<stride>(x + 1, v, n);
  for (int i = 0; i < stride; ++i)
    for (int l = 0; l < rk::kLanes; ++l)
      EXPECT_EQ(v[i][l], l < n ? x[1 + l * stride + i] : 0.0) << "n " << n << ", component " << i << ", lane " << l;
  rk::lanes_to_strided<stride>(v, y + 1, n);
  for (int k = 0; k < size; ++k)
    EXPECT_EQ(y[k], k >= 1 && k <= n * stride ? x[k] : -1.0) << "stride " << stride << ", n " << n << ", value " << k;
  double z[rk::kLanes + 2];
  for (int k = 0; k < rk::kLanes + 2; ++k) z[k] = -1.0;
  const rk::Lane a = rk::load_lanes(x + 1, n);
  rk::store_lanes(z + 1, a, n);
  for (int l = 0; l < rk::kLanes; ++l) EXPECT_EQ(a[l], l < n ? x[1 + l] : 0.0) << "n " << n << ", lane " << l;
  for (int k = 0; k < rk::kLanes + 2; ++k) EXPECT_EQ(z[k], k >= 1 && k <= n ? x[k] : -1.0) << "n " << n << ", value " << k;
  const rk::LaneMask first = rk::first_lanes(n);
  const rk::Lane rest = rk::rest_past(a, n, 7.0);
  for (int l = 0; l < rk::kLanes; ++l) {
    EXPECT_EQ(first[l], l < n ? -1 : 0) << "n " << n << ", lane " << l;
    EXPECT_EQ(rest[l], l < n ? x[1 + l] : 7.0) << "n " << n << ", lane " << l;
  }
}
TEST(J2, StridedLanesRoundTrip) {
  for (int n = 1; n <= rk::kLanes; ++n) {
    check_strided_round_trip<6>(n);  // tau, C_p^-1
    check_strided_round_trip<9>(n);  // F, P
  }
}

// e^x and ln x across the lanes (lanes.hpp) against libm, 2^20 samples each over the rate-dependent
// laws' range and beyond (|x| <= 700; ln over 1e-304 .. 1e304). Measured 2026-12-04: at most 1.000 ulp
// for both; 2 asked. Lanes out of range take libm's own value.
TEST(J2, LaneExpAndLogMatchLibm) {
  std::uint64_t seed = 7;
  auto uniform = [&] {  // in [-1, 1)
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    return double(seed >> 11) * 0x1.0p-52 - 1;
  };
  auto ulps = [](double a, double exact) {
    return std::abs(a - exact) / (std::nextafter(std::abs(exact), INFINITY) - std::abs(exact));
  };
  double worst_exp = 0, worst_log = 0, sum_exp = 0, sum_log = 0;
  for (int it = 0; it < (1 << 20) / rk::kLanes; ++it) {
    rk::Lane x, z;
    for (int l = 0; l < rk::kLanes; ++l) {
      x[l] = uniform() * (it % 3 == 0 ? 1 : it % 3 == 1 ? 30 : 700);
      z[l] = std::exp(uniform() * (it % 2 ? 700 : 3));
    }
    const rk::Lane ex = rk::exp(x), lz = rk::log(z);
    for (int l = 0; l < rk::kLanes; ++l) {
      const double e_ulps = ulps(ex[l], std::exp(x[l])), l_ulps = ulps(lz[l], std::log(z[l]));
      worst_exp = std::max(worst_exp, e_ulps), sum_exp += e_ulps;
      worst_log = std::max(worst_log, l_ulps), sum_log += l_ulps;
    }
  }
  EXPECT_LE(worst_exp, 2.0);
  EXPECT_LE(worst_log, 2.0);
  // The mean error, more sensitive than the worst to how the series are summed: measured 0.060 (exp) and
  // 0.016 ulp (log), Horner's and Estrin's alike; e^r summed by Estrin to its first term (the roundings
  // near 1 not Horner's) reads 0.25-0.40 ulp with its worst still at 1-2 ulp. Bounds twice the measured.
  EXPECT_LE(sum_exp / (1 << 20), 0.12);
  EXPECT_LE(sum_log / (1 << 20), 0.035);
  const rk::Lane out = rk::exp(rk::splat(800.0)), in = rk::exp(rk::splat(-800.0));
  EXPECT_EQ(out[0], std::exp(800.0));
  EXPECT_EQ(in[0], std::exp(-800.0));
  EXPECT_EQ(rk::log(rk::splat(0.0))[0], -INFINITY);
  EXPECT_TRUE(std::isnan(rk::log(rk::splat(-1.0))[0]));
  EXPECT_EQ(rk::log(rk::splat(1e-310))[0], std::log(1e-310));  // subnormal
  EXPECT_EQ(rk::log(rk::splat(1.0))[0], 0.0);
  EXPECT_EQ(rk::exp(rk::splat(0.0))[0], 1.0);
}

// Johnson-Cook (Johnson & Cook 1983, OFHC copper: A 90 MPa, B 292 MPa, n 0.31, C 0.025, m 1.09,
// T_melt 1356 K; rho 8960 kg/m^3, c 383 J/kgK).
const rk::J2Params kJohnsonCook =
    rk::J2Params::johnson_cook_law(117e9, 0.35, 90e6, 292e6, 0.31, 0.025, 1.0, 1.09, 293.15, 1356.0);

double jc_flow(double ep, double rate, double T) {
  double y, h, hr;
  kJohnsonCook.flow(ep, rate, T, y, h, hr);
  return y;
}

TEST(J2, JohnsonCookFlowAndSlopesMatchTheLaw) {
  const double A = 90e6, B = 292e6, n = 0.31, C = 0.025, m = 1.09, Tr = 293.15, Tm = 1356.0;
  const double ep = 0.3, rate = 2e3, T = 600;
  const double expected = (A + B * std::pow(ep, n)) * (1 + C * std::log(rate)) * (1 - std::pow((T - Tr) / (Tm - Tr), m));
  EXPECT_NEAR(jc_flow(ep, rate, T), expected, 1e-12 * expected);
  double y, h, hr;
  kJohnsonCook.flow(ep, rate, T, y, h, hr);
  const double d = 1e-6;  // central differences: their error (d^2) is far below the 1e-6 asked
  EXPECT_NEAR(h, (jc_flow(ep + d, rate, T) - jc_flow(ep - d, rate, T)) / (2 * d), 1e-6 * h);
  EXPECT_NEAR(hr, (jc_flow(ep, rate * (1 + d), T) - jc_flow(ep, rate * (1 - d), T)) / (2 * d * rate), 1e-6 * hr);
  // below the reference rate and the room temperature the law is quasi-static and cold; molten, no strength
  EXPECT_EQ(jc_flow(ep, 0.5, Tr - 50), A + B * std::pow(ep, n));
  EXPECT_EQ(jc_flow(ep, rate, Tm + 1), 0.0);
}

TEST(J2, JohnsonCookReturnLandsOnTheRateDependentFlowStress) {
  // one isochoric stretch from the virgin state, large enough to yield: the returned von Mises stress is
  // the flow stress at the new plastic strain, at the rate this increment's plastic strain took (dt)
  for (double dt : {0.0, 1e-6, 1e-4}) {
    for (double T : {293.15, 800.0}) {
      double cp[6] = {1, 1, 1, 0, 0, 0}, ep = 0;
      const double s = 1.01;
      const Eigen::Matrix3d F = Eigen::Vector3d(s, 1 / std::sqrt(s), 1 / std::sqrt(s)).asDiagonal();
      const rk::J2Update up = rk::j2_update(F, kJohnsonCook, cp, ep, T, dt);
      ASSERT_TRUE(up.plastic);
      const double flow = jc_flow(ep, dt > 0 ? ep / dt : 0.0, T);
      EXPECT_NEAR(von_mises(up.tau), flow, 1e-9 * flow) << "dt " << dt << " T " << T;
      EXPECT_NEAR(up.dissipation, flow * ep, 1e-9 * flow * ep);
    }
  }
}

// Adiabatic homogeneous compression at a constant true strain rate: the temperature rises by
// beta sigma d ep / (rho c) (Taylor-Quinney beta = 0.9) and softens the metal. Reference: the
// uniaxial-stress ODE, integrated here by RK4 in another form: sigma = E (eps - ep) (Hencky
// elasticity, log strain) equals the flow stress, which gives the plastic rate in closed form,
//   d ep / dt = rate0 exp((sigma / (strain part x thermal part) - 1) / C),  dT / dt = beta sigma (d ep / dt) / (rho c).
TEST(J2, JohnsonCookAdiabaticCompressionFollowsTheODE) {
  const double E = 117e9, rate = 1e3, beta = 0.9, rho = 8960, c = 383, T0 = 293.15, end = 0.5;
  const double A = 90e6, B = 292e6, n = 0.31, C = 0.025, m = 1.09, Tr = 293.15, Tm = 1356.0;
  // the ODE, RK4 in time from the first yield (elastic until E eps = A)
  auto derivative = [&](double t, double ep, double T, double& dep, double& dT) {
    const double sigma = E * (rate * t - ep);
    const double cold = (A + B * std::pow(std::max(ep, 0.0), n)) * (1 - std::pow((T - Tr) / (Tm - Tr), m));
    dep = sigma > cold ? std::exp((sigma / cold - 1) / C) : 0.0;  // rate0 = 1 /s
    dT = beta * sigma * dep / (rho * c);
  };
  double t = A / (E * rate), ep = 0, T = T0;
  const int steps = 200000;
  const double h = (end / rate - t) / steps;
  for (int k = 0; k < steps; ++k, t += h) {
    double a1, b1, a2, b2, a3, b3, a4, b4;
    derivative(t, ep, T, a1, b1);
    derivative(t + h / 2, ep + h / 2 * a1, T + h / 2 * b1, a2, b2);
    derivative(t + h / 2, ep + h / 2 * a2, T + h / 2 * b2, a3, b3);
    derivative(t + h, ep + h * a3, T + h * b3, a4, b4);
    ep += h / 6 * (a1 + 2 * a2 + 2 * a3 + a4), T += h / 6 * (b1 + 2 * b2 + 2 * b3 + b4);
  }
  const double sigma_ode = E * (end - ep), rise_ode = T - T0;

  // the return map in compression, dt per increment (as the solver's steps), T updated adiabatically
  struct Compression {
    double cp[6] = {1, 1, 1, 0, 0, 0}, ep = 0, T = 293.15;
    rk::J2Update step(double eps, double dt) {
      double lo = 0.9, hi = 1.5, lam = 1;
      rk::J2Update up;
      for (int it = 0; it < 100; ++it) {  // bisection on the lateral stretch: tau_yy = 0
        lam = 0.5 * (lo + hi);
        double cp_try[6];
        std::copy(cp, cp + 6, cp_try);
        double ep_try = ep;
        up = rk::j2_update(Eigen::Vector3d(std::exp(-eps), lam, lam).asDiagonal().toDenseMatrix(), kJohnsonCook, cp_try,
                           ep_try, T, dt);
        (up.tau(1, 1) > 0 ? hi : lo) = lam;
      }
      return rk::j2_update(Eigen::Vector3d(std::exp(-eps), lam, lam).asDiagonal().toDenseMatrix(), kJohnsonCook, cp, ep,
                           T, dt);
    }
  } point;
  const int increments = 2000;  // 2.5e-4 of strain each (the solver's steps are far smaller)
  const double dt = end / rate / increments;
  rk::J2Update up;
  for (int k = 1; k <= increments; ++k) {
    up = point.step(end * k / increments, dt);
    point.T += beta * up.dissipation / (rho * c);
  }
  const double sigma = -up.tau(0, 0);
  // measured (2026-12-02): stress 1.3e-5, temperature rise 2.0e-4, plastic strain 8e-8 from the ODE
  // (the increments' first-order temperature lag); bounds about twice that, far inside the 0.5 %
  // asked of the coupled update
  EXPECT_NEAR(sigma, sigma_ode, 3e-5 * sigma_ode) << "ODE " << sigma_ode << " Pa, T rise " << rise_ode << " K";
  EXPECT_NEAR(point.T - T0, rise_ode, 4e-4 * rise_ode) << "sigma " << sigma << " Pa vs " << sigma_ode;
  EXPECT_NEAR(point.ep, ep, 2e-7 * ep);
}

TEST(J2, JohnsonCookReturnConvergesOverTheRangeOfStates) {
  // plastic strain 0-0.5, 293-593 K, increments of 1 ns to 10 us. Measured: at most 3e-10 (the von
  // Mises stress's own round-off); a return that stops on a bisection step instead of its converged
  // Newton step is off by up to 3x.
  int plastic = 0;
  const double worst = worst_return(kJohnsonCook, 7, [](double a, double b, double c, double& ep0, double& T, double& dt) {
    ep0 = 0.5 * a, T = 293.15 + 300 * b, dt = std::pow(10, -9 + 4 * c);
  }, plastic);
  EXPECT_LT(worst, 1e-9);
}

namespace {

// Hansel-Spittel with illustrative parameters of a carbon steel's magnitude (about 62 MPa at 1100 C,
// a strain of 0.3 and 1 /s), every term in use: A 2000 MPa, m1 -0.0028, m2 0.15, m3 0.12, m4 -0.05,
// m5 -1e-4, m7 -0.3 (softening), m8 1e-4, m9 0.01; minima 0.01 and 0.01 /s.
const double kHs[9] = {2000e6, -0.0028, 0.15, 0.12, -0.05, -1e-4, -0.3, 1e-4, 0.01};
const rk::J2Params kHanselSpittel = rk::J2Params::hansel_spittel_law(200e9, 0.3, kHs, 0.01, 0.01);

// The formula as the databases write it, T in C (double, or long double for a reference)
template <class Real>
Real hs_law(const double a[9], Real ep, Real rate, Real T) {
  const Real c = T - 273.15;
  return a[0] * std::exp(a[1] * c) * std::pow(c, Real(a[8])) * std::pow(ep, Real(a[2])) * std::exp(a[4] / ep) *
         std::pow(1 + ep, a[5] * c) * std::exp(a[6] * ep) * std::pow(rate, a[3] + a[7] * c);
}

double hs_flow(double ep, double rate, double T) {
  double y, h, hr;
  kHanselSpittel.flow(ep, rate, T, y, h, hr);
  return y;
}

TEST(J2, HanselSpittelFlowAndSlopesMatchTheLaw) {
  for (double T : {1073.15, 1373.15, 1473.15})
    for (double ep : {0.05, 0.3, 1.5})
      for (double rate : {0.1, 1.0, 50.0}) {
        const double expected = hs_law(kHs, ep, rate, T);
        EXPECT_NEAR(hs_flow(ep, rate, T), expected, 1e-12 * expected) << T << " " << ep << " " << rate;
        double y, h, hr;
        kHanselSpittel.flow(ep, rate, T, y, h, hr);
        const double d = 1e-6;  // central differences: error d^2, far below the 1e-6 asked
        EXPECT_NEAR(h, (hs_flow(ep * (1 + d), rate, T) - hs_flow(ep * (1 - d), rate, T)) / (2 * d * ep), 1e-6 * std::abs(y));
        EXPECT_NEAR(hr, (hs_flow(ep, rate * (1 + d), T) - hs_flow(ep, rate * (1 - d), T)) / (2 * d * rate), 1e-6 * std::abs(hr));
      }
  // below the minima the law is held there, its slopes 0
  EXPECT_EQ(hs_flow(0.0, 1.0, 1373.15), hs_flow(0.01, 1.0, 1373.15));
  EXPECT_EQ(hs_flow(0.3, 1e-5, 1373.15), hs_flow(0.3, 0.01, 1373.15));
  double y, h, hr;
  kHanselSpittel.flow(0.001, 0.001, 1373.15, y, h, hr);
  EXPECT_EQ(h, 0.0);
  EXPECT_EQ(hr, 0.0);
  EXPECT_NEAR(hs_flow(0.3, 1.0, 1373.15), 61.9e6, 0.1e6);  // the magnitude named above
}

// The Freiberg form takes the law at (ep + 0.1, rate + 0.1): the C45 constants of
// geometry/materials/c45_hot.yaml at 1000 C, a strain of 0.3 and 1 /s give 107.3338 MPa, the formula
// evaluated independently (Python, double precision); the slopes by central differences.
TEST(J2, HanselSpittelWithOffsetsIsTheFreibergForm) {
  const double c45[9] = {3268.49e6, -0.00267855, 0.34446, 0, 0.000551814, -0.00132042, 0.0166334, 0.000149907, 0};
  const rk::J2Params p = rk::J2Params::hansel_spittel_law(120e9, 0.3, c45, 1e-6, 1e-6, 0.1, 0.1);
  auto flow = [&](double ep, double rate) {
    double y, h, hr;
    p.flow(ep, rate, 1273.15, y, h, hr);
    return y;
  };
  EXPECT_NEAR(flow(0.3, 1.0), 107.33381725830232e6, 1e-9 * 107.3e6);
  double y, h, hr;
  p.flow(0.3, 1.0, 1273.15, y, h, hr);
  const double d = 1e-6;
  EXPECT_NEAR(h, (flow(0.3 + d, 1.0) - flow(0.3 - d, 1.0)) / (2 * d), 1e-6 * y);
  EXPECT_NEAR(hr, (flow(0.3, 1.0 + d) - flow(0.3, 1.0 - d)) / (2 * d), 1e-6 * std::abs(hr));
  EXPECT_GT(flow(0.0, 0.0), 0.0);  // finite at rest: the offsets keep the law off its zero
}

// The rate-dependent return runs its Newton iterations across the lanes, each lane stopping on its own
// test: each point at its own temperature, in any company, as alone. Warm to hot (500-1000 C), and
// Johnson-Cook's copper from room temperature to 600 K, its rate law evaluated lane by lane.
TEST(J2, EachLaneComputesWhatItWouldAloneOnTheRateDependentLaws) {
  each_lane_alone(kHanselSpittel, 773.15, 50, 1e-4, 0.3);
  each_lane_alone(kJohnsonCook, 293.15, 30, 1e-7);
}

TEST(J2, HanselSpittelReturnLandsOnTheRateDependentFlowStress) {
  // hot states: strain 0-1.5, 1000-1250 C, increments of 0.1 us to 1 ms. Before the bracket widened
  // for a softening law below its least rate, 16 of them were off by more than 2e-8, up to 1.4e-6.
  int plastic = 0;
  const double worst = worst_return(kHanselSpittel, 11, [](double a, double b, double c, double& ep0, double& T, double& dt) {
    ep0 = 1.5 * a, T = 1273.15 + 250 * b, dt = std::pow(10, -7 + 4 * c);
  }, plastic);
  EXPECT_GT(plastic, 10000);
  // measured 8.6e-9: the rate the test recomputes, (ep - ep0) / dt, loses digits where a dgamma of
  // 3e-9 is added to a strain of 1.4 (2e-16 x 1.4 / 3e-9 = 1e-7 of the rate, times its exponent 0.25)
  EXPECT_LT(worst, 2e-8);
}

// The return solves for dgamma to its round-off, not only for a stress on the flow curve (the test
// above reads the rate back from ep, which costs digits): from ep0 = 0 the returned ep is dgamma itself,
// and a stretch F = diag(s, t, t) from C_p = I, s and t of a few bits (so b_e = F F^T is exact in
// doubles), has the trial stress 2 G (ln s - ln t); the root of q - 3 G dgamma = sigma_y(dgamma,
// dgamma / dt, T) is found here by bisection in long double on the law as written (minima held). The
// error is weighed in units of q / 3G, the scale of dgamma's round-off wherever the law takes most of
// the trial stress. `strained` counts the returns that end past the law's least strain with 3G dgamma
// below half of q: there the stop predicts the next step from the law's curvature.
struct DgammaError {
  double worst = 0;
  int plastic = 0, strained = 0;
};
template <class Flow>
DgammaError dgamma_error(const rk::J2Params& law, std::initializer_list<double> temperatures, std::initializer_list<int> stretches,
                         std::initializer_list<double> increments, double least_strain, const Flow& flow) {
  const long double G = law.shear;
  DgammaError e;
  for (double T : temperatures)
    for (int j : stretches)
      for (double dt : increments) {
        const double s = 1 + std::ldexp(j, -14), t = 1 - std::ldexp(j, -15);
        const Eigen::Matrix3d F = Eigen::Vector3d(s, t, t).asDiagonal();
        double cp[6] = {1, 1, 1, 0, 0, 0}, ep = 0;
        if (!rk::j2_update(F, law, cp, ep, T, dt).plastic) continue;
        ++e.plastic;
        const long double q = 2 * G * (std::log((long double)s) - std::log((long double)t));
        auto r = [&](long double dg) { return q - 3 * G * dg - flow(dg, dg / dt, (long double)T); };
        long double lo = 0, hi = q / (3 * G);  // r(lo) > 0 (plastic), r(hi) < 0
        for (int i = 0; i < 200; ++i) {
          const long double mid = (lo + hi) / 2;
          if (mid == lo || mid == hi) break;
          (r(mid) > 0 ? lo : hi) = mid;
        }
        e.strained += ep > least_strain && 3 * G * ep < q / 2;
        e.worst = std::max(e.worst, double(std::abs(ep - (lo + hi) / 2) * 3 * G / q));
      }
  return e;
}

// Hansel-Spittel as above without its e^(m4 / ep) (which makes the flow stress small at small strains),
// 1000-1200 C, increments 1 us to 10 ms; 57 of the 63 states plastic, 3G dgamma from 2e-4 to 0.91 of
// the trial stress (none past the least strain: the rate terms' curvature).
const double kHsNoM4[9] = {2000e6, -0.0028, 0.15, 0.12, 0, -1e-4, -0.3, 1e-4, 0.01};

TEST(J2, HanselSpittelReturnSolvesForDgammaToItsRoundOff) {
  const rk::J2Params law = rk::J2Params::hansel_spittel_law(200e9, 0.3, kHsNoM4, 0.01, 0.01);
  const DgammaError e = dgamma_error(law, {1273.15, 1373.15, 1473.15}, {1, 2, 3, 4, 6, 8, 16}, {1e-6, 1e-4, 1e-2}, 0.01,
                                     [](long double ep, long double rate, long double T) {
                                       return hs_law<long double>(kHsNoM4, std::max(ep, 0.01L), std::max(rate, 0.01L), T);
                                     });
  EXPECT_EQ(e.plastic, 57);
  // measured 2.35e-15 (2026-12-07): the trial stress's and the law's own round-off in double (the
  // reference's q and law are long double), not the iteration's; with a step below 1e-6 of dgamma
  // accepted without the prediction of the next (the stop before the quadratic test) 1.6e-14; with
  // Halley's steps and their rate terms' curvature left out 3.5e-15
  EXPECT_LT(e.worst, 5e-15);
}

// The same past the least strain, where the law's strain terms curve: every term of the law above, on
// a soft solid (E 2 GPa) so that one step's plastic strain passes 0.01 with the law still taking more
// than half of the trial stress; 72 states plastic, 11 of them so.
TEST(J2, HanselSpittelReturnSolvesForDgammaOnItsStrainTerms) {
  const rk::J2Params law = rk::J2Params::hansel_spittel_law(2e9, 0.3, kHs, 0.01, 0.01);
  const DgammaError e = dgamma_error(law, {1273.15, 1373.15, 1473.15}, {300, 400, 500, 600, 700, 800, 1000, 1200},
                                     {1e-6, 1e-4, 1e-2}, 0.01, [](long double ep, long double rate, long double T) {
                                       return hs_law<long double>(kHs, std::max(ep, 0.01L), std::max(rate, 0.01L), T);
                                     });
  EXPECT_EQ(e.plastic, 72);
  EXPECT_EQ(e.strained, 11);
  // measured 9.8e-16 with Halley's steps, 1.02e-15 with Newton's (2026-12-07); Halley's steps without
  // the strain terms' curvature (ln y)_ee: 2.8e-14, without the rate terms': 6.1e-14 (the stop predicts
  // a cubic convergence that is then only quadratic)
  EXPECT_LT(e.worst, 2e-15);
}

// Johnson-Cook (the OFHC copper above) from ep0 = 0, 20-320 C, increments 1 ns to 10 us; 63 of the 63
// states plastic, 14 of them ending where the stop predicts the next step from the law's curvature.
TEST(J2, JohnsonCookReturnSolvesForDgammaToItsRoundOff) {
  const DgammaError e = dgamma_error(
      kJohnsonCook, {293.15, 443.15, 593.15}, {24, 32, 48, 64, 96, 128, 256}, {1e-9, 1e-7, 1e-5}, 0.0,
      [](long double ep, long double rate, long double T) {
        const long double thermal = T <= 293.15L ? 1.0L : 1 - std::pow((T - 293.15L) / (1356.0L - 293.15L), 1.09L);
        return (90e6L + 292e6L * std::pow(ep, 0.31L)) * (1 + 0.025L * std::log(std::max(rate, 1.0L))) * thermal;
      });
  EXPECT_EQ(e.plastic, 63);
  EXPECT_EQ(e.strained, 14);  // with 3G dgamma below half of q: the stop on the predicted next step
  // measured 5.8e-16 with Halley's steps, 8.0e-16 with Newton's (2026-12-07); Halley's steps with the
  // strain term's curvature left out 9.0e-15
  EXPECT_LT(e.worst, 1.6e-15);
}

}  // namespace
