/* Wheel and rail profile files (docs/case-file.md "Wheel-rail profiles"):
 *   table     two numbers "y z" (or "y, z") a line; # comments, blank lines
 *   SIMPACK   .prr/.prw: '!' comments, the points between point.begin and point.end (y z
 *             [weight]), lengths in the unit of units.len.f (the unit's size per metre)
 *   Miniprof  .ban/.whl: a header up to the first blank line, then "X Y [more columns]"
 *             a line, a leading '"' ignored
 * Tables and SIMPACK files give z as a function of y (y strictly monotone); a Miniprof
 * file is a measured polyline (it may have vertical parts, e.g. the back of a flange)
 * that must not cross itself. */
#define _POSIX_C_SOURCE 200809L
#include "io/profile.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

/* The points as read, with the line each came from. */
typedef struct raw_points {
  size_t n, cap;
  double *y, *z;
  size_t *line;
} raw_points;

static void raw_free(raw_points *r)
{
  free(r->y);
  free(r->z);
  free(r->line);
  memset(r, 0, sizeof *r);
}

static int raw_add(raw_points *r, double y, double z, size_t line, rs_msg *msg)
{
  if (r->n == r->cap) {
    size_t cap = r->cap ? 2 * r->cap : 256;
    double *yy = realloc(r->y, cap * sizeof *yy);
    if (yy) r->y = yy;
    double *zz = yy ? realloc(r->z, cap * sizeof *zz) : NULL;
    if (zz) r->z = zz;
    size_t *ll = zz ? realloc(r->line, cap * sizeof *ll) : NULL;
    if (ll) r->line = ll;
    if (!ll) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
    r->cap = cap;
  }
  r->y[r->n] = y;
  r->z[r->n] = z;
  r->line[r->n] = line;
  r->n++;
  return RS_OK;
}

rs_profile_format rs_profile_format_of(const char *path)
{
  const char *dot = strrchr(path, '.');
  const char *slash = strrchr(path, '/');
  if (!dot || (slash && dot < slash)) return RS_PROFILE_TABLE;
  if (!strcasecmp(dot, ".prr") || !strcasecmp(dot, ".prw")) return RS_PROFILE_SIMPACK;
  if (!strcasecmp(dot, ".ban") || !strcasecmp(dot, ".whl")) return RS_PROFILE_MINIPROF;
  return RS_PROFILE_TABLE;
}

const char *rs_profile_format_name(rs_profile_format f)
{
  switch (f) {
  case RS_PROFILE_SIMPACK: return "SIMPACK";
  case RS_PROFILE_MINIPROF: return "Miniprof";
  case RS_PROFILE_TABLE: break;
  }
  return "table";
}

/* Up to `max` numbers separated by white space or one comma; the count read, or -1 when
 * something else is on the line. */
static int numbers(const char *s, double *v, int max)
{
  int n = 0;
  for (;;) {
    while (isspace((unsigned char)*s)) s++;
    if (!*s) return n;
    if (n > 0 && *s == ',') {
      s++;
      while (isspace((unsigned char)*s)) s++;
    }
    char *end;
    errno = 0;
    double x = strtod(s, &end);
    if (end == s || (*end && !isspace((unsigned char)*end) && *end != ',')) return -1;
    if (n < max) v[n] = x;
    n++;
    s = end;
  }
}

static char *trim(char *s)
{
  while (isspace((unsigned char)*s)) s++;
  size_t len = strlen(s);
  while (len > 0 && isspace((unsigned char)s[len - 1])) s[--len] = '\0';
  return s;
}

/* One data line of `what` ("y z" and what else may follow) into the points. */
static int data_line(raw_points *r, const char *path, size_t lineno, char *s, int min_cols,
                     int max_cols, const char *what, double unit, rs_msg *msg)
{
  double v[2];
  int n = numbers(s, v, 2);
  if (n < min_cols || (max_cols > 0 && n > max_cols))
    return rs_msg_set(msg, RS_ERR_INPUT, "%s:%zu: expected %s, got \"%.40s\"", path, lineno, what,
                      s);
  if (!isfinite(v[0]) || !isfinite(v[1]))
    return rs_msg_set(msg, RS_ERR_INPUT, "%s:%zu: y and z must be finite numbers, got \"%.40s\"",
                      path, lineno, s);
  return raw_add(r, v[0] * unit, v[1] * unit, lineno, msg);
}

/* The file's points (in mm when the file names its unit), by format. */
static int read_points(FILE *f, const char *path, rs_profile_format fmt, raw_points *r,
                       size_t *last_line, rs_msg *msg)
{
  char *line = NULL;
  size_t cap = 0, lineno = 0;
  int status = RS_OK;
  int in_points = 0, seen_begin = 0, seen_end = 0, in_header = 1;
  double unit = 1.0; /* file unit -> mm */
  while (status == RS_OK && getline(&line, &cap, f) >= 0) {
    lineno++;
    char *s = line;
    if (fmt == RS_PROFILE_TABLE) {
      s[strcspn(s, "#")] = '\0';
      s = trim(s);
      if (*s) status = data_line(r, path, lineno, s, 2, 2, "two numbers y z", 1.0, msg);
    } else if (fmt == RS_PROFILE_SIMPACK) {
      s[strcspn(s, "!")] = '\0';
      s = trim(s);
      if (!*s || seen_end) continue;
      if (!strcmp(s, "point.begin")) {
        in_points = seen_begin = 1;
      } else if (!strcmp(s, "point.end")) {
        if (!in_points)
          status =
              rs_msg_set(msg, RS_ERR_INPUT, "%s:%zu: point.end without point.begin", path, lineno);
        in_points = 0;
        seen_end = 1;
      } else if (in_points) {
        status = data_line(r, path, lineno, s, 2, 3, "y z [weight]", unit, msg);
      } else if (!strncmp(s, "units.len.f", 11) &&
                 (isspace((unsigned char)s[11]) || s[11] == '=')) {
        char *eq = strchr(s, '='), *end;
        double factor = eq ? strtod(eq + 1, &end) : 0.0;
        if (!eq || end == eq + 1 || !isfinite(factor) || !(factor > 0.0))
          status = rs_msg_set(msg, RS_ERR_INPUT,
                              "%s:%zu: units.len.f: expected a positive number (the length "
                              "unit's size per metre, 1000 for mm), got \"%.40s\"",
                              path, lineno, s);
        else
          unit = 1000.0 / factor;
      }
    } else { /* Miniprof */
      s = trim(s);
      if (in_header) {
        if (!*s) in_header = 0;
        continue;
      }
      if (*s == '"') s = trim(s + 1);
      if (*s) status = data_line(r, path, lineno, s, 2, 0, "numbers X Y ...", 1.0, msg);
    }
  }
  if (status == RS_OK && ferror(f))
    status =
        rs_msg_set(msg, RS_ERR_INPUT, "%s:%zu: cannot read: %s", path, lineno, strerror(errno));
  if (status == RS_OK && fmt == RS_PROFILE_SIMPACK && !seen_begin)
    status = rs_msg_set(msg, RS_ERR_INPUT,
                        "%s:%zu: no point.begin ... point.end block (a SIMPACK profile's points)",
                        path, lineno);
  else if (status == RS_OK && fmt == RS_PROFILE_SIMPACK && in_points)
    status = rs_msg_set(msg, RS_ERR_INPUT, "%s:%zu: point.begin without point.end", path, lineno);
  else if (status == RS_OK && fmt == RS_PROFILE_MINIPROF && in_header)
    status = rs_msg_set(msg, RS_ERR_INPUT,
                        "%s:%zu: no blank line ending the Miniprof header (the points follow it)",
                        path, lineno);
  free(line);
  *last_line = lineno;
  return status;
}

/* Sign of the turn a -> b -> c (cross product), exact zero for collinear points given
 * exactly. */
static double cross(double ay, double az, double by, double bz, double cy, double cz)
{
  return (by - ay) * (cz - az) - (bz - az) * (cy - ay);
}

static int on_segment(double ay, double az, double by, double bz, double py, double pz)
{
  return fmin(ay, by) <= py && py <= fmax(ay, by) && fmin(az, bz) <= pz && pz <= fmax(az, bz);
}

/* Whether the closed segments ab and cd share a point. */
static int segments_meet(const double *y, const double *z, size_t a, size_t c)
{
  const size_t b = a + 1, d = c + 1;
  const double d1 = cross(y[c], z[c], y[d], z[d], y[a], z[a]);
  const double d2 = cross(y[c], z[c], y[d], z[d], y[b], z[b]);
  const double d3 = cross(y[a], z[a], y[b], z[b], y[c], z[c]);
  const double d4 = cross(y[a], z[a], y[b], z[b], y[d], z[d]);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
    return 1;
  return (d1 == 0 && on_segment(y[c], z[c], y[d], z[d], y[a], z[a])) ||
         (d2 == 0 && on_segment(y[c], z[c], y[d], z[d], y[b], z[b])) ||
         (d3 == 0 && on_segment(y[a], z[a], y[b], z[b], y[c], z[c])) ||
         (d4 == 0 && on_segment(y[a], z[a], y[b], z[b], y[d], z[d]));
}

/* Duplicates, monotone y where the format requires it, self-intersections. */
static int check_points(const raw_points *r, const char *path, rs_profile_format fmt,
                        size_t last_line, int *monotone, rs_msg *msg)
{
  const double *y = r->y, *z = r->z;
  if (r->n < RS_PROFILE_MIN_POINTS)
    return rs_msg_set(msg, RS_ERR_INPUT, "%s:%zu: %zu points, a profile needs at least %d", path,
                      last_line, r->n, RS_PROFILE_MIN_POINTS);
  if (r->n > RS_PROFILE_MAX_POINTS)
    return rs_msg_set(msg, RS_ERR_INPUT, "%s:%zu: %zu points, at most %d are accepted", path,
                      r->line[RS_PROFILE_MAX_POINTS], r->n, RS_PROFILE_MAX_POINTS);
  for (size_t i = 1; i < r->n; i++)
    if (y[i] == y[i - 1] && z[i] == z[i - 1])
      return rs_msg_set(msg, RS_ERR_INPUT,
                        "%s:%zu: duplicate point (y, z) = (%g, %g) mm, the same as on line %zu",
                        path, r->line[i], y[i], z[i], r->line[i - 1]);
  const int rising = y[1] > y[0];
  int strict = 1;
  for (size_t i = 1; i < r->n && strict; i++) {
    if (rising ? y[i] > y[i - 1] : y[i] < y[i - 1]) continue;
    strict = 0;
    if (fmt != RS_PROFILE_MINIPROF)
      return rs_msg_set(msg, RS_ERR_INPUT,
                        "%s:%zu: y = %g mm after %g mm (line %zu): y must be strictly %s "
                        "(a %s profile gives z as a function of y)",
                        path, r->line[i], y[i], y[i - 1], r->line[i - 1],
                        rising ? "increasing" : "decreasing", rs_profile_format_name(fmt));
  }
  *monotone = strict;
  if (strict) return RS_OK; /* a graph z(y) cannot cross itself */
  for (size_t i = 0; i + 1 < r->n; i++) {
    /* the next segment turning straight back over this one */
    if (i + 2 < r->n && cross(y[i], z[i], y[i + 1], z[i + 1], y[i + 2], z[i + 2]) == 0 &&
        (y[i + 1] - y[i]) * (y[i + 2] - y[i + 1]) + (z[i + 1] - z[i]) * (z[i + 2] - z[i + 1]) < 0)
      return rs_msg_set(msg, RS_ERR_INPUT,
                        "%s:%zu: the profile turns back on itself at (y, z) = (%g, %g) mm "
                        "(the segments of lines %zu-%zu and %zu-%zu overlap)",
                        path, r->line[i + 1], y[i + 1], z[i + 1], r->line[i], r->line[i + 1],
                        r->line[i + 1], r->line[i + 2]);
    for (size_t j = i + 2; j + 1 < r->n; j++) {
      if (!segments_meet(y, z, i, j)) continue;
      for (size_t a = i; a <= i + 1; a++) /* a repeated point rather than a crossing */
        for (size_t b = j; b <= j + 1; b++)
          if (y[a] == y[b] && z[a] == z[b])
            return rs_msg_set(msg, RS_ERR_INPUT,
                              "%s:%zu: duplicate point (y, z) = (%g, %g) mm, the same as on "
                              "line %zu",
                              path, r->line[b], y[b], z[b], r->line[a]);
      return rs_msg_set(msg, RS_ERR_INPUT,
                        "%s:%zu: the profile crosses itself: the segment of lines %zu-%zu meets "
                        "that of lines %zu-%zu",
                        path, r->line[j + 1], r->line[i], r->line[i + 1], r->line[j],
                        r->line[j + 1]);
    }
  }
  return RS_OK;
}

/* A profile is a small text file: anything else (a device, a pipe, a file of gigabytes) is
 * refused before reading, as it would never end or fill the memory. */
#define PROFILE_MAX_BYTES (64L << 20)

int rs_profile_read(rs_profile *p, const char *path, const rs_profile_opts *o, rs_msg *msg)
{
  memset(p, 0, sizeof *p);
  const rs_profile_format fmt = rs_profile_format_of(path);
  FILE *f = fopen(path, "r");
  if (!f) return rs_msg_set(msg, RS_ERR_INPUT, "cannot open %s: %s", path, strerror(errno));
  struct stat st;
  if (fstat(fileno(f), &st) != 0) {
    const int err = errno;
    fclose(f);
    return rs_msg_set(msg, RS_ERR_INPUT, "cannot read %s: %s", path, strerror(err));
  }
  if (!S_ISREG(st.st_mode) || st.st_size > PROFILE_MAX_BYTES) {
    fclose(f);
    return rs_msg_set(msg, RS_ERR_INPUT, "%s: not a profile file (%s)", path,
                      S_ISDIR(st.st_mode)    ? "a directory"
                      : !S_ISREG(st.st_mode) ? "not a regular file"
                                             : "larger than 64 MB");
  }
  raw_points r = {0};
  size_t last_line = 0;
  int monotone = 0;
  int status = read_points(f, path, fmt, &r, &last_line, msg);
  fclose(f);
  if (status == RS_OK) status = check_points(&r, path, fmt, last_line, &monotone, msg);
  if (status != RS_OK) {
    raw_free(&r);
    return status;
  }
  const double scale = o && o->scale != 0.0 ? o->scale : 1.0;
  const double sy = (o && o->mirror ? -1.0 : 1.0) * scale;
  const int reverse = sy * (r.y[r.n - 1] - r.y[0]) < 0; /* stored with y increasing */
  p->format = fmt;
  p->n = r.n;
  p->monotone = monotone;
  p->y = r.y;
  p->z = r.z;
  free(r.line);
  for (size_t i = 0; i < p->n; i++) {
    p->y[i] *= sy;
    p->z[i] *= scale;
  }
  for (size_t i = 0; reverse && i < p->n / 2; i++) {
    size_t j = p->n - 1 - i;
    double t = p->y[i];
    p->y[i] = p->y[j];
    p->y[j] = t;
    t = p->z[i];
    p->z[i] = p->z[j];
    p->z[j] = t;
  }
  if (o && o->smoothing > 0.0) status = rs_profile_smooth(p, o->smoothing, msg);
  if (status != RS_OK) rs_profile_free(p);
  return status;
}

void rs_profile_free(rs_profile *p)
{
  if (!p) return;
  free(p->y);
  free(p->z);
  memset(p, 0, sizeof *p);
}

/* Solve the 3x3 system a x = b by Gaussian elimination with partial pivoting; 0 when a
 * pivot vanishes (fewer than three distinct abscissae in the window). */
static int solve3(double a[3][3], double b[3], double x[3])
{
  for (int k = 0; k < 3; k++) {
    int piv = k;
    for (int i = k + 1; i < 3; i++)
      if (fabs(a[i][k]) > fabs(a[piv][k])) piv = i;
    if (!(fabs(a[piv][k]) > 1e-12 * (fabs(a[0][0]) + 1e-300))) return 0;
    if (piv != k) {
      for (int j = 0; j < 3; j++) {
        double t = a[k][j];
        a[k][j] = a[piv][j];
        a[piv][j] = t;
      }
      double t = b[k];
      b[k] = b[piv];
      b[piv] = t;
    }
    for (int i = k + 1; i < 3; i++) {
      double m = a[i][k] / a[k][k];
      for (int j = k; j < 3; j++) a[i][j] -= m * a[k][j];
      b[i] -= m * b[k];
    }
  }
  for (int i = 2; i >= 0; i--) {
    double s = b[i];
    for (int j = i + 1; j < 3; j++) s -= a[i][j] * x[j];
    x[i] = s / a[i][i];
  }
  return 1;
}

/* The weighted quadratic fit of v(t) around t[i], evaluated at t[i]. The abscissae are
 * centred on t[i] and scaled by the length, so the system stays well conditioned. */
static double mls_value(const double *t, const double *v, size_t lo, size_t hi, size_t i,
                        double length)
{
  double a[3][3] = {{0}}, b[3] = {0}, c[3];
  size_t count = 0;
  for (size_t j = lo; j < hi; j++) {
    const double u = (t[j] - t[i]) / length, w = exp(-u * u);
    const double phi[3] = {1.0, u, u * u};
    for (int k = 0; k < 3; k++) {
      for (int l = 0; l < 3; l++) a[k][l] += w * phi[k] * phi[l];
      b[k] += w * phi[k] * v[j];
    }
    count++;
  }
  if (count < 3 || !solve3(a, b, c)) return v[i];
  return c[0];
}

int rs_profile_smooth(rs_profile *p, double length, rs_msg *msg)
{
  if (!(length > 0.0) || p->n < 3) return RS_OK;
  const size_t n = p->n;
  double *t = malloc(n * sizeof *t), *ny = malloc(n * sizeof *ny), *nz = malloc(n * sizeof *nz);
  if (!t || !ny || !nz) {
    free(t);
    free(ny);
    free(nz);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  }
  if (p->monotone) {
    memcpy(t, p->y, n * sizeof *t);
  } else {
    t[0] = 0.0;
    for (size_t i = 1; i < n; i++)
      t[i] = t[i - 1] + hypot(p->y[i] - p->y[i - 1], p->z[i] - p->z[i - 1]);
  }
  size_t lo = 0, hi = 0;
  for (size_t i = 0; i < n; i++) {
    while (t[i] - t[lo] > 3.0 * length) lo++;
    while (hi < n && t[hi] - t[i] <= 3.0 * length) hi++;
    nz[i] = mls_value(t, p->z, lo, hi, i, length);
    ny[i] = p->monotone ? p->y[i] : mls_value(t, p->y, lo, hi, i, length);
  }
  memcpy(p->y, ny, n * sizeof *ny);
  memcpy(p->z, nz, n * sizeof *nz);
  free(t);
  free(ny);
  free(nz);
  return RS_OK;
}

void rs_wheel_rail_free(rs_wheel_rail *w)
{
  if (!w) return;
  rs_profile_free(&w->rail);
  rs_profile_free(&w->wheel);
  free(w->rail_file);
  free(w->wheel_file);
  free(w->placed);
  rs_history_free(&w->lateral_history);
  rs_history_free(&w->yaw_history);
  free(w);
}

void rs_profile_range(const rs_profile *p, double y[2], double z[2])
{
  y[0] = y[1] = p->y[0];
  z[0] = z[1] = p->z[0];
  for (size_t i = 1; i < p->n; i++) {
    y[0] = fmin(y[0], p->y[i]);
    y[1] = fmax(y[1], p->y[i]);
    z[0] = fmin(z[0], p->z[i]);
    z[1] = fmax(z[1], p->z[i]);
  }
}

int rs_profile_z_at(const rs_profile *p, double y, double *z)
{
  for (size_t i = 0; i + 1 < p->n; i++) {
    const double y0 = p->y[i], y1 = p->y[i + 1];
    if ((y0 <= y && y <= y1) || (y1 <= y && y <= y0)) {
      *z = y1 == y0 ? p->z[i] : p->z[i] + (p->z[i + 1] - p->z[i]) * (y - y0) / (y1 - y0);
      return 1;
    }
  }
  *z = 0.0;
  return 0;
}
