/* A small C API for embedding rollsim (the Python package postproc/rollsim calls it through
 * ctypes): each call does what the command line does with the same case file and --set
 * assignments, writes the same netCDF file, and reports errors with the same message. No
 * state is kept between calls (nothing global: two calls are independent). */
#ifndef ROLLSIM_API_H
#define ROLLSIM_API_H

#include <stddef.h>

/* rollsim run CASE [--set ...] -o OUT. Returns the status (base/status.h: 0 ok, 2 invalid
 * input, 3 solver failure, 4 interrupted, 1 internal, 5 output); on failure msg holds the
 * command line's message. A case with profiles: is refused (2): its run writes one file per
 * contact patch, the command line's. */
int rs_api_run(const char *case_path, const char *const *sets, int nsets, const char *out_path,
               char *msg, size_t msg_len);
/* rollsim sweep CASE [--set ...] -o OUT (on profiles: a path of wheelset positions, its
 * progress called once at the end). */
int rs_api_sweep(const char *case_path, const char *const *sets, int nsets, const char *out_path,
                 char *msg, size_t msg_len);
/* rs_api_sweep with progress(ctx, points done, points in all) after every point (the
 * points are solved line by line as by rollsim sweep --part 1/1: the same numbers). */
typedef void (*rs_api_progress_fn)(void *ctx, size_t done, size_t total);
int rs_api_sweep_progress(const char *case_path, const char *const *sets, int nsets,
                          const char *out_path, rs_api_progress_fn progress, void *ctx, char *msg,
                          size_t msg_len);
/* rollsim check CASE [--set ...]: the resolved and derived values as the command prints
 * them ("key: value  # unit" lines), in *text (free with rs_api_free). */
int rs_api_check(const char *case_path, const char *const *sets, int nsets, char **text, char *msg,
                 size_t msg_len);
/* rollsim status FILE.nc: "key: value" lines in *text (free with rs_api_free): state
 * (complete, incomplete, failed, or "not a sweep"), points, written, failed, part,
 * parts, status (the attribute), last_written (ISO 8601, UTC) and summary (the line
 * rollsim status prints). 2 (message in msg) for a file that cannot be read or is
 * truncated. */
int rs_api_status(const char *path, char **text, char *msg, size_t msg_len);
void rs_api_free(void *p);
/* "rollsim <version>" */
const char *rs_api_version(void);

#endif
