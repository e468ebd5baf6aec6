// Reproducing kernel shape functions (Wang et al. 2007, eq. (3)):
//   N_I(X) = C(X; X - X_I) phi_a(X - X_I) V_I,   C = H^T(0) M^{-1}(X) H(X - X_I),
//   M(X)   = sum_I H(X - X_I) H^T(X - X_I) phi_a(X - X_I) V_I,
// with a linear (4 terms) or quadratic (10 terms) basis H, and their exact gradients.
#pragma once
#include <cstdint>
#include <span>
#include <string>

#include "kernel.hpp"

namespace rk {

enum class Basis { linear, quadratic };

inline Basis parse_basis(const std::string& name) { return name == "quadratic" ? Basis::quadratic : Basis::linear; }

struct RkParticles {  // the particle data a shape function needs (SoA views)
  const double* X;       // 3 per particle
  const double* volume;  // V_I
  const double* radius;  // support radius a_I
};

struct RkResult {
  bool regular = false;  // false: moment matrix singular (too few neighbours in the support)
  double rcond = 0;      // reciprocal condition estimate of the scaled moment matrix
};

// Evaluates N_I and grad N_I at x for the particles in `neighbours` (phi_a(x - X_I) > 0 expected).
// N has one entry per neighbour, dN three (d/dX, d/dY, d/dZ) per neighbour; dN null: N alone (the
// same N, without the gradients' work).
RkResult rk_shape(const double x[3], std::span<const std::int32_t> neighbours, const RkParticles& p,
                  Kernel kernel, Basis basis, double* N, double* dN);

// How evenly the neighbours surround x, whatever their support sizes: the smallest over the largest
// eigenvalue of the kernel-weighted (phi V) covariance of their offsets. Near 1 inside a lattice, a
// third or more at its faces, edges and corners, near 0 where they are flat or on a line; free of
// the support scale, unlike RkResult::rcond (its basis is scaled by the largest support around x).
double neighbour_spread(const double x[3], std::span<const std::int32_t> neighbours, const RkParticles& p,
                        Kernel kernel);

}  // namespace rk
