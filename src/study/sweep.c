/* Continuation lines of sweep points (study/sweep_lines.h): the points along a sweep's last
 * axis, each a case derived from the loaded one, solved in memory. Steady points continue
 * from the solution of the previous point along the last axis (the creepage of a
 * creep-force curve), which keeps Newton within reach of the active set. The driver over
 * the lines and the sweep file is study/sweep_dist.c. */
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
#include "study/errest.h"
#include "study/sweep.h"
#include "base/util.h"
#include "study/sweep_fields.h"
#include "study/sweep_lines.h"
#include "study/temperature.h"

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
  rs_errest est;                   /* the error estimate's companion grids of m */
  int est_tried;                   /* est built, or m found too coarse for it */
  rs_temperature_run temp;         /* mu(T), tau_c0(T): the coupling's temperatures (temp.T_used) */
} steady_chain;

static void chain_drop(steady_chain *ch)
{
  ch->jac_evals += ch->jac_now;
  ch->jac_now = 0;
  rs_steady_free(ch->st);
  ch->st = NULL;
  rs_temperature_run_free(&ch->temp);
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
  rs_errest_free(&ch->est);
  ch->est_tried = 0;
  if (ch->have_model) rs_model_free(&ch->m);
  ch->have_model = 0;
}

/* The model's rolling input held at x (an intermediate continuation point). */
static void set_rolling_value(rs_model *m, rs_rolling_input which, double x)
{
  rs_history *h = which == RS_ROLLING_CREEPAGE           ? &m->par.creepage
                  : which == RS_ROLLING_VELOCITY         ? &m->par.velocity
                  : which == RS_ROLLING_LATERAL_CREEPAGE ? &m->par.lateral_creepage
                  : which == RS_ROLLING_SPIN             ? &m->par.spin
                                                         : &m->par.shift_velocity;
  rs_history_free(h);
  *h = (rs_history){.kind = RS_HISTORY_CONSTANT, .value = x};
}

/* Continuation step refinement: a step whose solution changes the regime of more
 * than max(JUMP_MIN_CELLS, n/JUMP_FRACTION) cells, or fails, is halved (at most
 * MAX_HALVINGS times in a row), so that Newton follows the path of solutions instead
 * of leaping across a change of the active set to another zero of the residual. Along the
 * physical path only a few cells change regime per step. */
enum { JUMP_MIN_CELLS = 4, JUMP_FRACTION = 10, MAX_HALVINGS = 3 };

/* Where the steady state is unique any step lands on the solution the halved path reaches:
 * a 3D model with Coulomb friction, elastic or plastic without softening (k_tau >= 0).
 * Softening and velocity-dependent friction have several steady states (which one a point
 * reaches depends on the path). */
static int unique_steady(int dimension, const rs_friction *friction, int plastic, double k_tau)
{
  return dimension == 3 && !rs_friction_varies(friction) && (!plastic || k_tau >= 0.0);
}
static int unique_model(const rs_model *m)
{
  return unique_steady(m->el.dim, &m->par.friction, m->par.plasticity.on, m->par.plasticity.k_tau);
}
/* The jump test (halving a step whose solution changed the regime of many cells) stays for
 * velocity-dependent friction and in 2D. In 3D with Coulomb friction it is left out for
 * softening too: a step whose Newton fails, or whose zero the steady check refuses, is halved
 * anyway (continue_to), and a converged step taken whole lands where its halves land. */
static int halve_jumps(const rs_model *m)
{
  return m->el.dim != 3 || rs_friction_varies(&m->par.friction);
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
 * the active set of the plastic unknowns is searched); elastic models take such steps
 * whole, as midpoints cost them more iterations than they save. */
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
static int continue_to(steady_chain *ch, rs_rolling_input key, double x, double *y, int depth,
                       rs_stats *stats, rs_msg *msg)
{
  const int neq = ch->m.lay.neq, n = ch->m.grid.n;
  if (depth == 0 && unique_model(&ch->m) && ch->m.par.plasticity.on && ch->nsolved >= 1 &&
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
  /* 3D, Coulomb friction: a step whose Newton fails, or whose zero is not a physical steady
   * state, is halved before the solver's costly fallbacks (rolling the material from the last
   * solution) are tried, which only the last halving takes; the halves start from the last
   * solution itself, as the secant through the last two led the failed step astray
   * (bench/RESULTS.md, issue 42). */
  const int fast = ch->m.el.dim == 3 && !rs_friction_varies(&ch->m.par.friction);
  if (depth == 0 || !fast) secant(ch, x, y);
  rs_steady_set_fail_fast(ch->st, fast && depth < MAX_HALVINGS ? RS_FAIL_FAST : RS_FAIL_NEVER);
  int status = rs_steady_solve(ch->st, 0.0, y, stats, msg);
  rs_steady_set_fail_fast(ch->st, RS_FAIL_NEVER);
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
 * input `key`) when key is one. */
static int steady_point(const rs_case *c, steady_chain *ch, double **y, int *ny, int warm,
                        rs_rolling_input key, double x, int estimate, rs_diag *d, rs_fields *f,
                        rs_stats *sum, rs_msg *msg)
{
  int status = RS_OK;
  const int reuse = key != RS_ROLLING_NONE;
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
    if (status == RS_OK && rs_temperature_coupled(c))
      status = rs_temperature_run_create(&ch->temp, c, &ch->m, msg);
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
  if (status == RS_OK && ch->temp.T_used) { /* mu(T), tau_c0(T): the coupled steady state */
    status = rs_temperature_couple(&ch->temp, &ch->m, &ch->w, ch->st, *y, &stats, msg);
    if (status == RS_OK) status = regimes_of(ch, *y, ch->reg_last);
    if (status == RS_OK) memcpy(ch->ylast, *y, (size_t)ch->m.lay.neq * sizeof **y);
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
  if (status == RS_OK && c->temperature.on) { /* the point's surface temperature */
    rs_inputs in;
    rs_model_inputs_at(&ch->m, 0.0, &in);
    rs_diag dt;
    rs_temperature_run t;
    status = rs_model_diagnostics(&ch->m, &ch->w, &in, *y, ch->yp, &dt, NULL, NULL, NULL);
    if (status == RS_OK) status = rs_temperature_run_create(&t, c, &ch->m, msg);
    if (status == RS_OK) {
      rs_temperature_run_eval(&t, &ch->m, &ch->w, &in, *y, d);
      rs_temperature_run_free(&t);
    }
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
  /* the error estimate on the chain's companion grids, built with its model */
  if (status == RS_OK && estimate && !ch->est_tried) {
    char why[256];
    ch->est_tried = 1;
    if (rs_errest_admissible(&ch->m, why, sizeof why))
      status = rs_errest_create(&ch->est, &ch->m, ch->ctx, msg);
  }
  if (status == RS_OK && estimate) status = rs_errest_point(&ch->est, &ch->m, *y, d, msg);
  sum->nonlin_iters += stats.nonlin_iters;
  sum->lin_solves += stats.lin_solves;
  sum->refused += stats.refused;
  sum->couplings += stats.couplings;
  sum->coupling_newton += stats.coupling_newton;
  sum->coupling_products += stats.coupling_products;
  ch->jac_now = stats.jac_evals;
  if (status != RS_OK) chain_drop(ch); /* no reuse after a failure */
  return status;
}

/* The case of point j of the line: the base case with the line's fixed overrides and its
 * key at values[j] (ov holds nfixed + 1 overrides). */
static int line_case(const rs_sweep_line *line, rs_case_override *ov, size_t j, rs_case *c,
                     rs_msg *msg)
{
  for (int i = 0; i < line->nfixed; i++) ov[i] = line->fixed[i];
  ov[line->nfixed] = (rs_case_override){line->key, line->values[j]};
  return rs_case_derive(line->base, ov, line->nfixed + 1, c, msg);
}

/* Point j of the line on the chain ch (warm: continued from *y); one_thread: the point's
 * solver on one thread. Returns the point's status (RS_OK, or RS_ERR_SOLVER with why in
 * pmsg; then no warm start from it) or an input or internal error's. */
static int line_point(const rs_sweep_line *line, steady_chain *ch, rs_case_override *ov, double **y,
                      int *ny, size_t j, int warm, int one_thread, rs_stats *sum, rs_diag *d,
                      long *newton, rs_msg *pmsg)
{
  rs_case c;
  *newton = 0;
  int ps = line_case(line, ov, j, &c, pmsg);
  if (ps != RS_OK) return ps;
  if (one_thread) c.threads = 1;
  if (c.mode == RS_MODE_STEADY) {
    const long before = sum->nonlin_iters;
    ps = steady_point(&c, ch, y, ny, warm, rs_case_key_rolling(line->key), line->values[j],
                      line->estimate, d, line->fields, sum, pmsg);
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

/* The message of a point that stopped the line with an input or internal error. */
static int line_error(const rs_sweep_line *line, size_t j, int status, const rs_msg *pm,
                      rs_msg *msg)
{
  if (line->first_point >= 0)
    return rs_msg_set(msg, status, "sweep point %zu: %s", (size_t)line->first_point + j, pm->text);
  return rs_msg_set(msg, status, "%s=%.17g: %s", rs_case_key_name(line->key), line->values[j],
                    pm->text);
}

static void line_totals(const rs_sweep_line *line, const rs_stats *sum, const steady_chain *ch)
{
  if (line->stats) {
    line->stats->nonlin_iters += sum->nonlin_iters;
    line->stats->lin_solves += sum->lin_solves;
    line->stats->refused += sum->refused;
    line->stats->couplings += sum->couplings;
    line->stats->coupling_newton += sum->coupling_newton;
    line->stats->coupling_products += sum->coupling_products;
    line->stats->jac_evals += ch->jac_evals + ch->jac_now;
  }
  if (line->refined) *line->refined += ch->refined;
  if (line->midpoints) *line->midpoints += ch->midpoints;
}

/* A line of steady points along a rolling input where the steady state is unique. */
static int unique_line(const rs_case *c, int key, size_t n)
{
  return n >= 2 && c->mode == RS_MODE_STEADY && rs_case_key_rolling(key) != RS_ROLLING_NONE &&
         unique_steady(c->dimension, &c->friction, c->has_plasticity, c->k_tau);
}

int rs_sweep_line_far_first(const rs_case *c, int key, size_t n)
{
  return unique_line(c, key, n) && c->has_plasticity;
}

int rs_sweep_line_in_two(const rs_case *c, int key, size_t n)
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
 * split, so that a sweep's file does not depend on the threads' timing; partial slip costs
 * more than saturation (more so on fine grids), hence the smaller share for worker 0. */
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
    rs_case_override *ov = calloc((size_t)line->nfixed + 1, sizeof *ov);
    int mine = ov && SUNContext_Create(NULL, &ch.ctx) == 0 ? RS_OK : RS_ERR_INTERNAL;
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
      const int ps = line_point(line, &ch, ov, &y, &ny, j, warm, 1, &sum, &d, &newton, &pm);
      warm = 1;
#pragma omp critical(rs_sweep_line)
      {
        int st = ps;
        if (ps == RS_OK || ps == RS_ERR_SOLVER)
          st = line->point_done(line->ctx, j, ps, &d, newton, pm.text);
        else if (status == RS_OK)
          line_error(line, j, ps, &pm, msg);
        if (st != RS_OK && status == RS_OK) status = st;
      }
    }
#pragma omp critical(rs_sweep_line)
    line_totals(line, &sum, &ch);
    chain_drop(&ch);
    if (ch.ctx) SUNContext_Free(&ch.ctx);
    free(y);
    free(ov);
  }
  if (line->in_two) (*line->in_two)++;
  return status;
}
#endif

/* One continuation line in memory (study/sweep_lines.h): the points of rs_sweep_run's loop
 * along its last axis, with the same models, warm starts and continuation. */
int rs_sweep_line_eval(const rs_sweep_line *line, rs_msg *msg)
{
  rs_case_override *ov = calloc((size_t)line->nfixed + 1, sizeof *ov);
  if (!ov) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  int far = 0;
  if (line->n >= 2 && !line->fields) { /* 3D sweeps store no profiles */
    rs_case c;
    rs_msg cm = {{0}};
    if (line_case(line, ov, 0, &c, &cm) == RS_OK) {
      far = rs_sweep_line_far_first(&c, line->key, line->n);
      const int in_two = rs_sweep_line_in_two(&c, line->key, line->n); /* 0 without OpenMP */
      rs_case_free(&c);
#ifdef _OPENMP
      if (in_two) {
        free(ov);
        return line_in_two(line, msg);
      }
#else
      (void)in_two;
#endif
    }
  }
  steady_chain chain = {0};
  if (SUNContext_Create(NULL, &chain.ctx) != 0) {
    free(ov);
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
    const int ps = line_point(line, &chain, ov, &y, &ny, j, k > 0, 0, &sum, &d, &newton, &pm);
    if (ps == RS_OK || ps == RS_ERR_SOLVER)
      status = line->point_done(line->ctx, j, ps, &d, newton, pm.text);
    else
      status = line_error(line, j, ps, &pm, msg);
  }
  line_totals(line, &sum, &chain);
  chain_drop(&chain);
  SUNContext_Free(&chain.ctx);
  free(y);
  free(ov);
  return status;
}
