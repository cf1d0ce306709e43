/* rollsim fit CASE.yaml [-o FIT.nc] [--resume] [--set ...]: read the fit: block, fit, print the
 * summary (stop reason, fitted values with standard errors, correlations, notes). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "study/fit.h"
#include "cli/cli.h"

static void print_summary(const rs_fit_spec *f, const rs_fit_result *r, int status)
{
  const int n = f->nparams;
  printf("fit of %s to %zu points of %s (%s): %s\n", f->measured, f->npoints, f->data_path,
         f->kind == RS_FIT_STEADY    ? "steady points"
         : f->kind == RS_FIT_RIG_REV ? "twin-disc revolutions"
                                     : "twin-disc protocol steps",
         r->stop_reason);
  printf("  %-24s %14s %14s %14s   %s\n", "parameter", "start", "fitted", "std. error", "bounds");
  for (int k = 0; k < n; k++) {
    const rs_fit_param *q = &f->params[k];
    char se[32] = "n/a"; /* a fit stopped short of convergence has no covariance */
    if (isfinite(r->std_error[k])) snprintf(se, sizeof se, "%.4g", r->std_error[k]);
    printf("  %-24s %14.8g %14.8g %14s   [%g, %g] %s\n", q->key, q->start, r->fitted[k], se, q->lo,
           q->hi, q->unit);
  }
  if (status == RS_OK && n > 1) {
    printf("  correlation matrix:\n");
    for (int a = 0; a < n; a++) {
      printf("    %-22s", f->params[a].key);
      for (int b = 0; b <= a; b++) {
        const double rho = r->covariance[a * n + b] / (r->std_error[a] * r->std_error[b]);
        printf(" %+8.4f", rho);
      }
      printf("\n");
    }
  }
  printf("  residual norm %.6g (rms %.4g), %ld evaluations, wall time %.2f s\n", r->residual_norm,
         r->residual_norm / sqrt((double)f->npoints), r->evaluations, r->wall_seconds);
  if (r->resumed)
    printf("  resumed: %ld evaluations were in the file, %ld new\n", r->evaluations_before,
           r->evaluations - r->evaluations_before);
  if (r->notes[0]) {
    printf("  notes:\n");
    const char *p = r->notes;
    while (*p) {
      const char *e = strchr(p, '\n');
      const int len = e ? (int)(e - p) : (int)strlen(p);
      printf("    - %.*s\n", len, p);
      p += len + (e ? 1 : 0);
    }
  }
  printf("  output: %s%s%s%s\n", r->file, *r->backup ? " (the previous file kept as " : "",
         r->backup, *r->backup ? ")" : "");
}

int rs_cli_fit(const rs_case *c, const rs_fit_opts *o)
{
  rs_msg msg = {{0}};
  rs_fit_spec f;
  const char *case_path = c->source_path;
  int status = rs_fit_load(&f, c, &msg);
  if (status != RS_OK) {
    fprintf(stderr, "%s\n", msg.text);
    return status;
  }
  if (o->mpi_rank > 0) { /* an MPI worker: Jacobian columns for rank 0 */
    status = rs_fit_serve(&f, c, o, &msg);
    rs_fit_free(&f);
    return status;
  }
  printf("%s\n", c->title && *c->title ? c->title : case_path);
  if (o->mpi_size > 1)
    printf("  Jacobian columns on %d MPI ranks (column k on rank k mod %d)\n", o->mpi_size,
           o->mpi_size);
  if (c->overrides) printf("  with --set %s\n", c->overrides);
  rs_fit_result r;
  status = rs_fit_run(&f, c, o, &r, &msg);
  if (o->resume && status == RS_ERR_INPUT && !r.resumed) /* a refused --resume: nothing run */
    fprintf(stderr, "rollsim fit: %s\n", msg.text);
  else if (status != RS_OK)
    fprintf(stderr, "rollsim fit: %s: %s\n", case_path, msg.text);
  if (r.already_complete)
    printf("  %s: the fit is complete (%ld evaluations, residual norm %.6g): nothing to resume, "
           "the file is unchanged\n",
           r.file, r.evaluations, r.residual_norm);
  else if (r.fitted && (status != RS_ERR_INPUT || r.resumed))
    print_summary(&f, &r, status);
  rs_fit_result_free(&r);
  rs_fit_free(&f);
  return status;
}
