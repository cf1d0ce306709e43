/* Finite-difference columns of the fit's Jacobian (app/fit_internal.h), computed one
 * after the other in this process. */
#include <stdlib.h>
#include <string.h>

#include "app/fit_internal.h"

struct rs_fit_columns {
  int n;
  size_t m;
  double *p, *sim;
};

int rs_fit_columns_create(rs_fit_columns **c, const rs_fit_spec *f, rs_msg *msg)
{
  *c = calloc(1, sizeof **c);
  if (*c) {
    (*c)->n = f->nparams;
    (*c)->m = f->npoints;
    (*c)->p = calloc((size_t)f->nparams, sizeof *(*c)->p);
    (*c)->sim = calloc(f->npoints, sizeof *(*c)->sim);
  }
  if (!*c || !(*c)->p || !(*c)->sim) {
    rs_fit_columns_free(*c);
    *c = NULL;
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  }
  return RS_OK;
}

void rs_fit_columns_free(rs_fit_columns *c)
{
  if (!c) return;
  free(c->p);
  free(c->sim);
  free(c);
}

int rs_fit_columns_eval(rs_fit_columns *c, rs_fit_eval *e, const double *p, const double *sim0,
                        const double *w, double *jac, int ld, rs_msg *msg)
{
  for (int k = 0; k < c->n; k++) {
    memcpy(c->p, p, (size_t)c->n * sizeof *p);
    const double h = rs_fit_fd_step(&e->f->params[k], p[k]);
    c->p[k] = p[k] + h;
    const int status = rs_fit_eval_at(e, c->p, c->sim, msg);
    if (status != RS_OK) return status;
    for (size_t i = 0; i < c->m; i++)
      jac[(size_t)k * (size_t)ld + i] = w[i] * (c->sim[i] - sim0[i]) / h;
  }
  return RS_OK;
}
