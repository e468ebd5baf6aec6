// Stabilized conforming nodal integration (SCNI; Chen, Wu, Yoon & You 2001, IJNME 50: 435-466): one
// integration point per particle, its gradient smoothed over the particle's cell of the median dual of
// the prep mesh,
//   b_I(X_L) = 1/V_L  int_{dOmega_L} N_I n dGamma,   V_L = 1/3 int_{dOmega_L} (X - X_L) . n dGamma.
// The dual cell of node L is bounded, inside each mesh cell, by one quadrilateral per cell edge at L
// (edge midpoint, the centres of the two cell faces at the edge, the cell centre) and, on the domain
// boundary, by the quarter (hex) or third (tet) of each boundary face at L. Each face is bilinear and
// integrated with 2x2 Gauss points (its centre alone where it is a parallelogram), which is exact for
// the linear fields the RK basis reproduces, so the smoothed gradient of a linear field is exact. Neighbouring dual cells share their faces with
// opposite normals (conforming): the divergence consistency that makes the Galerkin linear patch test pass.
#pragma once
#include <cstdint>
#include <vector>

#include "cad_mesh.hpp"

namespace rk {

struct DualFaces {
  std::vector<double> X, nA;  // 3 per quadrature point: position, normal times area weight (out of `plus`)
  std::vector<std::int32_t> plus;   // the node whose dual cell the normal points out of
  std::vector<std::int32_t> minus;  // the node on the other side; -1 on the domain boundary
  std::size_t size() const { return plus.size(); }
};

// Every dual-cell face quadrature point of the mesh, in cell order (so any partition sums a node's
// faces in the same order).
DualFaces dual_faces(const VolumeMesh& mesh);

// V_L per node from the faces (the divergence theorem with the same quadrature).
std::vector<double> dual_volumes(const VolumeMesh& mesh, const DualFaces& faces);

struct Discretization;
// Replaces the Gauss points of `d` by one point per node (weight V_L) and fills d.faces, with plus and
// minus numbered as points. Throws rk::Error naming a node whose dual volume is not positive.
void use_nodal_points(const VolumeMesh& mesh, Discretization& d);

}  // namespace rk
