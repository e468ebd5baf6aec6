#include "material/j2_point.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>

namespace rk {
namespace {

// Matrix logarithm of b = I + X and exponential of A by truncated series, for the elastic stretches
// of metals (|X| <= 0.5): rational and polynomial in the argument, so exactly objective, and
// cheaper than an eigen-decomposition (which, per point, would not run across lanes). All the
// matrices of one series commute, so their products are symmetric (commuting_product). The number
// of terms, per lane, keeps the truncation below 1e-17, under double round-off (the loop bounds, 30
// and 40 terms, only guard termination); each lane starts its Horner recursion at its own term, so
// it computes what it would alone (docs/decisions.md, "Elastic log strain by series").

// 1 / n as constants: the series' coefficients 1 / (2k + 1) and 1 / k, the same doubles as the divisions
// (both correctly rounded) without a division in the recursions, and the factors of exp's term bound (a
// multiplication for a division there may move the bound's last bit: it only counts the terms)
constexpr int kSeriesTerms = 40;  // (the exp bound's loop; the log's stops at 30)
constexpr auto kInverse = [] {
  std::array<double, 2 * kSeriesTerms + 2> r{};
  for (int n = 1; n < int(r.size()); ++n) r[std::size_t(n)] = 1.0 / n;
  return r;
}();

// log(I + X) = 2 atanh(Y), Y = X (2I + X)^{-1} (X and Y commute): odd powers of Y only, and
// |Y| ~ |X|/2, so about a third of the terms of the plain series sum_k (-1)^{k+1} X^k / k.
Sym log_series(const Sym& X, Lane norm, LaneMask use) {
  const Sym Y = commuting_product(X, inverse(X + identity_sym(splat(2))));
  const Lane y = select(use, norm / (2 - norm), Lane{});
  Lane m{};  // Y^{2m+1} / (2m+1) below 1e-17 |Y|
  Lane t = y * y;
  for (int k = 0; k < 30; ++k, t *= y * y) {
    const LaneMask more = t > 1e-17;
    if (!any(more)) break;
    m += select(more, splat(1), Lane{});
  }
  const Sym Y2 = commuting_product(Y, Y);
  Sym r{};  // (a lane's first term is 1 / (2m + 1) I + Y^2 0, exactly its start)
  for (int k = int(*std::max_element(&m[0], &m[0] + kLanes)); k >= 0; --k)
    r = select(m >= double(k), identity_sym(splat(kInverse[std::size_t(2 * k + 1)])) + commuting_product(Y2, r), r);
  return splat(2) * commuting_product(Y, r);
}

// exp(A) = sum_k A^k / k!, Horner form, to the last term whose bound |A|^k / k! is above 1e-17 (past
// it the bounds only fall)
Sym exp_series(const Sym& A, Lane norm) {
  Lane n{};
  Lane t = norm;  // |A|^k / k!
  for (int k = 1; k < kSeriesTerms; ++k, t *= norm * kInverse[std::size_t(k + 1)]) {
    const LaneMask more = t > 1e-17;
    if (!any(more)) break;
    n += select(more, splat(1), Lane{});
  }
  const Sym I = identity_sym(splat(1));
  Sym r = I;
  for (int k = int(*std::max_element(&n[0], &n[0] + kLanes)); k >= 1; --k)
    r = select(n >= double(k), I + splat(kInverse[std::size_t(k)]) * commuting_product(A, r), r);
  return r;
}

Eigen::Matrix3d lane_of(const Sym& a, int l) {
  Eigen::Matrix3d m;
  m << a.v[0][l], a.v[3][l], a.v[5][l], a.v[3][l], a.v[1][l], a.v[4][l], a.v[5][l], a.v[4][l], a.v[2][l];
  return m;
}
void set_lane(Sym& a, int l, const Eigen::Matrix3d& m) {
  a.v[0][l] = m(0, 0), a.v[1][l] = m(1, 1), a.v[2][l] = m(2, 2);
  a.v[3][l] = m(0, 1), a.v[4][l] = m(1, 2), a.v[5][l] = m(2, 0);
}

// Each lane's temperature terms of a rate-dependent law (J2Params::at_temperature's formulas), once a
// return: Johnson-Cook's and Hansel-Spittel's across the lanes (lanes.hpp's exp and log: a pow a lane
// was 4.5 % of the Johnson-Cook Taylor bar's samples), a table's lane by lane.
struct TemperatureLanes {
  J2Params::AtTemperature at[kLanes];  // a table's
  Lane thermal = splat(1), log_a{}, strain_t{}, rate_exponent{};
  TemperatureLanes(const J2Params& p, Lane T) {
    if (p.johnson_cook) {  // 1 - T*^m between the room and the melting temperature, 1 below, 0 molten
      const Lane homologous = (T - p.t_room) / (p.t_melt - p.t_room);
      const LaneMask warm = (homologous > 0) & (homologous < 1);
      const Lane power = exp(p.jc_m * log(select(warm, homologous, splat(1))));
      thermal = select(warm, 1 - power, select(homologous >= 1, Lane{}, splat(1)));
    }
    if (p.hansel_spittel) {
      const Lane c = T - 273.15;  // the databases' Celsius; T^m9 at 1 C at the least
      log_a = p.hs_log_a + p.hs_m1 * c;
      if (p.hs_m9 != 0) log_a += p.hs_m9 * log(select(c > 1, c, splat(1)));
      strain_t = p.hs_m5 * c, rate_exponent = p.hs_m3 + p.hs_m8 * c;
    }
    if (p.table)
      for (int l = 0; l < kLanes; ++l) at[l] = p.at_temperature(T[l]);
  }
};

// The flow stress and its slopes d/d ep, d/d rate at each lane's (ep, rate): Johnson-Cook and
// Hansel-Spittel across the lanes (J2Params::johnson_cook_at's and hansel_spittel_at's formulas, with
// lanes.hpp's exp and log), a table lane by lane where `use`. With `curvature` (not for a table) also
// the second derivative along a return's path, rate = dgamma / dt: y_ee + 2 y_er / dt + y_rr / dt^2
// (y_ee alone where dt = 0), for Halley's step.
void flow_lanes(const J2Params& p, const TemperatureLanes& t, Lane ep, Lane rate, LaneMask use, Lane& y, Lane& h,
                Lane& hr, Lane* curvature = nullptr, double dt = 0) {
  if (p.johnson_cook) {
    const LaneMask strained = ep > 0, fast = rate > p.jc_rate0;
    const Lane hard = select(strained, p.jc_b * exp(p.jc_n * log(select(strained, ep, splat(1)))), Lane{});
    const Lane strain = p.yield0 + hard;
    const double at_zero = p.jc_n < 1 ? INFINITY : p.jc_b * p.jc_n;  // the slope at ep = 0
    const Lane strain_slope = select(strained, p.jc_n * hard / select(strained, ep, splat(1)), splat(at_zero));
    const Lane rate_factor = select(fast, 1 + p.jc_c * log(select(fast, rate, splat(p.jc_rate0)) / p.jc_rate0), splat(1));
    y = strain * rate_factor * t.thermal;
    h = strain_slope * rate_factor * t.thermal;
    hr = select(fast, strain * t.thermal * p.jc_c / rate, Lane{});
    if (curvature) {  // B n (n - 1) ep^(n-2) times the rest; (B n ep^(n-1)) (C / rate); - hr / rate
      *curvature = select(strained, h * (p.jc_n - 1) / select(strained, ep, splat(1)), Lane{});
      if (dt > 0)
        *curvature += select(fast, (2 * strain_slope * t.thermal * p.jc_c - hr / dt) / (rate * dt), Lane{});
    }
    return;
  }
  if (p.hansel_spittel) {
    const LaneMask strained = ep > p.hs_eps_min, fast = rate > p.hs_rate_min;
    const Lane e = select(strained, ep, splat(p.hs_eps_min)) + p.hs_eps_offset;
    const Lane r = select(fast, rate, splat(p.hs_rate_min)) + p.hs_rate_offset;
    const Lane m4_e = p.hs_m4 / e;  // (one division for the three terms in 1 / e)
    y = exp(t.log_a + p.hs_m2 * log(e) + m4_e + t.strain_t * log(1 + e) + p.hs_m7 * e + t.rate_exponent * log(r));
    const Lane log_slope = (p.hs_m2 - m4_e) / e + t.strain_t / (1 + e) + p.hs_m7;  // d ln y / d e
    h = select(strained, y * log_slope, Lane{});
    hr = select(fast, y * t.rate_exponent / r, Lane{});
    if (curvature) {  // y ((ln y)_e^2 + (ln y)_ee), y_e (ln y)_r, y_r (m3 + m8 T - 1) / r
      const Lane log_curve = (2 * m4_e - p.hs_m2) / (e * e) - t.strain_t / ((1 + e) * (1 + e));
      *curvature = select(strained, y * (log_slope * log_slope + log_curve), Lane{});
      if (dt > 0) *curvature += select(fast, (2 * h * t.rate_exponent + hr * (t.rate_exponent - 1) / dt) / (r * dt), Lane{});
    }
    return;
  }
  for (int l = 0; l < kLanes; ++l)
    if (use[l]) p.flow_at(ep[l], rate[l], t.at[l], y[l], h[l], hr[l]);
}

// The rate-dependent return across the lanes: per lane q - 3G dg = sigma_y(ep + dg, dg / dt, T) where the
// trial state passes the yield check sigma_y(ep, 0, T). The residual falls strictly with dg where sigma_y
// grows with strain and rate, and at dg0 = (q - y0) / 3G it is <= 0, so the root lies in [0, dg0]:
// Newton in log dgamma, kept in the bracket by bisection, from the last increment's rate (the point's
// plastic strain rate times dt) where that lies in the bracket, else from dg0 (docs/decisions.md,
// "Johnson-Cook": 6.8 iterations a return from dg0 on the Johnson-Cook Taylor bar). A law that softens
// with strain (Hansel-Spittel's m7 < 0) below its least rate can have its root just past dg0: the
// bracket then widens. Each lane stops on its own test; 100 iterations only guard the loop (the
// bracket halves at least every other one).
Lane rate_dependent_return(const J2Params& p, Lane q, J2Batch& b) {
  const TemperatureLanes t(p, b.T);
  const LaneMask all = ~LaneMask{};
  Lane y, h, hr;
  flow_lanes(p, t, b.ep, Lane{}, all, y, h, hr);
  const LaneMask plastic = q > y;
  if (!any(plastic)) return Lane{};
  const double dt = b.dt;
  const Lane three_g = splat(3 * p.shear), guess = b.rate_last * dt;
  Lane lo{}, hi = select(plastic, (q - y) / three_g, Lane{});
  Lane dg = select((guess > 0) & (guess < hi), guess, hi);
  LaneMask active = plastic;
  Lane last{};  // each lane's last step (0 before the first: no estimate of the next)
  const bool halley = !p.table;  // (a table's flow stress has no curvature here: Newton's steps)
  Lane curve{};
  for (int it = 0; it < 100 && any(active); ++it) {
    flow_lanes(p, t, b.ep + dg, dt > 0 ? dg / dt : Lane{}, active, y, h, hr, halley ? &curve : nullptr, dt);
    const Lane r = q - three_g * dg - y;
    active &= (r > 1e-15 * q) | (r < -1e-15 * q);  // at the round-off of q: converged
    lo = select(active & (r > 0), dg, lo);
    hi = select(active & ~(r > 0), dg, hi);
    hi = select(active & (lo >= hi), 2 * lo, hi);  // a law softening with strain: the bracket widens
    // Newton in log dgamma: the rate term C ln(dgamma / dt) is linear there (a dgamma of one step
    // is so small that it dominates the slope), and the strain term nearly so; with the residual's
    // second derivative, Halley's step N / (1 + N r'' / 2r'), N Newton's, r' = dr / d ln dgamma (cubic
    // convergence: one evaluation of the law fewer from a guess near the root)
    const Lane slope = (three_g + h) * dg + (dt > 0 ? hr * dg / dt : Lane{});  // -dr / d ln dgamma
    const Lane newton = select(active, r / slope, Lane{});
    Lane log_step = newton;
    LaneMask cubic{};
    if (halley) {  // r' = -slope, r'' = -slope - dgamma^2 curve
      const Lane d = 1 - newton * (-slope - dg * dg * curve) / (2 * slope);
      cubic = active & (d > 0.5) & (d < 2);  // (else Newton's: far from the root, or no finite curvature)
      log_step = select(cubic, newton / d, newton);
    }
    const Lane stepped = dg * exp(log_step);
    const LaneMask inside = (stepped > lo) & (stepped < hi);
    const Lane next = select(inside, stepped, 0.5 * (lo + hi));  // the step left the bracket (or slope infinite)
    cubic &= inside;
    // converged: a step below 1e-12 of dgamma (a tighter one is below the round-off of r when
    // dgamma is small against q / 3G), or the bracket at round-off; or a step below 1e-6 of dgamma
    // where Newton's convergence is quadratic, e_k+1 ~ |e_k|^3 / e_k-1^2 from the last two steps, and
    // puts the next one below dgamma's round-off, 1e-16 of it: its evaluation could not change dgamma
    // (where the returned stress is no cancellation, 3G dgamma below half of q, as in the power law's)
    const Lane step = next - dg, size = select(step < 0, -step, step);
    const LaneMask small = (size <= 1e-12 * dg) | (hi - lo <= 1e-15 * hi);
    // (after Halley's step e_k+1 ~ e_k^4 / e_k-1^3)
    const Lane last2 = last * last, size3 = size * size * size;
    const LaneMask predicted = (cubic & (size3 * size <= 1e-16 * next * last2 * select(last < 0, -last, last))) |
                               (~cubic & (size3 <= 1e-16 * next * last2));
    const LaneMask quadratic = (size <= 1e-6 * dg) & predicted & (three_g * next <= 0.5 * q);
    last = step;
    const LaneMask done = small | quadratic;
    dg = select(active, next, dg);
    active &= ~done;
  }
  b.plastic = plastic;
  b.ep = select(plastic, b.ep + dg, b.ep);
  b.dissipation = select(plastic, (q - three_g * dg) * dg, Lane{});  // the returned stress, sigma_y to the round-off
  return select(plastic, dg, Lane{});
}

// (1 + u)^n and its derivative n (1 + u)^(n-1) of the power law's exponent n (0 <= n <= 1), for
// 0 <= u <= 0.25, by the binomial series sum_k C(n, k) u^k (|C(n, k)| <= 1): per lane the terms while
// u^k > 1e-17 (at most 28), each lane's Horner recursion starting at its own last term.
void binomial_series(Lane u, const J2Params& p, Lane& value, Lane& slope) {
  const double* c = p.binomial;
  Lane m{};
  Lane t = u;
  for (int k = 1; k < J2Params::kBinomialTerms; ++k, t *= u) {
    const LaneMask more = t > 1e-17;
    if (!any(more)) break;
    m += select(more, splat(1), Lane{});
  }
  Lane r{};  // (a lane's first term is c[m] + u 0 = c[m] exactly)
  for (int k = int(*std::max_element(&m[0], &m[0] + kLanes)); k >= 0; --k) r = select(m >= double(k), c[k] + u * r, r);
  value = r;
  slope = p.exponent * r / (1 + u);
}

// The power law's return, q - 3G dgamma = K (z0 + dgamma)^n with z0 = eps0 + ep: Newton across the
// lanes on K z0^n (1 + u)^n, u = dgamma / z0, by the binomial series, so one power a point (sigma_y at
// ep, across the lanes by lanes.hpp's exp and log) instead of a pow an iteration. The root lies below
// dg0 = (q - sigma_y(ep)) / 3G; a lane whose dg0 passes z0 / 4 (a step's plastic strain a quarter of the strain so far: the first steps of an impact)
// iterates on pow alone. Newton stops at a step below 1e-14 of dgamma, or (across the lanes) below the
// round-off of q / 3G, where the residual's round-off can keep the step from falling under the first
// (steps of 1e-5 on 1 m/s upsetting), or where the law's curvature bounds the next step below dgamma's
// round-off (from the linear guess the first step is about 1e-6 of dgamma on the upsetting, and the
// bound then, from the law's constants, about 1e-18 of it); 50 iterations only guard the loop.
Lane power_law_return(const J2Params& p, Lane q, J2Batch& b) {
  Lane dgamma{};
  const Lane z0 = p.eps0 + b.ep;
  const Lane y0 = p.strength * exp(p.exponent * log(z0)), h0 = p.exponent * y0 / z0;  // sigma_y and its slope at ep
  b.plastic = q > y0;
  if (!any(b.plastic)) return dgamma;
  const LaneMask series = b.plastic & ((q - y0) / (3 * p.shear) <= 0.25 * z0);
  const LaneMask by_pow = b.plastic & ~series;
  for (int l = 0; l < kLanes && any(by_pow); ++l) {
    if (!by_pow[l]) continue;
    double y = y0[l], h = h0[l];
    double dg = (q[l] - y) / (3 * p.shear + h);
    for (int it = 0; it < 50; ++it) {
      p.yield_and_slope(b.ep[l] + dg, y, h);
      const double step = (q[l] - 3 * p.shear * dg - y) / (3 * p.shear + h);
      dg += step;
      if (std::abs(step) <= 1e-14 * (dg + 1e-300)) break;
    }
    dgamma[l] = dg;
    b.ep[l] += dg;
    b.dissipation[l] = p.yield(b.ep[l]) * dg;
  }
  if (!any(series)) return dgamma;
  const Lane three_g = splat(3 * p.shear);
  // the residual's curvature over dg >= 0 is at most y0 n (1 - n) / z0^2 ((1 + u)^(n - 2) <= 1) and its
  // slope at least 3G, so the error after a Newton step s is at most that / (2 3G) (2 s)^2; a lane stops
  // once that is below dgamma's round-off, 1e-16 of it, where the returned stress q - 3G dg is no
  // cancellation (3G dg below half of q, so dgamma's last bit moves the stress by at most its own); a
  // larger increment takes the steps that set its last bits (without them the stress of an increment of
  // u = 0.24 read 5 ulp off sigma_y, past the return test's 1e-15, built at -O1)
  const Lane curvature = y0 * (p.exponent * (1 - p.exponent)) / (z0 * z0);
  Lane dg = select(series, (q - y0) / (three_g + h0), Lane{}), value, slope;
  LaneMask active = series;
  for (int it = 0; it < 50 && any(active); ++it) {
    binomial_series(dg / z0, p, value, slope);
    const Lane step = (q - three_g * dg - y0 * value) / (three_g + y0 * slope / z0);
    dg = select(active, dg + step, dg);
    const Lane tolerance = 1e-14 * dg + 1e-15 * q / three_g;  // or at the round-off of q
    const Lane next_error = 2 * curvature * step * step / three_g;
    active &= ((step > tolerance) | (step < -tolerance)) & ((next_error > 1e-16 * dg) | (three_g * dg > 0.5 * q));
  }
  dgamma = select(series, dg, dgamma);
  b.ep = select(series, b.ep + dg, b.ep);
  b.dissipation = select(series, (q - three_g * dg) * dg, b.dissipation);  // the returned stress, sigma_y to the round-off
  return dgamma;
}

// Radial return: q - 3G dgamma = sigma_y(ep + dgamma). Linear hardening in one step across the lanes;
// the power law's and the rate-dependent laws' Newton iterations across the lanes. Returns dgamma (0
// where the trial state is elastic). Not inlined: where the returns land in j2_update decides which
// products the compiler fuses into multiply-adds there, so inlining them would move j2_update's
// round-off whenever a return's code changes size.
__attribute__((noinline)) Lane return_map(const J2Params& p, Lane q, J2Batch& b) {
  Lane dgamma{};
  b.plastic = LaneMask{};
  b.dissipation = Lane{};
  if (!p.plastic) return dgamma;
  if (p.power_law) return power_law_return(p, q, b);
  if (p.rate_dependent()) return rate_dependent_return(p, q, b);
  // linear hardening: one step, the same flops as J2Params::yield_and_slope and yield
  const Lane y = p.yield0 + p.hardening * b.ep;
  b.plastic = q > y;
  if (!any(b.plastic)) return dgamma;
  dgamma = select(b.plastic, (q - y) / (3 * p.shear + p.hardening), dgamma);
  b.ep = select(b.plastic, b.ep + dgamma, b.ep);
  b.dissipation = select(b.plastic, (p.yield0 + p.hardening * b.ep) * dgamma, b.dissipation);
  return dgamma;
}

}  // namespace

double J2Params::thermal_factor(double T) const {
  const double homologous = (T - t_room) / (t_melt - t_room);
  return homologous <= 0 ? 1.0 : homologous >= 1 ? 0.0 : 1 - std::pow(homologous, jc_m);
}

double J2Params::hot_yield(double ep) const {
  double y, h, hr;
  flow(ep, 0.0, table ? table->temperature.front() : 1273.15, y, h, hr);
  return y;
}

J2Params::AtTemperature J2Params::at_temperature(double T) const {
  AtTemperature at;
  at.T = T;
  if (johnson_cook) at.thermal = thermal_factor(T);
  if (hansel_spittel) {
    const double c = T - 273.15;  // the databases' Celsius
    // T^m9 at 1 C at the least: the laws are fitted far above freezing, and ln would fail at 0 C
    at.log_a = hs_log_a + hs_m1 * c + (hs_m9 != 0 ? hs_m9 * std::log(std::max(c, 1.0)) : 0.0);
    at.strain_t = hs_m5 * c, at.rate_exponent = hs_m3 + hs_m8 * c;
  }
  return at;
}

void J2Params::hansel_spittel_at(double ep, double rate, const AtTemperature& at, double& y, double& dy_dep,
                                 double& dy_drate) const {
  // in logs: ln sigma is a sum of terms; below a minimum its slope is 0
  const bool strained = ep > hs_eps_min, fast = rate > hs_rate_min;
  const double e = (strained ? ep : hs_eps_min) + hs_eps_offset, r = (fast ? rate : hs_rate_min) + hs_rate_offset;
  y = std::exp(at.log_a + hs_m2 * std::log(e) + hs_m4 / e + at.strain_t * std::log1p(e) + hs_m7 * e +
               at.rate_exponent * std::log(r));
  dy_dep = strained ? y * (hs_m2 / e - hs_m4 / (e * e) + at.strain_t / (1 + e) + hs_m7) : 0.0;
  dy_drate = fast ? y * at.rate_exponent / r : 0.0;
}

void J2Params::johnson_cook_at(double ep, double rate, double thermal, double& y, double& dy_dep, double& dy_drate) const {
  const double hard = jc_b * std::pow(ep, jc_n), strain = yield0 + hard;
  const double strain_slope = ep > 0 ? jc_n * hard / ep : (jc_n < 1 ? INFINITY : jc_b * jc_n);
  const bool fast = rate > jc_rate0;  // below the reference rate the law is quasi-static
  const double rate_factor = fast ? 1 + jc_c * std::log(rate / jc_rate0) : 1.0;
  y = strain * rate_factor * thermal;
  dy_dep = strain_slope * rate_factor * thermal;
  dy_drate = fast ? strain * thermal * jc_c / rate : 0.0;
}

void J2Batch::at_rest(int l) {
  for (int i = 0; i < 9; ++i) F.v[i][l] = (i % 4 == 0);
  for (int i = 0; i < 6; ++i) cp_inv.v[i][l] = (i < 3);
  ep[l] = 0, rate_last[l] = 0;
}

void j2_update(const J2Params& p, J2Batch& b) {
  const Sym be = congruence(b.F, b.cp_inv, false);  // trial elastic left Cauchy-Green tensor
  const Sym X = be + identity_sym(splat(-1));
  const Lane norm = sqrt(norm2(X));
  // eps = log(b_e) / 2: by series, or spectrally where the elastic stretch is large (|X| > 0.5,
  // beyond 17 terms of the series)
  const LaneMask spectral = norm > 0.5;
  Sym eps = splat(0.5) * log_series(X, norm, ~spectral);
  Eigen::Matrix3d vectors[kLanes];
  const bool any_spectral = any(spectral);
  for (int l = 0; l < kLanes && any_spectral; ++l) {
    if (!spectral[l]) continue;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(lane_of(be, l));
    vectors[l] = eig.eigenvectors();
    const Eigen::Vector3d e = 0.5 * eig.eigenvalues().array().log();
    set_lane(eps, l, vectors[l] * e.asDiagonal() * vectors[l].transpose());
  }
  const Lane vol = trace(eps);
  const Sym dev = eps + identity_sym(-vol / 3);
  const Lane two_g = splat(2 * p.shear);
  const Lane q = sqrt(1.5 * norm2(two_g * dev));  // trial von Mises stress (Kirchhoff)

  const Lane dgamma = return_map(p, q, b);
  const Lane scale = select(b.plastic, 1 - 3 * p.shear * dgamma / q, splat(1));
  // (component by component: a whole Sym assigned from a temporary is a call to memcpy, 2 % of the run)
  set(b.tau, (two_g * scale) * dev + identity_sym(p.bulk * vol));
  b.psi = 0.5 * p.bulk * vol * vol + p.shear * scale * scale * norm2(dev);
  if (!any(b.plastic)) return;

  // C_p^{-1} = F^{-1} b_e F^{-T} with the returned b_e = exp(2 eps_e), eps_e = eps - d_eps_p
  // (coaxial): b_e^trial exp(-2 d_eps_p), whose argument (one step's plastic strain) is tiny, or
  // spectrally where the stretch is large.
  const Sym deps_p = (1 - scale) * dev;
  Sym be_new = commuting_product(be, exp_series(splat(-2) * deps_p, 2 * sqrt(norm2(deps_p))));
  for (int l = 0; l < kLanes && any_spectral; ++l) {
    if (!spectral[l] || !b.plastic[l]) continue;
    const Eigen::Matrix3d& V = vectors[l];
    const Eigen::Vector3d e = (V.transpose() * lane_of(scale * dev + identity_sym(vol / 3), l) * V).diagonal();
    set_lane(be_new, l, V * (2 * e).array().exp().matrix().asDiagonal() * V.transpose());
  }
  Mat cof;  // F^{-1} = cof^T / det
  const Lane det = cofactor(b.F, cof);
  set(b.cp_inv, select(b.plastic, (1 / (det * det)) * congruence(cof, be_new, true), b.cp_inv));
}

J2Update j2_update(const Eigen::Matrix3d& F, const J2Params& p, double cp_inv[6], double& ep, double T, double dt) {
  J2Batch b;
  for (int l = 0; l < kLanes; ++l) b.at_rest(l), b.T[l] = T;
  b.dt = dt;
  for (int i = 0; i < 9; ++i) b.F.v[i][0] = F(i / 3, i % 3);
  for (int i = 0; i < 6; ++i) b.cp_inv.v[i][0] = cp_inv[i];
  b.ep[0] = ep;
  j2_update(p, b);
  for (int i = 0; i < 6; ++i) cp_inv[i] = b.cp_inv.v[i][0];
  ep = b.ep[0];
  return {lane_of(b.tau, 0), b.psi[0], b.dissipation[0], b.plastic[0] != 0};
}

}  // namespace rk
