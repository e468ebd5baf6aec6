// Deterministic sums: force contributions are converted to 64-bit fixed point and accumulated in
// 128-bit integers. Integer addition is associative, so a particle's force is bitwise the same
// whatever the order of its contributions and however the points are split over ranks: the answer
// does not depend on the rank count (DESIGN.md section 4). The scale is set each step from a global
// bound B on the contributions, |x| <= B, so that |x * scale| < 2^61 (resolution B * 2^-61).
#pragma once
#include <cmath>
#include <cstdint>

namespace rk {

__extension__ typedef __int128 int128;

struct FixedScale {
  double to_fixed = 1, to_double = 1;
  static FixedScale for_bound(double bound) {
    if (!(bound > 0) || !std::isfinite(bound)) return {};
    const int e = std::ilogb(bound) + 1;  // bound < 2^e
    return {std::ldexp(1.0, 61 - e), std::ldexp(1.0, e - 61)};
  }
  int128 fixed(double x) const { return truncate(x * to_fixed); }
  static int128 truncate(double scaled) { return int128(std::int64_t(scaled)); }  // scaled = x * to_fixed
  double real(int128 a) const { return double(a) * to_double; }
};

}  // namespace rk
