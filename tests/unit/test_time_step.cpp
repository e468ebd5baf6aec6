// The stable step is measured from the smallest principal stretch of F at the integration points.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>

#include "time_step.hpp"
#include "model.hpp"
#include "state.hpp"

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

// The step is the least over every point of h0_c sigma_min(F_g) / c_c, whichever cell is measured first
// (the last step's, to let the bounds skip sooner): the same value to the bit as every point measured, on
// 40 cells of points stretched unevenly near F = I (rotated) or compressed evenly along z (unrotated,
// where Gershgorin's bound is exact and many points lie within 1.5 % of the least). Each cell in turn
// is made the one that sets the step (its h0 2 % shorter), and every cell is tried first.
// `cells` cells of 8 points each, of copper
rk::Model copper_cells(std::size_t cells) {
  rk::Model md;
  const std::size_t per_cell = 8;
  md.m = cells * per_cell, md.cells = cells;
  for (std::size_t c = 0; c <= cells; ++c) md.cell_points.push_back(std::int32_t(c * per_cell));
  for (std::size_t g = 0; g < md.m; ++g) md.weight.push_back(1e-9), md.dN_max.push_back(1e3);
  rk::single_material(md, rk::J2Params::from(117.0e9, 0.35, 400.0e6, 100.0e6, true), 8930);
  return md;
}

rk::State at_rest(const rk::Model& md) {
  return rk::State::initial(md, std::array<double, 3>{}.data(), std::array<double, 9>{}.data());
}

TEST(TimeStep, StableStepIsTheLeastOverThePointsFromAnyFirstCell) {
  const std::size_t cells = 40;
  rk::Model md = copper_cells(cells);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(0, 1);
  rk::State st = at_rest(md);
  for (std::size_t g = 0; g < md.m; ++g) {
    double* F = &st.F[9 * g];
    if (g % 2 == 0) {  // compressed evenly: 0.700-0.710 along z
      const double c = 0.70 + 0.01 * U(rng);
      std::fill(F, F + 9, 0.0);
      F[0] = F[4] = 1.19, F[8] = c;
      st.J[g] = 1.19 * 1.19 * c;
    } else {
      const double a = 1 + 0.05 * U(rng), b = 1 - 0.05 * U(rng);
      stretch_between_rotations(a, b, 1, F);
      st.J[g] = a * b;
    }
  }
  const double wave = std::sqrt(md.materials[0].wave_speed2(1.0));
  for (std::size_t c = 0; c < cells; ++c) st.cell_J[c] = 1;
  for (std::size_t target = 0; target < cells; ++target) {
    md.cell_h0.assign(cells, 1e-3);
    md.cell_h0[target] *= 0.98;
    double least = std::numeric_limits<double>::infinity();
    for (std::size_t c = 0; c < cells; ++c)
      for (auto g = std::size_t(md.cell_points[c]); g < std::size_t(md.cell_points[c + 1]); ++g)
        least = std::min(least, md.cell_h0[c] / wave * rk::smallest_stretch(&st.F[9 * g], st.J[g]));
    for (std::size_t first = 0; first <= cells; ++first) {  // (first = cells: none)
      const rk::StableStep s = rk::stable_time_step(md, st, 0.9, true, first);
      ASSERT_EQ(s.dt, 0.9 * least) << "the least in cell " << target << ", cell " << first << " first";
      EXPECT_EQ(s.cell, target) << "cell " << first << " first";
    }
  }
}

// After a reference update the same pass finds the contact's step on the cells' edges on the new
// reference (Model::cell_h_reference): each least exact, to the bit, whichever cell sets either and
// whichever is first. The reference's edges here shrink in other cells than the step's, 3x, so a point
// that cannot set the step may set the contact's; the step's edges are those the model sets, at most
// step_growth times the reference's (4 here, so the compressed cell does not set the step).
TEST(TimeStep, TheContactsStepOnTheReferencesEdgesInTheSamePass) {
  const std::size_t cells = 24;
  rk::Model md = copper_cells(cells);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(0, 1);
  rk::State st = at_rest(md);
  for (std::size_t g = 0; g < md.m; ++g) {
    const double a = 1 + 0.01 * U(rng), b = 1 - 0.01 * U(rng);  // near F = I: the bounds skip most points
    stretch_between_rotations(a, b, 1, &st.F[9 * g]);
    st.J[g] = a * b;
  }
  const double wave = std::sqrt(md.materials[0].wave_speed2(1.0));
  for (std::size_t c = 0; c < cells; ++c) st.cell_J[c] = 1;
  for (std::size_t target = 0; target < cells; target += 5) {
    md.cell_h_reference.assign(cells, 1e-3);
    md.cell_h_reference[(target + 7) % cells] /= 3;  // compressed before the update
    md.cell_h0.assign(cells, 1e-3);
    for (std::size_t c = 0; c < cells; ++c) md.cell_h0[c] = std::min(md.cell_h0[c], 4 * md.cell_h_reference[c]);
    md.cell_h0[target] *= 0.9;
    double least = std::numeric_limits<double>::infinity(), reference = least;
    for (std::size_t c = 0; c < cells; ++c)
      for (auto g = std::size_t(md.cell_points[c]); g < std::size_t(md.cell_points[c + 1]); ++g) {
        const double stretch = rk::smallest_stretch(&st.F[9 * g], st.J[g]);
        least = std::min(least, md.cell_h0[c] / wave * stretch);
        reference = std::min(reference, md.cell_h_reference[c] / wave * stretch);
      }
    for (std::size_t first = 0; first <= cells; first += 3) {
      double on_reference = 0;
      const rk::StableStep s = rk::stable_time_step(md, st, 0.9, true, first, &on_reference);
      ASSERT_EQ(s.dt, 0.9 * least) << "the step, cell " << first << " first";
      ASSERT_EQ(on_reference, 0.9 * reference) << "the contact's, cell " << first << " first";
      EXPECT_GT(s.dt, on_reference) << "the edges 3x apart in one cell, the step grown past the contact's";
    }
  }
  md.cell_h_reference.clear();  // before an update: none
  double none = 0;
  rk::stable_time_step(md, st, 0.9, true, 0, &none);
  EXPECT_EQ(none, std::numeric_limits<double>::infinity());
}

// Each cell's own step, for the classes of multi-rate steps: in the class of its exact step (CFL times the
// least over its points) for every cycle length, never above that step, which is never above the ceiling that decides whether classes are counted at all. Cells of two sizes and
// three strains, 4 and 8x apart, as an impact's crushed foot beside its shank.
TEST(TimeStep, EachCellsStepIsInItsOwnClass) {
  const std::size_t cells = 24;
  rk::Model md = copper_cells(cells);
  rk::State st = at_rest(md);
  for (std::size_t c = 0; c < cells; ++c) {
    md.cell_h0.push_back(c % 2 ? 1e-3 : 0.25e-3);
    st.cell_J[c] = 1;
    const double squeeze = c % 3 == 0 ? 0.125 : c % 3 == 1 ? 0.5 : 0.97;  // along z, the rest rotated
    for (auto g = std::size_t(md.cell_points[c]); g < std::size_t(md.cell_points[c + 1]); ++g) {
      stretch_between_rotations(1.0 + 0.001 * double(g % 5), 1.0, squeeze, &st.F[9 * g]);
      st.J[g] = (1.0 + 0.001 * double(g % 5)) * squeeze;
    }
  }
  const double cfl = 0.9, wave = std::sqrt(md.materials[0].wave_speed2(1.0));
  const double least = rk::stable_time_step(md, st, cfl).dt;
  const auto class_of = [&](double x, int levels) {
    int k = 0;
    while (k < levels && double(2 << k) * least <= x) ++k;
    return k;
  };
  const double ceiling = rk::cell_time_step_ceiling(md, st, cfl);
  std::vector<double> dt_cell;
  int classes[5] = {};
  for (const int levels : {1, 2, 4}) {
    rk::cell_time_steps(md, st, cfl, least, levels, dt_cell);
    ASSERT_EQ(dt_cell.size(), cells);
    for (std::size_t c = 0; c < cells; ++c) {
      double own = std::numeric_limits<double>::infinity();
      for (auto g = std::size_t(md.cell_points[c]); g < std::size_t(md.cell_points[c + 1]); ++g)
        own = std::min(own, cfl * (md.cell_h0[c] / wave * rk::smallest_stretch(&st.F[9 * g], st.J[g])));
      EXPECT_EQ(class_of(dt_cell[c], levels), class_of(own, levels)) << "cell " << c << ", " << levels << " levels";
      EXPECT_LE(own, ceiling) << "cell " << c << ": the ceiling is above every cell's step";
      EXPECT_LE(dt_cell[c], own * (1 + 1e-15)) << "cell " << c << ": never above its own step (a bound: its round-off)";
      if (levels == 4) ++classes[class_of(own, 4)];
    }
  }
  EXPECT_GT(classes[0], 0);  // (the cells span the classes: the test compares more than one)
  EXPECT_GT(classes[2] + classes[3] + classes[4], 0);
  // a part at rest: the ceiling within the cells' spread of the least (all at the smallest step)
  rk::Model md8 = copper_cells(8);
  for (std::size_t c = 0; c < 8; ++c) md8.cell_h0.push_back(1e-3);
  rk::State rest = at_rest(md8);
  for (std::size_t c = 0; c < 8; ++c) rest.cell_J[c] = 1;
  EXPECT_LT(rk::cell_time_step_ceiling(md8, rest, cfl), 2 * rk::stable_time_step(md8, rest, cfl).dt);
}

}  // namespace
