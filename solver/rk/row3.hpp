// A row of three doubles updated as one: F_i. += u_i grad N and f += w P grad N in the neighbour
// loops. With AVX it is a four-wide vector (lane 3 is 0), one register and one instruction per
// update; without, three scalars (a vector of four there takes two registers and is slower:
// docs/decisions.md, "Vector registers in the hot loops").
#pragma once
#include <cstdint>
#ifdef __AVX__
#include <immintrin.h>
#endif

namespace rk {

#ifdef __AVX__
using Row3 = double __attribute__((vector_size(32)));
using FixedRow3 = long long __attribute__((vector_size(32)));
inline Row3 make_row3(double a, double b, double c) { return Row3{a, b, c, 0.0}; }
#if defined(__AVX512DQ__) && defined(__AVX512VL__)
inline FixedRow3 truncate_row(Row3 r) { return __builtin_convertvector(r, FixedRow3); }  // parallel/fixed_point.hpp
#elif defined(__AVX2__)
// AVX2 has no packed double -> int64 conversion (the compiler converts lane by lane through the
// scalar unit: 18 instructions); the same truncation from the bits, exact for |x| < 2^63 (the force
// terms' bound, parallel/fixed_point.hpp): the mantissa with its leading 1 shifted by the exponent
// (a shift by 64 or more gives 0: below 1 truncates to 0), then the sign. Unit test: bitwise the
// scalar conversion's.
inline FixedRow3 truncate_row(Row3 r) {
  const __m256i bits = _mm256_castpd_si256(__m256d(r));
  const __m256i e = _mm256_and_si256(_mm256_srli_epi64(bits, 52), _mm256_set1_epi64x(0x7ff));
  const __m256i m = _mm256_or_si256(_mm256_and_si256(bits, _mm256_set1_epi64x((1LL << 52) - 1)), _mm256_set1_epi64x(1LL << 52));
  const __m256i bias = _mm256_set1_epi64x(1075);  // the exponent of 2^52: the mantissa read as an integer
  const __m256i magnitude = _mm256_or_si256(_mm256_sllv_epi64(m, _mm256_sub_epi64(e, bias)),
                                            _mm256_srlv_epi64(m, _mm256_sub_epi64(bias, e)));
  const __m256i negative = _mm256_sub_epi64(_mm256_setzero_si256(), _mm256_srli_epi64(bits, 63));  // all ones where x < 0
  return FixedRow3(_mm256_sub_epi64(_mm256_xor_si256(magnitude, negative), negative));
}
#else
inline FixedRow3 truncate_row(Row3 r) { return __builtin_convertvector(r, FixedRow3); }  // parallel/fixed_point.hpp
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
inline FixedRow3 truncate_row(Row3 r) { return {{(long long)r.v[0], (long long)r.v[1], (long long)r.v[2]}}; }
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
