/* Helpers shared by the C unit tests: a case with the docs/case-file.md defaults
 * built directly (no YAML), and assertions that print what was expected. */
#ifndef ROLLSIM_TEST_SUPPORT_H
#define ROLLSIM_TEST_SUPPORT_H

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "io/case.h"
#include "physics/model.h"
#include "study/run.h"

/* The docs/verification.md Carter case: q = 178.9 N/mm, R = 500 mm, G = 82000, nu = 0.28,
 * mu = 0.3, xi = -2.4e-4, V = 30000 mm/s; elastic, steady. */
static inline void ts_carter_case(rs_case *c, int cells)
{
  memset(c, 0, sizeof *c);
  c->dimension = 2;
  c->normal_load.kind = RS_HISTORY_CONSTANT;
  c->normal_load.value = 178.9;
  c->radius = 500.0;
  c->normal_solution = RS_NORMAL_DISCRETE;
  c->reference_length = 200.0;
  c->cells = cells;
  c->extent = 1.05;
  c->shear_modulus = 82000.0;
  c->poisson_ratio = 0.28;
  c->mu = 0.3;
  c->layer_shear_modulus = 1.0;
  c->velocity.kind = RS_HISTORY_CONSTANT;
  c->velocity.value = 30000.0;
  c->creepage.kind = RS_HISTORY_CONSTANT;
  c->creepage.value = -2.4e-4;
  c->mode = RS_MODE_STEADY;
  c->end_time = 4e-4;
  c->rolled_distance = -1.0;
  c->output_interval = 1e-6;
  c->rtol = 1e-6;
  c->atol = 1e-9;
  c->max_order = 5;
  c->max_steps = 1000000;
}

/* The paper's Figure 7 set on that grid (cases/carter_plast.yaml): mu = 0.5,
 * xi = -4e-4, tau_c0 = 35 N/mm^2, k_tau = G k_rel/(1 - k_rel), floor 0.1 tau_c0. */
static inline void ts_fig7_case(rs_case *c, int cells, double k_rel)
{
  ts_carter_case(c, cells);
  c->mu = 0.5;
  c->creepage.value = -4e-4;
  c->has_plasticity = 1;
  c->tau_c0 = 35.0;
  c->k_tau = c->shear_modulus * k_rel / (1.0 - k_rel);
  c->tau_c_min = 0.1 * c->tau_c0;
}

/* A 3D elliptic contact (docs/model.md §10) on Carter's material: Rx = 100 mm, Ry = ratio Rx,
 * F = 1000 N, V = 30000 mm/s, mu = 0.3, n x n cells over +-1.1 a, +-1.1 b, with creepage,
 * lateral creepage and spin. */
static inline void ts_ellipse_case(rs_case *c, int n, double ratio, double xi, double eta,
                                   double phi)
{
  ts_carter_case(c, n);
  c->dimension = 3;
  c->radius = 100.0;
  c->radius_y = 100.0 * ratio;
  c->cells_y = n;
  c->extent = c->extent_y = 1.1;
  c->normal_load.value = 1000.0;
  c->mu = 0.3;
  c->creepage.value = xi;
  c->lateral_creepage = (rs_history){.kind = RS_HISTORY_CONSTANT, .value = eta};
  c->spin = (rs_history){.kind = RS_HISTORY_CONSTANT, .value = phi};
  c->tangential_force_y = (rs_history){.kind = RS_HISTORY_CONSTANT, .value = 0.0};
}

/* Plasticity with the yield limit tau_c0, work hardening k_rel (k_tau = G k_rel / (1 -
 * k_rel), G the case's shear modulus) and the floor tau_c_min = 0.1 tau_c0. */
static inline void ts_plasticity(rs_case *c, double tau_c0, double k_rel)
{
  c->has_plasticity = 1;
  c->tau_c0 = tau_c0;
  c->k_tau = c->shear_modulus * k_rel / (1.0 - k_rel);
  c->tau_c_min = 0.1 * tau_c0;
}

/* Deterministic numbers uniform in [-1, 1) (a 64-bit linear congruential generator). */
static inline double ts_random(unsigned long *state)
{
  *state = *state * 6364136223846793005UL + 1442695040888963407UL;
  return (double)(*state >> 11) / (double)(1UL << 52) - 1.0;
}

/* The paper's Table-1 contact (cases/meierhofer.yaml): q = 1323.6 N/mm, R = 11.75 mm,
 * G = 77519.4, nu = 0.29, mu = 0.5, grid +-1.05a; tau_c0, k_rel and xi as given. */
static inline void ts_table1_case(rs_case *c, int cells, double tau_c0, double k_rel, double xi)
{
  ts_carter_case(c, cells);
  c->normal_load.value = 1323.6;
  c->radius = 11.75;
  c->shear_modulus = 77519.4;
  c->poisson_ratio = 0.29;
  c->mu = 0.5;
  c->creepage.value = xi;
  ts_plasticity(c, tau_c0, k_rel);
}

/* The inputs of model m at time t. */
static inline rs_inputs ts_inputs(const rs_model *m, double t)
{
  rs_inputs in;
  rs_model_inputs_at(m, t, &in);
  return in;
}

/* The model functions at the inputs of time t. */
static inline int ts_diagnostics(const rs_model *m, rs_work *w, double t, const double *y,
                                 const double *yp, rs_diag *d, double *slip, double *tauc,
                                 signed char *regime)
{
  const rs_inputs in = ts_inputs(m, t);
  return rs_model_diagnostics(m, w, &in, y, yp, d, slip, tauc, regime);
}
static inline int ts_consistent_rates(const rs_model *m, rs_work *w, double t, double *y,
                                      double *yp, rs_msg *msg)
{
  const rs_inputs in = ts_inputs(m, t);
  return rs_model_consistent_rates(m, w, &in, y, yp, msg);
}
static inline int ts_residual(const rs_model *m, rs_work *w, double t, const double *y,
                              const double *yp, double cj, double *F)
{
  const rs_inputs in = ts_inputs(m, t);
  return rs_model_residual(m, w, &in, y, yp, cj, F);
}

static int ts_failures = 0;

/* Counts a failure and prints where and why (printf-style message) unless cond. */
#define TS_CHECK(cond, ...)                                                                        \
  do {                                                                                             \
    if (!(cond)) {                                                                                 \
      ts_failures++;                                                                               \
      fprintf(stderr, "%s:%d: check failed: %s: ", __FILE__, __LINE__, #cond);                     \
      fprintf(stderr, __VA_ARGS__);                                                                \
      fputc('\n', stderr);                                                                         \
    }                                                                                              \
  } while (0)

/* Passes when |got - want| <= tol; prints either way. */
static inline void ts_check(const char *what, double got, double want, double tol)
{
  const int ok = fabs(got - want) <= tol;
  printf("%s %s: got %.10g, want %.10g, tol %.3g (diff %.3g)\n", ok ? "ok  " : "FAIL", what, got,
         want, tol, fabs(got - want));
  if (!ok) ts_failures++;
}

static inline void ts_check_true(const char *what, int cond)
{
  printf("%s %s\n", cond ? "ok  " : "FAIL", what);
  if (!cond) ts_failures++;
}

#endif
