// A hexahedron's integration rules (prep/discretize.cpp, discretization.cell_rule): on an affine cell
// (sheared, scaled, off the origin) each integrates every monomial x^a y^b z^c up to its degree exactly,
// against the 3x3x3 Gauss rule (exact to degree 5 there), and misses one of the next degree (so the
// degree is the rule's, not more); the particle volumes lumped from its points sum to the cell's volume.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "discretize.hpp"

namespace {

// one hexahedron, x = c + A (xi + 1) / 2 with xi the gmsh corner signs
rk::VolumeMesh affine_hexahedron() {
  static const int s[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                              {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  const double A[3][3] = {{2.0, 0.3, -0.2}, {0.1, 1.5, 0.4}, {-0.3, 0.2, 1.2}}, c[3] = {0.7, -0.4, 1.1};
  rk::VolumeMesh m;
  for (const auto& corner : s) {
    for (int i = 0; i < 3; ++i) {
      double x = c[i];
      for (int k = 0; k < 3; ++k) x += A[i][k] * (corner[k] + 1) / 2;
      m.X.push_back(x);
    }
    m.surface.push_back(1), m.body.push_back(0);
  }
  for (int a = 0; a < 8; ++a) m.cell_nodes.push_back(a);
  m.cell_offsets.push_back(8);
  return m;
}

double rule_integral(const rk::Discretization& d, int a, int b, int c) {
  double sum = 0;
  for (std::size_t g = 0; g < d.point_weight.size(); ++g)
    sum += d.point_weight[g] * std::pow(d.point_X[3 * g], a) * std::pow(d.point_X[3 * g + 1], b) *
           std::pow(d.point_X[3 * g + 2], c);
  return sum;
}

struct HexRuleCase {
  std::string name;
  std::size_t points;
  int degree;
  int missed[3];  // a monomial of degree + 1 the rule does not integrate exactly
};

void PrintTo(const HexRuleCase& r, std::ostream* os) { *os << r.name; }

class CellRule : public ::testing::TestWithParam<HexRuleCase> {};

TEST_P(CellRule, IntegratesMonomialsToItsDegree) {
  const HexRuleCase& r = GetParam();
  const rk::VolumeMesh mesh = affine_hexahedron();
  const rk::Discretization exact = rk::discretize(mesh, 3), d = rk::discretize(mesh, 2, r.name);
  ASSERT_EQ(d.point_weight.size(), r.points);
  for (int a = 0; a <= r.degree; ++a)
    for (int b = 0; a + b <= r.degree; ++b)
      for (int c = 0; a + b + c <= r.degree; ++c) {
        // (the integrals are 1 to 23 here; measured 2026-12-07: at most 8.4e-16 of them apart, the sums' round-off)
        const double e = rule_integral(exact, a, b, c);
        EXPECT_NEAR(rule_integral(d, a, b, c), e, 2e-15 * std::max(1.0, std::abs(e))) << "x^" << a << " y^" << b << " z^" << c;
      }
  const double e = rule_integral(exact, r.missed[0], r.missed[1], r.missed[2]);  // (missed by 6.5e-4 to 4.9e-2 of it)
  EXPECT_GT(std::abs(rule_integral(d, r.missed[0], r.missed[1], r.missed[2]) - e), 1e-6 * std::abs(e))
      << "degree " << r.degree + 1 << " integrated exactly: the rule is not the one asked";
  double volume = 0, lumped = 0;
  for (double w : d.point_weight) volume += w;
  for (double v : d.volume) lumped += v;
  EXPECT_NEAR(volume, rule_integral(exact, 0, 0, 0), 1e-15 * volume);  // (measured 1.4e-16 and 2.7e-16 of it)
  EXPECT_NEAR(lumped, volume, 1e-15 * volume) << "the particle volumes tile the cell";
}

INSTANTIATE_TEST_SUITE_P(Hexahedron, CellRule,
                         ::testing::Values(HexRuleCase{"gauss", 8, 3, {2, 2, 0}}, HexRuleCase{"four_point", 4, 2, {1, 1, 1}},
                                           HexRuleCase{"six_point", 6, 3, {2, 2, 0}}),
                         [](const auto& info) { return info.param.name; });

}  // namespace
