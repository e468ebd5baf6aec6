// The exact essential BCs' constraint system: real RK rows N_J(X_I) of the particles on two
// faces of a 12^3 lattice (a fixed face: three directions each; a symmetry plane of non-axis normal
// where it meets it), lumped masses of +-30 %. Both SuiteSparse backends must enforce C v = c to
// round-off and agree on the multipliers; their set-up and per-solve times are printed (measured
// here, not asserted: the machines are shared).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "boundary/constraint_factor.hpp"
#include "neighbour_grid.hpp"
#include "rk_shape.hpp"

namespace {

struct System {
  rk::ConstraintRows A;    // C M^{-1/2}
  std::vector<double> C;   // dense rows of C, for the check (rows x cols)
  std::vector<double> inv_mass;  // per column
};

System lattice_constraints(int n) {
  const double h = 1e-3;
  std::vector<double> X, V, a;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        X.insert(X.end(), {h * i, h * j, h * k});
        V.push_back(h * h * h);
        a.push_back(2.0 * h);
      }
  const std::size_t np = V.size();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(0.7, 1.3);
  System s;
  for (std::size_t J = 0; J < np; ++J) {
    const double m = 7800 * V[J] * jitter(rng);
    for (int d = 0; d < 3; ++d) s.inv_mass.push_back(1 / m);
  }
  rk::NeighbourGrid grid(X.data(), a.data(), np);
  const rk::RkParticles parts{X.data(), V.data(), a.data()};
  const double tilt[3] = {0.6, 0.8, 0};  // symmetry plane through the x = 0, y = 0 edge... of normal (0.6, 0.8, 0)
  s.A.cols = std::int64_t(3 * np);
  for (std::size_t I = 0; I < np; ++I) {
    std::vector<std::array<double, 3>> dirs;
    if (X[3 * I + 2] == 0) dirs = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};                       // fixed face z = 0
    else if (X[3 * I] == 0) dirs = {{tilt[0], tilt[1], tilt[2]}};                         // a slanted condition on x = 0
    if (dirs.empty()) continue;
    std::vector<std::int32_t> nb;
    grid.covering(&X[3 * I], nb);
    std::vector<double> N(nb.size()), dN(3 * nb.size());
    EXPECT_TRUE(rk::rk_shape(&X[3 * I], nb, parts, rk::Kernel::cubic_bspline, rk::Basis::linear, N.data(), dN.data()).regular);
    for (const auto& e : dirs) {
      std::vector<double> dense(3 * np, 0.0);
      for (std::size_t k = 0; k < nb.size(); ++k)
        for (int d = 0; d < 3; ++d)
          if (e[d] != 0) {
            const std::int64_t c = 3 * nb[k] + d;
            dense[c] = N[k] * e[d];
            s.A.col.push_back(c);
            s.A.val.push_back(N[k] * e[d] * std::sqrt(s.inv_mass[c]));
          }
      s.A.offsets.push_back(std::int64_t(s.A.col.size()));
      s.C.insert(s.C.end(), dense.begin(), dense.end());
    }
  }
  s.A.rows = std::int64_t(s.A.offsets.size() - 1);
  return s;
}

TEST(ConstraintFactor, BothBackendsEnforceTheConstraintsToRoundOff) {
  const System s = lattice_constraints(12);
  const std::size_t rows = std::size_t(s.A.rows), cols = std::size_t(s.A.cols);
  ASSERT_GT(rows, 400u);
  std::mt19937 rng(5);
  std::normal_distribution<double> g(0, 1);
  std::vector<double> v0(cols), target(rows);
  for (auto& x : v0) x = 100 * g(rng);
  for (auto& x : target) x = g(rng);
  std::vector<double> lambda[2];
  for (int b = 0; b < 2; ++b) {
    const auto backend = b == 0 ? rk::ConstraintFactor::Backend::cholmod : rk::ConstraintFactor::Backend::spqr;
    const auto t0 = std::chrono::steady_clock::now();
    rk::ConstraintFactor factor(s.A, backend);
    const auto t1 = std::chrono::steady_clock::now();
    std::vector<double> rho(rows), lam(rows);
    for (std::size_t a = 0; a < rows; ++a) {
      rho[a] = -target[a];
      for (std::size_t c = 0; c < cols; ++c) rho[a] += s.C[a * cols + c] * v0[c];
    }
    const int solves = 200;
    for (int k = 0; k < solves; ++k) factor.solve(rho.data(), lam.data());
    const auto t2 = std::chrono::steady_clock::now();
    std::vector<double> v = v0;  // v = v0 - M^{-1} C^T lambda
    for (std::size_t a = 0; a < rows; ++a)
      for (std::size_t c = 0; c < cols; ++c) v[c] -= s.inv_mass[c] * s.C[a * cols + c] * lam[a];
    double worst = 0;
    for (std::size_t a = 0; a < rows; ++a) {
      double Cv = 0;
      for (std::size_t c = 0; c < cols; ++c) Cv += s.C[a * cols + c] * v[c];
      worst = std::max(worst, std::abs(Cv - target[a]));
    }
    EXPECT_LT(worst, 1e-10) << (b == 0 ? "cholmod" : "spqr");  // |v0| ~ 100, target ~ 1
    std::printf("%-8s %zu constraints: factor %.2f ms (%lld nonzeros), solve %.1f us, max |Cv - c| = %.1e\n",
                b == 0 ? "cholmod" : "spqr", rows, 1e3 * std::chrono::duration<double>(t1 - t0).count(),
                static_cast<long long>(factor.factor_nonzeros()),
                1e6 * std::chrono::duration<double>(t2 - t1).count() / solves, worst);
    lambda[b] = lam;
  }
  double scale = 0, diff = 0;
  for (std::size_t a = 0; a < rows; ++a)
    scale = std::max(scale, std::abs(lambda[0][a])), diff = std::max(diff, std::abs(lambda[0][a] - lambda[1][a]));
  EXPECT_LT(diff, 1e-9 * scale);
}

TEST(ConstraintFactor, DependentConstraintsAreOneClearError) {
  rk::ConstraintRows A;  // two identical rows
  A.rows = 2, A.cols = 2;
  A.offsets = {0, 2, 4};
  A.col = {0, 1, 0, 1};
  A.val = {0.5, 0.5, 0.5, 0.5};
  for (auto backend : {rk::ConstraintFactor::Backend::cholmod, rk::ConstraintFactor::Backend::spqr})
    EXPECT_THROW(rk::ConstraintFactor f(A, backend), std::exception);
}

}  // namespace
