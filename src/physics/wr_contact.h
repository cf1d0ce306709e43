/* Wheel-rail contact from profiles (docs/model.md §20): the vertical gap between a rail and a
 * wheel profile, its minima grouped into contact patches, each patch's tangent plane and
 * undeformed distance h(x, s), and the normal problem on every patch with one vertical wheel
 * load shared between them.
 *
 * Coordinates (mm): y lateral toward the track centre, z downward (the convention of the
 * Manchester benchmark's files), x along the track. The rail profile is given in track
 * coordinates (its inclination applied), its material below its surface (z larger); the
 * wheel profile in its own coordinates (z measured from the nominal rolling radius, its
 * material above the surface), placed at y_track = y_wheel + wheel_shift. The rail is
 * straight along x; the wheel a body of revolution about an axle along y. */
#ifndef ROLLSIM_WR_CONTACT_H
#define ROLLSIM_WR_CONTACT_H

#include <stddef.h>

#include "physics/normal3d.h"
#include "base/status.h"

/* Most patches kept: the lowest minima of the gap win. */
#define RS_WR_MAX_PATCHES 8

/* A profile as a polyline (y, z) in mm, y not necessarily monotone. */
typedef struct rs_wr_polyline {
  size_t n;
  const double *y, *z;
} rs_wr_polyline;

typedef struct rs_wr_input {
  rs_wr_polyline rail;   /* track coordinates */
  rs_wr_polyline wheel;  /* wheel profile coordinates */
  double wheel_shift;    /* mm: y_track = y_wheel + wheel_shift */
  double nominal_radius; /* mm, the wheel's radius where its profile has z = wheel_z0 */
  double wheel_z0;       /* mm, the wheel profile's z at its origin */
  double separation;     /* mm: two gap minima are separate patches when the gap rises
                          * more than this above the higher of them between them */
  double yaw;            /* rad, of the wheelset about the vertical (0: the axle along y) */
  double axle_offset;    /* mm, along the axle from the wheelset's centre (the yaw's pivot)
                          * out to the wheel profile's origin */
} rs_wr_input;

typedef struct rs_wr_patch {
  double y;              /* lateral position of the contact point, track coordinates */
  double z_rail;         /* the rail surface there */
  double y_wheel;        /* the contact point in the wheel profile's coordinates */
  double z_wheel;        /*   (z_wheel the wheel profile's z there) */
  double gap;            /* vertical gap there with the wheel at first contact, mm (0 for
                          * the first) */
  double delta;          /* contact angle, rad: atan of the rail's slope dz/dy there
                          * (positive toward the flange) */
  double rolling_radius; /* the wheel's radius there, mm */
  double x;              /* mm, the contact point's lead along the track from the axle's
                          * point at the same lateral position (0 without yaw) */
  double axle_height;    /* mm, the axle above the contact point (the rolling radius without
                          * yaw) */
  double curv_x;         /* 1/mm, the wheel's normal curvature along the track at the contact
                          * point (cos(delta)/r without yaw) */
  double y_lo, y_hi;     /* the patch's lateral range: between the gap maxima that separate
                          * it from its neighbours (or the ends of the common range) */
  /* h(0, s): the profiles' separation normal to the tangent plane against s (along the
   * tangent, from the contact point), on the union of both profiles' points within the
   * patch's range; s increasing. With yaw the wheel's side is its contact locus: h is then
   * the least separation over x at each s, reached at x = xo (NULL without yaw). */
  size_t ns;
  double *s, *h, *xo;
} rs_wr_patch;

typedef struct rs_wr_geometry {
  double wheel_z; /* z_track = z_wheel + wheel_z at first contact (min gap 0) */
  size_t n;       /* gap samples: the union of both profiles' points in the common */
  double *y, *g;  /*   lateral range; g = z_rail - z_wheel_track >= 0 */
  int npatch;     /* patches, in increasing y */
  int minima;     /* local minima of the gap found (before grouping) */
  rs_wr_patch patch[RS_WR_MAX_PATCHES];
} rs_wr_geometry;

/* The gap, its minima and the patches. RS_ERR_INPUT when the profiles share no lateral range
 * or the closest approach lies at an end of it (the wheel off the rail). */
int rs_wr_geometry_build(const rs_wr_input *in, rs_wr_geometry *geo, rs_msg *msg);
void rs_wr_geometry_free(rs_wr_geometry *geo);

/* h(0, s) of a patch by linear interpolation of its table (s within the table's range). */
double rs_wr_patch_h0(const rs_wr_patch *p, double s);

/* The undeformed distance of a patch at (x, s): h(0, s) + x^2 cos(delta) / (2 r); with yaw
 * h(s) + curv_x (x - xo(s))^2 / 2 (docs/model.md §20). */
double rs_wr_patch_h(const rs_wr_patch *p, double x, double s);

/* rs_wr_patch_h at the cell centres of grid (x along the track, the grid's y along s). */
void rs_wr_patch_gap(const rs_wr_patch *p, const rs_grid3d *grid, double *h);

/* The rail's gauge point: y of its innermost (largest y) crossing of the level gauge_height
 * below its top. Returns 0 when the rail does not reach that level. */
int rs_wr_gauge_point(const rs_wr_polyline *rail, double gauge_height, double *y);

/* The normal problem of every patch under a vertical wheel load. */
typedef struct rs_wr_patch_result {
  int loaded;          /* 0: the patch stays open at this load */
  double normal_force; /* F_n, N */
  double approach;     /* normal approach (dz - gap) cos(delta), mm */
  double area;         /* mm^2, cells with p > 0 */
  double x_extent[2];  /* mm, the contact's range along x (cell faces) */
  double s_extent[2];  /* mm, along s */
  double p_max;        /* N/mm^2 */
  rs_grid3d grid;      /* the patch's grid (x, s) */
  double *pn;          /* [nx ns] pressure, N/mm^2 */
  double h_min;        /* min of h on the grid */
} rs_wr_patch_result;

typedef struct rs_wr_solution {
  double dz;         /* vertical approach of the wheel from first contact, mm */
  double vertical;   /* sum F_n cos(delta) over the patches, N */
  int npatch;        /* = geo->npatch */
  int grid_rounds;   /* grid rounds (docs/model.md §20 "Grids") */
  int normal_solves; /* normal problems solved */
  rs_wr_patch_result patch[RS_WR_MAX_PATCHES];
} rs_wr_solution;

/* Relative tolerance of the vertical force balance (the outer root finder) and of every
 * patch's normal approach against (dz - gap) cos(delta) (the inner one). */
#define RS_WR_FORCE_TOL    1e-7
#define RS_WR_APPROACH_TOL 1e-9
/* Margin of a patch's grid on each side, as a fraction of its interpenetration region. */
#define RS_WR_MARGIN       0.1
/* Grids of at least 4 times this many cells along each axis start with a scout round on a
 * quarter of the cells (docs/model.md §20 "Grids"). */
#define RS_WR_SCOUT_CELLS  4

/* The vertical approach dz with sum F_n,i cos(delta_i) = vertical_load (N) and each patch's
 * pressure on nx x ns cells; G, nu the combined elastic constants. */
int rs_wr_normal_solve(const rs_wr_geometry *geo, double vertical_load, double shear_modulus,
                       double poisson_ratio, int nx, int ns, rs_wr_solution *sol, rs_msg *msg);
void rs_wr_solution_free(rs_wr_solution *sol);

#endif
