/* Hou's single element in 3D (docs/verification.md 13, issue 13): one material point of the
 * layer, p = k_e (u - u_pl), loaded along x into yield and then along y, integrated by
 * implicit Euler with the cell's contact law (rs_contact_law, ncomp = 2: the projection
 * on the disk |p| <= tau_c). Friction is kept inactive (g huge, no slip).
 *
 * Perfect plasticity (k_tau = 0), analytic: once on the yield circle |p| = tau_c0, a
 * displacement s along y turns p by the angle theta with tau_c0 dtheta = k_e cos(theta) ds,
 * so theta(s) = gd(k_e s / tau_c0) (the Gudermann function, 2 atan(tanh(x/2))), and the
 * plastic flow Du_pl/Dt is parallel to p at every step (radial return). Checked: flow
 * parallel to p to rounding, |p| = tau_c0, u*' = |u_pl'| to rounding, theta against gd
 * with first-order convergence of implicit Euler (error halves with the step).
 * With hardening (k_tau > 0): |p| = tau_c0 + k_tau u* at every plastic step. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "physics/contact_law.h"
#include "test_support.h"

#define KE   1.0e5 /* N/mm^3: element stiffness */
#define TAU0 100.0 /* N/mm^2 */

typedef struct element {
  double p[2], upl[2], ustar;
  double worst_parallel, worst_radius, worst_dustar, worst_hardening;
} element;

/* Solve 5 x 5 A x = b by Gaussian elimination with partial pivoting. */
static int solve5(double A[5][5], double b[5])
{
  for (int k = 0; k < 5; k++) {
    int piv = k;
    for (int i = k + 1; i < 5; i++)
      if (fabs(A[i][k]) > fabs(A[piv][k])) piv = i;
    if (A[piv][k] == 0.0) return -1;
    if (piv != k) {
      for (int j = 0; j < 5; j++) {
        const double t = A[k][j];
        A[k][j] = A[piv][j];
        A[piv][j] = t;
      }
      const double t = b[k];
      b[k] = b[piv];
      b[piv] = t;
    }
    for (int i = k + 1; i < 5; i++) {
      const double f = A[i][k] / A[k][k];
      for (int j = k; j < 5; j++) A[i][j] -= f * A[k][j];
      b[i] -= f * b[k];
    }
  }
  for (int k = 4; k >= 0; k--) {
    for (int j = k + 1; j < 5; j++) b[k] -= A[k][j] * b[j];
    b[k] /= A[k][k];
  }
  return 0;
}

/* One implicit Euler step of length dt to the total displacement u[2]. Unknowns z = (p_x,
 * p_y, f_x, f_y, d): f = Du_pl/Dt, d = Du* /Dt, u_pl = u_pl_old + dt f, u* = u*_old + dt d. */
/* The local Jacobian's entry, 0 where not present (rs_law_out) */
static double entry(const rs_law_out *o, int row, int var)
{
  return o->present[row][var] ? o->jac[row][var] : 0.0;
}

static int step(element *e, const rs_plasticity *pl, const double u[2], double dt)
{
  double z[5] = {e->p[0], e->p[1], 0.0, 0.0, 0.0};
  const int nc = 2;
  rs_law_out out;
  for (int it = 0; it < 50; it++) {
    rs_law_in in = {.ncomp = nc,
                    .in_contact = 1,
                    .p = {z[0], z[1]},
                    .vs = {0.0, 0.0},
                    .flow = {z[2], z[3]},
                    .dustar = z[4],
                    .ustar = e->ustar + dt * z[4],
                    .g = 1e12,
                    .r = KE * dt};
    memset(&out, 0, sizeof out); /* the law sets only the entries present on its branch */
    rs_contact_law(pl, &in, 1, &out);
    double F[5], A[5][5] = {{0}};
    for (int c = 0; c < 2; c++) { /* elastic element: p - k_e (u - u_pl) */
      F[c] = z[c] - KE * (u[c] - e->upl[c] - dt * z[2 + c]);
      A[c][c] = 1.0;
      A[c][2 + c] = KE * dt;
    }
    const int rows[3] = {rs_law_row_pl(nc, 0), rs_law_row_pl(nc, 1), rs_law_row_star(nc)};
    for (int k = 0; k < 3; k++) {
      const int row = rows[k];
      F[2 + k] = out.R[row];
      for (int c = 0; c < 2; c++) {
        A[2 + k][c] = entry(&out, row, rs_law_var_p(c));
        A[2 + k][2 + c] = entry(&out, row, rs_law_var_flow(nc, c));
      }
      A[2 + k][4] =
          entry(&out, row, rs_law_var_dustar(nc)) + dt * entry(&out, row, rs_law_var_ustar(nc));
    }
    double norm = 0.0;
    for (int k = 0; k < 5; k++) norm = fmax(norm, fabs(F[k]));
    if (norm <= 1e-13 * TAU0) break;
    if (it == 49 || solve5(A, F) != 0) return -1;
    for (int k = 0; k < 5; k++) z[k] -= F[k];
  }
  e->p[0] = z[0];
  e->p[1] = z[1];
  for (int c = 0; c < 2; c++) e->upl[c] += dt * z[2 + c];
  e->ustar += dt * z[4];
  const double pn = hypot(z[0], z[1]), fn = hypot(z[2], z[3]);
  if (fn > 1e-6 * TAU0 / KE) { /* a plastic step (rates are ~TAU0/KE per unit time) */
    e->worst_parallel = fmax(e->worst_parallel, fabs(z[2] * z[1] - z[3] * z[0]) / (fn * pn));
    e->worst_dustar = fmax(e->worst_dustar, fabs(z[4] - fn) / fn);
    const double tc = rs_yield_limit(pl, e->ustar);
    e->worst_hardening = fmax(e->worst_hardening, fabs(pn - tc) / tc);
    if (pl->k_tau == 0.0) e->worst_radius = fmax(e->worst_radius, fabs(pn - TAU0) / TAU0);
  }
  return 0;
}

/* Load along x to 3 yield displacements, then along y by S; returns theta at the end
 * (and the element). */
static double path(const rs_plasticity *pl, int steps, double S, element *e)
{
  memset(e, 0, sizeof *e);
  const double ux = 3.0 * TAU0 / KE;
  for (int k = 1; k <= steps; k++) {
    const double u[2] = {ux * k / steps, 0.0};
    if (step(e, pl, u, 1.0 / steps) != 0) return NAN;
  }
  for (int k = 1; k <= steps; k++) {
    const double u[2] = {ux, S * k / steps};
    if (step(e, pl, u, 1.0 / steps) != 0) return NAN;
  }
  return atan2(e->p[1], e->p[0]);
}

int main(void)
{
  const rs_plasticity perfect = {.on = 1, .tau_c0 = TAU0, .k_tau = 0.0, .tau_c_min = 10.0};
  const double S = 2.0 * TAU0 / KE;                           /* 2 yield displacements along y */
  const double theta = 2.0 * atan(tanh(0.5 * KE * S / TAU0)); /* gd(2) = 1.3018 rad */
  double err[3];
  const int steps[3] = {200, 400, 800};
  element e;
  for (int k = 0; k < 3; k++) {
    err[k] = path(&perfect, steps[k], S, &e) - theta;
    printf("     %d steps per leg: theta = %.9f rad, gd = %.9f, error %.3e\n", steps[k],
           theta + err[k], theta, err[k]);
  }
  /* Newton stops at 1e-13 tau_c0 in the rows (r = k_e dt): 1e-9 relative in the rates */
  ts_check("perfect plasticity: plastic flow parallel to p (sin of the angle)", e.worst_parallel,
           0.0, 1e-9);
  ts_check("perfect plasticity: |p| = tau_c0 in plastic steps (relative)", e.worst_radius, 0.0,
           1e-12);
  ts_check("Du*/Dt = |Du_pl/Dt| (relative)", e.worst_dustar, 0.0, 1e-9);
  /* implicit Euler is first order: the error halves with the step (ratio 2 within 10 %) */
  ts_check("theta error ratio 200 -> 400 steps (first order)", err[0] / err[1], 2.0, 0.2);
  ts_check("theta error ratio 400 -> 800 steps (first order)", err[1] / err[2], 2.0, 0.2);
  ts_check("theta against gd(k_e s/tau_c0) at 800 steps per leg (rad)", err[2], 0.0, 2e-3);
  ts_check_true("the traction turned (theta > 1 rad)", theta + err[2] > 1.0);

  const rs_plasticity hard = {.on = 1, .tau_c0 = TAU0, .k_tau = 2.0e4, .tau_c_min = 10.0};
  path(&hard, 400, S, &e);
  ts_check("hardening: |p| = tau_c0 + k_tau u* in plastic steps (relative)", e.worst_hardening, 0.0,
           1e-12);
  ts_check("hardening: plastic flow parallel to p", e.worst_parallel, 0.0, 1e-9);
  ts_check_true("hardening: u* grew", e.ustar > 0.0);
  return ts_failures ? 1 : 0;
}
