/* Output failures are reported, not crashed on: an unwritable or impossible path gives
 * RS_ERR_OUTPUT and a message naming the path, leaves no half-made file behind and no
 * handle; a field in the mask without data is refused without counting the record.
 * Usage: test_output_errors [DIR]  (default test_output_errors.d) */
#define _POSIX_C_SOURCE 200809L

#include <netcdf.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/case.h"
#include "io/output.h"
#include "test_support.h"

#define NX 4
static const double x[NX] = {-1.5, -0.5, 0.5, 1.5};

static rs_output_spec spec_for(const char *path)
{
  return (rs_output_spec){.path = path,
                          .title = "errors",
                          .case_text = "title: errors\n",
                          .history = "test_output_errors",
                          .dimension = 2,
                          .nx = NX,
                          .x = x,
                          .fields = RS_FIELD_PX | RS_FIELD_REGIME};
}

/* Creating PATH must fail with RS_ERR_OUTPUT, name PATH, and leave nothing behind. */
static void expect_create_failure(const char *path)
{
  rs_output_spec spec = spec_for(path);
  rs_output *out = (rs_output *)&spec; /* must be reset to NULL */
  rs_msg msg = {{0}};
  int status = rs_output_create(&out, &spec, &msg);
  printf("%s -> %d: %s\n", path, status, msg.text);
  TS_CHECK(status == RS_ERR_OUTPUT, "%s: status %d", path, status);
  TS_CHECK(out == NULL, "%s: handle not reset", path);
  TS_CHECK(strstr(msg.text, path) != NULL, "message \"%s\" names %s", msg.text, path);
  char part[600];
  snprintf(part, sizeof part, "%s.part", path);
  TS_CHECK(access(part, F_OK) != 0, "%s left behind", part);
}

int main(int argc, char **argv)
{
  const char *dir = argc > 1 ? argv[1] : "test_output_errors.d";
  char path[512];
  rs_msg msg = {{0}};

  /* a directory that cannot be created; a directory where no file can be created */
  expect_create_failure("/proc/forbidden/x.nc");
  expect_create_failure("/proc/x.nc");

  /* a parent "directory" that is a regular file */
  TS_CHECK(mkdir(dir, 0777) == 0 || access(dir, W_OK) == 0, "cannot use %s", dir);
  char plain[256];
  snprintf(plain, sizeof plain, "%s/plain_file", dir);
  FILE *f = fopen(plain, "w");
  TS_CHECK(f != NULL, "cannot create %s", plain);
  if (f) fclose(f);
  snprintf(path, sizeof path, "%s/sub/x.nc", plain);
  expect_create_failure(path);

  /* the path is an existing directory */
  snprintf(path, sizeof path, "%s/a_directory.nc", dir);
  TS_CHECK(mkdir(path, 0777) == 0 || access(path, F_OK) == 0, "cannot make %s", path);
  expect_create_failure(path);

  /* no path at all */
  {
    rs_output_spec spec = spec_for("");
    rs_output *out = NULL;
    TS_CHECK(rs_output_create(&out, &spec, &msg) == RS_ERR_OUTPUT && out == NULL, "empty path");
  }

  /* an impossible grid is a caller bug */
  {
    snprintf(path, sizeof path, "%s/nx0.nc", dir);
    rs_output_spec spec = spec_for(path);
    spec.nx = 0;
    rs_output *out = NULL;
    TS_CHECK(rs_output_create(&out, &spec, &msg) == RS_ERR_INTERNAL && out == NULL, "nx = 0");
  }

  /* a field in the mask without data: refused, record not counted, file still fine */
  {
    snprintf(path, sizeof path, "%s/missing_field.nc", dir);
    rs_output_spec spec = spec_for(path);
    rs_output *out = NULL;
    int status = rs_output_create(&out, &spec, &msg);
    TS_CHECK(status == RS_OK, "create %s: %s", path, msg.text);
    if (status == RS_OK) {
      double px[NX] = {1, 2, 3, 4};
      signed char regime[NX] = {0, 1, 2, 3};
      rs_record rec = {.time = 0.0, .Fx = 1.0, .Fn = 2.0, .px = px, .regime = NULL};
      status = rs_output_write(out, &rec, &msg);
      TS_CHECK(status == RS_ERR_INTERNAL, "write without regime: %d", status);
      TS_CHECK(strstr(msg.text, "regime") != NULL, "message \"%s\" names the field", msg.text);
      TS_CHECK(rs_output_records(out) == 0, "records %zu", rs_output_records(out));
      /* nothing of the refused record may reach the file, even after close */
      TS_CHECK(rs_output_close(out, &msg) == RS_OK, "close: %s", msg.text);
      int ncid, dimid;
      size_t nrec = 99;
      TS_CHECK(nc_open(path, NC_NOWRITE, &ncid) == NC_NOERR, "reopen %s", path);
      TS_CHECK(nc_inq_dimid(ncid, "time", &dimid) == NC_NOERR &&
                   nc_inq_dimlen(ncid, dimid, &nrec) == NC_NOERR && nrec == 0,
               "%s holds %zu records after a refused one", path, nrec);
      TS_CHECK(nc_close(ncid) == NC_NOERR, "close %s", path);
      /* a complete record is accepted */
      status = rs_output_create(&out, &spec, &msg);
      TS_CHECK(status == RS_OK, "create %s: %s", path, msg.text);
      rec.regime = regime;
      status = rs_output_write(out, &rec, &msg);
      TS_CHECK(status == RS_OK && rs_output_records(out) == 1, "write: %s", msg.text);
      TS_CHECK(rs_output_close(out, &msg) == RS_OK, "close: %s", msg.text);
    }
  }

  if (ts_failures) {
    fprintf(stderr, "%d check(s) failed\n", ts_failures);
    return 1;
  }
  printf("test_output_errors: all checks passed\n");
  return 0;
}
