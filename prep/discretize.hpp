// From the volume mesh to the RKPM discretization: integration points (Gauss rules in each cell),
// particle volumes consistent with the cells (lumped: V_I = sum_g w_g N^cell_I(xi_g), so sum V_I =
// sum of cell volumes) and the local particle spacing h_I (mean length of the cell edges at I).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "cad_mesh.hpp"
#include "nodal_integration.hpp"

namespace rk {

struct Discretization {
  std::vector<double> point_X;       // 3 per point
  std::vector<double> point_weight;  // m^3
  std::vector<std::int32_t> point_cell;
  std::vector<double> volume;   // per particle
  std::vector<double> spacing;  // per particle
  DualFaces faces;  // nodal integration only: the dual-cell face points, plus/minus numbered as points
};

// gauss_order: Gauss points per direction (hexahedra) or 1 / 4 points (tetrahedra); cell_rule: a
// hexahedron's rule, "gauss" (gauss_order^3 points), "four_point" or "six_point" (Scene::Discretization)
Discretization discretize(const VolumeMesh& mesh, int gauss_order, const std::string& cell_rule = "gauss");

// Each node's spacing h_I: the mean length of its cells' edges (0 for a node of no cell).
std::vector<double> node_spacing(const VolumeMesh& mesh);

// Edges of a cell as pairs of its local node numbers (gmsh ordering).
const std::vector<std::pair<int, int>>& cell_edges(int nodes_per_cell);

}  // namespace rk
