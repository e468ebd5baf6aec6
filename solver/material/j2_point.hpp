// The J2 update of one point with Eigen's matrices (tests, tools): the batch update of j2_plasticity.hpp
// run on one lane. Kept apart so the solver's files that see J2Params do not parse Eigen (2.4 s a file).
#pragma once
#include <Eigen/Dense>

#include "material/j2_plasticity.hpp"

namespace rk {

struct J2Update {
  Eigen::Matrix3d tau;
  double psi = 0, dissipation = 0;
  bool plastic = false;
};

// Updates cp_inv and ep in place. F must have det F > 0; T and dt as in J2Batch.
J2Update j2_update(const Eigen::Matrix3d& F, const J2Params& p, double cp_inv[6], double& ep, double T = 0,
                   double dt = 0);

}  // namespace rk
