/* Profile files (src/io/profile.c): one analytic circle arc y, z = R - sqrt(R^2 - y^2)
 * written as a two-column table, a SIMPACK .prr and a Miniprof .ban file reads back at its
 * nodes exactly (the numbers are printed with 17 digits, which read back to the same
 * double); mirroring and scaling are exact; the moving least-squares smoothing reproduces
 * a quadratic z(y) to rounding and damps a zigzag.
 *
 * Usage: test_profile WORKDIR */
#include "io/profile.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NP 41
static int failures;

static void check(int ok, const char *what)
{
  printf("%s: %s\n", ok ? "ok" : "FAIL", what);
  if (!ok) failures++;
}

/* The arc's nodes: y from -20 to 20 mm, unevenly spaced (y^3 spacing near the ends). */
static void arc(double *y, double *z)
{
  const double R = 60.0;
  for (int i = 0; i < NP; i++) {
    const double s = -1.0 + 2.0 * i / (NP - 1);
    y[i] = 20.0 * (0.7 * s + 0.3 * s * s * s);
    z[i] = R - sqrt(R * R - y[i] * y[i]);
  }
}

static void path_in(char *buf, size_t len, const char *dir, const char *name)
{
  snprintf(buf, len, "%s/%s", dir, name);
}

static int read_ok(rs_profile *p, const char *path, const rs_profile_opts *o)
{
  rs_msg msg = {{0}};
  int status = rs_profile_read(p, path, o, &msg);
  if (status != RS_OK) printf("  %s: %s\n", path, msg.text);
  return status == RS_OK;
}

static int same(const rs_profile *p, const double *y, const double *z, int n)
{
  if ((int)p->n != n) return 0;
  for (int i = 0; i < n; i++)
    if (p->y[i] != y[i] || p->z[i] != z[i]) return 0;
  return 1;
}

int main(int argc, char **argv)
{
  if (argc != 2) {
    fprintf(stderr, "usage: %s WORKDIR\n", argv[0]);
    return 2;
  }
  const char *dir = argv[1];
  double y[NP], z[NP];
  arc(y, z);
  char table[1024], prr[1024], ban[1024], prr_m[1024];
  path_in(table, sizeof table, dir, "arc.txt");
  path_in(prr, sizeof prr, dir, "arc.prr");
  path_in(ban, sizeof ban, dir, "arc.ban");
  path_in(prr_m, sizeof prr_m, dir, "arc_m.prr");

  /* the table: comments, a blank line, a comma-separated row */
  FILE *f = fopen(table, "w");
  if (!f) {
    perror(table);
    return 2;
  }
  fprintf(f, "# circle arc R = 60 mm\n\n");
  for (int i = 0; i < NP; i++)
    fprintf(f, i == 3 ? "%.17g, %.17g  # a comma\n" : "%.17g %.17g\n", y[i], z[i]);
  fclose(f);

  /* SIMPACK: header blocks, '!' comments, a weight column, a commented-out point */
  f = fopen(prr, "w");
  fprintf(f, "! SIMPACK rail profile\n  header.begin\n    version = 1 ! flag\n"
             "    type = 0\n  header.end\n  spline.begin\n    approx.smooth = 0\n"
             "    units.len.f = +1.000000000000000e+03 ! mm\n    point.begin\n"
             "    ! y z weight\n!99.0 99.0\n");
  for (int i = 0; i < NP; i++) fprintf(f, "%.17g\t%.17g%s\n", y[i], z[i], i % 2 ? "\t1.0" : "");
  fprintf(f, "    point.end\n  spline.end\n! end\n");
  fclose(f);

  /* the same in metres: units.len.f = 1 */
  f = fopen(prr_m, "w");
  fprintf(f, "spline.begin\nunits.len.f = 1.0\npoint.begin\n");
  for (int i = 0; i < NP; i++) fprintf(f, "%.17g %.17g\n", y[i] / 1000.0, z[i] / 1000.0);
  fprintf(f, "point.end\nspline.end\n");
  fclose(f);

  /* Miniprof: a header (with numbers in it) up to a blank line, '"' marks, more columns;
   * written from the last point to the first (stored with y increasing all the same) */
  f = fopen(ban, "w");
  fprintf(f,
          "Filename=arc.ban\nXYPoints=%d\nRefPoint1=0.0000, 0.0000\n32.58 37.11 14.71\n"
          "ColumnDef=X,Y,A\n\n",
          NP);
  for (int i = NP - 1; i >= 0; i--)
    fprintf(f, "%s%.17g %.17g -1.4190 0.005\n", i % 5 ? " " : "\"", y[i], z[i]);
  fclose(f);

  rs_profile pt, ps, pm, pmm;
  const rs_profile_opts plain = {0};
  if (!read_ok(&pt, table, &plain) || !read_ok(&ps, prr, &plain) || !read_ok(&pm, ban, &plain) ||
      !read_ok(&pmm, prr_m, &plain))
    return 1;
  check(pt.format == RS_PROFILE_TABLE && ps.format == RS_PROFILE_SIMPACK &&
            pm.format == RS_PROFILE_MINIPROF,
        "formats from the extensions");
  check(same(&pt, y, z, NP), "table: the arc's nodes read back exactly");
  check(same(&ps, y, z, NP), "SIMPACK .prr: the same points exactly");
  check(same(&pm, y, z, NP), "Miniprof .ban (written in reverse): the same points exactly");
  check(pt.monotone && ps.monotone && pm.monotone, "the arc is z(y), y increasing");
  double dev = 0.0;
  for (int i = 0; i < NP; i++) dev = fmax(dev, fmax(fabs(pmm.y[i] - y[i]), fabs(pmm.z[i] - z[i])));
  printf("  units.len.f = 1 (metres): largest difference %.3g mm\n", dev);
  check(dev <= 1e-12, "SIMPACK in metres: the points in mm to rounding (1e-12 mm)");

  /* mirror: y -> -y, stored with y increasing (so in reverse order); scale exact */
  rs_profile mir, sc, both;
  const rs_profile_opts om = {.mirror = 1}, os = {.scale = 25.4}, ob = {.mirror = 1, .scale = 0.5};
  if (!read_ok(&mir, table, &om) || !read_ok(&sc, table, &os) || !read_ok(&both, prr, &ob))
    return 1;
  int ok_m = mir.n == NP, ok_s = sc.n == NP, ok_b = both.n == NP;
  for (int i = 0; i < NP; i++) {
    const int j = NP - 1 - i;
    ok_m = ok_m && mir.y[i] == -y[j] && mir.z[i] == z[j];
    ok_s = ok_s && sc.y[i] == y[i] * 25.4 && sc.z[i] == z[i] * 25.4;
    ok_b = ok_b && both.y[i] == -0.5 * y[j] && both.z[i] == 0.5 * z[j];
  }
  check(ok_m, "mirror: y -> -y exactly");
  check(ok_s, "scale 25.4: every coordinate times 25.4 exactly");
  check(ok_b, "mirror and scale 0.5 together");

  /* smoothing: a quadratic z(y) is reproduced (the fit's basis holds it), to rounding */
  char quad[1024], zig[1024];
  path_in(quad, sizeof quad, dir, "quadratic.txt");
  path_in(zig, sizeof zig, dir, "zigzag.txt");
  f = fopen(quad, "w");
  double qy[NP], qz[NP];
  for (int i = 0; i < NP; i++) {
    qy[i] = y[i] + 3.0;
    qz[i] = 1.5 - 0.02 * qy[i] + 0.004 * qy[i] * qy[i];
    fprintf(f, "%.17g %.17g\n", qy[i], qz[i]);
  }
  fclose(f);
  rs_profile pq;
  const rs_profile_opts smooth = {.smoothing = 2.5};
  if (!read_ok(&pq, quad, &smooth)) return 1;
  double qdev = 0.0;
  for (int i = 0; i < NP; i++) qdev = fmax(qdev, fabs(pq.z[i] - qz[i]) + fabs(pq.y[i] - qy[i]));
  printf("  smoothing 2.5 mm of a quadratic: largest change %.3g mm\n", qdev);
  check(qdev <= 1e-9, "smoothing leaves a quadratic z(y) unchanged (1e-9 mm)");

  /* and damps a zigzag of +-0.01 mm on a line (the weights over +-2.5 mm average ~8 points) */
  f = fopen(zig, "w");
  for (int i = 0; i < 81; i++)
    fprintf(f, "%.17g %.17g\n", 0.5 * i, 0.1 * i + (i % 2 ? 0.01 : -0.01));
  fclose(f);
  rs_profile pz;
  if (!read_ok(&pz, zig, &smooth)) return 1;
  double zdev = 0.0;
  for (size_t i = 10; i + 10 < pz.n; i++) zdev = fmax(zdev, fabs(pz.z[i] - 0.1 * (double)i));
  printf("  smoothing 2.5 mm of a +-0.01 mm zigzag: largest deviation from the line %.3g mm\n",
         zdev);
  check(zdev < 0.002, "smoothing damps a zigzag of +-0.01 mm at least fivefold");

  rs_profile_free(&pt);
  rs_profile_free(&ps);
  rs_profile_free(&pm);
  rs_profile_free(&pmm);
  rs_profile_free(&mir);
  rs_profile_free(&sc);
  rs_profile_free(&both);
  rs_profile_free(&pq);
  rs_profile_free(&pz);
  printf("%s\n", failures ? "FAILED" : "all passed");
  return failures ? 1 : 0;
}
