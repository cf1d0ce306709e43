/* Surface temperature (physics/thermal.h, docs/model.md §18, docs/verification.md 26):
 *
 * 1. Kernel: the step response of the sum of exponentials meets 2 sqrt(l/pi) to the
 *    tolerance asked (checked here on points of its own, 200 per decade), for tolerances
 *    1e-2 ... 1e-6, with the number of modes printed (the accuracy table of bench/RESULTS.md).
 * 2. Moving band source (Carslaw & Jaeger, high-Peclet limit): a uniform flux q over a band
 *    of length 2a moving at V. Along a material path 1D conduction gives, t the time since
 *    the path entered the band,
 *      T - T_bulk = 2 q_b sqrt(t)/(beta sqrt(pi))                  in the band,
 *      T - T_bulk = 2 q_b (sqrt(t) - sqrt(t - 2a/V))/(beta sqrt(pi))  behind it.
 *    Equal bulk temperatures: both surfaces follow the same law with q_b = beta_b q/(beta_1 +
 *    beta_2) (then T1 = T2 holds with constant shares), so T - T_bulk = 2 q sqrt(t)/((beta_1
 *    + beta_2) sqrt(pi)). A piecewise-constant source is marched exactly, so the only error is
 *    the kernel's: within the tolerance (1 % and below), falling in proportion to it (observed
 *    order 1 in the tolerance: the least-squares slope over 1e-2 ... 1e-5 in [0.9, 1.2]; the
 *    rule's spacing h = pi^2/ln(1/tol) makes its error proportional to the tolerance). Equal bodies
 * (q1 = q2 = q/2 by symmetry) and beta_2 = 3 beta_1 (q1 = q/4) are both checked, the share to
 * 1e-12.
 * 3. Energy: q1 + q2 = q in every contact cell; the heat inputs sum to sum q dA to 1e-12.
 * 4. Two half-spaces at 0 and 150 degC brought into perfect contact, no heat generated: the
 *    contact temperature is (beta_1 T_1 + beta_2 T_2)/(beta_1 + beta_2) at once and for all
 *    time (the discrete march has it exactly: both bodies see the same linear operator up to
 *    1/beta, so that constant solves the discrete equations), to 1e-12 relative. The heat
 *    flowing into body 1 over the contact, beta_1 dT 2 sqrt(2a V/pi) exactly (the flux
 *    beta_1 dT/sqrt(pi t)), is met to 1e-5 on 300 cells with the kernel at 1e-7, and its
 *    error falls by a factor in [3, 5] per halving of the cell (second order, as collocation
 *    at the cell centres gives for this Abel equation: the quadrature of the 1/sqrt(t) flux
 *    is exact per cell, only its piecewise-constant representation errs).
 * 5. beta_2 -> infinity (1e8 beta_1): body 2 stays at its bulk temperature and takes all the
 *    heat; body 1 reads T_bulk_2 in the contact to 1e-6 K. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "physics/thermal.h"

static int failures;

static void check(int ok, const char *what, double got, double want)
{
  printf("%s %s: got %.10g, want %.10g\n", ok ? "ok  " : "FAIL", what, got, want);
  if (!ok) failures++;
}

static const double PI = 3.14159265358979323846;

static void kernel_table(void)
{
  printf("kernel: tolerance, modes, error of the step response over l in [1, 400]\n");
  for (double tol = 1e-2; tol > 1e-7; tol /= 10) {
    rs_thermal_kernel k;
    rs_msg msg = {{0}};
    if (rs_thermal_kernel_create(&k, 1.0, 400.0, tol, &msg) != RS_OK) {
      printf("FAIL kernel: %s\n", msg.text);
      failures++;
      continue;
    }
    double worst = 0.0;
    for (int i = 0; i <= 520; i++) { /* 200 per decade over 2.6 decades */
      const double l = pow(10.0, log10(400.0) * i / 520.0);
      worst = fmax(worst, fabs(rs_thermal_kernel_step(&k, l) / (2.0 * sqrt(l / PI)) - 1.0));
    }
    printf("  %.0e  %2d + 2  %.3g\n", tol, k.nmodes, worst);
    char what[64];
    snprintf(what, sizeof what, "kernel step error at tolerance %.0e", tol);
    check(worst <= tol, what, worst, tol);
    rs_thermal_kernel_free(&k);
  }
}

/* A row of nx cells over [-1.5, 1.5] mm, the band |x| < a = 1 mm. */
enum { NX_MAX = 800 };
static const double X_LO = -1.5, X_HI = 1.5, A = 1.0, V = 30000.0;

static void steel(rs_thermal_params *p, double beta_ratio)
{
  *p = (rs_thermal_params){.on = 1, .plastic_heat_fraction = 1.0, .kernel_tolerance = 1e-3};
  for (int b = 0; b < 2; b++) {
    p->conductivity[b] = 50e-3;
    p->heat_capacity[b] = 450.0;
    p->density[b] = 7.85e-6;
  }
  p->conductivity[1] *= beta_ratio * beta_ratio; /* beta = sqrt(lambda rho c) */
}

typedef struct band_run {
  double T1[NX_MAX], T2[NX_MAX], q1[NX_MAX], q2[NX_MAX], q[NX_MAX];
  signed char contact[NX_MAX];
  rs_thermal_result res;
  double dx, beta[2];
} band_run;

static int run_band(band_run *r, const rs_thermal_params *p, int nx, double qband)
{
  rs_thermal th;
  rs_msg msg = {{0}};
  r->dx = (X_HI - X_LO) / nx;
  for (int i = 0; i < nx; i++) {
    const double x = X_LO + (i + 0.5) * r->dx;
    r->contact[i] = fabs(x) < A;
    r->q[i] = r->contact[i] ? qband : 0.0;
  }
  if (rs_thermal_create(&th, p, nx, 1, r->dx, r->dx, &msg) != RS_OK) {
    printf("FAIL thermal: %s\n", msg.text);
    return failures++, 1;
  }
  rs_thermal_march(&th, V, r->q, r->contact, r->T1, r->T2, r->q1, r->q2, &r->res);
  r->beta[0] = th.beta[0];
  r->beta[1] = th.beta[1];
  rs_thermal_free(&th);
  return 0;
}

/* Largest error of T1 against the band solution, relative to the peak rise. */
static double band_error(const band_run *r, const rs_thermal_params *p, int nx, double qband)
{
  const double bsum = r->beta[0] + r->beta[1];
  double worst = 0.0, peak = 2.0 * qband * sqrt(2.0 * A / V) / (bsum * sqrt(PI));
  for (int i = 0; i < nx; i++) {
    const double x = X_LO + (i + 0.5) * r->dx;
    const double t = (A - x) / V, t_out = (-A - x) / V;
    double rise = 0.0;
    if (t > 0.0)
      rise = 2.0 * qband * (sqrt(t) - (t_out > 0.0 ? sqrt(t_out) : 0.0)) / (bsum * sqrt(PI));
    worst = fmax(worst, fabs(r->T1[i] - p->bulk[0] - rise) / peak);
    worst = fmax(worst, fabs(r->T2[i] - p->bulk[1] - rise) / peak);
  }
  return worst;
}

static void band(double beta_ratio)
{
  static band_run r;
  rs_thermal_params p;
  steel(&p, beta_ratio);
  p.bulk[0] = p.bulk[1] = 20.0;
  const int nx = 300;
  const double qband = 10.0; /* W/mm^2 */
  printf("band source, beta_2/beta_1 = %g: tolerance, error of T relative to the peak rise\n",
         beta_ratio);
  double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  int m = 0;
  for (double tol = 1e-2; tol > 1e-6; tol /= 10) {
    p.kernel_tolerance = tol;
    if (run_band(&r, &p, nx, qband)) return;
    const double err = band_error(&r, &p, nx, qband);
    char what[96];
    snprintf(what, sizeof what, "band error at tolerance %.0e (<= tolerance)", tol);
    check(err <= tol, what, err, tol);
    if (tol == 1e-3) check(err <= 0.01, "band error at the default tolerance (<= 1 %)", err, 0.01);
    sx += log10(tol);
    sy += log10(err);
    sxx += log10(tol) * log10(tol);
    sxy += log10(tol) * log10(err);
    m++;
  }
  /* least-squares slope of log error against log tolerance over four decades (the error of
   * single decades scatters with where the nodes fall) */
  const double order = (m * sxy - sx * sy) / (m * sxx - sx * sx);
  check(order >= 0.9 && order <= 1.2, "observed order in the tolerance, 1e-2 ... 1e-5", order, 1.0);
  /* the share and the energy */
  double share = 0.0, total = 0.0, sum_q = 0.0;
  for (int i = 0; i < nx; i++) {
    if (!r.contact[i]) continue;
    share = fmax(share, fabs(r.q1[i] / r.q[i] - 1.0 / (1.0 + beta_ratio)));
    total = fmax(total, fabs(r.q1[i] + r.q2[i] - r.q[i]) / r.q[i]);
    sum_q += r.q[i] * r.dx;
  }
  check(share <= 1e-12, "share q1/q = beta_1/(beta_1 + beta_2)", share, 0.0);
  check(total <= 1e-14, "q1 + q2 = q in the contact", total, 0.0);
  const double heat = r.res.heat_input[0] + r.res.heat_input[1];
  check(fabs(heat / sum_q - 1.0) <= 1e-12, "heat into both bodies = sum q dA (W/mm)", heat, sum_q);
}

static void cold_meets_hot(void)
{
  static band_run r;
  rs_thermal_params p;
  steel(&p, 2.0);
  p.bulk[0] = 0.0;
  p.bulk[1] = 150.0;
  p.kernel_tolerance = 1e-7;
  const double Tc = (1.0 * 0.0 + 2.0 * 150.0) / 3.0; /* beta_2 = 2 beta_1 */
  double err_prev = NAN;
  for (int nx = 150; nx <= 600; nx *= 2) {
    if (run_band(&r, &p, nx, 0.0)) return;
    double worst = 0.0;
    for (int i = 0; i < nx; i++)
      if (r.contact[i]) worst = fmax(worst, fmax(fabs(r.T1[i] - Tc), fabs(r.T2[i] - Tc)) / Tc);
    char what[96];
    snprintf(what, sizeof what,
             "%d cells: contact temperature (beta1 T1 + beta2 T2)/(beta1 + beta2)", nx);
    check(worst <= 1e-12, what, worst, 0.0);
    /* heat into body 1 over the band: int_0^{2a} beta_1 (Tc - 0)/sqrt(pi x/V) dx */
    double band_len = 0.0;
    for (int i = 0; i < nx; i++) band_len += r.contact[i] * r.dx;
    const double want = r.beta[0] * Tc * 2.0 * sqrt(band_len * V / PI);
    const double err = fabs(r.res.heat_input[0] / want - 1.0);
    snprintf(what, sizeof what, "%d cells: heat into body 1 (W/mm), error %.3g", nx, err);
    check(nx != 300 || err <= 1e-5, what, r.res.heat_input[0], want);
    check(fabs(r.res.heat_input[0] + r.res.heat_input[1]) <= 1e-12 * fabs(r.res.heat_input[0]),
          "no heat generated: body 2 gives what body 1 takes", r.res.heat_input[1],
          -r.res.heat_input[0]);
    if (!isnan(err_prev)) {
      snprintf(what, sizeof what, "%d cells: heat error falls by a factor in [3, 5]", nx);
      check(err_prev / err >= 3.0 && err_prev / err <= 5.0, what, err_prev / err, 4.0);
    }
    err_prev = err;
  }
}

static void rigid_body_2(void)
{
  static band_run r;
  rs_thermal_params p;
  steel(&p, 1e8);
  p.bulk[0] = 20.0;
  p.bulk[1] = 40.0;
  if (run_band(&r, &p, 300, 10.0)) return;
  double worst = 0.0;
  for (int i = 0; i < 300; i++)
    if (r.contact[i]) worst = fmax(worst, fabs(r.T1[i] - 40.0));
  check(worst <= 1e-6, "beta_2 -> infinity: T1 = T_bulk_2 in the contact (K)", worst, 0.0);
}

int main(void)
{
  kernel_table();
  band(1.0);
  band(3.0);
  cold_meets_hot();
  rigid_body_2();
  printf("%s: %d failure(s)\n", failures ? "FAILED" : "passed", failures);
  return failures ? 1 : 0;
}
