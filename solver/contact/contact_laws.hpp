// The pointwise contact laws, apart from the obstacle search and the loops over slaves
// (die_contact.cpp): for one slave in contact, the force the rigid obstacle puts on it.
// - Normal: penalty on the penetration depth d, f_n = k d along the obstacle's normal n (toward the
//   material), k = s m / dt_min^2 with s the scale at this run's CFL (Scene::penalty_scale_at_cfl: the
//   stiffness does not follow time.cfl), m the slave's mass and dt_min the smallest unclipped global
//   stable step so far (since the last reference update, which starts a new configuration): tied to the step, so contact never shrinks it (s <= 1), and never softening,
//   so a stiffness that follows the step's ringing does not pump energy into a ringing contact; at
//   most m / dt^2 (sqrt(k/m) dt <= 1, half the spring's stability limit) where the step grew back.
//   The spring stores k d^2 / 2.
// - Tangential: Coulomb friction. The stick force f_s is the force that stops the relative
//   tangential velocity v_t in one step (m |v_t| / dt, the caller's share of it); the slave sticks
//   when f_s <= mu f_n and slips with mu f_n otherwise, always against v_t.
// - The shear factor and hybrid laws of hot forging (tau = m k, tau = min(mu p, m k)) act on the part's
//   boundary faces (contact/die_contact.cpp) with the flow stress and pressure of the face's cell.
// Pure functions, unit-tested without particles or MPI (tests/unit/test_contact_laws.cpp).
#pragma once
#include <algorithm>
#include <cmath>

namespace rk {

// k = min(s m / dt_min^2, m / dt^2) (N/m)
inline double penalty_stiffness(double penalty_scale, double mass, double dt_min, double dt) {
  return std::min(penalty_scale * mass / (dt_min * dt_min), mass / (dt * dt));
}

// f = k d n: the normal force of a penalty spring of stiffness k compressed by depth d >= 0
inline void penalty_force(double k, double depth, const double normal[3], double f[3]) {
  for (int i = 0; i < 3; ++i) f[i] = k * depth * normal[i];
}

// The relative velocity's part tangential to the obstacle (unit normal n): v_t = v_rel - (v_rel . n) n.
// Returns |v_t|.
inline double tangential_velocity(const double v_rel[3], const double normal[3], double vt[3]) {
  double vn = 0;
  for (int i = 0; i < 3; ++i) vn += v_rel[i] * normal[i];
  for (int i = 0; i < 3; ++i) vt[i] = v_rel[i] - vn * normal[i];
  return std::sqrt(vt[0] * vt[0] + vt[1] * vt[1] + vt[2] * vt[2]);
}

// A friction force: min(f_stick, c x) against the sliding direction v_t / |v_t| (c x: mu f_n, or tau A);
// zero when c = 0 or nothing slides.
inline void sliding_friction(double c, double x, double stick_force, const double vt[3], double vt_norm, double f[3]) {
  f[0] = f[1] = f[2] = 0;
  if (!(c > 0 && vt_norm > 0)) return;
  const double magnitude = std::min(stick_force, c * x);
  for (int i = 0; i < 3; ++i) f[i] = -magnitude * vt[i] / vt_norm;
}

// Coulomb friction: the force min(f_stick, mu f_n) against the sliding direction.
inline void coulomb_friction(double mu, double normal_force, double stick_force, const double vt[3], double vt_norm,
                             double f[3]) {
  sliding_friction(mu, normal_force, stick_force, vt, vt_norm, f);
}

// The friction stress of the forging codes' laws at an interface where the material's flow stress is
// sigma_y (so its shear yield stress k = sigma_y / sqrt 3) and the contact pressure p >= 0:
// the shear factor law tau = m k (m in [0, 1]: 1 is sticking friction, the material shearing itself),
// and the hybrid law tau = min(mu p, m k) (Coulomb at low pressure, capped by the material's shear).
inline double shear_factor_stress(double m, double flow_stress) { return m * flow_stress / std::sqrt(3.0); }
inline double hybrid_friction_stress(double mu, double pressure, double m, double flow_stress) {
  return std::min(mu * std::max(pressure, 0.0), shear_factor_stress(m, flow_stress));
}

// The friction force of a stress tau over an area A: min(f_stick, tau A) against the sliding direction.
inline void interface_friction(double tau, double area, double stick_force, const double vt[3], double vt_norm,
                               double f[3]) {
  sliding_friction(tau, area, stick_force, vt, vt_norm, f);
}

}  // namespace rk
