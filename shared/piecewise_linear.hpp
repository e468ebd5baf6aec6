// A function piecewise linear through (x, y) points with ascending x, held at the first y below them
// and at the last above: a material property as a function of temperature (the scene's
// `material.*_table` keys) or a die's stroke against time (`motion.curve`). For a specific heat
// table its integral from x = 0 is the enthalpy per unit mass, and the integral's inverse the
// temperature of an enthalpy (the values are positive, so the integral rises strictly).
#pragma once
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace rk {

class PiecewiseLinear {
 public:
  PiecewiseLinear() = default;
  // points: ascending x (the scene checks); integral() and inverse_integral() ask x >= 0 and y > 0
  explicit PiecewiseLinear(std::vector<std::pair<double, double>> points) : p_(std::move(points)) {
    if (p_.empty()) return;
    integral_.resize(p_.size());
    integral_[0] = p_[0].first * p_[0].second;  // the first value held from 0 K
    for (std::size_t k = 1; k < p_.size(); ++k)
      integral_[k] = integral_[k - 1] + 0.5 * (p_[k].first - p_[k - 1].first) * (p_[k].second + p_[k - 1].second);
  }
  bool empty() const { return p_.empty(); }
  const std::vector<std::pair<double, double>>& points() const { return p_; }
  double front() const { return p_.front().second; }

  double at(double T) const {
    const std::size_t k = segment(T);
    if (k == 0) return p_.front().second;
    if (k == p_.size()) return p_.back().second;
    const auto& [T0, v0] = p_[k - 1];
    const auto& [T1, v1] = p_[k];
    return v0 + (v1 - v0) * (T - T0) / (T1 - T0);
  }

  // The slope of the segment [x_k-1, x_k) holding x; 0 outside the points.
  double slope_after(double x) const {
    for (std::size_t k = 1; k < p_.size(); ++k)
      if (x < p_[k].first && x >= p_[k - 1].first) return (p_[k].second - p_[k - 1].second) / (p_[k].first - p_[k - 1].first);
    return 0.0;
  }

  // The integral of the value from 0 K to T.
  double integral(double T) const {
    const std::size_t k = segment(T);
    if (k == 0) return T * p_.front().second;
    if (k == p_.size()) return integral_.back() + (T - p_.back().first) * p_.back().second;
    return integral_[k - 1] + 0.5 * (T - p_[k - 1].first) * (p_[k - 1].second + at(T));
  }

  // The temperature T at which integral(T) = H.
  double inverse_integral(double H) const {
    const auto k = std::size_t(std::lower_bound(integral_.begin(), integral_.end(), H) - integral_.begin());
    if (k == 0) return H / p_.front().second;
    if (k == p_.size()) return p_.back().first + (H - integral_.back()) / p_.back().second;
    // on segment k: v0 s + (v1 - v0) s^2 / (2 L) = H - I0, s = T - T0, solved without cancellation
    const double T0 = p_[k - 1].first, v0 = p_[k - 1].second, L = p_[k].first - T0;
    const double a = 0.5 * (p_[k].second - v0) / L, rest = H - integral_[k - 1];
    const double s = 2 * rest / (v0 + std::sqrt(v0 * v0 + 4 * a * rest));
    return T0 + s;
  }

 private:
  // the index of the first point above T (0: below the table, size: above it)
  std::size_t segment(double T) const {
    return std::size_t(std::lower_bound(p_.begin(), p_.end(), T, [](const auto& p, double x) { return p.first < x; }) -
                       p_.begin());
  }
  std::vector<std::pair<double, double>> p_;
  std::vector<double> integral_;  // the integral from 0 K to each point
};

}  // namespace rk
