/* Wheel and rail profiles read from files (docs/case-file.md "Wheel-rail profiles"):
 * plain two-column tables, SIMPACK .prr/.prw and Miniprof .ban/.whl. A profile is a
 * polyline (y, z) in mm, y lateral and z vertical as the file gives them (the SIMPACK and
 * Miniprof files of the Manchester benchmark: z positive downward), stored with y
 * increasing from the first point to the last. */
#ifndef ROLLSIM_PROFILE_H
#define ROLLSIM_PROFILE_H

#include <stddef.h>

#include "physics/history.h"
#include "physics/wr_contact.h"
#include "base/status.h"

typedef enum rs_profile_format {
  RS_PROFILE_TABLE = 0, /* two columns y z (any other extension) */
  RS_PROFILE_SIMPACK,   /* .prr (rail), .prw (wheel) */
  RS_PROFILE_MINIPROF   /* .ban (rail), .whl (wheel) */
} rs_profile_format;

/* Fewest points a profile may have (a local quadratic fit needs three; two more so that a
 * profile is more than one arc). */
#define RS_PROFILE_MIN_POINTS 5
/* Most points: the self-intersection check compares every pair of segments. */
#define RS_PROFILE_MAX_POINTS 20000

typedef struct rs_profile_opts {
  int mirror;       /* 1: y -> -y */
  double scale;     /* coordinates multiplied by this after the file's own unit (0: 1) */
  double smoothing; /* mm, length of the moving least-squares smoothing; 0: none */
} rs_profile_opts;

typedef struct rs_profile {
  rs_profile_format format;
  size_t n;
  double *y, *z; /* [n] mm */
  int monotone;  /* 1: y strictly increasing (tables and SIMPACK files require it) */
} rs_profile;

/* The profiles: block of a case (docs/case-file.md): the two profiles as read (mirrored,
 * scaled, smoothed) and the wheelset and track geometry that places them. */
typedef struct rs_wheel_rail {
  int has_rail, has_wheel;
  rs_profile rail, wheel;
  char *rail_file, *wheel_file;  /* as resolved against the case file's directory */
  double rail_inclination;       /* rad, rotation of the rail profile toward the track centre */
  double track_gauge;            /* mm, between the rails' gauge points */
  double gauge_height;           /* mm, below the top of the rail, where the gauge is measured */
  double flange_back_distance;   /* mm, between the wheels' flange backs */
  double nominal_rolling_radius; /* mm, of the wheel at its profile's origin (y = 0) */
  double flange_back_position;   /* mm, y of the wheel's flange back in its profile */
  double lateral_displacement;   /* mm, of the wheelset toward this rail (at t = 0) */
  double vertical_load;          /* N, on the wheel; 0: not given (no contact computed) */
  double patch_separation;       /* mm, the gap rise that separates two patches */
  int grid_cells[2];             /* cells of every patch's grid along x and s */
  double yaw;                    /* rad, of the wheelset about the vertical (at t = 0) */
  /* Both as histories (docs/case-file.md): constant unless the case gives a ramp, steps, sine
   * or table, which only transient runs follow (a moving wheelset, study/wheel_rail.h). */
  rs_history lateral_history, yaw_history;
  double wheel_angular_velocity; /* rad/s, of the wheel about its axle; 0: pure rolling of the
                                  * nominal rolling radius at rolling.velocity */
  double *placed;                /* [2 rail.n] the rail inclined: y then z (NULL: none) */
} rs_wheel_rail;

/* The wheel-rail contact input of the block (physics/wr_contact.h): the inclined rail, the
 * wheel placed laterally by the track gauge, flange-back distance and position and the
 * lateral displacement (docs/case-file.md). Needs both profiles; points into w. */
int rs_wheel_rail_input(const rs_wheel_rail *w, rs_wr_input *in, rs_msg *msg);

void rs_wheel_rail_free(rs_wheel_rail *w);

/* The profiles: keys a sweep on profiles varies (a path of wheelset positions, docs/case-file.md
 * "sweep:"): NAME is the key without its "profiles." prefix. rs_wheel_rail_position_key: the
 * key's unit and range (NULL when NAME is not one of them). rs_wheel_rail_set: the block with
 * NAME set to x (a constant, on a copy of the case's block: its histories are not freed); with
 * lateral_displacement the geometry must find a contact there (RS_ERR_INPUT with the reason,
 * without a file position, otherwise). */
typedef struct rs_wheel_rail_key {
  const char *name, *unit;
  double lo, hi;
} rs_wheel_rail_key;
const rs_wheel_rail_key *rs_wheel_rail_position_key(const char *name);
int rs_wheel_rail_set(rs_wheel_rail *w, const char *name, double x, rs_msg *msg);

/* The format a file name's extension stands for (case-insensitive). */
rs_profile_format rs_profile_format_of(const char *path);
const char *rs_profile_format_name(rs_profile_format f);

/* Read, check and transform a profile file. Errors (RS_ERR_INPUT) read
 * "FILE:LINE: what is wrong"; *p is then left empty. */
int rs_profile_read(rs_profile *p, const char *path, const rs_profile_opts *o, rs_msg *msg);
void rs_profile_free(rs_profile *p);

/* Moving least squares: each point replaced by the value at it of a quadratic fitted with
 * Gaussian weights exp(-(d/length)^2) to the points within 3 length: z(y) for a monotone
 * profile (d = y distance), y(s) and z(s) along the chord length s otherwise. A quadratic
 * z(y) (a polyline's straight line) is reproduced to rounding. */
int rs_profile_smooth(rs_profile *p, double length, rs_msg *msg);

/* Height range and the lateral range of a profile. */
void rs_profile_range(const rs_profile *p, double y[2], double z[2]);
/* z at lateral position y on the first segment that spans it (linear); 0 if none. */
int rs_profile_z_at(const rs_profile *p, double y, double *z);

#endif
