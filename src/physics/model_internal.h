/* Internal to the model (physics/model.h), split by concept:
 *   model.c           creation, inputs, normal pressure, kinematics, residual
 *   model_jacobian.c  Jacobian assembly (whole or near field), J v, row structure
 *   model_state.c     consistent rates, projection and interpolation of states
 *   model_check.c     reported quantities and the check of steady states */
#ifndef ROLLSIM_MODEL_INTERNAL_H
#define ROLLSIM_MODEL_INTERNAL_H

#include "physics/model.h"

/* Transport terms shared by residual, Jacobian, rates and diagnostics: u_el on the
 * padded grid, its rate, and the material derivatives of u_el, u_pl, u* (and mu with
 * friction memory, fresh material entering at mu_law(0)):
 *   (D f/Dt)_I = f'_I - V (f_up(I) - f_I)/dx   (first-order upwind, docs/model.md §5)
 *   v_s = V w + v_shift + Du_el/Dt + Du_pl/Dt,  u_el = A p + (h3/G3) p.
 * With in->linear the rigid slip and the inflow state are left out (the linear part,
 * for J v). */
void rs_model_kinematics(const rs_model *m, rs_work *w, const rs_inputs *in, const double *y,
                         const double *yp);
/* The same when the traction rates are rate times the tractions (rate >= 0; J v with
 * v' = cj v): A p' is then rate A p, one elastic product instead of two. rate < 0: as
 * rs_model_kinematics. */
void rs_model_kinematics_scaled(const rs_model *m, rs_work *w, const rs_inputs *in, const double *y,
                                const double *yp, double rate);

/* State of the material entering at the leading edge, per row of the grid (u_pl
 * components, then u*: (ncomp + 1) ny values): fresh (0), or the twin-disc memory at
 * in->t; none in the linear part. */
void rs_model_inflow(const rs_model *m, const rs_inputs *in, double *state);

/* Pressure for a load: the discrete normal solution or the Hertz pressure, as the
 * parameters say (approach may be NULL). */
int rs_model_pressure(const rs_model *m, rs_elastic_work *ew, double load, double *pn,
                      double *approach, rs_msg *msg);

/* Kinematics and the local laws of every cell into w (jac: with their local Jacobians and
 * the lists of rs_model_cell_flags), and the residual into F when F is not NULL. */
int rs_model_evaluate(const rs_model *m, rs_work *w, const rs_inputs *in, const double *y,
                      const double *yp, double cj, double *F, int jac);

/* The compact lists of the local Jacobians' present entries in w, allocated once. */
int rs_model_flags_alloc(const rs_model *m, rs_work *w);
/* Cell i's present entries from position *e of the lists on (advanced past them), and its
 * rows' dense flags and pivots (after its law with the Jacobian). */
void rs_model_cell_flags(const rs_model *m, rs_work *w, int i, int *e);

/* The local law of cell I from the kinematics in w (jac: also its local Jacobian). */
void rs_model_cell_law(const rs_model *m, const rs_work *w, const double *y, int I, int jac,
                       rs_law_out *out);

/* Traction bound of cell I in w's evaluation: mu p_n with mu the memory state of y, or the
 * bound of the memoryless model (the law at rest). */
static inline double rs_model_bound(const rs_model *m, const rs_work *w, const double *y, int I)
{
  const double g = m->lay.memory ? y[rs_at_mu(&m->lay, I)] * w->pn[I] : w->bound[I];
  return m->mu_factor ? m->mu_factor[I] * g : g;
}

static inline double rs_sign_of(double v) { return v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0); }

#endif
