/* rollsim command line (the commands and options: README; each command's help: cli/help.c):
 *   rollsim run CASE.yaml [-o OUT.nc] [--restart OLD.nc [--append]] [--set KEY=VALUE]... [--quiet]
 *   rollsim check CASE.yaml [--set KEY=VALUE]...
 *   rollsim sweep CASE.yaml [-o OUT.nc] [--part K/N] [--resume] [--set ...]
 *   rollsim status OUT.nc...   (rollsim check OUT.nc: the same)
 *   rollsim fit CASE.yaml [-o FIT.nc] [--resume] [--set ...]
 *   rollsim --help | --version
 * Exit codes: 0 success, 2 invalid input (nothing run), 3 solver failure (partial
 * results kept), 4 interrupted (partial results kept), 1 internal or output error. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "io/case.h"
#include "study/errest.h"
#include "study/fit.h"
#include "study/run.h"
#include "study/sweep.h"
#include "cli/cli.h"
#include "study/warnings.h"
#include "study/wheel_rail.h"
#include "study/mpi_session.h"
#include "study/sweep_dist.h"

#ifndef RS_VERSION
#define RS_VERSION "unknown"
#endif

/* The only process-wide state: set by SIGINT/SIGTERM, read between output records. */
static volatile sig_atomic_t interrupted = 0;

static void on_signal(int sig)
{
  (void)sig;
  interrupted = 1;
}

static void usage(FILE *f) { rs_cli_help(NULL, f); }

/* Whether two paths name the same existing file. */
static int same_file(const char *a, const char *b)
{
  struct stat sa, sb;
  return stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

/* The summary's first lines: the case's title and, under it, what --set changed (which
 * the title may not say). */
static void print_title(const rs_case *c, const char *case_path)
{
  printf("%s\n", c->title && *c->title ? c->title : case_path);
  if (c->overrides) printf("  with --set %s\n", c->overrides);
}

static int exit_code(int status)
{
  switch (status) {
  case RS_OK: return 0;
  case RS_ERR_INPUT: return 2;
  case RS_ERR_SOLVER: return 3;
  case RS_ERR_INTERRUPTED: return 4;
  default: return 1;
  }
}

/* The parsed command line. */
typedef struct cli_args {
  const char *cmd, *case_path, *out_path, *restart_path;
  int quiet, append, nsets;
  const char **sets; /* the --set KEY=VALUE strings [nsets] (owned array) */
  int part, parts;   /* sweep --part K/N, or 0 */
  int resume;        /* sweep or fit --resume */
  const rs_mpi *mpi; /* this process's MPI session (rank 0 of 1 without a launcher) */
} cli_args;

/* argv after the command: options and the case file. RS_OK, or RS_ERR_INPUT (message
 * printed). */
static int parse_args(int argc, char **argv, cli_args *a)
{
  a->sets = calloc((size_t)argc, sizeof *a->sets);
  if (!a->sets) return RS_ERR_INTERNAL;
  for (int i = 2; i < argc; i++) {
    const char *arg = argv[i];
    if (!strcmp(arg, "-o") || !strcmp(arg, "--output")) {
      if (++i >= argc) {
        fprintf(stderr, "rollsim: %s needs a file name\n", arg);
        return RS_ERR_INPUT;
      }
      a->out_path = argv[i];
    } else if (!strcmp(arg, "--restart") || !strncmp(arg, "--restart=", 10)) {
      if (strcmp(a->cmd, "run")) {
        fprintf(stderr, "rollsim %s: --restart applies to 'rollsim run' only\n", a->cmd);
        return RS_ERR_INPUT;
      }
      if (arg[9] == '=')
        a->restart_path = arg + 10;
      else if (++i < argc)
        a->restart_path = argv[i];
      if (!a->restart_path || !*a->restart_path) {
        fprintf(stderr, "rollsim: --restart needs a file name\n");
        return RS_ERR_INPUT;
      }
    } else if (!strcmp(arg, "--set")) {
      if (++i >= argc) {
        fprintf(stderr, "rollsim: --set needs KEY=VALUE\n");
        return RS_ERR_INPUT;
      }
      a->sets[a->nsets++] = argv[i];
    } else if (!strncmp(arg, "--set=", 6)) {
      a->sets[a->nsets++] = arg + 6;
    } else if (!strcmp(arg, "--append")) {
      if (strcmp(a->cmd, "run")) {
        fprintf(stderr, "rollsim %s: --append applies to 'rollsim run --restart OLD.nc' only\n",
                a->cmd);
        return RS_ERR_INPUT;
      }
      a->append = 1;
    } else if (!strcmp(arg, "--part")) {
      char tail = 0;
      if (strcmp(a->cmd, "sweep") || ++i >= argc ||
          sscanf(argv[i], "%d/%d%c", &a->part, &a->parts, &tail) != 2 || a->parts < 1 ||
          a->part < 1 || a->part > a->parts) {
        fprintf(stderr, "rollsim: --part applies to rollsim sweep and needs K/N with "
                        "1 <= K <= N, e.g. --part 2/8\n");
        return RS_ERR_INPUT;
      }
    } else if (!strcmp(arg, "--resume")) {
      if (strcmp(a->cmd, "sweep") && strcmp(a->cmd, "fit")) {
        fprintf(stderr, "rollsim %s: --resume applies to 'rollsim sweep' and 'rollsim fit' only\n",
                a->cmd);
        return RS_ERR_INPUT;
      }
      a->resume = 1;
    } else if (!strcmp(arg, "--quiet") || !strcmp(arg, "-q")) {
      a->quiet = 1;
    } else if (arg[0] == '-' && arg[1] != '\0') {
      fprintf(stderr, "rollsim: unknown option '%s'\n", arg);
      return RS_ERR_INPUT;
    } else if (!a->case_path) {
      a->case_path = arg;
    } else {
      fprintf(stderr, "rollsim: more than one case file ('%s' and '%s')\n", a->case_path, arg);
      return RS_ERR_INPUT;
    }
  }
  if (!a->case_path) {
    fprintf(stderr, "rollsim %s: missing CASE.yaml\n", a->cmd);
    return RS_ERR_INPUT;
  }
  if (a->append && !a->restart_path) {
    fprintf(stderr,
            "rollsim run: --append continues the file given by --restart OLD.nc: give it\n");
    return RS_ERR_INPUT;
  }
  if (a->append && a->out_path && !same_file(a->out_path, a->restart_path)) {
    fprintf(stderr, "rollsim run: --append writes into %s (the --restart file); leave out -o %s\n",
            a->restart_path, a->out_path);
    return RS_ERR_INPUT;
  }
  for (int k = 0; k < a->nsets; k++)
    if (!strchr(a->sets[k], '=')) {
      fprintf(stderr, "rollsim: --set %s: expected KEY=VALUE\n", a->sets[k]);
      return RS_ERR_INPUT;
    }
  return RS_OK;
}

/* rollsim check: the resolved case, the derived parameters and the sweep block. */
static int cmd_check(const rs_case *c, const cli_args *a, const rs_sweep *sw)
{
  rs_msg msg = {{0}};
  rs_case_print(c, stdout);
  rs_case_print_profiles(c, stdout);
  int status = rs_wheel_rail_print(c, stdout, &msg);
  if (status == RS_OK && !rs_wheel_rail_given(c)) status = rs_run_print_derived(c, stdout, &msg);
  if (status != RS_OK) fprintf(stderr, "%s: %s\n", a->case_path, msg.text);
  if (status == RS_OK && sw->naxes > 0) rs_cli_print_sweep(stdout, sw, c->dimension);
  return status == RS_ERR_SOLVER ? RS_ERR_INPUT : status;
}

/* The summary's output line: the file written and where an older one was kept ("" none). */
static void print_output(const char *file, const char *backup)
{
  printf("  output: %s%s%s%s\n", file, *backup ? " (the previous file kept as " : "", backup,
         *backup ? ")" : "");
}

/* rollsim sweep on profiles: a path of wheelset positions, on rank 0 only. */
static int cmd_sweep_positions(const rs_case *c, const cli_args *a, const rs_sweep *sw,
                               const rs_run_opts *o)
{
  if (a->mpi->rank > 0) return RS_OK;
  if (a->resume || a->parts > 0 || a->mpi->size > 1) {
    fprintf(stderr,
            "rollsim sweep: %s: a sweep on profiles runs in one process (no --resume, --part or "
            "mpirun yet): its positions take a fraction of a second each\n",
            a->case_path);
    return RS_ERR_INPUT;
  }
  print_title(c, a->case_path);
  const rs_wr_sweep_opts wo = {.output_path = o->output_path ? o->output_path : c->output_file,
                               .history = o->history,
                               .case_text = c->yaml_text ? c->yaml_text : "",
                               .table = a->quiet ? NULL : stdout,
                               .interrupt_flag = o->interrupt_flag};
  if (wo.table)
    printf("# lateral displacement mm, yaw rad; per patch: y on the rail mm, contact angle deg, "
           "F_n, F_x, F_s N "
           "(on the wheel)\n");
  rs_msg msg = {{0}};
  rs_wr_sweep_result res;
  const int status = rs_wheel_rail_sweep(c, sw, &wo, &res, &msg);
  if (status != RS_OK) fprintf(stderr, "rollsim: %s: %s\n", a->case_path, msg.text);
  if (!*res.file) return status;
  printf("sweep over %zu wheelset positions:", sw->npoints);
  for (int k = 0; k < sw->naxes; k++) printf(" %s", sw->axes[k].key);
  printf("; %zu solved, %zu failed, Newton iterations %ld, wall time %.3f s\n", res.done,
         res.failed, res.newton, res.wall_seconds);
  print_output(res.file, res.backup);
  return status;
}

/* rollsim sweep: every point of the case's sweep: block into one file. */
static int cmd_sweep(const rs_case *c, const cli_args *a, const rs_sweep *sw, const rs_run_opts *o)
{
  rs_msg msg = {{0}};
  if (sw->positions) return cmd_sweep_positions(c, a, sw, o);
  if (a->mpi->rank > 0) { /* an MPI worker: compute, print nothing */
    const rs_sweep_dist d = {.mpi = a->mpi, .resume = a->resume};
    rs_sweep_result sres;
    return rs_sweep_run_dist(sw, c, o, &d, &sres, &msg);
  }
  print_title(c, a->case_path);
  rs_sweep_result sres;
  const rs_sweep_dist d = {.mpi = a->mpi, .part = a->part, .parts = a->parts, .resume = a->resume};
  const int status = rs_sweep_run_dist(sw, c, o, &d, &sres, &msg);
  if (a->resume && status == RS_ERR_INPUT && sres.points_done + sres.points_failed == 0) {
    /* a refused --resume: nothing run */
    fprintf(stderr, "rollsim sweep: %s\n", msg.text);
    return status;
  }
  if (status != RS_OK) fprintf(stderr, "rollsim: %s: %s\n", a->case_path, msg.text);
  if (status == RS_ERR_OUTPUT && !*sres.file) return status; /* no file: nothing was run */
  if (a->mpi->size > 1)
    printf("sweep on %d MPI ranks (task farm over continuation lines; the solver statistics below "
           "are rank 0's)\n",
           a->mpi->size);
  if (a->parts > 0)
    printf("part %d of %d (continuation lines l with l mod %d = %d)\n", a->part, a->parts, a->parts,
           a->part - 1);
  if (a->resume)
    printf("resumed: %zu points of complete continuation lines kept from the file, the others "
           "computed\n",
           sres.points_kept);
  printf("sweep over");
  for (int k = 0; k < sw->naxes; k++) printf(" %s (%d)", sw->axes[k].key, sw->axes[k].n);
  printf(": %zu points solved, %zu failed, Newton iterations %ld, wall time %.3f s\n",
         sres.points_done, sres.points_failed, sres.newton_iters, sres.wall_seconds);
  printf("  steady points: linear solves %ld, Jacobian evaluations %ld, continuation steps "
         "halved %ld, intermediate points %ld\n",
         sres.lin_solves, sres.jac_evals, sres.refined, sres.midpoints);
  if (sres.error_estimate && sres.points_estimated > 0)
    printf("  error estimates: %zu of %zu points (%zu with the observed order in the asymptotic "
           "range), largest F_x/F_n error %.2g (variables Fx_error, traction_coefficient_error, "
           "error_reliable)\n",
           sres.points_estimated, sres.points_done, sres.points_reliable, sres.max_mu_error);
  else if (sres.error_estimate && sres.points_done > 0)
    printf("  error estimates: none (the grid is too coarse: the estimate solves each point "
           "again on grids of a half and a quarter of the cells, whose coarsest needs at least "
           "%d cells across the contact)\n",
           RS_ERREST_MIN_CELLS);
  if (sres.couplings > 0)
    printf("  temperature coupling: %ld coupled solves, %ld Newton steps, %ld Jacobian products\n",
           sres.couplings, sres.coupling_newton, sres.coupling_products);
  if (sres.lines_in_two > 0)
    printf("  solver.threads 2: %ld continuation line%s solved in two parts at once\n",
           sres.lines_in_two, sres.lines_in_two == 1 ? "" : "s");
  if (sres.refused > 0)
    printf("  steady check: %ld Newton solutions refused as not physical (recomputed by "
           "rolling the material)\n",
           sres.refused);
  printf("  output: %s%s%s%s%s\n", sres.file, *sres.backup ? " (the previous file kept as " : "",
         sres.backup, *sres.backup ? ")" : "",
         status == RS_OK ? "" : " -- incomplete, see `rollsim status`");
  return status;
}

/* The error estimate of a steady run's result (docs/model.md, "Discretisation error
 * estimates"), or why there is none. */
static void print_error_estimate(const rs_case *c, const rs_run_result *res)
{
  const rs_diag *d = &res->final;
  const int three = c->dimension == 3;
  if (!c->error_estimate) return;
  if (res->grid_chosen)
    printf("  grid.accuracy %g: grid of %d%s%.0d cells %s\n", c->accuracy, res->cells[0],
           three ? " x " : "", three ? res->cells[1] : 0,
           res->accuracy_met ? "chosen" : "(the finest allowed; accuracy not reached)");
  if (d->error_state == RS_ERROR_NONE) {
    printf("  error estimate: %s\n", *res->error_note ? res->error_note : "none");
    return;
  }
  printf("  F_x = %.6g +- %.2g %s (F_x/F_n +- %.2g)", d->Fx, d->Fx_error, three ? "N" : "N/mm",
         d->Fn != 0.0 ? d->Fx_error / fabs(d->Fn) : 0.0);
  if (three)
    printf(", F_y = %.6g +- %.2g N, M_z = %.6g +- %.2g N mm", d->Fy, d->Fy_error, d->Mz,
           d->Mz_error);
  printf("\n    estimated discretisation errors, from grids of 1/2 and 1/4 the cells; %s\n",
         d->error_state == RS_ERROR_RELIABLE
             ? "observed order within 10 % of 1 (asymptotic range)"
             : "UNRELIABLE: observed order not within 10 % of 1, a bound with safety factor 3");
  if (d->error_state == RS_ERROR_RELIABLE && isfinite(d->Fx_extrapolated)) {
    printf("  extrapolated to zero cell size: F_x = %.6g %s (F_x/F_n = %.6g)", d->Fx_extrapolated,
           three ? "N" : "N/mm", d->Fn != 0.0 ? d->Fx_extrapolated / d->Fn : 0.0);
    if (three) printf(", F_y = %.6g N, M_z = %.6g N mm", d->Fy_extrapolated, d->Mz_extrapolated);
    printf("\n");
  }
}

/* The summary of one run on stdout. */
static void print_summary(const rs_case *c, const cli_args *a, const rs_run_result *res, int status)
{
  const rs_diag *d = &res->final;
  const int three = c->dimension == 3;
  const char *fu = three ? "N" : "N/mm";
  const double ratio = d->Fn > 0 ? d->Fx / (res->mu * d->Fn) : 0.0;
  print_title(c, a->case_path);
  printf("  F_x/(mu F_n) = %.6f   (F_x = %.6g %s, F_n = %.6g %s, mu = %g) at t = %.6g s\n", ratio,
         d->Fx, fu, d->Fn, fu, res->mu, res->time);
  if (three)
    printf("  F_y = %.6g N, M_z = %.6g N mm   (xi = %.6g, eta = %.6g, phi = %.6g 1/mm)\n", d->Fy,
           d->Mz, d->creepage, d->lateral_creepage, d->spin);
  print_error_estimate(c, res);
  printf("  cells E/H/S/P = %d/%d/%d/%d\n", d->count[RS_EXTERIOR], d->count[RS_ADHESION],
         d->count[RS_SLIP], d->count[RS_PLASTIC]);
  if (c->temperature.on)
    printf("  T_max = %.4g degC   (heat into body 1/2: %.6g/%.6g %s; bulk %g/%g degC)\n", d->T_max,
           d->heat_input_1, d->heat_input_2, three ? "W" : "W/mm", c->temperature.bulk[0],
           c->temperature.bulk[1]);
  if (c->temperature.on && c->rig.on && res->rig_revolutions > 0 &&
      (c->temperature.disc_mass[0] > 0.0 || c->temperature.disc_mass[1] > 0.0))
    printf(
        "  disc bulk temperatures after revolution %.0f: %.4f/%.4f degC (temperature.disc_mass)\n",
        res->rig_revolutions, res->rig_bulk[0], res->rig_bulk[1]);
  /* A falling law can have several steady states: say which one this is. */
  if (rs_friction_varies(&c->friction) && c->mode == RS_MODE_STEADY)
    printf("  friction law %s (mu = %g at rest); steady branch: %s\n",
           rs_friction_name(c->friction.kind), c->mu,
           a->restart_path ? "the one Newton reached from the --restart state"
           : three         ? "the one connected to rest (continuation in the creepages and the "
                             "spin together from 0 in steps of 1/16, halved where Newton fails, "
                             "each started on the secant through the last two)"
                           : "the one connected to rest (continuation in the creepage from 0 in "
                             "steps of 1/16, halved where Newton fails, each started on the "
                             "secant through the last two)");
  const rs_stats *st = &res->stats;
  if (c->mode == RS_MODE_TRANSIENT && c->rtol > 0.0)
    printf("  solver.rtol %g\n", res->rtol);
  else if (c->mode == RS_MODE_TRANSIENT)
    printf("  solver.rtol auto = %g (0.06 dx/a within [1e-6, 3e-3], the time error below the "
           "grid's)\n",
           res->rtol);
  if (c->mode == RS_MODE_TRANSIENT)
    printf("  IDA steps %ld, Newton iterations %ld, failed solves %ld, error-test fails %ld\n"
           "  linear solves %ld, Jacobian evaluations %ld, factorisations %ld\n",
           st->steps, st->nonlin_iters, st->nonlin_fails, st->err_test_fails,
           /* KLU inside IDA's Newton: one linear solve per Newton iteration; 3D
            * (Newton-Krylov): GMRES iterations, and the near field's factorisations */
           st->lin_solves > 0 ? st->lin_solves : st->nonlin_iters, st->jac_evals,
           st->factorizations);
  else
    printf("  Newton iterations %ld, linear solves %ld, Jacobian evaluations %ld\n",
           st->nonlin_iters, st->lin_solves, st->jac_evals);
  if (st->couplings > 0)
    printf("  temperature coupling: %ld coupled solves, %ld Newton steps, %ld Jacobian products\n",
           st->couplings, st->coupling_newton, st->coupling_products);
  else if (c->mode == RS_MODE_TRANSIENT && st->coupling_products > 0)
    printf("  temperature coupling: %ld products with the coupling's Jacobian term in the steps' "
           "Newton iterations\n",
           st->coupling_products);
  /* Rolling transients: the cost per cell passage (docs/model.md §5: one passage is one cell
   * length rolled; a fixed-shift scheme takes one step per passage). */
  if (c->mode == RS_MODE_TRANSIENT && !c->rig.on && res->rolled > 0.0 && res->dx > 0.0)
    printf("  rolled %.6g mm = %.6g cell passages: %.3g steps per passage\n", res->rolled,
           res->rolled / res->dx, st->steps * res->dx / res->rolled);
  if (st->refused > 0)
    printf("  steady check: %ld Newton solution(s) refused as not physical (recomputed by "
           "rolling the material)\n",
           st->refused);
  if (c->rig.on) {
    const double T = c->rig.revolution_time;
    printf("  twin disc: %.6g revolutions of %.6g s, %.1f IDA steps per revolution "
           "(a fixed shift of one cell per step would need %.0f)\n",
           res->time / T, T, res->time > 0 ? st->steps * T / res->time : 0.0,
           T * rs_history_eval(&c->velocity, 0.0) / res->dx);
    printf("  protocol step   slip [%%]   traction coefficient (mean over the last %.0f %% of "
           "the step)\n",
           100.0 * c->rig.average_window);
    for (size_t j = 0; j < res->rig_nsteps; j++)
      printf("  %13zu %10.4f   %.6f\n", j + 1, 100.0 * res->rig_step_slip[j], res->rig_step_mu[j]);
  }
  printf("  wall time %.3f s\n", res->wall_seconds);
  if (a->append)
    printf("  output: %s (%zu records, %zu of them appended)%s\n", res->file, res->file_records,
           res->records, status == RS_OK ? "" : " -- incomplete, see status attribute");
  else
    printf("  output: %s (%zu records)%s\n", res->file, res->records,
           status == RS_OK ? "" : " -- incomplete, see status attribute");
  if (*res->backup) printf("  the previous %s was kept as %s\n", res->file, res->backup);
}

/* rollsim run: one case. */
/* rollsim run on profiles: one run file per loaded patch. */
static int cmd_run_patches(const rs_case *c, const cli_args *a, const rs_run_opts *o)
{
  if (a->restart_path) {
    fprintf(stderr,
            "rollsim run: %s: --restart is not built for runs on profiles (each patch has a file "
            "of its own)\n",
            a->case_path);
    return RS_ERR_INPUT;
  }
  if (!rs_wheel_rail_given(c)) {
    fprintf(stderr,
            "rollsim run: %s: profiles.vertical_load: not given: a run on profiles needs the "
            "wheel load to find the contact patches\n",
            a->case_path);
    return RS_ERR_INPUT;
  }
  print_title(c, a->case_path);
  rs_msg msg = {{0}};
  rs_wr_run_result res;
  const int status = rs_wheel_rail_run(c, o, a->quiet ? NULL : stdout, &res, &msg);
  if (status != RS_OK) fprintf(stderr, "rollsim: %s: %s\n", a->case_path, msg.text);
  if (status == RS_ERR_INPUT) return status; /* refused: nothing was run */
  if (rs_wheel_rail_moving(c)) {
    printf("moving wheelset: %zu intervals written, Newton iterations %ld, steps %ld\n",
           res.records, res.newton, res.steps);
    if (*res.file) print_output(res.file, res.backup);
  } else {
    printf("%d patch(es) found, %d run: Newton iterations %ld, steps %ld\n", res.patches, res.runs,
           res.newton, res.steps);
  }
  return status;
}

static int cmd_run(const rs_case *c, const cli_args *a, const rs_run_opts *o)
{
  if (c->has_profiles) return cmd_run_patches(c, a, o);
  rs_msg msg = {{0}};
  rs_run_result res;
  const int status = rs_run(c, o, &res, &msg);
  if (status != RS_OK) fprintf(stderr, "rollsim: %s: %s\n", a->case_path, msg.text);
  if (res.records > 0) print_summary(c, a, &res, status);
  rs_run_result_free(&res);
  return status;
}

/* SIGINT/SIGTERM set the flag read between output records. */
static void install_signal_handlers(void)
{
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  /* The flag is read between output records, and one output interval can take minutes of
   * solver work: a second SIGINT/SIGTERM then ends the process at once (default action; the
   * file stays valid with the records written so far, status "running"). */
  sa.sa_flags = SA_RESETHAND;
  sigaction(SIGINT, &sa, NULL);
  sigaction(SIGTERM, &sa, NULL);
}

/* The history attribute: date, version and the command line. */
static void history_text(int argc, char **argv, char *history, size_t size)
{
  const time_t now = time(NULL);
  char date[64];
  strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", gmtime(&now));
  int len = snprintf(history, size, "%s: rollsim %s", date, RS_VERSION);
  for (int i = 1; i < argc && len > 0 && (size_t)len < size; i++)
    len += snprintf(history + len, size - (size_t)len, " %s", argv[i]);
}

static int run_command(int argc, char **argv, cli_args *ap);

/* rollsim help [CMD]: the overview or one command's help. */
static int cmd_help(int argc, char **argv)
{
  const char *topic = argc > 2 && strcmp(argv[2], "--help") && strcmp(argv[2], "-h") ? argv[2]
                      : argc > 2                                                     ? "help"
                                                                                     : NULL;
  if (topic && rs_cli_help(topic, stdout) != 0) {
    fprintf(stderr, "rollsim help: unknown command '%s'\n", topic);
    return 2;
  }
  return topic ? 0 : rs_cli_help(NULL, stdout);
}

int main(int argc, char **argv)
{
  rs_cli_heap_setup();
  if (argc < 2) {
    usage(stderr);
    return 2;
  }
  if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
    usage(stdout);
    return 0;
  }
  if (!strcmp(argv[1], "--version")) {
    printf("rollsim %s\n", RS_VERSION);
    return 0;
  }
  cli_args a = {.cmd = argv[1]};
  if (!strcmp(a.cmd, "help")) return cmd_help(argc, argv);
  if (!strcmp(a.cmd, "merge")) return exit_code(rs_cli_merge(argc - 2, argv + 2));
  if (!strcmp(a.cmd, "status")) return exit_code(rs_cli_status(argc - 2, argv + 2));
  if (!strcmp(a.cmd, "check") && argc == 3 && strlen(argv[2]) > 3 &&
      !strcmp(argv[2] + strlen(argv[2]) - 3, ".nc")) /* rollsim check OUT.nc: its status */
    return exit_code(rs_cli_status(1, argv + 2));
  rs_mpi mpi;
  if (rs_mpi_start(&mpi, &argc, &argv) != 0) return 1;
  a.mpi = &mpi;
  const int code = run_command(argc, argv, &a);
  rs_mpi_finish(&mpi);
  return code;
}

/* Everything but help, merge and status, on every MPI rank. */
static int run_command(int argc, char **argv, cli_args *ap)
{
  cli_args a = *ap;
  if (a.mpi->rank > 0 && strcmp(a.cmd, "sweep") && strcmp(a.cmd, "fit"))
    return 0; /* other commands run once, on rank 0 */
  if (!rs_cli_is_command(a.cmd)) {
    fprintf(stderr, "rollsim: unknown command '%s'\n", a.cmd);
    usage(stderr);
    return 2;
  }
  for (int i = 2; i < argc; i++) /* rollsim CMD ... --help: that command's help, nothing run */
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      rs_cli_help(a.cmd, stdout);
      return 0;
    }
  int status = parse_args(argc, argv, &a);
  rs_case c;
  rs_sweep sw = {0};
  rs_msg msg = {{0}};
  if (status == RS_OK && (status = rs_case_load(&c, a.case_path, a.sets, a.nsets, &msg)) != RS_OK)
    fprintf(stderr, "%s\n", msg.text);
  if (status != RS_OK) {
    free(a.sets);
    return exit_code(status);
  }
  if (!strcmp(a.cmd, "fit") && (status = rs_case_refuse_profiles(&c, &msg)) != RS_OK) {
    if (a.mpi->rank == 0) fprintf(stderr, "%s\n", msg.text);
    rs_case_free(&c);
    free(a.sets);
    return exit_code(status);
  }
  if (c.has_sweep && strcmp(a.cmd, "run") &&
      strcmp(a.cmd, "fit")) { /* check and sweep: the sweep block is input too */
    if ((status = rs_sweep_load(&sw, &c, &msg)) != RS_OK) fprintf(stderr, "%s\n", msg.text);
  } else if (!strcmp(a.cmd, "sweep")) {
    fprintf(stderr, "%s: the case has no sweep: block (use rollsim run)\n", a.case_path);
    status = RS_ERR_INPUT;
  }
  if (status == RS_OK && a.mpi->rank == 0) {
    if (sw.naxes > 0)
      rs_warn_sweep(&c, &sw, stderr);
    else if (strcmp(a.cmd, "fit"))
      rs_warn_case(&c, stderr);
  }
  if (status == RS_OK && !strcmp(a.cmd, "check")) {
    status = cmd_check(&c, &a, &sw);
  } else if (status == RS_OK) {
    install_signal_handlers();
    char history[2048];
    history_text(argc, argv, history, sizeof history);
    const rs_run_opts o = {.output_path = a.out_path,
                           .history = history,
                           .restart_path = a.restart_path,
                           .append = a.append,
                           .cost_warning = 1,
                           .progress = !a.quiet && isatty(STDERR_FILENO),
                           .interrupt_flag = &interrupted};
    const rs_fit_opts fo = {.output_path = a.out_path,
                            .history = history,
                            .progress = o.progress,
                            .interrupt_flag = &interrupted,
                            .mpi_rank = a.mpi->rank,
                            .mpi_size = a.mpi->size,
                            .resume = a.resume};
    status = !strcmp(a.cmd, "sweep") ? cmd_sweep(&c, &a, &sw, &o)
             : !strcmp(a.cmd, "fit") ? rs_cli_fit(&c, &fo)
                                     : cmd_run(&c, &a, &o);
  }
  rs_sweep_free(&sw);
  rs_case_free(&c);
  free(a.sets);
  return exit_code(status);
}
