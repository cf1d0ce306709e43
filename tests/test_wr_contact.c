/* Wheel-rail contact from profiles (physics/wr_contact.h), docs/verification.md "Wheel-rail
 * contact from profiles". Argument: the directory of the shipped profiles (cases/profiles).
 *
 * (a) Circular arcs given as polylines: h(0, s) against the exact separation of two circles
 *     and h(x, s) against x^2 cos(delta)/(2r) + s^2/(2 R_eff), the contact angle and rolling
 *     radius against the line through the circles' centres; the per-patch normal solution
 *     against the Hertz ellipse on two grids, and against today's 3D normal problem with the
 *     gap from the radii on the same grid.
 * (b) A flat-topped rail under a cylindrical wheel: a patch at least the flat's width, with
 *     pressure peaks at its lateral ends (not the Hertz shape, whose maximum is central).
 * (c) Mirror symmetry on the S1002/UIC60 profiles.
 * (d) Two crowns under one wheel: two patches, the vertical force balance and the load split
 *     against two Hertz ellipses; on S1002/UIC60 at 8 mm one patch on the flange at the S1002
 *     flank's 70 degrees. */
#include "io/profile.h"
#include "physics/wr_contact.h"
#include "test_support.h"

#include <stdlib.h>
#include <string.h>

#include "physics/elastic2d.h" /* RS_PI */
#include "physics/elastic3d.h"

static const double G = 82000.0, NU = 0.28, FZ = 10000.0;

/* z = zc - sign sqrt(R^2 - (y - yc)^2): a circle through y in [y0, y1] at spacing d. */
typedef struct arc_line {
  size_t n;
  double y[8192], z[8192];
} arc_line;

static void arc(arc_line *a, double y0, double y1, double d, double yc, double zc, double R,
                double sign)
{
  a->n = (size_t)((y1 - y0) / d + 0.5) + 1;
  for (size_t i = 0; i < a->n; i++) {
    a->y[i] = y0 + (y1 - y0) * (double)i / (double)(a->n - 1);
    a->z[i] = zc - sign * sqrt(R * R - (a->y[i] - yc) * (a->y[i] - yc));
  }
}

static rs_wr_input input(const arc_line *rail, const arc_line *wheel, double shift)
{
  return (rs_wr_input){.rail = {rail->n, rail->y, rail->z},
                       .wheel = {wheel->n, wheel->y, wheel->z},
                       .wheel_shift = shift,
                       .nominal_radius = 460.0,
                       .wheel_z0 = 0.0,
                       .separation = 0.01};
}

/* Semi-axes from the second moments of the pressure: Int x^2 p / Int p = a^2/5 for the Hertz
 * ellipsoid. */
static void moments(const rs_wr_patch_result *r, double *a, double *b)
{
  double m0 = 0, mx = 0, ms = 0;
  for (int j = 0; j < r->grid.ny; j++)
    for (int i = 0; i < r->grid.nx; i++) {
      const double p = r->pn[(size_t)j * r->grid.nx + i];
      const double x = r->grid.x0 + (i + 0.5) * r->grid.dx;
      const double s = r->grid.y0 + (j + 0.5) * r->grid.dy;
      m0 += p, mx += p * x * x, ms += p * s * s;
    }
  *a = sqrt(5.0 * mx / m0);
  *b = sqrt(5.0 * ms / m0);
}

/* The Hertz load of an ellipse with gap curvatures A, B at approach d (bisection on ln F). */
static double hertz_load(double d, double A, double B)
{
  double lo = log(1e-3), hi = log(1e7);
  rs_msg msg = {{0}};
  for (int it = 0; it < 100; it++) {
    rs_hertz_ellipse hz;
    rs_hertz3d(exp(0.5 * (lo + hi)), A, B, G, NU, &hz, &msg);
    if (hz.approach < d)
      lo = 0.5 * (lo + hi);
    else
      hi = 0.5 * (lo + hi);
  }
  return exp(0.5 * (lo + hi));
}

static int geometry(const rs_wr_input *in, rs_wr_geometry *geo)
{
  rs_msg msg = {{0}};
  if (rs_wr_geometry_build(in, geo, &msg) == RS_OK) return 0;
  fprintf(stderr, "geometry: %s\n", msg.text);
  ts_failures++;
  return -1;
}

static int solve(const rs_wr_geometry *geo, int n, rs_wr_solution *sol)
{
  rs_msg msg = {{0}};
  if (rs_wr_normal_solve(geo, FZ, G, NU, n, n, sol, &msg) == RS_OK) return 0;
  fprintf(stderr, "normal solve: %s\n", msg.text);
  ts_failures++;
  return -1;
}

/* (a) A rail crown of radius Rr and a wheel profile of radius Rw (convex, centred at the
 * wheel's y = 0) sampled every d mm, the wheel shifted by `shift`: first contact on the line
 * through the centres, delta = asin(shift / (Rr + Rw)), on the wheel at y_w = -Rw sin(delta),
 * its rolling radius 460 - Rw (1 - cos(delta)). */
static void circles(double Rr, double Rw, double shift, double d, int check_hertz)
{
  static arc_line rail, wheel;
  /* the rail around its contact point Rr sin(delta), the wheel around its own -Rw sin(delta),
   * far enough for the checks below (|s| <= Rr/10) */
  const double dl = asin(shift / (Rr + Rw)), hr = fmin(0.9 * Rr, fmax(20.0, 0.12 * Rr));
  const double hw = fmin(0.9 * Rw, 2.0 * hr), yr = Rr * sin(dl), yw = -Rw * sin(dl);
  arc(&rail, fmax(yr - hr, -0.9 * Rr), fmin(yr + hr, 0.9 * Rr), d, 0.0, Rr, Rr, 1.0);
  arc(&wheel, fmax(yw - hw, -0.9 * Rw), fmin(yw + hw, 0.9 * Rw), d, 0.0, -Rw, Rw, -1.0);
  rs_wr_geometry geo;
  const rs_wr_input in = input(&rail, &wheel, shift);
  if (geometry(&in, &geo)) return;
  printf("-- circles Rr %g, Rw %g, shift %g, spacing %g\n", Rr, Rw, shift, d);
  ts_check("circles: one patch", geo.npatch, 1, 0);
  const rs_wr_patch *p = &geo.patch[0];
  const double delta = asin(shift / (Rr + Rw)), r = 460.0 - Rw * (1.0 - cos(delta));
  const double Reff = 1.0 / (1.0 / Rr + 1.0 / Rw);
  /* the contact point: the minimum of the piecewise linear gap refined by a parabola
   * through three samples, O(d^2) off; the angle from a parabola through three rail
   * points, O(d^2 / R^2) */
  ts_check("circles: contact point on the rail y (mm)", p->y, Rr * sin(delta), 0.05 * d * d);
  ts_check("circles: contact point on the wheel y (mm)", p->y_wheel, -Rw * sin(delta),
           0.05 * d * d);
  ts_check("circles: contact angle (rad)", p->delta, delta, 0.05 * d * d / Rr);
  ts_check("circles: rolling radius (mm)", p->rolling_radius, r, 0.05 * d * d);
  /* h(0, s): two circles touching at the contact point separate by (Rr - sqrt(Rr^2 - s^2)) +
   * (Rw - sqrt(Rw^2 - s^2)) normal to their common tangent. The polylines' chords lie within
   * d^2 / (8 R) of their arcs, and h is measured from the contact point on the chords, so
   * within twice d^2/8 (1/Rr + 1/Rw) (once when the contact point is a vertex of both). */
  const double chord = d * d / 8.0 * (1.0 / Rr + 1.0 / Rw);
  double err = 0.0;
  for (double s = -0.1 * Rr; s <= 0.1 * Rr; s += 0.01 * d)
    err = fmax(err, fabs(rs_wr_patch_h0(p, s) - (Rr - sqrt(Rr * Rr - s * s)) -
                         (Rw - sqrt(Rw * Rw - s * s))));
  ts_check("circles: h(0, s) against the circles, |s| <= Rr/10 (mm)", err, 0.0,
           (shift == 0.0 ? 1.05 : 2.0) * chord);
  /* h(x, s) against the Hertz gap x^2 cos(delta)/(2r) + s^2/(2 Reff) on +-5 mm: the chords and
   * the circles' quartic terms s^4/8 (1/Rr^3 + 1/Rw^3) */
  rs_grid3d grid = {.nx = 50, .ny = 50, .x0 = -5.0, .y0 = -5.0, .dx = 0.2, .dy = 0.2};
  double h[2500], errh = 0.0;
  rs_wr_patch_gap(p, &grid, h);
  for (int j = 0; j < grid.ny; j++)
    for (int i = 0; i < grid.nx; i++) {
      const double x = grid.x0 + (i + 0.5) * grid.dx, s = grid.y0 + (j + 0.5) * grid.dy;
      errh =
          fmax(errh, fabs(h[j * grid.nx + i] - x * x * cos(delta) / (2 * r) - s * s / (2 * Reff)));
    }
  const double quartic = pow(5.0, 4) / 8.0 * (1.0 / pow(Rr, 3) + 1.0 / pow(Rw, 3));
  ts_check("circles: h(x, s) against x^2 cos(delta)/(2r) + s^2/(2 Reff), |x|, |s| <= 5 (mm)", errh,
           0.0, (shift == 0.0 ? 1.05 : 2.0) * chord + 1.05 * quartic);
  /* the same rail with a flank that turns back under its head, 16 and 26 mm inward (y no
   * longer increasing, as a Miniprof rail's side): the surface searched through every segment
   * (the highest point at each y), the same patch and h */
  {
    static arc_line flank;
    flank = rail;
    const double ye = rail.y[rail.n - 1], ze = rail.z[rail.n - 1];
    const double add[3][2] = {{ye, ze + 1.0}, {ye - 16.0, ze + 2.0}, {ye - 26.0, ze + 2.5}};
    for (int k = 0; k < 3; k++) {
      flank.y[flank.n] = add[k][0];
      flank.z[flank.n++] = add[k][1];
    }
    rs_wr_geometry gf;
    const rs_wr_input inf = input(&flank, &wheel, shift);
    if (geometry(&inf, &gf) == 0) {
      ts_check("circles, rail with a flank turned back: contact point y (mm)", gf.patch[0].y, p->y,
               1e-12);
      ts_check("circles, rail with a flank turned back: contact angle (rad)", gf.patch[0].delta,
               p->delta, 1e-12);
      ts_check("circles, rail with a flank turned back: h(0, Rr/20) (mm)",
               rs_wr_patch_h0(&gf.patch[0], 0.05 * Rr), rs_wr_patch_h0(p, 0.05 * Rr), 1e-12);
      rs_wr_geometry_free(&gf);
    }
  }
  if (!check_hertz) {
    rs_wr_geometry_free(&geo);
    return;
  }
  /* the normal problem against the Hertz ellipse of A = cos(delta)/(2r), B = 1/(2 Reff) under
   * F_n = F_z / cos(delta); tolerances from the two grids (about 24 and 47 cells across the
   * contact): the 40-cell errors are 0.02-0.19 %, the 80-cell ones 0.005-0.04 %. The polyline
   * must be finer than the cells: a cell's second difference of h sees the chords' kinks,
   * d^2/(8R) / ds^2 against the curvature 1/Reff (with d = 0.05 mm and 80 cells p_max moves
   * by 0.3 % from grid to grid; with d = 0.01 mm it converges, 1301.9 .. 1303.5 N/mm^2 on
   * 40 .. 100 cells). */
  rs_hertz_ellipse hz;
  rs_msg msg = {{0}};
  rs_hertz3d(FZ / cos(delta), cos(delta) / (2 * r), 1.0 / (2 * Reff), G, NU, &hz, &msg);
  for (int n = 40; n <= 80; n += 40) {
    rs_wr_solution sol;
    if (solve(&geo, n, &sol)) continue;
    const rs_wr_patch_result *q = &sol.patch[0];
    const double tol = n == 40 ? 4e-3 : 1.5e-3;
    double a, b;
    moments(q, &a, &b);
    char what[160];
    snprintf(what, sizeof what, "circles, %d cells: F_n cos(delta) = F_z (N)", n);
    ts_check(what, q->normal_force * cos(p->delta), FZ, 1e-9 * FZ);
    snprintf(what, sizeof what, "circles, %d cells: normal approach / Hertz", n);
    ts_check(what, q->approach / hz.approach, 1.0, tol);
    snprintf(what, sizeof what, "circles, %d cells: a (second moment) / Hertz", n);
    ts_check(what, a / hz.a, 1.0, tol);
    snprintf(what, sizeof what, "circles, %d cells: b (second moment) / Hertz", n);
    ts_check(what, b / hz.b, 1.0, tol);
    snprintf(what, sizeof what, "circles, %d cells: p_max / Hertz p0", n);
    ts_check(what, q->p_max / hz.p0, 1.0, tol);
    /* today's 3D normal problem on the same grid with the gap from the radii (A x^2 + B s^2):
     * for one load the approach is monotone in the gap, so the two approaches differ by at
     * most max |h_profiles - h_radii| (plus the solver's 1e-11) */
    const size_t cells = (size_t)q->grid.nx * q->grid.ny;
    double *hp = malloc(cells * sizeof *hp), *hr = malloc(cells * sizeof *hr);
    double *pr = malloc(cells * sizeof *pr), dh = 0.0, approach = 0.0;
    rs_elastic3d el;
    rs_elastic3d_work work;
    rs_wr_patch_gap(p, &q->grid, hp);
    rs_normal3d_gap(&q->grid, cos(p->delta) / (2 * p->rolling_radius), 1.0 / (2 * Reff), hr);
    for (size_t k = 0; k < cells; k++) dh = fmax(dh, fabs(hp[k] - hr[k]));
    if (rs_elastic3d_create(&el, q->grid.nx, q->grid.ny, q->grid.dx, q->grid.dy, G, NU, &msg) ==
        RS_OK) {
      if (rs_elastic3d_work_create(&work, &el, &msg) == RS_OK) {
        if (rs_normal3d_solve(&el, &work, hr, q->normal_force, NULL, pr, &approach, NULL, &msg) ==
            RS_OK) {
          snprintf(what, sizeof what,
                   "circles, %d cells: approach from the profiles' h - from the radii' (mm)", n);
          ts_check(what, q->approach - approach, 0.0, dh + 1e-11 * q->approach);
        }
        rs_elastic3d_work_free(&work);
      }
      rs_elastic3d_free(&el);
    }
    free(hp);
    free(hr);
    free(pr);
    rs_wr_solution_free(&sol);
  }
  rs_wr_geometry_free(&geo);
}

/* (b) A rail with a flat top W = 20 mm wide (z = 0) rounded by arcs of radius 20 mm, under a
 * cylindrical wheel (z = 0): the gap is a plateau, the contact point its middle. The patch
 * spans at least the flat; its pressure along the centre line x = 0 peaks near the flat's
 * ends (the end effect of a flat punch with rounded edges) rather than at the centre, where
 * the Hertz pressure has its maximum. */
static void flat_top(void)
{
  static arc_line rail, wheel;
  const double W = 20.0, Rc = 20.0;
  rail.n = 0;
  for (double y = -25.0; y <= 25.0 + 1e-9; y += 0.1) {
    const double e = fmax(fabs(y) - 0.5 * W, 0.0);
    rail.y[rail.n] = y;
    rail.z[rail.n++] = Rc - sqrt(Rc * Rc - e * e);
  }
  wheel.n = 0;
  for (double y = -40.0; y <= 40.0 + 1e-9; y += 0.5) {
    wheel.y[wheel.n] = y;
    wheel.z[wheel.n++] = 0.0;
  }
  rs_wr_geometry geo;
  const rs_wr_input in = input(&rail, &wheel, 0.0);
  if (geometry(&in, &geo)) return;
  printf("-- flat-topped rail, flat %g mm\n", W);
  ts_check("flat top: one patch", geo.npatch, 1, 0);
  ts_check("flat top: contact point in the middle of the flat (mm)", geo.patch[0].y, 0.0, 1e-12);
  ts_check("flat top: contact angle (rad)", geo.patch[0].delta, 0.0, 1e-12);
  rs_wr_solution sol;
  if (solve(&geo, 40, &sol)) {
    rs_wr_geometry_free(&geo);
    return;
  }
  const rs_wr_patch_result *q = &sol.patch[0];
  printf("flat top: extent s %.4f .. %.4f, x %.4f .. %.4f, p_max %.2f, F_n %.1f\n", q->s_extent[0],
         q->s_extent[1], q->x_extent[0], q->x_extent[1], q->p_max, q->normal_force);
  ts_check_true("flat top: the patch spans at least the flat along s",
                q->s_extent[1] - q->s_extent[0] >= W);
  /* the centre line: the row of cells nearest x = 0 */
  const int ic = (int)floor(-q->grid.x0 / q->grid.dx);
  double p_centre = 0.0, p_edge = 0.0, s_edge = 0.0, ds = q->grid.dy;
  for (int j = 0; j < q->grid.ny; j++) {
    const double s = q->grid.y0 + (j + 0.5) * ds, pv = q->pn[(size_t)j * q->grid.nx + ic];
    if (fabs(s) < 0.5 * ds + 1e-12) p_centre = fmax(p_centre, pv);
    if (pv > p_edge) p_edge = pv, s_edge = s;
  }
  printf("flat top: centre line p(0) %.2f, max %.2f at s = %.3f\n", p_centre, p_edge, s_edge);
  ts_check_true("flat top: the centre line's pressure peaks in the outer quarters of the flat "
                "(|s| > W/4)",
                fabs(s_edge) > 0.25 * W);
  ts_check_true("flat top: that peak exceeds the centre's pressure by more than 10 %",
                p_edge > 1.1 * p_centre);
  rs_wr_solution_free(&sol);
  rs_wr_geometry_free(&geo);
}

/* (d) Two crowns of radius Rr = 100 mm centred at y = -+15 mm, the second lower by g0, under a
 * convex wheel of radius Rw = 60 mm: two patches, the second with vertical gap ~g0. The load
 * sharing against an independent path: each patch a Hertz ellipse (A = cos(delta_i)/(2 r_i),
 * B = 1/(2 Reff)), dz from sum F_i cos(delta_i) = F_z by bisection. */
static void two_crowns(void)
{
  static arc_line rail, wheel;
  const double Rr = 100.0, Rw = 60.0, c = 15.0, g0 = 0.01, d = 0.05;
  rail.n = 0;
  for (double y = -40.0; y <= 40.0 + 1e-9; y += d) {
    const double z1 = Rr - sqrt(Rr * Rr - (y + c) * (y + c));
    const double z2 = g0 + Rr - sqrt(Rr * Rr - (y - c) * (y - c));
    rail.y[rail.n] = y;
    rail.z[rail.n++] = fmin(z1, z2);
  }
  arc(&wheel, -50.0, 50.0, d, 0.0, -Rw, Rw, -1.0);
  rs_wr_geometry geo;
  const rs_wr_input in = input(&rail, &wheel, 0.0);
  if (geometry(&in, &geo)) return;
  printf("-- two crowns\n");
  ts_check("two crowns: two patches", geo.npatch, 2, 0);
  if (geo.npatch != 2) {
    rs_wr_geometry_free(&geo);
    return;
  }
  const double Reff = 1.0 / (1.0 / Rr + 1.0 / Rw);
  ts_check("two crowns: the first patch's gap (mm)", geo.patch[0].gap, 0.0, 1e-6);
  /* the lower crown's gap: g0 along the vertical, up to the wheel's tilt between the two
   * contact points (|delta| ~ 0.09: g0 (1 - cos) ~ 4e-5 g0) */
  ts_check("two crowns: the second patch's gap (mm)", geo.patch[1].gap, g0, 0.01 * g0);
  ts_check("two crowns: contact angles opposite (rad)", geo.patch[0].delta + geo.patch[1].delta,
           0.0, 1e-3);
  rs_wr_solution sol;
  if (solve(&geo, 40, &sol)) {
    rs_wr_geometry_free(&geo);
    return;
  }
  double A[2], B = 1.0 / (2.0 * Reff);
  for (int k = 0; k < 2; k++) A[k] = cos(geo.patch[k].delta) / (2.0 * geo.patch[k].rolling_radius);
  double lo = 0.0, hi = 1.0, fh[2] = {0, 0};
  for (int it = 0; it < 80; it++) {
    const double dz = 0.5 * (lo + hi);
    double sum = 0.0;
    for (int k = 0; k < 2; k++) {
      const double dk = (dz - geo.patch[k].gap) * cos(geo.patch[k].delta);
      fh[k] = dk > 0 ? hertz_load(dk, A[k], B) : 0.0;
      sum += fh[k] * cos(geo.patch[k].delta);
    }
    if (sum < FZ)
      lo = dz;
    else
      hi = dz;
  }
  printf("two crowns: dz %.6g (Hertz %.6g), F %.2f %.2f (Hertz %.2f %.2f), rounds %d, solves %d\n",
         sol.dz, 0.5 * (lo + hi), sol.patch[0].normal_force, sol.patch[1].normal_force, fh[0],
         fh[1], sol.grid_rounds, sol.normal_solves);
  ts_check("two crowns: force balance sum F_n cos(delta) / F_z", sol.vertical / FZ, 1.0,
           RS_WR_FORCE_TOL);
  ts_check_true("two crowns: both patches carry load", sol.patch[0].loaded && sol.patch[1].loaded);
  for (int k = 0; k < 2; k++) {
    /* each patch's approach is (dz - gap) cos(delta) to the inner root finder's tolerance */
    ts_check("two crowns: patch approach / (dz - gap) cos(delta)",
             sol.patch[k].approach / ((sol.dz - geo.patch[k].gap) * cos(geo.patch[k].delta)), 1.0,
             10 * RS_WR_APPROACH_TOL);
    /* against the Hertz split: the 40-cell discretisation (0.1 % in the approach, case (a))
     * moves the loads by ~3/2 of that relative to the approach beyond the gap */
    ts_check("two crowns: F_n / the Hertz split's", sol.patch[k].normal_force / fh[k], 1.0, 0.01);
  }
  ts_check("two crowns: dz / the Hertz split's", sol.dz / (0.5 * (lo + hi)), 1.0, 2e-3);
  rs_wr_solution_free(&sol);
  rs_wr_geometry_free(&geo);
}

/* The shipped S1002 wheel and UIC60 rail placed at lateral displacement dy (positive toward
 * the rail) as docs/case-file.md places them: the rail's gauge point (14 mm below its top) at
 * 1435/2 from the track centre, the wheel's flange back (y = 70 in its profile) at 1360/2.
 * The rail file has its gauge side at negative y, so it is read mirrored (rail_mirror: true)
 * to face the wheel's flange. mirror: the whole arrangement mirrored (the rail as in its file,
 * the wheel mirrored), so the wheel's shift changes sign. */
static int mbench(const char *dir, double dy, double yaw, int mirror, rs_profile *rail,
                  rs_profile *wheel, rs_wr_geometry *geo)
{
  char path[1024];
  rs_msg msg = {{0}};
  const rs_profile_opts facing = {.mirror = 1, .scale = 1.0},
                        ro = {.mirror = !mirror, .scale = 1.0},
                        wo = {.mirror = mirror, .scale = 1.0};
  snprintf(path, sizeof path, "%s/MBench_UIC60_v3.prr", dir);
  rs_profile gauge = {0};
  double yg = 0.0;
  if (rs_profile_read(&gauge, path, &facing, &msg) != RS_OK) goto fail;
  const rs_wr_polyline gl = {gauge.n, gauge.y, gauge.z};
  rs_wr_gauge_point(&gl, 14.0, &yg);
  rs_profile_free(&gauge);
  if (rs_profile_read(rail, path, &ro, &msg) != RS_OK) goto fail;
  snprintf(path, sizeof path, "%s/MBench_S1002_v3.prw", dir);
  if (rs_profile_read(wheel, path, &wo, &msg) != RS_OK) goto fail;
  const double shift = 717.5 + yg - 680.0 - 70.0 - dy;
  rs_wr_input in = {.rail = {rail->n, rail->y, rail->z},
                    .wheel = {wheel->n, wheel->y, wheel->z},
                    .wheel_shift = mirror ? -shift : shift,
                    .nominal_radius = 460.0,
                    .separation = 0.01,
                    .yaw = yaw,
                    .axle_offset = 750.0};
  rs_profile_z_at(wheel, 0.0, &in.wheel_z0);
  if (rs_wr_geometry_build(&in, geo, &msg) != RS_OK) goto fail;
  return 0;
fail:
  fprintf(stderr, "%s\n", msg.text);
  ts_failures++;
  return -1;
}

/* (c) Mirror symmetry: the same patch mirrored, to rounding (the mirrored grid is the same
 * grid reflected; the normal solves differ only in the order of their sums). */
static void mirrored(const char *dir, double dy)
{
  rs_profile rail[2] = {{0}}, wheel[2] = {{0}};
  rs_wr_geometry geo[2];
  rs_wr_solution sol[2];
  int ok = 1;
  for (int m = 0; m < 2; m++) {
    if (mbench(dir, dy, 0.0, m, &rail[m], &wheel[m], &geo[m])) return;
    ok = ok && solve(&geo[m], 40, &sol[m]) == 0;
  }
  if (ok) {
    printf("-- S1002/UIC60 at %g mm, mirrored\n", dy);
    ts_check("mirror: patches", geo[1].npatch, geo[0].npatch, 0);
    const rs_wr_patch *p = &geo[0].patch[0], *q = &geo[1].patch[geo[1].npatch - 1];
    ts_check("mirror: contact point y (mm), mirrored", q->y, -p->y, 1e-9);
    ts_check("mirror: contact angle (rad), opposite", q->delta, -p->delta, 1e-12);
    ts_check("mirror: rolling radius (mm)", q->rolling_radius, p->rolling_radius, 1e-9);
    const rs_wr_patch_result *a = &sol[0].patch[0], *b = &sol[1].patch[sol[1].npatch - 1];
    ts_check("mirror: F_n (relative)", b->normal_force / a->normal_force, 1.0, 1e-12);
    ts_check("mirror: p_max (relative)", b->p_max / a->p_max, 1.0, 1e-9);
    ts_check("mirror: vertical approach (relative)", sol[1].dz / sol[0].dz, 1.0, 1e-9);
    ts_check("mirror: contact area (mm^2)", b->area, a->area, 1e-9 * a->area);
    ts_check("mirror: s extent mirrored (mm)", b->s_extent[0], -a->s_extent[1], 1e-9);
  }
  for (int m = 0; m < 2; m++) {
    if (ok) rs_wr_solution_free(&sol[m]);
    rs_wr_geometry_free(&geo[m]);
    rs_profile_free(&rail[m]);
    rs_profile_free(&wheel[m]);
  }
}

/* S1002 on UIC60 (as shipped, 1:40): at 8 mm the contact is on the flange, whose flank the
 * S1002 drawing inclines at 70 degrees; one patch carries F_z / cos(delta). */
static void flange(const char *dir)
{
  rs_profile rail = {0}, wheel = {0};
  rs_wr_geometry geo;
  if (mbench(dir, 8.0, 0.0, 0, &rail, &wheel, &geo)) return;
  printf("-- S1002/UIC60 at 8 mm\n");
  ts_check("flange: one patch", geo.npatch, 1, 0);
  ts_check("flange: contact angle (deg), the S1002 flank's 70", geo.patch[0].delta * 180 / RS_PI,
           70.0, 1.0);
  rs_wr_solution sol;
  if (solve(&geo, 40, &sol) == 0) {
    ts_check("flange: F_n cos(delta) = F_z (N)",
             sol.patch[0].normal_force * cos(geo.patch[0].delta), FZ, 1e-9 * FZ);
    rs_wr_solution_free(&sol);
  }
  rs_wr_geometry_free(&geo);
  rs_profile_free(&rail);
  rs_profile_free(&wheel);
}

/* (e) Yaw (docs/model.md §20 "Yaw"). A cone r(u) = 460 + m u (its profile the line z = m u)
 * yawed by psi about the vertical 750 mm from its profile's origin, on a rail crown of radius
 * Rr sampled every d: the cone's lowest points for each track y form the straight locus
 * y(u) = u + shift + (750 - u)(1 - cos psi) - r(u) m tan(psi) sin(psi),
 * z(u) = m u - r(u)(1 - cos theta), sin theta = -m tan psi, of slope m / (cos psi cos theta):
 * the contact angle; the crown touches it where its own slope is that, y = Rr sin(delta). The
 * contact point lies ahead of the axle's point at its y by x = r sin(theta) / cos(psi) and
 * below the axle by r cos(theta). */
static void yawed_cone(double m, double psi, double Rr)
{
  static arc_line rail, wheel;
  const double tp = tan(psi), st = -m * tp, ct = sqrt(1.0 - st * st);
  const double delta = atan(m / (cos(psi) * ct)), yc = Rr * sin(delta), d = 0.01;
  arc(&rail, yc - 20.0, fmin(yc + 20.0, 0.995 * Rr), d, 0.0, Rr, Rr, 1.0);
  wheel.n = 121;
  for (size_t i = 0; i < wheel.n; i++)
    wheel.y[i] = -30.0 + 0.5 * (double)i, wheel.z[i] = m * wheel.y[i];
  rs_wr_input in = input(&rail, &wheel, yc);
  in.yaw = psi;
  in.axle_offset = 750.0;
  rs_wr_geometry geo;
  if (geometry(&in, &geo)) return;
  printf("-- cone m %g yawed %g rad on a crown of %g mm\n", m, psi, Rr);
  ts_check("yawed cone: one patch", geo.npatch, 1, 0);
  const rs_wr_patch *p = &geo.patch[0];
  /* u of the contact from y(u) = yc (linear in u) */
  const double vers = 1.0 - cos(psi), k = m * tp * sin(psi);
  const double u = (yc - yc - 750.0 * vers + 460.0 * k) / (1.0 - vers - m * k);
  const double r = 460.0 + m * u;
  ts_check("yawed cone: contact angle (rad)", p->delta, delta, 0.05 * d * d / Rr);
  ts_check("yawed cone: contact point on the rail y (mm)", p->y, yc, 0.05 * d * d);
  /* the wheel's side is linear in u: its y, radius and lead to the rail point's error */
  ts_check("yawed cone: contact point on the wheel y (mm)", p->y_wheel, u, 0.1 * d * d);
  ts_check("yawed cone: rolling radius (mm)", p->rolling_radius, r, 0.1 * m * d * d);
  ts_check("yawed cone: lead x = r sin(theta)/cos(psi) (mm)", p->x, r * st / cos(psi),
           1e-9 * r + 0.1 * d * d);
  ts_check("yawed cone: axle height r cos(theta) (mm)", p->axle_height, r * ct,
           1e-9 * r + 0.1 * d * d);
  /* along the track the cone curves by cos^2(theta) cos^2(psi) / (r sqrt(1 + m^2)) (a straight
   * profile: no curvature of its own), to the radius' error */
  ts_check("yawed cone: curvature along x (1/mm)", p->curv_x,
           ct * ct * cos(psi) * cos(psi) / (r * sqrt(1.0 + m * m)), 0.2 * m * d * d / (r * r));
  rs_wr_geometry_free(&geo);
}

/* The exact undeformed distance of a yawed wheel over a rail crown, both circles in their
 * profiles (rail: z = Rr - sqrt(Rr^2 - y^2); wheel: z = sqrt(Rw^2 - u^2) - Rw, or its negative
 * for a concave wheel, radius 460 + z), at (x, s) of the patch's tangent plane: the rail and the
 * wheel met along the normal through that point, the wheel by bisection on the surface of
 * revolution |P - axis| = r(u(P)) about the turned axle. */
typedef struct yaw_scene {
  double Rr, Rw, psi, L0, shift, axle_z; /* axle_z: the axle's z (downward), track frame */
  double concave;                        /* 1: the wheel's profile z = Rw - sqrt(Rw^2 - u^2) */
} yaw_scene;

static double exact_w(const yaw_scene *sc, const double q[3], const double n[3], int wheel)
{
  double lo = -3.0, hi = 3.0;
  for (int it = 0; it < 200; it++) {
    const double w = 0.5 * (lo + hi), P[3] = {q[0] + w * n[0], q[1] + w * n[1], q[2] + w * n[2]};
    double g;
    if (!wheel) { /* below the rail's surface: g > 0 */
      g = P[2] - (sc->Rr - sqrt(sc->Rr * sc->Rr - P[1] * P[1]));
    } else { /* outside the wheel: g > 0 */
      const double a[3] = {-sin(sc->psi), cos(sc->psi), 0.0};
      const double c[3] = {0.0, sc->shift + sc->L0, sc->axle_z};
      const double dp[3] = {P[0] - c[0], P[1] - c[1], P[2] - c[2]};
      const double along = dp[0] * a[0] + dp[1] * a[1], u = along + sc->L0;
      const double rho = sqrt(dp[0] * dp[0] + dp[1] * dp[1] + dp[2] * dp[2] - along * along);
      const double zw = sqrt(sc->Rw * sc->Rw - u * u) - sc->Rw;
      g = rho - (460.0 + (sc->concave ? -zw : zw));
    }
    if (g > 0)
      hi = w;
    else
      lo = w;
  }
  return 0.5 * (lo + hi);
}

/* The largest difference between rs_wr_patch_h and the exact h over |x - xo(0)|, |s| <= e,
 * both from their values at the contact point. */
static double yaw_h_error(const yaw_scene *sc, const rs_wr_patch *p, double X0, double e)
{
  const double t[3] = {0.0, cos(p->delta), sin(p->delta)},
               n[3] = {0.0, -sin(p->delta), cos(p->delta)};
  double err = 0.0, ref = 0.0;
  for (int i = -8; i <= 8; i++)
    for (int j = -8; j <= 8; j++) {
      const double x = e * i / 8.0, s = e * j / 8.0;
      const double q[3] = {X0 + x, p->y + s * t[1], p->z_rail + s * t[2]};
      const double h = exact_w(sc, q, n, 0) - exact_w(sc, q, n, 1);
      const double dh = rs_wr_patch_h(p, x, s) - h;
      if (i == 0 && j == 0) ref = dh;
      err = fmax(err, fabs(dh - ref));
    }
  return err;
}

/* A yawed wheel whose profile is a circle of radius Rw (convex, or concave as a flange root)
 * on a rail crown of radius Rr, both finely sampled, at the unyawed contact angle dl: h(x, s) =
 * h(s) + curv_x (x - xo(s))^2 / 2 is the exact distance to second order in (x, s)
 * (docs/model.md §20 "Yaw"), so its error shrinks about eightfold when the region +-e halves
 * (more than fourfold required: the polylines' chords, d^2/8 (1/Rr + 1/Rw) <= 2e-5 mm, and the
 * fourth-order terms), and it is a small part of what the yaw changes (against the unyawed
 * x^2 cos(delta)/(2r)). The concave wheel's own curvature along its profile lowers curv_x by
 * z'' sin^2(psi) (5 % at 50 mrad; with the opposite sign the error is 31 % of the change) and
 * skews the patch (the locus' lead moves by r z'' tan(psi) per mm of profile). */
static void yawed_torus(double Rr, double Rw, int concave, double dl, double psi, double e)
{
  static arc_line rail, wheel;
  const double d = 0.02, sg = concave ? -1.0 : 1.0;
  /* the unyawed contact: the rail at Rr sin(dl), the wheel at -sg Rw sin(dl) */
  const double yr = Rr * sin(dl), yw = -sg * Rw * sin(dl), shift = yr - yw;
  arc(&rail, fmax(yr - 6.0, -0.95 * Rr), fmin(yr + 6.0, 0.95 * Rr), d, 0.0, Rr, Rr, 1.0);
  arc(&wheel, fmax(yw - 6.0, -0.95 * Rw), fmin(yw + 6.0, 0.95 * Rw), d, 0.0, -sg * Rw, Rw, -sg);
  rs_wr_input in = input(&rail, &wheel, shift);
  in.yaw = psi;
  in.axle_offset = 750.0;
  rs_wr_geometry geo;
  if (geometry(&in, &geo)) return;
  printf("-- %s wheel Rw %g yawed %g rad on a crown of %g mm\n", concave ? "concave" : "convex", Rw,
         psi, Rr);
  ts_check("yawed circles: one patch", geo.npatch, 1, 0);
  const rs_wr_patch *p = &geo.patch[0];
  /* the axle's z: the wheel's lowest point over the whole locus lies on the rail at first
   * contact (z_track = z_profile + wheel_z, radius 460 + z_profile) */
  const yaw_scene sc = {Rr, Rw, psi, 750.0, shift, geo.wheel_z - 460.0, concave};
  /* the contact point's x from the wheelset's centre: the axle's point at its y, plus the lead */
  const double X0 = -(p->y - shift - 750.0) * tan(psi) + p->x;
  const double e1 = yaw_h_error(&sc, p, X0, e), e2 = yaw_h_error(&sc, p, X0, 0.5 * e);
  printf("   h(x, s) error on +-%g mm %.3g mm, on +-%g mm %.3g mm\n", e, e1, 0.5 * e, e2);
  ts_check("yawed circles: h error shrinks beyond second order (ratio on +-e / +-e/2 > 4)",
           e1 / e2 > 4.0, 1, 0);
  /* what the yaw changes: the locus offset xo(s) and curv_x against the unyawed formula */
  double change = 0.0;
  for (int i = -8; i <= 8; i++)
    for (int j = -8; j <= 8; j++) {
      const double x = e * i / 8.0, s = e * j / 8.0;
      change = fmax(change, fabs(rs_wr_patch_h(p, x, s) - rs_wr_patch_h0(p, s) -
                                 x * x * cos(p->delta) / (2.0 * p->rolling_radius)));
    }
  printf("   the yaw's change of h on +-%g mm %.3g mm\n", e, change);
  ts_check("yawed circles: h error below a tenth of the yaw's change on +-e", e1 < 0.1 * change, 1,
           0);
  rs_wr_geometry_free(&geo);
}

/* A concave profile (5 mm) at 0.1 rad on a 3 mm crown: z'' sin^2(psi) = 4.5e-3 outweighs the
 * circle's cos^2(theta) cos^2(psi)/r = 2.1e-3, the wheel curves toward the rail along the
 * track, the locus is a saddle and not the closest approach: refused. */
static void yawed_saddle(void)
{
  static arc_line rail, wheel;
  const double dl = 0.7, yr = 3.0 * sin(dl), yw = 5.0 * sin(dl);
  arc(&rail, -2.85, 2.85, 0.01, 0.0, 3.0, 3.0, 1.0);
  arc(&wheel, -4.75, 4.75, 0.01, 0.0, 5.0, 5.0, 1.0);
  rs_wr_input in = input(&rail, &wheel, yr - yw);
  in.yaw = 0.1;
  in.axle_offset = 750.0;
  rs_wr_geometry geo;
  rs_msg msg = {{0}};
  const int status = rs_wr_geometry_build(&in, &geo, &msg);
  printf("-- concave wheel Rw 5 yawed 0.1 rad on a crown of 3 mm: %s\n", msg.text);
  ts_check("yawed saddle: refused as input", status, RS_ERR_INPUT, 0);
  ts_check("yawed saddle: the message says why", strstr(msg.text, "curves toward the rail") != NULL,
           1, 0);
  in.yaw = 0.0;
  if (!geometry(&in, &geo)) { /* unyawed the same profiles are a contact */
    ts_check("yawed saddle: unyawed, one patch", geo.npatch, 1, 0);
    rs_wr_geometry_free(&geo);
  }
}

/* psi -> -psi mirrors the wheel along the track: the same patch with the lead's sign
 * reversed (every other number the same to rounding: they depend on psi through cos psi,
 * sin psi tan psi and sin^2 theta). And psi -> 0: the unyawed patch, the lead -r m psi. */
static void yaw_symmetry(const char *dir, double dy, double psi)
{
  rs_profile rail[3] = {{0}}, wheel[3] = {{0}};
  rs_wr_geometry geo[3];
  const double yaw[3] = {psi, -psi, 1e-7};
  int ok = 1;
  for (int k = 0; k < 3 && ok; k++) ok = !mbench(dir, dy, yaw[k], 0, &rail[k], &wheel[k], &geo[k]);
  if (ok) {
    printf("-- S1002/UIC60 at %g mm, yaw +-%g rad and 1e-7 rad\n", dy, psi);
    ts_check("yaw symmetry: patches", geo[1].npatch, geo[0].npatch, 0);
    const rs_wr_patch *a = &geo[0].patch[0], *b = &geo[1].patch[0];
    ts_check("yaw symmetry: contact point y (mm)", b->y, a->y, 1e-12);
    ts_check("yaw symmetry: contact angle (rad)", b->delta, a->delta, 1e-14);
    ts_check("yaw symmetry: rolling radius (mm)", b->rolling_radius, a->rolling_radius, 1e-12);
    ts_check("yaw symmetry: lead x (mm), opposite", b->x, -a->x, 1e-12);
    ts_check("yaw symmetry: h(1, 0.5) (mm)", rs_wr_patch_h(b, -1.0, 0.5),
             rs_wr_patch_h(a, 1.0, 0.5), 1e-12);
    rs_wr_solution sol[2];
    if (solve(&geo[0], 40, &sol[0]) == 0) {
      if (solve(&geo[1], 40, &sol[1]) == 0) {
        const rs_wr_patch_result *ra = &sol[0].patch[0], *rb = &sol[1].patch[0];
        ts_check("yaw symmetry: F_n (relative)", rb->normal_force / ra->normal_force, 1.0, 1e-9);
        ts_check("yaw symmetry: p_max (relative)", rb->p_max / ra->p_max, 1.0, 1e-9);
        ts_check("yaw symmetry: x extent mirrored (mm)", rb->x_extent[0], -ra->x_extent[1], 1e-9);
        rs_wr_solution_free(&sol[1]);
      }
      rs_wr_solution_free(&sol[0]);
    }
    /* the small-yaw limit: against the unyawed patch (geo[2] at 1e-7 against mbench at 0) */
    rs_profile r0 = {0}, w0 = {0};
    rs_wr_geometry g0;
    if (!mbench(dir, dy, 0.0, 0, &r0, &w0, &g0)) {
      const rs_wr_patch *c = &geo[2].patch[0], *z = &g0.patch[0];
      ts_check("small yaw: contact point y (mm)", c->y, z->y, 1e-6);
      ts_check("small yaw: contact angle (rad)", c->delta, z->delta, 1e-8);
      ts_check("small yaw: rolling radius (mm)", c->rolling_radius, z->rolling_radius, 1e-6);
      double err = 0.0, hmax = 0.0;
      for (double x = -5.0; x <= 5.0; x += 0.5)
        for (double s = -5.0; s <= 5.0; s += 0.25) {
          err = fmax(err, fabs(rs_wr_patch_h(c, x, s) - rs_wr_patch_h(z, x, s)));
          hmax = fmax(hmax, rs_wr_patch_h(z, x, s));
        }
      /* the yawed curvature along x from the wheel's slope, the unyawed from the rail's: they
       * differ by the polylines' kinks at the contact point, a percent of x^2 cos(delta)/(2r) */
      ts_check("small yaw: h(x, s) on +-5 mm, relative to its largest", err / hmax, 0.0, 0.01);
      rs_wr_geometry_free(&g0);
    }
    rs_profile_free(&r0);
    rs_profile_free(&w0);
  }
  for (int k = 0; k < 3; k++) {
    if (ok) rs_wr_geometry_free(&geo[k]);
    rs_profile_free(&rail[k]);
    rs_profile_free(&wheel[k]);
  }
}

int main(int argc, char **argv)
{
  if (argc < 2) {
    fprintf(stderr, "usage: test_wr_contact PROFILE_DIR\n");
    return 2;
  }
  circles(300.0, 1000.0, 0.0, 0.1, 1);
  circles(50.0, 200.0, 100.0, 0.01, 1);
  circles(50.0, 200.0, 100.0, 0.2, 0);
  flat_top();
  mirrored(argv[1], 3.0);
  two_crowns();
  flange(argv[1]);
  yawed_cone(0.5, 0.02, 300.0);
  yawed_cone(2.75, 0.024, 400.0);
  yawed_torus(40.0, 60.0, 0, asin(0.6), 0.024, 2.0);
  yawed_torus(12.0, 20.0, 1, 0.7, 0.05, 1.0);
  yawed_saddle();
  yaw_symmetry(argv[1], 3.0, 0.0072);
  yaw_symmetry(argv[1], 8.0, 0.0192);
  printf("%s: %d failure(s)\n", argv[0], ts_failures);
  return ts_failures ? 1 : 0;
}
