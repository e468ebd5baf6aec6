#include "boundary/constraint_factor.hpp"

#include <SuiteSparseQR.hpp>
#include <cholmod.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "error.hpp"

namespace rk {

struct ConstraintFactor::Impl {
  Backend backend;
  cholmod_common cc;
  std::int64_t n = 0;
  SuiteSparseQR_factorization<double>* QR = nullptr;    // spqr
  cholmod_dense* b = nullptr;  // spqr right-hand side
  // cholmod: L (columns sorted, diagonal first) and the fill-reducing order, solved by hand: two
  // plain triangular sweeps (no workspace, nothing allocated per step)
  std::vector<SuiteSparse_long> Lp, Li, perm;
  std::vector<double> Lx, y;
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
    cholmod_factor* L = cholmod_l_analyze(S, &m.cc);
    ok = L && cholmod_l_factorize(S, L, &m.cc) && m.cc.status == CHOLMOD_OK && L->minor == std::size_t(m.n);
    // a pivot that lost all but 1e-10 of its row's weight: a constraint that repeats others
    const auto* Lp = static_cast<const SuiteSparse_long*>(ok ? L->p : nullptr);
    const auto* Lx = static_cast<const double*>(ok ? L->x : nullptr);
    const auto* Perm = static_cast<const SuiteSparse_long*>(ok ? L->Perm : nullptr);
    for (std::int64_t j = 0; ok && j < m.n; ++j) {
      const std::int64_t a = Perm ? Perm[j] : j;
      double Saa = 0;
      for (auto k = A.offsets[a]; k < A.offsets[a + 1]; ++k) Saa += A.val[k] * A.val[k];
      ok = Lx[Lp[j]] * Lx[Lp[j]] > 1e-10 * Saa;
    }
    if (ok) {  // keep L's columns (sorted, diagonal first) and the order; the CHOLMOD factor goes
      m.perm.resize(std::size_t(m.n));
      for (std::int64_t j = 0; j < m.n; ++j) m.perm[j] = Perm ? Perm[j] : j;
      cholmod_sparse* Ls = cholmod_l_factor_to_sparse(L, &m.cc);
      const auto* p = static_cast<const SuiteSparse_long*>(Ls->p);
      const auto* i = static_cast<const SuiteSparse_long*>(Ls->i);
      const auto* x = static_cast<const double*>(Ls->x);
      m.Lp.assign(p, p + m.n + 1);
      m.Li.assign(i, i + p[m.n]);
      m.Lx.assign(x, x + p[m.n]);
      m.y.resize(std::size_t(m.n));
      factor_nnz_ = std::int64_t(p[m.n]);
      cholmod_l_free_sparse(&Ls, &m.cc);
    }
    cholmod_l_free_factor(&L, &m.cc);
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
  cholmod_l_free_dense(&m.b, &m.cc);
  if (m.QR) SuiteSparseQR_free(&m.QR, &m.cc);
  cholmod_l_finish(&m.cc);
  delete impl_;
  impl_ = nullptr;
}

void ConstraintFactor::solve(const double* rhs, double* lambda) {
  Impl& m = *impl_;
  if (m.backend == Backend::cholmod) {  // S = P^T L L^T P
    double* y = m.y.data();
    for (std::int64_t j = 0; j < m.n; ++j) y[j] = rhs[m.perm[j]];
    for (std::int64_t j = 0; j < m.n; ++j) {
      y[j] /= m.Lx[m.Lp[j]];
      for (auto k = m.Lp[j] + 1; k < m.Lp[j + 1]; ++k) y[m.Li[k]] -= m.Lx[k] * y[j];
    }
    for (std::int64_t j = m.n - 1; j >= 0; --j) {
      for (auto k = m.Lp[j] + 1; k < m.Lp[j + 1]; ++k) y[j] -= m.Lx[k] * y[m.Li[k]];
      y[j] /= m.Lx[m.Lp[j]];
    }
    for (std::int64_t j = 0; j < m.n; ++j) lambda[m.perm[j]] = y[j];
    return;
  }
  std::memcpy(m.b->x, rhs, sizeof(double) * std::size_t(m.n));
  cholmod_dense* y = SuiteSparseQR_solve(SPQR_RTX_EQUALS_ETB, m.QR, m.b, &m.cc);  // R^T y = E^T b
  cholmod_dense* z = SuiteSparseQR_solve(SPQR_RETX_EQUALS_B, m.QR, y, &m.cc);     // R E^T z = y
  std::memcpy(lambda, z->x, sizeof(double) * std::size_t(m.n));
  cholmod_l_free_dense(&y, &m.cc);
  cholmod_l_free_dense(&z, &m.cc);
}

}  // namespace rk
