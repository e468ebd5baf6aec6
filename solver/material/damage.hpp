// Ductile damage criteria, integrated over the plastic strain at each integration point:
//   normalized Cockcroft-Latham (Oh, Chen & Kobayashi, J. Eng. Ind. 101 (1979) 36):
//     D = int max(sigma_1, 0) / sigma_eq d ep,
//   Brozzo (Brozzo, De Luca & Rendina, 7th IDDRG Congress, 1972):
//     D = int 2 max(sigma_1, 0) / (3 (sigma_1 - sigma_m)) d ep,
//   Oyane (Oyane, Sato, Okimoto & Shima, J. Mech. Work. Technol. 4 (1980) 65), whose fracture
//   condition int (1 + sigma_m / (a sigma_eq)) d ep = b rkforge integrates times the material
//   constant a (the normalized form, critical value a b), taking no increment where the integrand is
//   negative (pressure closes no void that then reopens as damage):
//     D = int max(sigma_m / sigma_eq + a, 0) d ep,
// sigma_1 the largest principal stress, sigma_eq von Mises', sigma_m the mean stress. All are ratios
// of stresses, so the Kirchhoff stress serves as well as Cauchy's (they differ by J). Uniaxial tension
// gives dD = d ep (Cockcroft-Latham, Brozzo) and (1/3 + a) d ep (Oyane); uniaxial compression 0, 0 and
// max(a - 1/3, 0) d ep; pure shear 1/sqrt 3, 2/3 and a.
#pragma once
#include <algorithm>
#include <cmath>
#include <iterator>

#include "result_frame.hpp"

namespace rk {

// The criteria, in the order of the frames' fields (shared/result_frame.hpp): Cockcroft-Latham,
// Brozzo, Oyane; State::damage holds this many per point.
inline constexpr std::size_t kDamageCriteria = std::size(kDamageFields);

// The largest eigenvalue of the symmetric tensor s (Voigt xx, yy, zz, xy, yz, zx), by the
// trigonometric solution of the characteristic cubic.
inline double largest_principal(const double s[6]) {
  const double m = (s[0] + s[1] + s[2]) / 3;
  const double a = s[0] - m, b = s[1] - m, c = s[2] - m;
  const double off = s[3] * s[3] + s[4] * s[4] + s[5] * s[5];
  const double p2 = (a * a + b * b + c * c + 2 * off) / 6;  // (|dev s|^2 / 6)
  if (!(p2 > 1e-300)) return m;
  const double p = std::sqrt(p2);
  // det(dev s) / (2 p^3), clamped to the cosine's range against round-off
  const double det = a * (b * c - s[4] * s[4]) - s[3] * (s[3] * c - s[4] * s[5]) + s[5] * (s[3] * s[4] - b * s[5]);
  const double r = std::clamp(det / (2 * p2 * p), -1.0, 1.0);
  return m + 2 * p * std::cos(std::acos(r) / 3);
}

struct DamageIncrement {
  double cockcroft_latham = 0, brozzo = 0, oyane = 0;
};

// The criteria's increments over a plastic strain increment dep at stress s (Voigt); oyane_a: Oyane's a.
inline DamageIncrement damage_increment(const double s[6], double dep, double oyane_a = 0) {
  DamageIncrement d;
  const double m = (s[0] + s[1] + s[2]) / 3;
  const double a = s[0] - m, b = s[1] - m, c = s[2] - m;
  const double eq = std::sqrt(1.5 * (a * a + b * b + c * c + 2 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5])));
  if (!(dep > 0) || !(eq > 0)) return d;
  d.oyane = std::max(m / eq + oyane_a, 0.0) * dep;
  const double s1 = std::max(largest_principal(s), 0.0);
  if (s1 == 0) return d;
  d.cockcroft_latham = s1 / eq * dep;
  // sigma_1 - sigma_m >= 0 always (the largest principal is at least the mean); > 0 where eq > 0
  d.brozzo = 2 * s1 / (3 * (largest_principal(s) - m)) * dep;
  return d;
}

}  // namespace rk
