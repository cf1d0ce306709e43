/* Creepages of a wheel-rail contact from the wheelset's rigid-body motion (docs/model.md
 * "Wheelset kinematics"). The wheel is body 1, the rail (at rest) body 2. Every vector is in
 * one right-handed frame of the caller's, fixed to the track: x along the track in the
 * direction of travel, the others as the caller's profiles have them. */
#ifndef ROLLSIM_WR_KINEMATICS_H
#define ROLLSIM_WR_KINEMATICS_H

#include "base/status.h"

typedef struct rs_wheelset_motion {
  double velocity[3]; /* mm/s: of the wheelset's reference point (its centre) */
  double omega[3];    /* rad/s: its angular velocity (the wheel's spin about the axle,
                       * the yaw rate, the roll rate) */
  double centre[3];   /* mm: the reference point's position */
} rs_wheelset_motion;

/* The contact frame of a patch: unit vectors, t along the rolling direction, s lateral in
 * the tangent plane, n the normal into the wheel; (t, s, n) right-handed. */
typedef struct rs_contact_frame {
  double point[3]; /* mm: the contact point */
  double t[3], s[3], n[3];
} rs_contact_frame;

typedef struct rs_creepages {
  double xi, eta; /* longitudinal and lateral creepage (rollsim's signs: xi < 0 gives F_x > 0) */
  double phi;     /* spin, 1/mm */
  double v_roll;  /* mm/s: the rolling velocity they are divided by (the speed along t of
                   * the wheelset's reference point) */
} rs_creepages;

/* The creepages at a contact: the wheel's material velocity at the contact point minus the
 * rail's (zero), resolved along t and s and divided by v_roll; the spin the normal component
 * of the wheel's angular velocity divided by v_roll. RS_ERR_INPUT if the frame is not
 * orthonormal and right-handed to 1e-9, or v_roll is not positive. */
int rs_wr_creepages(const rs_wheelset_motion *w, const rs_contact_frame *f, rs_creepages *out,
                    rs_msg *msg);

/* The frame of a contact at `point`, in a right-handed frame with x along the track and z up
 * (toward the wheel), whose tangent plane holds the track's x axis and the
 * profile's tangent turned by the contact angle delta (rad) about x from the lateral axis y:
 * t = x, s = (0, cos delta, sin delta), n = t x s = (0, -sin delta, cos delta). */
void rs_wr_frame_from_angle(const double point[3], double delta, rs_contact_frame *f);

#endif
