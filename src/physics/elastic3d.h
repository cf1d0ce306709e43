/* Elastic influence coefficients of the 3D half-space for quasi-identical bodies,
 * piecewise-constant tractions on equal rectangles dx x dy (docs/model.md §2, §10).
 *
 * Point load on body 1 (minus it on body 2), displacement difference at (x, y) from
 * the load (Boussinesq-Cerruti, Johnson 1985 §3.2, doubled for two bodies):
 *   tangential Q_x: u_x = Q/(pi G) [(1-nu)/r + nu x^2/r^3],  u_y = Q/(pi G) nu x y/r^3
 *   tangential Q_y: the same with x <-> y
 *   normal P:       u_z = P (1-nu)/(pi G r)
 * (no normal-tangential coupling for identical bodies). Integrated over a loaded
 * rectangle in closed form (Kalker 1990 §1.6) with the primitives
 *   Int Int 1/r      -> x asinh(y/|x|) + y asinh(x/|y|)
 *   Int Int x^2/r^3  -> y asinh(x/|y|)
 *   Int Int y^2/r^3  -> x asinh(y/|x|)
 *   Int Int x y/r^3  -> -r
 * taken at the four corners by inclusion-exclusion.
 *
 * Grid: nx x ny cells, index I = iy nx + ix (x fastest). The coefficient A_ij(kx, ky)
 * is the displacement u_i at the centre of a cell offset by (kx dx, ky dy) from a cell
 * carrying unit traction p_j. Offsets kx in [-(nx-1), nx] (kx = nx serves the padded
 * column one cell beyond the leading edge, docs/model.md §5), ky in [-(ny-1), ny-1].
 *
 * Memory: the coefficients 4 (nx+1) ny doubles (stored for kx, ky >= 0, the rest by
 * symmetry); the transformed kernels 4 my (mx/2+1) complex doubles on the padded
 * grid mx x my (mx >= 2 nx, my >= 2 ny - 1, sizes 2^a 3^b 5^c); a work struct
 * mx my doubles + 2 my (mx/2+1) complex doubles. For nx = ny = 128: mx = my = 256,
 * 0.5 MB of coefficients, 2.0 MB of kernels, 1.5 MB per work struct.
 * Cost of one product by FFT: tangential 2 forward + 2 backward real 2D transforms of
 * mx x my and 4 complex multiply-adds per frequency; normal 1 + 1 transforms
 * (bench/normal3d_timing.c times them).
 * The direct sums cost (nout ny) (nx ny) multiply-adds per component pair. */
#ifndef ROLLSIM_ELASTIC3D_H
#define ROLLSIM_ELASTIC3D_H

#include "base/status.h"

typedef struct rs_elastic3d {
  int nx, ny;           /* cells of the contact grid along x (rolling) and y */
  double dx, dy;        /* cell sizes, mm */
  double shear_modulus; /* combined G, N/mm^2 */
  double poisson_ratio; /* combined nu */
  /* Coefficients, mm/(N/mm^2), for kx = 0..nx, ky = 0..ny-1 at [ky (nx+1) + kx].
   * xx, yy, zz are even in kx and in ky; xy is odd in each. */
  double *xx, *xy, *yy, *zz;
  struct rs_elastic3d_fft *fft; /* plans and transformed kernels (read-only after create) */
} rs_elastic3d;

/* Scratch space for the FFT products: one per thread applying the same rs_elastic3d
 * (the products never write through the const rs_elastic3d). */
typedef struct rs_elastic3d_work {
  int mx, my;        /* padded grid */
  double *grid;      /* [my mx] real work grid */
  double *grid2;     /* a second one (the y component in parallel) */
  int threads;       /* for the two components (rs_threads): set by the owner, default 1 */
  void *spectrum[2]; /* [my (mx/2+1)] complex spectra (fftw_complex) */
} rs_elastic3d_work;

/* Coefficient tables and FFT plans for an nx x ny grid of dx x dy cells. Not thread
 * safe (FFTW's planner) unless rs_elastic3d_planner_thread_safe was called; the applies
 * are. G > 0, -1 < nu <= 0.5. */
int rs_elastic3d_create(rs_elastic3d *el, int nx, int ny, double dx, double dy,
                        double shear_modulus, double poisson_ratio, rs_msg *msg);
void rs_elastic3d_free(rs_elastic3d *el);
/* Lets several threads create and free models (FFT plans) at once: FFTW's planner lock,
 * process-wide and kept by FFTW. Call before the threads start; calling it again is
 * harmless. */
void rs_elastic3d_planner_thread_safe(void);

int rs_elastic3d_work_create(rs_elastic3d_work *work, const rs_elastic3d *el, rs_msg *msg);
void rs_elastic3d_work_free(rs_elastic3d_work *work);

/* Coefficients for a field point offset (sx, sy) from the centre of a loaded dx x dy
 * rectangle: coef[0] = A_xx, coef[1] = A_xy = A_yx, coef[2] = A_yy, coef[3] = A_zz (the
 * closed form above). The corner sums are taken in long double against their
 * cancellation for far cells, which costs ~(r/d)^2 eps_long: within 1e-13 of A_zz up to 400
 * cells away against quadrature (test_elastic3d). */
void rs_elastic3d_rect(double dx, double dy, double sx, double sy, double shear_modulus,
                       double poisson_ratio, double coef[4]);

/* A_ij(kx, ky) for i, j in {0: x, 1: y, 2: z}, |kx| <= nx, |ky| <= ny - 1. */
static inline double rs_elastic3d_coef(const rs_elastic3d *el, int i, int j, int kx, int ky)
{
  const int ax = kx < 0 ? -kx : kx, ay = ky < 0 ? -ky : ky;
  const long at = (long)ay * (el->nx + 1) + ax;
  if (i == 2 || j == 2) return i == j ? el->zz[at] : 0.0;
  if (i != j) return (kx < 0) != (ky < 0) ? -el->xy[at] : el->xy[at];
  return i == 0 ? el->xx[at] : el->yy[at];
}

/* Tangential product u = A p with the x-y coupling: p = (px, py) on the nx x ny grid,
 * u = (ux, uy) on nxout x ny cells (nxout = nx, or nx + 1 to include the padded
 * column), index iy nxout + ix. By FFT convolution with the work struct's buffers. */
void rs_elastic3d_apply_tang(const rs_elastic3d *el, rs_elastic3d_work *work, const double *px,
                             const double *py, double *ux, double *uy, int nxout);
/* Normal product uz = A_zz pn, layout as above. */
void rs_elastic3d_apply_norm(const rs_elastic3d *el, rs_elastic3d_work *work, const double *pn,
                             double *uz, int nxout);

/* The same products by direct sums over the coefficient tables (small grids, tests). */
void rs_elastic3d_direct_tang(const rs_elastic3d *el, const double *px, const double *py,
                              double *ux, double *uy, int nxout);
void rs_elastic3d_direct_norm(const rs_elastic3d *el, const double *pn, double *uz, int nxout);

/* A lower bound of the smallest eigenvalue of A_zz on the nx x ny grid, mm/(N/mm^2):
 * the smallest transformed kernel value. The FFT kernel is the coefficient at the
 * minimal-image offset on the whole periodic mx x my grid (a symmetric circulant whose
 * eigenvalues are those values); the grid matrix is a principal submatrix of it, so by
 * Cauchy interlacing its eigenvalues are not below them (Golub & Van Loan, Thm 8.1.7).
 * <= 0 would mean the embedding is not positive definite (not seen: test_elastic3d). */
double rs_elastic3d_norm_lower_eigenvalue(const rs_elastic3d *el);

#endif
