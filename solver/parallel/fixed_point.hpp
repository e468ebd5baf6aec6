// Deterministic sums: force contributions are converted to fixed point and accumulated in 64-bit
// integers. Integer addition is associative, so a particle's force is bitwise the same whatever the
// order of its contributions and however the points are split over ranks: the answer does not
// depend on the rank count (docs/decisions.md, "Rank-count independence by fixed-point force sums").
// The scale is set each step from a global bound B on the contributions, |x| <= B, and the headroom
// h, the bits for the most contributions any particle receives (force_headroom: counted over all
// ranks, so it does not depend on the partition either): |x * scale| < 2^(62-h); resolution
// B * 2^(h-62) (2^-53 B at 500 contributions), the rounding of a double sum of the same terms; the
// internal force's sums take h >= 12 (rk/row3.hpp kRowHeadroom: one add rounds their terms). A
// step whose every term, at its bound, could sum past int64 takes more bits (step_headroom), so no
// sum can overflow.
#pragma once
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace rk {

using Fixed = std::int64_t;

struct FixedScale {
  double to_fixed = 1, to_double = 1;
  static FixedScale for_bound(double bound, int headroom) {
    if (!(bound > 0) || !std::isfinite(bound)) return {};
    const int e = std::ilogb(bound) + 1;  // bound < 2^e
    // at most 2^1023, a finite double: a bound below about 2^-960 would make the scale infinite
    const int p = std::min(62 - headroom - e, std::numeric_limits<double>::max_exponent - 1);
    return {std::ldexp(1.0, p), std::ldexp(1.0, -p)};
  }
  Fixed fixed(double x) const { return truncate(x * to_fixed); }
  static Fixed truncate(double scaled) { return Fixed(scaled); }  // scaled = x * to_fixed
  double real(Fixed a) const { return double(a) * to_double; }
};

// Bits that hold `terms` contributions: 2^headroom > terms.
inline int headroom_bits(std::int64_t terms) { return int(std::bit_width(std::uint64_t(terms))); }

// The most terms a particle's force sum receives in a step, over all ranks: the points' internal
// forces (each at most the step's force bound) and the contacts (each at most the contact bound).
struct ForceTerms {
  std::int64_t internal = 0, contact = 0;
};

// The headroom of a step's force sums: `headroom` (the scale's resolution), raised while the worst
// sum at it could leave int64. With B < 2^e the scale is 2^(62 - h - e), so the worst sum, every
// term at its bound and all of one sign, is W 2^(62 - h) with W = (internal bound + contact
// contact_bound) / 2^e; it fits while W < 2^(h + 1). Integer sums that cannot overflow: no undefined
// behaviour, whatever the contacts do.
inline int step_headroom(int headroom, const ForceTerms& terms, double bound, double contact_bound) {
  if (!(bound > 0) || !std::isfinite(bound)) return headroom;  // no scale (FixedScale::for_bound)
  const int e = std::ilogb(bound) + 1;
  const double worst = (double(terms.internal) * bound + double(terms.contact) * std::min(contact_bound, bound)) *
                       std::ldexp(1.0, -e) * (1 + 1e-12);  // the rounding of this estimate, and more
  int h = headroom;
  while (h < 62 && worst >= std::ldexp(1.0, h + 1)) ++h;
  return h;
}

}  // namespace rk
