// Symmetry planes, imposed nodally (on the particle coefficients; approximate for non-interpolating
// RK shape functions, exact methods come with the transformation method): the velocity of a
// particle on a plane loses its components along the plane normals (orthonormalized per particle).
#pragma once
#include "model.hpp"
#include "state.hpp"

namespace rk {

void apply_symmetry(const Model& md, State& st);

}  // namespace rk
