/* Private: the coarse space of the 3D preconditioner (linsys_krylov.h), a two-level
 * correction for what the near field misses: the far field of the elastic operator.
 *
 * Coarse space: aggregates of s x s cells, one unknown per aggregate and traction component
 * (a traction constant over the aggregate); Z maps coarse unknowns to traction unknowns.
 * Coarse operator: Galerkin, E = Z^T J Z on the traction rows. The aggregates tile the grid
 * from an offset that leaves the (nx mod s) / 2 columns and (ny mod s) / 2 rows at each edge
 * out (cells outside the contact for the usual extents; they keep the near field only), so
 * every aggregate has the same shape, and on a uniform grid the elastic part of J Z is the
 * traction rows' local Jacobians (with respect to v_s) times one template translated: the
 * kinematic kernel dv_s/dp (docs/model.md §5) summed over an aggregate. E is accumulated from
 * a table of that template, row cell by row cell, without a product by J, and factored by
 * LAPACK (dgetrf); aggregates without a cell in the contact are left out. */
#ifndef ROLLSIM_LINSYS_COARSE_H
#define ROLLSIM_LINSYS_COARSE_H

#include "physics/model.h"

typedef struct rs_coarse {
  int sx, sy;       /* cells per aggregate along x and y */
  int ax, ay, nagg; /* aggregates along x, along y, in all */
  int ox0, oy0;     /* the first aggregate's first column and row */
  int nq, nyt;      /* template table: entries per (component pair, row, phase), rows */
  double *ta, *td;  /* the template's parts in cj and in -V/dx (polyphase tables) */
  double *tab;      /* cj ta - (V/dx) td, for the cj and V/dx of `rate` */
  double tab_cj, tab_a;
  int *agg;   /* per cell: its aggregate (numbered for the table), -1: none */
  int *keep;  /* per aggregate: its coarse index, -1: left out (no cell in contact) */
  int nk, nc; /* aggregates kept, coarse unknowns (2 nk) */
  double *G;  /* nagg-wide accumulation, then the kept part: E^T by columns */
  int *ipiv;
  double *e; /* coarse vector */
  int ready; /* E factored */
  long setups;
} rs_coarse;

/* The coarse space of model m (3D, two components, no extra unknowns) with aggregates of
 * size x size cells. RS_OK, RS_ERR_INTERNAL (out of memory). */
int rs_coarse_create(rs_coarse *c, const rs_model *m, int size, int size_y);
void rs_coarse_free(rs_coarse *c);
/* E = Z^T J Z for the linearisation in w (rs_model_linearise at cj, velocity) and factored;
 * ready says whether it could be (else the preconditioner goes without it). */
int rs_coarse_setup(rs_coarse *c, const rs_model *m, const rs_work *w, double cj, double velocity);
/* y = Z E^-1 Z^T v: y's traction entries set (zero outside the aggregates), the others
 * untouched. */
void rs_coarse_solve(rs_coarse *c, const rs_model *m, const double *v, double *y);

#endif
