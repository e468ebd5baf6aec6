// Finite-strain J2 plasticity, logarithmic elastic strain, radial return in Kirchhoff stress
// (Simo 1992; de Souza Neto, Peric & Owen, Computational Methods for Plasticity, box 14.3).
// The plastic state is C_p^{-1} (so b_e^trial = F C_p^{-1} F^T depends on F only: objective by
// construction) and the equivalent plastic strain ep. Isotropic hardening, linear
// sigma_y = sigma_y0 + H ep or power law sigma_y = K (eps0 + ep)^n (seed Table 4);
// `plastic = false` gives the Hencky hyperelastic special case.
// The update runs kLanes integration points at once (lanes.hpp); j2_update(F, ...) is one point.
#pragma once
#include <Eigen/Dense>
#include <cmath>

#include "material/lanes.hpp"

namespace rk {

struct J2Params {
  double bulk = 0, shear = 0;              // K, G (Pa)
  double yield0 = 0, hardening = 0;        // linear: sigma_y0, H (Pa)
  bool plastic = true;
  bool power_law = false;                  // power law: sigma_y = K (eps0 + ep)^n
  double strength = 0, eps0 = 0, exponent = 0;
  static J2Params from(double E, double nu, double yield0, double H, bool plastic) {
    return {E / (3 * (1 - 2 * nu)), E / (2 * (1 + nu)), yield0, H, plastic};
  }
  static J2Params power(double E, double nu, double K, double eps0, double n) {
    J2Params p = from(E, nu, K * std::pow(eps0, n), 0, true);
    p.power_law = true, p.strength = K, p.eps0 = eps0, p.exponent = n;
    return p;
  }
  double yield(double ep) const { return power_law ? strength * std::pow(eps0 + ep, exponent) : yield0 + hardening * ep; }
  // sigma_y and d sigma_y / d ep together (one pow for the power law)
  void yield_and_slope(double ep, double& y, double& h) const {
    if (!power_law) {
      y = yield0 + hardening * ep, h = hardening;
      return;
    }
    y = strength * std::pow(eps0 + ep, exponent);
    h = exponent * y / (eps0 + ep);
  }
};

// kLanes points: F (with F-bar applied), C_p^{-1} (Voigt xx, yy, zz, xy, yz, zx) and ep in; the
// updated C_p^{-1} and ep, the Kirchhoff stress and the energies out. Every F must have det F > 0;
// a lane not in use holds F = I, C_p^{-1} = I (at_rest).
struct J2Batch {
  Mat F;
  Sym cp_inv;
  Lane ep;
  Sym tau;            // Kirchhoff stress (Pa)
  Lane psi;           // stored elastic energy per reference volume (J/m^3)
  Lane dissipation;   // plastic work of this increment per reference volume (J/m^3)
  LaneMask plastic;   // the trial state was outside the yield surface (a return was made)
  void at_rest(int lane);
};

void j2_update(const J2Params& p, J2Batch& b);

struct J2Update {
  Eigen::Matrix3d tau;
  double psi = 0, dissipation = 0;
  bool plastic = false;
};

// One point (tests, tools): updates cp_inv and ep in place. F must have det F > 0.
J2Update j2_update(const Eigen::Matrix3d& F, const J2Params& p, double cp_inv[6], double& ep);

}  // namespace rk
