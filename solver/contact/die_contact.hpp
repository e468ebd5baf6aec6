// Contact of the workpiece with the moving rigid dies (seed 4.3), at two kinds of slave:
// - every owned particle, at X_I + d_I (its coefficient), not only those on the initial surface: in
//   forging the material folds and interior particles reach the dies;
// - every integration point of this rank, at the material point X_g + u^h(X_g), the force spread as
//   N_J(X_g) f onto the coefficients d_J. RK shape functions do not interpolate: with the
//   coefficients alone held, the field between them reached 0.3-0.6 mm (a quarter of a spacing)
//   into the punch corner of back extrusion, and the reference updates, which move the points to
//   the field, squeezed that material back onto the surface: the cup lost 12 % of its volume.
// Normal: penalty k = penalty_scale * m / dt^2 on the penetration depth, m the particle's mass or the
// point's rho w_g (tied to the stable step, so contact never shrinks it: sqrt(k/m) dt =
// sqrt(penalty_scale) < 2). Tangential: Coulomb friction, stick when the force that stops the
// relative tangential velocity in one step is within mu |f_n|, slip with mu |f_n| against the sliding
// direction otherwise. A point's stick force stops half its sliding: a particle and the points around
// it sample the same interface, and together they must not reverse it. A slave is looked up only
// when its distance to the die at its last lookup, less how far it and the die have moved since,
// may have run out (the same contacts as a lookup of every slave at every step). Computed by each
// particle's and each point's OWNER only; the forces enter the fixed-point partial sums, so shared
// copies receive them exactly once.
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
  double max_penetration = 0;   // this step, particles and points (m)
  double spring_energy = 0;     // energy stored in the penalty springs now, sum k d^2 / 2 (J)
  std::int64_t contacts = 0;    // this step: particles in contact
  std::int64_t point_contacts = 0;  // this step: integration points in contact
};

class DieContact {
 public:
  DieContact(const Model& md, const Scene& scene, const std::vector<DieSurface>& surfaces);
  bool empty() const { return dies_.empty(); }

  // Contact forces at time t from the positions and the velocities v^{n-1/2}; dt is the previous
  // (global) step. Adds -f_c to the fixed-point partials (after compute and the bound reduction).
  // Returns the largest force contribution to one particle, for the fixed-point bound.
  double compute(const Model& md, const State& st, double t, double dt);
  void add_to(const Model& md, State& st, const FixedScale& scale) const;
  // After the velocity update: the work of this step's contact forces with vbar.
  void account(const Model& md, const State& st, const std::vector<double>& v_old, double dt_avg, double t);

  // Moves x out of any die it is inside, onto the die's surface (a reference update's new particle
  // and point positions, on the material: its penalty contacts reach a little into the dies).
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
    std::int32_t slave, die;  // a local particle, or an integration point
    bool point;
    double normal_force[3], friction_force[3];
  };
  // The field of a (3 per particle) at point g.
  static void field_value(const Model& md, const std::vector<double>& a, std::size_t g, double out[3]);
  std::vector<Die> dies_;
  std::vector<DieSurface> surfaces_;
  std::vector<std::unique_ptr<DieSearch>> search_;
  std::vector<std::int32_t> slaves_;  // owned particles
  std::vector<double> point_N_max_, point_N_sum_;  // per point: max |N_J(X_g)|, sum |N_J(X_g)|
  // per die and slave (the owned particles, then the points): a lower bound on its distance to the die
  std::vector<double> clearance_;
  std::vector<double> u_last_, stroke_last_;  // at the last compute
  std::vector<Active> active_;        // reserved once: no allocation per step
  std::vector<DieTotals> totals_;
  std::vector<double> die_box_;  // per die at t = 0: lo[3], hi[3]
  double penalty_scale_;
};

}  // namespace rk
