/* The contact grid (docs/model.md §2, §5): nx x ny equal cells over the potential contact
 * area, cell centres x0 + (i + 1/2) dx, cell index I = iy nx + ix (x fastest). 2D line
 * contact is ny = 1 with unit width (forces per mm of width). Rolling is along +x:
 * material enters at the high-x edge, so the upstream (inflow-side) neighbour of a cell
 * is the next cell in x, and the cells of the last column take the inflow state. */
#ifndef ROLLSIM_GRID_H
#define ROLLSIM_GRID_H

#include "base/status.h"

typedef struct rs_grid {
  int nx, ny, n;                 /* cells along x, along y (1 in 2D), in all */
  double dx, dy;                 /* mm (2D: dy = 1, the unit width) */
  double area;                   /* dx dy, mm^2 (2D: dx, per unit width) */
  double x_lo, x_hi, y_lo, y_hi; /* outer edges, mm (2D: y_lo = y_hi = 0) */
  double *x, *y;                 /* cell centres, mm [nx], [ny] (2D: y = {0}) */
} rs_grid;

/* Cells with outer edges x_lo..x_hi (nx cells) and y_lo..y_hi (ny cells); 2D: ny = 1 and
 * y_lo = y_hi = 0 (unit width). RS_ERR_INPUT for an empty or reversed range. */
int rs_grid_create(rs_grid *g, int nx, double x_lo, double x_hi, int ny, double y_lo, double y_hi,
                   rs_msg *msg);
void rs_grid_free(rs_grid *g);

/* Upstream neighbour of cell I (the next cell in +x), or -1 where the inflow state
 * enters (the last column). */
static inline int rs_grid_upstream(const rs_grid *g, int I)
{
  return (I % g->nx) + 1 < g->nx ? I + 1 : -1;
}

/* The row (y index) of cell I. */
static inline int rs_grid_row(const rs_grid *g, int I) { return I / g->nx; }

#endif
