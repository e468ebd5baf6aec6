#include "boundary/constraint_factor.hpp"

#include <SuiteSparseQR.hpp>
#include <cholmod.h>

#include <algorithm>
#include <cstring>

#include "error.hpp"

namespace rk {

struct ConstraintFactor::Impl {
  Backend backend;
  cholmod_common cc;
  std::int64_t n = 0;
  cholmod_factor* L = nullptr;                          // cholmod
  SuiteSparseQR_factorization<double>* QR = nullptr;    // spqr
  cholmod_dense *b = nullptr, *x = nullptr, *Y = nullptr, *E = nullptr;
};

ConstraintFactor::ConstraintFactor(const ConstraintRows& A, Backend backend) : impl_(new Impl) {
  Impl& m = *impl_;
  m.backend = backend;
  m.n = A.rows;
  cholmod_l_start(&m.cc);
  m.cc.supernodal = CHOLMOD_SIMPLICIAL;
  m.cc.final_ll = 1;
  m.cc.print = 0;
  // A's compressed rows are A^T's compressed columns
  cholmod_sparse* At = cholmod_l_allocate_sparse(A.cols, A.rows, A.val.size(), 1, 1, 0, CHOLMOD_REAL, &m.cc);
  auto* p = static_cast<SuiteSparse_long*>(At->p);
  auto* i = static_cast<SuiteSparse_long*>(At->i);
  auto* x = static_cast<double*>(At->x);
  std::copy(A.offsets.begin(), A.offsets.end(), p);
  std::copy(A.col.begin(), A.col.end(), i);
  std::copy(A.val.begin(), A.val.end(), x);
  bool ok = true;
  if (backend == Backend::cholmod) {
    cholmod_sparse* Am = cholmod_l_transpose(At, 1, &m.cc);
    cholmod_sparse* full = cholmod_l_aat(Am, nullptr, 0, 1, &m.cc);  // S = A A^T
    cholmod_sparse* S = cholmod_l_copy(full, 1, 1, &m.cc);          // symmetric, upper part
    m.L = cholmod_l_analyze(S, &m.cc);
    ok = m.L && cholmod_l_factorize(S, m.L, &m.cc) && m.cc.status == CHOLMOD_OK && m.L->minor == std::size_t(m.n);
    // a pivot that lost all but 1e-10 of its row's weight: a constraint that repeats others
    const auto* Lp = static_cast<const SuiteSparse_long*>(ok ? m.L->p : nullptr);
    const auto* Lx = static_cast<const double*>(ok ? m.L->x : nullptr);
    const auto* Perm = static_cast<const SuiteSparse_long*>(ok ? m.L->Perm : nullptr);
    for (std::int64_t j = 0; ok && j < m.n; ++j) {
      const std::int64_t a = Perm ? Perm[j] : j;
      double Saa = 0;
      for (auto k = A.offsets[a]; k < A.offsets[a + 1]; ++k) Saa += A.val[k] * A.val[k];
      ok = Lx[Lp[j]] * Lx[Lp[j]] > 1e-10 * Saa;
    }
    if (m.L) {
      cholmod_factor* Lc = cholmod_l_copy_factor(m.L, &m.cc);
      cholmod_sparse* Ls = cholmod_l_factor_to_sparse(Lc, &m.cc);
      factor_nnz_ = Ls ? std::int64_t(cholmod_l_nnz(Ls, &m.cc)) : 0;
      cholmod_l_free_sparse(&Ls, &m.cc);
      cholmod_l_free_factor(&Lc, &m.cc);
    }
    cholmod_l_free_sparse(&S, &m.cc);
    cholmod_l_free_sparse(&full, &m.cc);
    cholmod_l_free_sparse(&Am, &m.cc);
  } else {
    m.QR = SuiteSparseQR_factorize<double>(SPQR_ORDERING_DEFAULT, SPQR_DEFAULT_TOL, At, &m.cc);
    ok = m.QR && m.QR->rank == m.n;
    factor_nnz_ = std::int64_t(m.cc.SPQR_istat[0]);  // nnz(R), as SPQR counts it
  }
  cholmod_l_free_sparse(&At, &m.cc);
  if (!ok) {
    const std::string which = backend == Backend::cholmod ? "CHOLMOD" : "SPQR";
    release();
    throw Error("the essential boundary conditions depend on each other (" + which +
                " found the constraint matrix singular): two faces hold the same particles' motion");
  }
  m.b = cholmod_l_zeros(m.n, 1, CHOLMOD_REAL, &m.cc);
}

ConstraintFactor::~ConstraintFactor() { release(); }

void ConstraintFactor::release() {
  if (!impl_) return;
  Impl& m = *impl_;
  for (cholmod_dense** d : {&m.b, &m.x, &m.Y, &m.E}) cholmod_l_free_dense(d, &m.cc);
  cholmod_l_free_factor(&m.L, &m.cc);
  if (m.QR) SuiteSparseQR_free(&m.QR, &m.cc);
  cholmod_l_finish(&m.cc);
  delete impl_;
  impl_ = nullptr;
}

void ConstraintFactor::solve(const double* rhs, double* lambda) {
  Impl& m = *impl_;
  std::memcpy(m.b->x, rhs, sizeof(double) * std::size_t(m.n));
  if (m.backend == Backend::cholmod) {
    cholmod_l_solve2(CHOLMOD_A, m.L, m.b, nullptr, &m.x, nullptr, &m.Y, &m.E, &m.cc);
    std::memcpy(lambda, m.x->x, sizeof(double) * std::size_t(m.n));
    return;
  }
  cholmod_dense* y = SuiteSparseQR_solve(SPQR_RTX_EQUALS_ETB, m.QR, m.b, &m.cc);  // R^T y = E^T b
  cholmod_dense* z = SuiteSparseQR_solve(SPQR_RETX_EQUALS_B, m.QR, y, &m.cc);     // R E^T z = y
  std::memcpy(lambda, z->x, sizeof(double) * std::size_t(m.n));
  cholmod_l_free_dense(&y, &m.cc);
  cholmod_l_free_dense(&z, &m.cc);
}

}  // namespace rk
