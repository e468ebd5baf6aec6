// Contact of the workpiece with the moving rigid dies (seed 4.3), its fixed rigid walls and its
// symmetry planes: one treatment for every rigid obstacle. The slaves are material points, each with
// its row of shape functions:
// - every owned particle at X_I + u^h(X_I) (not at its coefficient X_I + d_I), not only those on
//   the initial surface: in forging the material folds and interior particles reach the dies;
// - every integration point of this rank at X_g + u^h(X_g) (with nodal integration the points are
//   the particles' material points, and the particles are not slaves again);
// a slave's contact force f acts on the field there, spread as N_J f onto the coefficients d_J.
// RK shape functions do not interpolate: a die that held the coefficients let the field between and
// at them reach into it (0.3-0.6 mm into back extrusion's punch corner with only the particles'
// coefficients held; 2-20 um at the particles with the points held too), and each reference
// update, which moves the material to the field, had to cut that layer off at the die surface:
// back extrusion's cup lost 12 mm^3 per update (its wall ended at 88 % of its height). Held at the
// field, the material is where the dies let it be, and an update leaves it there.
// Rigid walls are frictionless fixed planes for the same slaves (a wall that held the coefficients
// kinematically let the field at the impact face's rim reach through it, and the same Taylor bar read
// a footprint 3 % apart from the one held on a flat die).
// Symmetry planes are frictionless fixed planes for the same slaves, except the particles (and nodal
// points) lying on the plane, which the EBCs hold both ways (a one-sided hold on them biased the
// material away from the plane: the quarter Taylor bar 1.3 % wider). The nodal EBCs hold the
// coefficients of the particles on a plane, not the field, and a die that presses the field near
// a plane pushed it across (back extrusion's punch corner: integration points 4.8 mm past y = 0 at
// 12 mm of stroke, then a singular moment matrix).
// Normal: penalty k = penalty_scale * m / dt^2 on the penetration depth, m the particle's mass or the
// point's rho w_g (tied to the stable step, so contact never shrinks it: spread over a row, it
// stiffens the coefficients by sum_J N_J^2 k / m_J, with sum_J N_J^2 at most 0.85 and 0.14-0.25 on
// average, measured on back extrusion and wheel forging). Tangential: Coulomb friction, stick when
// the force that stops the relative tangential velocity in one step is within mu |f_n|, slip with
// mu |f_n| against the sliding direction otherwise. A point's stick force stops half its sliding: a
// particle and the points around it sample the same interface, and together they must not reverse
// it. A slave is looked up only when its distance to the die at its last lookup, less how far it
// and the die have moved since, may have run out (the same contacts as a lookup of every slave at
// every step). Computed by each particle's and each point's OWNER only; the forces enter the
// fixed-point partial sums, so shared copies receive them exactly once.
#pragma once
#include <memory>
#include <vector>

#include "die_search.hpp"
#include "model.hpp"
#include "scene.hpp"
#include "state.hpp"

namespace rk {

struct DieTotals {       // per die, per rigid wall, and one for the symmetry planes, over this rank's slaves
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
  bool empty() const { return dies_.empty() && planes_.empty(); }  // nothing to meet

  // Contact forces at time t from the positions and the velocities v^{n-1/2}; dt is the previous
  // (global) step. Adds -f_c to the fixed-point partials (after compute and the bound reduction).
  // Returns the largest force contribution to one particle, for the fixed-point bound.
  double compute(const Model& md, const State& st, double t, double dt);
  void add_to(const Model& md, State& st, const FixedScale& scale) const;
  // After the velocity update: the work of this step's contact forces with vbar.
  void account(const Model& md, const State& st, const std::vector<double>& v_old, double dt_avg, double t);

  // The box the part may move in: its initial box joined with every die's box at time t, grown by a
  // quarter of its largest side. A particle outside has left the tools (a health check).
  void box(const double part_lo[3], const double part_hi[3], double t, double lo[3], double hi[3]) const;

  // One entry per die, one per rigid wall, then one for the symmetry planes (when the scene has any).
  const std::vector<DieTotals>& totals() const { return totals_; }
  std::vector<DieTotals>& totals() { return totals_; }  // restored from a checkpoint
  const Die& die(std::size_t k) const { return dies_[k]; }
  std::size_t size() const { return dies_.size(); }  // the dies (totals()[0 .. size()))
  // The force of rigid wall w on the part along the wall's normal, this step (totals()[size() + w]).
  double wall_force(std::size_t w) const;
  // How deep this rank's material is past a symmetry plane this step (m), and the local particle
  // there (the slave's, or the point's largest N_J; -1 when none is past), for the health check.
  double symmetry_depth() const;
  std::int32_t deepest_particle(const Model& md) const;

 private:
  struct Row {  // a slave's shape functions (md.material_* or the point's): u^h(x) = sum_k N[k] d_{cols[k]}
    const std::int32_t* cols;
    const double* N;
    std::int32_t size;
  };
  struct Active {
    std::int32_t slave, obstacle;  // slave: particles first, then points; obstacle: dies, then planes
    double normal_force[3], friction_force[3];
  };
  Row row(const Model& md, std::size_t s) const;
  void material_point(const Model& md, const State& st, std::size_t s, double x[3]) const;
  void material_value(const Model& md, const std::vector<double>& a, std::size_t s, double out[3]) const;

  std::vector<Die> dies_;
  std::vector<DieSurface> surfaces_;
  std::vector<std::unique_ptr<DieSearch>> search_;
  struct Plane {          // a fixed frictionless plane: a rigid wall or a symmetry plane
    double point[3], normal[3];  // the normal toward the material
    std::size_t total;           // its entry in totals_
  };
  std::vector<Plane> planes_;  // the rigid walls, then the symmetry planes
  std::size_t walls_ = 0;
  std::int32_t deepest_ = -1;  // this step's slave deepest past a symmetry plane
  std::vector<std::int32_t> particles_;  // the owned particles (slaves 0 .. particles_.size())
  std::vector<double> mass_, N_sum_, N_max_;  // per slave: m, sum_J |N_J|, max_J |N_J|
  // per obstacle and slave: a lower bound on its distance to the obstacle
  std::vector<double> clearance_;
  std::vector<double> u_last_, stroke_last_;  // at the last compute
  std::vector<Active> active_;        // reserved once: no allocation per step
  std::vector<DieTotals> totals_;
  std::vector<double> die_box_;  // per die at t = 0: lo[3], hi[3]
  double penalty_scale_, margin_ = 0;
};

}  // namespace rk
