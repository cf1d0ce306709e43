/* Friction laws mu(|v_s|) and their slopes (physics/friction.h). */
#include "physics/friction.h"

#include <math.h>

/* The law at s >= 0. */
static double law(const rs_friction *f, double s, double *slope)
{
  double mu = 0.0, d = 0.0;
  switch (f->kind) {
  case RS_FRICTION_COULOMB: mu = f->mu; break;
  case RS_FRICTION_LINEAR:
    mu = f->mu_kinetic;
    for (int i = 0; i < f->terms; i++) {
      const double w = 2.0 * f->half_velocity[i];
      if (s < w) { /* the kink at s = 2 v_i takes the slope of the falling side */
        mu += f->mu_excess[i] * (1.0 - s / w);
        d -= f->mu_excess[i] / w;
      }
    }
    break;
  case RS_FRICTION_EXPONENTIAL:
    mu = f->mu_kinetic;
    for (int i = 0; i < f->terms; i++) {
      const double k = 0.69314718055994530942 / f->half_velocity[i],
                   e = f->mu_excess[i] * exp(-k * s);
      mu += e;
      d -= k * e;
    }
    break;
  case RS_FRICTION_RATIONAL: {
    mu = f->mu_kinetic;
    const double q1 = s / f->half_velocity[0], den1 = 1.0 + q1;
    mu += f->mu_excess[0] / den1;
    d -= f->mu_excess[0] / (den1 * den1 * f->half_velocity[0]);
    if (f->terms > 1) {
      const double q2 = s / f->half_velocity[1], den2 = 1.0 + q2 * q2;
      mu += f->mu_excess[1] / den2;
      d -= f->mu_excess[1] * 2.0 * q2 / (den2 * den2 * f->half_velocity[1]);
    }
    break;
  }
  case RS_FRICTION_POLACH: {
    const double e = exp(-f->polach_b * s);
    mu = f->mu_static * ((1.0 - f->polach_a) * e + f->polach_a);
    d = -f->mu_static * (1.0 - f->polach_a) * f->polach_b * e;
    break;
  }
  }
  if (slope) *slope = d;
  return mu;
}

double rs_friction_eval(const rs_friction *f, double s, double *slope)
{
  if (f->kind == RS_FRICTION_COULOMB) {
    if (slope) *slope = 0.0;
    return f->mu;
  }
  if (s >= 0.0) return law(f, s, slope);
  double d0;
  const double mu0 = law(f, 0.0, &d0); /* the tangent at 0 */
  if (slope) *slope = d0;
  return mu0 + d0 * s;
}

const char *rs_friction_name(rs_friction_kind kind)
{
  static const char *const names[] = {"coulomb", "linear", "exponential", "rational", "polach"};
  return (unsigned)kind < sizeof names / sizeof names[0] ? names[kind] : "?";
}
