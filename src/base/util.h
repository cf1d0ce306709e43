/* Private helpers shared by several modules. */
#ifndef ROLLSIM_UTIL_H
#define ROLLSIM_UTIL_H

/* LAPACK: general dense LU solve (column-major). */
extern void dgesv_(const int *n, const int *nrhs, double *a, const int *lda, int *ipiv, double *b,
                   const int *ldb, int *info);
/* LAPACK: dense LU factorisation and solve with it (column-major). */
extern void dgetrf_(const int *m, const int *n, double *a, const int *lda, int *ipiv, int *info);
extern void dgetrs_(const char *trans, const int *n, const int *nrhs, const double *a,
                    const int *lda, const int *ipiv, double *b, const int *ldb, int *info);
/* LAPACK: Cholesky factorisation of a symmetric positive definite matrix and the inverse
 * from it (column-major; uplo "L" or "U"). */
extern void dpotrf_(const char *uplo, const int *n, double *a, const int *lda, int *info);
extern void dpotri_(const char *uplo, const int *n, double *a, const int *lda, int *info);

/* Monotonic wall-clock time in seconds (progress, ETA and reported wall times). */
double rs_wall_clock(void);

/* Threads for the work a solve splits in two (3D: the FFT products' two components, the
 * near field's two halves): the requested number (solver.threads), at most 2 and at most
 * what OpenMP allows (OMP_NUM_THREADS; 1 under MPI with several ranks). The results do not
 * depend on it. */
int rs_threads(int requested);
/* Inside a parallel region: this thread's number and the team's size (0 and 1 without
 * OpenMP). */
int rs_thread_num(void);
int rs_thread_count(void);

#endif
