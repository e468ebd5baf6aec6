// Scatter: f^int_I = sum_g w_g P_g grad_X N_I(X_g) (seed eq. (19)) from this rank's own points,
// accumulated in fixed point (fixed_point.hpp) so the result is independent of summation order.
#pragma once
#include "fixed_point.hpp"
#include "model.hpp"
#include "state.hpp"

namespace rk {

void compute_internal_force(const Model& md, State& st, const FixedScale& scale);

}  // namespace rk
