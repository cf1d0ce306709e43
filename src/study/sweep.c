/* rollsim sweep (study/sweep.h): every combination of the swept values, one
 * netCDF file. Steady points continue from the solution of the previous point
 * along the last axis (the creepage of a creep-force curve), which keeps Newton
 * within reach of the active set. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "physics/elastic3d.h"
#include "physics/model.h"
#include "io/output.h"
#include "solve/steady.h"
#include "study/sweep.h"
#include "base/util.h"
#include "study/sweep_fields.h"
#include "study/sweep_lines.h"

static void fill_point(rs_sweep_point *pt, const rs_diag *d)
{
  pt->Fx = d->Fx;
  pt->Fn = d->Fn;
  pt->creepage = d->creepage;
  pt->Fy = d->Fy;
  pt->Mz = d->Mz;
  pt->lateral_creepage = d->lateral_creepage;
  pt->spin = d->spin;
  pt->velocity = d->velocity;
  pt->n_exterior = d->count[RS_EXTERIOR];
  pt->n_adhesion = d->count[RS_ADHESION];
  pt->n_slip = d->count[RS_SLIP];
  pt->n_plastic = d->count[RS_PLASTIC];
  pt->frictional_power = d->frictional_power;
  pt->plastic_power = d->plastic_power;
  pt->elastic_energy = d->elastic_energy;
  pt->converged = 1;
}

/* Steady points along the last axis share one model and one solver when that axis
 * is a rolling input (a creep-force curve): grid, coefficients, normal solution and
 * the solver's allocations are kept, and each point starts from the last solution. */
typedef struct steady_chain {
  SUNContext ctx; /* the sweep's (not owned) */
  rs_model m;
  int have_model;
  rs_steady *st;
  rs_work w;
  double *yp;
  long jac_now; /* Jacobian evaluations of the current solver (it counts from its creation) */
  double *yprev, *ylast; /* solutions of the last two points on this chain (secant predictor) */
  double xprev, xlast;   /* their values of the swept input */
  signed char *reg_last, *reg_new; /* regimes of the last solution and of a new one */
  int nsolved;                     /* points solved on this chain */
  int changed_last;                /* cells whose regime changed over the last step */
  long jac_evals;                  /* of solvers already freed */
  long refined;                    /* continuation steps halved (regime jump or failure) */
  long midpoints;                  /* approximate midpoints tried (SUBSTEP_CELLS) */
  rs_diag diag;                    /* the point's results, from regimes_of at the last solution */
  int have_diag;                   /* diag is of the solution in hand */
} steady_chain;

static void chain_drop(steady_chain *ch)
{
  ch->jac_evals += ch->jac_now;
  ch->jac_now = 0;
  rs_steady_free(ch->st);
  ch->st = NULL;
  rs_work_free(&ch->w);
  free(ch->yp);
  free(ch->yprev);
  free(ch->ylast);
  free(ch->reg_last);
  free(ch->reg_new);
  ch->yp = ch->yprev = ch->ylast = NULL;
  ch->reg_last = ch->reg_new = NULL;
  ch->nsolved = 0;
  ch->changed_last = 0;
  if (ch->have_model) rs_model_free(&ch->m);
  ch->have_model = 0;
}

/* Keys whose change leaves everything but the rolling inputs of the model unchanged. */
static int rolling_key(const char *key)
{
  return !strcmp(key, "rolling.creepage") || !strcmp(key, "rolling.velocity") ||
         !strcmp(key, "rolling.shift_velocity") || !strcmp(key, "rolling.lateral_creepage") ||
         !strcmp(key, "rolling.spin");
}

/* The model's rolling input `key` held at x (an intermediate continuation point). */
static void set_rolling_value(rs_model *m, const char *key, double x)
{
  rs_history *h = !strcmp(key, "rolling.creepage")           ? &m->par.creepage
                  : !strcmp(key, "rolling.velocity")         ? &m->par.velocity
                  : !strcmp(key, "rolling.lateral_creepage") ? &m->par.lateral_creepage
                  : !strcmp(key, "rolling.spin")             ? &m->par.spin
                                                             : &m->par.shift_velocity;
  rs_history_free(h);
  *h = (rs_history){.kind = RS_HISTORY_CONSTANT, .value = x};
}

/* Continuation step refinement: a step whose solution changes the regime of more
 * than max(JUMP_MIN_CELLS, n/JUMP_FRACTION) cells, or fails, is halved (at most
 * MAX_HALVINGS times in a row), so that Newton follows the path of solutions instead
 * of leaping across a change of the active set to another zero of the residual.
 * Measured on cases/creep_curves.yaml (41 points, 100 cells): up to 16 cells change
 * per step along the physical path, 1-3 in most steps. */
enum { JUMP_MIN_CELLS = 4, JUMP_FRACTION = 10, MAX_HALVINGS = 3 };

/* Where the steady state is unique the jump test only costs time: a 3D model with
 * Coulomb friction, elastic or plastic without softening (k_tau >= 0). Any step there
 * lands on the solution the halved path reaches (bench/cases/hertz3d_curve.yaml at 44 x
 * 44 cells, sweeps of 2, 4 or 7 points against 61 along the same line: F_x, F_y, M_z
 * within 3.5e-9 N / N mm and the same regime counts at every point, elastic, k_rel = 0
 * and 0.3, and a spin sweep), and the halving made 4-point sweeps 3-6 times slower than
 * without it (plastic k_rel = 0.3: 321 -> 69 Newton iterations, 1.95 -> 0.36 s). Softening
 * and velocity-dependent friction have several steady states (softening, k_rel = -0.3:
 * F_x = 848.4 N or 902.2 N at xi = -0.4 %, by the path), so the test stays there, as in
 * 2D, where it was introduced and costs little. */
static int unique_steady(int dimension, const rs_friction *friction, int plastic, double k_tau)
{
  return dimension == 3 && !rs_friction_varies(friction) && (!plastic || k_tau >= 0.0);
}
static int halve_jumps(const rs_model *m)
{
  return !unique_steady(m->el.dim, &m->par.friction, m->par.plasticity.on, m->par.plasticity.k_tau);
}

/* The regimes of a solution y (and its results, kept in ch->diag). */
static int regimes_of(steady_chain *ch, const double *y, signed char *reg)
{
  rs_inputs in;
  rs_model_inputs_at(&ch->m, 0.0, &in);
  const rs_work *we = ch->st ? rs_steady_evaluated(ch->st, y) : NULL;
  int status = RS_OK;
  if (we) /* the solver's last residual was evaluated at y */
    rs_model_diagnostics_of(&ch->m, we, &in, y, &ch->diag, NULL, NULL, reg);
  else
    status = rs_model_diagnostics(&ch->m, &ch->w, &in, y, ch->yp, &ch->diag, NULL, NULL, reg);
  ch->have_diag = status == RS_OK;
  return status;
}

/* Plastic models where the steady state is unique: a step over which more than
 * SUBSTEP_CELLS cells changed regime is followed by one with an approximate solution at
 * its midpoint (rs_steady_approximate to SUBSTEP_TOL, at most SUBSTEP_ITERS Newton
 * iterations), the next secant predictor's base. The plastic Newton iterations per point
 * grow with the cells that change regime in a step (the line search cuts the steps while
 * the active set of the plastic unknowns is searched): along the 30-point plastic creep
 * curve of bench/cases, at most 104 cells per step and 4-8 iterations per point at 44 x 44
 * cells, 130-870 and up to 31 iterations at 128 x 128; with the midpoints there 462 -> 359
 * Newton iterations (two threads), 19.6 -> 13.2 s, and every point the same to 2e-12 of the
 * forces. Measured thresholds (128 x 128, two threads): every step 376 iterations, 200 cells
 * 359, 400 cells 359; up to three intermediate points (one per 150 / 400 cells): 454 / 375;
 * midpoint tolerance 1e-1 / 3e-2 / 1e-2 / 3e-3: 444 / 361 / 359 / 363. Elastic models take
 * such steps whole: the elastic curve at 128 x 128 took 204 Newton iterations without
 * midpoints and 280 with them (16.3 against 19.6 s). Measured again with the solver of
 * 2026-11-27 (Newton / GMRES iterations, the same curve): midpoint tolerance 1e-2 / 2e-2 /
 * 3e-2 / 5e-2 / 7e-2 / 1e-1 at 128 x 128 cells, one thread, 317 / 314 / 307 / 303 / 322 / 379
 * Newton (2116 / 2098 / 2046 / 2004 / 2214 GMRES); two threads 1e-2 / 2e-2 / 3e-2 / 5e-2 346 /
 * 342 / 338 / 331 (2285 / 2271 / 2237 / 2182); 100 x 100 1e-2 / 3e-2 / 5e-2 274 / 273 / 278
 * (1733 / 1705 / 1729), 88 x 88 263 / 262 / 260; 3e-2 for a margin from the rise above 5e-2.
 * Without midpoints 402 Newton iterations at 128 x 128 (one thread); at most 3 or 4 Newton
 * iterations per midpoint 453 / 459. */
enum { SUBSTEP_CELLS = 400, SUBSTEP_ITERS = 15 };
#define SUBSTEP_TOL 3e-2

/* The secant predictor y + (y - y_prev)(x - x_last)/(x_last - x_prev) from the last two
 * solutions on the chain (the tractions follow the input piecewise linearly between
 * changes of the active set). */
static void secant(const steady_chain *ch, double x, double *y)
{
  if (ch->nsolved < 2 || ch->xlast == ch->xprev) return;
  const double f = (x - ch->xlast) / (ch->xlast - ch->xprev);
  for (int i = 0; i < ch->m.lay.neq; i++) y[i] += f * (ch->ylast[i] - ch->yprev[i]);
}

/* The chain's last two solutions become (last, y at x). */
static void chain_push(steady_chain *ch, double x, const double *y)
{
  const size_t bytes = (size_t)ch->m.lay.neq * sizeof *y;
  memcpy(ch->yprev, ch->ylast, bytes);
  memcpy(ch->ylast, y, bytes);
  ch->xprev = ch->xlast;
  ch->xlast = x;
  ch->nsolved++;
}

/* From the last solution on the chain (in y on entry) to the swept input at x: the
 * midpoint first after a large change of the active set (SUBSTEP_CELLS), the secant
 * predictor, Newton, and the step halved where the regimes jump. On success y and the
 * chain hold the solution at x. */
static int continue_to(steady_chain *ch, const char *key, double x, double *y, int depth,
                       rs_stats *stats, rs_msg *msg)
{
  const int neq = ch->m.lay.neq, n = ch->m.grid.n;
  if (depth == 0 && !halve_jumps(&ch->m) && ch->m.par.plasticity.on && ch->nsolved >= 1 &&
      ch->changed_last > SUBSTEP_CELLS) {
    const double xmid = 0.5 * (ch->xlast + x);
    set_rolling_value(&ch->m, key, xmid);
    secant(ch, xmid, y);
    ch->midpoints++;
    if (rs_steady_approximate(ch->st, 0.0, y, SUBSTEP_TOL, SUBSTEP_ITERS, stats) == RS_OK)
      chain_push(ch, xmid, y); /* the regimes stay those of the last solution */
    else
      memcpy(y, ch->ylast, (size_t)neq * sizeof *y);
  }
  set_rolling_value(&ch->m, key, x);
  secant(ch, x, y);
  int status = rs_steady_solve(ch->st, 0.0, y, stats, msg);
  int changed = 0;
  if (status == RS_OK && (status = regimes_of(ch, y, ch->reg_new)) == RS_OK)
    for (int i = 0; i < n; i++) changed += ch->reg_new[i] != ch->reg_last[i];
  const int jump =
      halve_jumps(&ch->m) &&
      changed > (n / JUMP_FRACTION > JUMP_MIN_CELLS ? n / JUMP_FRACTION : JUMP_MIN_CELLS);
  if ((status == RS_ERR_SOLVER || (status == RS_OK && jump)) && depth < MAX_HALVINGS) {
    ch->refined++;
    const double xmid = 0.5 * (ch->xlast + x);
    memcpy(y, ch->ylast, (size_t)neq * sizeof *y);
    status = continue_to(ch, key, xmid, y, depth + 1, stats, msg);
    if (status == RS_OK) status = continue_to(ch, key, x, y, depth + 1, stats, msg);
    return status;
  }
  if (status != RS_OK) return status;
  chain_push(ch, x, y);
  memcpy(ch->reg_last, ch->reg_new, (size_t)n);
  ch->changed_last = changed;
  return RS_OK;
}

/* One steady point, warm-started from y (length neq of this grid) when warm; the
 * model and solver of the previous point are reused (continuation in the rolling
 * input `key`) when reuse. */
static int steady_point(const rs_case *c, steady_chain *ch, double **y, int *ny, int warm,
                        int reuse, const char *key, double x, rs_diag *d, rs_fields *f,
                        rs_stats *sum, rs_msg *msg)
{
  int status = RS_OK;
  const int chained =
      reuse && warm && ch->have_model && ch->st && ch->nsolved >= 1 && *ny == ch->m.lay.neq;
  if (!chained) {
    chain_drop(ch);
    status = rs_model_from_case(&ch->m, c, msg);
    if (status != RS_OK) return status;
    ch->have_model = 1;
    const size_t neq = (size_t)ch->m.lay.neq, n = (size_t)ch->m.grid.n;
    ch->yp = calloc(neq, sizeof *ch->yp);
    ch->yprev = calloc(neq, sizeof *ch->yprev);
    ch->ylast = calloc(neq, sizeof *ch->ylast);
    ch->reg_last = calloc(n, 1);
    ch->reg_new = calloc(n, 1);
    if (!ch->yp || !ch->yprev || !ch->ylast || !ch->reg_last || !ch->reg_new ||
        rs_work_create(&ch->w, &ch->m) != RS_OK)
      status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
    if (status == RS_OK) status = rs_steady_create(&ch->st, &ch->m, ch->ctx, msg);
  }
  if (status == RS_OK && (!warm || *ny != ch->m.lay.neq)) {
    free(*y);
    *y = calloc((size_t)ch->m.lay.neq, sizeof **y);
    *ny = ch->m.lay.neq;
    if (!*y)
      status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
    else
      rs_model_rest_state(&ch->m, *y);
  }
  rs_stats stats = {0};
  ch->have_diag = 0;
  if (status == RS_OK && chained) {
    status = continue_to(ch, key, x, *y, 0, &stats, msg);
  } else if (status == RS_OK) {
    status = rs_steady_solve(ch->st, 0.0, *y, &stats, msg);
    if (status == RS_OK) status = regimes_of(ch, *y, ch->reg_last);
    if (status == RS_OK) {
      memcpy(ch->ylast, *y, (size_t)ch->m.lay.neq * sizeof **y);
      ch->xlast = x;
      ch->nsolved = reuse ? 1 : 0; /* a chain starts only along a rolling input */
    }
  }
  /* the point's profiles (output.fields; 2D sweep files) */
  const int keep = f && f->n == ch->m.grid.n && ch->m.lay.ncomp == 1;
  if (status == RS_OK && !keep && ch->have_diag) { /* regimes_of evaluated the solution */
    *d = ch->diag;
  } else if (status == RS_OK) {
    rs_inputs in;
    rs_model_inputs_at(&ch->m, 0.0, &in);
    status = rs_model_diagnostics(&ch->m, &ch->w, &in, *y, ch->yp, d, keep ? f->slip : NULL,
                                  keep ? f->tauc : NULL, keep ? f->regime : NULL);
  }
  if (status == RS_OK && keep) {
    const rs_layout *L = &ch->m.lay;
    const size_t bytes = (size_t)ch->m.grid.n * sizeof(double);
    memcpy(f->px, *y + rs_at_p(L, 0, 0), bytes);
    memcpy(f->upl, *y + rs_at_upl(L, 0, 0), bytes);
    memcpy(f->ustar, *y + rs_at_ustar(L, 0), bytes);
    for (int i = 0; i < ch->m.grid.n; i++) /* each cell's bound g = mu(|v_s|) p_n */
      f->mu[i] = ch->w.pn[i] > 0.0 ? ch->w.law[i].g / ch->w.pn[i] : NAN;
    for (int i = 0; i < ch->m.grid.n && L->memory; i++) /* friction memory: the state */
      f->mu[i] = (*y)[rs_at_mu(L, i)];
    memcpy(f->pn, ch->w.pn, bytes);
  }
  sum->nonlin_iters += stats.nonlin_iters;
  sum->lin_solves += stats.lin_solves;
  sum->refused += stats.refused;
  ch->jac_now = stats.jac_evals;
  if (status != RS_OK) chain_drop(ch); /* no reuse after a failure */
  return status;
}

/* What a sweep's points are written to (rs_sweep_run). */
typedef struct sweep_writer {
  const rs_sweep *s;
  const rs_run_opts *o;
  rs_sweep_output *out;
  rs_sweep_result *res;
  const rs_fields *buf; /* the points' profiles (a common grid), or NULL */
  double started;
  size_t p0;  /* the first point of the line solved by rs_sweep_line_eval */
  rs_msg msg; /* why the line's callback stopped it */
} sweep_writer;

/* Point p solved (ps RS_OK, d its quantities) or failed (RS_ERR_SOLVER, why): written,
 * progress shown, and RS_ERR_INTERRUPTED once the user has interrupted the sweep. */
static int record_point(sweep_writer *w, size_t p, int ps, const rs_diag *d, const char *why,
                        rs_msg *msg)
{
  const rs_sweep *s = w->s;
  rs_sweep_result *res = w->res;
  rs_sweep_point pt;
  memset(&pt, 0, sizeof pt);
  if (ps == RS_OK) {
    fill_point(&pt, d);
    if (w->buf) {
      pt.px = w->buf->px;
      pt.pn = w->buf->pn;
      pt.slip = w->buf->slip;
      pt.upl = w->buf->upl;
      pt.ustar = w->buf->ustar;
      pt.tauc = w->buf->tauc;
      pt.regime = w->buf->regime;
      pt.mu = w->buf->mu;
    }
    res->points_done++;
  } else {
    pt.Fx = pt.Fn = pt.creepage = pt.velocity = NAN;
    pt.Fy = pt.Mz = pt.lateral_creepage = pt.spin = NAN;
    pt.frictional_power = pt.plastic_power = pt.elastic_energy = NAN;
    pt.n_exterior = pt.n_adhesion = pt.n_slip = pt.n_plastic = -1;
    res->points_failed++;
    const rs_sweep_axis *ax = &s->axes[s->naxes - 1];
    fprintf(stderr, "rollsim sweep: point %zu (%s=%.17g): %s\n", p, ax->key,
            ax->values[p % (size_t)ax->n], why);
  }
  int status = rs_sweep_output_write(w->out, p, &pt, msg);
  const size_t done = res->points_done + res->points_failed;
  if (w->o->progress) {
    fprintf(stderr, "\rsweep: %zu/%zu points, %zu failed, %.1f s ", done, s->npoints,
            res->points_failed, rs_wall_clock() - w->started);
    fflush(stderr);
  }
  if (status == RS_OK && w->o->interrupt_flag && *w->o->interrupt_flag)
    status = rs_msg_set(msg, RS_ERR_INTERRUPTED, "interrupted after %zu of %zu points", done,
                        s->npoints);
  return status;
}

static int line_point_written(void *ctx, size_t j, int status, const rs_diag *d, long newton,
                              const char *why)
{
  sweep_writer *w = ctx;
  (void)newton;
  return record_point(w, w->p0 + j, status, d, why, &w->msg);
}

int rs_sweep_run(const rs_sweep *s, const char *case_path, const char *const *sets, int nsets,
                 const rs_run_opts *o, rs_sweep_result *res, rs_msg *msg)
{
  const double started = rs_wall_clock();
  memset(res, 0, sizeof *res);
  rs_case base;
  int status = rs_case_load(&base, case_path, sets, nsets, msg);
  if (status != RS_OK) return status;
  const char *path = o->output_path ? o->output_path : base.output_file;
  snprintf(res->file, sizeof res->file, "%s", path);
  double *grid_x = NULL; /* the common grid of the points' profiles, or NULL */
  int grid_n = 0;
  rs_fields buf = {0};

  const char **keys = calloc((size_t)s->naxes, sizeof *keys);
  int *sizes = calloc((size_t)s->naxes, sizeof *sizes);
  const double **values = calloc((size_t)s->naxes, sizeof *values);
  const char **all = calloc((size_t)(nsets + s->naxes), sizeof *all);
  char(*assign)[256] = calloc((size_t)s->naxes, sizeof *assign);
  if (!keys || !sizes || !values || !all || !assign) {
    status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
    goto done;
  }
  for (int a = 0; a < s->naxes; a++) {
    keys[a] = s->axes[a].key;
    sizes[a] = s->axes[a].n;
    values[a] = s->axes[a].values;
  }
  for (int i = 0; i < nsets; i++) all[i] = sets[i];
  /* Profiles (output.fields) when every point has the base case's grid. */
  const unsigned fields = rs_sweep_profile_fields(&base, 1);
  if (fields) {
    char why[512];
    int common = 0;
    status = rs_sweep_common_grid(s, case_path, sets, nsets, &common, &grid_x, &grid_n, why,
                                  sizeof why, msg);
    if (status != RS_OK) goto done;
    if (!common)
      fprintf(stderr,
              "rollsim sweep: warning: output.fields not stored: %s, and the profiles "
              "of a sweep file share one x axis (output.fields: [] silences this)\n",
              why);
    else if (rs_fields_alloc(&buf, grid_n) != RS_OK) {
      status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
      goto done;
    }
  }
  rs_sweep_output_spec spec = {.path = path,
                               .fields = grid_x ? fields : 0,
                               .nx = (size_t)grid_n,
                               .x = grid_x,
                               .title = base.title,
                               .case_text = base.yaml_text,
                               .history = o->history,
                               .dimension = base.dimension,
                               .naxes = s->naxes,
                               .keys = keys,
                               .sizes = sizes,
                               .values = values};
  rs_sweep_output *out = NULL;
  status = rs_sweep_output_create(&out, &spec, msg);
  if (status != RS_OK) goto done;
  if (rs_sweep_output_backup(out))
    snprintf(res->backup, sizeof res->backup, "%s", rs_sweep_output_backup(out));

  double *y = NULL;
  int ny = 0;
  steady_chain chain = {0};
  if (SUNContext_Create(NULL, &chain.ctx) != 0) {
    status = rs_msg_set(msg, RS_ERR_INTERNAL, "could not create the SUNDIALS context");
    rs_msg tmp;
    rs_sweep_output_close(out, "failed: could not create the SUNDIALS context", &tmp);
    goto done;
  }
  rs_stats steady_sum = {0};
  rs_msg point_msg = {{0}};
  sweep_writer wr = {
      .s = s, .o = o, .out = out, .res = res, .buf = grid_x ? &buf : NULL, .started = started};
  const rs_sweep_axis *last = &s->axes[s->naxes - 1];
  long line_refined = 0, line_midpoints = 0;
  for (size_t p = 0; p < s->npoints && status == RS_OK; p++) {
    size_t rest = p;
    int last_index = 0;
    for (int a = s->naxes - 1; a >= 0; a--) {
      const int k = (int)(rest % (size_t)s->axes[a].n);
      rest /= (size_t)s->axes[a].n;
      if (a == s->naxes - 1) last_index = k;
      snprintf(assign[a], sizeof assign[a], "%s=%.17g", s->axes[a].key, s->axes[a].values[k]);
      all[nsets + a] = assign[a];
    }
    rs_case c;
    rs_diag d;
    int ps = rs_case_load(&c, case_path, all, nsets + s->naxes, &point_msg);
    const int in_two = ps == RS_OK && rs_sweep_line_in_two(&c, last->key, (size_t)last->n);
    if (ps == RS_OK && last_index == 0 && !grid_x &&
        (in_two || rs_sweep_line_far_first(&c, last->key, (size_t)last->n))) {
      /* the whole line at once: in two parts (solver.threads: 2), or far first */
      rs_case_free(&c);
      wr.p0 = p;
      wr.msg.text[0] = '\0';
      const rs_sweep_line line = {.case_path = case_path,
                                  .sets = all,
                                  .nsets = nsets + s->naxes - 1,
                                  .key = last->key,
                                  .values = last->values,
                                  .n = (size_t)last->n,
                                  .point_done = line_point_written,
                                  .ctx = &wr,
                                  .interrupt_flag = o->interrupt_flag,
                                  .stats = &steady_sum,
                                  .refined = &line_refined,
                                  .midpoints = &line_midpoints,
                                  .in_two = &res->lines_in_two,
                                  .in_two_known = in_two};
      status = rs_sweep_line_eval(&line, &point_msg);
      if (status != RS_OK)
        rs_msg_set(msg, status, "%s", wr.msg.text[0] ? wr.msg.text : point_msg.text);
      p += (size_t)last->n - 1;
      continue;
    }
    if (ps == RS_OK) {
      if (c.mode == RS_MODE_STEADY) {
        ps = steady_point(&c, &chain, &y, &ny, last_index > 0, rolling_key(last->key), last->key,
                          last->values[last_index], &d, grid_x ? &buf : NULL, &steady_sum,
                          &point_msg);
      } else {
        rs_run_opts po = *o;
        po.no_output = 1;
        po.progress = 0;
        po.cost_warning = 0;
        po.final_fields = grid_x ? &buf : NULL;
        rs_run_result rr;
        ps = rs_run(&c, &po, &rr, &point_msg);
        d = rr.final;
        res->newton_iters += rr.stats.nonlin_iters;
        rs_run_result_free(&rr);
      }
      rs_case_free(&c);
    }
    if (ps != RS_OK && ps != RS_ERR_SOLVER) {
      status = rs_msg_set(msg, ps, "sweep point %zu: %s", p, point_msg.text);
      break;
    }
    if (ps == RS_ERR_SOLVER) {
      free(y); /* no warm start from a failed point */
      y = NULL;
      ny = 0;
    }
    status = record_point(&wr, p, ps, &d, point_msg.text, msg);
  }
  if (o->progress) fputc('\n', stderr);
  chain_drop(&chain);
  SUNContext_Free(&chain.ctx);
  res->newton_iters += steady_sum.nonlin_iters;
  res->lin_solves = steady_sum.lin_solves;
  res->jac_evals = chain.jac_evals + steady_sum.jac_evals; /* the latter: lines' */
  res->refused = steady_sum.refused;
  res->refined = chain.refined + line_refined;
  res->midpoints = chain.midpoints + line_midpoints;
  free(y);
  if (status == RS_OK && res->points_failed > 0)
    status =
        rs_msg_set(msg, RS_ERR_SOLVER, "%zu of %zu sweep points did not converge (NaN in the file)",
                   res->points_failed, s->npoints);
  char why[RS_MSG_LEN + 16];
  snprintf(why, sizeof why, "%s%s",
           status == RS_OK                ? "complete"
           : status == RS_ERR_INTERRUPTED ? "interrupted"
                                          : "failed: ",
           status == RS_OK || status == RS_ERR_INTERRUPTED ? "" : msg->text);
  rs_msg tmp;
  int cs = rs_sweep_output_close(out, why, status == RS_OK ? msg : &tmp);
  if (status == RS_OK) status = cs;
done:
  res->wall_seconds = rs_wall_clock() - started;
  free(grid_x);
  rs_fields_free(&buf);
  free(keys);
  free(sizes);
  free(values);
  free(all);
  free(assign);
  rs_case_free(&base);
  return status;
}

/* The case of point j of the line (its key at values[j]); all holds the line's sets and
 * one more entry. */
static int line_case(const rs_sweep_line *line, const char **all, char *assign, size_t len,
                     size_t j, rs_case *c, rs_msg *msg)
{
  snprintf(assign, len, "%s=%.17g", line->key, line->values[j]);
  all[line->nsets] = assign;
  return rs_case_load(c, line->case_path, all, line->nsets + 1, msg);
}

/* Point j of the line on the chain ch (warm: continued from *y); one_thread: the point's
 * solver on one thread. Returns the point's status (RS_OK, or RS_ERR_SOLVER with why in
 * pmsg; then no warm start from it) or an input or internal error's. */
static int line_point(const rs_sweep_line *line, steady_chain *ch, const char **all, double **y,
                      int *ny, size_t j, int warm, int one_thread, rs_stats *sum, rs_diag *d,
                      long *newton, rs_msg *pmsg)
{
  char assign[320];
  rs_case c;
  *newton = 0;
  int ps = line_case(line, all, assign, sizeof assign, j, &c, pmsg);
  if (ps != RS_OK) return ps;
  if (one_thread) c.threads = 1;
  if (c.mode == RS_MODE_STEADY) {
    const long before = sum->nonlin_iters;
    ps = steady_point(&c, ch, y, ny, warm, rolling_key(line->key), line->key, line->values[j], d,
                      line->fields, sum, pmsg);
    *newton = sum->nonlin_iters - before;
  } else {
    rs_run_opts po = {
        .no_output = 1, .final_fields = line->fields, .interrupt_flag = line->interrupt_flag};
    rs_run_result rr;
    ps = rs_run(&c, &po, &rr, pmsg);
    *d = rr.final;
    *newton = rr.stats.nonlin_iters;
    rs_run_result_free(&rr);
  }
  rs_case_free(&c);
  if (ps == RS_ERR_SOLVER) { /* no warm start from a failed point */
    free(*y);
    *y = NULL;
    *ny = 0;
  }
  return ps;
}

static void line_totals(const rs_sweep_line *line, const rs_stats *sum, const steady_chain *ch)
{
  if (line->stats) {
    line->stats->nonlin_iters += sum->nonlin_iters;
    line->stats->lin_solves += sum->lin_solves;
    line->stats->refused += sum->refused;
    line->stats->jac_evals += ch->jac_evals + ch->jac_now;
  }
  if (line->refined) *line->refined += ch->refined;
  if (line->midpoints) *line->midpoints += ch->midpoints;
}

/* A line of steady points along a rolling input where the steady state is unique. */
static int unique_line(const rs_case *c, const char *key, size_t n)
{
  return n >= 2 && c->mode == RS_MODE_STEADY && rolling_key(key) &&
         unique_steady(c->dimension, &c->friction, c->has_plasticity, c->k_tau);
}

int rs_sweep_line_far_first(const rs_case *c, const char *key, size_t n)
{
  return unique_line(c, key, n) && c->has_plasticity;
}

int rs_sweep_line_in_two(const rs_case *c, const char *key, size_t n)
{
#ifdef _OPENMP
  return unique_line(c, key, n) && rs_threads(c->threads) == 2;
#else
  (void)c;
  (void)key;
  (void)n;
  return 0;
#endif
}

/* The k-th point of a line solved from its end with the larger |value| (far first). */
static size_t far_first_point(const rs_sweep_line *line, size_t k)
{
  const size_t n = line->n;
  return fabs(line->values[n - 1]) < fabs(line->values[0]) ? k : n - 1 - k;
}

#ifdef _OPENMP
/* A line solved in two parts: its points ordered from the end with the smaller |value|
 * (a creep curve's rest end, whichever way the sweep runs) to the other, the first
 * IN_TWO_SMALL of them in that order go to worker 0, the rest to worker 1, and each
 * worker solves its part from its larger |value| back (its first point from rest). A fixed
 * split, so that a sweep's file does not depend on the threads' timing. Measured on the
 * 30-point creep curves of bench/cases (2-core VM, single runs):
 * - partial slip costs more than saturation, and more so on fine grids: the first 12
 *   points at 128 x 128 cells (plastic) forward 310 Newton iterations, 23.6 s; the last 18
 *   back from the end 249, 16.9 s (the two as processes side by side: 23.7 / 18.1 s);
 * - plastic continuation towards smaller creepage takes fewer iterations: the first 12
 *   points at 128^2 back 241 (20.9 s), the whole 44^2 curve back 172 against 193 (the
 *   elastic 44^2 curve 165 against 152);
 * - with two threads (worker 0 forward from the first point / back towards it, split at):
 *   plastic 44^2 forward 0.35 / 0.4 / 0.45 / 0.5: 0.65 / 0.68 / 0.74 / 0.78 s, back 0.64 /
 *   0.67 / 0.73 / 0.79 s; elastic 44^2 forward 0.59 / 0.57 / 0.52 / 0.56 s, back 0.58 /
 *   0.54 / 0.56 / 0.61 s; plastic 128^2 forward 0.3 / 0.35 / 0.4: 20.3 / 21.5 / 23.7 s, back
 *   0.35 / 0.4: 20.0 / 21.6 s.
 * Measured again after the solver's speed-ups of 2026-11-27 (each worker's CPU time summed
 * over its points, so that the machine's changes of speed cancel in the ratio): split at
 * 0.35 worker 1 took 1.04-1.17 times worker 0's time on the plastic 44^2 curve and
 * 1.27-1.39 on the elastic one, at 0.4 0.95-1.02 and 0.95-1.10, at 0.45 0.77-0.84
 * (plastic); the same Newton and GMRES totals. Paired wall times 0.4 against 0.35: plastic
 * 44^2 0.999 (median of 15, noise), plastic 128^2 0.932 (median of 5; 346 against 364 Newton
 * iterations). */
#define IN_TWO_SMALL 0.40
static size_t in_two_split(size_t n)
{
  const size_t k = (size_t)floor(IN_TWO_SMALL * (double)n + 0.5);
  return k < 1 ? 1 : k >= n ? n - 1 : k;
}

/* The line in two parts (in_two_split): each worker continues from its own last
 * solution on one thread. Where the steady state is unique (rs_sweep_line_in_two) a
 * point does not depend on the path to it beyond Newton's tolerance. */
static int line_in_two(const rs_sweep_line *line, rs_msg *msg)
{
  rs_elastic3d_planner_thread_safe(); /* each worker creates models and coarse grids */
  const size_t n = line->n, split = in_two_split(n);
  /* point k in the order from the smaller |value| end (far_first_point(line, n - 1 - k)):
   * worker 0 takes split - 1 down to 0, worker 1 n - 1 down to split */
  size_t next[2] = {split, n};
  int status = RS_OK;
#pragma omp parallel num_threads(2)
  {
    const int w = omp_get_thread_num();
    steady_chain ch = {0};
    rs_stats sum = {0};
    const char **all = calloc((size_t)line->nsets + 1, sizeof *all);
    int mine = all && SUNContext_Create(NULL, &ch.ctx) == 0 ? RS_OK : RS_ERR_INTERNAL;
    for (int i = 0; all && i < line->nsets; i++) all[i] = line->sets[i];
    double *y = NULL;
    int ny = 0, warm = 0;
    for (;;) {
      size_t j = 0;
      int take = 0;
#pragma omp critical(rs_sweep_line)
      {
        if (mine != RS_OK && status == RS_OK)
          status = rs_msg_set(msg, mine, "out of memory (sweep line in two parts)");
        if (status == RS_OK && next[w] > (w == 0 ? 0 : split)) {
          const size_t k = --next[w];
          j = far_first_point(line, n - 1 - k);
          take = 1;
        }
      }
      if (!take) break;
      rs_diag d;
      long newton = 0;
      rs_msg pm = {{0}};
      const int ps = line_point(line, &ch, all, &y, &ny, j, warm, 1, &sum, &d, &newton, &pm);
      warm = 1;
#pragma omp critical(rs_sweep_line)
      {
        int st = ps;
        if (ps == RS_OK || ps == RS_ERR_SOLVER)
          st = line->point_done(line->ctx, j, ps, &d, newton, pm.text);
        else if (status == RS_OK)
          rs_msg_set(msg, ps, "%s=%.17g: %s", line->key, line->values[j], pm.text);
        if (st != RS_OK && status == RS_OK) status = st;
      }
    }
#pragma omp critical(rs_sweep_line)
    line_totals(line, &sum, &ch);
    chain_drop(&ch);
    if (ch.ctx) SUNContext_Free(&ch.ctx);
    free(y);
    free(all);
  }
  if (line->in_two) (*line->in_two)++;
  return status;
}
#endif

/* One continuation line in memory (study/sweep_lines.h): the points of rs_sweep_run's loop
 * along its last axis, with the same models, warm starts and continuation. */
int rs_sweep_line_eval(const rs_sweep_line *line, rs_msg *msg)
{
#ifdef _OPENMP
  if (line->in_two_known) return line_in_two(line, msg);
#endif
  const char **all = calloc((size_t)line->nsets + 1, sizeof *all);
  if (!all) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  for (int i = 0; i < line->nsets; i++) all[i] = line->sets[i];
  int far = 0;
  if (line->n >= 2 && !line->fields) { /* 3D sweeps store no profiles */
    char assign[320];
    rs_case c;
    rs_msg cm = {{0}};
    if (line_case(line, all, assign, sizeof assign, 0, &c, &cm) == RS_OK) {
      far = rs_sweep_line_far_first(&c, line->key, line->n);
      const int in_two = rs_sweep_line_in_two(&c, line->key, line->n); /* 0 without OpenMP */
      rs_case_free(&c);
#ifdef _OPENMP
      if (in_two) {
        free(all);
        return line_in_two(line, msg);
      }
#else
      (void)in_two;
#endif
    }
  }
  steady_chain chain = {0};
  if (SUNContext_Create(NULL, &chain.ctx) != 0) {
    free(all);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "could not create the SUNDIALS context");
  }
  double *y = NULL;
  int ny = 0, status = RS_OK;
  rs_stats sum = {0};
  for (size_t k = 0; k < line->n && status == RS_OK; k++) {
    const size_t j = far ? far_first_point(line, k) : k;
    rs_diag d;
    long newton = 0;
    rs_msg pm = {{0}};
    const int ps = line_point(line, &chain, all, &y, &ny, j, k > 0, 0, &sum, &d, &newton, &pm);
    if (ps == RS_OK || ps == RS_ERR_SOLVER)
      status = line->point_done(line->ctx, j, ps, &d, newton, pm.text);
    else
      status = rs_msg_set(msg, ps, "%s=%.17g: %s", line->key, line->values[j], pm.text);
  }
  line_totals(line, &sum, &chain);
  chain_drop(&chain);
  SUNContext_Free(&chain.ctx);
  free(y);
  free(all);
  return status;
}
