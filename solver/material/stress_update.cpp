#include "material/stress_update.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <stdexcept>

#include "material/damage.hpp"
#include "material/j2_plasticity.hpp"

namespace rk {
namespace {

// Up to kLanes points of one update, one a lane: `consecutive` where they are n consecutive points, whose
// values are then read and written across the lanes as vectors (the lanes past n at rest).
struct Batch {
  const std::size_t* point;
  int n;
  bool consecutive;
};

// The k-th batch of the points pts[0 .. count).
Batch batch_of(const std::size_t* pts, std::size_t count, std::size_t k) {
  Batch bt{pts + k * kLanes, int(std::min<std::size_t>(kLanes, count - k * kLanes)), true};
  for (int l = 1; l < bt.n && bt.consecutive; ++l) bt.consecutive = bt.point[l] == bt.point[0] + std::size_t(l);
  return bt;
}

// F of the batch's points across the lanes (the rest of the lanes the identity).
void lanes_of_F(const State& st, const Batch& bt, Mat& F) {
  if (bt.consecutive) {
    strided_to_lanes<9>(&st.F[9 * bt.point[0]], F.v, bt.n);
    for (int i = 0; i < 9; i += 4) F.v[i] = rest_past(F.v[i], bt.n, 1);
    return;
  }
  for (int l = 0; l < kLanes; ++l)
    for (int i = 0; i < 9; ++i) F.v[i][l] = l < bt.n ? st.F[9 * bt.point[l] + std::size_t(i)] : (i % 4 == 0);
}

// |F^T F - I|^2 across the lanes.
Lane green_strain2(const Mat& F) {
  Lane e2{};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      const Lane c = F.v[a] * F.v[b] + F.v[3 + a] * F.v[3 + b] + F.v[6 + a] * F.v[6 + b] - (a == b ? 1.0 : 0.0);
      e2 += c * c;
    }
  return e2;
}

// The batch's points (the rest of the lanes at rest), F theirs across the lanes, of cell c with F-bar
// (without, the cell whose last update time they share); with a thermal strain their stress-free
// stretches into `stretch`.
void load(const Model& md, const State& st, std::size_t c, const Batch& bt, const Mat& F, J2Batch& b, Lane& stretch) {
  Lane r = splat(1);  // Jbar / J (the lanes at rest: 1)
  const std::size_t g = bt.point[0];
  const int n = bt.n;
  if (md.fbar && bt.consecutive) {
    r = st.cell_J[c] / rest_past(load_lanes(&st.J[g], n), n, 1);
  } else if (md.fbar) {
    Lane J = splat(1);
    LaneMask used{};
    for (int l = 0; l < n; ++l) J[l] = st.J[bt.point[l]], used[l] = -1;
    r = select(used, st.cell_J[c] / J, r);
  }
  Lane ratio = cube_root_near_one(r);
  // the thermal stretch taken out: F_mech = F / stretch(T) (1 + alpha (T - T0), or from rho(T)). C_p^-1 is
  // pushed forward at a reference update with the whole F, so the total stretch is right here.
  if (md.thermal_strain() && bt.consecutive && md.density_table.empty()) {
    stretch = md.linear_thermal_stretch(load_lanes(&st.temperature[g], n));
    stretch = rest_past(stretch, n, 1);  // (the lanes at rest: unstretched)
    ratio /= stretch;
  } else if (md.thermal_strain()) {
    for (int l = 0; l < n; ++l) stretch[l] = md.thermal_stretch(st.temperature[bt.point[l]]), ratio[l] /= stretch[l];
  }
  if (bt.consecutive) {  // (a lane written one at a time and then read as a vector stalls: docs/decisions.md)
    strided_to_lanes<6>(&st.cp_inv[6 * g], b.cp_inv.v, n);
    for (int i = 0; i < 3; ++i) b.cp_inv.v[i] = rest_past(b.cp_inv.v[i], n, 1);
    b.ep = load_lanes(&st.ep[g], n);
    if (!st.temperature.empty()) b.T = load_lanes(&st.temperature[g], n);
    if (!st.plastic_rate.empty()) b.rate_last = load_lanes(&st.plastic_rate[g], n);
  } else {
    for (int l = 0; l < kLanes; ++l) {
      if (l >= n) {
        b.at_rest(l);
        continue;
      }
      const std::size_t p = bt.point[l];
      for (int i = 0; i < 6; ++i) b.cp_inv.v[i][l] = st.cp_inv[6 * p + i];
      b.ep[l] = st.ep[p];
      if (!st.temperature.empty()) b.T[l] = st.temperature[p];
      if (!st.plastic_rate.empty()) b.rate_last[l] = st.plastic_rate[p];
    }
  }
  for (int i = 0; i < 9; ++i) b.F.v[i] = ratio * F.v[i];  // (the lanes at rest: 1 times the identity)
  // the increment from the last state took the last step (0 at the start: no rate); with multi-rate
  // steps the cell's own
  b.dt = st.cell_t_last.empty() ? st.dt_half : st.t - st.cell_t_last[c];
}

// P = tau_eff F^{-T} = tau_eff cof(F) / det F for the batch's points (tau theirs across the lanes),
// and their force bounds.
void first_piola(const Model& md, State& st, const Batch& bt, double pc, const Mat& F, const Sym& tau) {
  Mat cof;
  const std::size_t g = bt.point[0];
  const int n = bt.n;
  Lane J{}, q{};  // the volume ratio from t = 0 and the bulk viscosity's pressure (the rest of the lanes 0, or the last point's)
  if (bt.consecutive) {  // (as State::total_J)
    J = st.J_ref.empty() ? load_lanes(&st.J[g], n) : load_lanes(&st.J[g], n) * load_lanes(&st.J_ref[g], n);
    if (!st.q.empty()) q = load_lanes(&st.q[g], n);
  } else {
    for (int l = 0; l < kLanes; ++l) {
      const std::size_t p = bt.point[std::min(l, n - 1)];
      J[l] = st.total_J(p);
      if (!st.q.empty()) q[l] = st.q[p];
    }
  }
  Lane shift = md.fbar ? J * pc - (tau.v[0] + tau.v[1] + tau.v[2]) / 3 : Lane{};
  if (!st.q.empty()) shift -= J * q;  // (material/bulk_viscosity.hpp)
  Sym te = tau;
  for (int i = 0; i < 3; ++i) te.v[i] += shift;
  const Lane inv_det = 1 / cofactor(F, cof);
  const Mat t = full(te);
  Lane P[9], norm2{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      P[3 * i + j] = (t.v[3 * i] * cof.v[j] + t.v[3 * i + 1] * cof.v[3 + j] + t.v[3 * i + 2] * cof.v[6 + j]) * inv_det;
      norm2 += P[3 * i + j] * P[3 * i + j];
    }
  Lane w{}, dN_max{};
  if (bt.consecutive) w = load_lanes(&md.weight[g], n), dN_max = load_lanes(&md.dN_max[g], n);
  else
    for (int l = 0; l < n; ++l) w[l] = md.weight[bt.point[l]], dN_max[l] = md.dN_max[bt.point[l]];
  const Lane bound = w * sqrt(norm2) * dN_max;
  if (bt.consecutive) {
    lanes_to_strided<9>(P, &st.P[9 * g], n);
    store_lanes(&st.force_bound[g], bound, n);
    return;
  }
  for (int l = 0; l < n; ++l) {
    for (int i = 0; i < 9; ++i) st.P[9 * bt.point[l] + i] = P[i][l];
    st.force_bound[bt.point[l]] = bound[l];
  }
}

// The pressure p (compression positive) of point g, or of its cell with F-bar, against the bound.
// floor: p_ref at ep = 0, its least over the materials (hardening is never negative: scene.cpp), so a
// pressure that cannot raise the rank's largest ratio so far skips sigma_y(ep) (a pow for the power law).
void check_pressure(const J2Params& law, const PressureBound& b, double floor, double p, double ep, std::size_t g,
                    StressHealth& h) {
  if (!(std::abs(p) > h.pressure_ratio * floor)) return;  // (and so not past the bound either)
  const double ref = b.impact + (law.plastic ? law.yield(ep) : 0.0);
  if (!(ref > 0)) return;  // an elastic part at rest and untouched: nothing to scale a bound with
  const double r = std::abs(p) / ref;
  if (r > h.pressure_ratio) h.pressure_ratio = r, h.pressure = p;
  if (b.ratio > 0 && !(r <= b.ratio) && h.ok) h.ok = false, h.point = g, h.pressure_stop = true;
}

static_assert(kMaxCellPoints >= std::size_t(kLanes));

// The damage criteria over the points pts[0 .. count) of one cell (or batch), at the stress the force
// uses: with F-bar the point's deviator and the cell's pressure (Kirchhoff, pc per unit J), which is
// free of the point-to-point pressure scatter of the point's own.
void accumulate_damage(const Model& md, State& st, const std::size_t* pts, std::size_t count, double pc,
                       const double* increment) {
  for (std::size_t j = 0; j < count; ++j) {
    const std::size_t p = pts[j];
    const double dep = increment[j];
    if (!(dep > 0)) continue;
    const double* t = &st.tau[6 * p];
    const double shift = md.fbar ? st.total_J(p) * pc - (t[0] + t[1] + t[2]) / 3 : 0.0;
    const double s[6] = {t[0] + shift, t[1] + shift, t[2] + shift, t[3], t[4], t[5]};
    const DamageIncrement d = damage_increment(s, dep, md.oyane_a);
    double* D = &st.damage[kDamageCriteria * p];
    D[0] += md.damage_cockcroft_latham ? d.cockcroft_latham : 0.0;
    D[1] += md.damage_brozzo ? d.brozzo : 0.0;
    D[2] += md.damage_oyane ? d.oyane : 0.0;
  }
}

}  // namespace

namespace {

// listed: the points of the cells in `cells` only (multi-rate steps: the cells due), else every point
StressHealth update_points(const Model& md, State& st, const PressureBound& bound, bool listed,
                           std::span<const std::int32_t> cells) {
  StressHealth health;
  double thermal_work = 0;
  double floor = std::numeric_limits<double>::infinity();
  for (const Solid& s : md.materials) floor = std::min(floor, bound.impact + (s.law.plastic ? s.law.yield(0.0) : 0.0));
  // a cell's batches and their F, kept for P once the cell's pressure is known (filled in place: a
  // copy of these structs is a memmove call); an F-bar cell holds at most kMaxCellPoints points
  J2Batch batch[(kMaxCellPoints + kLanes - 1) / kLanes];
  Mat F_batch[std::size(batch)];
  std::size_t pts[kMaxCellPoints];  // the points updated together: an F-bar cell's, or a batch's
  const std::size_t count = listed ? cells.size() : md.cells;
  const auto cell_at = [&](std::size_t i) { return listed ? std::size_t(cells[i]) : i; };
  // F-bar couples the points of a cell; without it (volumetric: none, nodal integration, one point a
  // cell) the points go kLanes at a time whatever their cells, of one material each batch, and where
  // listed, of cells last updated together (their increment's time)
  for (std::size_t i = 0, g_next = 0; md.fbar || listed ? i < count : g_next < md.m;) {
    std::size_t npts = 0, c = 0;
    if (md.fbar) {
      c = cell_at(i++);
      for (auto g = md.cell_points[c]; g < md.cell_points[c + 1]; ++g) pts[npts++] = std::size_t(g);
    } else if (!listed) {
      const std::size_t g0 = g_next;
      do pts[npts++] = g_next++;
      while (npts < std::size_t(kLanes) && g_next < md.m && md.point_material[g_next] == md.point_material[g0]);
    } else {  // (multi-rate steps without F-bar: cells of one point, gauss_order 1)
      c = cell_at(i);
      for (; i < count && npts < std::size_t(kLanes); ++i) {
        const std::size_t ci = cell_at(i), g = std::size_t(md.cell_points[ci]);
        if (!st.cell_t_last.empty() && st.cell_t_last[ci] != st.cell_t_last[c]) break;
        if (md.cell_points[ci + 1] - md.cell_points[ci] > 1)
          throw std::logic_error("update_stress: a listed cell of more than one point without F-bar");
        if (md.cell_points[ci + 1] == md.cell_points[ci]) continue;
        if (npts > 0 && md.point_material[g] != md.point_material[pts[0]]) break;
        pts[npts++] = g;
      }
    }
    if (npts == 0) continue;
    const J2Params& law = md.material_at(pts[0]).law;  // (a cell never spans two bodies)
    bool cell_ok = true;
    for (std::size_t j = 0; j < npts; ++j)
      if (const std::size_t g = pts[j]; !(st.J[g] > 0) || !std::isfinite(st.J[g])) {
        if (health.ok) health = {false, g, st.J[g]};
        cell_ok = false;
      }
    if (!cell_ok) continue;
    double wp = 0, wJ = 0, w = 0, ep_max = 0;
    double increment[kMaxCellPoints];  // the points' plastic strain increments (for the damage)
    Lane stretch[std::size(batch)];
    // every batch loaded before the first update: their F-bar ratios' chains of divisions overlap
    for (std::size_t k = 0; k * kLanes < npts; ++k) {
      const Batch bt = batch_of(pts, npts, k);
      lanes_of_F(st, bt, F_batch[k]);
      if (md.green_strain) {
        const Lane e2 = green_strain2(F_batch[k]);  // (the rest of the lanes the identity: 0)
        for (int l = 0; l < bt.n; ++l) health.green_strain2 = std::max(health.green_strain2, e2[l]);
      }
      load(md, st, c, bt, F_batch[k], batch[k], stretch[k]);
    }
    for (std::size_t k = 0; k * kLanes < npts; ++k) {
      const Batch bt = batch_of(pts, npts, k);
      const int n = bt.n;
      J2Batch& b = batch[k];
      j2_update(law, b);
      Lane weight{};
      if (bt.consecutive) weight = load_lanes(&md.weight[bt.point[0]], n);
      else
        for (int l = 0; l < n; ++l) weight[l] = md.weight[bt.point[l]];
      const Lane weighted_mean = weight * (b.tau.v[0] + b.tau.v[1] + b.tau.v[2]) / 3;  // w tr(tau) / 3, for the cell's pressure
      // a batch of consecutive points, where nothing below needs the point's last state lane by lane (the
      // damage's increment), is stored as vectors (its plastic rate from the last ep, the last stress's trace for
      // the thermal strain's work taken first); C_p^-1 only where it changed
      const bool as_vectors = bt.consecutive && st.damage.empty();
      Lane trace_last{}, thermal_log{};  // with a thermal strain: ln(stretch / its last), across the lanes
      if (as_vectors) {
        const std::size_t g = bt.point[0];
        if (!st.stretch_last.empty()) {
          for (int l = 0; l < n; ++l) trace_last[l] = st.tau[6 * (g + l)] + st.tau[6 * (g + l) + 1] + st.tau[6 * (g + l) + 2];
          const Lane last = load_lanes(&st.stretch_last[g], n);
          thermal_log = log(select(last > 0, stretch[k] / last, splat(1)));
        }
        if (!st.plastic_rate.empty())
          store_lanes(&st.plastic_rate[g], b.dt > 0 ? (b.ep - load_lanes(&st.ep[g], n)) / b.dt : Lane{}, n);
        lanes_to_strided<6>(b.tau.v, &st.tau[6 * g], n);
        if (any(b.plastic)) lanes_to_strided<6>(b.cp_inv.v, &st.cp_inv[6 * g], n);
        store_lanes(&st.ep[g], b.ep, n);
        store_lanes(&st.psi[g], b.psi, n);
        store_lanes(&st.wp[g], load_lanes(&st.wp[g], n) + b.dissipation, n);
      }
      for (int l = 0; l < n; ++l) {
        const std::size_t p = bt.point[l];
        double* t = &st.tau[6 * p];
        const double trace_before = as_vectors ? trace_last[l] : t[0] + t[1] + t[2];
        if (!as_vectors) {
          for (int i = 0; i < 6; ++i) t[i] = b.tau.v[i][l], st.cp_inv[6 * p + i] = b.cp_inv.v[i][l];
          if (!st.plastic_rate.empty()) st.plastic_rate[p] = b.dt > 0 ? (b.ep[l] - st.ep[p]) / b.dt : 0.0;
          if (!st.damage.empty()) increment[k * kLanes + std::size_t(l)] = b.ep[l] - st.ep[p];
          st.ep[p] = b.ep[l];
          st.psi[p] = b.psi[l];
          st.wp[p] += b.dissipation[l];
        }
        if (!st.stretch_last.empty()) {  // the stress's work on the thermal strain over the step (trapezoid)
          if (st.stretch_last[p] > 0)
            thermal_work += md.weight[p] * 0.5 * (trace_before + t[0] + t[1] + t[2]) *
                            (as_vectors ? thermal_log[l] : std::log(stretch[k][l] / st.stretch_last[p]));
          st.stretch_last[p] = stretch[k][l];
        }
        // the plastic work's heat, at once at the point (spread by conduction at the next thermal update)
        if (!st.temperature.empty() && b.dissipation[l] != 0) {
          const double heating = md.taylor_quinney * b.dissipation[l] / md.capacity_at(st.temperature[p]);
          st.temperature[p] += heating;
          if (!st.heat_pending.empty()) st.heat_pending[p] += heating;
        }
        health.plastic += b.plastic[l] != 0;
        wp += weighted_mean[l];
        wJ += md.weight[p] * st.total_J(p);
        w += md.weight[p];
        // The material's volume ratio (the cell's with F-bar): no solid metal is squeezed to half its
        // volume or stretched to twice it by forming or impact pressures (docs/decisions.md,
        // "Materials"), so past that the state is not physical (a pressure of 0.69 K, 90 GPa in copper).
        const double J = md.fbar ? 0.0 : st.total_J(p);
        if (!md.fbar && !(J > kMinVolumeRatio && J < 1 / kMinVolumeRatio) && health.ok) health = {false, p, J};
        if (!md.fbar)
          check_pressure(law, bound, floor, (st.q.empty() ? 0.0 : st.q[p]) - (t[0] + t[1] + t[2]) / (3 * J), st.ep[p], p, health);
        ep_max = std::max(ep_max, st.ep[p]);
      }
    }
    const std::size_t g0 = pts[0];
    if (md.fbar && !(wJ > kMinVolumeRatio * w && wJ < w / kMinVolumeRatio) && health.ok) health = {false, g0, wJ / w};
    if (md.fbar && health.ok) check_pressure(law, bound, floor, (st.q.empty() ? 0.0 : st.q[g0]) - wp / wJ, ep_max, g0, health);
    if (!health.ok) continue;
    const double pc = md.fbar ? wp / wJ : 0.0;
    if (!st.damage.empty()) accumulate_damage(md, st, pts, npts, pc, increment);
    for (std::size_t k = 0; k * kLanes < npts; ++k) first_piola(md, st, batch_of(pts, npts, k), pc, F_batch[k], batch[k].tau);
  }
  st.thermal_work += thermal_work;
  return health;
}

}  // namespace

StressHealth update_stress(const Model& md, State& st, const PressureBound& bound) {
  return update_points(md, st, bound, false, {});
}

StressHealth update_stress(const Model& md, State& st, const PressureBound& bound, std::span<const std::int32_t> cells) {
  return update_points(md, st, bound, true, cells);
}

double fastest_speed(const Scene& scene, const double lo[3], const double hi[3]) {
  double v2 = 0;
  for (int corner = 0; corner < 8; ++corner) {  // v0 + G X is linear: its largest speed is at a corner
    const double X[3] = {corner & 1 ? hi[0] : lo[0], corner & 2 ? hi[1] : lo[1], corner & 4 ? hi[2] : lo[2]};
    double s2 = 0;
    for (int i = 0; i < 3; ++i) {
      double v = scene.initial.velocity[i];
      for (int j = 0; j < 3; ++j) v += scene.initial.velocity_gradient[3 * i + j] * X[j];
      s2 += v * v;
    }
    v2 = std::max(v2, s2);
  }
  double v = std::sqrt(v2);
  for (const auto& b : scene.bodies) v = std::max(v, norm(b.velocity));
  for (const auto& d : scene.dies) v = std::max(v, d.motion.fastest());
  for (const auto& f : scene.prescribed_faces) v = std::max(v, f.motion.fastest());
  return v;
}

}  // namespace rk
