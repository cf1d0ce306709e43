/* Discretisation error estimates of a steady solution's forces (docs/model.md §19): the
 * same point solved on two companion grids with about 2 and 4 times the cell size over
 * the same potential contact area, and Richardson extrapolation with the observed order
 * of the three results. */
#ifndef ROLLSIM_ERREST_H
#define ROLLSIM_ERREST_H

#include <stddef.h>

#include "physics/model.h"
#include "solve/steady.h"
#include "base/status.h"

/* Observed orders within RS_ERREST_P_TOL of the scheme's order 1 mark the grids as in the
 * asymptotic range (Oberkampf and Roy 2010, sec. 8.7: 10 %); outside it the order used is
 * clipped to [RS_ERREST_P_MIN, 1]. */
#define RS_ERREST_P_TOL           0.1
#define RS_ERREST_P_MIN           0.5
/* Safety factors: three grids in the asymptotic range (Roache's grid convergence index),
 * and the fallback with the scheme's formal order 1 outside it. */
#define RS_ERREST_SAFETY          1.25
#define RS_ERREST_SAFETY_FALLBACK 3.0
/* Differences below this fraction of the quantity's scale are the solver's tolerance,
 * not discretisation error: the result has converged in the grid. */
#define RS_ERREST_NOISE           1e-9
/* The coarsest companion keeps at least this many cells across the Hertz contact along
 * each axis. */
#define RS_ERREST_MIN_CELLS       6

/* The error of F1 (cells of size h1) from F2 and F3 on grids of h2 = r21 h1 and
 * h3 = r32 h2: a magnitude in *err; returns 1 (reliable: the observed order lies in the
 * band, or every difference is below noise) or 0 (the fallback). */
int rs_errest_combine(double f1, double f2, double f3, double r21, double r32, double noise,
                      double *err);
/* The same, and in *extrap the extrapolated F (Richardson with the observed order: second
 * order where the grids are asymptotic), or NaN when the estimate is not reliable. */
int rs_errest_combine_extrapolate(double f1, double f2, double f3, double r21, double r32,
                                  double noise, double *err, double *extrap);

/* d without an estimate: error_state RS_ERROR_NONE, the errors and extrapolated forces NaN. */
void rs_errest_none(rs_diag *d);
/* d's estimate (errors, extrapolated forces, error_state) set to e's. */
void rs_errest_copy(rs_diag *d, const rs_diag *e);

/* The estimate of d's F_x (3D: F_y, M_z) from the same point's results d2, d3 on grids of
 * cell size ratios r21, r32 (the scales from m's friction and d->Fn): d's error fields. */
void rs_errest_diag(const rs_model *m, double r21, double r32, const rs_diag *d2, const rs_diag *d3,
                    rs_diag *d);

/* The companion grids of a model and their solvers, kept over the points of a run or a
 * continuation line (only the rolling inputs may change between points). */
typedef struct rs_errest {
  int on; /* companions built */
  rs_model m[2];
  rs_steady *st[2];
  rs_work w[2];
  double *y[2], *yp[2];
  double r21, r32; /* cell size ratios h2/h1, h3/h2 */
} rs_errest;

/* Whether model m admits an estimate; if not, why[len] says why (in the user's terms). */
int rs_errest_admissible(const rs_model *m, char *why, size_t len);
/* Build the companions of m (admissible). RS_OK (e->on 0 when a companion's normal problem
 * failed: no estimate), or RS_ERR_INTERNAL. */
int rs_errest_create(rs_errest *e, const rs_model *m, SUNContext ctx, rs_msg *msg);
void rs_errest_free(rs_errest *e);
/* The estimate for the steady solution y of m at t = 0 (with diagnostics d of it, whose
 * Fx, Fy, Mz and Fn are F1): the companions take m's rolling inputs, start from y
 * interpolated and are solved; d->Fx_error, Fy_error, Mz_error and error_state are set.
 * A companion that fails leaves error_state RS_ERROR_NONE (RS_OK still: the point stands). */
int rs_errest_point(rs_errest *e, const rs_model *m, const double *y, rs_diag *d, rs_msg *msg);

/* grid.accuracy (docs/case-file.md): the steady point of model m solved on grids of twice
 * the cells along each axis after another (each from the last one's solution), from the
 * case's grid divided by 4 where that still resolves the contact, until the estimated error
 * of F_x (3D: F_y too, and M_z in mu F_n a) on a grid at least as fine as the case's is at
 * most accuracy mu F_n,
 * or the next grid finer than the case's would exceed the cap. On RS_OK m is the model of
 * the last grid solved, *y its solution (malloc'ed), d its diagnostics with the estimate,
 * *reached 1 if the accuracy was met. RS_ERR_SOLVER when a grid's solve failed (msg names
 * the grid). */
/* The largest of d's estimated errors of F_x (3D: F_y in mu F_n, M_z in mu F_n a). */
double rs_errest_worst(const rs_model *m, const rs_diag *d);
#define RS_ACCURACY_MAX_CELLS_2D 4096L
#define RS_ACCURACY_MAX_CELLS_3D 65536L
int rs_errest_refine(rs_model *m, SUNContext ctx, double accuracy, double **y, rs_diag *d,
                     int *reached, rs_msg *msg);

#endif
