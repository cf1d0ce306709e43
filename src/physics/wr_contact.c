/* Wheel-rail contact geometry from profiles (physics/wr_contact.h, docs/model.md §20): the
 * vertical gap, its minima, the patches and each patch's undeformed distance in its tangent
 * plane. */
#include "physics/wr_contact.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* 1 when the polyline's y strictly increases (tables and SIMPACK files). */
static int increasing(const double *py, size_t n)
{
  for (size_t i = 0; i + 1 < n; i++)
    if (!(py[i + 1] > py[i])) return 0;
  return 1;
}

/* z of a polyline at y over all segments that span y: the lowest surface point (min z, the
 * rail: z downward, material below) or the highest one of the wheel (max z, material
 * above). seg: the segment that gives it (may be NULL). NAN when no segment spans y. An
 * increasing polyline has one such segment, found by bisection; any other (a Miniprof
 * flank) is searched through. */
static double envelope(const double *py, const double *pz, size_t n, int inc, double shift,
                       double y, int want_max, size_t *seg)
{
  if (inc) {
    if (!(y >= py[0] + shift && y <= py[n - 1] + shift)) return NAN;
    size_t lo = 0, hi = n - 1;
    while (hi - lo > 1) {
      const size_t mid = (lo + hi) / 2;
      if (py[mid] + shift <= y)
        lo = mid;
      else
        hi = mid;
    }
    if (seg) *seg = lo;
    const double a = py[lo] + shift, b = py[lo + 1] + shift;
    return pz[lo] + (pz[lo + 1] - pz[lo]) * (y - a) / (b - a);
  }
  double best = NAN;
  for (size_t i = 0; i + 1 < n; i++) {
    const double a = py[i] + shift, b = py[i + 1] + shift;
    const double lo = fmin(a, b), hi = fmax(a, b);
    if (!(y >= lo && y <= hi) || a == b) continue;
    const double z = pz[i] + (pz[i + 1] - pz[i]) * (y - a) / (b - a);
    if (isnan(best) || (want_max ? z > best : z < best)) {
      best = z;
      if (seg) *seg = i;
    }
  }
  return best;
}

static int cmp_double(const void *a, const void *b)
{
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* The slope dz/dy at y of the parabola through three consecutive points of a polyline
 * around segment seg (the two nearer y); the segment's slope when those are not a
 * function of y. A circle sampled at spacing d gives its slope to O(d^2 / R^2). */
static double local_slope(const double *py, const double *pz, size_t n, size_t seg, double y)
{
  const double seg_slope = (pz[seg + 1] - pz[seg]) / (py[seg + 1] - py[seg]);
  if (n < 3) return seg_slope;
  size_t k;
  if (seg == 0)
    k = 0;
  else if (seg + 2 >= n)
    k = n - 3;
  else
    k = fabs(y - py[seg]) < fabs(y - py[seg + 1]) ? seg - 1 : seg;
  const double y0 = py[k], y1 = py[k + 1], y2 = py[k + 2];
  if (!((y0 < y1 && y1 < y2) || (y0 > y1 && y1 > y2))) return seg_slope;
  const double d1 = (pz[k + 1] - pz[k]) / (y1 - y0), d2 = (pz[k + 2] - pz[k + 1]) / (y2 - y1);
  const double c = (d2 - d1) / (y2 - y0);
  return d1 + c * (2.0 * y - y0 - y1);
}

/* The chain of a polyline's points in the tangent frame at C = (cy, cz), angle delta: u along
 * the tangent, w along the normal (downward for delta = 0), walked from segment seg both ways
 * while u keeps growing away from it, so that w is a function of u. The polyline is placed
 * at (y + shift, z + zshift). Returns the chain's length; u[], w[] in increasing u; y_of[]
 * the track y of each point. */
static size_t tangent_chain(const double *py, const double *pz, size_t n, double shift,
                            double zshift, size_t seg, double cy, double cz, double delta,
                            double *u, double *w, double *y_of)
{
  const double c = cos(delta), s = sin(delta);
#define UCOORD(i) ((py[i] + shift - cy) * c + (pz[i] + zshift - cz) * s)
  const int up = UCOORD(seg + 1) >= UCOORD(seg);
  const long jhi = up ? (long)seg + 1 : (long)seg, jlo = up ? (long)seg : (long)seg + 1;
  const long dir = jhi - jlo; /* index step toward larger u */
  long first = jlo;           /* walk down from jlo while u decreases */
  while (first - dir >= 0 && first - dir < (long)n && UCOORD(first - dir) < UCOORD(first))
    first -= dir;
  long last = jhi; /* and up from jhi while it increases */
  while (last + dir >= 0 && last + dir < (long)n && UCOORD(last + dir) > UCOORD(last)) last += dir;
  size_t m = 0;
  for (long j = first;; j += dir) {
    u[m] = UCOORD(j);
    w[m] = -(py[j] + shift - cy) * s + (pz[j] + zshift - cz) * c;
    y_of[m] = py[j] + shift;
    m++;
    if (j == last) break;
  }
#undef UCOORD
  return m;
}

/* Linear interpolation of w(u) on a chain (u increasing, within range). */
static double chain_at(const double *u, const double *w, size_t m, double x)
{
  size_t lo = 0, hi = m - 1;
  while (hi - lo > 1) {
    const size_t mid = (lo + hi) / 2;
    if (u[mid] <= x)
      lo = mid;
    else
      hi = mid;
  }
  if (u[hi] == u[lo]) return w[lo];
  return w[lo] + (w[hi] - w[lo]) * (x - u[lo]) / (u[hi] - u[lo]);
}

/* The range of u around u = 0 over which the chain's y stays within [ylo, yhi] (the
 * crossings interpolated linearly). */
static void chain_clip(const double *u, const double *y, size_t m, double ylo, double yhi,
                       double *umin, double *umax)
{
  size_t k0 = 0;
  while (k0 + 1 < m && u[k0 + 1] <= 0.0) k0++;
  *umin = u[0];
  *umax = u[m - 1];
  for (size_t k = k0 + 1; k < m; k++)
    if (y[k] < ylo || y[k] > yhi) {
      const double b = y[k] < ylo ? ylo : yhi;
      *umax = u[k - 1] + (u[k] - u[k - 1]) * (b - y[k - 1]) / (y[k] - y[k - 1]);
      break;
    }
  for (size_t k = k0 + 1; k-- > 0;)
    if (y[k] < ylo || y[k] > yhi) {
      const double b = y[k] < ylo ? ylo : yhi;
      *umin = u[k + 1] + (u[k] - u[k + 1]) * (b - y[k + 1]) / (y[k] - y[k + 1]);
      break;
    }
}

/* The patch's h(0, s) table: both profiles in the tangent frame at the contact point,
 * their normal separation on the union of their points, within the patch's lateral range. */
static int patch_table(const rs_wr_input *in, double wheel_z, rs_wr_patch *p, size_t rseg,
                       size_t wseg, rs_msg *msg)
{
  const size_t nr = in->rail.n, nw = in->wheel.n;
  double *buf = malloc((3 * (nr + nw) + 2 * (nr + nw)) * sizeof *buf);
  if (!buf) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  double *ur = buf, *wr = ur + nr, *yr = wr + nr;
  double *uw = yr + nr, *ww = uw + nw, *yw = ww + nw;
  double *su = yw + nw;
  const double zr = p->z_rail, zw = p->z_rail - p->gap;
  const size_t mr =
      tangent_chain(in->rail.y, in->rail.z, nr, 0.0, 0.0, rseg, p->y, zr, p->delta, ur, wr, yr);
  const size_t mw = tangent_chain(in->wheel.y, in->wheel.z, nw, in->wheel_shift, wheel_z, wseg,
                                  p->y, zw, p->delta, uw, ww, yw);
  if (mr < 2 || mw < 2) {
    free(buf);
    return rs_msg_set(msg, RS_ERR_INPUT, "the profiles turn back at the contact point y = %.3f mm",
                      p->y);
  }
  double lo, hi;
  chain_clip(ur, yr, mr, p->y_lo, p->y_hi, &lo, &hi);
  lo = fmax(lo, uw[0]);
  hi = fmin(hi, uw[mw - 1]);
  size_t m = 0;
  su[m++] = lo;
  for (size_t k = 0; k < mr; k++)
    if (ur[k] > lo && ur[k] < hi) su[m++] = ur[k];
  for (size_t k = 0; k < mw; k++)
    if (uw[k] > lo && uw[k] < hi) su[m++] = uw[k];
  su[m++] = hi;
  qsort(su, m, sizeof *su, cmp_double);
  p->s = malloc(m * sizeof *p->s);
  p->h = malloc(m * sizeof *p->h);
  if (!p->s || !p->h) {
    free(buf);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  }
  size_t k = 0;
  for (size_t j = 0; j < m; j++) {
    if (k > 0 && su[j] <= p->s[k - 1]) continue;
    p->s[k] = su[j];
    p->h[k] = chain_at(ur, wr, mr, su[j]) - chain_at(uw, ww, mw, su[j]);
    k++;
  }
  p->ns = k;
  free(buf);
  /* h from its minimum: the refined contact point may lie a chord's sag off the polylines'
   * closest points; the patch then closes when (dz - gap) cos(delta) exceeds 0 */
  double hmin = INFINITY;
  for (size_t j = 0; j < k; j++) hmin = fmin(hmin, p->h[j]);
  for (size_t j = 0; j < k; j++) p->h[j] -= hmin;
  p->gap = fmax(p->gap + hmin / cos(p->delta), 0.0);
  if (k < 2 || !(lo < 0 && hi > 0))
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "the contact point y = %.3f mm lies at an end of a profile", p->y);
  return RS_OK;
}

double rs_wr_patch_h0(const rs_wr_patch *p, double s)
{
  return chain_at(p->s, p->h, p->ns, fmin(fmax(s, p->s[0]), p->s[p->ns - 1]));
}

void rs_wr_patch_gap(const rs_wr_patch *p, const rs_grid3d *grid, double *h)
{
  const double cx = cos(p->delta) / (2.0 * p->rolling_radius);
  for (int j = 0; j < grid->ny; j++) {
    const double h0 = rs_wr_patch_h0(p, grid->y0 + (j + 0.5) * grid->dy);
    for (int i = 0; i < grid->nx; i++) {
      const double x = grid->x0 + (i + 0.5) * grid->dx;
      h[(size_t)j * grid->nx + i] = h0 + cx * x * x;
    }
  }
}

int rs_wr_gauge_point(const rs_wr_polyline *rail, double gauge_height, double *y)
{
  double top = INFINITY;
  for (size_t i = 0; i < rail->n; i++) top = fmin(top, rail->z[i]);
  const double level = top + gauge_height;
  int found = 0;
  for (size_t i = 0; i + 1 < rail->n; i++) {
    const double a = rail->z[i] - level, b = rail->z[i + 1] - level;
    if ((a < 0) == (b < 0) || a == b) continue;
    const double yc = rail->y[i] + (rail->y[i + 1] - rail->y[i]) * a / (a - b);
    if (!found || yc > *y) *y = yc;
    found = 1;
  }
  return found;
}

void rs_wr_geometry_free(rs_wr_geometry *geo)
{
  free(geo->y);
  free(geo->g);
  for (int k = 0; k < RS_WR_MAX_PATCHES; k++) {
    free(geo->patch[k].s);
    free(geo->patch[k].h);
  }
  memset(geo, 0, sizeof *geo);
}

/* A minimum of the sampled gap: index range [a, b] of a plateau (a == b for a point). */
typedef struct minimum {
  size_t a, b;
} minimum;

int rs_wr_geometry_build(const rs_wr_input *in, rs_wr_geometry *geo, rs_msg *msg)
{
  memset(geo, 0, sizeof *geo);
  const rs_wr_polyline *r = &in->rail, *w = &in->wheel;
  double rlo = INFINITY, rhi = -INFINITY, wlo = INFINITY, whi = -INFINITY;
  for (size_t i = 0; i < r->n; i++) rlo = fmin(rlo, r->y[i]), rhi = fmax(rhi, r->y[i]);
  for (size_t i = 0; i < w->n; i++)
    wlo = fmin(wlo, w->y[i] + in->wheel_shift), whi = fmax(whi, w->y[i] + in->wheel_shift);
  const double lo = fmax(rlo, wlo), hi = fmin(rhi, whi);
  if (!(lo < hi))
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "the wheel (y %.3f .. %.3f mm as placed) and the rail (y %.3f .. %.3f mm) "
                      "share no lateral range",
                      wlo, whi, rlo, rhi);
  /* samples: every point of either profile in the common range (the gap is linear between) */
  const size_t cap = r->n + w->n + 2;
  geo->y = malloc(cap * sizeof *geo->y);
  geo->g = malloc(cap * sizeof *geo->g);
  minimum *mins = malloc(cap * sizeof *mins);
  if (!geo->y || !geo->g || !mins) {
    free(mins);
    rs_wr_geometry_free(geo);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  }
  size_t n = 0;
  geo->y[n++] = lo;
  for (size_t i = 0; i < r->n; i++)
    if (r->y[i] > lo && r->y[i] < hi) geo->y[n++] = r->y[i];
  for (size_t i = 0; i < w->n; i++)
    if (w->y[i] + in->wheel_shift > lo && w->y[i] + in->wheel_shift < hi)
      geo->y[n++] = w->y[i] + in->wheel_shift;
  geo->y[n++] = hi;
  qsort(geo->y, n, sizeof *geo->y, cmp_double);
  size_t m = 0;
  for (size_t k = 0; k < n; k++)
    if (m == 0 || geo->y[k] > geo->y[m - 1]) geo->y[m++] = geo->y[k];
  n = m;
  double gmin = INFINITY;
  const int rinc = increasing(r->y, r->n), winc = increasing(w->y, w->n);
  for (size_t k = 0; k < n; k++) {
    geo->g[k] = envelope(r->y, r->z, r->n, rinc, 0.0, geo->y[k], 0, NULL) -
                envelope(w->y, w->z, w->n, winc, in->wheel_shift, geo->y[k], 1, NULL);
    gmin = fmin(gmin, geo->g[k]);
  }
  geo->n = n;
  geo->wheel_z = gmin;
  for (size_t k = 0; k < n; k++) geo->g[k] -= gmin;
  /* local minima (a plateau counts once) */
  size_t nm = 0;
  for (size_t k = 0; k < n;) {
    size_t e = k;
    while (e + 1 < n && geo->g[e + 1] == geo->g[k]) e++;
    const int left = k == 0 || geo->g[k - 1] > geo->g[k];
    const int right = e + 1 == n || geo->g[e + 1] > geo->g[k];
    if (left && right) mins[nm++] = (minimum){k, e};
    k = e + 1;
  }
  geo->minima = (int)nm;
  /* the grouping rule: consecutive minima are one patch unless the gap between them rises
   * more than `separation` above the higher of the two */
  size_t best[RS_WR_MAX_PATCHES];
  double bound[RS_WR_MAX_PATCHES + 1];
  int np = 0;
  bound[0] = lo;
  for (size_t q = 0; q < nm; q++) {
    if (q > 0) {
      size_t top = mins[q - 1].b;
      for (size_t k = mins[q - 1].b; k <= mins[q].a; k++)
        if (geo->g[k] > geo->g[top]) top = k;
      const double higher = fmax(geo->g[mins[q - 1].a], geo->g[mins[q].a]);
      if (geo->g[top] - higher <= in->separation) { /* the same patch: keep its lowest */
        if (geo->g[mins[q].a] < geo->g[mins[best[np - 1]].a]) best[np - 1] = q;
        continue;
      }
      if (np == RS_WR_MAX_PATCHES) {
        free(mins);
        rs_wr_geometry_free(geo);
        return rs_msg_set(msg, RS_ERR_INPUT,
                          "the gap between wheel and rail has more than %d separate minima: "
                          "raise the patch separation or smooth the profiles",
                          RS_WR_MAX_PATCHES);
      }
      bound[np] = geo->y[top];
    }
    best[np++] = q;
  }
  bound[np] = hi;
  int status = RS_OK;
  for (int k = 0; k < np && status == RS_OK; k++) {
    rs_wr_patch *p = &geo->patch[k];
    const minimum mn = mins[best[k]];
    size_t c = (mn.a + mn.b) / 2;
    double y = mn.a == mn.b ? geo->y[c] : 0.5 * (geo->y[mn.a] + geo->y[mn.b]);
    if (mn.a == 0 || mn.b + 1 == n) {
      status = rs_msg_set(msg, RS_ERR_INPUT,
                          "the closest approach of wheel and rail lies at y = %.3f mm, an end of "
                          "their common lateral range %.3f .. %.3f mm (the wheel off the rail)",
                          y, lo, hi);
      break;
    }
    if (mn.a == mn.b) { /* the vertex of the parabola through the three samples */
      const double y0 = geo->y[c - 1], y1 = geo->y[c], y2 = geo->y[c + 1];
      const double d1 = (geo->g[c] - geo->g[c - 1]) / (y1 - y0);
      const double d2 = (geo->g[c + 1] - geo->g[c]) / (y2 - y1);
      const double cc = (d2 - d1) / (y2 - y0);
      if (cc > 0) y = fmin(fmax(0.5 * (y0 + y1) - d1 / (2.0 * cc), y0), y2);
    }
    size_t rseg = 0, wseg = 0;
    p->y = y;
    p->z_rail = envelope(r->y, r->z, r->n, rinc, 0.0, y, 0, &rseg);
    p->y_wheel = y - in->wheel_shift;
    p->z_wheel = envelope(w->y, w->z, w->n, winc, in->wheel_shift, y, 1, &wseg);
    p->gap = fmax(p->z_rail - p->z_wheel - geo->wheel_z, 0.0);
    p->delta = atan(local_slope(r->y, r->z, r->n, rseg, y));
    p->rolling_radius = in->nominal_radius + p->z_wheel - in->wheel_z0;
    p->y_lo = bound[k];
    p->y_hi = bound[k + 1];
    status = patch_table(in, geo->wheel_z, p, rseg, wseg, msg);
  }
  geo->npatch = np;
  free(mins);
  if (status != RS_OK) rs_wr_geometry_free(geo);
  return status;
}
