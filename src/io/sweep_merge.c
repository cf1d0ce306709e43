/* rollsim merge (io/sweep_merge.h): the parts of a sweep written by rollsim sweep
 * --part K/N joined into one sweep file. Each part has the full sweep's shape, with the
 * points of its lines written (`converged` 0 or 1) and the others unwritten (netCDF's
 * default fill). The merged file is made by the sweep writer itself (same layout as a
 * serial sweep's) and every point copied from the part that computed it. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <netcdf.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/output_internal.h"
#include "io/case.h"
#include "io/output.h"
#include "io/sweep_merge.h"

typedef struct part_file {
  const char *path;
  int ncid, part, parts;
  char *case_text;
} part_file;

static const char *const scalar_names[] = {
    "Fx",     "Fn",        "creepage",         "velocity",      "n_exterior",     "n_adhesion",
    "n_slip", "n_plastic", "frictional_power", "plastic_power", "elastic_energy", "converged"};
/* regime (index 6) is bytes; mu (7) only with a velocity-dependent friction law */
static const char *const field_names[] = {"px",    "pn",   "slip",   "upl",
                                          "ustar", "tauc", "regime", "mu"};
static const unsigned field_bits[] = {RS_FIELD_PX,    RS_FIELD_PN,   RS_FIELD_SLIP,   RS_FIELD_UPL,
                                      RS_FIELD_USTAR, RS_FIELD_TAUC, RS_FIELD_REGIME, RS_FIELD_MU};
#define N_MERGE_FIELDS 8

static int open_part(part_file *p, rs_msg *msg)
{
  int err = nc_open(p->path, NC_NOWRITE, &p->ncid);
  if (err) return rs_msg_set(msg, RS_ERR_INPUT, "%s: cannot open: %s", p->path, nc_strerror(err));
  if (nc_get_att_int(p->ncid, NC_GLOBAL, "part", &p->part) ||
      nc_get_att_int(p->ncid, NC_GLOBAL, "parts", &p->parts))
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "%s: not a sweep part (no part/parts attributes: written by rollsim sweep "
                      "--part K/N)",
                      p->path);
  p->case_text = rs_output_get_text(p->ncid, NC_GLOBAL, "case");
  return p->case_text ? RS_OK : rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
}

int rs_sweep_merge(const char *out_path, const char *const *paths, int nparts, const char *history,
                   rs_sweep_merge_result *res, rs_msg *msg)
{
  memset(res, 0, sizeof *res);
  part_file *p = calloc((size_t)nparts, sizeof *p);
  if (!p) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  int status = RS_OK;
  for (int i = 0; i < nparts; i++) {
    p[i].path = paths[i];
    p[i].ncid = -1;
  }
  for (int i = 0; i < nparts && status == RS_OK; i++) status = open_part(&p[i], msg);
  const int N = status == RS_OK ? p[0].parts : 0;
  for (int i = 1; i < nparts && status == RS_OK; i++) {
    if (strcmp(p[i].case_text, p[0].case_text))
      status = rs_msg_set(msg, RS_ERR_INPUT,
                          "%s: a part of another case than %s (case attributes "
                          "differ)",
                          p[i].path, p[0].path);
    else if (p[i].parts != N)
      status = rs_msg_set(msg, RS_ERR_INPUT, "%s: part %d/%d, but %s is part %d/%d", p[i].path,
                          p[i].part, p[i].parts, p[0].path, p[0].part, N);
    for (int j = 0; j < i && status == RS_OK; j++)
      if (p[j].part == p[i].part)
        status = rs_msg_set(msg, RS_ERR_INPUT, "part %d/%d given twice: %s and %s", p[i].part, N,
                            p[j].path, p[i].path);
  }
  /* The layout, from the first part. */
  int ncid = status == RS_OK ? p[0].ncid : -1, fx_id = -1, naxes = 0, dims[NC_MAX_VAR_DIMS];
  char keys[NC_MAX_VAR_DIMS][NC_MAX_NAME + 1];
  const char *key_ptrs[NC_MAX_VAR_DIMS];
  int sizes[NC_MAX_VAR_DIMS];
  double *values[NC_MAX_VAR_DIMS] = {0};
  size_t npoints = 1, nx = 0;
  double *x = NULL;
  unsigned fields = 0;
  char *title = NULL, *case_text = NULL, units[64] = "";
  if (status == RS_OK &&
      (nc_inq_varid(ncid, "Fx", &fx_id) || nc_inq_varndims(ncid, fx_id, &naxes) ||
       nc_inq_vardimid(ncid, fx_id, dims)))
    status = rs_msg_set(msg, RS_ERR_INPUT, "%s: not a sweep file (no Fx)", p[0].path);
  for (int a = 0; status == RS_OK && a < naxes; a++) {
    size_t len;
    int cid;
    char name[NC_MAX_NAME + 1];
    nc_inq_dim(ncid, dims[a], name, &len);
    sizes[a] = (int)len;
    npoints *= len;
    values[a] = malloc(len * sizeof *values[a]);
    if (!values[a] || nc_inq_varid(ncid, name, &cid) || nc_get_var_double(ncid, cid, values[a]))
      status = rs_msg_set(msg, RS_ERR_INPUT, "%s: no coordinate variable %s", p[0].path, name);
    size_t klen = 0;
    if (status == RS_OK && (nc_inq_attlen(ncid, cid, "key", &klen) || klen > NC_MAX_NAME ||
                            nc_get_att_text(ncid, cid, "key", keys[a])))
      status = rs_msg_set(msg, RS_ERR_INPUT, "%s: %s has no key attribute", p[0].path, name);
    if (status == RS_OK) keys[a][klen] = '\0';
    key_ptrs[a] = keys[a];
  }
  for (int f = 0; status == RS_OK && f < N_MERGE_FIELDS; f++) {
    int id;
    if (nc_inq_varid(ncid, field_names[f], &id) == NC_NOERR) fields |= field_bits[f];
  }
  if (status == RS_OK && fields) {
    int xd, xid;
    if (nc_inq_dimid(ncid, "x", &xd) || nc_inq_dimlen(ncid, xd, &nx) ||
        nc_inq_varid(ncid, "x", &xid) || !(x = malloc(nx * sizeof *x)) ||
        nc_get_var_double(ncid, xid, x))
      status = rs_msg_set(msg, RS_ERR_INPUT, "%s: profiles without an x axis", p[0].path);
  }
  if (status == RS_OK) {
    title = rs_output_get_text(ncid, NC_GLOBAL, "title");
    case_text = rs_output_get_text(ncid, NC_GLOBAL, "case");
    nc_get_att_text(ncid, fx_id, "units", units);
    if (!title || !case_text) status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  }
  /* Owner of every point: the part whose `converged` is written there. */
  int *owner = status == RS_OK ? malloc(npoints * sizeof *owner) : NULL;
  int *conv = status == RS_OK ? malloc(npoints * sizeof *conv) : NULL;
  if (status == RS_OK && (!owner || !conv))
    status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  for (size_t k = 0; status == RS_OK && k < npoints; k++) owner[k] = -1;
  for (int i = 0; status == RS_OK && i < nparts; i++) {
    int cid;
    if (nc_inq_varid(p[i].ncid, "converged", &cid) || nc_get_var_int(p[i].ncid, cid, conv))
      status = rs_msg_set(msg, RS_ERR_INPUT, "%s: no converged variable", p[i].path);
    for (size_t k = 0; status == RS_OK && k < npoints; k++)
      if (conv[k] != NC_FILL_INT) {
        if (owner[k] >= 0)
          status = rs_msg_set(msg, RS_ERR_INPUT, "point %zu is in %s and in %s", k,
                              p[owner[k]].path, p[i].path);
        owner[k] = i;
      }
  }
  /* Coverage: name the missing points (their swept values), at most 8. */
  if (status == RS_OK) {
    size_t missing = 0, len = 0;
    char list[RS_MSG_LEN / 2] = "";
    for (size_t k = 0; k < npoints; k++) {
      if (owner[k] >= 0) continue;
      if (missing++ < 8 && len < sizeof list) {
        size_t rest = k, idx[NC_MAX_VAR_DIMS];
        for (int a = naxes - 1; a >= 0; a--) {
          idx[a] = rest % (size_t)sizes[a];
          rest /= (size_t)sizes[a];
        }
        len += (size_t)snprintf(list + len, sizeof list - len, "\n  point %zu (part %zu/%d):", k,
                                (k / (size_t)sizes[naxes - 1]) % (size_t)N + 1, N);
        for (int a = 0; a < naxes && len < sizeof list; a++)
          len += (size_t)snprintf(list + len, sizeof list - len, " %s=%.10g", keys[a],
                                  values[a][idx[a]]);
      }
    }
    if (missing) {
      char given[256] = "";
      size_t gl = 0;
      for (int i = 0; i < nparts && gl < sizeof given; i++)
        gl += (size_t)snprintf(given + gl, sizeof given - gl, "%s%d", i ? ", " : "", p[i].part);
      status = rs_msg_set(msg, RS_ERR_INPUT,
                          "the parts do not cover the sweep: %zu of %zu points missing (parts "
                          "given: %s of %d)%s%s",
                          missing, npoints, given, N, list, missing > 8 ? "\n  ..." : "");
    }
  }
  /* Write: the serial sweep's layout, every point from its owner. */
  rs_sweep_output *out = NULL;
  int err_vid;
  const int with_errors =
      status == RS_OK && nc_inq_varid(p[0].ncid, "error_reliable", &err_vid) == NC_NOERR;
  if (status == RS_OK) {
    int t_id; /* T_max: the parts carry the surface temperature */
    const int temperature = nc_inq_varid(ncid, "T_max", &t_id) == NC_NOERR;
    const rs_sweep_output_spec spec = {.path = out_path,
                                       .error_estimate = with_errors,
                                       .title = title,
                                       .case_text = case_text,
                                       .history = history,
                                       .dimension = strcmp(units, "N") ? 2 : 3,
                                       .naxes = naxes,
                                       .keys = key_ptrs,
                                       .sizes = sizes,
                                       .values = (const double *const *)values,
                                       .fields = fields,
                                       .nx = nx,
                                       .x = x,
                                       .temperature = temperature};
    status = rs_sweep_output_create(&out, &spec, msg);
    if (status == RS_OK && rs_sweep_output_backup(out))
      snprintf(res->backup, sizeof res->backup, "%s", rs_sweep_output_backup(out));
  }
  double *rows = status == RS_OK && nx ? malloc(N_MERGE_FIELDS * nx * sizeof *rows) : NULL;
  signed char *regime = status == RS_OK && nx ? malloc(nx) : NULL;
  if (status == RS_OK && nx && (!rows || !regime))
    status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  for (size_t k = 0; status == RS_OK && k < npoints; k++) {
    const int id = p[owner[k]].ncid;
    size_t start[NC_MAX_VAR_DIMS + 1], count[NC_MAX_VAR_DIMS + 1], rest = k;
    for (int a = naxes - 1; a >= 0; a--) {
      start[a] = rest % (size_t)sizes[a];
      count[a] = 1;
      rest /= (size_t)sizes[a];
    }
    start[naxes] = 0;
    count[naxes] = nx;
    double d[12];
    int err = 0;
    for (int v = 0; v < 12 && !err; v++) {
      int vid;
      err = nc_inq_varid(id, scalar_names[v], &vid);
      if (!err) err = nc_get_var1_double(id, vid, start, &d[v]);
    }
    rs_sweep_point pt = {.Fx = d[0],
                         .Fn = d[1],
                         .creepage = d[2],
                         .velocity = d[3],
                         .n_exterior = (int)d[4],
                         .n_adhesion = (int)d[5],
                         .n_slip = (int)d[6],
                         .n_plastic = (int)d[7],
                         .frictional_power = d[8],
                         .plastic_power = d[9],
                         .elastic_energy = d[10],
                         .converged = (int)d[11]};
    if (!err && fields && pt.converged) {
      const double **dst[N_MERGE_FIELDS] = {&pt.px,    &pt.pn,   &pt.slip, &pt.upl,
                                            &pt.ustar, &pt.tauc, NULL,     &pt.mu};
      for (int f = 0; f < N_MERGE_FIELDS && !err; f++) {
        int vid;
        if (!(fields & field_bits[f])) continue;
        err = nc_inq_varid(id, field_names[f], &vid);
        if (!err && f == 6) {
          err = nc_get_vara_schar(id, vid, start, count, regime);
          pt.regime = regime;
        } else if (!err) {
          err = nc_get_vara_double(id, vid, start, count, rows + (size_t)f * nx);
          *dst[f] = rows + (size_t)f * nx;
        }
      }
    }
    /* 3D: the lateral force, spin moment, the two creepages and the Hertz semi-axes
     * (absent in 2D files; the semi-axes NaN from parts written without them) */
    static const char *const names3d[6] = {"Fy",   "Mz",      "lateral_creepage",
                                           "spin", "hertz_a", "hertz_b"};
    double *dst3[6] = {&pt.Fy, &pt.Mz, &pt.lateral_creepage, &pt.spin, &pt.hertz_a, &pt.hertz_b};
    pt.hertz_a = pt.hertz_b = NAN;
    for (int v = 0; v < 6 && !err; v++) {
      int vid;
      if (nc_inq_varid(id, names3d[v], &vid) == NC_NOERR)
        err = nc_get_var1_double(id, vid, start, dst3[v]);
    }
    /* surface temperature (a temperature: block; the parts are of one case) */
    static const char *const names_t[3] = {"T_max", "heat_input_1", "heat_input_2"};
    double *dst_t[3] = {&pt.T_max, &pt.heat_input_1, &pt.heat_input_2};
    for (int v = 0; v < 3 && !err; v++) {
      int vid;
      if (nc_inq_varid(id, names_t[v], &vid) == NC_NOERR)
        err = nc_get_var1_double(id, vid, start, dst_t[v]);
    }
    /* the error estimates and extrapolated forces (steady sweeps; F_y and M_z in 3D; parts
     * written before the extrapolated variables existed have none) */
    static const char *const names_err[6] = {"Fx_error",        "Fy_error",
                                             "Mz_error",        "Fx_extrapolated",
                                             "Fy_extrapolated", "Mz_extrapolated"};
    double *dst_err[6] = {&pt.Fx_error,        &pt.Fy_error,        &pt.Mz_error,
                          &pt.Fx_extrapolated, &pt.Fy_extrapolated, &pt.Mz_extrapolated};
    pt.Fx_error = pt.Fy_error = pt.Mz_error = NAN;
    pt.Fx_extrapolated = pt.Fy_extrapolated = pt.Mz_extrapolated = NAN;
    pt.error_reliable = -1;
    for (int v = 0; v < 6 && with_errors && !err; v++) {
      int vid;
      if (nc_inq_varid(id, names_err[v], &vid) == NC_NOERR)
        err = nc_get_var1_double(id, vid, start, dst_err[v]);
    }
    if (with_errors && !err && nc_inq_varid(id, "error_reliable", &err_vid) == NC_NOERR)
      err = nc_get_var1_int(id, err_vid, start, &pt.error_reliable);
    if (err)
      status =
          rs_msg_set(msg, RS_ERR_INPUT, "%s: point %zu: %s", p[owner[k]].path, k, nc_strerror(err));
    else
      status = rs_sweep_output_write(out, k, &pt, msg);
    if (status == RS_OK) {
      if (pt.converged)
        res->points_done++;
      else
        res->points_failed++;
    }
  }
  if (out) {
    rs_msg tmp;
    char why[256] = "complete";
    if (status != RS_OK)
      snprintf(why, sizeof why, "failed: merge");
    else if (res->points_failed > 0) /* as the serial sweep says it */
      snprintf(why, sizeof why,
               "failed: %zu of %zu sweep points did not converge (NaN in the file)",
               res->points_failed, npoints);
    const int cs = rs_sweep_output_close(out, why, status == RS_OK ? msg : &tmp);
    if (status == RS_OK) status = cs;
    if (status != RS_OK) remove(out_path);
  }
  res->npoints = npoints;
  res->parts = N;
  for (int i = 0; i < nparts; i++) {
    if (p[i].ncid >= 0) nc_close(p[i].ncid);
    free(p[i].case_text);
  }
  for (int a = 0; a < naxes; a++) free(values[a]);
  free(p);
  free(x);
  free(title);
  free(case_text);
  free(owner);
  free(conv);
  free(rows);
  free(regime);
  return status;
}
