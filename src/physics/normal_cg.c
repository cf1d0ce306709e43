/* 2D normal contact by conjugate gradients with the load as a constraint (docs/model.md §3),
 * after Polonsky & Keer (1999, Wear 231, 206-219). The discrete problem is
 *
 *   minimise 1/2 p.A p + h.p  over p >= 0 with dx sum p = load,
 *
 * whose optimality conditions are those of §3 with the approach delta as the
 * multiplier of the load: on the contact cells C = {p > 0} the gap
 * r = A p + h - delta vanishes, outside C it is >= 0. A is positive definite on
 * vectors of zero sum (the logarithmic kernel), so the minimiser is unique: the
 * direct method's solution.
 *
 * One iteration: delta = mean over C of A p + h, so that r on C is the gradient
 * projected on zero-sum vectors; the direction t = r + beta t_old (zero sum on C,
 * zero outside) and the step tau = r.t / t.A t keep the load. Cells whose pressure
 * would turn negative leave C (p = 0); cells outside C that penetrate (r < 0) enter
 * it with p = -tau r; either restarts the directions (beta = 0) and rescales the
 * pressure to the load. With C fixed this is plain CG on A_CC restricted to zero-sum
 * vectors: about 3.5 sqrt(n) iterations to convergence on Carter's case (condition
 * number about 0.7 m on m contact cells). Products by rs_elastic2d_apply (FFT
 * convolution from RS_ELASTIC_FFT_FROM cells). r and u = A p follow the recurrences
 * r -= tau P A t, u -= tau A t while C stays; they are recomputed from p after a
 * change of C and to confirm convergence. */
#include "physics/normal_methods.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The iteration's state on the grid of n cells. */
typedef struct cg_state {
  const rs_elastic2d *el;
  rs_elastic2d_work *w;
  int n;
  const double *h; /* undeformed gap */
  double *p;       /* pressure, > 0 exactly on C */
  double *u;       /* A p */
  double *res;     /* r = A p + h - delta on C, 0 outside */
  double delta;    /* approach: mean over C of A p + h */
  int m;           /* cells in C */
} cg_state;

/* Rescale p to the load (sum p = target), then u, delta and r from p. */
static void recompute(cg_state *s, double target)
{
  const int n = s->n;
  double sum = 0.0;
  for (int i = 0; i < n; i++) sum += s->p[i];
  for (int i = 0; i < n; i++) s->p[i] *= target / sum;
  rs_elastic2d_apply(s->el, s->w, s->el->norm, s->p, s->u, n);
  double sum_gap = 0.0;
  s->m = 0;
  for (int i = 0; i < n; i++)
    if (s->p[i] > 0.0) {
      s->m++;
      sum_gap += s->u[i] + s->h[i];
    }
  s->delta = sum_gap / s->m;
  for (int i = 0; i < n; i++) s->res[i] = s->p[i] > 0.0 ? s->u[i] + s->h[i] - s->delta : 0.0;
}

/* Convergence (see below): ||r||_2 over C below CG_TOL lambda p_max from the
 * recurrence, confirmed by the recomputed r to CG_CONFIRM. */
#define CG_TOL     1e-11
#define CG_CONFIRM 1e-8

int rs_normal2d_solve_cg(const rs_elastic2d *el, rs_elastic2d_work *w, const double *h, double load,
                         double *pn, double *delta_out, int *iterations, rs_msg *msg)
{
  const int n = el->n;
  if (!(load > 0.0))
    return rs_msg_set(msg, RS_ERR_INTERNAL,
                      "normal problem: the CG method needs a positive load (got %g N/mm)", load);
  const double target = load / el->dx;
  double *u = malloc((size_t)n * sizeof *u);
  double *res = malloc((size_t)n * sizeof *res);
  double *dir = malloc((size_t)n * sizeof *dir);   /* t */
  double *adir = malloc((size_t)n * sizeof *adir); /* A t */
  int status = RS_OK;
  if (!u || !res || !dir || !adir) {
    status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory in the normal problem (%d cells)", n);
    goto done;
  }
  cg_state s = {.el = el, .w = w, .n = n, .h = h, .p = pn, .u = u, .res = res};
  /* Start: the Hertz ellipse on the estimated half-width (uniform pressure when there
   * is no estimate). Any start gives the same solution. */
  const double h_start = rs_normal2d_start_gap(el, load);
  double hmax = 0.0;
  int nstart = 0;
  for (int i = 0; i < n; i++) {
    hmax = fmax(hmax, h[i]);
    pn[i] = h[i] < h_start ? sqrt(1.0 - h[i] / h_start) : 0.0;
    nstart += pn[i] > 0.0;
    dir[i] = 0.0;
  }
  if (nstart == 0)
    for (int i = 0; i < n; i++) pn[i] = 1.0;
  /* Convergence. lambda = (A(0) - A(1))/2 lies below the smallest eigenvalue of A_CC
   * on zero-sum vectors, which is 0.708 (A(0) - A(1)) on 100..1000 cells (a
   * cell-to-cell mode; the ratio does not depend on G, nu, L or dx, and a subset C
   * only raises it), so ||r||_2 <= CG_TOL lambda p_max bounds the pressure error by
   * CG_TOL p_max in every cell (for the final C, down to the rounding of A p).
   * The recomputed r carries that rounding, about 1e-16 |delta| per cell (its RMS is
   * 1e-12 lambda p_max on 1600 cells, growing like n): it only has to confirm the
   * recurrence, to CG_CONFIRM in RMS. Penetration is judged as in the direct method. */
  const double lambda = 0.5 * (rs_elastic2d_norm(el, 0) - rs_elastic2d_norm(el, 1));
  const int max_iter = 4 * n + 100;
  int fresh = 1, confirming = 0, restart = 1, steps = 0;
  double rr_old = 1.0, tol_gap = 0.0;
  while (1) {
    if (fresh) {
      recompute(&s, target);
      tol_gap = 1e-12 * (hmax + fabs(s.delta));
      fresh = 0;
    }
    /* r on C has zero sum up to rounding, which the zero-sum directions cannot
     * remove: it belongs to delta. */
    double sum_res = 0.0;
    for (int i = 0; i < n; i++) sum_res += res[i];
    const double mean_res = sum_res / s.m;
    s.delta += mean_res;
    double rr = 0.0, pmax = 0.0;
    int penetrates = 0;
    for (int i = 0; i < n; i++) {
      if (pn[i] > 0.0) {
        res[i] -= mean_res;
        rr += res[i] * res[i];
        pmax = fmax(pmax, pn[i]);
      } else if (u[i] + h[i] - s.delta < -tol_gap) {
        penetrates = 1;
      }
    }
    const double scale = lambda * pmax;
    if (confirming) {
      confirming = 0;
      if (!penetrates && sqrt(rr / s.m) <= CG_CONFIRM * scale) break;
    } else if (!penetrates && sqrt(rr) <= CG_TOL * scale) {
      fresh = confirming = 1;
      continue;
    }
    if (steps == max_iter) {
      status = rs_msg_set(msg, RS_ERR_SOLVER,
                          "normal problem: CG did not converge in %d iterations (%d cells, "
                          "||r|| = %.3g lambda p_max)",
                          max_iter, n, sqrt(rr) / scale);
      goto done;
    }
    steps++;
    /* Direction: zero outside C, zero sum on C; step along it. */
    const double beta = restart ? 0.0 : rr / rr_old;
    rr_old = rr;
    double sum_dir = 0.0;
    for (int i = 0; i < n; i++) {
      dir[i] = pn[i] > 0.0 ? res[i] + beta * dir[i] : 0.0;
      sum_dir += dir[i];
    }
    for (int i = 0; i < n; i++)
      if (pn[i] > 0.0) dir[i] -= sum_dir / s.m;
    rs_elastic2d_apply(el, w, el->norm, dir, adir, n);
    double rt = 0.0, tat = 0.0, sum_adir = 0.0;
    for (int i = 0; i < n; i++)
      if (pn[i] > 0.0) {
        rt += res[i] * dir[i];
        tat += dir[i] * adir[i];
        sum_adir += adir[i];
      }
    if (!(tat > 0.0)) {
      status = rs_msg_set(msg, RS_ERR_SOLVER,
                          "normal problem: CG breakdown at iteration %d (t.A t = %g)", steps, tat);
      goto done;
    }
    const double tau = rt / tat, mean_adir = sum_adir / s.m;
    restart = 0;
    for (int i = 0; i < n; i++) {
      if (pn[i] > 0.0) {
        pn[i] -= tau * dir[i];
        if (pn[i] <= 0.0) { /* tension: leave the contact */
          pn[i] = 0.0;
          restart = 1;
        }
      } else {
        const double gap = u[i] + h[i] - s.delta;
        if (gap < -tol_gap) { /* penetration: enter the contact */
          pn[i] = -tau * gap;
          restart = 1;
        }
      }
    }
    if (restart) {
      fresh = 1;
      continue;
    }
    s.delta -= tau * mean_adir;
    for (int i = 0; i < n; i++) {
      u[i] -= tau * adir[i];
      if (pn[i] > 0.0) res[i] -= tau * (adir[i] - mean_adir);
    }
  }
  if (delta_out) *delta_out = s.delta;
  if (iterations) *iterations = steps;
done:
  free(u);
  free(res);
  free(dir);
  free(adir);
  return status;
}
