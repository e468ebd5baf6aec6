#include "discretize.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <string>

#include "error.hpp"

namespace rk {
namespace {

struct RulePoint {
  double xi[3];
  double w;
};

// A hexahedron's rule on [-1,1]^3 (volume 8): the tensor Gauss-Legendre rule (order = points per
// direction, exact to degree 2 order - 1), or a symmetric rule with fewer points:
// - four_point: the 2x2x2 rule's points at alternate corners (a regular tetrahedron), weight 2 each;
//   exact to degree 2: sum w xi^2 = 4 x 2 / 3 = 8/3, and the odd moments cancel in pairs (of the
//   cubic ones all but xi eta zeta);
// - six_point: the face centres, weight 4/3 each (Stroud 1971, "Approximate calculation of multiple
//   integrals", the cube's degree-3 rule of 2n points); exact to degree 3: sum w xi^2 = 2 x 4/3 = 8/3,
//   and every odd moment cancels. Its points lie on the cell's faces, so an interior face holds two.
std::vector<RulePoint> hex_rule(int order, const std::string& cell_rule) {
  if (cell_rule == "four_point") {
    const double r = 1 / std::sqrt(3.0);
    return {{{-r, -r, -r}, 2.0}, {{r, r, -r}, 2.0}, {{r, -r, r}, 2.0}, {{-r, r, r}, 2.0}};
  }
  if (cell_rule == "six_point") {
    const double w = 4.0 / 3;
    return {{{-1, 0, 0}, w}, {{1, 0, 0}, w}, {{0, -1, 0}, w}, {{0, 1, 0}, w}, {{0, 0, -1}, w}, {{0, 0, 1}, w}};
  }
  if (cell_rule != "gauss") throw Error("discretize: unknown cell rule '" + cell_rule + "'");
  std::vector<double> x, w;
  if (order == 1) x = {0.0}, w = {2.0};
  else if (order == 2) x = {-1 / std::sqrt(3.0), 1 / std::sqrt(3.0)}, w = {1.0, 1.0};
  else x = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, w = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  std::vector<RulePoint> rule;
  for (std::size_t k = 0; k < x.size(); ++k)
    for (std::size_t j = 0; j < x.size(); ++j)
      for (std::size_t i = 0; i < x.size(); ++i) rule.push_back({{x[i], x[j], x[k]}, w[i] * w[j] * w[k]});
  return rule;
}

// Tetrahedron rules on the unit tet (volume 1/6): centroid for order 1, the 4-point degree-2 rule otherwise.
std::vector<RulePoint> tet_rule(int order) {
  if (order == 1) return {{{0.25, 0.25, 0.25}, 1.0 / 6}};
  const double a = 0.5854101966249685, b = 0.1381966011250105;
  return {{{b, b, b}, 1.0 / 24}, {{a, b, b}, 1.0 / 24}, {{b, a, b}, 1.0 / 24}, {{b, b, a}, 1.0 / 24}};
}

// Cell shape functions and their parametric derivatives (gmsh node order).
void hex_shape(const double* xi, double* N, double (*dN)[3]) {
  static const int s[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                              {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  for (int a = 0; a < 8; ++a) {
    const double f[3] = {1 + s[a][0] * xi[0], 1 + s[a][1] * xi[1], 1 + s[a][2] * xi[2]};
    N[a] = f[0] * f[1] * f[2] / 8;
    dN[a][0] = s[a][0] * f[1] * f[2] / 8;
    dN[a][1] = f[0] * s[a][1] * f[2] / 8;
    dN[a][2] = f[0] * f[1] * s[a][2] / 8;
  }
}
void tet_shape(const double* xi, double* N, double (*dN)[3]) {
  N[0] = 1 - xi[0] - xi[1] - xi[2];
  N[1] = xi[0], N[2] = xi[1], N[3] = xi[2];
  const double d[4][3] = {{-1, -1, -1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int a = 0; a < 4; ++a)
    for (int k = 0; k < 3; ++k) dN[a][k] = d[a][k];
}

}  // namespace

std::vector<double> node_spacing(const VolumeMesh& mesh) {
  std::vector<double> spacing(mesh.node_count(), 0.0);
  std::vector<int> edges(mesh.node_count(), 0);
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    const std::int32_t* nodes = mesh.cell_nodes.data() + mesh.cell_offsets[c];
    for (auto [a, b] : cell_edges(mesh.cell_offsets[c + 1] - mesh.cell_offsets[c])) {
      const double* p = &mesh.X[3 * std::size_t(nodes[a])];
      const double* r = &mesh.X[3 * std::size_t(nodes[b])];
      const double len = std::sqrt((p[0] - r[0]) * (p[0] - r[0]) + (p[1] - r[1]) * (p[1] - r[1]) + (p[2] - r[2]) * (p[2] - r[2]));
      for (int e : {a, b}) spacing[std::size_t(nodes[e])] += len, ++edges[std::size_t(nodes[e])];
    }
  }
  for (std::size_t i = 0; i < spacing.size(); ++i) spacing[i] = edges[i] > 0 ? spacing[i] / edges[i] : 0.0;
  return spacing;
}

const std::vector<std::pair<int, int>>& cell_edges(int nodes_per_cell) {
  static const std::vector<std::pair<int, int>> hex{{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                                    {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  static const std::vector<std::pair<int, int>> tet{{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  return nodes_per_cell == 8 ? hex : tet;
}

Discretization discretize(const VolumeMesh& mesh, int gauss_order, const std::string& cell_rule) {
  Discretization d;
  const std::size_t n = mesh.node_count();
  d.volume.assign(n, 0.0);
  const auto hex = hex_rule(gauss_order, cell_rule), tet = tet_rule(gauss_order);
  double N[8], dN[8][3];
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    const std::int32_t* nodes = mesh.cell_nodes.data() + mesh.cell_offsets[c];
    const int per = mesh.cell_offsets[c + 1] - mesh.cell_offsets[c];
    const auto& rule = per == 8 ? hex : tet;
    for (const auto& q : rule) {
      if (per == 8) hex_shape(q.xi, N, dN);
      else tet_shape(q.xi, N, dN);
      Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
      double x[3] = {0, 0, 0};
      for (int a = 0; a < per; ++a)
        for (int i = 0; i < 3; ++i) {
          x[i] += N[a] * mesh.X[3 * nodes[a] + i];
          for (int k = 0; k < 3; ++k) J(i, k) += mesh.X[3 * nodes[a] + i] * dN[a][k];
        }
      const double detJ = J.determinant();
      if (!(detJ > 0)) {
        double centre[3] = {0, 0, 0};  // (the nodes' mean: named even where the shape functions are not finite)
        for (int a = 0; a < per; ++a)
          for (int i = 0; i < 3; ++i) centre[i] += mesh.X[3 * std::size_t(nodes[a]) + std::size_t(i)] / per;
        throw Error("mesh cell " + std::to_string(c) + " near (" + std::to_string(centre[0]) + ", " +
                    std::to_string(centre[1]) + ", " + std::to_string(centre[2]) + ") m is inverted or degenerate (gmsh's mesh of the "
                    "CAD at this spacing: another discretization.spacing, or for an STL a finer faceting or the STEP, may mesh)");
      }
      const double w = q.w * detJ;
      d.point_X.insert(d.point_X.end(), x, x + 3);
      d.point_weight.push_back(w);
      d.point_cell.push_back(std::int32_t(c));
      for (int a = 0; a < per; ++a) d.volume[nodes[a]] += w * N[a];
    }
  }
  d.spacing = node_spacing(mesh);
  for (std::size_t i = 0; i < n; ++i)
    if (!(d.spacing[i] > 0) || !(d.volume[i] > 0)) throw Error("mesh node " + std::to_string(i) + " belongs to no valid cell");
  return d;
}

}  // namespace rk
