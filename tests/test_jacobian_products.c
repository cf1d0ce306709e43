/* The model's exact Jacobian-vector products (rs_model_jv, used by the Newton-Krylov
 * solver) against central differences of the residual, and against the assembled
 * Jacobian (rs_model_jacobian) applied to the same vectors, for an elastic, a plastic
 * and a force-controlled model, with the steady scaling (c_j = 0) and a transient one
 * (c_j = V/dx).
 *
 * The states are steady solutions perturbed by 1 % (random, deterministic), so that no
 * cell sits on a switch of its branches; a direction is used only if the branches at
 * y + h v and y - h v equal those at y. Within one set of branches the residual is
 * linear in y (the projections are affine there, tau_c is linear in u*, |Du_pl/Dt| has
 * one sign), so the central difference is exact up to roundoff: eps |F| / h with
 * h = 1e-6 |y| / |v| gives ~1e-10 relative; the tolerance is 1e-6 relative to |J v|.
 * The assembled Jacobian applied to v must agree to 1e-12 relative (the same products,
 * summed in another order).
 *
 * Velocity-dependent friction (docs/model.md §11): at the bound R_f = p - s mu(eta) p_n is
 * curved in v_s, so the central difference has an O(h^2) error mu'' h^2 |v_s(v)|^2 p_n;
 * Richardson's extrapolation of the differences at h and h/2 removes it (error O(h^4)
 * plus roundoff ~eps |F| / h), and every law is checked to the same 1e-6, on Carter's
 * contact (mu(0) = 0.3, half velocities of 10 mm/s, slip speeds up to ~7 mm/s: the
 * falling part of each law) and on the plastic Table-1 contact (100 mm/s).
 * Without the term g'(eta) on v_s the steady differences missed by 0.16 relative
 * (rational law, v_h = 3 mm/s). The same for every law in 3D (the disk law, elastic and
 * plastic, 16 x 16 cells), and for friction memory in 3D (without the memory row's terms
 * across the direction s the steady differences missed by 1.2-1.9 % relative). */
#include <stdlib.h>

#include "solve/steady.h"
#include "test_support.h"

static double norm_inf(const double *v, int n)
{
  double m = 0.0;
  for (int i = 0; i < n; i++) m = fmax(m, fabs(v[i]));
  return m;
}

static void check_model(const char *name, rs_case *c)
{
  rs_model m;
  rs_msg msg = {{0}};
  if (rs_model_from_case(&m, c, &msg) != RS_OK) {
    printf("FAIL %s: %s\n", name, msg.text);
    ts_failures++;
    return;
  }
  if (c->friction.memory_distance > 0.0)
    ts_check_true("friction memory: a state mu per cell in the layout",
                  m.lay.memory == 1 && m.lay.neq == (2 * m.lay.ncomp + 2) * m.grid.n);
  const int neq = m.lay.neq;
  double *y = calloc((size_t)neq, sizeof *y), *yp = calloc((size_t)neq, sizeof *yp);
  double *v = malloc((size_t)neq * sizeof *v), *jv = malloc((size_t)neq * sizeof *jv);
  double *jm = malloc((size_t)neq * sizeof *jm), *fp = malloc((size_t)neq * sizeof *fp);
  double *fm = malloc((size_t)neq * sizeof *fm), *z = malloc((size_t)neq * sizeof *z);
  double *fd = malloc((size_t)neq * sizeof *fd);
  unsigned char *br = malloc((size_t)m.grid.n);
  rs_work w, wlin, wfd;
  rs_work_create(&w, &m);
  rs_work_create(&wlin, &m);
  rs_work_create(&wfd, &m);
  rs_csr J = {.cap = rs_model_jac_capacity(&m, 0, 0)};
  J.rowptr = malloc(((size_t)neq + 1) * sizeof *J.rowptr);
  J.col = malloc((size_t)J.cap * sizeof *J.col);
  J.val = malloc((size_t)J.cap * sizeof *J.val);
  rs_steady *s = NULL;
  rs_stats st = {0};
  if (rs_steady_create(&s, &m, NULL, &msg) != RS_OK ||
      rs_steady_solve(s, 0.0, y, &st, &msg) != RS_OK) {
    printf("FAIL %s steady: %s\n", name, msg.text);
    ts_failures++;
    goto done;
  }
  unsigned long seed = 12345;
  const double ymax = norm_inf(y, neq);
  for (int i = 0; i < neq; i++)
    y[i] += 0.01 * ymax * ts_random(&seed) * (i < m.lay.ncomp * m.grid.n ? 1.0 : 1e-3);
  const rs_inputs in = ts_inputs(&m, 0.0);
  const double cjs[2] = {0.0, in.velocity / m.grid.dx};
  for (int k = 0; k < 2; k++) {
    const double cj = cjs[k];
    /* yp consistent with a backward-Euler step from y - v0 / cj is not needed: any yp
     * is a point of the residual; take yp = 0 (steady) or a random rate. */
    for (int i = 0; i < neq; i++) yp[i] = cj > 0.0 ? 0.01 * ymax * cj * ts_random(&seed) : 0.0;
    rs_model_jacobian(&m, &w, &in, y, yp, cj, 0, 0, &J);
    memcpy(br, w.branch, (size_t)m.grid.n);
    int used = 0;
    double worst_fd = 0.0, worst_mat = 0.0;
    for (int trial = 0; trial < 20 && used < 5; trial++) {
      for (int i = 0; i < neq; i++)
        v[i] = ts_random(&seed) * (i < m.lay.ncomp * m.grid.n ? ymax : 1e-3 * ymax);
      const double h = 1e-6 * norm_inf(y, neq) / norm_inf(v, neq);
      int same = 1;
      /* central differences at h (into fd) and h/2 (fp - fm), then Richardson */
      for (int half = 0; half < 2; half++) {
        const double hh = half ? 0.5 * h : h;
        for (int sgn = -1; sgn <= 1; sgn += 2) {
          for (int i = 0; i < neq; i++) z[i] = y[i] + sgn * hh * v[i];
          double *zp = malloc((size_t)neq * sizeof *zp);
          for (int i = 0; i < neq; i++) zp[i] = yp[i] + sgn * hh * cj * v[i];
          rs_model_residual(&m, &wfd, &in, z, zp, cj, sgn < 0 ? fm : fp);
          free(zp);
          same = same && !memcmp(wfd.branch, br, (size_t)m.grid.n);
        }
        for (int i = 0; i < neq; i++) {
          const double d = (fp[i] - fm[i]) / (2.0 * hh);
          fd[i] = half ? (4.0 * d - fd[i]) / 3.0 : d;
        }
      }
      if (!same) continue;
      used++;
      rs_model_jv(&m, &w, &wlin, &in, cj, v, jv);
      for (int i = 0; i < neq; i++) { /* the assembled matrix on v */
        double sum = 0.0;
        for (int64_t q = J.rowptr[i]; q < J.rowptr[i + 1]; q++) sum += J.val[q] * v[J.col[q]];
        jm[i] = sum;
      }
      const double scale = norm_inf(jv, neq);
      for (int i = 0; i < neq; i++) {
        worst_fd = fmax(worst_fd, fabs(fd[i] - jv[i]) / scale);
        worst_mat = fmax(worst_mat, fabs(jm[i] - jv[i]) / scale);
      }
    }
    char what[160];
    snprintf(what, sizeof what, "%s, c_j = %g: directions without a branch switch", name, cj);
    ts_check_true(what, used >= 3);
    snprintf(what, sizeof what, "%s, c_j = %g: max |FD - J v| / |J v|", name, cj);
    ts_check(what, worst_fd, 0.0, 1e-6);
    snprintf(what, sizeof what, "%s, c_j = %g: max |J_assembled v - J v| / |J v|", name, cj);
    ts_check(what, worst_mat, 0.0, 1e-12);
  }
done:
  rs_steady_free(s);
  rs_work_free(&w);
  rs_work_free(&wlin);
  rs_work_free(&wfd);
  free(J.rowptr);
  free(J.col);
  free(J.val);
  free(y);
  free(yp);
  free(v);
  free(jv);
  free(jm);
  free(fp);
  free(fm);
  free(z);
  free(fd);
  free(br);
  rs_model_free(&m);
}

/* A velocity-dependent law on case c with mu(0) = 0.3 (c->mu set to it), half velocities
 * v_h (and 10/3 v_h, rational's second term; Polach: B = 0.6/v_h). */
static void set_law(rs_case *c, rs_friction_kind kind, double v_h)
{
  rs_friction f = {.kind = kind, .mu_kinetic = 0.2, .terms = 1};
  f.mu_excess[0] = 0.1;
  f.half_velocity[0] = v_h;           /* mm/s */
  if (kind == RS_FRICTION_RATIONAL) { /* two terms */
    f.terms = 2;
    f.mu_excess[0] = 0.06;
    f.mu_excess[1] = 0.04;
    f.half_velocity[1] = 10.0 / 3.0 * v_h;
  }
  if (kind == RS_FRICTION_POLACH) {
    f.mu_static = 0.3;
    f.polach_a = 0.4;
    f.polach_b = 0.6 / v_h; /* s/mm */
  }
  c->friction = f;
  c->mu = rs_friction_mu(&f, 0.0);
}

/* The 16 x 16 test ellipse, elastic or with the plastic layer (tau_c0 = 120 N/mm^2 below
 * mu p0, hardening). */
static void ellipse_case(rs_case *c, int plastic)
{
  ts_ellipse_case(c, 16, 2.0, -8e-4, 4e-4, 2e-4);
  if (!plastic) return;
  c->has_plasticity = 1;
  c->tau_c0 = 120.0;
  c->k_tau = 2000.0;
  c->tau_c_min = 10.0;
}

int main(void)
{
  rs_case c;
  const rs_friction_kind laws[] = {RS_FRICTION_LINEAR, RS_FRICTION_EXPONENTIAL,
                                   RS_FRICTION_RATIONAL, RS_FRICTION_POLACH};
  for (int k = 0; k < 4; k++) {
    char name[96];
    ts_carter_case(&c, 100);
    /* v_h = 10 mm/s: linear's kink at 2 v_h above every slip speed (a cell on it has two
     * slopes); at 3 mm/s the exponential and Polach laws fall so steeply that steady
     * Newton did not converge */
    set_law(&c, laws[k], 10.0);
    snprintf(name, sizeof name, "elastic Carter, %s friction, 100 cells",
             rs_friction_name(laws[k]));
    check_model(name, &c);
  }
  ts_table1_case(&c, 100, 200.0, 0.0387, -0.01);
  set_law(&c, RS_FRICTION_EXPONENTIAL, 100.0); /* slip speeds up to ~300 mm/s */
  check_model("plastic Table-1 contact, exponential friction, xi = -1 %, 100 cells", &c);
  /* Friction memory (docs/model.md §11): the memory rows r (d_c Dmu/Dt + max(|v_s|, s0)
   * (mu - mu_law(eta))) are dense through v_s, and the bound mu p_n of a slipping cell
   * depends on the state mu: d_c = 0.05 mm (a few contact lengths of sliding on Carter's
   * contact), s0 = 1 mm/s below most slip speeds and 5 mm/s above many. */
  const double s0s[2] = {1.0, 5.0};
  for (int k = 0; k < 2; k++) {
    char name[128];
    ts_carter_case(&c, 100);
    set_law(&c, RS_FRICTION_EXPONENTIAL, 10.0);
    c.friction.memory_distance = 0.05;
    c.friction.memory_velocity = s0s[k];
    snprintf(name, sizeof name, "elastic Carter, exponential friction with memory (s0 = %g mm/s)",
             s0s[k]);
    check_model(name, &c);
  }
  ts_table1_case(&c, 100, 200.0, 0.0387, -0.01);
  set_law(&c, RS_FRICTION_RATIONAL, 100.0);
  c.friction.memory_distance = 0.002;
  c.friction.memory_velocity = 1.0;
  check_model("plastic Table-1 contact, rational friction with memory, xi = -1 %", &c);
  /* 3D (the disk law): g = mu(eta) p_n with eta = -s.v_s, s the direction of p - r v_s,
   * which turns with p and v_s; the perturbed states have v_s off -s, so the terms of
   * d eta / d p and the part of d eta / d v_s across s are exercised. 16 x 16 cells, rigid
   * slip speeds up to V |(xi, eta)| = 27 mm/s (plus the spin's) against half velocities of
   * 40 mm/s (at 10 mm/s steady Newton did not converge for the exponential, rational and
   * Polach laws, so there was no state to perturb). Leaving out the terms across s missed
   * by 0.9-5.9 % relative, leaving out the whole g' term by 3.9-18 %. */
  for (int plastic = 0; plastic < 2; plastic++)
    for (int k = 0; k < 4; k++) {
      char name[128];
      ellipse_case(&c, plastic);
      set_law(&c, laws[k], 40.0);
      snprintf(name, sizeof name, "3D %s, %s friction, 16 x 16 cells",
               plastic ? "plastic (tau_c0 = 120 N/mm^2)" : "elastic", rs_friction_name(laws[k]));
      check_model(name, &c);
    }
  /* 3D friction memory: the memory row depends on v_s through eta = -s.v_s and |v_s| in
   * both components, and on p through s; the friction rows of slipping cells on mu
   * (g = mu p_n). d_c = 0.05 mm (a few percent of the semi-axes), s0 below and above
   * many slip speeds; elastic and plastic. */
  for (int k = 0; k < 4; k++) {
    char name[160];
    ellipse_case(&c, k >= 2);
    set_law(&c, k % 2 ? RS_FRICTION_RATIONAL : RS_FRICTION_EXPONENTIAL, 40.0);
    c.friction.memory_distance = 0.05;
    c.friction.memory_velocity = k == 1 ? 5.0 : 1.0;
    snprintf(name, sizeof name, "3D %s, %s friction with memory (s0 = %g mm/s), 16 x 16 cells",
             k >= 2 ? "plastic" : "elastic", rs_friction_name(c.friction.kind),
             c.friction.memory_velocity);
    check_model(name, &c);
  }
  ellipse_case(&c, 0);
  check_model("3D elastic, Coulomb, 16 x 16 cells", &c);
  ts_carter_case(&c, 100);
  check_model("elastic Carter, 100 cells", &c);
  ts_fig7_case(&c, 100, 0.6);
  check_model("plastic Carter k_rel = 0.6, 100 cells", &c);
  ts_table1_case(&c, 100, 200.0, 0.0387, -0.01);
  check_model("plastic Table-1 contact, xi = -1 %, 100 cells", &c);
  ts_carter_case(&c, 100);
  c.force_control = 1;
  c.tangential_force.kind = RS_HISTORY_CONSTANT;
  c.tangential_force.value = 30.0; /* N/mm: 0.56 mu F_n */
  check_model("elastic Carter, prescribed F_x = 30 N/mm, 100 cells", &c);
  return ts_failures ? 1 : 0;
}
