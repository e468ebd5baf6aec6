// Window functions phi(z), z = r / a (a = support radius), and their derivatives dphi/dz.
// Only the scale matters: the RK correction restores the reproducing conditions.
#pragma once
#include <string>

#include "error.hpp"

namespace rk {

enum class Kernel { cubic_bspline, quartic_spline };

inline Kernel parse_kernel(const std::string& name) {
  if (name == "cubic_bspline") return Kernel::cubic_bspline;
  if (name == "quartic_spline") return Kernel::quartic_spline;
  throw Error("unknown kernel '" + name + "'");
}

// Cubic B-spline (C2), Liu, Jun & Zhang 1995, eq. (2.10) in normalized form.
inline void cubic_bspline(double z, double& phi, double& dphi) {
  if (z <= 0.5) {
    phi = 2.0 / 3.0 - 4.0 * z * z + 4.0 * z * z * z;
    dphi = -8.0 * z + 12.0 * z * z;
  } else if (z < 1.0) {
    const double w = 1.0 - z;
    phi = 4.0 / 3.0 * w * w * w;
    dphi = -4.0 * w * w;
  } else {
    phi = dphi = 0.0;
  }
}

// Quartic spline (C2): 1 - 6z^2 + 8z^3 - 3z^4.
inline void quartic_spline(double z, double& phi, double& dphi) {
  if (z < 1.0) {
    phi = 1.0 - 6.0 * z * z + 8.0 * z * z * z - 3.0 * z * z * z * z;
    dphi = -12.0 * z + 24.0 * z * z - 12.0 * z * z * z;
  } else {
    phi = dphi = 0.0;
  }
}

inline void window(Kernel k, double z, double& phi, double& dphi) {
  if (k == Kernel::cubic_bspline)
    cubic_bspline(z, phi, dphi);
  else
    quartic_spline(z, phi, dphi);
}

}  // namespace rk
