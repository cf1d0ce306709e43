/* Internals shared by the wheel-rail studies (study/wheel_rail.h): one wheelset position solved
 * (patches, vertical balance, per-patch steady tangential problems; wheel_rail_position.c), the
 * columns of the files over positions or time (wheel_rail_sweep.c) and the runs
 * (wheel_rail_run.c). */
#ifndef ROLLSIM_WHEEL_RAIL_INTERNAL_H
#define ROLLSIM_WHEEL_RAIL_INTERNAL_H

#include "io/output.h"
#include "io/profile.h"
#include "physics/model.h"
#include "physics/wr_contact.h"
#include "physics/wr_kinematics.h"
#include "study/wheel_rail.h"

/* The wheelset's motion at one time: forward speed V (mm/s), yaw psi (rad), the wheel's
 * angular velocity omega about the axle (rad/s); moving wheelsets also the lateral velocity
 * toward the track centre (mm/s), the yaw rate (rad/s) and the distance from the contact's
 * lateral position to the wheelset's centre line (mm, toward the track centre). */
typedef struct wr_motion {
  double V, psi, omega;
  double v_lateral, yaw_rate, to_centre;
} wr_motion;

/* The creepages of a patch for the wheelset's motion (docs/model.md §21). */
int wr_patch_creepages(const rs_wr_patch *p, const wr_motion *mo, rs_creepages *cr, rs_msg *msg);

/* The model parameters of a loaded patch's tangential problem on its grid cut to the contact;
 * *pn_out (the pressure par points to) is the caller's to free once the model is created. */
int wr_patch_params(const rs_case *c, const rs_wr_patch *p, const rs_wr_patch_result *r, double V,
                    const rs_creepages *cr, rs_model_params *par, double **pn_out, rs_msg *msg);

/* A patch's solution kept for the next round of the vertical balance or the next interval of a
 * moving wheelset: its model (only its grid and layout are read later) and state. */
typedef struct patch_state {
  int valid;
  rs_model m;
  double *y;
  double rail_y, delta; /* the contact point on the rail (mm) and the contact angle (rad) */
} patch_state;
void wr_patch_state_free(patch_state *k);
/* The patch of last that p continues (CARRY_DISTANCE mm on the rail, CARRY_ANGLE rad), or NULL. */
#define CARRY_DISTANCE 2.0
#define CARRY_ANGLE    0.05
const patch_state *wr_nearest_patch(const patch_state *last, const rs_wr_patch *p);
/* The state of from carried onto the model m of the patch now at rail_y (wheel_rail_position.c). */
int wr_carry_state(const patch_state *from, double rail_y, double delta, const rs_model *m,
                   rs_work *w, const rs_inputs *in, double *y, rs_msg *msg);

/* A loaded patch's tangential model (wr_patch_params) with its work and zeroed state y and
 * rates yp; on failure nothing is left to free. wr_patch_finish ends a patch's solve: with
 * status RS_OK and keep the model and y move into keep, otherwise they are freed; returns
 * status. */
int wr_patch_model(const rs_case *c, const rs_wr_patch *p, const rs_wr_patch_result *r, double V,
                   const rs_creepages *cr, rs_model *m, rs_work *w, double **y, double **yp,
                   rs_msg *msg);
int wr_patch_finish(int status, const rs_wr_patch *p, rs_model *m, rs_work *w, double *y,
                    double *yp, patch_state *keep);

/* The steady tangential problem of a loaded patch (wheel_rail_position.c). */
int wr_patch_tangential(const rs_case *c, const rs_wr_patch *p, const rs_wr_patch_result *r,
                        double V, const rs_creepages *cr, rs_diag *d, long *newton,
                        const patch_state *from, patch_state *keep, rs_msg *msg);

/* Everything at one wheelset position: the patches, the load sharing and, rolling, each
 * loaded patch's creepages and steady tangential solution. */
typedef struct wr_position {
  rs_wr_geometry geo;
  rs_wr_solution sol;
  double V, omega; /* mm/s, rad/s */
  int tangential;  /* 1: V > 0, cr and d of the loaded patches filled */
  rs_creepages cr[RS_WR_MAX_PATCHES];
  rs_diag d[RS_WR_MAX_PATCHES];
  long newton;                /* Newton iterations of the tangential solves */
  double v_lateral, yaw_rate; /* a moving wheelset's (mm/s toward the track centre, rad/s) */
  double centre;              /* the wheelset's centre line, y on the rail profile (mm) */
  double normal_load;         /* N: sum F_n cos(delta), the load the normal problem balanced */
  double vertical;    /* N: the wheel's vertical force sum (F_n cos(delta) - F_s sin(delta)) */
  int balance_rounds; /* normal and tangential solves of the vertical balance */
} wr_position;

/* The wheel's vertical force (up) of a solved position. */
double wr_vertical_force(const wr_position *pos);
void wr_position_free(wr_position *pos);
/* Everything at the position of w at time t (its velocity), with a moving wheelset's lateral
 * velocity and yaw rate (0 otherwise), the vertical balance closed (docs/model.md §20). On
 * failure nothing is left to free. */
int wr_position_solve(const rs_case *c, const rs_wheel_rail *w, double t, double v_lateral,
                      double yaw_rate, wr_position *pos, rs_msg *msg);

/* The columns of a sweep file on profiles (docs/file-format.md "Wheel-rail sweep files"). */
enum {
  C_Y,
  C_YAW,
  C_OMEGA,
  C_NPATCH,
  C_DZ,
  C_FX_TRACK,
  C_FY_TRACK,
  C_FZ_TRACK,
  C_NEWTON,
  C_CONVERGED,
  C_POSITION_COLS
};
enum {
  P_RAIL_Y,
  P_RAIL_Z,
  P_WHEEL_Y,
  P_WHEEL_Z,
  P_DELTA,
  P_RADIUS,
  P_FN,
  P_APPROACH,
  P_AREA,
  P_PMAX,
  P_XI,
  P_ETA,
  P_PHI,
  P_FX,
  P_FS,
  P_MN,
  P_PATCH_COLS
};
extern const rs_positions_column wr_position_cols[C_POSITION_COLS];
extern const rs_positions_column wr_patch_cols[P_PATCH_COLS];
/* A solved position into row i of the position columns pc [n][C_POSITION_COLS] and the patch
 * columns pp [n][RS_WR_MAX_PATCHES][P_PATCH_COLS]. */
void wr_position_store(const wr_position *pos, size_t i, double *pc, double *pp);

#endif
