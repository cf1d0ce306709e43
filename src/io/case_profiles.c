/* The profiles: block (docs/case-file.md "Wheel-rail profiles"): the rail and wheel
 * profile files (io/profile.h), their options and the track and wheelset geometry. Read
 * by rs_case_load; `rollsim check` prints a summary, the other commands refuse such a
 * case until the wheel-rail contact search exists. */
#define _POSIX_C_SOURCE 200809L
#include "io/case_internal.h"
#include "io/profile.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *const profile_keys[] = {"rail",
                                           "wheel",
                                           "rail_mirror",
                                           "wheel_mirror",
                                           "scale",
                                           "smoothing",
                                           "rail_inclination",
                                           "track_gauge",
                                           "gauge_height",
                                           "flange_back_distance",
                                           "nominal_rolling_radius",
                                           NULL};

static const yaml_node_t *profiles_node(const rs_case_doc *d)
{
  yaml_node_t *root = rs_case_doc_root((rs_case_doc *)d);
  return root ? rs_case_lookup(d, root, "profiles") : NULL;
}

/* A number key of the block within [lo, hi]; absent or null keeps *x. */
static int number_key(const rs_case_doc *d, const yaml_node_t *map, const char *name, double lo,
                      double hi, const char *unit, double *x)
{
  char key[64];
  snprintf(key, sizeof key, "profiles.%s", name);
  const yaml_node_t *n = rs_case_lookup(d, map, name);
  if (!n || rs_case_is_null(n)) return RS_OK;
  int status = rs_case_number(d, n, key, x);
  if (status == RS_OK && !(*x >= lo && *x <= hi))
    status = rs_case_error(d, n, key, "%g %s is outside [%g, %g] %s", *x, unit, lo, hi, unit);
  return status;
}

static int bool_key(const rs_case_doc *d, const yaml_node_t *map, const char *name, int *x)
{
  static const char *const names[] = {"false", "true", NULL};
  char key[64];
  snprintf(key, sizeof key, "profiles.%s", name);
  const yaml_node_t *n = rs_case_lookup(d, map, name);
  if (!n || rs_case_is_null(n)) return RS_OK;
  return rs_case_choice(d, n, key, names, x);
}

/* rail_inclination: an angle in rad, or a slope "1:N" (the angle atan(1/N)). */
static int inclination_key(const rs_case_doc *d, const yaml_node_t *map, double *x)
{
  const char *key = "profiles.rail_inclination";
  const yaml_node_t *n = rs_case_lookup(d, map, "rail_inclination");
  if (!n || rs_case_is_null(n)) return RS_OK;
  if (n->type == YAML_SCALAR_NODE && strchr((const char *)n->data.scalar.value, ':')) {
    const char *s = (const char *)n->data.scalar.value;
    char *end;
    double slope = 0.0;
    if (!strncmp(s, "1:", 2)) slope = strtod(s + 2, &end);
    if (strncmp(s, "1:", 2) || end == s + 2 || *end || !(slope >= 10.0 && slope <= 1e6))
      return rs_case_error(
          d, n, key, "expected an angle in rad or a slope \"1:N\" with N >= 10, got \"%.40s\"", s);
    *x = atan(1.0 / slope);
    return RS_OK;
  }
  int status = rs_case_number(d, n, key, x);
  if (status == RS_OK && !(*x >= -0.1 && *x <= 0.1))
    status = rs_case_error(d, n, key, "%g rad is outside [-0.1, 0.1] rad (1:10 is 0.0997 rad)", *x);
  return status;
}

/* One profile file: its path relative to the case file, read with the block's options. */
static int profile_key(const rs_case_doc *d, const yaml_node_t *map, const char *name,
                       const rs_profile_opts *o, int *has, rs_profile *p, char **file)
{
  char key[64], got[96];
  snprintf(key, sizeof key, "profiles.%s", name);
  const yaml_node_t *n = rs_case_lookup(d, map, name);
  if (!n || rs_case_is_null(n)) return RS_OK;
  if (n->type != YAML_SCALAR_NODE)
    return rs_case_error(d, n, key, "expected a profile file name, got %s",
                         rs_case_describe(n, got, sizeof got));
  const char *fname = (const char *)n->data.scalar.value;
  size_t len = strlen(d->dir) + strlen(fname) + 1;
  if (!(*file = malloc(len))) return rs_msg_set(d->msg, RS_ERR_INTERNAL, "out of memory");
  snprintf(*file, len, "%s%s", fname[0] == '/' ? "" : d->dir, fname);
  rs_msg pm = {{0}};
  int status = rs_profile_read(p, *file, o, &pm);
  if (status == RS_ERR_INPUT) return rs_case_error(d, n, key, "%s", pm.text);
  if (status != RS_OK) return rs_msg_set(d->msg, status, "%s", pm.text);
  *has = 1;
  return RS_OK;
}

int rs_case_profiles_read(const rs_case_doc *d, struct rs_wheel_rail **out)
{
  *out = NULL;
  const yaml_node_t *map = profiles_node(d);
  if (!map) return RS_OK;
  int status = rs_case_check_mapping(d, map, "profiles", profile_keys);
  if (status != RS_OK) return status;
  rs_wheel_rail *w = calloc(1, sizeof *w);
  if (!w) return rs_msg_set(d->msg, RS_ERR_INTERNAL, "out of memory");
  /* standard gauge and a common wheelset (docs/case-file.md) */
  w->track_gauge = 1435.0;
  w->gauge_height = 14.0;
  w->flange_back_distance = 1360.0;
  w->nominal_rolling_radius = 460.0;
  rs_profile_opts ro = {.scale = 1.0}, wo = {.scale = 1.0};
  double scale = 1.0, smoothing = 0.0;
  status = number_key(d, map, "scale", 1e-6, 1e6, "", &scale);
  if (status == RS_OK) status = number_key(d, map, "smoothing", 0.0, 100.0, "mm", &smoothing);
  if (status == RS_OK) status = bool_key(d, map, "rail_mirror", &ro.mirror);
  if (status == RS_OK) status = bool_key(d, map, "wheel_mirror", &wo.mirror);
  if (status == RS_OK) status = inclination_key(d, map, &w->rail_inclination);
  if (status == RS_OK)
    status = number_key(d, map, "track_gauge", 500.0, 2500.0, "mm", &w->track_gauge);
  if (status == RS_OK)
    status = number_key(d, map, "gauge_height", 0.0, 50.0, "mm", &w->gauge_height);
  if (status == RS_OK)
    status =
        number_key(d, map, "flange_back_distance", 400.0, 2500.0, "mm", &w->flange_back_distance);
  if (status == RS_OK)
    status = number_key(d, map, "nominal_rolling_radius", 50.0, 2000.0, "mm",
                        &w->nominal_rolling_radius);
  ro.scale = wo.scale = scale;
  ro.smoothing = wo.smoothing = smoothing;
  if (status == RS_OK)
    status = profile_key(d, map, "rail", &ro, &w->has_rail, &w->rail, &w->rail_file);
  if (status == RS_OK)
    status = profile_key(d, map, "wheel", &wo, &w->has_wheel, &w->wheel, &w->wheel_file);
  if (status == RS_OK && !w->has_rail && !w->has_wheel)
    status = rs_case_error(d, map, "profiles", "names no profile: give rail: FILE, wheel: FILE");
  if (status != RS_OK) {
    rs_wheel_rail_free(w);
    return status;
  }
  *out = w;
  return RS_OK;
}

/* The rail as placed: rotated about its origin by the inclination, its top sloping down
 * toward the track centre (y toward the centre, z downward). */
static void place_rail(const rs_profile *p, double theta, size_t i, double *y, double *z)
{
  *y = p->y[i] * cos(theta) - p->z[i] * sin(theta);
  *z = p->y[i] * sin(theta) + p->z[i] * cos(theta);
}

/* Lateral positions where the polyline (y[i], z[i]) crosses the level z = h: the largest
 * (the gauge point of a rail, y toward the centre), or, going up a flange, the first
 * crossing downward past y0 and the next one upward (its front and back faces). */
static int crossings(const double *y, const double *z, size_t n, double h, double y0, double *front,
                     double *back)
{
  int found = 0;
  for (size_t i = 0; i + 1 < n; i++) {
    const double a = z[i] - h, b = z[i + 1] - h;
    if ((a < 0) == (b < 0) || a == b) continue;
    const double yc = y[i] + (y[i + 1] - y[i]) * a / (a - b);
    if (yc < y0) continue;
    if (!found && b > a) {
      *front = yc;
      found = 1;
    } else if (found == 1 && b < a) {
      *back = yc;
      return 2;
    }
  }
  return found;
}

void rs_case_print_profiles(const rs_case *c, FILE *out)
{
  const rs_wheel_rail *w = c->profiles;
  if (!w) return;
  double yr[2], zr[2];
  fprintf(out, "# profiles: y lateral toward the track centre, z downward, mm\n");
  if (w->has_rail) {
    const rs_profile *p = &w->rail;
    rs_profile_range(p, yr, zr);
    fprintf(out, "profiles.rail: %s  # %s, %zu points, y %.3f .. %.3f, z %.3f .. %.3f\n",
            w->rail_file, rs_profile_format_name(p->format), p->n, yr[0], yr[1], zr[0], zr[1]);
    double *py = malloc(p->n * sizeof *py), *pz = malloc(p->n * sizeof *pz);
    if (py && pz) {
      double top = INFINITY;
      for (size_t i = 0; i < p->n; i++) {
        place_rail(p, w->rail_inclination, i, &py[i], &pz[i]);
        top = fmin(top, pz[i]);
      }
      double gauge = NAN;
      for (size_t i = 0; i + 1 < p->n; i++) { /* the innermost crossing of the gauge level */
        const double h = top + w->gauge_height, a = pz[i] - h, b = pz[i + 1] - h;
        if ((a < 0) == (b < 0) || a == b) continue;
        const double yc = py[i] + (py[i + 1] - py[i]) * a / (a - b);
        if (isnan(gauge) || yc > gauge) gauge = yc;
      }
      rs_profile pl = {.n = p->n, .y = py, .z = pz};
      rs_profile_range(&pl, yr, zr);
      char slope[32] = "none";
      if (w->rail_inclination != 0.0)
        snprintf(slope, sizeof slope, "1:%.4g", 1.0 / tan(fabs(w->rail_inclination)));
      fprintf(out,
              "profiles.rail_inclination: %.9g  # rad (%s); the rail inclined: y %.3f .. %.3f, "
              "z %.3f .. %.3f\n",
              w->rail_inclination, slope, yr[0], yr[1], zr[0], zr[1]);
      if (isnan(gauge))
        fprintf(out, "# rail gauge point: none (the profile does not reach %g mm below its top)\n",
                w->gauge_height);
      else
        fprintf(out, "# rail gauge point: y = %.3f mm, %g mm below the rail's top (z = %.3f)\n",
                gauge, w->gauge_height, top);
    }
    free(py);
    free(pz);
  }
  if (w->has_wheel) {
    const rs_profile *p = &w->wheel;
    rs_profile_range(p, yr, zr);
    fprintf(out, "profiles.wheel: %s  # %s, %zu points, y %.3f .. %.3f, z %.3f .. %.3f\n",
            w->wheel_file, rs_profile_format_name(p->format), p->n, yr[0], yr[1], zr[0], zr[1]);
    double z0, front = NAN, back = NAN;
    if (rs_profile_z_at(p, 0.0, &z0)) {
      fprintf(out, "# wheel flange height: %.3f mm (its lowest point below the profile at y = 0)\n",
              zr[1] - z0);
      if (crossings(p->y, p->z, p->n, z0 + 10.0, 0.0, &front, &back) == 2)
        fprintf(out, "# wheel flange thickness: %.3f mm (10 mm below the profile at y = 0)\n",
                back - front);
      else
        fprintf(out, "# wheel flange thickness: not measured (the profile does not reach the "
                     "back of the flange 10 mm below y = 0)\n");
    } else {
      fprintf(out, "# wheel flange: not measured (the profile does not span y = 0)\n");
    }
  }
  fprintf(out, "profiles.track_gauge: %g  # mm\n", w->track_gauge);
  fprintf(out, "profiles.gauge_height: %g  # mm\n", w->gauge_height);
  fprintf(out, "profiles.flange_back_distance: %g  # mm\n", w->flange_back_distance);
  fprintf(out, "profiles.nominal_rolling_radius: %g  # mm\n", w->nominal_rolling_radius);
  fprintf(out, "# profiles read and checked; the wheel-rail contact search is not available "
               "yet, so run, sweep and fit refuse this case\n");
}
