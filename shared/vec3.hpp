// Small fixed-size vector type used at input boundaries (scene, geometry). Hot loops use raw SoA arrays.
#pragma once
#include <array>
#include <cmath>

namespace rk {

using Vec3 = std::array<double, 3>;

inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }

}  // namespace rk
