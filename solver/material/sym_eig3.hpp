// Eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations (Golub & Van Loan,
// Matrix Computations, section 8.5). Accurate to round-off in every eigenvalue, also for the nearly
// equal eigenvalues of b_e ~ I at small strain (where closed-form cubic solutions lose digits), and
// faster than a general tridiagonal QR for this size. Converges quadratically: 3-4 sweeps (stops when
// the off-diagonal is below 1e-18 of the diagonal, round-off; 12 sweeps only guard the loop).
#pragma once
#include <cmath>

namespace rk {

// a: symmetric matrix (row-major 3x3), destroyed. On return w[i] are the eigenvalues and the columns
// of V (row-major, V[3*r + i]) the unit eigenvectors.
inline void sym_eig3(double a[9], double w[3], double V[9]) {
  for (int i = 0; i < 9; ++i) V[i] = (i % 4 == 0) ? 1.0 : 0.0;
  constexpr int P[3] = {0, 0, 1}, Q[3] = {1, 2, 2};
  for (int sweep = 0; sweep < 12; ++sweep) {
    const double off = a[1] * a[1] + a[2] * a[2] + a[5] * a[5];
    const double diag = a[0] * a[0] + a[4] * a[4] + a[8] * a[8];
    if (off <= 1e-36 * diag || off == 0.0) break;
    for (int k = 0; k < 3; ++k) {
      const int p = P[k], q = Q[k], r = 3 - p - q;
      const double apq = a[3 * p + q];
      if (apq == 0.0) continue;
      const double theta = (a[3 * q + q] - a[3 * p + p]) / (2 * apq);
      const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1));
      const double c = 1 / std::sqrt(t * t + 1), s = t * c;
      a[3 * p + p] -= t * apq;
      a[3 * q + q] += t * apq;
      a[3 * p + q] = a[3 * q + p] = 0;
      const double arp = a[3 * r + p], arq = a[3 * r + q];
      a[3 * r + p] = a[3 * p + r] = c * arp - s * arq;
      a[3 * r + q] = a[3 * q + r] = s * arp + c * arq;
      for (int i = 0; i < 3; ++i) {
        const double vip = V[3 * i + p], viq = V[3 * i + q];
        V[3 * i + p] = c * vip - s * viq;
        V[3 * i + q] = s * vip + c * viq;
      }
    }
  }
  w[0] = a[0], w[1] = a[4], w[2] = a[8];
}

}  // namespace rk
