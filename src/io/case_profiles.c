/* The profiles: block (docs/case-file.md "Wheel-rail profiles"): the rail and wheel
 * profile files (io/profile.h), their options and the track and wheelset geometry. Read
 * by rs_case_load; `rollsim check` prints a summary (and study/wheel_rail.c the contact),
 * the other commands refuse such a case until runs on profiles exist. */
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
                                           "flange_back_position",
                                           "lateral_displacement",
                                           "vertical_load",
                                           "patch_separation",
                                           "grid_cells",
                                           "yaw",
                                           "wheel_angular_velocity",
                                           NULL};

static void place_rail(const rs_profile *p, double theta, size_t i, double *y, double *z);

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

/* grid_cells: two whole numbers [along x, along s] within [4, 400]. */
static int cells_key(const rs_case_doc *d, const yaml_node_t *map, int cells[2])
{
  const char *key = "profiles.grid_cells";
  const yaml_node_t *n = rs_case_lookup(d, map, "grid_cells");
  if (!n || rs_case_is_null(n)) return RS_OK;
  char got[96];
  if (n->type != YAML_SEQUENCE_NODE ||
      n->data.sequence.items.top - n->data.sequence.items.start != 2)
    return rs_case_error(d, n, key, "expected two numbers of cells [along x, along s], got %s",
                         rs_case_describe(n, got, sizeof got));
  for (int k = 0; k < 2; k++) {
    const yaml_node_t *e =
        yaml_document_get_node((yaml_document_t *)&d->doc, n->data.sequence.items.start[k]);
    double x;
    int status = rs_case_number(d, e, key, &x);
    if (status != RS_OK) return status;
    if (!(x >= 4 && x <= 400 && x == floor(x)))
      return rs_case_error(d, e, key, "%g cells: expected a whole number in [4, 400]", x);
    cells[k] = (int)x;
  }
  return RS_OK;
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

int rs_wheel_rail_input(const rs_wheel_rail *w, rs_wr_input *in, rs_msg *msg)
{
  if (!w->has_rail || !w->has_wheel || !w->placed)
    return rs_msg_set(msg, RS_ERR_INPUT, "the contact needs both profiles: rail: and wheel:");
  const size_t n = w->rail.n;
  const rs_wr_polyline rail = {n, w->placed, w->placed + n};
  double yg;
  if (!rs_wr_gauge_point(&rail, w->gauge_height, &yg))
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "the rail does not reach %g mm below its top (gauge_height), "
                      "where its gauge point is placed",
                      w->gauge_height);
  /* track y of a point of the rail profile: gauge/2 + yg - y_rail from the centre; of the
   * wheel profile: fb/2 + fbpos - y_wheel - dy (dy > 0 moves the wheel outward, toward
   * this rail's gauge face); both in the rail profile's coordinates: */
  double z0 = 0.0;
  rs_profile_z_at(&w->wheel, 0.0, &z0);
  *in = (rs_wr_input){.rail = rail,
                      .wheel = {w->wheel.n, w->wheel.y, w->wheel.z},
                      .wheel_shift = 0.5 * w->track_gauge + yg - 0.5 * w->flange_back_distance -
                                     w->flange_back_position - w->lateral_displacement,
                      .nominal_radius = w->nominal_rolling_radius,
                      .wheel_z0 = z0,
                      .separation = w->patch_separation,
                      .yaw = w->yaw,
                      .axle_offset = 0.5 * w->flange_back_distance + w->flange_back_position};
  return RS_OK;
}

/* With vertical_load: both profiles, the rail inclined, and a contact the geometry finds at
 * the lateral displacement (the wheel on the rail). */
static int contact_check(const rs_case_doc *d, const yaml_node_t *map, rs_wheel_rail *w)
{
  const yaml_node_t *n = rs_case_lookup(d, map, "vertical_load");
  if (!w->has_rail || !w->has_wheel)
    return rs_case_error(d, n, "profiles.vertical_load",
                         "the contact needs both profiles: give rail: FILE and wheel: FILE");
  const size_t np = w->rail.n;
  if (!(w->placed = malloc(2 * np * sizeof *w->placed)))
    return rs_msg_set(d->msg, RS_ERR_INTERNAL, "out of memory");
  for (size_t i = 0; i < np; i++)
    place_rail(&w->rail, w->rail_inclination, i, &w->placed[i], &w->placed[np + i]);
  rs_wr_input in;
  rs_msg m = {{0}};
  int status = rs_wheel_rail_input(w, &in, &m);
  if (status == RS_OK) {
    rs_wr_geometry geo;
    status = rs_wr_geometry_build(&in, &geo, &m);
    if (status == RS_OK) rs_wr_geometry_free(&geo);
  }
  if (status == RS_ERR_INPUT) {
    const yaml_node_t *at = rs_case_lookup(d, map, "lateral_displacement");
    return rs_case_error(d, at ? at : n, at ? "profiles.lateral_displacement" : "profiles",
                         "%g mm: %s", w->lateral_displacement, m.text);
  }
  if (status != RS_OK) return rs_msg_set(d->msg, status, "%s", m.text);
  return RS_OK;
}

static const rs_wheel_rail_key position_keys[] = {
    {"lateral_displacement", "mm", -50.0, 50.0},
    {"yaw", "rad", -0.1, 0.1},
    {"wheel_angular_velocity", "rad/s", 1e-6, 1e5},
};

const rs_wheel_rail_key *rs_wheel_rail_position_key(const char *name)
{
  for (size_t k = 0; k < sizeof position_keys / sizeof *position_keys; k++)
    if (!strcmp(position_keys[k].name, name)) return &position_keys[k];
  return NULL;
}

static double *position_field(rs_wheel_rail *w, const char *name)
{
  return !strcmp(name, "lateral_displacement") ? &w->lateral_displacement
         : !strcmp(name, "yaw")                ? &w->yaw
                                               : &w->wheel_angular_velocity;
}

static rs_history *position_history(rs_wheel_rail *w, const char *name)
{
  return !strcmp(name, "lateral_displacement") ? &w->lateral_history
         : !strcmp(name, "yaw")                ? &w->yaw_history
                                               : NULL;
}

/* A position key: lateral_displacement and yaw a history (its value at t = 0 the number the
 * steady problems use), every value within the key's range; wheel_angular_velocity a number. */
static int position_key(const rs_case_doc *d, const yaml_node_t *map, const char *name,
                        rs_wheel_rail *w)
{
  const rs_wheel_rail_key *k = rs_wheel_rail_position_key(name);
  rs_history *h = position_history(w, name);
  if (!h) return number_key(d, map, name, k->lo, k->hi, k->unit, position_field(w, name));
  char key[64];
  snprintf(key, sizeof key, "profiles.%s", name);
  const yaml_node_t *n = rs_case_lookup(d, map, name);
  if (!n || rs_case_is_null(n)) {
    *h = (rs_history){.kind = RS_HISTORY_CONSTANT, .value = *position_field(w, name)};
    return RS_OK;
  }
  int status = rs_case_history(d, n, key, k->unit, h);
  /* the keys' ranges are symmetric: the largest |value| over all times bounds them */
  const double largest = status == RS_OK ? rs_history_max_abs(h, 0.0, INFINITY) : 0.0;
  if (status == RS_OK && !(largest <= k->hi))
    status = rs_case_error(d, n, key, "%g %s is outside [%g, %g] %s", largest, k->unit, k->lo,
                           k->hi, k->unit);
  if (status == RS_OK) *position_field(w, name) = rs_history_eval(h, 0.0);
  return status;
}

int rs_wheel_rail_set(rs_wheel_rail *w, const char *name, double x, rs_msg *msg)
{
  const rs_wheel_rail_key *k = rs_wheel_rail_position_key(name);
  if (!k) return rs_msg_set(msg, RS_ERR_INPUT, "not a wheelset position key");
  if (!(x >= k->lo && x <= k->hi))
    return rs_msg_set(msg, RS_ERR_INPUT, "%g %s is outside [%g, %g] %s", x, k->unit, k->lo, k->hi,
                      k->unit);
  *position_field(w, name) = x;
  rs_history *h = position_history(w, name);
  if (h) *h = (rs_history){.kind = RS_HISTORY_CONSTANT, .value = x};
  if (strcmp(name, "lateral_displacement") || !w->placed) return RS_OK;
  rs_wr_input in;
  rs_msg m = {{0}};
  int status = rs_wheel_rail_input(w, &in, &m);
  rs_wr_geometry geo;
  if (status == RS_OK && (status = rs_wr_geometry_build(&in, &geo, &m)) == RS_OK)
    rs_wr_geometry_free(&geo);
  return status == RS_OK ? RS_OK : rs_msg_set(msg, status, "%g mm: %s", x, m.text);
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
  w->flange_back_position = 70.0; /* S1002 and the UIC wheels: tape circle to flange back */
  w->patch_separation = 0.01;
  w->grid_cells[0] = w->grid_cells[1] = 40;
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
  if (status == RS_OK)
    status =
        number_key(d, map, "flange_back_position", -200.0, 200.0, "mm", &w->flange_back_position);
  if (status == RS_OK) status = position_key(d, map, "lateral_displacement", w);
  if (status == RS_OK)
    status = number_key(d, map, "vertical_load", 1e-3, 1e7, "N", &w->vertical_load);
  if (status == RS_OK)
    status = number_key(d, map, "patch_separation", 0.0, 10.0, "mm", &w->patch_separation);
  if (status == RS_OK) status = cells_key(d, map, w->grid_cells);
  if (status == RS_OK) status = position_key(d, map, "yaw", w);
  if (status == RS_OK) status = position_key(d, map, "wheel_angular_velocity", w);
  ro.scale = wo.scale = scale;
  ro.smoothing = wo.smoothing = smoothing;
  if (status == RS_OK)
    status = profile_key(d, map, "rail", &ro, &w->has_rail, &w->rail, &w->rail_file);
  if (status == RS_OK)
    status = profile_key(d, map, "wheel", &wo, &w->has_wheel, &w->wheel, &w->wheel_file);
  if (status == RS_OK && !w->has_rail && !w->has_wheel)
    status = rs_case_error(d, map, "profiles", "names no profile: give rail: FILE, wheel: FILE");
  if (status == RS_OK && w->vertical_load > 0) status = contact_check(d, map, w);
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
  fprintf(out, "profiles.flange_back_position: %g  # mm\n", w->flange_back_position);
  fprintf(out, "profiles.lateral_displacement: %g  # mm, toward this rail%s\n",
          w->lateral_displacement,
          rs_history_is_constant(&w->lateral_history) ? "" : " (at t = 0; a history)");
  if (w->vertical_load > 0) fprintf(out, "profiles.vertical_load: %g  # N\n", w->vertical_load);
  fprintf(out, "profiles.patch_separation: %g  # mm\n", w->patch_separation);
  fprintf(out, "profiles.grid_cells: [%d, %d]\n", w->grid_cells[0], w->grid_cells[1]);
  fprintf(out, "profiles.yaw: %g  # rad%s\n", w->yaw,
          rs_history_is_constant(&w->yaw_history) ? "" : " (at t = 0; a history)");
  if (w->wheel_angular_velocity > 0)
    fprintf(out, "profiles.wheel_angular_velocity: %.9g  # rad/s\n", w->wheel_angular_velocity);
  else
    fprintf(out, "profiles.wheel_angular_velocity: null  # pure rolling of the nominal radius\n");
  fprintf(out,
          "# profiles read and checked; %s; rollsim run runs each patch, rollsim sweep a path "
          "of wheelset positions (sweep: profiles.lateral_displacement, yaw, "
          "wheel_angular_velocity); fits on profiles are not built yet\n",
          w->vertical_load > 0 ? "the steady problem per patch follows"
                               : "give vertical_load for the contact patches");
}
