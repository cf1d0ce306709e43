/* The contact grid (physics/grid.h). */
#include "physics/grid.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int rs_grid_create(rs_grid *g, int nx, double x_lo, double x_hi, int ny, double y_lo, double y_hi,
                   rs_msg *msg)
{
  memset(g, 0, sizeof *g);
  const int line = ny == 1 && y_lo == 0.0 && y_hi == 0.0;
  if (nx < 1 || ny < 1 || !(x_hi > x_lo) || (!line && !(y_hi > y_lo)))
    return rs_msg_set(msg, RS_ERR_INPUT, "grid: %d x %d cells over [%g, %g] x [%g, %g] mm is empty",
                      nx, ny, x_lo, x_hi, y_lo, y_hi);
  g->nx = nx;
  g->ny = ny;
  g->n = nx * ny;
  g->dx = (x_hi - x_lo) / nx;
  g->dy = line ? 1.0 : (y_hi - y_lo) / ny;
  g->area = line ? g->dx : g->dx * g->dy;
  g->x_lo = x_lo;
  g->x_hi = x_hi;
  g->y_lo = y_lo;
  g->y_hi = y_hi;
  g->x = malloc((size_t)nx * sizeof *g->x);
  g->y = malloc((size_t)ny * sizeof *g->y);
  if (!g->x || !g->y) {
    rs_grid_free(g);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for a grid of %d x %d cells", nx, ny);
  }
  for (int i = 0; i < nx; i++) g->x[i] = x_lo + (i + 0.5) * g->dx;
  for (int j = 0; j < ny; j++) g->y[j] = line ? 0.0 : y_lo + (j + 0.5) * g->dy;
  return RS_OK;
}

void rs_grid_free(rs_grid *g)
{
  free(g->x);
  free(g->y);
  memset(g, 0, sizeof *g);
}
