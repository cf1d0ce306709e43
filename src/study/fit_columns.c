/* Finite-difference columns of the fit's Jacobian (study/fit_internal.h). Serially one
 * after the other; under MPI column k is computed by rank k mod size: rank 0 sends the
 * parameters to every other rank, computes its own columns and collects the others'
 * simulated values. Each column is computed whole by the same code from the same p and
 * step, so the Jacobian has the serial one's bits. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "study/fit_internal.h"
#include "study/mpi_session.h"

enum { TAG_PARAMS = 11, TAG_COLUMN = 12, TAG_STOP = 13 };

struct rs_fit_columns {
  int n;
  size_t m;
  int rank, size;
  double *p, *sim, *msg; /* msg: [k, status, sim...] */
};

int rs_fit_columns_create(rs_fit_columns **c, const rs_fit_spec *f, int rank, int size, rs_msg *msg)
{
  *c = calloc(1, sizeof **c);
  if (*c) {
    (*c)->n = f->nparams;
    (*c)->m = f->npoints;
    (*c)->rank = rank;
    (*c)->size = size > 1 ? size : 1;
    (*c)->p = calloc((size_t)f->nparams, sizeof *(*c)->p);
    (*c)->sim = calloc(f->npoints, sizeof *(*c)->sim);
    (*c)->msg = calloc(f->npoints + 2, sizeof *(*c)->msg);
  }
  if (!*c || !(*c)->p || !(*c)->sim || !(*c)->msg) {
    rs_fit_columns_free(*c);
    *c = NULL;
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  }
  return RS_OK;
}

void rs_fit_columns_free(rs_fit_columns *c)
{
  if (!c) return;
  if (c->rank == 0) /* the workers wait for parameters: tell them to stop */
    for (int r = 1; r < c->size; r++) {
      const double none = 0;
      rs_mpi_send_doubles(&none, 1, r, TAG_STOP);
    }
  free(c->p);
  free(c->sim);
  free(c->msg);
  free(c);
}

/* Simulated values at p + h_k e_k into sim. */
static int column_sim(rs_fit_columns *c, rs_fit_eval *e, const double *p, int k, double *h,
                      double *sim, rs_msg *msg)
{
  memcpy(c->p, p, (size_t)c->n * sizeof *p);
  *h = rs_fit_fd_step(&e->f->params[k], p[k]);
  c->p[k] = p[k] + *h;
  return rs_fit_eval_at(e, c->p, sim, msg);
}

int rs_fit_columns_eval(rs_fit_columns *c, rs_fit_eval *e, const double *p, const double *sim0,
                        const double *w, double *jac, int ld, rs_msg *msg)
{
  for (int r = 1; r < c->size && r < c->n; r++)
    if (rs_mpi_send_doubles(p, c->n, r, TAG_PARAMS) != 0)
      return rs_msg_set(msg, RS_ERR_INTERNAL, "MPI_Send failed");
  int status = RS_OK;
  for (int k = 0; k < c->n; k++) {
    double h;
    int st;
    if (k % c->size == 0) {
      st = column_sim(c, e, p, k, &h, c->sim, msg);
    } else {
      int n = 0;
      if (rs_mpi_recv_doubles(c->msg, (int)c->m + 2, k % c->size, TAG_COLUMN, NULL, NULL, &n) != 0)
        return rs_msg_set(msg, RS_ERR_INTERNAL, "MPI_Recv failed");
      st = (int)c->msg[1];
      h = rs_fit_fd_step(&e->f->params[k], p[k]);
      memcpy(c->sim, c->msg + 2, c->m * sizeof *c->sim);
      e->evaluations++;
      if (st != RS_OK)
        rs_msg_set(msg, st, "rank %d: column %d (%s) failed", k % c->size, k + 1,
                   e->f->params[k].key);
    }
    if (st != RS_OK && status == RS_OK) status = st;
    for (size_t i = 0; st == RS_OK && i < c->m; i++)
      jac[(size_t)k * (size_t)ld + i] = w[i] * (c->sim[i] - sim0[i]) / h;
  }
  return status;
}

int rs_fit_columns_serve(rs_fit_columns *c, rs_fit_eval *e)
{
  double *p = malloc((size_t)c->n * sizeof *p);
  if (!p) return RS_ERR_INTERNAL;
  for (;;) {
    int tag = 0, n = 0;
    if (rs_mpi_recv_doubles(p, c->n, 0, -1, NULL, &tag, &n) != 0 || tag == TAG_STOP) break;
    for (int k = c->rank; k < c->n; k += c->size) {
      double h;
      rs_msg msg = {{0}};
      const int st = column_sim(c, e, p, k, &h, c->msg + 2, &msg);
      c->msg[0] = k;
      c->msg[1] = st;
      if (st != RS_OK)
        for (size_t i = 0; i < c->m; i++) c->msg[2 + i] = NAN;
      rs_mpi_send_doubles(c->msg, (int)c->m + 2, 0, TAG_COLUMN);
    }
  }
  free(p);
  return RS_OK;
}
