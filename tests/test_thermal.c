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
 *    heat; body 1 reads T_bulk_2 in the contact to 1e-6 K.
 * 6. The modes as DAE state (docs/model.md §18, "Heat memory"), on a band with a varying source,
 *    beta_2 = 2 beta_1 and bulk 20 / 60 degC:
 *    - the march's modes are a steady state of the DAE: their rates are 0 exactly (the same
 *      arithmetic cell by cell), and the temperatures of that state are the march's, bitwise;
 *    - a BDF step's rows solved by rs_thermal_dae_solve: the residual at (pred + cor,
 *      ratepred + cj cor) vanishes to 1e-12 of the rates' scale;
 *    - a state uniform along x under a uniform source in a contact covering the grid (equal
 *      bodies and bulks: shares q/2) is the material point's exact law: theta_k' = V q_b -
 *      V r_k theta_k (V q_b for the mode of rate 0) away from the leading edge, to 1e-12; and the
 *      state of a uniform source switched on a path l ago, theta_k = q_b (1 - e^(-r_k l))/r_k,
 *      theta_0 = q_b l, gives T - T_bulk = q_b S(l + dx/2)/(beta sqrt(V)) at every cell but the
 *      first (the cell centre counts the half cell it has crossed), to 1e-12, within the kernel
 *      tolerance of 2 q_b sqrt(t + dx/(2V))/(beta sqrt(pi)), t = l/V. */
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

static void dae_rows(void)
{
  enum { NX = 120 };
  static double q[NX], T1[NX], T2[NX], U1[NX], U2[NX];
  static signed char contact[NX];
  rs_thermal_params p;
  steel(&p, 2.0);
  p.bulk[0] = 20.0;
  p.bulk[1] = 60.0;
  rs_thermal th;
  rs_msg msg = {{0}};
  const double dx = (X_HI - X_LO) / NX;
  if (rs_thermal_create(&th, &p, NX, 1, dx, dx, &msg) != RS_OK) {
    printf("FAIL thermal: %s\n", msg.text);
    failures++;
    return;
  }
  for (int i = 0; i < NX; i++) {
    const double x = X_LO + (i + 0.5) * dx;
    contact[i] = fabs(x) < A;
    q[i] = contact[i] ? 10.0 * (1.0 - x * x) * (1.2 + x) : 0.0;
  }
  const int ns = rs_thermal_nstate(&th);
  double *state = calloc((size_t)ns, sizeof *state), *rate = calloc((size_t)ns, sizeof *rate);
  double *pred = calloc((size_t)ns, sizeof *pred), *ratepred = calloc((size_t)ns, sizeof *ratepred);
  double *cor = calloc((size_t)ns, sizeof *cor), *F = calloc((size_t)ns, sizeof *F);
  if (!state || !rate || !pred || !ratepred || !cor || !F) {
    printf("FAIL out of memory\n");
    failures++;
    goto done;
  }
  rs_thermal_result r, rs;
  rs_thermal_march_state(&th, V, q, contact, T1, T2, NULL, NULL, &r, state);
  rs_thermal_dae_rates(&th, V, q, contact, state, rate);
  double worst = 0.0;
  for (int k = 0; k < ns; k++) worst = fmax(worst, fabs(rate[k]));
  check(worst == 0.0, "the march's modes: DAE rates 0 exactly", worst, 0.0);
  rs_thermal_state_eval(&th, V, q, contact, state, U1, U2, NULL, NULL, &rs);
  int same = rs.T_max == r.T_max && rs.heat_input[0] == r.heat_input[0];
  for (int i = 0; i < NX; i++) same &= U1[i] == T1[i] && U2[i] == T2[i];
  check(same, "temperatures of the steady state = the march's, bitwise", rs.T_max, r.T_max);

  /* a BDF step: predictor perturbed from the steady state, then solved */
  double scale = 0.0;
  for (int k = 0; k < ns; k++) {
    pred[k] = state[k] * (1.0 + 0.01 * sin(0.7 * k));
    ratepred[k] = 1e3 * V * state[k] * cos(0.3 * k) / (X_HI - X_LO);
    scale = fmax(scale, fabs(ratepred[k]));
  }
  const double cj = 3.0 * V / dx;
  rs_thermal_dae_solve(&th, V, q, contact, cj, pred, ratepred, state, cor);
  for (int k = 0; k < ns; k++) rate[k] = ratepred[k] + cj * cor[k];
  rs_thermal_dae_residual(&th, V, q, contact, state, rate, F);
  worst = 0.0;
  for (int k = 0; k < ns; k++) worst = fmax(worst, fabs(F[k]));
  check(worst <= 1e-12 * scale, "a BDF step's rows solved exactly (residual / rate scale)",
        worst / scale, 0.0);

  /* uniform source, contact over the grid, equal bodies and bulks */
  rs_thermal_free(&th);
  steel(&p, 1.0);
  p.bulk[0] = p.bulk[1] = 20.0;
  if (rs_thermal_create(&th, &p, NX, 1, dx, dx, &msg) != RS_OK) {
    printf("FAIL thermal: %s\n", msg.text);
    failures++;
    goto done;
  }
  const int K = th.ker.nmodes;
  const double q0 = 5.0, qb = 0.5 * q0, l = 0.4; /* W/mm^2, mm of path since the start */
  for (int i = 0; i < NX; i++) {
    contact[i] = 1;
    q[i] = q0;
  }
  for (int b = 0; b < 2; b++)
    for (int k = 0; k <= K; k++)
      for (int i = 0; i < NX; i++)
        state[(b * (K + 1) + k) * NX + i] =
            k == K ? qb * l : qb * -expm1(-th.ker.rate[k] * l) / th.ker.rate[k];
  rs_thermal_dae_rates(&th, V, q, contact, state, rate);
  double wrate = 0.0, wT = 0.0, wlaw = 0.0;
  for (int b = 0; b < 2; b++)
    for (int k = 0; k <= K; k++)
      for (int i = 0; i < NX - 1; i++) {
        const double th_k = state[(b * (K + 1) + k) * NX + i];
        const double want = k == K ? V * qb : V * qb - V * th.ker.rate[k] * th_k;
        wrate = fmax(wrate, fabs(rate[(b * (K + 1) + k) * NX + i] - want) / (V * qb));
      }
  check(wrate <= 1e-12, "uniform state: theta' = V q_b - V r_k theta (relative to V q_b)", wrate,
        0.0);
  rs_thermal_state_eval(&th, V, q, contact, state, U1, U2, NULL, NULL, &rs);
  const double want_T = qb * rs_thermal_kernel_step(&th.ker, l + 0.5 * dx) / (th.beta[0] * sqrt(V));
  const double law = 2.0 * qb * sqrt((l + 0.5 * dx) / V) / (th.beta[0] * sqrt(PI));
  for (int i = 0; i < NX - 1; i++) {
    wT = fmax(wT, fmax(fabs(U1[i] - 20.0 - want_T), fabs(U2[i] - 20.0 - want_T)) / want_T);
    wlaw = fmax(wlaw, fabs(U1[i] - 20.0 - law) / law);
  }
  check(wT <= 1e-12, "uniform state: T - T_bulk = q_b S(l + dx/2)/(beta sqrt(V))", wT, 0.0);
  check(wlaw <= p.kernel_tolerance,
        "uniform state: 2 q_b sqrt(t + dx/(2V))/(beta sqrt(pi)) to the kernel tolerance", wlaw,
        p.kernel_tolerance);
done:
  free(state);
  free(rate);
  free(pred);
  free(ratepred);
  free(cor);
  free(F);
  rs_thermal_free(&th);
}

int main(void)
{
  kernel_table();
  band(1.0);
  band(3.0);
  cold_meets_hot();
  rigid_body_2();
  dae_rows();
  printf("%s: %d failure(s)\n", failures ? "FAILED" : "passed", failures);
  return failures ? 1 : 0;
}
