// The state that evolves (and is all a checkpoint needs): particle displacements and velocities,
// integration-point plastic state and stress. Structure of arrays; sizes fixed at start-up so the
// step loop never allocates. Voigt order for symmetric tensors: xx, yy, zz, xy, yz, zx.
#pragma once
#include <cstdint>
#include <vector>

#include "model.hpp"
#include "parallel/fixed_point.hpp"

namespace rk {

inline constexpr std::size_t kForceStride = 4;  // State::partial's entries per particle

struct State {
  double t = 0;
  std::int64_t step = 0;
  double dt_half = 0;  // dt^{n-1/2}, the step that led to the current positions
  // with multi-rate steps (subcycles.hpp; empty otherwise): each particle's own last step, the span of
  // its velocity v^{n-1/2}
  std::vector<double> particle_dt_half;
  // and each cell's last update time (its next increment spans t - cell_t_last)
  std::vector<double> cell_t_last;

  // particles (3 per particle)
  std::vector<double> u, v, force;  // displacement d_I, velocity, net internal force f^int_I
  // fixed-point force accumulators (own points, then summed), kForceStride per particle: x, y, z and
  // a zero pad, so that one vector instruction adds a term to a particle
  std::vector<Fixed> partial;

  // integration points
  std::vector<double> F;       // 9 per point, row-major F_ik = delta_ik + sum_I u_Ii dN_I/dX_k
  std::vector<double> J;       // det F
  std::vector<double> P;       // 9 per point, first Piola-Kirchhoff stress used in the force
  std::vector<double> tau;     // 6 per point, Kirchhoff stress (F-bar)
  std::vector<double> cp_inv;  // 6 per point, plastic state C_p^{-1}
  std::vector<double> ep;      // equivalent plastic strain
  std::vector<double> psi;     // stored elastic energy density (J/m^3, reference volume)
  std::vector<double> wp;      // accumulated plastic work density (J/m^3, reference volume)
  std::vector<double> plastic_rate;  // the last increment's d ep / dt (1/s); with shear friction or a temperature (else empty)
  std::vector<double> force_bound;  // per point: w |P| max|grad N|, bounds its force contributions
  std::vector<double> cell_J;  // cell-averaged det F (F-bar)
  // bulk viscosity (material/bulk_viscosity.hpp), empty when off: q, the stable step's factor, and the det F
  // (from t = 0; the cell's with F-bar) at the last step
  std::vector<double> q, dt_factor, J_last;
  // temperature (K) per point where the material has one (material.specific_heat; empty otherwise):
  // raised by the plastic work of each increment, and with conduction set to T^h(X_g) at each
  // thermal update (thermal/heat_transfer.hpp)
  std::vector<double> temperature;
  // conduction only (material.conductivity; empty otherwise): the particles' temperature
  // coefficients T_I, and each point's plastic heating since the last thermal update (K), which
  // `temperature` already holds and the next update spreads to the particles
  std::vector<double> particle_temperature, heat_pending;
  std::vector<double> surface_heat;  // per particle: the friction's heat at it as a contact slave (J), owner only
  double thermal_t = 0, thermal_dt = 0;  // the last thermal update's time and its stable step (s)
  std::int64_t thermal_step = 0;         // the mechanical step of the last thermal update
  std::int64_t thermal_updates = 0;
  double ambient_heat = 0;  // given to the ambient by this rank's surface faces, cumulative (J)

  // reference updates (rk/reference_update.hpp); empty until the first: the particles' displacements
  // at the last update (F is gathered from d - d^ref) and each point's det F up to it
  std::vector<double> u_ref, J_ref;
  // d_I - d_I^ref four apart (the fourth 0), the deformation gradient's copy (rk/kinematics.cpp): not state,
  // rewritten at every gather
  std::vector<double> d_gather;
  std::int64_t reference_updates = 0;
  // det of the deformation gradient from t = 0 (J above is since the last reference update)
  double total_J(std::size_t g) const { return J_ref.empty() ? J[g] : J[g] * J_ref[g]; }

  // work of the body force done on the OWNED particles of this rank (sum over ranks = total); the
  // contact forces' work is the obstacles' (contact/die_contact.hpp)
  double external_work = 0;
  // work of the pair forces of the part's contact with itself and between bodies on this rank's slaves
  // (contact/part_contact.hpp): the springs' energy while they are compressed, zero once they let go
  double part_contact_work = 0;
  double update_work = 0;  // kinetic energy changed by reference updates (<= 0: smoothed away)
  double viscous_work = 0;  // work of the bulk viscosity on this rank's points (dissipated, >= 0)
  // with a thermal strain (Model::thermal_strain; empty otherwise): each point's stress-free stretch at
  // its last stress update (0: none yet), and the work the stress did on the thermal strain, sum_g w_g
  // int tr(tau) d ln(stretch), on this rank's points: part of the internal energy (the stress's work on
  // the whole strain), which the stored energy psi of the mechanical strain alone leaves out
  std::vector<double> stretch_last;
  // ductile damage (Scene::damage; empty without it): kDamageCriteria per point, normalized
  // Cockcroft-Latham, Brozzo and Oyane (material/damage.hpp), each 0 where the scene does not ask for it
  std::vector<double> damage;
  double thermal_work = 0;
  std::int64_t contacts = 0;
  // time.stable_step = frequency (highest_frequency.hpp; empty otherwise): the power iteration's vector
  // (3 per particle, towards the highest mode of M^-1 K), and the ratio of its step 2 / omega_max to
  // the cells' estimate at its last iteration (0: none since the start or the last reference update)
  std::vector<double> stiff_mode;
  double step_ratio = 0;
  // the rams of the dies driven by their press (contact/presses.hpp), in die order; the same on every rank
  struct Ram {
    double stroke = 0, speed = 0;  // s^n (m) and v^{n-1/2} (m/s) along the die's direction
    double delivered = 0;          // energy delivered to the whole part (J)
    double blows = 0;              // blows begun (a hammer or screw press)
    double stopped = 0;            // 1: at rest for good
    double since_t = 0, since_s = 0;  // a hydraulic press's stall window: its start time and stroke
  };
  static constexpr std::size_t kRamValues = 7;  // the doubles of a Ram (its checkpoint row)
  std::vector<Ram> rams;

  // v_I = velocity + gradient X_I (gradient row-major: d v_i / d X_j)
  static State initial(const Model& md, const double velocity[3], const double gradient[9]);
};

}  // namespace rk
