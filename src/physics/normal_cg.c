/* Constrained conjugate gradients for the normal contact problem, for any dimension
 * (physics/normal_cg.h; Polonsky & Keer 1999, Wear 231, 206-219).
 *
 * With the contact set C = {p > 0} fixed, the problem is: minimise 1/2 p.A p + h.p on C
 * with sum p fixed. Its gradient A p + h projected on zero-sum vectors is the gap
 * residual r = A p + h - delta on C, delta = mean over C of A p + h. CG on that subspace:
 * directions t = r + beta t_old (zero sum on C, zero outside), step tau = r.t / t.A t,
 * which keeps the load. The contact set changes inside the iteration (Polonsky & Keer):
 * cells whose pressure would turn negative leave C (p = 0); cells outside C that
 * penetrate (A p + h - delta < 0) enter with p = -tau (A p + h - delta) > 0. Either
 * restarts the directions (beta = 0), rescales p to the load and recomputes u = A p;
 * otherwise u, r and delta follow the recurrences u -= tau A t, r -= tau P A t, where P
 * removes the mean over C. One product A t per iteration. */
#include "physics/normal_cg.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct cg_state {
  const rs_normal_operator *op;
  const double *h; /* undeformed gap */
  double *p;       /* pressure, > 0 exactly on C */
  double *u;       /* A p */
  double *r;       /* gap residual on C, 0 outside */
  double delta;    /* approach: mean over C of u + h */
  int m;           /* cells in C */
} cg_state;

/* Rescale p to the load (sum p = target), then u = A p, delta and r from it. */
static void recompute(cg_state *s, double target)
{
  const int n = s->op->n;
  double sum = 0.0;
  for (int i = 0; i < n; i++) sum += s->p[i];
  for (int i = 0; i < n; i++) s->p[i] *= target / sum;
  s->op->apply(s->op->context, s->p, s->u);
  double sum_gap = 0.0;
  s->m = 0;
  for (int i = 0; i < n; i++)
    if (s->p[i] > 0.0) {
      s->m++;
      sum_gap += s->u[i] + s->h[i];
    }
  s->delta = sum_gap / s->m;
  for (int i = 0; i < n; i++) s->r[i] = s->p[i] > 0.0 ? s->u[i] + s->h[i] - s->delta : 0.0;
}

int rs_normal_cg_solve(const rs_normal_operator *op, const double *gap, double load,
                       const double *start, double *pn, double *approach, int *iterations,
                       rs_msg *msg)
{
  const int n = op->n;
  if (!(load > 0.0) || !isfinite(load))
    return rs_msg_set(msg, RS_ERR_INPUT, "normal problem: the load must be positive (got %g N)",
                      load);
  if (n < 1 || !(op->cell_area > 0.0) || !(op->lambda > 0.0))
    return rs_msg_set(msg, RS_ERR_INTERNAL,
                      "normal problem: bad operator (%d cells, cell area %g, lambda %g)", n,
                      op->cell_area, op->lambda);
  double *work = malloc(4 * (size_t)n * sizeof *work);
  if (!work)
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory in the normal problem (%d cells)", n);
  double *u = work, *r = work + n, *dir = work + 2 * (size_t)n, *adir = work + 3 * (size_t)n;
  cg_state s = {.op = op, .h = gap, .p = pn, .u = u, .r = r};
  const double target = load / op->cell_area;
  double hmax = 0.0, start_sum = 0.0;
  for (int i = 0; i < n; i++) {
    hmax = fmax(hmax, fabs(gap[i]));
    pn[i] = start && start[i] > 0.0 ? start[i] : 0.0;
    start_sum += pn[i];
    dir[i] = 0.0;
  }
  if (!(start_sum > 0.0) || !isfinite(start_sum))
    for (int i = 0; i < n; i++) pn[i] = 1.0;
  const int max_iter = 4 * n + 100;
  int status = RS_OK, fresh = 1, confirming = 0, restart = 1, steps = 0;
  double rr_old = 1.0, tol_gap = 0.0;
  while (1) {
    if (fresh) {
      recompute(&s, target);
      tol_gap = 1e-12 * (hmax + fabs(s.delta));
      fresh = 0;
    }
    /* The part of r along the constant vector belongs to delta (rounding only). */
    double sum_r = 0.0;
    for (int i = 0; i < n; i++) sum_r += r[i];
    const double mean_r = sum_r / s.m;
    s.delta += mean_r;
    double rr = 0.0, pmax = 0.0;
    int penetrates = 0;
    for (int i = 0; i < n; i++) {
      if (pn[i] > 0.0) {
        r[i] -= mean_r;
        rr += r[i] * r[i];
        pmax = fmax(pmax, pn[i]);
      } else if (u[i] + gap[i] - s.delta < -tol_gap) {
        penetrates = 1;
      }
    }
    const double scale = op->lambda * pmax;
    if (confirming) {
      confirming = 0;
      if (!penetrates && sqrt(rr / s.m) <= RS_NORMAL_CG_CONFIRM * scale) break;
    } else if (!penetrates && sqrt(rr) <= RS_NORMAL_CG_TOL * scale) {
      fresh = confirming = 1;
      continue;
    }
    if (steps == max_iter) {
      status = rs_msg_set(msg, RS_ERR_SOLVER,
                          "normal problem: CG did not converge in %d iterations (%d cells, "
                          "%d in contact, ||r|| = %.3g lambda p_max)",
                          max_iter, n, s.m, sqrt(rr) / scale);
      goto done;
    }
    steps++;
    /* Direction: zero outside C, zero sum on C. */
    const double beta = restart ? 0.0 : rr / rr_old;
    rr_old = rr;
    double sum_dir = 0.0;
    for (int i = 0; i < n; i++) {
      dir[i] = pn[i] > 0.0 ? r[i] + beta * dir[i] : 0.0;
      sum_dir += dir[i];
    }
    for (int i = 0; i < n; i++)
      if (pn[i] > 0.0) dir[i] -= sum_dir / s.m;
    op->apply(op->context, dir, adir);
    double rt = 0.0, tat = 0.0, sum_adir = 0.0;
    for (int i = 0; i < n; i++)
      if (pn[i] > 0.0) {
        rt += r[i] * dir[i];
        tat += dir[i] * adir[i];
        sum_adir += adir[i];
      }
    if (!(tat > 0.0)) {
      status = rs_msg_set(msg, RS_ERR_SOLVER,
                          "normal problem: CG breakdown at iteration %d (t.A t = %g): the "
                          "influence operator is not positive definite",
                          steps, tat);
      goto done;
    }
    const double tau = rt / tat, mean_adir = sum_adir / s.m;
    restart = 0;
    for (int i = 0; i < n; i++) {
      if (pn[i] > 0.0) {
        pn[i] -= tau * dir[i];
        if (pn[i] <= 0.0) { /* tension: leaves the contact */
          pn[i] = 0.0;
          restart = 1;
        }
      } else {
        const double g = u[i] + gap[i] - s.delta;
        if (g < -tol_gap) { /* penetration: enters the contact */
          pn[i] = -tau * g;
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
      if (pn[i] > 0.0) r[i] -= tau * (adir[i] - mean_adir);
    }
  }
  if (approach) *approach = s.delta;
  if (iterations) *iterations = steps;
done:
  free(work);
  return status;
}
