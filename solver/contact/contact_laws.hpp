// The pointwise contact laws, apart from the obstacle search and the loops over slaves
// (die_contact.cpp): for one slave in contact, the force the rigid obstacle puts on it.
// - Normal: penalty on the penetration depth d, f_n = k d along the obstacle's normal n (toward the
//   material), k = s m / dt_min^2 with s the scale at this run's CFL (Scene::penalty_scale_at_cfl: the
//   stiffness does not follow time.cfl), m the slave's mass and dt_min the smallest unclipped global
//   stable step so far (since the last reference update, which starts a new configuration): tied to the step, so contact never shrinks it (s <= 1), and never softening,
//   so a stiffness that follows the step's ringing does not pump energy into a ringing contact; at
//   most m / dt^2 (sqrt(k/m) dt <= 1, half the spring's stability limit) where the step grew back.
//   The spring stores k d^2 / 2. A spring held at that limit (after a reference update the step grows
//   past the new reference's step its stiffness keeps to: Scene::reference_updates.step_growth) rings
//   near the step's own period, so it takes a dashpot of a fraction xi of critical, c = 2 xi sqrt(k m)
//   = 2 xi m / dt (contact.damping, 0.2: the central difference's limit for the damped spring,
//   2 (sqrt(1 + xi^2) - xi) = 1.63, stays above its sqrt(k/m) dt = 1). The spring never pulls.
// - Tangential: Coulomb friction with an elastic stick, a tangential spring of the same stiffness k
//   loaded by the slip and capped at mu f_n (the return map of penalty friction in the explicit FE
//   codes); its stiffness held like the normal's, a stuck slave's slip does not grow with the step.
//   The spring stores |f_t|^2 / (2 k).
// - The shear factor and hybrid laws of hot forging (tau = m k, tau = min(mu p, m k)) act on the part's
//   boundary faces (contact/die_contact.cpp) with the flow stress and pressure of the face's cell, through
//   the same elastic stick (its k from the face's mass) capped at tau A.
// Pure functions, unit-tested without particles or MPI (tests/unit/test_contact_laws.cpp).
#pragma once
#include <algorithm>
#include <cmath>

namespace rk {

// k = min(s m / dt_min^2, m / dt^2) (N/m)
inline double penalty_stiffness(double penalty_scale, double mass, double dt_min, double dt) {
  return std::min(penalty_scale * mass / (dt_min * dt_min), mass / (dt * dt));
}

// The dashpot of a penalty spring (N s/m): 2 xi m / dt where its stiffness is held at m / dt^2 (the step
// past the one it was set at: dt^2 s > dt_min^2), 0 elsewhere.
inline double penalty_damping(double damping, double penalty_scale, double mass, double dt_min, double dt) {
  return penalty_scale * dt * dt > dt_min * dt_min ? 2 * damping * mass / dt : 0.0;
}

// f = f_n n, f_n = max(k d - c v_n, 0): the normal force of a penalty spring of stiffness k compressed by
// depth d >= 0, with its dashpot c (0: none), v_n the material's velocity along the normal relative to the
// obstacle (< 0 approaching); it pushes, never pulls. Returns f_n.
inline double penalty_force(double k, double depth, double c, double vn, const double normal[3], double f[3]) {
  const double fn = std::max(k * depth - c * vn, 0.0);
  for (int i = 0; i < 3; ++i) f[i] = fn * normal[i];
  return fn;
}

// The relative velocity's part tangential to the obstacle (unit normal n): v_t = v_rel - (v_rel . n) n.
// Returns |v_t|.
inline double tangential_velocity(const double v_rel[3], const double normal[3], double vt[3]) {
  double vn = 0;
  for (int i = 0; i < 3; ++i) vn += v_rel[i] * normal[i];
  for (int i = 0; i < 3; ++i) vt[i] = v_rel[i] - vn * normal[i];
  return std::sqrt(vt[0] * vt[0] + vt[1] * vt[1] + vt[2] * vt[2]);
}

// Friction with an elastic stick: a tangential spring of the normal's stiffness k between the slave and
// the point of the obstacle it stuck to, its force capped at c (mu f_n for Coulomb, tau A for the shear
// factor's laws). The last step's friction force f_old, its part in the tangent plane of the normal n,
// is loaded by the step's tangential slip v_t dt into the trial force f* = f_old,t - k dt v_t; the slave
// sticks (f = f*) while |f*| <= c and slips with f = c f* / |f*| otherwise. A stuck slave slides at most
// c / k whatever the step (mu d for Coulomb, d its penetration), where a stick force that stops the
// sliding in one step leaks a slip that grows with the step. Zero when c = 0.
inline void stick_friction(double cap, double k, const double f_old[3], const double normal[3], const double vt[3],
                           double dt, double f[3]) {
  f[0] = f[1] = f[2] = 0;
  if (!(cap > 0)) return;
  const double on_normal = f_old[0] * normal[0] + f_old[1] * normal[1] + f_old[2] * normal[2];
  for (int i = 0; i < 3; ++i) f[i] = f_old[i] - on_normal * normal[i] - k * dt * vt[i];
  const double trial = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  if (trial > cap)
    for (int i = 0; i < 3; ++i) f[i] *= cap / trial;
}

// Coulomb friction: the elastic stick capped at mu f_n.
inline void coulomb_friction(double mu, double normal_force, double k, const double f_old[3], const double normal[3],
                             const double vt[3], double dt, double f[3]) {
  stick_friction(mu > 0 ? mu * normal_force : 0.0, k, f_old, normal, vt, dt, f);
}

// The energy an elastic stick of stiffness k stores at its force f: |f|^2 / (2 k) (J).
inline double stick_energy(const double f[3], double k) { return (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]) / (2 * k); }

// The friction stress of the forging codes' laws at an interface where the material's flow stress is
// sigma_y (so its shear yield stress k = sigma_y / sqrt 3) and the contact pressure p >= 0:
// the shear factor law tau = m k (m in [0, 1]: 1 is sticking friction, the material shearing itself),
// and the hybrid law tau = min(mu p, m k) (Coulomb at low pressure, capped by the material's shear).
inline double shear_factor_stress(double m, double flow_stress) { return m * flow_stress / std::sqrt(3.0); }
inline double hybrid_friction_stress(double mu, double pressure, double m, double flow_stress) {
  return std::min(mu * std::max(pressure, 0.0), shear_factor_stress(m, flow_stress));
}

// The friction force of a stress tau over an area A: the elastic stick capped at tau A.
inline void interface_friction(double tau, double area, double k, const double f_old[3], const double normal[3],
                               const double vt[3], double dt, double f[3]) {
  stick_friction(tau * area, k, f_old, normal, vt, dt, f);
}

}  // namespace rk
