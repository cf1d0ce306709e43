/* Friction laws (docs/model.md §11, docs/case-file.md friction): the coefficient of
 * friction as a function of the slip speed |v_s| (mm/s) and its derivative.
 *   coulomb:     mu
 *   linear:      mu_k + sum_i dmu_i max(0, 1 - |v_s| / (2 v_i))
 *   exponential: mu_k + sum_i dmu_i exp(-ln2 |v_s| / v_i)
 *   rational:    mu_k + dmu_1 / (1 + |v_s|/v_1) + dmu_2 / (1 + (|v_s|/v_2)^2)
 *   polach:      mu_s ((1 - A) exp(-B |v_s|) + A)
 * (CONTACT's friction laws L = 2, 4, 3 and Polach's). Below a speed of 0 (a Newton
 * iterate whose slip points along the traction) every law is continued by its tangent
 * at 0, so that mu stays smooth where slip starts. */
#ifndef ROLLSIM_FRICTION_H
#define ROLLSIM_FRICTION_H

typedef enum {
  RS_FRICTION_COULOMB = 0,
  RS_FRICTION_LINEAR,
  RS_FRICTION_EXPONENTIAL,
  RS_FRICTION_RATIONAL,
  RS_FRICTION_POLACH
} rs_friction_kind;

#define RS_FRICTION_MAX_TERMS 2

typedef struct rs_friction {
  rs_friction_kind kind;
  double mu;                                   /* coulomb */
  double mu_kinetic;                           /* linear, exponential, rational */
  int terms;                                   /* 1 or 2 */
  double mu_excess[RS_FRICTION_MAX_TERMS];     /* added to mu_kinetic at rest */
  double half_velocity[RS_FRICTION_MAX_TERMS]; /* mm/s */
  double mu_static, polach_a, polach_b;        /* polach; B in s/mm */
  /* Friction memory (docs/model.md §11, CONTACT's M-law): mu is a state per cell with
   * d_c Dmu/Dt = -max(|v_s|, s0) (mu - mu_law(|v_s|)); d_c = 0: no memory. */
  double memory_distance; /* d_c, mm */
  double memory_velocity; /* s0, mm/s */
} rs_friction;

/* Coefficient of friction at slip speed s (mm/s), and d mu / d s into *slope (may be
 * NULL). Coulomb gives mu and a slope of exactly 0. */
double rs_friction_eval(const rs_friction *f, double s, double *slope);

/* Coefficient of friction at slip speed s (mm/s). */
static inline double rs_friction_mu(const rs_friction *f, double s)
{
  return rs_friction_eval(f, s, 0);
}

/* 1 if mu depends on the slip speed (every law but Coulomb). */
static inline int rs_friction_varies(const rs_friction *f)
{
  return f->kind != RS_FRICTION_COULOMB;
}

/* 1 if mu is a state with memory (a velocity-dependent law with d_c > 0). */
static inline int rs_friction_has_memory(const rs_friction *f)
{
  return f->kind != RS_FRICTION_COULOMB && f->memory_distance > 0.0;
}

/* Name of a law as the case file spells it. */
const char *rs_friction_name(rs_friction_kind kind);

#endif
