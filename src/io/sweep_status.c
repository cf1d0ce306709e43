/* rollsim status: a sweep file's points written (converged is netCDF's default fill where
 * none was: docs/file-format.md), those that failed (converged 0), its status attribute
 * and when it was last written. A writer killed by SIGKILL leaves status "running"
 * (io/output_sweep.c): the counts say how far it got, and the writer attribute ("HOST
 * PID") whether that process still runs, when it ran on this host. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <netcdf.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/output_internal.h"
#include "io/sweep_status.h"

/* Whether process pid of this host is a running rollsim: 1 yes, 0 no (gone, a zombie, or
 * the pid reused by another program). */
static int rollsim_alive(long pid)
{
  if (pid <= 0 || (kill((pid_t)pid, 0) != 0 && errno != EPERM)) return 0;
  char path[64], line[256] = "";
  snprintf(path, sizeof path, "/proc/%ld/stat", pid);
  FILE *f = fopen(path, "r");
  if (!f) return 1; /* no /proc: trust kill */
  const int got = fgets(line, sizeof line, f) != NULL;
  fclose(f);
  /* "PID (COMM) STATE ..." */
  const char *open = strchr(line, '('), *close = strrchr(line, ')');
  if (!got || !open || !close || close < open || close[1] != ' ') return 0;
  return strncmp(open + 1, "rollsim", 7) == 0 && close[2] != 'Z' && close[2] != 'X';
}

static void read_writer(int ncid, rs_sweep_file_status *st)
{
  char *text = rs_output_get_text(ncid, NC_GLOBAL, "writer");
  const char *sp = text ? strrchr(text, ' ') : NULL;
  if (sp && sp > text && (size_t)(sp - text) < sizeof st->writer_host) {
    memcpy(st->writer_host, text, (size_t)(sp - text));
    st->writer_pid = strtol(sp + 1, NULL, 10);
    char host[sizeof st->writer_host] = "";
    if (gethostname(host, sizeof host - 1) != 0) host[0] = '\0';
    st->writer_alive = strcmp(host, st->writer_host) ? -1 : rollsim_alive(st->writer_pid);
  }
  free(text);
}

int rs_sweep_file_status_read(const char *path, rs_sweep_file_status *st, rs_msg *msg)
{
  memset(st, 0, sizeof *st);
  struct stat sb;
  if (stat(path, &sb) != 0) return rs_msg_set(msg, RS_ERR_INPUT, "%s: no such file", path);
  st->mtime = sb.st_mtime;
  long long data_end = 0, size = 0;
  if (rs_nc_classic_data_end(path, &data_end, &size) != 0)
    return rs_msg_set(msg, RS_ERR_INPUT, "%s: not a netCDF file of rollsim (64-bit offset)", path);
  if (size < data_end)
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "%s: truncated (%lld of %lld bytes): its points cannot be trusted", path,
                      size, data_end);
  int ncid, id, ndims, dims[NC_MAX_VAR_DIMS];
  int err = nc_open(path, NC_NOWRITE, &ncid);
  if (err) return rs_msg_set(msg, RS_ERR_INPUT, "%s: %s", path, nc_strerror(err));
  char *text = rs_output_get_text(ncid, NC_GLOBAL, "status");
  snprintf(st->status, sizeof st->status, "%s", text ? text : "");
  free(text);
  read_writer(ncid, st);
  if (nc_get_att_int(ncid, NC_GLOBAL, "part", &st->part) ||
      nc_get_att_int(ncid, NC_GLOBAL, "parts", &st->parts))
    st->part = st->parts = 0;
  st->sweep = !nc_inq_varid(ncid, "converged", &id) && !nc_inq_varid(ncid, "Fx", &ndims) &&
              !nc_inq_varndims(ncid, id, &ndims) && ndims >= 1 && !nc_inq_vardimid(ncid, id, dims);
  size_t total = 1, nlast = 1;
  for (int a = 0; st->sweep && a < ndims; a++) {
    size_t n = 0;
    st->sweep = !nc_inq_dimlen(ncid, dims[a], &n);
    total *= n;
    nlast = n;
  }
  int *conv = st->sweep && total ? malloc(total * sizeof *conv) : NULL;
  if (st->sweep && total && (!conv || nc_get_var_int(ncid, id, conv))) {
    free(conv);
    nc_close(ncid);
    return rs_msg_set(msg, RS_ERR_INPUT, "%s: cannot read its converged variable", path);
  }
  nc_close(ncid);
  for (size_t k = 0; conv && k < total; k++) {
    if (st->parts > 0 && (k / nlast) % (size_t)st->parts != (size_t)(st->part - 1)) continue;
    st->npoints++;
    st->written += conv[k] != NC_FILL_INT;
    st->failed += conv[k] == 0;
  }
  free(conv);
  st->state = st->written < st->npoints ? RS_SWEEP_INCOMPLETE
              : st->failed > 0          ? RS_SWEEP_FAILED
                                        : RS_SWEEP_COMPLETE;
  if (st->sweep && st->state == RS_SWEEP_COMPLETE && strncmp(st->status, "complete", 8))
    st->state = RS_SWEEP_INCOMPLETE; /* every point there, but the writer did not finish */
  return RS_OK;
}

void rs_sweep_file_status_line(const rs_sweep_file_status *st, char *buf, size_t len)
{
  char when[64], part[64] = "";
  strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", gmtime(&st->mtime));
  if (!st->sweep) {
    snprintf(buf, len, "not a sweep file (status: %s), last written at %s", st->status, when);
    return;
  }
  if (st->parts > 0) snprintf(part, sizeof part, " of part %d/%d", st->part, st->parts);
  char why[400];
  if (strncmp(st->status, "running", 7))
    snprintf(why, sizeof why, "%s", st->status);
  else if (!st->writer_host[0])
    snprintf(why, sizeof why, "running: the writer was killed, or is still running");
  else if (st->writer_alive > 0)
    snprintf(why, sizeof why, "running: process %ld on this host is writing it", st->writer_pid);
  else if (st->writer_alive == 0)
    snprintf(why, sizeof why, "running, but its writer, process %ld on this host, is gone: killed",
             st->writer_pid);
  else
    snprintf(why, sizeof why,
             "running: its writer is process %ld on host %s, still running or killed (this host "
             "cannot tell)",
             st->writer_pid, st->writer_host);
  switch (st->state) {
  case RS_SWEEP_COMPLETE:
    snprintf(buf, len, "complete: %zu of %zu points%s", st->written, st->npoints, part);
    break;
  case RS_SWEEP_FAILED:
    snprintf(buf, len, "failed: %zu of %zu points%s did not converge (NaN in the file)", st->failed,
             st->npoints, part);
    break;
  default:
    snprintf(buf, len, "incomplete: %zu of %zu points%s (status: %s), last written at %s",
             st->written, st->npoints, part, why, when);
  }
}
