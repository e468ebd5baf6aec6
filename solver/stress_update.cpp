#include "stress_update.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "material/j2_plasticity.hpp"

namespace rk {

StressHealth update_stress(const Model& md, State& st) {
  StressHealth health;
  for (std::size_t c = 0; c < md.cells; ++c) {
    double wp = 0, wJ = 0;
    for (auto g = md.cell_points[c]; g < md.cell_points[c + 1]; ++g) {
      if (!(st.J[g] > 0) || !std::isfinite(st.J[g])) {
        if (health.ok) health = {false, std::size_t(g), st.J[g]};
        continue;
      }
      const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> F(&st.F[9 * g]);
      const double ratio = md.fbar ? std::cbrt(st.cell_J[c] / st.J[g]) : 1.0;
      const J2Update up = j2_update(ratio * F, md.material, &st.cp_inv[6 * g], st.ep[g]);
      double* t = &st.tau[6 * g];
      t[0] = up.tau(0, 0), t[1] = up.tau(1, 1), t[2] = up.tau(2, 2), t[3] = up.tau(0, 1), t[4] = up.tau(1, 2),
      t[5] = up.tau(2, 0);
      st.psi[g] = up.psi;
      st.wp[g] += up.dissipation;
      health.plastic += up.plastic;
      wp += md.weight[g] * (t[0] + t[1] + t[2]) / 3;
      wJ += md.weight[g] * st.total_J(g);
    }
    if (!health.ok) continue;
    const double pc = md.fbar ? wp / wJ : 0.0;
    for (auto g = md.cell_points[c]; g < md.cell_points[c + 1]; ++g) {
      const double* t = &st.tau[6 * g];
      Eigen::Matrix3d te;
      te << t[0], t[3], t[5], t[3], t[1], t[4], t[5], t[4], t[2];
      if (md.fbar) te.diagonal().array() += st.total_J(g) * pc - te.trace() / 3;
      const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> F(&st.F[9 * g]);
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> P(&st.P[9 * g]);
      P = te * F.inverse().transpose();
      st.force_bound[g] = md.weight[g] * P.norm() * md.dN_max[g];
    }
  }
  return health;
}

}  // namespace rk
