/* Creepages from the wheelset's rigid-body motion (wr_kinematics.h). */
#include "physics/wr_kinematics.h"

#include <math.h>

static double dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross(const double a[3], const double b[3], double c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/* Largest deviation of (t, s, n) from an orthonormal right-handed triple. */
static double frame_error(const rs_contact_frame *f)
{
  double txs[3];
  cross(f->t, f->s, txs);
  double e = fmax(fabs(dot(f->t, f->t) - 1.0), fabs(dot(f->s, f->s) - 1.0));
  e = fmax(e, fmax(fabs(dot(f->n, f->n) - 1.0), fabs(dot(f->t, f->s))));
  for (int k = 0; k < 3; k++) e = fmax(e, fabs(txs[k] - f->n[k]));
  return e;
}

int rs_wr_creepages(const rs_wheelset_motion *w, const rs_contact_frame *f, rs_creepages *out,
                    rs_msg *msg)
{
  const double err = frame_error(f);
  if (!(err <= 1e-9))
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "the contact frame is not orthonormal and right-handed (off by %.3g)", err);
  const double v_roll = dot(w->velocity, f->t);
  if (!(v_roll > 0.0))
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "the wheelset does not roll along the contact (velocity along it %.6g mm/s)",
                      v_roll);
  /* the wheel's material velocity at the contact point: v_c + omega x (p - c) */
  double arm[3], turn[3], v[3];
  for (int k = 0; k < 3; k++) arm[k] = f->point[k] - w->centre[k];
  cross(w->omega, arm, turn);
  for (int k = 0; k < 3; k++) v[k] = w->velocity[k] + turn[k];
  out->xi = dot(v, f->t) / v_roll;
  out->eta = dot(v, f->s) / v_roll;
  out->phi = dot(w->omega, f->n) / v_roll;
  out->v_roll = v_roll;
  return RS_OK;
}

void rs_wr_frame_from_angle(const double point[3], double delta, rs_contact_frame *f)
{
  for (int k = 0; k < 3; k++) f->point[k] = point[k];
  const double c = cos(delta), s = sin(delta);
  f->t[0] = 1.0;
  f->t[1] = f->t[2] = 0.0;
  f->s[0] = 0.0;
  f->s[1] = c;
  f->s[2] = s;
  f->n[0] = 0.0;
  f->n[1] = -s;
  f->n[2] = c;
}
