#include "contact/die_contact.hpp"

#include "kinematics.hpp"

#include <algorithm>
#include <cmath>

namespace rk {

DieContact::DieContact(const Model& md, const Scene& scene, const std::vector<DieSurface>& surfaces)
    : dies_(scene.dies), surfaces_(surfaces), totals_(scene.dies.size()), penalty_scale_(scene.contact.penalty_scale) {
  double hmax = 0;
  for (std::size_t I = 0; I < md.n; ++I)
    if (md.owned[I]) slaves_.push_back(std::int32_t(I)), hmax = std::max(hmax, md.spacing[I]);
  // Penetrations stay far below half a spacing (the penalty is stiff); deeper ones would be missed.
  for (const auto& s : surfaces_) search_.push_back(std::make_unique<DieSearch>(s, 0.5 * hmax));
  active_.reserve((slaves_.size() + md.m) * std::max<std::size_t>(1, dies_.size()));
  clearance_.assign((slaves_.size() + md.m) * dies_.size(), 0.0);  // 0: looked up at the first step
  stroke_last_.assign(dies_.size(), 0.0);
  point_N_max_.assign(md.m, 0.0);
  point_N_sum_.assign(md.m, 0.0);
  for (std::size_t g = 0; g < md.m; ++g)
    for (auto k = md.nbr_offsets[g]; k < md.nbr_offsets[g + 1]; ++k) {
      point_N_max_[g] = std::max(point_N_max_[g], std::abs(md.N[k]));
      point_N_sum_[g] += std::abs(md.N[k]);
    }
  for (const auto& sf : surfaces_) {
    double b[6] = {1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
    for (std::size_t v = 0; v < sf.vertices.size() / 3; ++v)
      for (int d = 0; d < 3; ++d) b[d] = std::min(b[d], sf.vertices[3 * v + d]), b[3 + d] = std::max(b[3 + d], sf.vertices[3 * v + d]);
    die_box_.insert(die_box_.end(), b, b + 6);
  }
}

double DieContact::compute(const Model& md, const State& st, double t, double dt) {
  active_.clear();
  if (dies_.empty()) return 0;
  // How far any local coefficient moved since the last call: a particle moved at most that, a point
  // at most sum_J |N_J(X_g)| times that.
  double moved = 0;
  if (u_last_.size() == st.u.size()) {
    double worst = 0;
    for (std::size_t I = 0; I < md.n; ++I) {
      double d2 = 0;
      for (int i = 0; i < 3; ++i) d2 += (st.u[3 * I + i] - u_last_[3 * I + i]) * (st.u[3 * I + i] - u_last_[3 * I + i]);
      worst = std::max(worst, d2);
    }
    moved = std::sqrt(worst);
  }
  u_last_ = st.u;  // sized at the first call
  const std::size_t slots = slaves_.size() + md.m;
  double largest = 0;
  for (std::size_t k = 0; k < dies_.size(); ++k) {
    const DieMotion& mo = dies_[k].motion;
    const double stroke = mo.stroke(t), rate = mo.rate(t), die_moved = std::abs(stroke - stroke_last_[k]);
    stroke_last_[k] = stroke;
    const double clear = 1e-6 * search_[k]->margin();  // only a slave at least this far out is skipped
    DieTotals& tot = totals_[k];
    tot.force[0] = tot.force[1] = tot.force[2] = 0;
    tot.max_penetration = 0;
    tot.spring_energy = 0;
    tot.contacts = tot.point_contacts = 0;
    // Slave `slot` at x (current) of mass m: its forces, if it is inside the die. velocity(v) gives
    // its velocity; share bounds the part of the force one column receives.
    auto engage = [&](std::size_t slot, const double* x, double m, auto velocity, std::int32_t slave, bool point,
                      double share) {
      double y[3];
      for (int i = 0; i < 3; ++i) y[i] = x[i] - stroke * mo.direction[i];
      const DieHit hit = search_[k]->nearest(y);
      clearance_[k * slots + slot] = hit.found ? std::max(hit.gap, 0.0) : search_[k]->margin();
      if (!hit.found || hit.gap >= 0) return false;
      const double depth = -hit.gap;
      const double kI = penalty_scale_ * m / (dt * dt);
      Active a{slave, std::int32_t(k), point, {}, {}};
      double vt[3], vn = 0;
      velocity(vt);
      for (int i = 0; i < 3; ++i) {
        a.normal_force[i] = kI * depth * hit.normal[i];
        vt[i] -= rate * mo.direction[i];
        vn += vt[i] * hit.normal[i];
      }
      for (int i = 0; i < 3; ++i) vt[i] -= vn * hit.normal[i];
      const double fn = kI * depth, vt_norm = std::sqrt(vt[0] * vt[0] + vt[1] * vt[1] + vt[2] * vt[2]);
      const double mu = dies_[k].friction;
      if (mu > 0 && vt_norm > 0) {
        const double stick = (point ? 0.5 : 1.0) * m * vt_norm / dt;  // stops (half) the sliding in one step
        const double f = std::min(stick, mu * fn);
        for (int i = 0; i < 3; ++i) a.friction_force[i] = -f * vt[i] / vt_norm;
      }
      for (int i = 0; i < 3; ++i) {
        tot.force[i] += a.normal_force[i] + a.friction_force[i];
        largest = std::max(largest, share * std::abs(a.normal_force[i] + a.friction_force[i]));
      }
      tot.max_penetration = std::max(tot.max_penetration, depth);
      tot.spring_energy += 0.5 * kI * depth * depth;
      active_.push_back(a);
      return true;
    };
    // Skipped while it cannot have reached the die since its last lookup.
    auto clear_of_die = [&](std::size_t slot, double reach) {
      double& c = clearance_[k * slots + slot];
      c -= reach + die_moved;
      return c > clear;
    };
    for (std::size_t s = 0; s < slaves_.size(); ++s) {
      if (clear_of_die(s, moved)) continue;
      const std::size_t I = std::size_t(slaves_[s]);
      double x[3];
      for (int i = 0; i < 3; ++i) x[i] = md.X[3 * I + i] + st.u[3 * I + i];
      const auto velocity = [&](double* v) { for (int i = 0; i < 3; ++i) v[i] = st.v[3 * I + i]; };
      tot.contacts += engage(s, x, md.mass[I], velocity, std::int32_t(I), false, 1.0);
    }
    for (std::size_t g = 0; g < md.m; ++g) {
      if (clear_of_die(slaves_.size() + g, point_N_sum_[g] * moved)) continue;
      double x[3];
      point_position(md, st, g, x);
      const auto velocity = [&](double* v) { field_value(md, st.v, g, v); };
      tot.point_contacts += engage(slaves_.size() + g, x, md.density * md.weight[g], velocity, std::int32_t(g), true, point_N_max_[g]);
    }
  }
  return largest;
}

void DieContact::field_value(const Model& md, const std::vector<double>& a, std::size_t g, double out[3]) {
  out[0] = out[1] = out[2] = 0;
  for (auto k = md.nbr_offsets[g]; k < md.nbr_offsets[g + 1]; ++k)
    for (int i = 0; i < 3; ++i) out[i] += md.N[k] * a[3 * std::size_t(md.nbr[k]) + i];
}

void DieContact::push_out(double t, double* x) const {
  for (std::size_t k = 0; k < dies_.size(); ++k) {
    const DieMotion& mo = dies_[k].motion;
    double y[3];
    for (int i = 0; i < 3; ++i) y[i] = x[i] - mo.stroke(t) * mo.direction[i];
    const DieHit hit = search_[k]->nearest(y);
    if (hit.found && hit.gap < 0)
      for (int i = 0; i < 3; ++i) x[i] -= hit.gap * hit.normal[i];
  }
}

void DieContact::box(const double part_lo[3], const double part_hi[3], double t, double lo[3], double hi[3]) const {
  for (int d = 0; d < 3; ++d) lo[d] = part_lo[d], hi[d] = part_hi[d];
  for (std::size_t k = 0; k < dies_.size(); ++k) {
    const double shift = dies_[k].motion.stroke(t);
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], die_box_[6 * k + d] + shift * dies_[k].motion.direction[d]);
      hi[d] = std::max(hi[d], die_box_[6 * k + 3 + d] + shift * dies_[k].motion.direction[d]);
    }
  }
  const double grow = 0.25 * std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  for (int d = 0; d < 3; ++d) lo[d] -= grow, hi[d] += grow;
}

void DieContact::add_to(const Model& md, State& st, const FixedScale& scale) const {
  for (const auto& a : active_) {
    double f[3];
    for (int i = 0; i < 3; ++i) f[i] = a.normal_force[i] + a.friction_force[i];
    if (!a.point) {
      for (int i = 0; i < 3; ++i) st.partial[3 * std::size_t(a.slave) + i] -= scale.fixed(f[i]);
      continue;
    }
    const std::size_t g = std::size_t(a.slave);  // f acts on the field at the point: N_J f on d_J
    for (auto k = md.nbr_offsets[g]; k < md.nbr_offsets[g + 1]; ++k)
      for (int i = 0; i < 3; ++i) st.partial[3 * std::size_t(md.nbr[k]) + i] -= scale.fixed(md.N[k] * f[i]);
  }
}

void DieContact::account(const Model& md, const State& st, const std::vector<double>& v_old, double dt_avg, double t) {
  for (const auto& a : active_) {
    const DieMotion& mo = dies_[a.die].motion;
    const double rate = mo.rate(t);
    DieTotals& tot = totals_[a.die];
    double before[3], after[3];
    if (a.point) {
      field_value(md, v_old, std::size_t(a.slave), before);
      field_value(md, st.v, std::size_t(a.slave), after);
    } else {
      for (int i = 0; i < 3; ++i) before[i] = v_old[3 * a.slave + i], after[i] = st.v[3 * a.slave + i];
    }
    for (int i = 0; i < 3; ++i) {
      const double vbar = 0.5 * (before[i] + after[i]);
      const double f = a.normal_force[i] + a.friction_force[i];
      tot.contact_work += dt_avg * f * vbar;
      tot.press_work += dt_avg * f * rate * mo.direction[i];
      tot.friction_work -= dt_avg * a.friction_force[i] * (vbar - rate * mo.direction[i]);
    }
  }
}

}  // namespace rk
