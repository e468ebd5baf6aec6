// The pointwise contact laws, apart from the obstacle search and the loops over slaves
// (die_contact.cpp): for one slave in contact, the force the rigid obstacle puts on it.
// - Normal: penalty on the penetration depth d, f_n = k d along the obstacle's normal n (toward the
//   material), k = s m / dt^2 with m the slave's mass and dt the last unclipped global stable step:
//   tied to the step, so contact never shrinks it (s <= 1). The spring stores k d^2 / 2.
// - Tangential: Coulomb friction. The stick force f_s is the force that stops the relative
//   tangential velocity v_t in one step (m |v_t| / dt, the caller's share of it); the slave sticks
//   when f_s <= mu f_n and slips with mu f_n otherwise, always against v_t.
// Pure functions, unit-tested without particles or MPI (tests/unit/test_contact_laws.cpp).
#pragma once
#include <algorithm>
#include <cmath>

namespace rk {

// k = s m / dt^2 (N/m)
inline double penalty_stiffness(double penalty_scale, double mass, double dt) { return penalty_scale * mass / (dt * dt); }

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

// Coulomb friction: the force min(f_stick, mu f_n) against the sliding direction v_t / |v_t|;
// zero when mu = 0 or nothing slides.
inline void coulomb_friction(double mu, double normal_force, double stick_force, const double vt[3], double vt_norm,
                             double f[3]) {
  f[0] = f[1] = f[2] = 0;
  if (!(mu > 0 && vt_norm > 0)) return;
  const double magnitude = std::min(stick_force, mu * normal_force);
  for (int i = 0; i < 3; ++i) f[i] = -magnitude * vt[i] / vt_norm;
}

}  // namespace rk
