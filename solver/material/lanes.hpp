// Several integration points at once: a Lane holds one double per point (GCC/Clang vector extension,
// one register wide: 2 points with SSE2, 4 with AVX, 8 with AVX-512; CMake option RK_NATIVE), so the 3x3 algebra
// of the stress update runs kLanes points per instruction stream. Each lane computes exactly what it
// would alone: no result depends on which other points share its batch (rank independence).
// Symmetric tensors in Voigt order xx, yy, zz, xy, yz, zx; full tensors row-major.
#pragma once
#include <cmath>
#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace rk {

#if defined(__AVX512F__)
constexpr int kLanes = 8;  // one 512-bit register: the 8 points of a 2x2x2 Gauss cell
#elif defined(__AVX__)
constexpr int kLanes = 4;  // one 256-bit register
#else
constexpr int kLanes = 2;  // one SSE2 register (4 lanes there spill: docs/decisions.md, "Speed")
#endif
using Lane = double __attribute__((vector_size(8 * kLanes)));
using LaneMask = long long __attribute__((vector_size(8 * kLanes)));  // -1 true, 0 false

inline Lane splat(double x) { return Lane{} + x; }
// m ? a : b lane by lane, as a bitwise blend (casts between vectors of one size keep the bits;
// the vector ?: compiles to per-element branches without AVX)
inline Lane select(LaneMask m, Lane a, Lane b) { return (Lane)(((LaneMask)a & m) | ((LaneMask)b & ~m)); }
// one instruction for the lanes (the per-lane form keeps a scalar square root and its errno check):
// IEEE square roots, correctly rounded, so the bits are the per-lane ones
inline Lane sqrt(Lane x) {
#if defined(__AVX512F__)
  return (Lane)_mm512_mask_sqrt_pd((__m512d)x, __mmask8(0xff), (__m512d)x);  // (the unmasked form warns in GCC 12)
#elif defined(__AVX__)
  return (Lane)_mm256_sqrt_pd((__m256d)x);
#elif defined(__SSE2__)
  return (Lane)_mm_sqrt_pd((__m128d)x);
#else
  for (int l = 0; l < kLanes; ++l) x[l] = __builtin_sqrt(x[l]);
  return x;
#endif
}
// whether a lane is true: one test of the register (the per-lane form branches on every lane)
inline bool any(LaneMask m) {
#if defined(__AVX512F__)
  return _mm512_test_epi64_mask((__m512i)m, (__m512i)m) != 0;
#elif defined(__AVX__)
  return _mm256_movemask_pd((__m256d)m) != 0;  // the sign bits: a true lane is -1
#elif defined(__SSE2__)
  return _mm_movemask_pd((__m128d)m) != 0;
#else
  for (int l = 0; l < kLanes; ++l)
    if (m[l]) return true;
  return false;
#endif
}

// The lanes below n true, the rest false.
inline LaneMask first_lanes(int n) {
  static const LaneMask index = [] {
    LaneMask m{};
    for (int l = 0; l < kLanes; ++l) m[l] = l;
    return m;
  }();
  return index < (LaneMask{} + n);
}
// v with its lanes from n on set to `rest` (a partial batch's lanes at rest; v itself where n = kLanes)
inline Lane rest_past(Lane v, int n, double rest) { return n == kLanes ? v : select(first_lanes(n), v, splat(rest)); }

// kLanes consecutive values x[0 .. kLanes) across the lanes: one vector load (a lane written one at a
// time through memory and then read as a vector stalls its load until the writes land).
inline Lane load_lanes(const double* x) {
  Lane v;
  __builtin_memcpy(&v, x, sizeof v);
  return v;
}
// The first n of them (0 < n <= kLanes), the other lanes 0: a masked load, nothing past x[n - 1] read.
inline Lane load_lanes(const double* x, int n) {
  if (n == kLanes) return load_lanes(x);
#if defined(__AVX512F__)
  return (Lane)_mm512_maskz_loadu_pd(__mmask8((1u << n) - 1), x);
#elif defined(__AVX__)
  return (Lane)_mm256_maskload_pd(x, (__m256i)first_lanes(n));
#else
  Lane v{};
  for (int l = 0; l < n; ++l) v[l] = x[l];
  return v;
#endif
}
// x[0], x[stride], .. x[(kLanes - 1) stride] across the lanes, built in the registers (for the same reason;
// a gather instruction measured slower): component i of kLanes consecutive points of `stride` values.
template <int stride>
inline Lane strided_lanes(const double* x) {
#if defined(__AVX512F__)
  return (Lane)_mm512_set_pd(x[7 * stride], x[6 * stride], x[5 * stride], x[4 * stride], x[3 * stride], x[2 * stride],
                             x[stride], x[0]);
#elif defined(__AVX__)
  return (Lane)_mm256_set_pd(x[3 * stride], x[2 * stride], x[stride], x[0]);
#elif defined(__SSE2__)
  return (Lane)_mm_set_pd(x[stride], x[0]);
#else
  Lane v;
  for (int l = 0; l < kLanes; ++l) v[l] = x[l * stride];
  return v;
#endif
}

// v[i] = component i of the n <= kLanes consecutive points of `stride` values at x (strided_lanes of
// each component; the lanes past n 0), and back (nothing past the n points' rows read or written): with
// AVX the points' rows are read and written as vectors and transposed 4x4 in the registers, four points
// at a time (with 8 lanes, two fours joined into each register), instead of a lane insert or extract for
// every value; with 2 lanes component by component.
#if defined(__AVX__)
inline void transpose4(__m256d& a, __m256d& b, __m256d& c, __m256d& d) {
  const __m256d ab_lo = _mm256_unpacklo_pd(a, b), ab_hi = _mm256_unpackhi_pd(a, b);  // a0 b0 a2 b2, a1 b1 a3 b3
  const __m256d cd_lo = _mm256_unpacklo_pd(c, d), cd_hi = _mm256_unpackhi_pd(c, d);
  a = _mm256_permute2f128_pd(ab_lo, cd_lo, 0x20), b = _mm256_permute2f128_pd(ab_hi, cd_hi, 0x20);
  c = _mm256_permute2f128_pd(ab_lo, cd_lo, 0x31), d = _mm256_permute2f128_pd(ab_hi, cd_hi, 0x31);
}
// the first n <= 4 of the four points at x to v[i] = their component i (a missing point's 0)
template <int stride>
inline void four_to_columns(const double* x, __m256d* v, int n) {
  static_assert(stride % 4 == 1 || stride % 4 == 2);
  const __m256d zero = _mm256_setzero_pd();
  const __m128d zero2 = _mm_setzero_pd();
  auto row = [&](int l, int j) { return l < n ? _mm256_loadu_pd(x + l * stride + j) : zero; };
  for (int j = 0; j + 4 <= stride; j += 4) {
    __m256d a = row(0, j), b = row(1, j), c = row(2, j), d = row(3, j);
    transpose4(a, b, c, d);
    v[j] = a, v[j + 1] = b, v[j + 2] = c, v[j + 3] = d;
  }
  constexpr int last = stride - stride % 4;
  auto at = [&](int l) { return l < n ? x[l * stride + last] : 0.0; };
  if constexpr (stride % 4 == 1) {
    v[last] = _mm256_set_pd(at(3), at(2), at(1), at(0));
  } else {  // the last two components: a pair a point
    auto pair = [&](int l) { return l < n ? _mm_loadu_pd(x + l * stride + last) : zero2; };
    const __m256d even = _mm256_set_m128d(pair(2), pair(0)), odd = _mm256_set_m128d(pair(3), pair(1));
    v[last] = _mm256_unpacklo_pd(even, odd), v[last + 1] = _mm256_unpackhi_pd(even, odd);
  }
}
// and back, the first n <= 4 points
template <int stride>
inline void columns_to_four(const __m256d* v, double* x, int n) {
  static_assert(stride % 4 == 1 || stride % 4 == 2);
  for (int j = 0; j + 4 <= stride; j += 4) {
    __m256d r[4] = {v[j], v[j + 1], v[j + 2], v[j + 3]};
    transpose4(r[0], r[1], r[2], r[3]);
    for (int l = 0; l < 4; ++l)
      if (l < n) _mm256_storeu_pd(x + l * stride + j, r[l]);
  }
  constexpr int last = stride - stride % 4;
  if constexpr (stride % 4 == 1) {
    const __m128d lo = _mm256_castpd256_pd128(v[last]), hi = _mm256_extractf128_pd(v[last], 1);
    if (n > 0) _mm_storel_pd(x + last, lo);
    if (n > 1) _mm_storeh_pd(x + stride + last, lo);
    if (n > 2) _mm_storel_pd(x + 2 * stride + last, hi);
    if (n > 3) _mm_storeh_pd(x + 3 * stride + last, hi);
  } else {
    const __m256d even = _mm256_unpacklo_pd(v[last], v[last + 1]);  // points 0 and 2
    const __m256d odd = _mm256_unpackhi_pd(v[last], v[last + 1]);
    if (n > 0) _mm_storeu_pd(x + last, _mm256_castpd256_pd128(even));
    if (n > 1) _mm_storeu_pd(x + stride + last, _mm256_castpd256_pd128(odd));
    if (n > 2) _mm_storeu_pd(x + 2 * stride + last, _mm256_extractf128_pd(even, 1));
    if (n > 3) _mm_storeu_pd(x + 3 * stride + last, _mm256_extractf128_pd(odd, 1));
  }
}
#endif
template <int stride>
inline void strided_to_lanes(const double* x, Lane* v, int n = kLanes) {
#if defined(__AVX512F__)
  __m256d first[stride], second[stride];
  four_to_columns<stride>(x, first, n < 4 ? n : 4);
  if (n > 4) four_to_columns<stride>(x + 4 * stride, second, n - 4);
  else
    for (int i = 0; i < stride; ++i) second[i] = _mm256_setzero_pd();
  for (int i = 0; i < stride; ++i) v[i] = __builtin_shufflevector(first[i], second[i], 0, 1, 2, 3, 4, 5, 6, 7);
#elif defined(__AVX__)
  __m256d c[stride];
  four_to_columns<stride>(x, c, n);
  for (int i = 0; i < stride; ++i) v[i] = (Lane)c[i];
#else
  for (int i = 0; i < stride; ++i) {
    if (n == kLanes) {
      v[i] = strided_lanes<stride>(x + i);
      continue;
    }
    v[i] = Lane{};
    for (int l = 0; l < n; ++l) v[i][l] = x[l * stride + i];
  }
#endif
}
template <int stride>
inline void lanes_to_strided(const Lane* v, double* x, int n = kLanes) {
#if defined(__AVX512F__)
  __m256d first[stride], second[stride];
  for (int i = 0; i < stride; ++i)
    first[i] = __builtin_shufflevector(v[i], v[i], 0, 1, 2, 3), second[i] = __builtin_shufflevector(v[i], v[i], 4, 5, 6, 7);
  columns_to_four<stride>(first, x, n < 4 ? n : 4);
  if (n > 4) columns_to_four<stride>(second, x + 4 * stride, n - 4);
#elif defined(__AVX__)
  __m256d c[stride];
  for (int i = 0; i < stride; ++i) c[i] = (__m256d)v[i];
  columns_to_four<stride>(c, x, n);
#else
  for (int l = 0; l < n; ++l)
    for (int i = 0; i < stride; ++i) x[l * stride + i] = v[i][l];
#endif
}
// x[0 .. kLanes) = v: one vector store
inline void store_lanes(double* x, Lane v) { __builtin_memcpy(x, &v, sizeof v); }
// x[0 .. n) = the first n lanes of v: a masked store, nothing past x[n - 1] written
inline void store_lanes(double* x, Lane v, int n) {
  if (n == kLanes) return store_lanes(x, v);
#if defined(__AVX512F__)
  _mm512_mask_storeu_pd(x, __mmask8((1u << n) - 1), (__m512d)v);
#elif defined(__AVX__)
  _mm256_maskstore_pd(x, (__m256i)first_lanes(n), (__m256d)v);
#else
  for (int l = 0; l < n; ++l) x[l] = v[l];
#endif
}

// r^(1/3) for r near 1 (the F-bar ratio Jbar/J): two Newton steps from 1 + e/3 - e^2/9, e = r - 1,
// reach round-off for |e| <= 0.1 (initial error 5e^3/81, squared by each step); lanes farther out
// take std::cbrt. Replaces a libm call per point (docs/decisions.md, "Speed").
inline Lane cube_root_near_one(Lane r) {
  const Lane e = r - 1;
  Lane x = 1 + e * (1.0 / 3 - e * (1.0 / 9));
  for (int i = 0; i < 2; ++i) x -= (x * x * x - r) / (3 * x * x);
  const LaneMask far = (e > 0.1) | (e < -0.1);
  if (!any(far)) return x;
  for (int l = 0; l < kLanes; ++l)
    if (far[l]) x[l] = std::cbrt(r[l]);
  return x;
}

// e^x and ln x lane by lane, within 2 ulp of libm (tests/unit/test_j2.cpp): the rate-dependent laws'
// flow stress and their return's Newton step take kLanes points per instruction stream instead of a
// libm call per point and iteration (docs/decisions.md, "e^x and ln x across the lanes for the
// flow-stress laws").
// exp: x = k ln 2 + r with ln 2 in two parts (Cody & Waite: k ln2_hi is exact), |r| <= ln 2 / 2, e^r by
// its Taylor series to r^13 (the next term is below 5e-18), times 2^k built in the exponent bits;
// lanes with |x| > 700 (or NaN) take std::exp.
inline Lane exp(Lane x) {
  constexpr double ln2_hi = 6.93147180369123816490e-01, ln2_lo = 1.90821492927058770002e-10;
  constexpr double round = 0x1.8p52;  // adding it rounds |y| < 2^51 to an integer
  const Lane k = (x * 1.4426950408889634 + round) - round;
  const Lane r = (x - k * ln2_hi) - k * ln2_lo;
  // 1 + r (1 + r S), S = sum_n>=2 r^(n-2) / n! by Estrin's scheme: pairs c_n + c_n+1 r joined by r^2 and
  // r^4 (six multiply-adds deep instead of Horner's thirteen: a return waits on the series' latency, not
  // its flops); the last two steps as Horner's, so the rounding near 1 is its (mean error 0.06 ulp both)
  constexpr double c[12] = {1.0 / 2, 1.0 / 6, 1.0 / 24, 1.0 / 120, 1.0 / 720, 1.0 / 5040, 1.0 / 40320,
                            1.0 / 362880, 1.0 / 3628800, 1.0 / 39916800, 1.0 / 479001600, 1.0 / 6227020800};
  const Lane r2 = r * r, r4 = r2 * r2;
  const Lane a0 = c[0] + c[1] * r, a1 = c[2] + c[3] * r, a2 = c[4] + c[5] * r, a3 = c[6] + c[7] * r,
             a4 = c[8] + c[9] * r, a5 = c[10] + c[11] * r;
  const Lane S = (a0 + a1 * r2) + ((a2 + a3 * r2) + (a4 + a5 * r2) * r4) * r4;
  const Lane p = 1 + r * (1 + r * S);
  const LaneMask bits = (__builtin_convertvector(k, LaneMask) + 1023) << 52;
  Lane y = p * (Lane)bits;
  if (!any(~((x <= 700) & (x >= -700)))) return y;  // (NaN lanes are out of range)
  for (int l = 0; l < kLanes; ++l)
    if (!(std::abs(x[l]) <= 700)) y[l] = std::exp(x[l]);
  return y;
}

// ln: x = m 2^e with m in [sqrt(1/2), sqrt(2)) from the bits, f = m - 1, and as fdlibm computes it,
// ln(1 + f) = f - (f^2/2 - s (f^2/2 + R)), s = f / (2 + f), R = sum_k>=1 2 s^2k / (2k + 1) (Taylor to
// k = 11: |s| <= 0.172, the next term below 1e-18; by Estrin's scheme, as exp's); lanes not positive,
// normal and finite take std::log.
inline Lane log(Lane x) {
  constexpr double ln2_hi = 6.93147180369123816490e-01, ln2_lo = 1.90821492927058770002e-10;
  const LaneMask bits = (LaneMask)x;
  LaneMask e = ((bits >> 52) & 0x7ff) - 1023;
  Lane m = (Lane)((bits & 0x000fffffffffffffLL) | 0x3ff0000000000000LL);  // in [1, 2)
  const LaneMask high = m > 1.4142135623730951;
  m = select(high, 0.5 * m, m);
  e -= high;  // (true is -1)
  const Lane f = m - 1, s = f / (2 + f), z = s * s, half_f2 = 0.5 * f * f;
  // R = z sum_k=1..11 2 z^(k-1) / (2k + 1)
  constexpr double c[11] = {2.0 / 3, 2.0 / 5, 2.0 / 7, 2.0 / 9, 2.0 / 11, 2.0 / 13, 2.0 / 15, 2.0 / 17, 2.0 / 19, 2.0 / 21, 2.0 / 23};
  const Lane z2 = z * z, z4 = z2 * z2, z8 = z4 * z4;
  const Lane a0 = c[0] + c[1] * z, a1 = c[2] + c[3] * z, a2 = c[4] + c[5] * z, a3 = c[6] + c[7] * z, a4 = c[8] + c[9] * z;
  const Lane b0 = a0 + a1 * z2, b1 = a2 + a3 * z2, b2 = a4 + c[10] * z2;
  const Lane R = z * ((b0 + b1 * z4) + b2 * z8);
  const Lane ef = __builtin_convertvector(e, Lane);
  Lane y = ef * ln2_hi - ((half_f2 - (s * (half_f2 + R) + ef * ln2_lo)) - f);
  if (!any(~((x >= 0x1p-1022) & (x <= 0x1.fffffffffffffp1023)))) return y;
  for (int l = 0; l < kLanes; ++l)
    if (!(x[l] >= 0x1p-1022 && x[l] <= 0x1.fffffffffffffp1023)) y[l] = std::log(x[l]);
  return y;
}

struct Sym {  // symmetric 3x3, Voigt order
  Lane v[6];
};
struct Mat {  // 3x3, row-major
  Lane v[9];
};

// to = from, component by component: GCC copies a whole Sym (192 bytes with AVX) from a temporary by a
// call to memcpy, whose vzeroupper and call cost more than the six stores from the registers
inline void set(Sym& to, const Sym& from) {
#pragma GCC unroll 6  // (as a loop GCC makes it a memcpy again)
  for (int i = 0; i < 6; ++i) to.v[i] = from.v[i];
}

inline Sym identity_sym(Lane diag) {
  const Lane z{};
  return {{diag, diag, diag, z, z, z}};
}
inline Sym operator*(Lane s, const Sym& a) {
  Sym r;
  for (int i = 0; i < 6; ++i) r.v[i] = s * a.v[i];
  return r;
}
inline Sym operator+(const Sym& a, const Sym& b) {
  Sym r;
  for (int i = 0; i < 6; ++i) r.v[i] = a.v[i] + b.v[i];
  return r;
}
inline Sym select(LaneMask m, const Sym& a, const Sym& b) {
  Sym r;
  for (int i = 0; i < 6; ++i) r.v[i] = select(m, a.v[i], b.v[i]);
  return r;
}
inline Lane trace(const Sym& a) { return a.v[0] + a.v[1] + a.v[2]; }
inline Lane norm2(const Sym& a) {  // Frobenius, squared
  return a.v[0] * a.v[0] + a.v[1] * a.v[1] + a.v[2] * a.v[2] +
         2 * (a.v[3] * a.v[3] + a.v[4] * a.v[4] + a.v[5] * a.v[5]);
}

// A B for COMMUTING symmetric A, B (polynomials in the same tensor): the product is symmetric.
inline Sym commuting_product(const Sym& A, const Sym& B) {
  const Lane *a = A.v, *b = B.v;
  return {{a[0] * b[0] + a[3] * b[3] + a[5] * b[5], a[3] * b[3] + a[1] * b[1] + a[4] * b[4],
           a[5] * b[5] + a[4] * b[4] + a[2] * b[2], a[0] * b[3] + a[3] * b[1] + a[5] * b[4],
           a[3] * b[5] + a[1] * b[4] + a[4] * b[2], a[5] * b[0] + a[4] * b[3] + a[2] * b[5]}};
}

inline Sym inverse(const Sym& A) {  // adjugate / det
  const Lane* a = A.v;
  const Lane c0 = a[1] * a[2] - a[4] * a[4], c3 = a[4] * a[5] - a[3] * a[2], c5 = a[3] * a[4] - a[1] * a[5];
  const Lane inv = 1 / (a[0] * c0 + a[3] * c3 + a[5] * c5);
  return {{c0 * inv, (a[0] * a[2] - a[5] * a[5]) * inv, (a[0] * a[1] - a[3] * a[3]) * inv, c3 * inv,
           (a[3] * a[5] - a[0] * a[4]) * inv, c5 * inv}};
}

inline Mat full(const Sym& S) {
  const Lane* s = S.v;
  return {{s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2]}};
}

// F S F^T (transpose = false) or F^T S F (transpose = true)
inline Sym congruence(const Mat& F, const Sym& S, bool transpose) {
  const Mat s = full(S);
  auto f = [&](int i, int j) { return transpose ? F.v[3 * j + i] : F.v[3 * i + j]; };
  Lane A[9];  // f S
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) A[3 * i + j] = f(i, 0) * s.v[j] + f(i, 1) * s.v[3 + j] + f(i, 2) * s.v[6 + j];
  auto c = [&](int i, int j) { return A[3 * i] * f(j, 0) + A[3 * i + 1] * f(j, 1) + A[3 * i + 2] * f(j, 2); };
  return {{c(0, 0), c(1, 1), c(2, 2), c(0, 1), c(1, 2), c(2, 0)}};
}

// Cofactor matrix of F (F^{-T} = cof F / det F); returns det F.
inline Lane cofactor(const Mat& F, Mat& cof) {
  const Lane* f = F.v;
  for (int r = 0; r < 3; ++r) {  // row r = row (r+1) x row (r+2)
    const Lane *a = f + 3 * ((r + 1) % 3), *b = f + 3 * ((r + 2) % 3);
    cof.v[3 * r] = a[1] * b[2] - a[2] * b[1];
    cof.v[3 * r + 1] = a[2] * b[0] - a[0] * b[2];
    cof.v[3 * r + 2] = a[0] * b[1] - a[1] * b[0];
  }
  return f[0] * cof.v[0] + f[1] * cof.v[1] + f[2] * cof.v[2];
}

}  // namespace rk
