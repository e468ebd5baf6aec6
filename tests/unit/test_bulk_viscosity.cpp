// Bulk viscosity: the closed form q = rho l |e| (C_q l |e| + C_l c) in compression and 0 in
// expansion, the stable step's factor 1 / (r + sqrt(1 + r^2)), r = (C_l c + C_q l |e|) / c, the work
// of q as the trapezoid over the volume change, F-bar's one q per cell, and nothing when off.
#include <gtest/gtest.h>

#include <cmath>

#include "material/bulk_viscosity.hpp"
#include "time_step.hpp"

namespace {

// One cell of two points (weights 1 and 3 m^3 of reference volume), edge h0, copper-like constants.
rk::Model cell(bool fbar) {
  rk::Model md;
  md.cells = 1;
  md.m = 2;
  md.fbar = fbar;
  md.cell_points = {0, 2};
  md.cell_h0 = {1e-3};
  md.cell_node_offsets = {0, 2};  // two particles, spacings 0.8 and 1.2 mm: l = 1 mm J^(1/3)
  md.cell_nodes = {0, 1};
  md.spacing0 = {0.8e-3, 1.2e-3};
  md.weight = {1.0, 3.0};
  md.materials = {rk::Solid{{}, 8930, 187.8e9}};
  md.cell_material = {0};
  md.point_material = {0, 0};
  return md;
}

rk::State state(const rk::Model& md) {
  rk::State st;
  st.J.assign(md.m, 1.0);
  st.cell_J.assign(md.cells, 1.0);
  st.F.assign(9 * md.m, 0.0);
  for (std::size_t g = 0; g < md.m; ++g) st.F[9 * g] = st.F[9 * g + 4] = st.F[9 * g + 8] = 1.0;
  return st;
}

void set_J(const rk::Model& md, rk::State& st, double J0, double J1) {
  st.J = {J0, J1};
  st.cell_J[0] = (md.weight[0] * J0 + md.weight[1] * J1) / (md.weight[0] + md.weight[1]);
}

const rk::Scene::BulkViscosity kDefaults{1.5, 0.06};

// The bulk viscosity on, its first (rate-free) update at J = 1, then one step of 10 ns to J0, J1.
rk::State one_step(const rk::Model& md, double J0, double J1) {
  rk::State st = state(md);
  rk::init_bulk_viscosity(md, st, kDefaults);
  rk::update_bulk_viscosity(md, st, kDefaults);
  st.dt_half = 1e-8;
  set_J(md, st, J0, J1);
  rk::update_bulk_viscosity(md, st, kDefaults);
  return st;
}

TEST(BulkViscosity, ClosedFormInCompressionNoneInExpansion) {
  const rk::Model md = cell(false);
  rk::State st = state(md);
  rk::init_bulk_viscosity(md, st, kDefaults);
  ASSERT_EQ(st.q.size(), md.m);
  rk::update_bulk_viscosity(md, st, kDefaults);  // the first step: no rate yet
  EXPECT_EQ(st.q[0], 0.0);
  st.dt_half = 1e-8;
  set_J(md, st, 0.999, 1.001);  // point 0 compressed, point 1 expanded over the step
  st.cell_J[0] = 0.999;
  rk::update_bulk_viscosity(md, st, kDefaults);
  const double J = 0.999, e = std::log(1 / J) / 1e-8, l = 1e-3 * std::cbrt(J);
  const double c = std::sqrt(md.materials[0].wave_modulus * 0.999 / md.materials[0].density);
  const double Q = 0.06 * c + 1.5 * l * e;
  EXPECT_NEAR(st.q[0] / (md.materials[0].density / J * l * e * Q), 1.0, 1e-12);
  EXPECT_GT(st.q[0], 1e8) << "0.1 % in 10 ns: a shock-like rate, q of the order of 100 MPa";
  EXPECT_EQ(st.q[1], 0.0) << "expansion: no viscosity";
  EXPECT_NEAR(st.dt_factor[0] * (Q / c + std::sqrt(1 + Q * Q / (c * c))), 1.0, 1e-12);
  EXPECT_EQ(st.dt_factor[1], 1.0);
  // the work: (0 + q) / 2 times the volume lost (point 0); point 1 expanded with q = 0 throughout
  EXPECT_NEAR(st.viscous_work / (0.5 * st.q[0] * md.weight[0] * (1 - J)), 1.0, 1e-12);
  // the next step holds J: no rate, q falls to 0 and the trapezoid adds nothing more
  const double w1 = st.viscous_work;
  rk::update_bulk_viscosity(md, st, kDefaults);
  EXPECT_EQ(st.q[0], 0.0);
  EXPECT_EQ(st.viscous_work, w1);
}

TEST(BulkViscosity, OneValuePerCellWithFbar) {
  const rk::Model md = cell(true);
  const rk::State st = one_step(md, 0.996, 1.0);  // the cell's volume falls by 0.1 %
  EXPECT_GT(st.q[0], 0.0);
  EXPECT_EQ(st.q[0], st.q[1]) << "the cell's J: one q for its points";
  const double Jbar = 0.999;
  EXPECT_NEAR(st.viscous_work / (0.5 * st.q[0] * 4.0 * (1 - Jbar)), 1.0, 1e-12) << "the cell's volume change";
}

TEST(BulkViscosity, TheStableStepShrinksByItsFactor) {
  const rk::Model md = cell(false);
  const rk::State st = one_step(md, 0.999, 0.9995);
  EXPECT_LT(st.dt_factor[0], 0.94) << "the linear term alone takes 6 %";
  // the points keep F = I (stretch 1): the step is h0 / c times the smaller factor
  const double dt_plain = md.cell_h0[0] / std::sqrt(md.materials[0].wave_modulus * st.cell_J[0] / md.materials[0].density);
  EXPECT_NEAR(rk::stable_time_step(md, st, 1.0).dt / (dt_plain * std::min(st.dt_factor[0], st.dt_factor[1])), 1.0, 1e-12);
}

TEST(BulkViscosity, OffCostsNothing) {
  const rk::Model md = cell(false);
  rk::State st = state(md);
  rk::init_bulk_viscosity(md, st, rk::Scene::BulkViscosity{0, 0});
  EXPECT_TRUE(st.q.empty() && st.dt_factor.empty() && st.J_last.empty());
  st.dt_half = 1e-8;
  set_J(md, st, 0.9, 0.9);
  rk::update_bulk_viscosity(md, st, rk::Scene::BulkViscosity{0, 0});
  EXPECT_EQ(st.viscous_work, 0.0);
}

}  // namespace
