// Finite-strain J2 plasticity, logarithmic elastic strain, radial return in Kirchhoff stress
// (Simo 1992; de Souza Neto, Peric & Owen, Computational Methods for Plasticity, box 14.3).
// The plastic state is C_p^{-1} (so b_e^trial = F C_p^{-1} F^T depends on F only: objective by
// construction) and the equivalent plastic strain ep. Isotropic hardening, linear
// sigma_y = sigma_y0 + H ep or power law sigma_y = K (eps0 + ep)^n (Wang et al. 2007, Table 4), or the flow
// stress of strain, strain rate and temperature of Johnson & Cook (1983),
//   sigma_y = (A + B ep^n) (1 + C ln max(rate / rate0, 1)) (1 - T*^m),  T* = (T - T_room) / (T_melt - T_room),
// or the hot-forging databases' Hansel & Spittel (1979) form, with T in Celsius as they give it,
//   sigma_y = A e^(m1 T) T^m9 ep^m2 e^(m4 / ep) (1 + ep)^(m5 T) e^(m7 ep) rate^(m3 + m8 T),
// ep and rate held at their minima below them. Both returns are rate-dependent: the plastic strain
// rate is this increment's, dgamma / dt, solved with dgamma (not the last step's rate).
// `plastic = false` gives the Hencky hyperelastic case.
// The update runs kLanes integration points at once (lanes.hpp); j2_point.hpp updates one point.
#pragma once
#include <cmath>

#include <memory>

#include "flow_table.hpp"
#include "material/lanes.hpp"

namespace rk {

struct J2Params {
  double bulk = 0, shear = 0;              // K, G (Pa)
  double yield0 = 0, hardening = 0;        // linear: sigma_y0, H (Pa)
  bool plastic = true;
  bool power_law = false;                  // power law: sigma_y = K (eps0 + ep)^n
  double strength = 0, eps0 = 0, exponent = 0;
  static constexpr int kBinomialTerms = 32;
  double binomial[kBinomialTerms] = {};     // C(n, k), the power law's return's series (j2_plasticity.cpp)
  // Johnson-Cook: A = yield0, B, n, C, rate0 (1/s), m, T_room and T_melt (K)
  bool johnson_cook = false;
  double jc_b = 0, jc_n = 1, jc_c = 0, jc_rate0 = 1, jc_m = 1, t_room = 293.15, t_melt = 0;
  // Hansel-Spittel: ln A (A in Pa; the log once, at_temperature takes it at every return), m1 (1/C), m2,
  // m3, m4, m5 (1/C), m7, m8 (1/C), m9; ep and rate minima
  bool hansel_spittel = false;
  double hs_log_a = 0, hs_m1 = 0, hs_m2 = 0, hs_m3 = 0, hs_m4 = 0, hs_m5 = 0, hs_m7 = 0, hs_m8 = 0, hs_m9 = 0;
  double hs_eps_min = 0, hs_rate_min = 0;
  double hs_eps_offset = 0, hs_rate_offset = 0;  // the law taken at ep + offset, rate + offset (the Freiberg fits')
  // a flow stress table (shared/flow_table.hpp), trilinear in (strain, ln rate, temperature)
  std::shared_ptr<const FlowTable> table;
  bool rate_dependent() const { return johnson_cook || hansel_spittel || table; }
  static J2Params from(double E, double nu, double yield0, double H, bool plastic) {
    J2Params p;
    p.bulk = E / (3 * (1 - 2 * nu)), p.shear = E / (2 * (1 + nu)), p.yield0 = yield0, p.hardening = H, p.plastic = plastic;
    return p;
  }
  static J2Params power(double E, double nu, double K, double eps0, double n) {
    J2Params p = from(E, nu, K * std::pow(eps0, n), 0, true);
    p.power_law = true, p.strength = K, p.eps0 = eps0, p.exponent = n;
    p.binomial[0] = 1;
    for (int k = 1; k < kBinomialTerms; ++k) p.binomial[k] = p.binomial[k - 1] * (n - k + 1) / k;
    return p;
  }
  static J2Params johnson_cook_law(double E, double nu, double A, double B, double n, double C, double rate0, double m,
                                   double t_room, double t_melt) {
    J2Params p = from(E, nu, A, 0, true);
    p.johnson_cook = true, p.jc_b = B, p.jc_n = n, p.jc_c = C, p.jc_rate0 = rate0, p.jc_m = m;
    p.t_room = t_room, p.t_melt = t_melt;
    return p;
  }
  static J2Params hansel_spittel_law(double E, double nu, const double a_m[9], double eps_min, double rate_min,
                                     double eps_offset = 0, double rate_offset = 0) {
    J2Params p = from(E, nu, 0, 0, true);
    p.hansel_spittel = true, p.hs_log_a = std::log(a_m[0]);
    p.hs_m1 = a_m[1], p.hs_m2 = a_m[2], p.hs_m3 = a_m[3], p.hs_m4 = a_m[4];
    p.hs_m5 = a_m[5], p.hs_m7 = a_m[6], p.hs_m8 = a_m[7], p.hs_m9 = a_m[8], p.hs_eps_min = eps_min, p.hs_rate_min = rate_min;
    p.hs_eps_offset = eps_offset, p.hs_rate_offset = rate_offset;
    p.yield0 = p.yield(0);
    return p;
  }
  // The flow stress at ep (Johnson-Cook: quasi-static, at the room temperature; Hansel-Spittel: at
  // the least rate, at 1000 C; a table: at its least rate and temperature), for the bounds that only
  // need its scale.
  double yield(double ep) const {
    if (johnson_cook) return yield0 + jc_b * std::pow(ep, jc_n);
    if (hansel_spittel || table) return hot_yield(ep);
    return power_law ? strength * std::pow(eps0 + ep, exponent) : yield0 + hardening * ep;
  }
  double hot_yield(double ep) const;
  // The rate-dependent laws' flow stress at (ep, rate, T) and its slopes d/d ep and d/d rate;
  // flow_at takes what depends on T alone (at_temperature), which a return computes once for its
  // iterations: Johnson-Cook's thermal factor 1 - T*^m (1 below the room temperature, 0 molten),
  // Hansel-Spittel's ln(A e^(m1 T) T^m9), m5 T and the rate exponent m3 + m8 T.
  struct AtTemperature {
    double thermal = 1, log_a = 0, strain_t = 0, rate_exponent = 0, T = 0;
  };
  AtTemperature at_temperature(double T) const;
  double thermal_factor(double T) const;
  void flow_at(double ep, double rate, const AtTemperature& at, double& y, double& dy_dep, double& dy_drate) const {
    if (hansel_spittel) return hansel_spittel_at(ep, rate, at, y, dy_dep, dy_drate);
    if (table) return table->at(ep, rate, at.T, y, dy_dep, dy_drate);
    johnson_cook_at(ep, rate, at.thermal, y, dy_dep, dy_drate);
  }
  void johnson_cook_at(double ep, double rate, double thermal, double& y, double& dy_dep, double& dy_drate) const;
  void hansel_spittel_at(double ep, double rate, const AtTemperature& at, double& y, double& dy_dep, double& dy_drate) const;
  void flow(double ep, double rate, double T, double& y, double& dy_dep, double& dy_drate) const {
    flow_at(ep, rate, at_temperature(T), y, dy_dep, dy_drate);
  }
  // The flow stress of any law at (ep, rate, T): the rate-dependent laws' flow, the others' yield(ep).
  double flow_stress(double ep, double rate, double T) const {
    if (!rate_dependent()) return yield(ep);
    double y, h, hr;
    flow(ep, rate, T, y, h, hr);
    return y;
  }
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
  Lane T{};           // temperature (K), rate-dependent laws only: the start of the increment's
  Lane rate_last{};   // the last increment's plastic strain rate (1/s), rate-dependent laws only: the return's first guess (0: none)
  double dt = 0;      // the increment's time (s), rate-dependent laws only: rate = dgamma / dt (0: no rate effect)
  void at_rest(int lane);
};

void j2_update(const J2Params& p, J2Batch& b);

}  // namespace rk
