/* Velocity-dependent friction in 3D steady rolling (docs/model.md §10-11, docs/verification.md 14),
 * on an elastic elliptic contact: Rx = 100 mm, Ry = 200 mm, F = 1000 N, G = 82000 N/mm^2, nu =
 * 0.28, V = 30000 mm/s, 22 x 22 cells over +-1.1 a, +-1.1 b.
 *
 * 1. Coulomb limit. At xi = -8e-4, eta = 4e-4, phi = 2e-4 1/mm (partial slip; the slip
 *    speeds of the Coulomb solution, recomputed as in 2., reach 86 mm/s), the exponential
 *    law with v_h = 1e9 mm/s and the Polach law with B = 1e-9 s/mm are Coulomb with mu =
 *    mu_k + mu_excess = 0.3 (mu_static) to within dmu = mu_excess ln2 |v_s| / v_h
 *    (exponential) or mu_s (1 - A) B |v_s| (Polach), evaluated at twice the largest slip
 *    speed: 1.2e-8 and 3.1e-8. The bound changes by dmu p_n <= dmu p0, and the tractions
 *    by about as much (the adhesion zone answers a change of the slip zone's tractions
 *    elastically, no more). Tolerance 1e-8 p0 (Newton: a residual below 1e-9 of the
 *    bound's scale, plus margin) plus 3 dmu p0, both components, against the Coulomb
 *    solution.
 * 2. Full sliding. At xi = -1 %, eta = 0.5 %, phi = 1e-4 1/mm (rigid slip ~335 mm/s, no
 *    adhesion), every contact cell carries |p| = mu(|v_s|) p_n with v_s opposite to p,
 *    where v_s = V (xi - phi y, eta + phi x) + D u_el/Dt is recomputed here from the
 *    tractions by direct sums over the influence coefficients A_ab(kx, ky) (u_el = sum A p,
 *    D/Dt = -V (u(ix+1) - u(ix))/dx, the upwind difference of the model; the solver uses FFT
 *    products), not taken from the model's kinematics. Tolerance 1e-8 p0 (Newton tolerance
 *    and roundoff), direction to 1e-6 in the cosine; the bound the law reports (the g of
 *    each cell, which the output's mu field divides by p_n) equals mu(|v_s|) p_n to the same
 *    tolerance; |F|/F_n lies between mu at the fastest and the slowest cell. Every law, with
 *    parameters whose mu(335 mm/s) lies between mu_k and mu(0) (the check sees the law). */
#include <stdlib.h>

#include "solve/steady.h"
#include "test_support.h"

/* mu(0) = 0.3 for every law; the excess halves at about v_h (exponential, rational's first
 * term), the linear law's kink at 2 v_h. */
static void set_law(rs_case *c, rs_friction_kind kind, double v_h)
{
  rs_friction f = {.kind = kind, .mu_kinetic = 0.2, .terms = 1};
  f.mu_excess[0] = 0.1;
  f.half_velocity[0] = v_h;
  if (kind == RS_FRICTION_RATIONAL) {
    f.terms = 2;
    f.mu_excess[0] = f.mu_excess[1] = 0.05;
    f.half_velocity[1] = 3.0 * v_h;
  }
  if (kind == RS_FRICTION_POLACH) {
    f.mu_static = 0.3;
    f.polach_a = 0.4;
    f.polach_b = 0.3 / v_h; /* s/mm */
  }
  c->friction = f;
  c->mu = rs_friction_mu(&f, 0.0);
}

static int solve(rs_case *c, rs_model *m, double **y, rs_stats *st)
{
  rs_msg msg = {{0}};
  if (rs_model_from_case(m, c, &msg) != RS_OK) {
    printf("FAIL model: %s\n", msg.text);
    return ts_failures++, 1;
  }
  *y = calloc((size_t)m->lay.neq, sizeof **y);
  rs_steady *s = NULL;
  const int status = rs_steady_create(&s, m, NULL, &msg) == RS_OK
                         ? rs_steady_solve(s, 0.0, *y, st, &msg)
                         : RS_ERR_SOLVER;
  rs_steady_free(s);
  if (status != RS_OK) {
    printf("FAIL steady: %s\n", msg.text);
    rs_model_free(m);
    free(*y);
    return ts_failures++, 1;
  }
  return 0;
}

/* v_s of every cell (2 blocks of n) from the tractions by direct sums (elastic, steady). */
static void slip_velocity(const rs_model *m, const rs_case *c, const double *y, double *vs)
{
  const int nx = m->grid.nx, ny = m->grid.ny, n = m->grid.n;
  const double V = c->velocity.value, xi = c->creepage.value;
  const double eta = c->lateral_creepage.value, phi = c->spin.value;
  double *u = malloc(2 * (size_t)(nx + 1) * (size_t)ny * sizeof *u);
  for (int a = 0; a < 2; a++)
    for (int iy = 0; iy < ny; iy++)
      for (int ix = 0; ix <= nx; ix++) { /* the padded column ix = nx included */
        double sum = 0.0;
        for (int b = 0; b < 2; b++)
          for (int J = 0; J < n; J++)
            sum += rs_elastic_op_coef(&m->el, a, b, ix - J % nx, iy - J / nx) * y[b * n + J];
        u[((size_t)a * ny + iy) * (nx + 1) + ix] =
            sum + (ix < nx ? m->layer_flex * y[a * n + iy * nx + ix] : 0.0);
      }
  for (int a = 0; a < 2; a++)
    for (int iy = 0; iy < ny; iy++)
      for (int ix = 0; ix < nx; ix++) {
        const double *ua = u + ((size_t)a * ny + iy) * (nx + 1);
        const double rigid =
            a == 0 ? V * (xi - phi * m->grid.y[iy]) : V * (eta + phi * m->grid.x[ix]);
        vs[a * n + iy * nx + ix] = rigid - V * (ua[ix + 1] - ua[ix]) / m->grid.dx;
      }
  free(u);
}

static void coulomb_limit(void)
{
  rs_case c;
  rs_model mc;
  double *yc = NULL;
  rs_stats st = {0};
  ts_ellipse_case(&c, 22, 2.0, -8e-4, 4e-4, 2e-4);
  if (solve(&c, &mc, &yc, &st)) return;
  const int n = mc.grid.n;
  double *vs = malloc(2 * (size_t)n * sizeof *vs);
  slip_velocity(&mc, &c, yc, vs);
  double vmax = 0.0;
  int slipping = 0;
  for (int i = 0; i < n; i++) {
    const double v = hypot(vs[i], vs[n + i]);
    if (mc.pn[i] > 0.0) vmax = fmax(vmax, v);
    slipping += mc.pn[i] > 0.0 && v > 1.0; /* mm/s */
  }
  printf("Coulomb solution: %d slipping cells, slip speeds up to %.4g mm/s\n", slipping, vmax);
  ts_check_true("Coulomb solution: partial slip", slipping > 0);
  for (int k = 0; k < 2; k++) {
    rs_case cf = c;
    rs_model mf;
    double *yf = NULL;
    set_law(&cf, k == 0 ? RS_FRICTION_EXPONENTIAL : RS_FRICTION_POLACH, 1.0);
    if (k == 0) {
      cf.friction.half_velocity[0] = 1e9; /* mm/s */
    } else {
      cf.friction.polach_b = 1e-9; /* s/mm */
    }
    cf.mu = rs_friction_mu(&cf.friction, 0.0);
    if (solve(&cf, &mf, &yf, &st)) continue;
    const double dmu = 0.3 - rs_friction_mu(&cf.friction, 2.0 * vmax); /* margin: 2 vmax */
    double worst = 0.0;
    for (int i = 0; i < 2 * n; i++) worst = fmax(worst, fabs(yf[i] - yc[i]));
    char what[160];
    snprintf(what, sizeof what,
             "Coulomb limit (%s, mu(2 v_max) = 0.3 - %.2g): max |p - p_Coulomb| / p0, both "
             "components",
             k == 0 ? "exponential v_h = 1e9 mm/s" : "Polach B = 1e-9 s/mm", dmu);
    ts_check(what, worst / mc.hertz_p0, 0.0, 1e-8 + 3.0 * dmu);
    free(yf);
    rs_model_free(&mf);
  }
  free(vs);
  free(yc);
  rs_model_free(&mc);
}

static void full_sliding(rs_friction_kind kind, double v_h)
{
  rs_case c;
  rs_model m;
  double *y = NULL;
  rs_stats st = {0};
  ts_ellipse_case(&c, 22, 2.0, -0.01, 0.005, 1e-4);
  set_law(&c, kind, v_h);
  const char *name = rs_friction_name(kind);
  if (solve(&c, &m, &y, &st)) return;
  const int n = m.grid.n;
  double *vs = malloc(2 * (size_t)n * sizeof *vs);
  slip_velocity(&m, &c, y, vs);
  /* the bound each cell's law used, from the model at the solution */
  rs_work w;
  rs_work_create(&w, &m);
  double *F = malloc((size_t)m.lay.neq * sizeof *F), *yp = calloc((size_t)m.lay.neq, sizeof *yp);
  const rs_inputs in = ts_inputs(&m, 0.0);
  rs_model_residual(&m, &w, &in, y, yp, 0.0, F);
  double worst = 0.0, worst_g = 0.0, worst_cos = 0.0, mu_lo = INFINITY, mu_hi = 0.0;
  double Fx = 0.0, Fy = 0.0, Fn = 0.0;
  int slipping = 0, contact = 0;
  for (int i = 0; i < n; i++) {
    if (!(m.pn[i] > 0.0)) continue;
    contact++;
    const double v = hypot(vs[i], vs[n + i]), p = hypot(y[i], y[n + i]);
    const double mu = rs_friction_mu(&c.friction, v);
    worst = fmax(worst, fabs(p - mu * m.pn[i]));
    worst_g = fmax(worst_g, fabs(w.law[i].g - mu * m.pn[i]));
    worst_cos = fmax(worst_cos, 1.0 + (y[i] * vs[i] + y[n + i] * vs[n + i]) / (p * v));
    slipping += v > 1.0; /* mm/s */
    mu_lo = fmin(mu_lo, mu);
    mu_hi = fmax(mu_hi, mu);
    Fx += y[i] * m.grid.area;
    Fy += y[n + i] * m.grid.area;
    Fn += m.pn[i] * m.grid.area;
  }
  const double ratio = hypot(Fx, Fy) / Fn;
  printf("%s (v_h %g mm/s), full sliding: F_x = %.6g N, F_y = %.6g N, |F|/F_n = %.5f, mu over "
         "the patch [%.5f, %.5f], %d Newton iterations\n",
         name, v_h, Fx, Fy, ratio, mu_lo, mu_hi, (int)st.nonlin_iters);
  char what[200];
  snprintf(what, sizeof what, "%s, full sliding: every contact cell slips (%d of %d)", name,
           slipping, contact);
  ts_check_true(what, slipping == contact && contact > 0);
  snprintf(what, sizeof what, "%s, full sliding: max (1 + cos(p, v_s)) (v_s opposite to p)", name);
  ts_check(what, worst_cos, 0.0, 1e-6);
  snprintf(what, sizeof what, "%s, full sliding: max ||p| - mu(|v_s|) p_n| / p0", name);
  ts_check(what, worst / m.hertz_p0, 0.0, 1e-8);
  snprintf(what, sizeof what, "%s, full sliding: max |g - mu(|v_s|) p_n| / p0 (the law's bound)",
           name);
  ts_check(what, worst_g / m.hertz_p0, 0.0, 1e-8);
  snprintf(what, sizeof what,
           "%s, full sliding: |F|/F_n within mu over the patch (which spans > 1e-3), below mu(0)",
           name);
  ts_check_true(what, ratio >= mu_lo - 1e-12 && ratio <= mu_hi + 1e-12 &&
                          mu_hi < rs_friction_mu(&c.friction, 0.0) && mu_hi - mu_lo > 1e-3);
  rs_work_free(&w);
  free(F);
  free(yp);
  free(vs);
  free(y);
  rs_model_free(&m);
}

int main(void)
{
  coulomb_limit();
  full_sliding(RS_FRICTION_LINEAR, 250.0); /* kink at 500 mm/s, above every slip speed */
  full_sliding(RS_FRICTION_EXPONENTIAL, 100.0);
  full_sliding(RS_FRICTION_RATIONAL, 100.0);
  full_sliding(RS_FRICTION_POLACH, 100.0);
  return ts_failures ? 1 : 0;
}
