/* A small sinusoidal creepage in full adhesion (docs/verification.md 7; issue: varying
 * creepage): the problem is linear, so F_x is sinusoidal at the same frequency, and
 * as the frequency falls its amplitude and phase approach the quasi-static steady
 * response K xi(t), K = dF_x/dxi of steady rolling. The 2D force builds up slowly
 * (time constant of many contact lengths, docs/model.md §2), so "low" means a period of
 * tens of thousands of contact passages. Three frequencies; at the lowest the amplitude
 * ratio is within 1e-3 of 1 and the phase lag below 1e-3 rad. The fit is the
 * projection on sin/cos over the last two full periods (M equally spaced samples);
 * what is left after the fit, relative to the amplitude, measures the harmonics. */
#include <stdlib.h>

#include "physics/model.h"
#include "solve/steady.h"
#include "test_support.h"

static double total_force(const rs_model *m, const double *y)
{
  double f = 0;
  for (int i = 0; i < m->grid.n; i++) f += y[i] * m->grid.dx;
  return f;
}

int main(void)
{
  const double xi0 = -2e-8, xia = 1e-8; /* |xi| <= 3e-8: no cell slips (tested below) */
  rs_case c;
  ts_carter_case(&c, 52);
  c.extent = 1.04;
  rs_msg msg = {{0}};
  /* quasi-static gain from two steady solves */
  double F[2];
  for (int k = 0; k < 2; k++) {
    c.creepage.value = xi0 + (k ? xia : -xia);
    rs_model m;
    rs_model_from_case(&m, &c, &msg);
    double *y = calloc((size_t)m.lay.neq, sizeof *y);
    rs_steady *s = NULL;
    rs_stats st = {0};
    if (rs_steady_create(&s, &m, NULL, &msg) || rs_steady_solve(s, 0.0, y, &st, &msg)) {
      printf("FAIL steady: %s\n", msg.text);
      return 1;
    }
    F[k] = total_force(&m, y);
    rs_steady_free(s);
    free(y);
    rs_model_free(&m);
  }
  const double K = (F[1] - F[0]) / (2 * xia);
  /* Hz; one contact passage takes 2a/V = 6.7e-5 s; the force lags with a time constant of
   * about 3 passages (phase ~ 2 pi f tau), so 0.5 Hz gives a lag of order 6e-4 rad */
  const double freqs[3] = {2000.0, 50.0, 0.5};
  double amp_err[3], phase[3];
  for (int k = 0; k < 3; k++) {
    const double f = freqs[k], period = 1.0 / f;
    c.creepage.kind = RS_HISTORY_SINE;
    c.creepage.mean = xi0;
    c.creepage.amplitude = xia;
    c.creepage.frequency = f;
    c.creepage.phase = 0.0;
    c.mode = RS_MODE_TRANSIENT;
    rs_model m;
    rs_model_from_case(&m, &c, &msg);
    double *y = calloc((size_t)m.lay.neq, sizeof *y), *yp = calloc((size_t)m.lay.neq, sizeof *yp);
    rs_work w;
    rs_work_create(&w, &m);
    /* start from the steady state at the mean creepage (the sine starts there) */
    rs_steady *s = NULL;
    rs_stats st = {0};
    rs_steady_create(&s, &m, NULL, &msg);
    rs_steady_solve(s, 0.0, y, &st, &msg);
    rs_steady_free(s);
    ts_consistent_rates(&m, &w, 0.0, y, yp, &msg);
    const int periods = 8, M = 200; /* fit over the last two periods */
    const double t_end = periods * period;
    rs_transient_opts o = {.rtol = 1e-8,
                           .atol = 1e-12,
                           .max_order = 5,
                           .max_steps = 10000000,
                           .max_newton = 10,
                           .t_stop = t_end};
    rs_transient *tr = NULL;
    if (rs_transient_create(&tr, &m, NULL, 0.0, y, yp, &o, &msg)) return 1;
    double a = 0, b = 0, mean = 0;
    double *samples = calloc((size_t)(2 * M), sizeof *samples);
    int slip_cells = 0;
    for (int j = 1; j <= 2 * M; j++) {
      const double t = (periods - 2) * period + j * period / M;
      if (rs_transient_advance(tr, t, y, yp, &msg)) {
        printf("FAIL advance f = %g: %s\n", f, msg.text);
        return 1;
      }
      rs_diag d;
      ts_diagnostics(&m, &w, t, y, yp, &d, NULL, NULL, NULL);
      slip_cells += d.count[RS_SLIP];
      const double fx = total_force(&m, y), ph = 2 * RS_PI * f * t;
      samples[j - 1] = fx;
      a += fx * sin(ph) / M; /* 2/(2M) over two periods */
      b += fx * cos(ph) / M;
      mean += fx / (2 * M);
    }
    double resid = 0;
    for (int j = 1; j <= 2 * M; j++) {
      const double ph = 2 * RS_PI * f * ((periods - 2) * period + j * period / M);
      resid = fmax(resid, fabs(samples[j - 1] - (mean + a * sin(ph) + b * cos(ph))));
    }
    const double amp = sqrt(a * a + b * b);
    amp_err[k] = amp / fabs(K * xia) - 1.0;
    phase[k] = atan2(-b, a); /* lag of F behind K xi (K > 0 for xi > 0? sign handled below) */
    if (K * xia < 0) phase[k] = atan2(b, -a);
    rs_stats ts;
    rs_transient_get_stats(tr, &ts);
    printf("f = %7.1f Hz (%.0f contact passages per period): amplitude/quasi-static - 1 = %+.3e, "
           "phase lag %.3e rad, harmonics %.1e of the amplitude, slip cells %d, IDA steps %ld\n",
           f, period / (2.0 / 30000.0), amp_err[k], phase[k], resid / amp, slip_cells, ts.steps);
    char what[96];
    snprintf(what, sizeof what, "f = %g Hz: F_x sinusoidal (fit residual / amplitude)", f);
    ts_check(what, resid / amp, 0.0, 1e-3);
    snprintf(what, sizeof what, "f = %g Hz: full adhesion (no slip cell in any sample)", f);
    ts_check_true(what, slip_cells == 0);
    rs_transient_free(tr);
    rs_work_free(&w);
    free(samples);
    free(y);
    free(yp);
    c.creepage.kind = RS_HISTORY_CONSTANT;
    rs_model_free(&m);
  }
  ts_check_true("amplitude error falls with frequency",
                fabs(amp_err[0]) > fabs(amp_err[1]) && fabs(amp_err[1]) > fabs(amp_err[2]));
  ts_check_true("phase lag falls with frequency",
                fabs(phase[0]) > fabs(phase[1]) && fabs(phase[1]) > fabs(phase[2]));
  ts_check("lowest frequency: amplitude / quasi-static", 1.0 + amp_err[2], 1.0, 1e-3);
  ts_check("lowest frequency: phase lag (rad)", phase[2], 0.0, 1e-3);
  return ts_failures ? 1 : 0;
}
