#include "rk_shape.hpp"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <cmath>

namespace rk {
namespace {

// Basis H(xi) and dH/dxi_k for xi = (x - X_I) / scale.
template <int NB>
void basis(const double xi[3], Eigen::Matrix<double, NB, 1>& H, Eigen::Matrix<double, NB, 3>& dH) {
  H.setZero();
  dH.setZero();
  H(0) = 1;
  for (int k = 0; k < 3; ++k) {
    H(1 + k) = xi[k];
    dH(1 + k, k) = 1;
  }
  if constexpr (NB == 10) {
    for (int k = 0; k < 3; ++k) {  // x^2, y^2, z^2
      H(4 + k) = xi[k] * xi[k];
      dH(4 + k, k) = 2 * xi[k];
    }
    const int a[3] = {0, 1, 2}, b[3] = {1, 2, 0};  // xy, yz, zx
    for (int m = 0; m < 3; ++m) {
      H(7 + m) = xi[a[m]] * xi[b[m]];
      dH(7 + m, a[m]) += xi[b[m]];
      dH(7 + m, b[m]) += xi[a[m]];
    }
  }
}

// kGradient: grad N as well (dN); without it the moment matrix's derivatives are not formed, and N is
// bit for bit the same
template <int NB, bool kGradient>
RkResult shape(const double x[3], std::span<const std::int32_t> nb, const RkParticles& p, Kernel kernel,
               double* N, double* dN) {
  using Vec = Eigen::Matrix<double, NB, 1>;
  using Mat = Eigen::Matrix<double, NB, NB>;
  // Scale the basis by the largest support for conditioning (the moment matrix is then O(1)).
  double scale = 0;
  for (auto I : nb) scale = std::max(scale, p.radius[I]);
  if (scale <= 0 || nb.empty()) return {};
  const double inv = 1.0 / scale;

  Mat M = Mat::Zero();
  Mat dM[3] = {Mat::Zero(), Mat::Zero(), Mat::Zero()};
  Vec H;
  Eigen::Matrix<double, NB, 3> dH;
  for (auto I : nb) {
    const double d[3] = {x[0] - p.X[3 * I], x[1] - p.X[3 * I + 1], x[2] - p.X[3 * I + 2]};
    const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const double a = p.radius[I];
    double phi, dphi;
    window(kernel, r / a, phi, dphi);
    if (phi <= 0) continue;
    const double xi[3] = {d[0] * inv, d[1] * inv, d[2] * inv};
    basis<NB>(xi, H, dH);
    const double w = phi * p.volume[I];
    M.noalias() += w * H * H.transpose();
    if constexpr (kGradient)
      for (int k = 0; k < 3; ++k) {
        const double dw = (r > 0 ? dphi * d[k] / (r * a) : 0.0) * p.volume[I];
        const Vec dHk = dH.col(k) * inv;
        dM[k].noalias() += w * (dHk * H.transpose() + H * dHk.transpose()) + dw * H * H.transpose();
      }
  }
  Eigen::LDLT<Mat> ldlt(M);
  RkResult result;
  // Pivot ratio of the scaled moment matrix: LDLT's own rcond() ignores zero pivots. Below 1e-10 the
  // solve would keep fewer than 6 of its 16 digits: singular.
  const Vec D = ldlt.vectorD().cwiseAbs();
  result.rcond = D.maxCoeff() > 0 ? D.minCoeff() / D.maxCoeff() : 0.0;
  if (ldlt.info() != Eigen::Success || !(result.rcond > 1e-10)) return result;
  result.regular = true;

  Vec e0 = Vec::Zero();
  e0(0) = 1;
  const Vec b = ldlt.solve(e0);  // M b = H(0)
  Vec db[3];
  if constexpr (kGradient)
    for (int k = 0; k < 3; ++k) db[k] = -ldlt.solve(dM[k] * b);  // b,k = -M^{-1} M,k b

  for (std::size_t j = 0; j < nb.size(); ++j) {
    const auto I = nb[j];
    const double d[3] = {x[0] - p.X[3 * I], x[1] - p.X[3 * I + 1], x[2] - p.X[3 * I + 2]};
    const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const double a = p.radius[I];
    double phi, dphi;
    window(kernel, r / a, phi, dphi);
    const double xi[3] = {d[0] * inv, d[1] * inv, d[2] * inv};
    basis<NB>(xi, H, dH);
    const double V = p.volume[I];
    const double bH = b.dot(H);
    N[j] = bH * phi * V;
    if constexpr (kGradient)
      for (int k = 0; k < 3; ++k) {
        const double dphik = r > 0 ? dphi * d[k] / (r * a) : 0.0;
        dN[3 * j + k] = (db[k].dot(H) * phi + b.dot(dH.col(k)) * inv * phi + bH * dphik) * V;
      }
  }
  return result;
}

}  // namespace

RkResult rk_shape(const double x[3], std::span<const std::int32_t> neighbours, const RkParticles& p,
                  Kernel kernel, Basis basis_kind, double* N, double* dN) {
  if (!dN)
    return basis_kind == Basis::quadratic ? shape<10, false>(x, neighbours, p, kernel, N, dN)
                                          : shape<4, false>(x, neighbours, p, kernel, N, dN);
  return basis_kind == Basis::quadratic ? shape<10, true>(x, neighbours, p, kernel, N, dN)
                                        : shape<4, true>(x, neighbours, p, kernel, N, dN);
}

double neighbour_spread(const double x[3], std::span<const std::int32_t> neighbours, const RkParticles& p,
                        Kernel kernel) {
  double sw = 0;
  Eigen::Vector3d s1 = Eigen::Vector3d::Zero();
  Eigen::Matrix3d s2 = Eigen::Matrix3d::Zero();
  for (auto I : neighbours) {
    const Eigen::Vector3d d(x[0] - p.X[3 * I], x[1] - p.X[3 * I + 1], x[2] - p.X[3 * I + 2]);
    double phi, dphi;
    window(kernel, d.norm() / p.radius[I], phi, dphi);
    if (phi <= 0) continue;
    const double w = phi * p.volume[I];
    sw += w, s1 += w * d, s2 += w * d * d.transpose();
  }
  if (!(sw > 0)) return 0.0;
  const Eigen::Vector3d mean = s1 / sw;
  const Eigen::Matrix3d C = s2 / sw - mean * mean.transpose();
  const Eigen::Vector3d lambda = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(C, Eigen::EigenvaluesOnly).eigenvalues();
  return lambda(2) > 0 ? std::max(0.0, lambda(0)) / lambda(2) : 0.0;
}

}  // namespace rk
