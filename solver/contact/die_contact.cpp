#include "contact/die_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact/contact_laws.hpp"
#include "error.hpp"
#include "parallel/overlap_exchange.hpp"
#include "rk/kinematics.hpp"
#include "rk/surface_faces.hpp"
#include "running_extrema.hpp"

namespace rk {

DieContact::DieContact(const Model& md, const Scene& scene, const std::vector<DieSurface>& surfaces, DieContact* previous)
    : dies_(scene.dies), penalty_scale_(scene.penalty_scale_at_cfl()), damping_(scene.contact.damping) {
  for (const RigidWall& w : scene.rigid_walls) {  // its normal points into the part's side
    Plane p{{w.point[0], w.point[1], w.point[2]}, {w.normal[0], w.normal[1], w.normal[2]}, dies_.size() + planes_.size()};
    planes_.push_back(p);
  }
  walls_ = planes_.size();
  for (const SymmetryPlane& s : scene.symmetry_planes) {  // the normal toward this rank's material
    double side = 0;
    for (std::size_t I = 0; I < md.n; ++I)
      for (int i = 0; i < 3; ++i) side += (md.Xr[3 * I + i] - s.point[i]) * s.normal[i];
    const double sign = side < 0 ? -1.0 : 1.0;
    planes_.push_back({{s.point[0], s.point[1], s.point[2]}, {sign * s.normal[0], sign * s.normal[1], sign * s.normal[2]},
                       dies_.size() + walls_});
  }
  if (empty()) return;
  totals_.resize(dies_.size() + walls_ + (planes_.size() > walls_ ? 1 : 0));
  // With nodal integration the points are the particles' material points, with the same rows: they
  // hold the material there, and particle slaves beside them would press it twice.
  const bool nodal = scene.discretization.integration == "nodal";
  double hmax = 0;
  for (std::size_t I = 0; I < md.n; ++I)
    if (md.owned[I]) {
      hmax = std::max(hmax, md.spacing[I]);
      if (!nodal) particles_.push_back(std::int32_t(I)), particle_ids_.push_back(md.global_id[I]);
    }
  // Penetrations stay far below half a spacing (the penalty is stiff); deeper ones would be missed.
  margin_ = 0.5 * hmax;
  // a slave's candidate triangles are gathered again once it has moved a quarter of the margin (die_candidates.hpp);
  // the searches hold their surfaces by reference, so both move over together (a vector's move keeps its elements)
  const std::size_t slaves = particles_.size() + md.m;
  if (previous && previous->margin_ == margin_ && previous->search_.size() == surfaces.size()) {
    surfaces_ = std::move(previous->surfaces_), search_ = std::move(previous->search_);
    // and the slaves' candidate lists where the slaves are the same (a rank keeps its points and owned
    // particles, in the same order): a list holds for any position near its origin, old or new reference
    if (previous->particle_ids_ == particle_ids_ && previous->mass_.size() == slaves)
      candidates_ = std::move(previous->candidates_);
  } else {
    surfaces_ = surfaces;
    for (const auto& s : surfaces_) search_.push_back(std::make_unique<DieSearch>(s, margin_, 0.25 * margin_));
  }
  if (candidates_.slaves() != slaves) candidates_ = DieCandidates(slaves, dies_.size());
  mass_.resize(slaves), N_sum_.assign(slaves, 0.0), N_max_.assign(slaves, 0.0);
  for (std::size_t s = 0; s < slaves; ++s) {
    const std::size_t g = s - particles_.size();  // (a point's, for s past the particles)
    mass_[s] = s < particles_.size() ? md.mass[particles_[s]] : md.material_at(g).density * md.weight[g];
    const Row r = row(md, s);
    for (std::int32_t k = 0; k < r.size; ++k) N_sum_[s] += std::abs(r.N[k]), N_max_[s] = std::max(N_max_[s], std::abs(r.N[k]));
  }
  const std::size_t obstacles = dies_.size() + planes_.size();
  active_.reserve(slaves * obstacles);
  std::size_t coulomb = 0;  // the dies with Coulomb friction at the slaves (compute)
  for (const Die& d : dies_) coulomb += d.friction > 0 && !(d.shear_factor > 0);
  sticks_.reserve(slaves * coulomb), last_sticks_.reserve(slaves * coulomb);
  clearance_.assign(slaves * obstacles, 0.0);  // 0: looked up at the first step
  const std::size_t blocks = (slaves + kBlock - 1) / kBlock;
  block_N_sum_.assign(blocks, 0.0);
  for (std::size_t s = 0; s < slaves; ++s) block_N_sum_[s / kBlock] = std::max(block_N_sum_[s / kBlock], N_sum_[s]);
  block_floor_.assign(blocks * obstacles, 0.0), block_moved_.assign(blocks * obstacles, 0.0);
  block_die_moved_.assign(blocks * obstacles, 0.0);
  // A particle on a symmetry plane (or, with nodal integration, its point) is held on it by the
  // essential BCs, both ways (u . n = 0); a one-sided penalty on it as well would push back the
  // material that crossed and let go of what moved away, a bias away from the plane (docs/decisions.md,
  // "Contact"). It is never looked up for that plane. On the plane: within 1e-9 of the coordinates'
  // scale, their round-off.
  for (std::size_t k = dies_.size() + walls_; k < obstacles; ++k) {
    const Plane& p = planes_[k - dies_.size()];
    const double on = 1e-9 * (std::abs(p.point[0]) + std::abs(p.point[1]) + std::abs(p.point[2]) + hmax);
    for (std::size_t s = 0; s < slaves; ++s) {
      const double* X = s < particles_.size() ? &md.Xr[3 * std::size_t(particles_[s])] : &md.point_X[3 * (s - particles_.size())];
      double gap = 0;
      for (int i = 0; i < 3; ++i) gap += (X[i] - p.point[i]) * p.normal[i];
      if (std::abs(gap) <= on) clearance_[k * slaves + s] = std::numeric_limits<double>::infinity();
    }
  }
  stroke_last_.assign(dies_.size(), 0.0);
  for (const Die& d : dies_) shear_ = shear_ || d.shear_factor > 0;
  if (shear_) {  // the boundary faces' masses for the stick force: each node's shared among its faces
    const std::size_t faces = md.surface_face_offsets.size() - 1;
    std::vector<Fixed> count(md.n, 0);  // over all ranks: the same on every partition
    for (auto node : md.surface_face_nodes) ++count[std::size_t(node)];
    OverlapExchange(md, 1).sum(count);
    face_mass_.assign(faces, 0.0);
    for (std::size_t f = 0; f < faces; ++f)
      for (auto k = md.surface_face_offsets[f]; k < md.surface_face_offsets[f + 1]; ++k) {
        const auto I = std::size_t(md.surface_face_nodes[std::size_t(k)]);
        face_mass_[f] += md.mass[I] / double(count[I]);
      }
    face_active_.reserve(faces);
    face_sticks_.reserve(faces), last_face_sticks_.reserve(faces);
    face_N_sum_.assign(faces, 0.0);
    for (std::size_t f = 0; f < faces; ++f)
      for (auto k = md.surface_face_offsets[f]; k < md.surface_face_offsets[f + 1]; ++k) {
        const auto I = std::size_t(md.surface_face_nodes[std::size_t(k)]);
        double sum = 0;
        for (auto j = md.material_offsets[I]; j < md.material_offsets[I + 1]; ++j) sum += std::abs(md.material_N[std::size_t(j)]);
        face_N_sum_[f] = std::max(face_N_sum_[f], sum);
      }
    face_clearance_.assign(faces * dies_.size(), 0.0);  // 0: looked up at the first step
  }
  die_moved_.assign(dies_.size(), 0.0);
  die_rate_.assign(dies_.size(), 0.0);
  driven_.assign(2 * dies_.size(), 0.0);
  triangle0_.assign(1, 0);
  for (const auto& sf : surfaces_) triangle0_.push_back(triangle0_.back() + sf.triangle_count());
  touched_.assign(triangle0_.back(), 0);
  for (const auto& sf : surfaces_) {
    double b[6] = {1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
    for (std::size_t v = 0; v < sf.vertices.size() / 3; ++v)
      for (int d = 0; d < 3; ++d) b[d] = std::min(b[d], sf.vertices[3 * v + d]), b[3 + d] = std::max(b[3 + d], sf.vertices[3 * v + d]);
    die_box_.insert(die_box_.end(), b, b + 6);
  }
}

DieContact::Row DieContact::row(const Model& md, std::size_t s) const {
  if (s < particles_.size()) {
    const auto I = std::size_t(particles_[s]);
    const auto k0 = md.material_offsets[I];
    return {&md.material_cols[std::size_t(k0)], &md.material_N[std::size_t(k0)], md.material_offsets[I + 1] - k0};
  }
  const std::size_t g = s - particles_.size();
  return {&md.nbr[std::size_t(md.nbr_offsets[g])], &md.N[std::size_t(md.nbr_offsets[g])],
          std::int32_t(md.nbr_offsets[g + 1] - md.nbr_offsets[g])};  // one point's neighbours
}

void DieContact::material_point(const Model& md, const State& st, std::size_t s, double x[3]) const {
  if (s < particles_.size()) material_position(md, st, std::size_t(particles_[s]), x);
  else point_position(md, st, s - particles_.size(), x);
}

void DieContact::material_value(const Model& md, const std::vector<double>& a, std::size_t s, double out[3]) const {
  const Row r = row(md, s);
  out[0] = out[1] = out[2] = 0;
  for (std::int32_t k = 0; k < r.size; ++k)
    for (int i = 0; i < 3; ++i) out[i] += r.N[k] * a[3 * std::size_t(r.cols[k]) + i];
}

std::vector<double> DieContact::stick_rows() const {
  std::vector<double> rows;
  for (const Stick& k : sticks_) {
    const auto s = std::size_t(k.slave);
    const double slave = s < particles_.size() ? double(particle_ids_[s]) : -double(s - particles_.size() + 1);
    rows.insert(rows.end(), {slave, double(k.obstacle), k.force[0], k.force[1], k.force[2]});
  }
  for (const Stick& k : face_sticks_)  // a face's: its index, its die as -(k + 1)
    rows.insert(rows.end(), {double(k.slave), -double(k.obstacle + 1), k.force[0], k.force[1], k.force[2]});
  return rows;
}

void DieContact::set_stick_rows(const std::vector<double>& rows, const std::string& source) {
  std::vector<std::pair<std::int64_t, std::int32_t>> by_id;  // owned particle's global id -> its slave
  for (std::size_t s = 0; s < particles_.size(); ++s) by_id.emplace_back(particle_ids_[s], std::int32_t(s));
  std::sort(by_id.begin(), by_id.end());
  sticks_.clear(), face_sticks_.clear();
  for (std::size_t r = 0; r + kStickValues <= rows.size(); r += kStickValues) {
    const double key = rows[r], die = rows[r + 1];
    if (die < 0) {  // a boundary face's, on die -die - 1
      if (!(key >= 0 && key < double(face_mass_.size()) && -die - 1 < double(dies_.size()) && dies_[std::size_t(-die - 1)].shear_factor > 0))
        throw Error(source + ": a friction stick names boundary face " + std::to_string(std::int64_t(key)) + " on die " +
                    std::to_string(std::int64_t(-die - 1)) + ", which this rank's contact does not hold");
      face_sticks_.push_back({std::int32_t(key), std::int32_t(-die - 1), {rows[r + 2], rows[r + 3], rows[r + 4]}});
      continue;
    }
    std::int64_t slave = -1;
    if (key >= 0) {
      const auto it = std::lower_bound(by_id.begin(), by_id.end(), std::make_pair(std::int64_t(key), std::int32_t(-1)));
      if (it != by_id.end() && it->first == std::int64_t(key)) slave = it->second;
    } else if (-key - 1 < double(mass_.size() - particles_.size())) {  // a point's
      slave = std::int64_t(particles_.size()) + std::int64_t(-key - 1);
    }
    if (slave < 0 || !(die >= 0 && die < double(dies_.size())))
      throw Error(source + ": a friction stick names " + (key >= 0 ? "particle " : "point ") +
                  std::to_string(std::int64_t(key >= 0 ? key : -key - 1)) + " on die " + std::to_string(std::int64_t(die)) +
                  ", which this rank's contact does not hold");
    sticks_.push_back({std::int32_t(slave), std::int32_t(die), {rows[r + 2], rows[r + 3], rows[r + 4]}});
  }
  std::sort(sticks_.begin(), sticks_.end(), [](const Stick& a, const Stick& b) { return by_die(a) < by_die(b); });
  std::sort(face_sticks_.begin(), face_sticks_.end(), [](const Stick& a, const Stick& b) { return by_face(a) < by_face(b); });
}

const double* DieContact::carried(const std::vector<Stick>& last, std::size_t& cursor, StickKey want, StickKey (*key)(const Stick&)) {
  static constexpr double kNone[3] = {0, 0, 0};
  while (cursor < last.size() && key(last[cursor]) < want) ++cursor;
  return cursor < last.size() && key(last[cursor]) == want ? last[cursor].force : kNone;
}

double DieContact::compute(const Model& md, const State& st, double t, double dt, double dt_min) {
  active_.clear();
  sticks_.swap(last_sticks_);  // the last step's sticks, in (obstacle, slave) order as the loops below meet them
  sticks_.clear();
  if (empty()) return 0;
  // How far any local coefficient moved since the last call: a slave moved at most sum_J |N_J| times that.
  double moved = 0;
  if (u_last_.size() == st.u.size()) {
    moved = std::sqrt(largest_of(md.n, 0.0, [&](std::size_t I) {
      double d2 = 0;
      for (int i = 0; i < 3; ++i) d2 += (st.u[3 * I + i] - u_last_[3 * I + i]) * (st.u[3 * I + i] - u_last_[3 * I + i]);
      return d2;
    }));
  }
  u_last_ = st.u;  // sized at the first call
  moved_ = moved;
  deepest_ = -1;
  const std::size_t slaves = particles_.size() + md.m;
  double largest = 0;
  for (auto& tot : totals_) {
    tot.force[0] = tot.force[1] = tot.force[2] = 0;
    tot.max_penetration = 0;
    tot.spring_energy = 0;
    tot.contacts = tot.point_contacts = 0;
  }
  std::size_t held = 0;  // the first of the last step's sticks not before the slave in hand (by_die)
  for (std::size_t k = 0; k < dies_.size() + planes_.size(); ++k) {
    const bool die = k < dies_.size();
    const DieMotion* mo = die ? &dies_[k].motion : nullptr;
    const double stroke = die ? this->stroke(k, t) : 0.0, rate = die ? rate_before(k, t, st.dt_half) : 0.0;
    const double die_moved = die ? std::abs(stroke - stroke_last_[k]) : 0.0;
    if (die) stroke_last_[k] = stroke, die_moved_[k] = die_moved, die_rate_[k] = rate;
    // Coulomb at the slaves; with a shear factor the faces take the friction (face_friction)
    const double mu = die && !(dies_[k].shear_factor > 0) ? dies_[k].friction : 0.0;
    const double margin = margin_;
    // a clearance under 1e-6 of the margin is the bound's round-off: the slave is looked up
    const double clear = 1e-6 * margin;  // only a slave at least this far out is skipped
    DieTotals& tot = totals_[die ? k : planes_[k - dies_.size()].total];
    // The obstacle's closest point to x (current), in its own frame.
    auto nearest = [&](std::size_t s, const double* x) {
      if (die) {
        double y[3];
        for (int i = 0; i < 3; ++i) y[i] = x[i] - stroke * mo->direction[i];
        return candidates_.nearest(*search_[k], k, s, y);
      }
      const Plane& p = planes_[k - dies_.size()];
      DieHit hit{true, 0, {p.normal[0], p.normal[1], p.normal[2]}, -1};
      for (int i = 0; i < 3; ++i) hit.gap += (x[i] - p.point[i]) * p.normal[i];
      return hit;
    };
    // each slave's clearance less the most it and the obstacle can have moved; a slave is skipped while
    // it cannot have reached the obstacle, and a block of slaves while none of them can (its floor): its
    // motion is then kept for it and taken off its slaves when it is next looked into
    double* clearance = &clearance_[k * slaves];
    const double* N_sum = N_sum_.data();
    const std::size_t blocks = block_N_sum_.size();
    for (std::size_t b = 0; b < blocks; ++b) {
      double& block_floor = block_floor_[k * blocks + b];
      double& pending = block_moved_[k * blocks + b];
      double& pending_die = block_die_moved_[k * blocks + b];
      pending += moved, pending_die += die_moved;
      block_floor -= block_N_sum_[b] * moved + die_moved;
      if (block_floor > clear) continue;
      const std::size_t s0 = b * kBlock, s1 = std::min(slaves, s0 + kBlock);
      for (std::size_t s = s0; s < s1; ++s) clearance[s] -= N_sum[s] * pending + pending_die;
      pending = pending_die = 0;
      for (std::size_t s = s0; s < s1; ++s) {
        double& c = clearance[s];
        if (c > clear) continue;
        double x[3];
        material_point(md, st, s, x);
        const DieHit hit = nearest(s, x);
        c = hit.found ? std::max(hit.gap, 0.0) : margin;
        if (!hit.found || hit.gap >= 0) continue;
        const double depth = -hit.gap, m = mass_[s];
        const double kI = penalty_stiffness(penalty_scale_, m, dt_min, dt);
        Active a{std::int32_t(s), std::int32_t(k), {}, {}, die ? hit.triangle : -1, 0.0, 0.0};
        if (die) touched_[triangle0_[k] + std::size_t(hit.triangle)] = 1;
        double v_rel[3], vt[3];  // the material's velocity relative to the obstacle
        material_value(md, st.v, s, v_rel);
        if (die)
          for (int i = 0; i < 3; ++i) v_rel[i] -= rate * mo->direction[i];
        tangential_velocity(v_rel, hit.normal, vt);
        const double vn = v_rel[0] * hit.normal[0] + v_rel[1] * hit.normal[1] + v_rel[2] * hit.normal[2];
        const double fn = penalty_force(kI, depth, penalty_damping(damping_, penalty_scale_, m, dt_min, dt), vn, hit.normal,
                                        a.normal_force);
        a.dashpot = fn > 0 ? 1 - kI * depth / fn : 0.0;
        if (mu > 0) {  // the elastic stick carried from the last step, loaded by this step's slip
          const double* f_old = carried(last_sticks_, held, {std::int32_t(k), std::int32_t(s)}, by_die);
          coulomb_friction(mu, kI * depth, kI, f_old, hit.normal, vt, dt, a.friction_force);
          const double stored = stick_energy(a.friction_force, kI);
          a.stick_stored = stored - stick_energy(f_old, kI);
          tot.spring_energy += stored;
          sticks_.push_back({std::int32_t(s), std::int32_t(k), {a.friction_force[0], a.friction_force[1], a.friction_force[2]}});
        }
        for (int i = 0; i < 3; ++i) {
          tot.force[i] += a.normal_force[i] + a.friction_force[i];
          largest = std::max(largest, N_max_[s] * std::abs(a.normal_force[i] + a.friction_force[i]));
        }
        if (depth > tot.max_penetration && !die && k - dies_.size() >= walls_) deepest_ = std::int32_t(s);
        tot.max_penetration = std::max(tot.max_penetration, depth);
        tot.spring_energy += 0.5 * kI * depth * depth;
        (s < particles_.size() ? tot.contacts : tot.point_contacts) += 1;
        active_.push_back(a);
      }
      const double* block = clearance + s0;  // its new floor
      block_floor = least_of(s1 - s0, std::numeric_limits<double>::infinity(), [&](std::size_t j) { return block[j]; });
    }
  }
  if (shear_) face_friction(md, st, t, dt, dt_min, largest);
  return largest;
}

void DieContact::face_velocity(const Model& md, const std::vector<double>& v, std::size_t f, double out[3]) const {
  const auto k0 = md.surface_face_offsets[f], n = md.surface_face_offsets[f + 1] - k0;
  out[0] = out[1] = out[2] = 0;
  for (auto k = k0; k < k0 + n; ++k)
    for (int i = 0; i < 3; ++i) out[i] += v[3 * std::size_t(md.surface_face_nodes[std::size_t(k)]) + i] / n;
}

void DieContact::face_friction(const Model& md, const State& st, double t, double dt, double dt_min, double& largest) {
  face_active_.clear();
  face_sticks_.swap(last_face_sticks_);  // the last step's, in face order as the loop below meets them
  face_sticks_.clear();
  std::size_t held = 0;                  // the first of them not before this face
  const std::size_t faces = face_mass_.size();
  for (std::size_t f = 0; f < faces; ++f) {
    const int n = md.surface_face_offsets[f + 1] - md.surface_face_offsets[f];
    double centre[3];
    const double area = surface_face(md, st, f, centre);
    for (std::size_t k = 0; k < dies_.size(); ++k) {
      const Die& die = dies_[k];
      if (!(die.shear_factor > 0)) continue;
      const double rate = die_rate_[k], touch = kFaceTouch * std::sqrt(area);
      double& clear = face_clearance_[k * faces + f];
      clear -= face_N_sum_[f] * moved_ + die_moved_[k];
      if (clear > touch) continue;  // still farther than its touch distance: no lookup
      const DieHit hit = die_hit(k, centre, t);
      clear = hit.found ? std::max(hit.gap, 0.0) : margin_;
      if (!hit.found || hit.gap >= touch) continue;
      // the flow stress and the pressure on the face of its cell's points (Cauchy stress tau / J)
      const auto c = std::size_t(md.surface_face_cell[f]);
      const auto g0 = std::size_t(md.cell_points[c]), g1 = std::size_t(md.cell_points[c + 1]);
      double flow = 0, pressure = 0;
      for (auto g = g0; g < g1; ++g) {
        const double rate_g = st.plastic_rate.empty() ? 0.0 : st.plastic_rate[g];
        const double y_g = md.material_at(g).law.flow_stress(st.ep[g], rate_g, st.temperature.empty() ? 0.0 : st.temperature[g]);
        const double* tau = &st.tau[6 * g];
        const double* nn = hit.normal;
        const double tnn = tau[0] * nn[0] * nn[0] + tau[1] * nn[1] * nn[1] + tau[2] * nn[2] * nn[2] +
                           2 * (tau[3] * nn[0] * nn[1] + tau[4] * nn[1] * nn[2] + tau[5] * nn[2] * nn[0]);
        flow += y_g / double(g1 - g0);
        pressure -= tnn / st.total_J(g) / double(g1 - g0);
      }
      const double tau = die.friction > 0 ? hybrid_friction_stress(die.friction, pressure, die.shear_factor, flow)
                                           : shear_factor_stress(die.shear_factor, flow);
      double v_rel[3], vt[3];
      face_velocity(md, st.v, f, v_rel);
      for (int i = 0; i < 3; ++i) v_rel[i] -= rate * die.motion.direction[i];
      tangential_velocity(v_rel, hit.normal, vt);
      FaceFriction ff{std::int32_t(f), std::int32_t(k), {}, hit.triangle, 0.0};
      touched_[triangle0_[k] + std::size_t(hit.triangle)] = 1;
      // the elastic stick carried from the last step on this die (a face meets one die at a time)
      const double* f_old = carried(last_face_sticks_, held, {std::int32_t(f), std::int32_t(k)}, by_face);
      const double kI = penalty_stiffness(penalty_scale_, face_mass_[f], dt_min, dt);
      interface_friction(tau, area, kI, f_old, hit.normal, vt, dt, ff.force);
      const double stored = stick_energy(ff.force, kI);
      ff.stick_stored = stored - stick_energy(f_old, kI);
      face_sticks_.push_back({std::int32_t(f), std::int32_t(k), {ff.force[0], ff.force[1], ff.force[2]}});
      DieTotals& tot = totals_[k];
      tot.spring_energy += stored;
      for (int i = 0; i < 3; ++i) {
        tot.force[i] += ff.force[i];
        largest = std::max(largest, std::abs(ff.force[i]) / n);
      }
      face_active_.push_back(ff);
      break;  // one die a face
    }
  }
}

DieHit DieContact::die_hit(std::size_t k, const double x[3], double t) const {
  const double stroke = this->stroke(k, t);
  double y[3];  // in the die's own frame
  for (int i = 0; i < 3; ++i) y[i] = x[i] - stroke * dies_[k].motion.direction[i];
  return search_[k]->nearest(y);
}

int DieContact::touching(const double x[3], double t, double tolerance) const {
  for (std::size_t k = 0; k < dies_.size(); ++k) {
    const DieHit hit = die_hit(k, x, t);
    if (hit.found && hit.gap < tolerance) return int(k);
  }
  for (const Plane& p : planes_) {
    double gap = 0;
    for (int i = 0; i < 3; ++i) gap += (x[i] - p.point[i]) * p.normal[i];
    if (gap < tolerance) return -2;
  }
  return -1;
}

double DieContact::reaction_bound(std::size_t k) const {
  const double* d = dies_[k].motion.direction.data();
  double largest = 0;
  for (const auto& a : active_)
    if (std::size_t(a.obstacle) == k)
      largest = std::max(largest, std::abs((a.normal_force[0] + a.friction_force[0]) * d[0] + (a.normal_force[1] + a.friction_force[1]) * d[1] +
                                           (a.normal_force[2] + a.friction_force[2]) * d[2]));
  for (const auto& ff : face_active_)
    if (std::size_t(ff.die) == k) largest = std::max(largest, std::abs(ff.force[0] * d[0] + ff.force[1] * d[1] + ff.force[2] * d[2]));
  return largest;
}

Fixed DieContact::reaction(std::size_t k, const FixedScale& scale) const {
  const double* d = dies_[k].motion.direction.data();
  Fixed sum = 0;
  for (const auto& a : active_)
    if (std::size_t(a.obstacle) == k)
      sum += scale.fixed((a.normal_force[0] + a.friction_force[0]) * d[0] + (a.normal_force[1] + a.friction_force[1]) * d[1] +
                         (a.normal_force[2] + a.friction_force[2]) * d[2]);
  for (const auto& ff : face_active_)
    if (std::size_t(ff.die) == k) sum += scale.fixed(ff.force[0] * d[0] + ff.force[1] * d[1] + ff.force[2] * d[2]);
  return sum;
}

double DieContact::surface_load_bound() const {
  double largest = 0;
  for (const auto& a : active_)
    if (a.triangle >= 0)
      for (int i = 0; i < 3; ++i) largest = std::max({largest, std::abs(a.normal_force[i]), std::abs(a.friction_force[i])});
  for (const auto& ff : face_active_)
    for (int i = 0; i < 3; ++i) largest = std::max(largest, std::abs(ff.force[i]));
  return 2 * largest;  // the normal force's magnitude is at most sqrt 3 of its largest component
}

void DieContact::surface_loads(const FixedScale& scale, std::vector<Fixed>& out) const {
  out.assign(4 * triangle0_.back(), 0);
  for (const auto& a : active_) {
    if (a.triangle < 0) continue;
    Fixed* t = &out[4 * (triangle0_[std::size_t(a.obstacle)] + std::size_t(a.triangle))];
    const double* f = a.normal_force;
    t[0] += scale.fixed(std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]));
    for (int i = 0; i < 3; ++i) t[1 + i] -= scale.fixed(a.friction_force[i]);  // on the die
  }
  for (const auto& ff : face_active_) {  // a face's friction: tangential (the faces carry no normal force)
    Fixed* t = &out[4 * (triangle0_[std::size_t(ff.die)] + std::size_t(ff.triangle))];
    for (int i = 0; i < 3; ++i) t[1 + i] -= scale.fixed(ff.force[i]);
  }
}

void DieContact::count_terms(const Model& md, std::vector<Fixed>& terms) const {
  if (empty()) return;
  const auto obstacles = Fixed(dies_.size() + planes_.size());
  for (std::size_t s = 0; s < particles_.size() + md.m; ++s) {
    const Row r = row(md, s);
    for (std::int32_t k = 0; k < r.size; ++k) terms[std::size_t(r.cols[k])] += obstacles;
  }
  if (shear_)
    for (auto node : md.surface_face_nodes) ++terms[std::size_t(node)];
}

double DieContact::symmetry_depth() const { return planes_.size() > walls_ ? totals_.back().max_penetration : 0.0; }

std::int32_t DieContact::deepest_particle(const Model& md) const {
  if (deepest_ < 0) return -1;
  if (std::size_t(deepest_) < particles_.size()) return particles_[std::size_t(deepest_)];
  const std::size_t g = std::size_t(deepest_) - particles_.size();  // a point: its strongest particle
  std::int32_t best = md.nbr[std::size_t(md.nbr_offsets[g])];
  double most = -1;
  for (auto k = md.nbr_offsets[g]; k < md.nbr_offsets[g + 1]; ++k)
    if (md.N[std::size_t(k)] > most) most = md.N[std::size_t(k)], best = md.nbr[std::size_t(k)];
  return best;
}

double DieContact::wall_force(std::size_t w) const {
  const Plane& p = planes_[w];
  const double* f = totals_[p.total].force;
  return f[0] * p.normal[0] + f[1] * p.normal[1] + f[2] * p.normal[2];
}

void DieContact::box(const double part_lo[3], const double part_hi[3], double t, double lo[3], double hi[3]) const {
  for (int d = 0; d < 3; ++d) lo[d] = part_lo[d], hi[d] = part_hi[d];
  for (std::size_t k = 0; k < dies_.size(); ++k) {
    const double shift = stroke(k, t);
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], die_box_[6 * k + d] + shift * dies_[k].motion.direction[d]);
      hi[d] = std::max(hi[d], die_box_[6 * k + 3 + d] + shift * dies_[k].motion.direction[d]);
    }
  }
  const double grow = 0.25 * std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  for (int d = 0; d < 3; ++d) lo[d] -= grow, hi[d] += grow;
}

void DieContact::add_to(const Model& md, std::vector<Fixed>& partial, const FixedScale& scale) const {
  for (const auto& a : active_) {  // f acts on the field at the slave: N_J f on d_J
    const Row r = row(md, std::size_t(a.slave));
    for (std::int32_t k = 0; k < r.size; ++k)
      for (int i = 0; i < 3; ++i)
        partial[kForceStride * std::size_t(r.cols[k]) + i] -= scale.fixed(r.N[k] * (a.normal_force[i] + a.friction_force[i]));
  }
  for (const auto& ff : face_active_) {  // a face's friction, equally on its nodes' coefficients
    const auto k0 = md.surface_face_offsets[std::size_t(ff.face)], k1 = md.surface_face_offsets[std::size_t(ff.face) + 1];
    for (auto k = k0; k < k1; ++k)
      for (int i = 0; i < 3; ++i)
        partial[kForceStride * std::size_t(md.surface_face_nodes[std::size_t(k)]) + i] -= scale.fixed(ff.force[i] / double(k1 - k0));
  }
}

void DieContact::account(const Model& md, State& st, const std::vector<double>& v_old, double dt_avg, double t) {
  const bool conducting = !st.surface_heat.empty();
  for (const auto& a : active_) {
    const bool die = std::size_t(a.obstacle) < dies_.size();
    const double rate = die ? this->rate(std::size_t(a.obstacle), t) : 0.0;
    const double* direction = die ? dies_[a.obstacle].motion.direction.data() : nullptr;
    DieTotals& tot = totals_[die ? std::size_t(a.obstacle) : planes_[std::size_t(a.obstacle) - dies_.size()].total];
    double before[3], after[3];
    material_value(md, v_old, std::size_t(a.slave), before);
    material_value(md, st.v, std::size_t(a.slave), after);
    double friction = 0;  // the heat friction and the penalty's dashpot made this step (J)
    for (int i = 0; i < 3; ++i) {
      const double vbar = 0.5 * (before[i] + after[i]), die_v = die ? rate * direction[i] : 0.0;
      const double f = a.normal_force[i] + a.friction_force[i];
      tot.contact_work += dt_avg * f * vbar;
      tot.press_work += dt_avg * f * die_v;
      friction -= dt_avg * (a.friction_force[i] + a.dashpot * a.normal_force[i]) * (vbar - die_v);
    }
    friction -= a.stick_stored;  // what the elastic stick stores is not dissipated
    tot.friction_work += friction;
    if (!conducting || !die || friction == 0) continue;
    const double to_die = dies_[std::size_t(a.obstacle)].friction_heat_share * friction;
    tot.heat += to_die;
    if (std::size_t(a.slave) < particles_.size()) {
      st.surface_heat[std::size_t(particles_[std::size_t(a.slave)])] += friction - to_die;
    } else {
      const std::size_t g = std::size_t(a.slave) - particles_.size();
      const double rise = (friction - to_die) / (md.capacity_at(st.temperature[g]) * md.weight[g]);
      st.temperature[g] += rise, st.heat_pending[g] += rise;
    }
  }
  for (const auto& ff : face_active_) {  // the faces' friction: its heat into the face's cell's points
    const Die& die = dies_[std::size_t(ff.die)];
    double before[3], after[3], friction = 0;
    face_velocity(md, v_old, std::size_t(ff.face), before);
    face_velocity(md, st.v, std::size_t(ff.face), after);
    for (int i = 0; i < 3; ++i) {
      const double vbar = 0.5 * (before[i] + after[i]), die_v = rate(std::size_t(ff.die), t) * die.motion.direction[i];
      totals_[std::size_t(ff.die)].contact_work += dt_avg * ff.force[i] * vbar;
      totals_[std::size_t(ff.die)].press_work += dt_avg * ff.force[i] * die_v;
      friction -= dt_avg * ff.force[i] * (vbar - die_v);
    }
    friction -= ff.stick_stored;  // what the elastic stick stores is not dissipated
    DieTotals& tot = totals_[std::size_t(ff.die)];
    tot.friction_work += friction;
    if (!conducting || friction == 0) continue;
    const double to_die = die.friction_heat_share * friction;
    tot.heat += to_die;
    const auto c = std::size_t(md.surface_face_cell[std::size_t(ff.face)]);
    double volume = 0;
    for (auto g = md.cell_points[c]; g < md.cell_points[c + 1]; ++g) volume += md.weight[std::size_t(g)];
    const double per_volume = (friction - to_die) / volume;
    for (auto g = md.cell_points[c]; g < md.cell_points[c + 1]; ++g) {
      const double rise = per_volume / md.capacity_at(st.temperature[std::size_t(g)]);
      st.temperature[std::size_t(g)] += rise, st.heat_pending[std::size_t(g)] += rise;
    }
  }
}

}  // namespace rk
