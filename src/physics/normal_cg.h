/* The discrete normal contact problem for any dimension (docs/model.md §3), solved by
 * conjugate gradients with the load as a constraint (Polonsky & Keer 1999, Wear 231,
 * 206-219): find p >= 0 and the approach delta with
 *
 *   g = A p + h - delta >= 0,   p g = 0 (cell by cell),   cell_area sum p = load,
 *
 * i.e. minimise 1/2 p.A p + h.p over p >= 0 with the load fixed (delta is the load's
 * multiplier). The solver sees the problem only through an operator "u = A p" on n
 * cells, the undeformed gap h and the cell area, so one solver serves the 2D line
 * kernel and the 3D half-space alike. A must be symmetric and positive definite on
 * pressures of zero sum (the 2D logarithmic kernel is; the 3D one is on all pressures),
 * which makes the solution unique. */
#ifndef ROLLSIM_NORMAL_CG_H
#define ROLLSIM_NORMAL_CG_H

#include "base/status.h"

/* u[n] = A p[n] (displacement difference per pressure, mm/(N/mm^2)). */
typedef void (*rs_normal_apply_fn)(void *context, const double *p, double *u);

typedef struct rs_normal_operator {
  int n;                    /* cells */
  double cell_area;         /* load of unit pressure on one cell: dx dy (3D, mm^2), dx (2D) */
  double lambda;            /* a lower bound (> 0) of the smallest eigenvalue of A on
                             * zero-sum pressures, mm/(N/mm^2); it turns the gap residual
                             * into a pressure error bound for the stopping test. 3D:
                             * rs_elastic3d_norm_lower_eigenvalue; 2D: (A(0) - A(1))/2. */
  rs_normal_apply_fn apply; /* the product */
  void *context;            /* passed to apply */
} rs_normal_operator;

/* Stopping test: the gap residual r on the contact cells satisfies
 * ||r||_2 <= RS_NORMAL_CG_TOL lambda max(p), which bounds the pressure error by
 * RS_NORMAL_CG_TOL max(p) in every cell; it is confirmed from a recomputed A p to
 * RS_NORMAL_CG_CONFIRM in RMS (that product carries rounding, ~1e-16 |delta| a cell). */
#define RS_NORMAL_CG_TOL     1e-11
#define RS_NORMAL_CG_CONFIRM 1e-8

/* Solve for pn[n] (N/mm^2) and the approach (mm; may be NULL). gap[n]: undeformed gap h
 * at the cells (any shape). start[n]: a start pressure (>= 0, positive sum; scaled to the
 * load) or NULL for a uniform one; any start gives the same solution. iterations: CG
 * iterations (products A t; may be NULL). Needs load > 0. Cells outside the contact get
 * p = 0 exactly; gap within 1e-12 (max h + |delta|) of 0 on the contact and above -that
 * outside. */
int rs_normal_cg_solve(const rs_normal_operator *op, const double *gap, double load,
                       const double *start, double *pn, double *approach, int *iterations,
                       rs_msg *msg);

#endif
