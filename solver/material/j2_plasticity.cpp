#include "material/j2_plasticity.hpp"

#include <cmath>

namespace rk {

J2Update j2_update(const Eigen::Matrix3d& F, const J2Params& p, double cp_inv[6], double& ep) {
  Eigen::Matrix3d Cpi;
  Cpi << cp_inv[0], cp_inv[3], cp_inv[5], cp_inv[3], cp_inv[1], cp_inv[4], cp_inv[5], cp_inv[4], cp_inv[2];
  const Eigen::Matrix3d be = F * Cpi * F.transpose();  // trial elastic left Cauchy-Green tensor
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(be);
  const Eigen::Vector3d lam2 = eig.eigenvalues();
  const Eigen::Matrix3d& n = eig.eigenvectors();

  Eigen::Vector3d eps;  // principal logarithmic elastic strains
  for (int i = 0; i < 3; ++i) eps(i) = 0.5 * std::log(lam2(i));
  const double vol = eps.sum();
  Eigen::Vector3d dev = eps.array() - vol / 3;
  Eigen::Vector3d s = 2 * p.shear * dev;  // principal deviatoric Kirchhoff stress
  const double q = std::sqrt(1.5 * s.squaredNorm());

  J2Update out;
  if (p.plastic) {
    const double yield = p.yield0 + p.hardening * ep;
    if (q > yield) {
      const double dgamma = (q - yield) / (3 * p.shear + p.hardening);  // exact for linear hardening
      const double scale = 1 - 3 * p.shear * dgamma / q;
      s *= scale;
      dev *= scale;
      ep += dgamma;
      out.dissipation = (p.yield0 + p.hardening * ep) * dgamma;
    }
  }
  const Eigen::Vector3d tau_principal = s.array() + p.bulk * vol;
  out.tau = n * tau_principal.asDiagonal() * n.transpose();
  out.psi = 0.5 * p.bulk * vol * vol + p.shear * dev.squaredNorm();

  if (out.dissipation > 0) {  // C_p^{-1} = F^{-1} b_e F^{-T} with the returned b_e
    const Eigen::Vector3d b = (2 * (dev.array() + vol / 3)).exp();
    const Eigen::Matrix3d be_new = n * b.asDiagonal() * n.transpose();
    const Eigen::Matrix3d Fi = F.inverse();
    const Eigen::Matrix3d C = Fi * be_new * Fi.transpose();
    cp_inv[0] = C(0, 0), cp_inv[1] = C(1, 1), cp_inv[2] = C(2, 2);
    cp_inv[3] = 0.5 * (C(0, 1) + C(1, 0)), cp_inv[4] = 0.5 * (C(1, 2) + C(2, 1)), cp_inv[5] = 0.5 * (C(2, 0) + C(0, 2));
  }
  return out;
}

}  // namespace rk
