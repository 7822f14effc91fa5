#pragma once
// The LAPACK routines the dense Floquet routes call (Debian's liblapack, or
// OpenBLAS through the alternatives): Hessenberg reduction, its eigenvalues,
// eigenvectors of selected eigenvalues, Q applied. Fortran calling convention,
// hidden string lengths last.
#include <cstddef>

extern "C" {
void dgehrd_(const int *n, const int *ilo, const int *ihi, double *a, const int *lda, double *tau, double *work, const int *lwork, int *info);
void dhseqr_(const char *job, const char *compz, const int *n, const int *ilo, const int *ihi, double *h, const int *ldh, double *wr, double *wi, double *z,
             const int *ldz, double *work, const int *lwork, int *info, size_t, size_t);
void dhsein_(const char *side, const char *eigsrc, const char *initv, int *select, const int *n, const double *h, const int *ldh, double *wr, const double *wi,
             double *vl, const int *ldvl, double *vr, const int *ldvr, const int *mm, int *m, double *work, int *ifaill, int *ifailr, int *info, size_t, size_t,
             size_t);
void dorghr_(const int *n, const int *ilo, const int *ihi, double *a, const int *lda, const double *tau, double *work, const int *lwork, int *info);
void dtrsen_(const char *job, const char *compq, const int *select, const int *n, double *t, const int *ldt, double *q, const int *ldq, double *wr, double *wi,
             int *m, double *s, double *sep, double *work, const int *lwork, int *iwork, const int *liwork, int *info, size_t, size_t);
void dormhr_(const char *side, const char *trans, const int *m, const int *n, const int *ilo, const int *ihi, const double *a, const int *lda,
             const double *tau, double *c, const int *ldc, double *work, const int *lwork, int *info, size_t, size_t);
}

// The exterior Floquet route (stability/floquet_exterior.cpp): the symmetric
// tridiagonal eigenproblem of K (divide and conquer), the complex generalized
// eigenproblem of its local linear problems, and the real matrix product.
extern "C" {
void dstevd_(const char *jobz, const int *n, double *d, double *e, double *z, const int *ldz, double *work, const int *lwork, int *iwork, const int *liwork,
             int *info, size_t);
void zggev_(const char *jobvl, const char *jobvr, const int *n, void *a, const int *lda, void *b, const int *ldb, void *alpha, void *beta, void *vl,
            const int *ldvl, void *vr, const int *ldvr, void *work, const int *lwork, double *rwork, int *info, size_t, size_t);
void dgemm_(const char *ta, const char *tb, const int *m, const int *n, const int *k, const double *alpha, const double *a, const int *lda, const double *b,
            const int *ldb, const double *beta, double *c, const int *ldc, size_t, size_t);
}
