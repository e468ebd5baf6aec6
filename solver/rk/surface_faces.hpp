// The part's boundary faces (Model::surface_face_*) where the particles' coefficients put them now:
// x_I = X_I + d_I (the RK coefficients, not the material's values: a face is as fine as the field).
#pragma once
#include <cmath>

#include "model.hpp"
#include "state.hpp"

namespace rk {

// Face f's centre and area now: half the cross product of the diagonals (a quadrilateral) or of two
// edges (a triangle); that half cross product, the outward normal times the area, into `normal` if given.
inline double surface_face(const Model& md, const State& st, std::size_t f, double centre[3], double* normal = nullptr) {
  const auto k0 = md.surface_face_offsets[f], n = md.surface_face_offsets[f + 1] - k0;
  double x[4][3];
  centre[0] = centre[1] = centre[2] = 0;
  for (int a = 0; a < n; ++a) {
    const auto I = std::size_t(md.surface_face_nodes[std::size_t(k0 + a)]);
    for (int i = 0; i < 3; ++i) x[a][i] = md.X[3 * I + i] + st.u[3 * I + i], centre[i] += x[a][i] / n;
  }
  double d1[3], d2[3];
  for (int i = 0; i < 3; ++i) {
    d1[i] = n == 4 ? x[2][i] - x[0][i] : x[1][i] - x[0][i];
    d2[i] = n == 4 ? x[3][i] - x[1][i] : x[2][i] - x[0][i];
  }
  const double a[3] = {d1[1] * d2[2] - d1[2] * d2[1], d1[2] * d2[0] - d1[0] * d2[2], d1[0] * d2[1] - d1[1] * d2[0]};
  if (normal)
    for (int i = 0; i < 3; ++i) normal[i] = 0.5 * a[i];
  return 0.5 * std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

// A face touches a die or a plane whose surface lies within this fraction of its size (the square
// root of its area) outside it, or that it is inside: the penalty contact leaves the nodes of a face
// on a die a little inside it, and a face at the edge of the contact, a node lifting off, still
// touches across the thin gap.
inline constexpr double kFaceTouch = 0.1;

}  // namespace rk
