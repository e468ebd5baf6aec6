// Particle-to-segment contact of the particles with the moving rigid dies (seed 4.3). Every owned
// particle is a slave, not only those on the initial surface: in forging the material folds and
// interior particles reach the dies (a bin lookup is all a particle far from the dies costs).
// Normal: penalty k_I = penalty_scale * m_I / dt^2 on the penetration depth (tied to the stable step,
// so contact never shrinks it: sqrt(k/m) dt = sqrt(penalty_scale) < 2). Tangential: Coulomb friction,
// stick when the force that stops the relative tangential velocity in one step is within mu |f_n|,
// slip with mu |f_n| against the sliding direction otherwise. Computed by each particle's OWNER
// only; the force enters the fixed-point partial sums, so shared copies receive it exactly once.
#pragma once
#include <memory>
#include <vector>

#include "die_search.hpp"
#include "model.hpp"
#include "scene.hpp"
#include "state.hpp"

namespace rk {

struct DieTotals {       // per die, over the owned particles of this rank
  double force[3] = {0, 0, 0};  // force of the die on the modeled part this step (N)
  double press_work = 0;        // work done by the die on the part, cumulative (J)
  double friction_work = 0;     // dissipated by friction, cumulative (J), >= 0
  double contact_work = 0;      // work of normal + friction forces on the part, cumulative (J)
  double max_penetration = 0;   // this step (m)
  double spring_energy = 0;     // energy stored in the penalty springs now, sum k d^2 / 2 (J)
  std::int64_t contacts = 0;    // this step
};

class DieContact {
 public:
  DieContact(const Model& md, const Scene& scene, const std::vector<DieSurface>& surfaces);
  bool empty() const { return dies_.empty(); }

  // Contact forces at time t from the positions and the velocities v^{n-1/2}; dt is the previous
  // (global) step. Adds -f_c to the fixed-point partials of the owned particles (after compute and
  // the bound reduction). Returns the largest force component, for the fixed-point bound.
  double compute(const Model& md, const State& st, double t, double dt);
  void add_to(State& st, const FixedScale& scale) const;
  // After the velocity update: the work of this step's contact forces with vbar.
  void account(const State& st, const std::vector<double>& v_old, double dt_avg, double t);

  // A reference update's new position x of a particle whose position is now c: a particle in
  // contact stays at c (its contact force does not jump), one that is not is moved out of any die
  // it would be inside.
  void project(double t, const double* c, double* x) const;
  // Moves x out of any die it is inside, onto the die's surface (a reference update's integration
  // points: the field between the contact-held coefficients can reach past a die).
  void push_out(double t, double* x) const;

  // The box the part may move in: its initial box joined with every die's box at time t, grown by a
  // quarter of its largest side. A particle outside has left the tools (a health check).
  void box(const double part_lo[3], const double part_hi[3], double t, double lo[3], double hi[3]) const;

  const std::vector<DieTotals>& totals() const { return totals_; }
  std::vector<DieTotals>& totals() { return totals_; }  // restored from a checkpoint
  const Die& die(std::size_t k) const { return dies_[k]; }
  std::size_t size() const { return dies_.size(); }

 private:
  struct Active {
    std::int32_t particle, die;
    double normal_force[3], friction_force[3];
  };
  std::vector<Die> dies_;
  std::vector<DieSurface> surfaces_;
  std::vector<std::unique_ptr<DieSearch>> search_;
  std::vector<std::int32_t> slaves_;  // owned particles
  std::vector<Active> active_;        // reserved once: no allocation per step
  std::vector<DieTotals> totals_;
  std::vector<double> die_box_;  // per die at t = 0: lo[3], hi[3]
  double penalty_scale_;
};

}  // namespace rk
