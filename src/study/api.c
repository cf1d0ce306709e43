/* The embedding API (rollsim/api.h): the command line's run, sweep and check without the
 * printing. Everything lives on the caller's stack or in what it frees. */
#define _POSIX_C_SOURCE 200809L
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "rollsim/api.h"
#include "io/case.h"
#include "io/sweep_status.h"
#include "study/run.h"
#include "study/sweep.h"
#include "study/sweep_dist.h"
#include "study/wheel_rail.h"

static int finish(int status, const rs_msg *m, char *msg, size_t len)
{
  if (msg && len) snprintf(msg, len, "%s", status == 0 ? "" : m->text);
  return status;
}

/* The case (loaded once) and its sweep: block. */
static int load_sweep(rs_case *c, rs_sweep *sw, const char *case_path, const char *const *sets,
                      int nsets, rs_msg *m)
{
  int status = rs_case_load(c, case_path, sets, nsets, m);
  if (status != RS_OK) return status;
  if (!c->has_sweep)
    status = rs_msg_set(m, RS_ERR_INPUT, "%s: the case has no sweep: block (use rollsim run)",
                        case_path);
  else if (status == RS_OK)
    status = rs_sweep_load(sw, c, m);
  if (status != RS_OK) rs_case_free(c);
  return status;
}

int rs_api_run(const char *case_path, const char *const *sets, int nsets, const char *out_path,
               char *msg, size_t msg_len)
{
  rs_msg m = {{0}};
  rs_case c;
  int status = rs_case_load(&c, case_path, sets, nsets, &m);
  if (status != RS_OK) return finish(status, &m, msg, msg_len);
  if (c.has_profiles) { /* one file per patch: the command line's */
    rs_msg_set(&m, RS_ERR_INPUT,
               "%s: profiles: a run on profiles writes one file per contact patch and is the "
               "command line's (rollsim run); the API's sweep runs paths of wheelset positions",
               case_path);
    rs_case_free(&c);
    return finish(RS_ERR_INPUT, &m, msg, msg_len);
  }
  volatile sig_atomic_t stop = 0;
  const rs_run_opts o = {.output_path = out_path,
                         .history = "rollsim " RS_VERSION " (API: rs_api_run)",
                         .interrupt_flag = &stop};
  rs_run_result res;
  status = rs_run(&c, &o, &res, &m);
  rs_run_result_free(&res);
  rs_case_free(&c);
  return finish(status, &m, msg, msg_len);
}

/* rollsim sweep as the API runs it: the serial farm, with progress when given; `history`
 * names the API call in the file. */
static int api_sweep(const char *case_path, const char *const *sets, int nsets,
                     const char *out_path, const char *history, rs_api_progress_fn progress,
                     void *ctx, char *msg, size_t msg_len)
{
  rs_msg m = {{0}};
  rs_case c;
  rs_sweep sw;
  int status = load_sweep(&c, &sw, case_path, sets, nsets, &m);
  if (status != RS_OK) return finish(status, &m, msg, msg_len);
  volatile sig_atomic_t stop = 0;
  if (sw.positions) { /* a sweep on profiles: a path of wheelset positions */
    const rs_wr_sweep_opts wo = {.output_path = out_path,
                                 .history = history,
                                 .case_text = c.yaml_text ? c.yaml_text : "",
                                 .interrupt_flag = &stop};
    rs_wr_sweep_result wres;
    status = rs_wheel_rail_sweep(&c, &sw, &wo, &wres, &m);
    if (progress) progress(ctx, wres.done + wres.failed, sw.npoints);
    rs_sweep_free(&sw);
    rs_case_free(&c);
    return finish(status, &m, msg, msg_len);
  }
  const rs_run_opts o = {.output_path = out_path, .history = history, .interrupt_flag = &stop};
  const rs_sweep_dist d = {.progress = progress, .progress_ctx = ctx};
  rs_sweep_result res;
  status = rs_sweep_run_dist(&sw, &c, &o, &d, &res, &m);
  rs_sweep_free(&sw);
  rs_case_free(&c);
  return finish(status, &m, msg, msg_len);
}

int rs_api_sweep(const char *case_path, const char *const *sets, int nsets, const char *out_path,
                 char *msg, size_t msg_len)
{
  return api_sweep(case_path, sets, nsets, out_path, "rollsim " RS_VERSION " (API: rs_api_sweep)",
                   NULL, NULL, msg, msg_len);
}

int rs_api_sweep_progress(const char *case_path, const char *const *sets, int nsets,
                          const char *out_path, rs_api_progress_fn progress, void *ctx, char *msg,
                          size_t msg_len)
{
  return api_sweep(case_path, sets, nsets, out_path,
                   "rollsim " RS_VERSION " (API: rs_api_sweep_progress)", progress, ctx, msg,
                   msg_len);
}

int rs_api_check(const char *case_path, const char *const *sets, int nsets, char **text, char *msg,
                 size_t msg_len)
{
  *text = NULL;
  rs_msg m = {{0}};
  rs_case c;
  int status = rs_case_load(&c, case_path, sets, nsets, &m);
  if (status != RS_OK) return finish(status, &m, msg, msg_len);
  size_t len = 0;
  FILE *f = open_memstream(text, &len);
  if (!f) {
    rs_case_free(&c);
    rs_msg_set(&m, RS_ERR_INTERNAL, "out of memory");
    return finish(RS_ERR_INTERNAL, &m, msg, msg_len);
  }
  rs_case_print(&c, f);
  rs_case_print_profiles(&c, f);
  status = rs_wheel_rail_print(&c, f, &m);
  if (status == RS_OK && !rs_wheel_rail_given(&c)) status = rs_run_print_derived(&c, f, &m);
  fclose(f);
  rs_case_free(&c);
  if (status == RS_ERR_SOLVER) status = RS_ERR_INPUT; /* as rollsim check */
  return finish(status, &m, msg, msg_len);
}

int rs_api_status(const char *path, char **text, char *msg, size_t msg_len)
{
  *text = NULL;
  rs_msg m = {{0}};
  rs_sweep_file_status st;
  int status = rs_sweep_file_status_read(path, &st, &m);
  if (status != RS_OK) return finish(status, &m, msg, msg_len);
  size_t len = 0;
  FILE *f = open_memstream(text, &len);
  if (!f) {
    rs_msg_set(&m, RS_ERR_INTERNAL, "out of memory");
    return finish(RS_ERR_INTERNAL, &m, msg, msg_len);
  }
  static const char *const states[] = {"complete", "failed", "incomplete"};
  char when[64], line[512];
  strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", gmtime(&st.mtime));
  rs_sweep_file_status_line(&st, line, sizeof line);
  fprintf(f, "state: %s\npoints: %zu\nwritten: %zu\nfailed: %zu\npart: %d\nparts: %d\n",
          st.sweep ? states[st.state] : "not a sweep", st.npoints, st.written, st.failed, st.part,
          st.parts);
  fprintf(f, "status: %s\nlast_written: %s\nsummary: %s\n", st.status, when, line);
  fclose(f);
  return finish(RS_OK, &m, msg, msg_len);
}

void rs_api_free(void *p) { free(p); }

const char *rs_api_version(void) { return "rollsim " RS_VERSION; }
