/* The profiles of sweep points (output.fields in a sweep file, study/sweep_fields.h): buffers for
 * one point's fields, and the check that every point has the same grid, so that the
 * profiles share one x axis. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "study/sweep_fields.h"
#include "physics/model.h"

int rs_fields_alloc(rs_fields *f, int n)
{
  memset(f, 0, sizeof *f);
  const size_t m = (size_t)(n > 0 ? n : 1);
  f->px = malloc(m * sizeof(double));
  f->pn = malloc(m * sizeof(double));
  f->slip = malloc(m * sizeof(double));
  f->upl = malloc(m * sizeof(double));
  f->ustar = malloc(m * sizeof(double));
  f->tauc = malloc(m * sizeof(double));
  f->regime = malloc(m);
  f->mu = malloc(m * sizeof(double));
  if (!f->px || !f->pn || !f->slip || !f->upl || !f->ustar || !f->tauc || !f->regime || !f->mu) {
    rs_fields_free(f);
    return RS_ERR_INTERNAL;
  }
  f->n = n;
  return RS_OK;
}

void rs_fields_free(rs_fields *f)
{
  free(f->px);
  free(f->pn);
  free(f->slip);
  free(f->upl);
  free(f->ustar);
  free(f->tauc);
  free(f->regime);
  free(f->mu);
  memset(f, 0, sizeof *f);
}

/* y = [p | upl | ustar] (physics/model.h). */
void rs_fields_copy(rs_fields *f, int n, const double *y, const double *pn, const double *slip,
                    const double *tauc, const signed char *regime, const double *mu)
{
  const size_t bytes = (size_t)n * sizeof(double);
  memcpy(f->px, y, bytes);
  memcpy(f->upl, y + n, bytes);
  memcpy(f->ustar, y + 2 * n, bytes);
  memcpy(f->pn, pn, bytes);
  memcpy(f->slip, slip, bytes);
  memcpy(f->tauc, tauc, bytes);
  memcpy(f->regime, regime, (size_t)n);
  memcpy(f->mu, mu, bytes);
}

unsigned rs_sweep_profile_fields(const rs_case *c, int warn)
{
  const unsigned fields =
      (c->has_plasticity ? c->fields : c->fields & ~(unsigned)RS_FIELD_TAUC) |
      (c->fields && (rs_friction_varies(&c->friction) || c->mu_table.n) ? (unsigned)RS_FIELD_MU
                                                                        : 0u);
  if (fields && c->dimension == 3) {
    if (warn)
      fprintf(stderr, "rollsim sweep: warning: output.fields not stored: a 3D sweep file holds "
                      "the forces and counts of every point; rollsim run gives a point's fields "
                      "(output.fields: [] silences this)\n");
    return 0;
  }
  return fields;
}

/* The model of the case derived with one override. */
static int model_with(const rs_case *base, rs_case_override ov, rs_model *m, rs_msg *msg)
{
  rs_case c;
  int status = rs_case_derive(base, &ov, 1, &c, msg);
  if (status != RS_OK) return status;
  status = rs_model_from_case(m, &c, msg);
  rs_case_free(&c);
  return status;
}

int rs_sweep_common_grid(const rs_sweep *s, const rs_case *c, int *common_out, double **x, int *n,
                         char *why, size_t why_len, rs_msg *msg)
{
  *x = NULL;
  *n = 0;
  *common_out = 0;
  why[0] = '\0';
  rs_model base;
  int status = rs_model_from_case(&base, c, msg);
  if (status != RS_OK) return status;
  double xmax = 0.0;
  for (int i = 0; i < base.grid.n; i++) xmax = fmax(xmax, fabs(base.grid.x[i]));
  int common = 1;
  for (int a = 0; a < s->naxes && common; a++) {
    /* A rolling input leaves the grid as it is: it is sized on the normal load, whose
     * largest value depends on the run's length only when the load varies. */
    if (rs_case_key_rolling(s->axes[a].key_index) != RS_ROLLING_NONE &&
        rs_history_is_constant(&c->normal_load))
      continue;
    for (int k = 0; k < s->axes[a].n && common; k++) {
      rs_model m;
      const rs_case_override ov = {s->axes[a].key_index, s->axes[a].values[k]};
      if ((status = model_with(c, ov, &m, msg)) != RS_OK) {
        rs_model_free(&base);
        return status;
      }
      common = m.grid.n == base.grid.n;
      for (int i = 0; common && i < m.grid.n; i++)
        common = fabs(m.grid.x[i] - base.grid.x[i]) <= 1e-12 * xmax;
      if (!common)
        snprintf(why, why_len,
                 "the grid changes with %s (%s = %.6g: %d cells over [%.6g, %.6g] mm)",
                 s->axes[a].key, s->axes[a].key, s->axes[a].values[k], m.grid.n, m.grid.x[0],
                 m.grid.x[m.grid.n - 1]);
      rs_model_free(&m);
    }
  }
  if (common) {
    *x = malloc((size_t)base.grid.n * sizeof **x);
    if (!*x) {
      rs_model_free(&base);
      return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
    }
    memcpy(*x, base.grid.x, (size_t)base.grid.n * sizeof **x);
    *n = base.grid.n;
  }
  rs_model_free(&base);
  *common_out = common;
  return RS_OK;
}
