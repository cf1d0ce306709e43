/* Plausibility warnings (study/warnings.h): inputs that are valid but most likely not what the
 * user meant, and runs that will take very long. They go to stderr and never change
 * the exit code. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "study/warnings.h"
#include "base/util.h"
#include "physics/elastic2d.h" /* RS_PI */
#include "physics/normal3d.h"

/* Carter's saturation creepage of the elastic 2D contact, mu a/R, with the Hertz
 * half-width a = sqrt(4 q R (1 - nu)/(pi G)) at the largest load of the run
 * (docs/verification.md 2); *a gets a. In 3D a is the Hertz ellipse's semi-axis along the
 * rolling direction at the largest load (N), and mu a/R_x the same scale of the
 * creepage of full sliding (Kalker's theory gives it within a factor of order one, by far
 * less than the factor the warning allows). A layer or plasticity move saturation, but
 * by far less than that factor too. */
static double saturation_creepage(const rs_case *c, double *a)
{
  const double q = rs_history_max_abs(&c->normal_load, 0.0, c->end_time);
  *a = sqrt(4.0 * q * c->radius * (1.0 - c->poisson_ratio) / (RS_PI * c->shear_modulus));
  rs_hertz_ellipse hz;
  rs_msg ignored = {{0}};
  if (c->dimension == 3 && q > 0.0 &&
      rs_hertz3d(q, 0.5 / c->radius, 0.5 / c->radius_y, c->shear_modulus, c->poisson_ratio, &hz,
                 &ignored) == RS_OK)
    *a = hz.a;
  return c->mu * *a / c->radius;
}

/* A creepage (symbol xi or eta) that looks like a percentage. */
static int warn_percent(double max_abs, const char *symbol, const char *where, FILE *err)
{
  if (!(max_abs >= RS_WARN_PERCENT) || !isfinite(max_abs)) return 0;
  fprintf(err,
          "rollsim: warning: %s reaches |%s| = %.6g, that is %.6g %% creepage: creepage is a "
          "fraction, not a percentage; did you mean %.6g %% (|%s| = %.6g)?\n",
          where, symbol, max_abs, 100.0 * max_abs, max_abs, symbol, max_abs / 100.0);
  return 1;
}

int rs_warn_creepage(const rs_case *c, double max_abs, const char *where, FILE *err)
{
  if (!(max_abs > 0.0) || !isfinite(max_abs)) return 0;
  int count = warn_percent(max_abs, "xi", where, err);
  double a;
  const double xi_sat = saturation_creepage(c, &a);
  if (max_abs > RS_WARN_SATURATION_FACTOR * xi_sat) {
    fprintf(err,
            "rollsim: warning: %s reaches |xi| = %.6g, %.3g times the creepage of full sliding "
            "mu a/R = %.6g (elastic contact: mu = %g, a = %.6g mm, R = %g mm): the whole contact "
            "slides (F_x = mu F_n) long before%s\n",
            where, max_abs, max_abs / xi_sat, xi_sat, c->mu, a, c->radius,
            c->has_plasticity ? " (local plasticity delays saturation, rarely by this much)" : "");
    count++;
  }
  return count;
}

/* 3D softening (k_tau < 0): the steady problem can have several solutions, each stable
 * under rolling, and which one Newton finds depends on its start (on the bench ellipse at
 * k_rel = -0.3, xi = -0.4 %, the solve from rest and the transient from rest settle 6 %
 * apart in F_x; usability_tests.cmake). 2D softening has shown one solution by every path. */
static int warn_softening(const rs_case *c, FILE *err)
{
  const int steady = c->mode == RS_MODE_STEADY || c->initial_state == RS_START_STEADY;
  if (c->dimension != 3 || !c->has_plasticity || !(c->k_tau < 0.0) || !steady) return 0;
  fprintf(err, "rollsim: warning: plasticity.k_rel < 0 (softening) in 3D: the steady state "
               "need not be unique, and the one found depends on where Newton starts (a "
               "sweep from a lower creepage and a transient from rest can settle on another "
               "one); simulation.mode: transient, initial_state: rest follows the physical "
               "path\n");
  return 1;
}

/* The largest |value| of a history over the run (its start for a steady case). */
static double history_max_abs(const rs_case *c, const rs_history *h)
{
  return c->mode == RS_MODE_STEADY ? fabs(rs_history_eval(h, 0.0))
                                   : rs_history_max_abs(h, 0.0, c->end_time);
}

/* The largest |value| of a sweep's axis of `key`; -1 when the key is not swept. */
static double swept_max_abs(const rs_sweep *s, const char *key)
{
  for (int a = 0; a < s->naxes; a++) {
    if (strcmp(s->axes[a].key, key)) continue;
    double max_abs = 0.0;
    for (int k = 0; k < s->axes[a].n; k++) max_abs = fmax(max_abs, fabs(s->axes[a].values[k]));
    return max_abs;
  }
  return -1.0;
}

/* The lateral creepage eta of a 3D case (a percentage only: its saturation scale is not
 * Carter's mu a/R). */
static int warn_lateral(const rs_case *c, const rs_sweep *s, FILE *err)
{
  if (c->dimension != 3 || c->force_control || c->rig.on) return 0;
  const double swept = s ? swept_max_abs(s, "rolling.lateral_creepage") : -1.0;
  return swept >= 0.0 ? warn_percent(swept, "eta", "sweep: rolling.lateral_creepage", err)
                      : warn_percent(history_max_abs(c, &c->lateral_creepage), "eta",
                                     "rolling.lateral_creepage", err);
}

/* The case's creepages, or the swept values of a sweep `s` (NULL: none) where it sweeps one. */
static int warn_inputs(const rs_case *c, const rs_sweep *s, FILE *err)
{
  const int soft = warn_softening(c, err);
  if (c->force_control) return soft;
  const double swept = s ? swept_max_abs(s, "rolling.creepage") : -1.0;
  return soft + warn_lateral(c, s, err) +
         (swept >= 0.0
              ? rs_warn_creepage(c, swept, "sweep: rolling.creepage", err)
              : rs_warn_creepage(c, history_max_abs(c, &c->creepage),
                                 c->rig.on ? "the twin-disc slip" : "rolling.creepage", err));
}

int rs_warn_case(const rs_case *c, FILE *err) { return warn_inputs(c, NULL, err); }

int rs_warn_sweep(const rs_case *base, const rs_sweep *s, FILE *err)
{
  return warn_inputs(base, s, err);
}

void rs_cost_watch_init(rs_cost_watch *w, const rs_case *c, int cells, double t0, double started)
{
  *w = (rs_cost_watch){.c = c, .cells = cells, .t0 = t0, .started = started, .done = 0};
}

/* "1 h 05 min", "12 min 30 s", "45 s" */
static void format_duration(double seconds, char *buf, size_t len)
{
  const long s = (long)(seconds + 0.5);
  if (s >= 3600)
    snprintf(buf, len, "%ld h %02ld min", s / 3600, (s % 3600) / 60);
  else if (s >= 60)
    snprintf(buf, len, "%ld min %02ld s", s / 60, s % 60);
  else
    snprintf(buf, len, "%ld s", s);
}

/* The histories whose changes drive the transient (the rig's own protocol aside). */
static int driving_histories(const rs_case *c, const rs_history **h)
{
  int n = 0;
  h[n++] = &c->normal_load;
  h[n++] = &c->velocity;
  h[n++] = &c->shift_velocity;
  if (c->force_control) {
    h[n++] = &c->tangential_force;
    if (c->dimension == 3) h[n++] = &c->tangential_force_y;
  } else {
    h[n++] = &c->creepage;
  }
  if (c->dimension == 3) {
    h[n++] = &c->lateral_creepage;
    h[n++] = &c->spin;
  }
  return n;
}

/* Inputs that do not change with time: the run ends in steady rolling. */
static int constant_inputs(const rs_case *c)
{
  const rs_history *h[8];
  const int n = driving_histories(c, h);
  for (int k = 0; k < n; k++)
    if (!rs_history_is_constant(h[k])) return 0;
  return !c->rig.on && rs_history_eval(&c->velocity, 0.0) > 0.0;
}

/* Inputs that only jump (constant or steps histories, no rig): each jump starts a transient
 * like the start-up. */
static int jumping_inputs(const rs_case *c)
{
  const rs_history *h[8];
  const int n = driving_histories(c, h);
  for (int k = 0; k < n; k++)
    if (!rs_history_is_constant(h[k]) && h[k]->kind != RS_HISTORY_STEPS) return 0;
  return !c->rig.on && rs_history_is_constant(&c->velocity) &&
         rs_history_eval(&c->velocity, 0.0) > 0.0;
}

/* The contact's transit time 2a/V at the start (0 when V = 0). */
static double contact_time(const rs_case *c, double t0)
{
  double a;
  saturation_creepage(c, &a);
  const double V = rs_history_eval(&c->velocity, t0);
  return V > 0.0 ? 2.0 * a / V : 0.0;
}

double rs_cost_decay_time(const rs_case *c, double t0, double rho1, double tmid1, double rho2,
                          double tmid2)
{
  const double prior = (c->dimension == 3 ? RS_COST_DECAY_LENGTHS_3D : RS_COST_DECAY_LENGTHS_2D) *
                       contact_time(c, t0);
  if (!(prior > 0.0) || (!constant_inputs(c) && !jumping_inputs(c))) return INFINITY;
  const double span = tmid2 - tmid1;
  if (!(rho1 > 0.0) || !(rho2 > 0.0) || !(span >= 0.5 * prior)) return prior; /* too short */
  return rho1 > rho2 ? span / log(rho1 / rho2) : INFINITY; /* measured; or no decay seen */
}

/* Steps of a density rho at `from` decaying with time constant tau, over [from, to]. */
static double decayed_steps(double rho, double tau, double from, double to)
{
  if (!(to > from)) return 0.0;
  return isinf(tau) ? rho * (to - from) : rho * tau * -expm1(-(to - from) / tau);
}

double rs_cost_steps_left(const rs_case *c, double t0, double t, double rho, double tau)
{
  double t_end = c->end_time;
  if (constant_inputs(c)) /* settled by RS_COST_SETTLE_LENGTHS contact lengths at the latest */
    t_end = c->mode == RS_MODE_TRANSIENT && c->initial_state == RS_START_STEADY && t0 == 0.0
                ? 0.0
                : fmin(t_end, t0 + RS_COST_SETTLE_LENGTHS * contact_time(c, t0));
  if (!jumping_inputs(c)) return decayed_steps(rho, tau, t, t_end);
  /* each jump after t starts a transient as dense as the present one was at its start (the
   * present density traced back along its decay to the last jump, or the run's start): the
   * segments between jumps */
  const rs_history *h[8];
  const int n = driving_histories(c, h);
  double last = t0; /* the present transient's start */
  for (int k = 0; k < n; k++)
    if (h[k]->kind == RS_HISTORY_STEPS)
      for (size_t j = 0; j < h[k]->n; j++)
        if (h[k]->t[j] > last && h[k]->t[j] <= t) last = h[k]->t[j];
  const double rho_start = isinf(tau) ? rho : rho * exp((t - last) / tau);
  double steps = 0.0, from = t;
  for (;;) {
    double next = t_end; /* the first jump after `from` */
    for (int k = 0; k < n; k++)
      if (h[k]->kind == RS_HISTORY_STEPS)
        for (size_t j = 0; j < h[k]->n; j++)
          if (h[k]->t[j] > from && h[k]->t[j] < next) next = h[k]->t[j];
    steps += decayed_steps(from == t ? rho : rho_start, tau, from, next);
    if (next >= t_end) return steps;
    from = next;
  }
}

/* The projected wall time of the rest of the run from the window (t_a, wall_a, steps_a) to
 * (t, now, steps), its steps (*steps_left; decaying with *tau) and those at the window's
 * density all along (*flat_steps): the window's cost per step times the steps. 0 when there
 * is nothing to project. */
static double projected_rest(rs_cost_watch *w, double t, double now, long steps, double *steps_left,
                             double *flat_steps, double *tau)
{
  const double dt = t - w->t_a, dwall = now - w->wall_a;
  const long dsteps = steps - w->steps_a;
  if (!(dt > 0.0) || dsteps <= 0 || !(dwall > 0.0)) return 0.0;
  const double rho = dsteps / dt, tmid = 0.5 * (t + w->t_a);
  *tau = rs_cost_decay_time(w->c, w->t0, w->rho1, w->tmid1, rho, tmid);
  w->rho1 = rho;
  w->tmid1 = tmid;
  *steps_left = rs_cost_steps_left(w->c, w->t0, t, rho, *tau);
  *flat_steps = rs_cost_steps_left(w->c, w->t0, t, rho, INFINITY);
  return dwall / dsteps * *steps_left; /* at the window's cost per step */
}

int rs_cost_watch_update(rs_cost_watch *w, double t, long steps, double now, FILE *err)
{
  if (w->done) return 0;
  const double elapsed = now - w->started;
  if (w->confirming && elapsed < RS_COST_CONFIRM_SECONDS) return 0;
  if (!w->confirming) {
    if (elapsed < 0.5 * RS_COST_PROBE_SECONDS) return 0;
    if (!w->sampled && elapsed < RS_COST_PROBE_SECONDS) {
      w->sampled = 1;
      w->t_a = t;
      w->wall_a = now;
      w->steps_a = steps;
      return 0;
    }
    if (elapsed < RS_COST_PROBE_SECONDS) return 0;
    if (!w->sampled) { /* the first records came slowly: the window is the whole run so far */
      w->t_a = w->t0;
      w->wall_a = w->started;
      w->steps_a = 0;
    }
  }
  const double dt = t - w->t_a, dwall = now - w->wall_a;
  const long dsteps = steps - w->steps_a;
  double steps_left = 0.0, flat_steps = 0.0, tau = INFINITY;
  const double remaining = projected_rest(w, t, now, steps, &steps_left, &flat_steps, &tau);
  if (remaining < RS_COST_WARN_SECONDS) {
    w->done = 1;
    return 0;
  }
  if (!w->confirming) {
    /* the second window starts where the first ended, and lasts at least one record */
    w->confirming = 1;
    w->t_a = t;
    w->wall_a = now;
    w->steps_a = steps;
    return 0;
  }
  w->done = 1;
  const rs_case *c = w->c;
  const int constant = constant_inputs(c);
  const double cost = dwall / dsteps;
  char eta[64], flat[160] = "";
  format_duration(remaining, eta, sizeof eta);
  if (!isinf(tau)) {
    char flat_eta[32];
    format_duration(cost * flat_steps, flat_eta, sizeof flat_eta);
    snprintf(flat, sizeof flat, "; %.3g steps, %s, if they stayed as dense", flat_steps, flat_eta);
  }
  char how[160];
  if (isinf(tau))
    snprintf(how, sizeof how, "at this density %s", constant ? "until it settles" : "to the end");
  else
    snprintf(how, sizeof how, "the steps thinning out by e every %.3g contact lengths 2a/V%s",
             tau / contact_time(c, w->t0),
             jumping_inputs(c) && !constant ? " after each input step" : "");
  fprintf(err,
          "rollsim: warning: a long transient: at t = %.6g s of %.6g s, after %ld IDA steps "
          "in %.1f s, the last %ld steps (%.3g ms each, %d cells) covered %.3g s: %s about "
          "%.3g steps (%s%s), ETA %s (%.0f s).\n",
          t, c->end_time, steps, elapsed, dsteps, 1e3 * cost, w->cells, dt,
          constant ? "settling to steady rolling needs" : "the rest needs", steps_left, how, flat,
          eta, remaining);
  if (constant)
    fprintf(err, "rollsim: hint: the inputs are constant, so the run ends in steady rolling: "
                 "simulation.mode: steady (--set simulation.mode=steady) computes that state "
                 "directly, in well under a second.\n");
  else
    fprintf(err, "rollsim: hint: fewer cells (grid.cells), a shorter simulation.end_time or "
                 "rolled_distance, or a larger solver.rtol make it cheaper.\n");
  fflush(err);
  return 1;
}
