// The constraint system of the exact essential BCs, factorized once with SuiteSparse.
//
// With the constraint matrix C (rows: e_k N_J(X_I), one per constrained direction) and the lumped
// masses M, enforcing C v = c on the velocities with the least mass-weighted change gives
//   v = v* - M^{-1} C^T lambda,   S lambda = C v* - c,   S = C M^{-1} C^T = A A^T,  A = C M^{-1/2}.
// S is symmetric positive definite (one row per constrained direction, rows independent) and
// fixed in the total-Lagrangian setting, so it is factorized once; a step costs two sparse
// triangular solves. Two backends, measured against each other in tests/unit/test_constraint_factor:
//   cholmod  sparse Cholesky of S = L L^T (simplicial: no BLAS, so bitwise the same on every rank),
//          solved with two plain triangular sweeps over L
//   spqr     sparse QR of A^T = Q R, S = R^T R (never forms S; better conditioned, slower)
#pragma once
#include <cstdint>
#include <vector>

namespace rk {

// A in compressed rows: row a holds columns col[offsets[a] .. offsets[a+1]) with values val.
struct ConstraintRows {
  std::int64_t rows = 0, cols = 0;
  std::vector<std::int64_t> offsets{0};
  std::vector<std::int64_t> col;
  std::vector<double> val;
};

class ConstraintFactor {
 public:
  enum class Backend { cholmod, spqr };
  // Throws rk::Error if S is singular (constraints that depend on each other).
  ConstraintFactor(const ConstraintRows& A, Backend backend = Backend::cholmod);
  ~ConstraintFactor();
  ConstraintFactor(const ConstraintFactor&) = delete;
  ConstraintFactor& operator=(const ConstraintFactor&) = delete;

  // lambda = S^{-1} rhs (both of length rows). The cholmod backend allocates nothing.
  void solve(const double* rhs, double* lambda);
  std::int64_t factor_nonzeros() const { return factor_nnz_; }

 private:
  void release();
  struct Impl;
  Impl* impl_;
  std::int64_t factor_nnz_ = 0;
};

}  // namespace rk
