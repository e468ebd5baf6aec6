#include "contact/die_contact.hpp"

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
  active_.reserve(slaves_.size() * std::max<std::size_t>(1, dies_.size()));
  for (const auto& sf : surfaces_) {
    double b[6] = {1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
    for (std::size_t v = 0; v < sf.vertices.size() / 3; ++v)
      for (int d = 0; d < 3; ++d) b[d] = std::min(b[d], sf.vertices[3 * v + d]), b[3 + d] = std::max(b[3 + d], sf.vertices[3 * v + d]);
    die_box_.insert(die_box_.end(), b, b + 6);
  }
}

double DieContact::compute(const Model& md, const State& st, double t, double dt) {
  active_.clear();
  double largest = 0;
  for (std::size_t k = 0; k < dies_.size(); ++k) {
    const DieMotion& mo = dies_[k].motion;
    const double stroke = mo.stroke(t), rate = mo.rate(t);
    DieTotals& tot = totals_[k];
    tot.force[0] = tot.force[1] = tot.force[2] = 0;
    tot.max_penetration = 0;
    tot.spring_energy = 0;
    tot.contacts = 0;
    for (const auto I : slaves_) {
      double x[3];
      for (int i = 0; i < 3; ++i) x[i] = md.X[3 * I + i] + st.u[3 * I + i] - stroke * mo.direction[i];
      const DieHit hit = search_[k]->nearest(x);
      if (!hit.found || hit.gap >= 0) continue;
      const double depth = -hit.gap;
      const double kI = penalty_scale_ * md.mass[I] / (dt * dt);
      Active a{I, std::int32_t(k), {}, {}};
      double vt[3], vn = 0;
      for (int i = 0; i < 3; ++i) {
        a.normal_force[i] = kI * depth * hit.normal[i];
        vt[i] = st.v[3 * I + i] - rate * mo.direction[i];
        vn += vt[i] * hit.normal[i];
      }
      for (int i = 0; i < 3; ++i) vt[i] -= vn * hit.normal[i];
      const double fn = kI * depth, vt_norm = std::sqrt(vt[0] * vt[0] + vt[1] * vt[1] + vt[2] * vt[2]);
      const double mu = dies_[k].friction;
      if (mu > 0 && vt_norm > 0) {
        const double stick = md.mass[I] * vt_norm / dt;  // stops the sliding in one step
        const double f = std::min(stick, mu * fn);
        for (int i = 0; i < 3; ++i) a.friction_force[i] = -f * vt[i] / vt_norm;
      }
      for (int i = 0; i < 3; ++i) {
        tot.force[i] += a.normal_force[i] + a.friction_force[i];
        largest = std::max(largest, std::abs(a.normal_force[i] + a.friction_force[i]));
      }
      tot.max_penetration = std::max(tot.max_penetration, depth);
      tot.spring_energy += 0.5 * kI * depth * depth;
      ++tot.contacts;
      active_.push_back(a);
    }
  }
  return largest;
}

void DieContact::project(double t, const double* c, double* x) const {
  for (std::size_t k = 0; k < dies_.size(); ++k) {
    const DieMotion& mo = dies_[k].motion;
    double y[3];
    for (int i = 0; i < 3; ++i) y[i] = c[i] - mo.stroke(t) * mo.direction[i];
    const DieHit now = search_[k]->nearest(y);
    if (now.found && now.gap < 0) {  // in contact: it stays where it is
      for (int i = 0; i < 3; ++i) x[i] = c[i];
      return;
    }
  }
  push_out(t, x);
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

void DieContact::add_to(State& st, const FixedScale& scale) const {
  for (const auto& a : active_)
    for (int i = 0; i < 3; ++i) st.partial[3 * std::size_t(a.particle) + i] -= scale.fixed(a.normal_force[i] + a.friction_force[i]);
}

void DieContact::account(const State& st, const std::vector<double>& v_old, double dt_avg, double t) {
  for (const auto& a : active_) {
    const DieMotion& mo = dies_[a.die].motion;
    const double rate = mo.rate(t);
    DieTotals& tot = totals_[a.die];
    for (int i = 0; i < 3; ++i) {
      const double vbar = 0.5 * (v_old[3 * a.particle + i] + st.v[3 * a.particle + i]);
      const double f = a.normal_force[i] + a.friction_force[i];
      tot.contact_work += dt_avg * f * vbar;
      tot.press_work += dt_avg * f * rate * mo.direction[i];
      tot.friction_work -= dt_avg * a.friction_force[i] * (vbar - rate * mo.direction[i]);
    }
  }
}

}  // namespace rk
