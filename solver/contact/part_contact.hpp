// Contact of the part with itself and between its bodies: a fold's or a lap's faces meeting, two bars
// in impact, a part and its insert. The same treatment as the dies' (contact/die_contact.hpp), on the
// material: the slaves are the owned surface particles' material points x_I = X_I + u^h(X_I), and a
// slave's force f acts on the field there, spread as N_J f onto the coefficients d_J.
// - Two surface particles repel as spheres of diameter d = 0.75 discretization.spacing:
//   f = k_IJ (d - r) e, r = |x_I - x_J|, e = (x_I - x_J) / r. No particle of one surface passes between
//   the particles of the other; the faces stop 0.75 spacing apart (docs/decisions.md, "Contact of the
//   part with itself and between bodies").
// - k_IJ = s mu_IJ / dt_min^2 (contact_laws.hpp's penalty with the pair's reduced mass mu_IJ): the pair's
//   spring is as stiff for its two masses as a die's for one, so contact never shortens the step.
// - Which pairs meet: each particle must lie in front of the other's surface, (x_J - x_I) . n_I > 0
//   and (x_I - x_J) . n_J > 0, and their outward normals must face each other (more than 120 degrees
//   apart): a thin region squeezed to a spacing has material between its faces, and a curved surface's
//   neighbours lie beside each other, not in front. Of one body, the pair must also have been more than
//   one spacing apart at t = 0 (closer particles are neighbours: the continuum holds them).
//   The normal n_I: the mean of the unit outward normals of the part's free boundary faces at I (the
//   faces on a symmetry plane are not free), where the coefficients put them now (rk/surface_faces.hpp),
//   summed over the ranks in fixed point. A particle without a free face is no slave.
// - Parallel: each rank sends its owned surface particles to the ranks whose surface particles' box,
//   grown by d, holds them. Each owner sums its own slave's pairs in the order of the
//   partners' global ids, so the forces are the same bitwise on every partition.
// On with `contact.self` or bodies; otherwise nothing is computed or exchanged.
#pragma once
#include <cstdint>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "model.hpp"
#include "parallel/comm.hpp"
#include "parallel/fixed_point.hpp"
#include "parallel/overlap_exchange.hpp"
#include "scene.hpp"
#include "state.hpp"

namespace rk {

class PartContact {
 public:
  PartContact(const Model& md, const Scene& scene, const Comm& comm);  // collective

  // The pairs' forces at t^n; dt the previous global step, dt_min the smallest so far (contact_laws.hpp).
  // Collective (one exchange of the surface particles near other ranks). Returns the largest force
  // contribution to one coefficient, for the fixed-point bound.
  double compute(const Model& md, const State& st, double dt, double dt_min, const Comm& comm);
  // Adds -N_J f to the fixed-point partials of the slaves' rows (kForceStride per particle, as
  // State::partial; after compute and the bound reduction).
  void add_to(const Model& md, std::vector<Fixed>& partial, const FixedScale& scale) const;
  // After the velocity update: the work of this step's pair forces on the material, into st.part_contact_work.
  void account(const Model& md, State& st, const std::vector<double>& v_old, double dt_avg) const;
  // One term per coefficient of every slave's row (a slave's pairs are summed before they are spread).
  void count_terms(const Model& md, std::vector<Fixed>& terms) const;

  // This step, over this rank's slaves: the slaves in contact, the springs' energy (each pair's half
  // at each of its particles), the deepest d - r.
  std::int64_t contacts() const { return std::int64_t(active_.size()); }
  double spring_energy() const { return spring_energy_; }
  double max_penetration() const { return max_penetration_; }

 private:
  static constexpr int kRecord = 13;  // global id, x[3], n[3], X0[3], h, m, body
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  void normals(const Model& md, const State& st);
  void pack(const Model& md, const State& st);
  void exchange(const Comm& comm);
  void bin();
  // the bin of x shifted by (dx, dy, dz) bins; -1 outside the candidates' box
  std::int64_t key(const double x[3], int dx = 0, int dy = 0, int dz = 0) const;
  double pair_force(std::size_t s, double dt, double dt_min, double f[3]);

  bool on_ = false, self_ = false;
  double penalty_scale_ = 0.25, d_ = 0;  // d: the spheres' diameter
  std::vector<std::int32_t> slaves_;      // owned particles with a free boundary face
  std::vector<std::int32_t> free_faces_;  // the rank's boundary faces off the symmetry planes
  std::vector<Fixed> normal_sum_;         // per local particle, 3: its free faces' unit normals
  std::unique_ptr<OverlapExchange> normal_exchange_;
  std::vector<double> N_max_;             // per slave: max_J |N_J| of its row
  std::vector<double> mine_, candidates_;  // kRecord per particle: this rank's slaves, then what others sent
  std::vector<double> boxes_, send_, received_;
  std::vector<int> send_counts_, recv_counts_;
  std::vector<std::pair<std::int64_t, std::int32_t>> bins_;  // (bin key, candidate), sorted
  double lo_[3]{}, dims_[3]{};
  struct Hit {
    double id, f[3], energy, depth;
  };
  std::vector<Hit> hits_;  // one slave's pairs, sorted by the partner's id before they are summed
  struct Active {
    std::int32_t slave;
    double f[3];
  };
  std::vector<Active> active_;
  double spring_energy_ = 0, max_penetration_ = 0;
};

}  // namespace rk
