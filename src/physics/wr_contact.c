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
 * the track y of each point, idx[] (unless NULL) its index in the polyline. */
static size_t tangent_chain(const double *py, const double *pz, size_t n, double shift,
                            double zshift, size_t seg, double cy, double cz, double delta,
                            double *u, double *w, double *y_of, size_t *idx)
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
    if (idx) idx[m] = (size_t)j;
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

/* The wheel's contact locus under yaw (docs/model.md §20 "Yaw"): per wheel profile point, the
 * lowest point of the turned wheel's circle there for the track y it maps to, in track
 * coordinates, with what a patch needs there. */
typedef struct wr_locus {
  size_t n;
  double *y, *z;      /* track y; z the wheel profile's z raised by r (1 - cos theta) */
  double *u, *zw, *r; /* the wheel profile point and its radius */
  double *X;          /* x from the wheelset's centre */
  double *zpp;        /* the profile's second derivative there */
  double *buf;
} wr_locus;

/* The profile's slope and second derivative at point k from the parabola through it and its
 * neighbours (the first or last three at an end); where those are not a function of y, the
 * slope of a segment at k and no curvature. 0 when that segment is vertical. */
static int point_slope(const double *py, const double *pz, size_t n, size_t k, double *m,
                       double *zpp)
{
  *zpp = 0.0;
  if (n >= 3) {
    const size_t j = k == 0 ? 0 : k + 1 >= n ? n - 3 : k - 1;
    const double y0 = py[j], y1 = py[j + 1], y2 = py[j + 2];
    if ((y0 < y1 && y1 < y2) || (y0 > y1 && y1 > y2)) {
      const double d1 = (pz[j + 1] - pz[j]) / (y1 - y0), d2 = (pz[j + 2] - pz[j + 1]) / (y2 - y1);
      const double c = (d2 - d1) / (y2 - y0);
      *m = d1 + c * (2.0 * py[k] - y0 - y1);
      *zpp = 2.0 * c;
      return 1;
    }
  }
  const size_t a = k + 1 < n ? k : k - 1; /* the segment after k (before it at the end) */
  if (py[a + 1] == py[a]) return 0;
  *m = (pz[a + 1] - pz[a]) / (py[a + 1] - py[a]);
  return 1;
}

/* The locus of a wheel yawed by psi about the vertical through the wheelset's centre: its
 * axle a = (-sin psi, cos psi, 0) (x along the track, y toward the track centre, z up), the
 * profile point u at (u - axle_offset) a from the centre, on a circle of radius r(u). The
 * point of that circle at angle theta from the bottom is the lowest for its track y where
 * sin theta = -r'(u) tan psi; a profile too steep for that (|r' tan psi| >= 1, a side of the
 * flange facing along the axle) has no lowest point there, and those points are left out. */
static int locus_build(const rs_wr_input *in, wr_locus *L, rs_msg *msg)
{
  const rs_wr_polyline *w = &in->wheel;
  const size_t n = w->n;
  memset(L, 0, sizeof *L);
  if (!(L->buf = malloc(7 * n * sizeof *L->buf)))
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  double *b = L->buf;
  L->y = b, L->z = b + n, L->u = b + 2 * n, L->zw = b + 3 * n, L->r = b + 4 * n;
  L->X = b + 5 * n, L->zpp = b + 6 * n;
  const double psi = in->yaw, sp = sin(psi), cp = cos(psi), tp = tan(psi);
  const double vers = 2.0 * sin(0.5 * psi) * sin(0.5 * psi); /* 1 - cos psi */
  size_t k = 0;
  for (size_t i = 0; i < n; i++) {
    double m, zpp;
    if (!point_slope(w->y, w->z, n, i, &m, &zpp)) continue;
    const double st = -m * tp;
    if (!(fabs(st) < 1.0)) continue;
    const double ct = sqrt(1.0 - st * st), u = w->y[i];
    const double r = in->nominal_radius + w->z[i] - in->wheel_z0;
    /* y = y_centre + (u - L0) cos psi + r sin theta sin psi with y_centre = shift + L0 */
    L->y[k] = u + in->wheel_shift + (in->axle_offset - u) * vers + r * st * sp;
    L->z[k] = w->z[i] - r * st * st / (1.0 + ct);
    L->u[k] = u, L->zw[k] = w->z[i], L->r[k] = r, L->zpp[k] = zpp;
    L->X[k] = (in->axle_offset - u) * sp + r * st * cp;
    k++;
  }
  L->n = k;
  if (k < 2) {
    free(L->buf);
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "the wheel profile is too steep everywhere for a lowest point at yaw %g rad",
                      psi);
  }
  return RS_OK;
}

/* The patch's h(0, s) table: both profiles in the tangent frame at the contact point,
 * their normal separation on the union of their points, within the patch's lateral range.
 * With a locus L (in->wheel its points) also the locus' offset xo(s) along the track. */
static int patch_table(const rs_wr_input *in, double wheel_z, rs_wr_patch *p, size_t rseg,
                       size_t wseg, const wr_locus *L, rs_msg *msg)
{
  const size_t nr = in->rail.n, nw = in->wheel.n;
  double *buf = malloc((3 * (nr + nw) + 2 * (nr + nw) + nw) * sizeof *buf);
  size_t *idx = L ? malloc(nw * sizeof *idx) : NULL;
  if (!buf || (L && !idx)) {
    free(buf);
    free(idx);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  }
  double *ur = buf, *wr = ur + nr, *yr = wr + nr;
  double *uw = yr + nr, *ww = uw + nw, *yw = ww + nw;
  double *su = yw + nw, *xw = su + 2 * (nr + nw);
  const double zr = p->z_rail, zw = p->z_rail - p->gap;
  const size_t mr = tangent_chain(in->rail.y, in->rail.z, nr, 0.0, 0.0, rseg, p->y, zr, p->delta,
                                  ur, wr, yr, NULL);
  const size_t mw = tangent_chain(in->wheel.y, in->wheel.z, nw, in->wheel_shift, wheel_z, wseg,
                                  p->y, zw, p->delta, uw, ww, yw, idx);
  if (mr < 2 || mw < 2) {
    free(buf);
    free(idx);
    return rs_msg_set(msg, RS_ERR_INPUT, "the profiles turn back at the contact point y = %.3f mm",
                      p->y);
  }
  if (L)
    for (size_t k = 0; k < mw; k++) xw[k] = L->X[idx[k]];
  free(idx);
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
  if (L) p->xo = malloc(m * sizeof *p->xo);
  if (!p->s || !p->h || (L && !p->xo)) {
    free(buf);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  }
  const double xc = L ? chain_at(uw, xw, mw, 0.0) : 0.0;
  size_t k = 0;
  for (size_t j = 0; j < m; j++) {
    if (k > 0 && su[j] <= p->s[k - 1]) continue;
    p->s[k] = su[j];
    p->h[k] = chain_at(ur, wr, mr, su[j]) - chain_at(uw, ww, mw, su[j]);
    if (L) p->xo[k] = chain_at(uw, xw, mw, su[j]) - xc;
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

double rs_wr_patch_h(const rs_wr_patch *p, double x, double s)
{
  if (!p->xo) return rs_wr_patch_h0(p, s) + x * x * cos(p->delta) / (2.0 * p->rolling_radius);
  const double dx = x - chain_at(p->s, p->xo, p->ns, fmin(fmax(s, p->s[0]), p->s[p->ns - 1]));
  return rs_wr_patch_h0(p, s) + 0.5 * p->curv_x * dx * dx;
}

void rs_wr_patch_gap(const rs_wr_patch *p, const rs_grid3d *grid, double *h)
{
  if (p->xo) {
    for (int j = 0; j < grid->ny; j++)
      for (int i = 0; i < grid->nx; i++)
        h[(size_t)j * grid->nx + i] =
            rs_wr_patch_h(p, grid->x0 + (i + 0.5) * grid->dx, grid->y0 + (j + 0.5) * grid->dy);
    return;
  }
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
    free(geo->patch[k].xo);
  }
  memset(geo, 0, sizeof *geo);
}

/* A minimum of the sampled gap: index range [a, b] of a plateau (a == b for a point). */
typedef struct minimum {
  size_t a, b;
} minimum;

/* The wheel's side of a patch whose contact point lies on segment seg of the locus: the
 * profile point, its radius and the profile's second derivative by linear interpolation
 * along the segment. The point of that circle where the wheel's tangent plane is the
 * patch's (angle delta about the track's x) has tan theta = -tan(delta) sin(psi): there the
 * wheel's material moves within the tangent plane (the lead x = -h tan(delta) tan(psi), h
 * the axle's height). The wheel's normal curvature along the track: Euler's formula with the
 * circle's 1/(r sqrt(1 + m^2)) and the profile's -z''/(1 + m^2)^(3/2), the track's x turned
 * from the circle's direction by alpha, cos^2 alpha = cos^2 theta cos^2 psi, m the profile's
 * slope there, tan(delta) cos(psi) cos(theta). */
static void locus_point(const wr_locus *L, double psi, size_t seg, rs_wr_patch *p)
{
  const double dy = L->y[seg + 1] - L->y[seg];
  const double f = dy != 0.0 ? (p->y - L->y[seg]) / dy : 0.0;
#define LERP(a) (L->a[seg] + f * (L->a[seg + 1] - L->a[seg]))
  p->y_wheel = LERP(u);
  p->z_wheel = LERP(zw);
  p->rolling_radius = LERP(r);
  const double zpp = LERP(zpp);
#undef LERP
  const double cp = cos(psi), sp = sin(psi), td = tan(p->delta);
  const double ct = 1.0 / sqrt(1.0 + td * td * sp * sp), m = td * cp * ct;
  p->axle_height = p->rolling_radius * ct;
  p->x = -p->axle_height * td * sp / cp;
  p->curv_x = (ct * ct * cp * cp / p->rolling_radius - zpp * sp * sp) / sqrt(1.0 + m * m);
}

/* The geometry of the wheel profile in `in`, or (L given) of the wheel's locus L, in->wheel
 * then its points in track coordinates. */
static int build(const rs_wr_input *in, const wr_locus *L, rs_wr_geometry *geo, rs_msg *msg)
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
    p->x = 0.0;
    p->axle_height = p->rolling_radius;
    p->curv_x = cos(p->delta) / p->rolling_radius;
    status = patch_table(in, geo->wheel_z, p, rseg, wseg, L, msg);
    if (status == RS_OK && L) {
      locus_point(L, in->yaw, wseg, p);
      if (!(p->curv_x > 0.0)) /* a saddle of the wheel: the locus is no closest approach */
        status = rs_msg_set(msg, RS_ERR_INPUT,
                            "at yaw %g rad the wheel curves toward the rail along the track at the "
                            "contact point y = %.3f mm (its profile's own curvature outweighs its "
                            "circle's): its contact locus does not hold there",
                            in->yaw, p->y);
    }
  }
  geo->npatch = np;
  free(mins);
  if (status != RS_OK) rs_wr_geometry_free(geo);
  return status;
}

int rs_wr_geometry_build(const rs_wr_input *in, rs_wr_geometry *geo, rs_msg *msg)
{
  if (in->yaw == 0.0) return build(in, NULL, geo, msg);
  wr_locus L;
  int status = locus_build(in, &L, msg);
  if (status != RS_OK) {
    memset(geo, 0, sizeof *geo);
    return status;
  }
  rs_wr_input li = *in;
  li.wheel = (rs_wr_polyline){L.n, L.y, L.z};
  li.wheel_shift = 0.0;
  status = build(&li, &L, geo, msg);
  free(L.buf);
  return status;
}
