// A row of three doubles updated as one: F_i. += u_i grad N and f += w P grad N in the neighbour
// loops. With AVX it is a four-wide vector (lane 3 is 0), one register and one instruction per
// update; without, three scalars (a vector of four there takes two registers and is slower:
// docs/decisions.md, "Vector registers in the hot loops").
#pragma once
#include <cmath>
#include <cstdint>
#ifdef __AVX__
#include <immintrin.h>
#endif

namespace rk {

// The fixed-point headroom of the force loop's sums, at least: a term at its bound B < 2^e is below
// 2^(62 - 12) = 2^50 after the scale (parallel/fixed_point.hpp), within round_row's exact range with a
// factor 2 to spare for a bound's own rounding. The resolution B 2^(h - 62) is then 2^-50 B where fewer
// than 2^12 terms meet at a particle (8x a double's rounding of B, and of the sums' 2^-53 B before).
constexpr int kRowHeadroom = 12;

#ifdef __AVX__
using Row3 = double __attribute__((vector_size(32)));
using FixedRow3 = long long __attribute__((vector_size(32)));
inline Row3 make_row3(double a, double b, double c) { return Row3{a, b, c, 0.0}; }
#if defined(__AVX512DQ__) && defined(__AVX512VL__)
// to the nearest integer, ties to even (the rounding mode's default): one instruction
inline FixedRow3 round_row(Row3 r) { return FixedRow3(_mm256_cvtpd_epi64(__m256d(r))); }
#else
// Without AVX-512 there is no packed double -> int64 conversion (GCC converted lane by lane through the
// scalar unit, 18 instructions). Below 2^51, x + 1.5 2^52 lies in the binade of 2^52, whose doubles are
// the integers: the add rounds x to the nearest (ties to even) and the sum's bits less 1.5 2^52's are
// that integer. Two instructions; the force loop's scale keeps its terms below 2^50 (kRowHeadroom).
// Unit test: std::llrint's, bit for bit.
inline FixedRow3 round_row(Row3 x) {
  constexpr double kRound = 0x1.8p52;
  return (FixedRow3)(x + kRound) - (FixedRow3)(Row3{} + kRound);
}
#endif
// acc[0 .. 4) += f, lane 3 included (f's is 0): one load, add and store, so a particle's
// accumulators are four apart (State::partial)
using Fixed4 = std::int64_t __attribute__((vector_size(32), aligned(8)));  // (stores alias int64_t only)
inline void add_row(std::int64_t* acc, FixedRow3 f) {
  *reinterpret_cast<Fixed4*>(acc) += __builtin_convertvector(f, Fixed4);
}
#else
struct Row3 {
  double v[3];
  double operator[](int i) const { return v[i]; }
  Row3& operator+=(const Row3& o) {
    for (int i = 0; i < 3; ++i) v[i] += o.v[i];
    return *this;
  }
  friend Row3 operator+(Row3 a, const Row3& b) { return a += b; }
  friend Row3 operator*(double s, Row3 a) {
    for (double& x : a.v) x *= s;
    return a;
  }
  friend Row3 operator*(Row3 a, double s) { return s * a; }
};
struct FixedRow3 {
  long long v[3];
  long long operator[](int i) const { return v[i]; }
};
inline Row3 make_row3(double a, double b, double c) { return Row3{{a, b, c}}; }
inline FixedRow3 round_row(Row3 r) { return {{std::llrint(r.v[0]), std::llrint(r.v[1]), std::llrint(r.v[2])}}; }
inline void add_row(std::int64_t* acc, FixedRow3 f) {
  for (int i = 0; i < 3; ++i) acc[i] += f.v[i];
}
#endif

inline Row3 load_row3(const double* p) { return make_row3(p[0], p[1], p[2]); }
// The row at p padded to four (p[3] is 0): on AVX one load.
#ifdef __AVX__
using Double4 = double __attribute__((vector_size(32), aligned(8)));
inline Row3 load_row4(const double* p) { return *reinterpret_cast<const Double4*>(p); }
#else
inline Row3 load_row4(const double* p) { return make_row3(p[0], p[1], p[2]); }
#endif

}  // namespace rk
