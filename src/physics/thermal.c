/* Surface temperature (physics/thermal.h, docs/model.md §18). */
#include "physics/thermal.h"

#include "physics/model.h"
#include "physics/rig.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Points per decade of path length at which the step response is checked. */
enum { CHECK_PER_DECADE = 60, MAX_REFINE = 30 };

/* Nodes u_k = u_lo + k h, weights (h/pi) e^(u_k/2); the tails beyond the first and the last
 * node as geometric sums of the same trapezoidal rule (so that the truncated rule equals the
 * infinite one where the tail modes are fully decayed or not decayed at all). */
static int build(rs_thermal_kernel *k, double h, double u_lo, double u_hi)
{
  const int K = (int)ceil((u_hi - u_lo) / h) + 1;
  double *w = malloc((size_t)K * sizeof *w), *r = malloc((size_t)K * sizeof *r);
  if (!w || !r) {
    free(w);
    free(r);
    return RS_ERR_INTERNAL;
  }
  for (int i = 0; i < K; i++) {
    const double u = u_lo + i * h;
    w[i] = h / M_PI * exp(0.5 * u);
    r[i] = exp(u);
  }
  const double g = exp(-0.5 * h) / -expm1(-0.5 * h); /* sum_{j >= 1} e^(-j h/2) */
  free(k->weight);
  free(k->rate);
  k->weight = w;
  k->rate = r;
  k->nmodes = K;
  k->step = h;
  k->weight0 = h / M_PI * exp(0.5 * u_lo) * g;
  k->local = h / M_PI * exp(-0.5 * (u_lo + (K - 1) * h)) * g;
  return RS_OK;
}

double rs_thermal_kernel_step(const rs_thermal_kernel *k, double l)
{
  double s = k->weight0 * l + k->local;
  for (int i = 0; i < k->nmodes; i++) s += k->weight[i] * -expm1(-k->rate[i] * l) / k->rate[i];
  return s;
}

static double step_error(const rs_thermal_kernel *k)
{
  const double decades = log10(k->l_max / k->l_min);
  const int m = (int)ceil(decades * CHECK_PER_DECADE) + 1;
  double worst = 0.0;
  for (int i = 0; i <= m; i++) {
    const double l = i == m ? k->l_max : k->l_min * pow(10.0, decades * i / m);
    const double exact = 2.0 * sqrt(l / M_PI);
    worst = fmax(worst, fabs(rs_thermal_kernel_step(k, l) / exact - 1.0));
  }
  return worst;
}

int rs_thermal_kernel_create(rs_thermal_kernel *k, double l_min, double l_max, double tol,
                             rs_msg *msg)
{
  memset(k, 0, sizeof *k);
  if (!(tol > 0.0 && tol <= 0.1))
    return rs_msg_set(msg, RS_ERR_INPUT, "temperature kernel: tolerance %g outside (0, 0.1]", tol);
  if (!(l_min > 0.0 && l_max > l_min && isfinite(l_max)))
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "temperature kernel: path lengths [%g, %g] mm: need 0 < l_min < l_max", l_min,
                      l_max);
  k->l_min = l_min;
  k->l_max = l_max;
  /* The trapezoidal rule's error is about e^(-pi^2/h) (the integrand is analytic in the
   * strip |Im u| < pi/2); the slow tail lumped into one mode of rate 0 errs by about
   * (rate_lo l)^(3/2)/(6 sqrt(pi)) relative at l = l_max, the fast tail taken as
   * instantaneous by about z^(-3/2) e^(-z)/(2 sqrt(pi)) at z = rate_hi l_min. */
  double h = M_PI * M_PI / log(1.0 / tol);
  double lo_margin = fmax(0.0, -2.0 / 3.0 * log(2.0 * sqrt(M_PI) * tol) - 0.5 * h);
  double z = 0.5;
  while (pow(z, 1.5) * exp(z) * 2.0 * sqrt(M_PI) < 1.0 / tol) z *= 1.05;
  double hi_margin = log(z) + 0.5 * h;
  for (int attempt = 0; attempt < MAX_REFINE; attempt++) {
    if (build(k, h, -log(l_max) - lo_margin, -log(l_min) + hi_margin) != RS_OK) {
      rs_thermal_kernel_free(k);
      return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for the temperature kernel");
    }
    k->error = step_error(k);
    if (k->error <= tol) return RS_OK;
    h *= 0.85; /* the estimates above fell short: a finer and wider rule */
    lo_margin += 0.5;
    hi_margin += 0.5;
  }
  const double err = k->error;
  rs_thermal_kernel_free(k);
  return rs_msg_set(msg, RS_ERR_INTERNAL,
                    "temperature kernel: relative error %.3g above the tolerance %g", err, tol);
}

void rs_thermal_kernel_free(rs_thermal_kernel *k)
{
  free(k->weight);
  free(k->rate);
  k->weight = k->rate = NULL;
  k->nmodes = 0;
}

int rs_thermal_create(rs_thermal *th, const rs_thermal_params *p, int nx, int ny, double dx,
                      double area, rs_msg *msg)
{
  memset(th, 0, sizeof *th);
  th->par = *p;
  th->nx = nx;
  th->ny = ny;
  th->dx = dx;
  th->area = area;
  for (int b = 0; b < 2; b++)
    th->beta[b] = sqrt(p->conductivity[b] * p->density[b] * p->heat_capacity[b]);
  const double l_max = fmax(nx * dx, p->path_max);
  int status = rs_thermal_kernel_create(&th->ker, 0.5 * dx, l_max, p->kernel_tolerance, msg);
  if (status != RS_OK) return status;
  const int K = th->ker.nmodes;
  th->decay_half = malloc((size_t)K * sizeof *th->decay_half);
  th->decay_full = malloc((size_t)K * sizeof *th->decay_full);
  th->gain_full = malloc((size_t)K * sizeof *th->gain_full);
  th->inv_gain = malloc((size_t)(K + 1) * sizeof *th->inv_gain);
  th->theta = malloc(2 * (size_t)(K + 1) * sizeof *th->theta);
  if (!th->decay_half || !th->decay_full || !th->gain_full || !th->inv_gain || !th->theta) {
    rs_thermal_free(th);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for the temperature modes");
  }
  for (int k = 0; k < K; k++) {
    const double r = th->ker.rate[k];
    th->decay_half[k] = exp(-0.5 * r * dx);
    th->decay_full[k] = exp(-r * dx);
    th->gain_full[k] = -expm1(-r * dx) / r;
    th->inv_gain[k] = 1.0 / th->gain_full[k];
  }
  th->inv_gain[K] = 1.0 / dx;
  th->self_half = rs_thermal_kernel_step(&th->ker, 0.5 * dx);
  return RS_OK;
}

void rs_thermal_free(rs_thermal *th)
{
  rs_thermal_kernel_free(&th->ker);
  free(th->decay_half);
  free(th->decay_full);
  free(th->gain_full);
  free(th->inv_gain);
  free(th->theta);
  free(th->transfer);
  free(th->inflow);
  free(th->exit_buf);
  th->decay_half = th->decay_full = th->gain_full = th->inv_gain = th->theta = NULL;
  th->transfer = th->inflow = th->exit_buf = NULL;
  th->memory = NULL;
}

/* Per body b and mode k the state theta = int q_b(l') e^(-rate_k (l - l')) dl' (W/mm) at the
 * cell's downstream edge; the mode of rate 0 is the plain integral (the last entry). With
 * q_b constant over a cell the update is exact (the exponentially fitted upwind step):
 *   theta_out = theta_in e^(-rate dx) + q_b (1 - e^(-rate dx))/rate.
 * At the centre T_b = T_bulk + (H_b + S(dx/2) q_b)/(beta_b sqrt(V)) with H_b the history
 * decayed over half a cell; T1 = T2 and q1 + q2 = q in the contact fix q1. The march and the
 * DAE's rows share this cell's arithmetic: up[b] points at body b's modes entering the cell
 * (stride apart; NULL: fresh material). */
static void cell_partition(const rs_thermal *th, double s, const double *const up[2], int stride,
                           double q, int contact, double qb[2], double T[2])
{
  const int K = th->ker.nmodes;
  const double *w = th->ker.weight;
  double H[2];
  for (int b = 0; b < 2; b++) {
    double hist = 0.0;
    if (up[b]) {
      hist = th->ker.weight0 * up[b][K * stride];
      for (int k = 0; k < K; k++) hist += w[k] * up[b][k * stride] * th->decay_half[k];
    }
    H[b] = th->par.bulk[b] + s * hist / th->beta[b];
  }
  /* B_b: the temperature rise of body b at a cell centre per unit of its own flux there */
  const double B[2] = {s * th->self_half / th->beta[0], s * th->self_half / th->beta[1]};
  qb[0] = qb[1] = 0.0;
  if (contact) {
    qb[0] = (H[1] - H[0] + B[1] * q) / (B[0] + B[1]);
    qb[1] = q - qb[0];
  }
  T[0] = H[0] + B[0] * qb[0];
  T[1] = H[1] + B[1] * qb[1];
}

/* The modes leaving a cell whose entering modes are up (NULL: fresh) under the flux qb. */
static double mode_out(const rs_thermal *th, const double *up, int stride, int k, double qb)
{
  const int K = th->ker.nmodes;
  if (k == K) return (up ? up[K * stride] : 0.0) + qb * th->dx;
  return (up ? up[k * stride] * th->decay_full[k] : 0.0) + qb * th->gain_full[k];
}

/* The modes entering cell (ix, iy) of the DAE state: those of the cell upstream, at the
 * leading edge a rig's inflow (stride ny) or none (fresh material). */
static void entering(const rs_thermal *th, const double *state, int iy, int ix, const double *up[2],
                     int *stride)
{
  const int n = th->nx * th->ny, M = th->ker.nmodes + 1, i = iy * th->nx + ix;
  if (ix + 1 < th->nx) {
    for (int b = 0; b < 2; b++) up[b] = state + (size_t)b * M * n + i + 1;
    *stride = n;
  } else if (th->inflow) {
    for (int b = 0; b < 2; b++) up[b] = th->inflow + (size_t)b * M * th->ny + iy;
    *stride = th->ny;
  }
}

static void march(rs_thermal *th, double V, const double *q, const signed char *contact,
                  const double *from_state, double *T1, double *T2, double *q1, double *q2,
                  rs_thermal_result *res, double *state)
{
  const int nx = th->nx, n = th->nx * th->ny, K = th->ker.nmodes, M = K + 1;
  res->heat_input[0] = res->heat_input[1] = 0.0;
  if (!(V > 0.0)) {
    for (int i = 0; i < n; i++) {
      T1[i] = T2[i] = NAN;
      if (q1) q1[i] = NAN;
      if (q2) q2[i] = NAN;
    }
    res->T_max = res->heat_input[0] = res->heat_input[1] = NAN;
    return;
  }
  const double s = 1.0 / sqrt(V);
  double T_max = -INFINITY;
  for (int iy = 0; iy < th->ny; iy++) {
    double *theta[2] = {th->theta, th->theta + M};
    memset(th->theta, 0, 2 * (size_t)M * sizeof *th->theta); /* fresh material */
    for (int b = 0; th->inflow && b < 2; b++) /* or a rig's material coming around again */
      for (int k = 0; k <= K; k++) theta[b][k] = th->inflow[((size_t)b * M + k) * th->ny + iy];
    for (int ix = nx - 1; ix >= 0; ix--) {
      const int i = iy * nx + ix;
      double qb[2], T[2];
      if (from_state) { /* the modes entering: those of the DAE state upstream */
        const double *up[2] = {NULL, NULL};
        int stride = n;
        entering(th, from_state, iy, ix, up, &stride);
        cell_partition(th, s, up, stride, q[i], contact[i], qb, T);
      } else {
        const double *up[2] = {theta[0], theta[1]};
        cell_partition(th, s, up, 1, q[i], contact[i], qb, T);
        for (int b = 0; b < 2; b++) {
          for (int k = 0; k <= K; k++) theta[b][k] = mode_out(th, theta[b], 1, k, qb[b]);
          for (int k = 0; state && k <= K; k++) state[((size_t)b * M + k) * n + i] = theta[b][k];
        }
      }
      T1[i] = T[0];
      T2[i] = T[1];
      if (q1) q1[i] = qb[0];
      if (q2) q2[i] = qb[1];
      if (contact[i]) T_max = fmax(T_max, fmax(T1[i], T2[i]));
      for (int b = 0; b < 2; b++) res->heat_input[b] += qb[b] * th->area;
    }
  }
  res->T_max = T_max > -INFINITY ? T_max : NAN;
}

void rs_thermal_march(rs_thermal *th, double V, const double *q, const signed char *contact,
                      double *T1, double *T2, double *q1, double *q2, rs_thermal_result *res)
{
  march(th, V, q, contact, NULL, T1, T2, q1, q2, res, NULL);
}

void rs_thermal_march_state(rs_thermal *th, double V, const double *q, const signed char *contact,
                            double *T1, double *T2, double *q1, double *q2, rs_thermal_result *res,
                            double *state)
{
  march(th, V, q, contact, NULL, T1, T2, q1, q2, res, state);
}

void rs_thermal_state_eval(rs_thermal *th, double V, const double *q, const signed char *contact,
                           const double *state, double *T1, double *T2, double *q1, double *q2,
                           rs_thermal_result *res)
{
  march(th, V, q, contact, state, T1, T2, q1, q2, res, NULL);
}

/* Per cell and mode the relaxation rate c_k = V/g_k (g_k = (1 - e^(-rate_k dx))/rate_k, dx for
 * the mode of rate 0) and the mode the cell relaxes to, theta_out of the exact step: the
 * right-hand side f of theta' = c_k (theta_out - theta) (docs/model.md §18). One cell's block
 * at a time through `visit`, in the order of the march (from the leading edge), so that the
 * solve can use the modes upstream as just computed. */
enum { DAE_RESIDUAL, DAE_RATES, DAE_SOLVE };
static void dae_pass(rs_thermal *th, int what, double V, const double *q,
                     const signed char *contact, double *state, const double *rate, double *out,
                     double cj, const double *pred, const double *ratepred)
{
  const int nx = th->nx, n = th->nx * th->ny, K = th->ker.nmodes, M = K + 1;
  const int moving = V > 0.0;
  const double s = moving ? 1.0 / sqrt(V) : 0.0;
  /* per mode c_k (without rolling the modes are frozen: no material path, docs/model.md §18)
   * and, for the solve, 1/(cj + c_k) */
  double *c = th->theta, *inv = th->theta + M;
  for (int k = 0; k <= K; k++) {
    c[k] = moving ? V * th->inv_gain[k] : 0.0;
    inv[k] = what == DAE_SOLVE ? 1.0 / (cj + c[k]) : 0.0;
  }
  for (int iy = 0; iy < th->ny; iy++)
    for (int ix = nx - 1; ix >= 0; ix--) {
      const int i = iy * nx + ix;
      double qb[2] = {0.0, 0.0}, T[2];
      const double *up[2] = {NULL, NULL};
      int stride = n;
      entering(th, state, iy, ix, up, &stride);
      if (moving) cell_partition(th, s, up, stride, q[i], contact[i], qb, T);
      for (int b = 0; b < 2; b++)
        for (int k = 0; k <= K; k++) {
          const size_t at = ((size_t)b * M + k) * n + i;
          const double target = moving ? mode_out(th, up[b], stride, k, qb[b]) : 0.0;
          if (what == DAE_RESIDUAL) {
            out[at] = rate[at] - c[k] * (target - state[at]);
          } else if (what == DAE_RATES) {
            out[at] = c[k] * (target - state[at]);
          } else { /* pred + cor solves ratepred + cj cor = c (target - pred - cor) */
            const double cor = (c[k] * (target - pred[at]) - ratepred[at]) * inv[k];
            out[at] = cor;
            state[at] = pred[at] + cor;
          }
        }
    }
}

void rs_thermal_dae_residual(rs_thermal *th, double V, const double *q, const signed char *contact,
                             const double *state, const double *rate, double *F)
{
  dae_pass(th, DAE_RESIDUAL, V, q, contact, (double *)state, rate, F, 0.0, NULL, NULL);
}

void rs_thermal_dae_rates(rs_thermal *th, double V, const double *q, const signed char *contact,
                          const double *state, double *rate)
{
  dae_pass(th, DAE_RATES, V, q, contact, (double *)state, NULL, rate, 0.0, NULL, NULL);
}

void rs_thermal_dae_solve(rs_thermal *th, double V, const double *q, const signed char *contact,
                          double cj, const double *pred, const double *ratepred, double *state,
                          double *cor)
{
  dae_pass(th, DAE_SOLVE, V, q, contact, state, NULL, cor, cj, pred, ratepred);
}

void rs_thermal_state_temperature(rs_thermal *th, double V, const double *state, double *T)
{
  const int nx = th->nx, n = th->nx * th->ny, K = th->ker.nmodes;
  const double s = 1.0 / sqrt(V);
  for (int iy = 0; iy < th->ny; iy++)
    for (int ix = nx - 1; ix >= 0; ix--) {
      const int i = iy * nx + ix;
      const double *up[2] = {NULL, NULL};
      int stride = n;
      entering(th, state, iy, ix, up, &stride);
      double hist = 0.0, in0 = 0.0;
      if (up[0]) {
        in0 = up[0][K * stride];
        hist = th->ker.weight0 * in0;
        for (int k = 0; k < K; k++)
          hist += th->ker.weight[k] * up[0][k * stride] * th->decay_half[k];
      }
      const double q1 = (state[(size_t)K * n + i] - in0) / th->dx;
      T[i] = th->par.bulk[0] + s * (hist + th->self_half * q1) / th->beta[0];
    }
}

void rs_thermal_sources(const rs_thermal *th, const rs_model *m, const rs_work *w, const double *y,
                        double *fric, double *plast, double *q, signed char *contact)
{
  const double frac = th->par.plastic_heat_fraction;
  rs_model_power_densities(m, w, y, fric, plast);
  /* N/(mm s) = N mm/(s mm^2) = 1e-3 W/mm^2 */
  for (int i = 0; i < m->grid.n; i++) {
    contact[i] = w->pn[i] > 0.0;
    q[i] = 1e-3 * (fric[i] + frac * plast[i]);
  }
}

/* One disc's transfer matrix over its free path P (mm): without convection each mode decays
 * by its exact factor e^(-rate P) (the mode of rate 0 is kept); with it the path is marched in
 * segments growing geometrically from a cell (the excess decays like 1/sqrt(l) from the
 * exit), each under the convective flux q = -h dT at its centre, dT the surface excess there
 * (collocated like a cell of the march: dT = s (H + S(dl/2) q)/beta, solved for q), the
 * modes then stepped exactly under that flux. Column j: the modes after the path from the
 * unit mode j at the exit. */
static int transfer_matrix(const rs_thermal *th, int b, double P, double V, double *A)
{
  const int K = th->ker.nmodes, M = K + 1;
  const double *w = th->ker.weight, *r = th->ker.rate, h = th->par.convection;
  memset(A, 0, (size_t)M * M * sizeof *A);
  if (!(h > 0.0) || !(P > 0.0)) {
    for (int k = 0; k < K; k++) A[k * M + k] = exp(-r[k] * fmax(P, 0.0));
    A[K * M + K] = 1.0;
    return RS_OK;
  }
  double *v = malloc((size_t)M * sizeof *v);
  if (!v) return RS_ERR_INTERNAL;
  const double s = 1.0 / sqrt(V), beta = th->beta[b];
  for (int j = 0; j < M; j++) {
    memset(v, 0, (size_t)M * sizeof *v);
    v[j] = 1.0;
    double done = 0.0, dl = th->dx;
    while (done < P) {
      if (done + 1.5 * dl > P) dl = P - done; /* the last segment takes the rest */
      double hist = th->ker.weight0 * v[K];
      for (int k = 0; k < K; k++) hist += w[k] * v[k] * exp(-0.5 * r[k] * dl);
      const double self = rs_thermal_kernel_step(&th->ker, 0.5 * dl);
      const double dT = s * hist / beta / (1.0 + s * self * h / beta), q = -h * dT;
      for (int k = 0; k < K; k++) v[k] = v[k] * exp(-r[k] * dl) - q * expm1(-r[k] * dl) / r[k];
      v[K] += q * dl;
      done += dl;
      dl *= 1.1;
    }
    for (int k = 0; k < M; k++) A[k * M + j] = v[k];
  }
  free(v);
  return RS_OK;
}

int rs_thermal_rig_attach(rs_thermal *th, const rs_rig_memory *mem, const double path[2], double V,
                          rs_msg *msg)
{
  const int M = th->ker.nmodes + 1;
  const size_t width = 2 * (size_t)M * th->ny;
  if (mem->width != (int)width || !(V > 0.0))
    return rs_msg_set(msg, RS_ERR_INTERNAL, "temperature: the twin-disc memory does not fit");
  th->transfer = malloc(2 * (size_t)M * M * sizeof *th->transfer);
  th->inflow = calloc(width, sizeof *th->inflow);
  th->exit_buf = malloc(width * sizeof *th->exit_buf);
  if (!th->transfer || !th->inflow || !th->exit_buf)
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for the twin-disc heat memory");
  for (int b = 0; b < 2; b++)
    if (transfer_matrix(th, b, path[b], V, th->transfer + (size_t)b * M * M) != RS_OK)
      return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for the twin-disc heat memory");
  th->memory = mem;
  return RS_OK;
}

void rs_thermal_inflow_at(rs_thermal *th, double t)
{
  if (!th->memory) return;
  const int M = th->ker.nmodes + 1, ny = th->ny;
  for (int b = 0; b < 2; b++) {
    /* disc b's own record, one free path ago (the other half of the buffer is not used) */
    rs_rig_memory_exit(th->memory, t - th->memory->delay[b], th->exit_buf);
    const double *A = th->transfer + (size_t)b * M * M, *e = th->exit_buf + (size_t)b * M * ny;
    double *in = th->inflow + (size_t)b * M * ny;
    for (int iy = 0; iy < ny; iy++)
      for (int j = 0; j < M; j++) {
        double sum = 0.0;
        for (int k = 0; k < M; k++) sum += A[j * M + k] * e[k * ny + iy];
        in[j * ny + iy] = sum;
      }
  }
}

void rs_thermal_inlet_temperature(const rs_thermal *th, double V, double T[2])
{
  const int K = th->ker.nmodes, M = K + 1, ny = th->ny;
  for (int b = 0; b < 2; b++) {
    double sum = 0.0;
    for (int iy = 0; th->inflow && iy < ny; iy++) {
      const double *in = th->inflow + (size_t)b * M * ny + iy;
      double hist = th->ker.weight0 * in[K * ny];
      for (int k = 0; k < K; k++) hist += th->ker.weight[k] * in[k * ny];
      sum += hist;
    }
    T[b] = th->par.bulk[b] + sum / ny / (th->beta[b] * sqrt(V));
  }
}
