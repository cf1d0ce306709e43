/* 3D normal contact (physics/normal3d.h, physics/normal_cg.h), docs/verification.md 9.
 *
 * Elliptic integrals: Legendre's relation E K' + E' K - K K' = pi/2 (exact), Gauss-
 * Legendre quadrature of the defining integrals, and the series as k -> 0 and kc -> 0
 * (Abramowitz & Stegun 17.3.11-12, 17.3.26, 17.3.36), each to rounding (1e-14 or
 * better; E loses eps ln(4/kc) to the cancellation in E = K - k^2 D, which the Hertz
 * formulas avoid by using D).
 * Hertz formulas, by an independent path: the displacement of the Hertz pressure,
 * integrated numerically with the point-load kernel u_z = P (1-nu)/(pi G r), must close
 * the gap inside the ellipse, u_z = delta - A x^2 - B y^2 (1e-9 of delta; quadrature
 * accuracy), for a circle, a wheel-rail-like and a slender ellipse. The circle against
 * its closed form a^3 = 3 F R (1-nu)/(4 G), delta = a^2/R (derived from the same kernel),
 * and the slender limit against the 2D line contact: with q = pi b p0/2 the load per
 * unit length at the centre section, the 2D half-width sqrt(4 q Ry (1-nu)/(pi G)) equals
 * b up to the relative correction kc^2 (2 ln(4/kc) - 3)/8 (expanding K, E for kc -> 0),
 * asserted to 5 % of that correction.
 * Discrete problem on 60 x 60 cells over +-1.1a x +-1.1b (docs/verification.md 9): a, b from
 * the second moments (Int x^2 p / Int p = a^2/5 for the Hertz ellipsoid) and p0 from
 * max p within 1 %; the load to 1e-12; complementarity with the gap from direct sums
 * (the solver's 1e-12 (max h + |delta|)). The CG solution against an independent dense
 * active-set solution (LAPACK dgesv) on a smaller grid with a non-Hertzian gap, and from
 * two different starts: 1e-9 p_max (CG stops at 1e-11 p_max, LU is accurate to ~1e-12). */
#include "physics/elastic2d.h"
#include "physics/normal.h"
#include "physics/normal3d.h"
#include "physics/normal_cg.h"
#include "test_quadrature.h"
#include "test_support.h"

#include <stdlib.h>

extern void dgesv_(const int *n, const int *nrhs, double *a, const int *lda, int *ipiv, double *b,
                   const int *ldb, int *info);

static const double G = 82000.0, NU = 0.28, LOAD = 10000.0;

/* Composite Gauss-Legendre rule: 48 points on each of `panels` panels of [lo, hi]. */
typedef struct rule {
  double node[48], weight[48];
} rule;

static void check_elliptic_integrals(const rule *q)
{
  static const double kcs[] = {0.95, 0.7071067811865476, 0.5, 0.2, 0.05};
  double legendre = 0.0, quad = 0.0;
  for (size_t c = 0; c < sizeof kcs / sizeof kcs[0]; c++) {
    const double kc = kcs[c], k = sqrt(1.0 - kc * kc);
    double K, E, Kp, Ep;
    rs_elliptic_ke(kc, &K, &E);
    rs_elliptic_ke(k, &Kp, &Ep); /* the complementary modulus */
    legendre = fmax(legendre, fabs(E * Kp + Ep * K - K * Kp - 0.5 * RS_PI) / (0.5 * RS_PI));
    double Kq = 0.0, Eq = 0.0;
    const int panels = 8;
    const double h = 0.5 * RS_PI / panels;
    for (int a = 0; a < panels; a++)
      for (int i = 0; i < 48; i++) {
        const double t = h * (a + 0.5 * (1.0 + q->node[i])), s = sin(t);
        const double root = sqrt(1.0 - k * k * s * s), w = 0.5 * h * q->weight[i];
        Kq += w / root;
        Eq += w * root;
      }
    quad = fmax(quad, fmax(fabs(K / Kq - 1.0), fabs(E / Eq - 1.0)));
  }
  /* Rounding: the relation combines products of size up to K K' ~ 2 pi/2 (a few eps);
   * the quadrature sums 384 terms (~sqrt(384) eps). */
  ts_check("Legendre relation E K' + E' K - K K' = pi/2 (relative)", legendre, 0.0, 2e-15);
  ts_check("K, E against quadrature of their integrals (relative)", quad, 0.0, 1e-14);
  /* Series: k -> 0 (A&S 17.3.11-12) and kc -> 0 (17.3.26, 17.3.36). */
  const double k = 1e-3, kc0 = sqrt(1.0 - k * k);
  double K, E;
  rs_elliptic_ke(kc0, &K, &E);
  const double K_series = 0.5 * RS_PI * (1.0 + k * k / 4.0 + 9.0 * pow(k, 4) / 64.0);
  const double E_series = 0.5 * RS_PI * (1.0 - k * k / 4.0 - 3.0 * pow(k, 4) / 64.0);
  ts_check("K(k = 1e-3) against its series (relative)", K / K_series - 1.0, 0.0, 4e-16);
  ts_check("E(k = 1e-3) against its series (relative)", E / E_series - 1.0, 0.0, 4e-16);
  const double kc = 1e-6, L = log(4.0 / kc);
  rs_elliptic_ke(kc, &K, &E);
  ts_check("K(kc = 1e-6) = ln(4/kc) + kc^2/4 (ln(4/kc) - 1) (relative)",
           K / (L + 0.25 * kc * kc * (L - 1.0)) - 1.0, 0.0, 4e-16);
  /* E = K - k^2 D cancels as kc -> 0: relative error ~ eps K/E = eps ln(4/kc). */
  ts_check("E(kc = 1e-6) = 1 + kc^2/2 (ln(4/kc) - 1/2) (relative)",
           E / (1.0 + 0.5 * kc * kc * (L - 0.5)) - 1.0, 0.0, 4.0 * L * 2.2e-16);
}

/* u_z at (x, y) inside the ellipse due to the Hertz pressure, c (1-nu) Int Int p/r dA, in
 * polar coordinates about the point: Int dtheta Int_0^rho_max p drho. Along a ray
 * 1 - X^2/a^2 - Y^2/b^2 = alpha (rho_max - rho)(rho - rho_min); rho = rho_max (1 - t^2)
 * makes the square root smooth in t. Trapezoidal rule in theta (periodic, smooth). */
static double hertz_displacement(const rs_hertz_ellipse *hz, double x, double y, int ntheta,
                                 const rule *q)
{
  const double a2 = hz->a * hz->a, b2 = hz->b * hz->b;
  const double gamma = 1.0 - x * x / a2 - y * y / b2;
  double sum = 0.0;
  for (int j = 0; j < ntheta; j++) {
    const double t = 2.0 * RS_PI * j / ntheta, ct = cos(t), st = sin(t);
    const double alpha = ct * ct / a2 + st * st / b2, beta = 2.0 * (x * ct / a2 + y * st / b2);
    const double root = sqrt(beta * beta + 4.0 * alpha * gamma);
    const double rmax = beta >= 0.0 ? 2.0 * gamma / (beta + root) : (root - beta) / (2.0 * alpha);
    const double rmin = -gamma / (alpha * rmax);
    double ray = 0.0;
    for (int i = 0; i < 48; i++) {
      const double s = 0.5 * (1.0 + q->node[i]), rho = rmax * (1.0 - s * s);
      ray += 0.5 * q->weight[i] * s * sqrt(alpha * rmax * (rho - rmin)) * 2.0 * rmax * s;
    }
    sum += ray;
  }
  return (1.0 - NU) / (RS_PI * G) * hz->p0 * sum * 2.0 * RS_PI / ntheta;
}

static void check_hertz_closes_gap(const char *name, double curv_x, double curv_y, const rule *q)
{
  rs_hertz_ellipse hz;
  rs_msg msg = {{0}};
  if (rs_hertz3d(LOAD, curv_x, curv_y, G, NU, &hz, &msg) != RS_OK) {
    printf("FAIL %s: %s\n", name, msg.text);
    ts_failures++;
    return;
  }
  static const double pts[][2] = {{0, 0}, {0.5, 0.3}, {-0.2, 0.7}, {0.9, 0}, {0.1, -0.95}};
  double worst = 0.0, est = 0.0;
  for (size_t k = 0; k < sizeof pts / sizeof pts[0]; k++) {
    const double x = pts[k][0] * hz.a, y = pts[k][1] * hz.b;
    const double u = hertz_displacement(&hz, x, y, 4096, q);
    est = fmax(est, fabs(u - hertz_displacement(&hz, x, y, 2048, q)) / hz.approach);
    worst = fmax(worst, fabs(u - (hz.approach - curv_x * x * x - curv_y * y * y)) / hz.approach);
  }
  printf("     %s: a = %.6g mm, b = %.6g mm, p0 = %.6g N/mm^2, delta = %.6g mm, e = %.6g, "
         "major along %s\n",
         name, hz.a, hz.b, hz.p0, hz.approach, hz.eccentricity, hz.major_along_x ? "x" : "y");
  char what[160];
  snprintf(what, sizeof what,
           "%s: Hertz pressure closes the gap, |u_z - (delta - h)|/delta (quadrature %.1g)", name,
           est);
  ts_check(what, worst, 0.0, 1e-9);
}

static void check_hertz_limits(void)
{
  const double R = 300.0;
  rs_hertz_ellipse hz, near;
  rs_msg msg = {{0}};
  rs_hertz3d(LOAD, 0.5 / R, 0.5 / R, G, NU, &hz, &msg);
  const double a = cbrt(3.0 * LOAD * R * (1.0 - NU) / (4.0 * G));
  ts_check("circle: a = (3 F R (1-nu)/(4 G))^(1/3) (relative)", hz.a / a - 1.0, 0.0, 1e-15);
  ts_check("circle: b = a (relative)", hz.b / a - 1.0, 0.0, 1e-15);
  ts_check("circle: p0 = 3F/(2 pi a^2) (relative)", hz.p0 / (1.5 * LOAD / (RS_PI * a * a)) - 1.0,
           0.0, 1e-15);
  ts_check("circle: delta = a^2/R (relative)", hz.approach / (a * a / R) - 1.0, 0.0, 1e-15);
  rs_hertz3d(LOAD, 0.5 / R, 0.5 / R * (1.0 + 1e-9), G, NU, &near, &msg);
  ts_check("nearly a circle (B/A - 1 = 1e-9): a continuous (relative)", near.a / a - 1.0, 0.0,
           1e-9);
  /* Slender ellipse -> line contact across its minor axis (y). */
  for (double ratio = 1e3; ratio <= 1e5; ratio *= 100.0) {
    const double A = 0.5 / 460.0, B = A * ratio;
    rs_hertz3d(LOAD, A, B, G, NU, &hz, &msg);
    const double q = 0.5 * RS_PI * hz.b * hz.p0, Ry = 0.5 / B;
    double half_2d, p0_2d;
    rs_hertz2d(q, Ry, G, NU, &half_2d, &p0_2d);
    const double kc = hz.b / hz.a, L = log(4.0 / kc), pred = -kc * kc * (2.0 * L - 3.0) / 8.0;
    char what[160];
    snprintf(what, sizeof what,
             "B/A = %.0e: b / (2D half-width at q = pi b p0/2) - 1 vs kc^2 (2 ln(4/kc) - 3)/8",
             ratio);
    ts_check(what, hz.b / half_2d - 1.0, pred, 0.05 * fabs(pred));
  }
  TS_CHECK(rs_hertz3d(LOAD, -1.0, 1.0, G, NU, &hz, &msg) == RS_ERR_INPUT, "negative curvature");
  TS_CHECK(rs_hertz3d(0.0, 1.0, 1.0, G, NU, &hz, &msg) == RS_ERR_INPUT, "zero load");
}

/* Dense active-set solution (Kalker 1990 §5.1 style), independent of the CG and of the
 * FFT: A_CC p_C - delta = -h_C, area sum p_C = load, drop tension, add penetration. */
static int dense_solve(const rs_elastic3d *el, const double *h, double load, double *p,
                       double *delta)
{
  const int nx = el->nx, n = nx * el->ny;
  int *active = malloc((size_t)n * sizeof *active), *index = malloc((size_t)n * sizeof *index);
  int *pivot = malloc((size_t)(n + 1) * sizeof *pivot);
  double *mat = malloc((size_t)(n + 1) * (n + 1) * sizeof *mat);
  double *rhs = malloc((size_t)(n + 1) * sizeof *rhs);
  const double scale = rs_elastic3d_coef(el, 2, 2, 0, 0);
  double hmax = 0.0;
  for (int i = 0; i < n; i++) {
    active[i] = 1;
    hmax = fmax(hmax, fabs(h[i]));
  }
  int done = 0;
  for (int iter = 0; iter < 4 * n && !done; iter++) {
    int m = 0;
    for (int i = 0; i < n; i++)
      if (active[i]) index[m++] = i;
    const int ld = m + 1, one = 1;
    for (int c = 0; c < m; c++) {
      for (int r = 0; r < m; r++)
        mat[(size_t)c * ld + r] = rs_elastic3d_coef(el, 2, 2, index[r] % nx - index[c] % nx,
                                                    index[r] / nx - index[c] / nx);
      mat[(size_t)c * ld + m] = scale;
      rhs[c] = -h[index[c]];
    }
    for (int r = 0; r < m; r++) mat[(size_t)m * ld + r] = -scale;
    mat[(size_t)m * ld + m] = 0.0;
    rhs[m] = scale * load / (el->dx * el->dy);
    int info = 0;
    dgesv_(&ld, &one, mat, &ld, pivot, rhs, &ld, &info);
    if (info != 0) break;
    *delta = scale * rhs[m];
    int changed = 0;
    for (int i = 0; i < n; i++) p[i] = 0.0;
    for (int c = 0; c < m; c++) {
      p[index[c]] = rhs[c];
      if (rhs[c] < 0.0) {
        active[index[c]] = 0;
        changed = 1;
      }
    }
    if (!changed)
      for (int i = 0; i < n; i++) {
        if (active[i]) continue;
        double g = h[i] - *delta;
        for (int j = 0; j < n; j++)
          g += rs_elastic3d_coef(el, 2, 2, i % nx - j % nx, i / nx - j / nx) * p[j];
        if (g < -1e-12 * (hmax + fabs(*delta))) {
          active[i] = 1;
          changed = 1;
        }
      }
    done = !changed;
  }
  free(active);
  free(index);
  free(pivot);
  free(mat);
  free(rhs);
  return done ? 0 : -1;
}

/* Complementarity with the gap from direct sums; returns the number of contact cells. */
static int check_complementarity(const char *name, const rs_elastic3d *el, const double *h,
                                 const double *pn, double delta)
{
  const int n = el->nx * el->ny;
  double *u = malloc((size_t)n * sizeof *u), hmax = 0.0, on = 0.0, out = INFINITY, pmin = 0.0;
  rs_elastic3d_direct_norm(el, pn, u, el->nx);
  int contact = 0;
  for (int i = 0; i < n; i++) hmax = fmax(hmax, fabs(h[i]));
  for (int i = 0; i < n; i++) {
    const double g = h[i] - delta + u[i];
    pmin = fmin(pmin, pn[i]);
    if (pn[i] > 0.0) {
      on = fmax(on, fabs(g));
      contact++;
    } else {
      out = fmin(out, g);
    }
  }
  const double tol = 1e-12 * (hmax + fabs(delta));
  char what[160];
  snprintf(what, sizeof what, "%s: |gap| on the contact, relative to max h + |delta|", name);
  ts_check(what, on / (hmax + fabs(delta)), 0.0, 1e-12);
  snprintf(what, sizeof what, "%s: no tension, no penetration outside (min gap %.2g)", name,
           out / (hmax + fabs(delta)));
  ts_check_true(what, pmin >= 0.0 && out >= -tol);
  free(u);
  return contact;
}

static void check_discrete_hertz(const char *name, double Rx, double Ry, int cells)
{
  rs_hertz_ellipse hz;
  rs_msg msg = {{0}};
  const double A = 0.5 / Rx, B = 0.5 / Ry;
  rs_hertz3d(LOAD, A, B, G, NU, &hz, &msg);
  const rs_grid3d grid = {.nx = cells,
                          .ny = cells,
                          .x0 = -1.1 * hz.a,
                          .y0 = -1.1 * hz.b,
                          .dx = 2.2 * hz.a / cells,
                          .dy = 2.2 * hz.b / cells};
  rs_elastic3d el;
  rs_elastic3d_work work;
  if (rs_elastic3d_create(&el, grid.nx, grid.ny, grid.dx, grid.dy, G, NU, &msg) != RS_OK ||
      rs_elastic3d_work_create(&work, &el, &msg) != RS_OK) {
    printf("FAIL %s: %s\n", name, msg.text);
    ts_failures++;
    return;
  }
  const int n = cells * cells;
  double *h = malloc((size_t)n * sizeof *h), *pn = malloc((size_t)n * sizeof *pn);
  rs_normal3d_gap(&grid, A, B, h);
  double delta = 0.0;
  int iters = 0;
  if (rs_normal3d_solve(&el, &work, h, LOAD, NULL, pn, &delta, &iters, &msg) != RS_OK) {
    printf("FAIL %s: %s\n", name, msg.text);
    ts_failures++;
  } else {
    double sum = 0.0, mxx = 0.0, myy = 0.0, pmax = 0.0;
    for (int j = 0; j < cells; j++)
      for (int i = 0; i < cells; i++) {
        const double x = grid.x0 + (i + 0.5) * grid.dx, y = grid.y0 + (j + 0.5) * grid.dy;
        const double p = pn[j * cells + i];
        sum += p;
        mxx += x * x * p;
        myy += y * y * p;
        pmax = fmax(pmax, p);
      }
    const int contact = check_complementarity(name, &el, h, pn, delta);
    printf("     %s, %d x %d cells: %d CG iterations, %d cells in contact, delta %.6g mm "
           "(Hertz %.6g, %+.2f %%)\n",
           name, cells, cells, iters, contact, delta, hz.approach,
           100.0 * (delta / hz.approach - 1.0));
    char what[160];
    snprintf(what, sizeof what, "%s: load dx dy sum p (relative)", name);
    ts_check(what, sum * grid.dx * grid.dy / LOAD, 1.0, 1e-12);
    snprintf(what, sizeof what, "%s: a = sqrt(5 Int x^2 p / Int p) vs Hertz a, 1 %%", name);
    ts_check(what, sqrt(5.0 * mxx / sum), hz.a, 0.01 * hz.a);
    snprintf(what, sizeof what, "%s: b = sqrt(5 Int y^2 p / Int p) vs Hertz b, 1 %%", name);
    ts_check(what, sqrt(5.0 * myy / sum), hz.b, 0.01 * hz.b);
    snprintf(what, sizeof what, "%s: max p vs Hertz p0, 1 %%", name);
    ts_check(what, pmax, hz.p0, 0.01 * hz.p0);
  }
  free(h);
  free(pn);
  rs_elastic3d_work_free(&work);
  rs_elastic3d_free(&el);
}

/* A non-Hertzian (wavy) gap on a small grid: CG from two starts against the dense
 * active-set solution. */
static void check_against_dense(void)
{
  rs_hertz_ellipse hz;
  rs_msg msg = {{0}};
  const double A = 0.5 / 460.0, B = 0.5 / 300.0;
  rs_hertz3d(LOAD, A, B, G, NU, &hz, &msg);
  const rs_grid3d grid = {.nx = 18,
                          .ny = 14,
                          .x0 = -1.3 * hz.a,
                          .y0 = -1.3 * hz.b,
                          .dx = 2.6 * hz.a / 18,
                          .dy = 2.6 * hz.b / 14};
  const int n = grid.nx * grid.ny;
  rs_elastic3d el;
  rs_elastic3d_work work;
  if (rs_elastic3d_create(&el, grid.nx, grid.ny, grid.dx, grid.dy, G, NU, &msg) != RS_OK ||
      rs_elastic3d_work_create(&work, &el, &msg) != RS_OK) {
    printf("FAIL dense: %s\n", msg.text);
    ts_failures++;
    return;
  }
  double *h = malloc((size_t)n * sizeof *h), *start = malloc((size_t)n * sizeof *start);
  double *p_dense = malloc((size_t)n * sizeof *p_dense), *p_cg = malloc((size_t)n * sizeof *p_cg);
  double *p_warm = malloc((size_t)n * sizeof *p_warm);
  rs_normal3d_gap(&grid, A, B, h);
  for (int j = 0; j < grid.ny; j++)
    for (int i = 0; i < grid.nx; i++) {
      const double x = grid.x0 + (i + 0.5) * grid.dx, y = grid.y0 + (j + 0.5) * grid.dy;
      h[j * grid.nx + i] += 0.2 * hz.approach * cos(2.0 * RS_PI * x / (0.8 * hz.a)) *
                            cos(2.0 * RS_PI * y / (1.1 * hz.b));
    }
  rs_hertz3d_pressure(&hz, &grid, start);
  double d_dense = 0.0, d_cg = 0.0, d_warm = 0.0;
  int it_cg = 0, it_warm = 0;
  const int ok =
      dense_solve(&el, h, LOAD, p_dense, &d_dense) == 0 &&
      rs_normal3d_solve(&el, &work, h, LOAD, NULL, p_cg, &d_cg, &it_cg, &msg) == RS_OK &&
      rs_normal3d_solve(&el, &work, h, LOAD, start, p_warm, &d_warm, &it_warm, &msg) == RS_OK;
  ts_check_true("wavy gap: dense active set and CG (uniform and Hertz starts) converge", ok);
  if (ok) {
    double pmax = 0.0, diff = 0.0, diff_warm = 0.0;
    for (int i = 0; i < n; i++) {
      pmax = fmax(pmax, p_dense[i]);
      diff = fmax(diff, fabs(p_cg[i] - p_dense[i]));
      diff_warm = fmax(diff_warm, fabs(p_warm[i] - p_cg[i]));
    }
    const int contact = check_complementarity("wavy gap", &el, h, p_cg, d_cg);
    printf("     wavy gap, 18 x 14 cells: %d in contact; CG %d iterations (uniform start), %d "
           "(Hertz start)\n",
           contact, it_cg, it_warm);
    ts_check("wavy gap: CG - dense pressure, relative to p_max", diff / pmax, 0.0, 1e-9);
    ts_check("wavy gap: CG - dense approach (relative)", d_cg / d_dense - 1.0, 0.0, 1e-9);
    ts_check("wavy gap: uniform vs Hertz start, relative to p_max", diff_warm / pmax, 0.0, 1e-9);
  }
  TS_CHECK(rs_normal3d_solve(&el, &work, h, 0.0, NULL, p_cg, NULL, NULL, &msg) == RS_ERR_INPUT,
           "zero load must be refused");
  free(h);
  free(start);
  free(p_dense);
  free(p_cg);
  free(p_warm);
  rs_elastic3d_work_free(&work);
  rs_elastic3d_free(&el);
}

int main(void)
{
  rule q;
  if (tq_gauss_legendre(48, q.node, q.weight) != 0) {
    printf("FAIL Gauss-Legendre rule\n");
    return 1;
  }
  check_elliptic_integrals(&q);
  check_hertz_closes_gap("circle R = 300 mm", 0.5 / 300.0, 0.5 / 300.0, &q);
  check_hertz_closes_gap("wheel-rail Rx = 460, Ry = 300 mm", 0.5 / 460.0, 0.5 / 300.0, &q);
  check_hertz_closes_gap("slender Rx = 20, Ry = 460 mm", 0.5 / 20.0, 0.5 / 460.0, &q);
  check_hertz_limits();
  check_discrete_hertz("circle R = 300 mm", 300.0, 300.0, 60);
  check_discrete_hertz("wheel-rail Rx = 460, Ry = 300 mm", 460.0, 300.0, 60);
  check_discrete_hertz("slender Rx = 20, Ry = 460 mm", 20.0, 460.0, 60);
  check_against_dense();
  return ts_failures ? 1 : 0;
}
