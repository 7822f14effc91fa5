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
void dormhr_(const char *side, const char *trans, const int *m, const int *n, const int *ilo, const int *ihi, const double *a, const int *lda,
             const double *tau, double *c, const int *ldc, double *work, const int *lwork, int *info, size_t, size_t);
}
