// The pressure's health bound: the fastest start or tool (v_max of rho c_L v_max), and the stress
// update measuring a uniformly compressed F-bar cell's pressure against the bound and stopping past it.
#include <gtest/gtest.h>

#include <cmath>

#include "material/stress_update.hpp"

namespace {

const double kLo[3] = {0, 0, 0}, kHi[3] = {0.01, 0.01, 0.2};

TEST(PressureBound, FastestStartOrTool) {
  rk::Scene s;
  EXPECT_EQ(rk::fastest_speed(s, kLo, kHi), 0.0) << "at rest, no tools";
  s.initial.velocity = {0, 0, -227};
  EXPECT_DOUBLE_EQ(rk::fastest_speed(s, kLo, kHi), 227.0);
  s.initial.velocity = {0, 0, 0};
  s.initial.velocity_gradient[3] = 5;   // v_y = 5 1/s x: 0 at the clamp, 0.05 m/s at x = 0.01
  s.initial.velocity_gradient[5] = -5;  // v_y -= 5 1/s z: -1 m/s at z = 0.2, the fastest corner
  EXPECT_NEAR(rk::fastest_speed(s, kLo, kHi), 1.0, 1e-12);
  rk::Die die;
  die.motion.curve = rk::PiecewiseLinear({{0, 0}, {1e-3, 2e-3}, {2e-3, 2.5e-3}});  // 2 m/s, then 0.5 m/s
  s.dies.push_back(die);
  EXPECT_NEAR(rk::fastest_speed(s, kLo, kHi), 2.0, 1e-12);
  rk::EssentialFace face;
  face.motion.speed = -10;
  s.prescribed_faces.push_back(face);
  EXPECT_DOUBLE_EQ(rk::fastest_speed(s, kLo, kHi), 10.0);
}

// One F-bar cell of two points compressed uniformly to volume ratio J: elastic (below the yield),
// Hencky's Kirchhoff pressure -K ln J, the Cauchy pressure -K ln J / J.
struct Compressed {
  rk::Model md;
  rk::State st;
  double pressure = 0;
  explicit Compressed(double J) {
    md.m = 2, md.cells = 1, md.fbar = true;
    md.cell_points = {0, 2};
    md.weight = {1e-9, 3e-9};
    md.dN_max = {1e3, 1e3};
    rk::single_material(md, rk::J2Params::from(117.0e9, 0.35, 400.0e6, 100.0e6, true), 8930);
    st = rk::State::initial(md, std::array<double, 3>{}.data(), std::array<double, 9>{}.data());
    const double stretch = std::cbrt(J);
    for (std::size_t g = 0; g < md.m; ++g)
      st.F[9 * g] = st.F[9 * g + 4] = st.F[9 * g + 8] = stretch, st.J[g] = J;
    st.cell_J[0] = J;
    pressure = -md.materials[0].law.bulk * std::log(J) / J;
  }
};

TEST(PressureBound, CompressedCellMeasuredAndStoppedPastTheBound) {
  Compressed c(0.99);  // 1.44 GPa (K = 130 GPa) in copper: within the yield surface (pure volume change)
  const double impact = 1e9, ref = impact + 400.0e6;  // rho0 c_L v + sigma_y(0)
  const rk::StressHealth h = rk::update_stress(c.md, c.st, {impact, 0});  // no bound: measured only
  EXPECT_TRUE(h.ok);
  EXPECT_NEAR(h.pressure / c.pressure, 1.0, 1e-9);
  EXPECT_NEAR(h.pressure_ratio / (c.pressure / ref), 1.0, 1e-9);
  const double ratio = c.pressure / ref;
  EXPECT_TRUE(rk::update_stress(c.md, c.st, {impact, 1.01 * ratio}).ok) << "below the bound";
  const rk::StressHealth out = rk::update_stress(c.md, c.st, {impact, 0.99 * ratio});
  EXPECT_FALSE(out.ok);
  EXPECT_TRUE(out.pressure_stop) << "stopped by the pressure, not the volume ratio";
  EXPECT_NEAR(out.pressure / c.pressure, 1.0, 1e-9);
  // the same cell expanded: tension counts as much as compression
  Compressed e(1.01);
  const rk::StressHealth t = rk::update_stress(e.md, e.st, {impact, 0.99 * std::abs(e.pressure) / ref});
  EXPECT_TRUE(t.pressure_stop);
  EXPECT_LT(t.pressure, 0);
}

TEST(PressureBound, ElasticPartUntouchedHasNoScale) {
  Compressed c(0.99);
  c.md.materials[0].law.plastic = false;  // elastic, at rest, no tools: p_ref = 0, no ratio and no stop
  const rk::StressHealth h = rk::update_stress(c.md, c.st, {0, 20});
  EXPECT_TRUE(h.ok);
  EXPECT_EQ(h.pressure_ratio, 0.0);
}

}  // namespace
