// A row of three doubles held in a four-wide vector (one AVX register, two SSE2 registers): the
// neighbour loops update all three components of a row with one instruction stream. Lane 3 is 0.
#pragma once
namespace rk {

using Row3 = double __attribute__((vector_size(32)));
using FixedRow3 = long long __attribute__((vector_size(32)));  // truncated to integers (fixed_point.hpp)

inline Row3 load_row3(const double* p) { return Row3{p[0], p[1], p[2], 0.0}; }

}  // namespace rk
