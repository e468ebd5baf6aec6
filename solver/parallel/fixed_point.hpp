// Deterministic sums: force contributions are converted to fixed point and accumulated in 64-bit
// integers. Integer addition is associative, so a particle's force is bitwise the same whatever the
// order of its contributions and however the points are split over ranks: the answer does not
// depend on the rank count (docs/decisions.md, "Rank-count independence by fixed-point force sums").
// The scale is set each step from a global bound B on the contributions, |x| <= B, and the headroom
// h, the bits for the most contributions any particle receives (force_headroom: counted over all
// ranks, so it does not depend on the partition either): |x * scale| < 2^(62-h), so no sum can
// overflow; resolution B * 2^(h-62) (2^-53 B at 500 contributions), the rounding of a double sum of
// the same terms.
#pragma once
#include <bit>
#include <cmath>
#include <cstdint>

namespace rk {

using Fixed = std::int64_t;

struct FixedScale {
  double to_fixed = 1, to_double = 1;
  static FixedScale for_bound(double bound, int headroom) {
    if (!(bound > 0) || !std::isfinite(bound)) return {};
    const int e = std::ilogb(bound) + 1;  // bound < 2^e
    return {std::ldexp(1.0, 62 - headroom - e), std::ldexp(1.0, e + headroom - 62)};
  }
  Fixed fixed(double x) const { return truncate(x * to_fixed); }
  static Fixed truncate(double scaled) { return Fixed(scaled); }  // scaled = x * to_fixed
  double real(Fixed a) const { return double(a) * to_double; }
};

// Bits that hold `terms` contributions: 2^headroom > terms.
inline int headroom_bits(std::int64_t terms) { return int(std::bit_width(std::uint64_t(terms))); }

}  // namespace rk
