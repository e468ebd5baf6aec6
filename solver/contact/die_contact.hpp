// Contact of the workpiece with the moving rigid dies (Wang et al. 2007, Sec. 4.3), its fixed rigid walls and its
// symmetry planes: one treatment for every rigid obstacle, on the material, not on the coefficients.
// The slaves are material points, each with its row of shape functions:
// - every owned particle at X_I + u^h(X_I), not only those on the initial surface;
// - every integration point of this rank at X_g + u^h(X_g) (with nodal integration the points are
//   the particles' material points, and the particles are not slaves again).
// A slave's contact force f acts on the field there, spread as N_J f onto the coefficients d_J.
// Rigid walls and symmetry planes are frictionless fixed planes for the same slaves, except that the
// particles (and nodal points) lying on a symmetry plane are left to the essential BCs, which hold
// them there both ways; a symmetry plane's normal points to the side of the rank's particles.
// The pointwise laws are in contact/contact_laws.hpp: penalty k = s m / dt_min^2 (m the particle's mass
// or the point's rho w_g, dt_min the smallest stable step so far, so contact never shortens it; at most m / dt^2,
// a spring held there damped at contact.damping of critical) and Coulomb friction
// with an elastic stick of the same k, whose force a slave carries from step to step while it touches the die.
// A slave is looked up only when its clearance at its last lookup, less how far it and the die may
// have moved since, may have run out, and a block of slaves only when its least clearance may have.
// Computed by each particle's and each point's OWNER only; the forces enter the fixed-point partial
// sums, so shared copies receive them exactly once.
// Why each choice, with what was measured: docs/decisions.md, "Contact".
#pragma once
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "contact/die_candidates.hpp"
#include "die_search.hpp"
#include "parallel/fixed_point.hpp"
#include "model.hpp"
#include "scene.hpp"
#include "state.hpp"

namespace rk {

struct DieTotals {       // per die, per rigid wall, and one for the symmetry planes, over this rank's slaves
  double force[3] = {0, 0, 0};  // force of the die on the modeled part this step (N)
  double press_work = 0;        // work done by the die on the part, cumulative (J)
  double friction_work = 0;     // dissipated by friction and the penalty's dashpot, cumulative (J), >= 0
  double contact_work = 0;      // work of normal + friction forces on the part, cumulative (J)
  double max_penetration = 0;   // this step, particles and points (m)
  double spring_energy = 0;     // energy stored in the penalty springs now, sum k d^2 / 2 (J)
  std::int64_t contacts = 0;    // this step: particles in contact
  std::int64_t point_contacts = 0;  // this step: integration points in contact
  double heat = 0;              // conducted from the part into the die, cumulative (J)
};

class DieContact {
 public:
  // previous: the contact this one replaces (a reference update): its dies' searches are taken over where
  // they fit (the same margin; the dies' triangles never change), instead of built again
  DieContact(const Model& md, const Scene& scene, const std::vector<DieSurface>& surfaces, DieContact* previous = nullptr);
  bool empty() const { return dies_.empty() && planes_.empty(); }  // nothing to meet

  // Contact forces at time t from the positions and the velocities v^{n-1/2}; dt is the previous
  // (global) step, dt_min the smallest so far (contact_laws.hpp). Returns the largest force contribution
  // to one particle, for the fixed-point bound.
  double compute(const Model& md, const State& st, double t, double dt, double dt_min);
  // Adds -f_c to the fixed-point partials (kForceStride per particle, as State::partial; after compute
  // and the bound reduction).
  void add_to(const Model& md, std::vector<Fixed>& partial, const FixedScale& scale) const;
  // After the velocity update: the work of this step's contact forces with vbar. With heat
  // conduction, the friction's heat is shared between the die (its `heat`) and the part: at a point
  // slave its temperature rises, at a particle slave its surface_heat gathers it for the next thermal
  // update.
  void account(const Model& md, State& st, const std::vector<double>& v_old, double dt_avg, double t);

  // The box the part may move in: its initial box joined with every die's box at time t, grown by a
  // quarter of its largest side (room for the material the tools push out). A particle outside has
  // left the tools (a health check).
  void box(const double part_lo[3], const double part_hi[3], double t, double lo[3], double hi[3]) const;

  // What the point x (a surface face's centre) touches at time t, within `tolerance` outside it (or
  // any depth inside): a die's index, -2 for a rigid wall or a symmetry plane, -1 for nothing.
  int touching(const double x[3], double t, double tolerance) const;

  // Adds to terms[J] the most contact terms add_to can put into particle J's fixed-point force in a
  // step from this rank (for the headroom, internal_force.hpp): one per obstacle (die, rigid wall,
  // symmetry plane) for every slave whose row holds J, one for every face with friction holding J
  // (a face meets one die at a time). Set-up only.
  void count_terms(const Model& md, std::vector<Fixed>& terms) const;
  // The contact terms a particle usually takes from the boundary faces' friction (for the scale's
  // resolution, the fixed-point headroom): none without a shear factor; a node's faces, 64.
  int face_terms() const { return shear_ ? 64 : 0; }

  // One entry per die, one per rigid wall, then one for the symmetry planes (when the scene has any).
  const std::vector<DieTotals>& totals() const { return totals_; }
  std::vector<DieTotals>& totals() { return totals_; }  // restored from a checkpoint
  const Die& die(std::size_t k) const { return dies_[k]; }
  std::size_t size() const { return dies_.size(); }  // the dies (totals()[0 .. size()))
  // Die k's stroke and its rate at time t: its motion's, or for a die driven by its press what
  // Presses last told drive().
  double stroke(std::size_t k, double t) const { return dies_[k].motion.driven() ? driven_[2 * k] : dies_[k].motion.stroke(t); }
  double rate(std::size_t k, double t) const { return dies_[k].motion.driven() ? driven_[2 * k + 1] : dies_[k].motion.rate(t); }
  // Die k's velocity over the step that brought the part to t (dt long, 0 at the first), the step of the part's
  // v^{n-1/2} that the contact meets it with: a curve's slope changes at its points, and its slope after t (the
  // next step's) read the last row of a run ending where its curve ends with the die already stopped (the hot
  // upsetting's dashpots: the press force 51.3 kN there against 56.2 kN a row before and 56.4 kN with the curve
  // run on). Other motions' rate(k, t): a press's is its v^{n-1/2} already.
  double rate_before(std::size_t k, double t, double dt) const {
    const DieMotion& mo = dies_[k].motion;
    if (mo.driven() || mo.curve.empty() || !(dt > 0)) return rate(k, t);
    return (mo.stroke(t) - mo.stroke(t - dt)) / dt;
  }
  void drive(std::size_t k, double stroke, double rate) { driven_[2 * k] = stroke, driven_[2 * k + 1] = rate; }
  // This step's force of die k on the part along its direction: the largest single contribution, and
  // their sum in fixed point (the same on every partition).
  double reaction_bound(std::size_t k) const;
  Fixed reaction(std::size_t k, const FixedScale& scale) const;
  // This rank's contact terms that may push a die (particle and point slaves, boundary faces with friction)
  std::size_t terms() const { return mass_.size() + face_mass_.size(); }

  // The dies' surfaces, their triangles numbered over all dies (die k's from triangle0(k)):
  // - this step's loads on them, per triangle the normal force (N, >= 0) and the tangential force
  //   on the die (3 components), each contribution in fixed point (the same on every partition), and
  //   the largest single contribution (the scale's bound);
  // - which triangles the material has touched so far (1), this rank's slaves and faces (checkpointed).
  std::size_t triangle0(std::size_t k) const { return triangle0_[k]; }
  double surface_load_bound() const;
  void surface_loads(const FixedScale& scale, std::vector<Fixed>& out) const;  // 4 per triangle
  const std::vector<std::int64_t>& touched() const { return touched_; }
  std::vector<std::int64_t>& touched() { return touched_; }  // restored from a checkpoint
  // The force of rigid wall w on the part along the wall's normal, this step (totals()[size() + w]).
  double wall_force(std::size_t w) const;
  // How deep this rank's material is past a symmetry plane this step (m), and the local particle
  // there (the slave's, or the point's largest N_J; -1 when none is past), for the health check.
  double symmetry_depth() const;
  std::int32_t deepest_particle(const Model& md) const;

  // The friction's elastic sticks (contact_laws.hpp): the friction force each slave (Coulomb) or
  // boundary face (the shear factor's laws) put on the die it touched at the last step, which the next
  // step loads further. As rows of kStickValues: a slave named by its particle's global id (>= 0) or its
  // point's index g as -(g + 1), with its die k; a face by its index, with its die as -(k + 1); so that
  // they survive a reference update (which renumbers the local particles) and a checkpoint.
  static constexpr std::size_t kStickValues = 5;  // slave, die, force (3)
  std::vector<double> stick_rows() const;
  void set_stick_rows(const std::vector<double>& rows, const std::string& source);

 private:
  struct Row {  // a slave's shape functions (md.material_* or the point's): u^h(x) = sum_k N[k] d_{cols[k]}
    const std::int32_t* cols;
    const double* N;
    std::int32_t size;
  };
  struct Active {
    std::int32_t slave, obstacle;  // slave: particles first, then points; obstacle: dies, then planes
    double normal_force[3], friction_force[3];
    std::int32_t triangle;         // of the die's surface (-1: a plane)
    double stick_stored;           // the energy this step put into its elastic stick (J; what its friction does not dissipate)
    double dashpot;                // the dashpot's share of the normal force (contact_laws.hpp; 0 without)
  };
  Row row(const Model& md, std::size_t s) const;
  DieHit die_hit(std::size_t k, const double x[3], double t) const;  // x's closest point on die k at time t
  void material_point(const Model& md, const State& st, std::size_t s, double x[3]) const;
  void material_value(const Model& md, const std::vector<double>& a, std::size_t s, double out[3]) const;

  std::vector<Die> dies_;
  std::vector<DieSurface> surfaces_;
  std::vector<std::unique_ptr<DieSearch>> search_;
  DieCandidates candidates_;  // the slaves' triangles near them
  struct Plane {          // a fixed frictionless plane: a rigid wall or a symmetry plane
    double point[3], normal[3];  // the normal toward the material
    std::size_t total;           // its entry in totals_
  };
  std::vector<Plane> planes_;  // the rigid walls, then the symmetry planes
  std::size_t walls_ = 0;
  std::int32_t deepest_ = -1;  // this step's slave deepest past a symmetry plane
  std::vector<std::int32_t> particles_;  // the owned particles (slaves 0 .. particles_.size())
  std::vector<std::int64_t> particle_ids_;  // their global ids
  std::vector<double> mass_, N_sum_, N_max_;  // per slave: m, sum_J |N_J|, max_J |N_J|
  // per obstacle and slave: a lower bound on its distance to the obstacle
  std::vector<double> clearance_;
  // the slaves in blocks of kBlock: per block its largest sum_J |N_J|, and per obstacle and block a lower
  // bound on its slaves' clearances and the motion (coefficients', obstacle's) not yet taken off them,
  // so that a block that cannot touch costs one subtraction a step, not one a slave
  static constexpr std::size_t kBlock = 64;
  std::vector<double> block_N_sum_, block_floor_, block_moved_, block_die_moved_;
  std::vector<double> u_last_, stroke_last_;  // at the last compute
  std::vector<Active> active_;        // reserved once: no allocation per step
  struct Stick {  // a slave's friction force on die `obstacle`
    std::int32_t slave, obstacle;
    double force[3];
  };
  // The orders the loops meet the sticks in: the slaves' die by die, the faces' face by face.
  using StickKey = std::pair<std::int32_t, std::int32_t>;
  static StickKey by_die(const Stick& k) { return {k.obstacle, k.slave}; }
  static StickKey by_face(const Stick& k) { return {k.slave, k.obstacle}; }
  // The force of the stick `want` carried from the last step (zero when none), walking `cursor` on
  // through `last`, which is in the order `key` of the loop that asks.
  static const double* carried(const std::vector<Stick>& last, std::size_t& cursor, StickKey want, StickKey (*key)(const Stick&));
  std::vector<Stick> sticks_, last_sticks_;  // this step's and the last's, by_die (reserved once)

  // Shear factor and hybrid friction (dies with shear_factor > 0) on the part's boundary faces of this
  // rank: a face whose centre is within a tenth of its size of such a die (or inside it) slides with
  // the mean velocity of its nodes and takes tau = m k (or min(mu p, m k)) over its area, k and p from
  // its cell's points, through an elastic stick capped at tau A (its stiffness the penalty's on the
  // face's mass: its nodes' masses, each shared among the node's boundary faces); the force is spread
  // equally over its nodes.
  struct FaceFriction {
    std::int32_t face, die;
    double force[3];
    std::int32_t triangle;
    double stick_stored;  // the energy this step put into its elastic stick (J)
  };
  void face_friction(const Model& md, const State& st, double t, double dt, double dt_min, double& largest);
  void face_velocity(const Model& md, const std::vector<double>& v, std::size_t f, double out[3]) const;
  std::vector<double> face_mass_;  // per boundary face: sum over its nodes of m_I / (the node's face count)
  // per boundary face: the largest sum_J |N_J| of its nodes' rows (its centre moves at most that times
  // the largest coefficient's move); per die and face: a lower bound on the centre's distance to the
  // die (its gap at the last lookup, less what both may have moved since): a face farther than its
  // touch distance is not looked up
  std::vector<double> face_N_sum_, face_clearance_;
  double moved_ = 0;                // the largest coefficient move of this step's compute
  std::vector<double> die_moved_;   // per die: its stroke's change in this step's compute
  std::vector<double> die_rate_;    // per die: rate_before in this step's compute (the faces' friction reads it)
  std::vector<FaceFriction> face_active_;  // reserved once
  std::vector<Stick> face_sticks_, last_face_sticks_;  // the faces' elastic sticks (slave: the face), by_face
  bool shear_ = false;                     // a die has shear_factor > 0
  std::vector<DieTotals> totals_;
  std::vector<double> die_box_;  // per die at t = 0: lo[3], hi[3]
  std::vector<double> driven_;   // per die: the stroke and rate a press set (drive)
  std::vector<std::size_t> triangle0_;  // per die: its first triangle's number over all dies, then the count
  std::vector<std::int64_t> touched_;   // per triangle: touched by this rank's material so far (0 / 1)
  double penalty_scale_, damping_, margin_ = 0;
};

}  // namespace rk
