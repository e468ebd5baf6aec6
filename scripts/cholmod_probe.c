/* LD_PRELOAD probe for the exact EBCs' constraint factor (solver/boundary/constraint_factor.cpp),
 * which rksolve does not report: prints, per rank, the constraint rows n, nnz(A A^T) (upper part),
 * nnz(A), nnz(L), the heap the factorization holds at once (glibc mallinfo2) and the seconds spent in cholmod_l_analyze / cholmod_l_factorize.
 *   gcc -O2 -shared -fPIC -o /tmp/cholmod_probe.so scripts/cholmod_probe.c -ldl
 *   LD_PRELOAD=/tmp/cholmod_probe.so build/bin/rksolve CASE ...   (mpirun: -x LD_PRELOAD=...)
 * Lines start with "cholmod_probe"; nothing in rksolve changes. */
#define _GNU_SOURCE
#include <cholmod.h>
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <malloc.h>
#include <time.h>

static double heap_mib(void) {
  struct mallinfo2 m = mallinfo2();
  return (m.uordblks + m.hblkhd) / 1048576.0;
}
static double heap0;

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}
static const char* rank(void) {
  const char* r = getenv("OMPI_COMM_WORLD_RANK");
  return r ? r : "0";
}

cholmod_sparse* cholmod_l_transpose(cholmod_sparse* A, int values, cholmod_common* c) {
  static cholmod_sparse* (*real)(cholmod_sparse*, int, cholmod_common*);
  if (!real) real = dlsym(RTLD_NEXT, "cholmod_l_transpose");
  heap0 = heap_mib();
  fprintf(stderr, "cholmod_probe rank %s: A rows %ld cols %ld nnz %ld, heap %.1f MiB\n", rank(), (long)A->ncol,
          (long)A->nrow, (long)((SuiteSparse_long*)A->p)[A->ncol], heap0);
  return real(A, values, c);
}

cholmod_sparse* cholmod_l_copy(cholmod_sparse* A, int stype, int mode, cholmod_common* c) {
  static cholmod_sparse* (*real)(cholmod_sparse*, int, int, cholmod_common*);
  if (!real) real = dlsym(RTLD_NEXT, "cholmod_l_copy");
  cholmod_sparse* S = real(A, stype, mode, c);
  if (S && stype == 1)
    fprintf(stderr, "cholmod_probe rank %s: S = A A^T n %ld nnz(upper) %ld\n", rank(), (long)S->nrow,
            (long)((SuiteSparse_long*)S->p)[S->ncol]);
  return S;
}

cholmod_factor* cholmod_l_analyze(cholmod_sparse* A, cholmod_common* c) {
  static cholmod_factor* (*real)(cholmod_sparse*, cholmod_common*);
  if (!real) real = dlsym(RTLD_NEXT, "cholmod_l_analyze");
  double t0 = now();
  cholmod_factor* L = real(A, c);
  fprintf(stderr, "cholmod_probe rank %s: analyze %.4f s, ordering %d, predicted nnz(L) %.0f\n", rank(),
          now() - t0, c->selected >= 0 ? c->method[c->selected].ordering : -1, c->lnz);
  return L;
}

int cholmod_l_factorize(cholmod_sparse* A, cholmod_factor* L, cholmod_common* c) {
  static int (*real)(cholmod_sparse*, cholmod_factor*, cholmod_common*);
  if (!real) real = dlsym(RTLD_NEXT, "cholmod_l_factorize");
  double t0 = now();
  int ok = real(A, L, c);
  fprintf(stderr, "cholmod_probe rank %s: factorize %.4f s, flops %.3g\n", rank(), now() - t0, c->fl);
  return ok;
}

cholmod_sparse* cholmod_l_factor_to_sparse(cholmod_factor* L, cholmod_common* c) {
  static cholmod_sparse* (*real)(cholmod_factor*, cholmod_common*);
  if (!real) real = dlsym(RTLD_NEXT, "cholmod_l_factor_to_sparse");
  cholmod_sparse* S = real(L, c);
  if (S) {
    long n = (long)S->ncol, nnz = (long)((SuiteSparse_long*)S->p)[S->ncol];
    fprintf(stderr, "cholmod_probe rank %s: L n %ld nnz %ld, kept %.1f MiB (Lp, Li, Lx, perm)\n", rank(), n, nnz,
            (8.0 * (n + 1) + 16.0 * nnz + 8.0 * n) / 1048576.0);
    fprintf(stderr, "cholmod_probe rank %s: heap above the start of the factorization %.1f MiB (A^T, A, A A^T twice, L, L as sparse)\n",
            rank(), heap_mib() - heap0);
  }
  return S;
}
