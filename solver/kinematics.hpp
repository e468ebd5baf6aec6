// Gather: F_g = I + sum_I d_I (x) grad_X N_I(X_g) at every integration point (total Lagrangian),
// and the F-bar cell average of det F.
#pragma once
#include "model.hpp"
#include "state.hpp"

namespace rk {

void compute_deformation_gradient(const Model& md, State& st);

}  // namespace rk
