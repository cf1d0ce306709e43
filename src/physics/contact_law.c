/* The contact law of one cell (rollsim/contact_law.h): the interval projections of
 * model.md §4 for one tangential component. */
#include "rollsim/contact_law.h"

#include <math.h>
#include <string.h>

static double sign_of(double v) { return v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0); }

double rs_yield_limit(const rs_plasticity *pl, double ustar)
{
  if (!pl->on) return INFINITY;
  return fmax(pl->tau_c_min, pl->tau_c0 + pl->k_tau * fmax(ustar, 0.0));
}

double rs_yield_slope(const rs_plasticity *pl, double ustar)
{
  return (pl->on && ustar >= 0.0 && pl->tau_c0 + pl->k_tau * ustar > pl->tau_c_min) ? pl->k_tau
                                                                                    : 0.0;
}

rs_state rs_contact_state(const rs_plasticity *pl, int in_contact, double p_norm, double g,
                          double ustar)
{
  if (!in_contact) return RS_STATE_OUTSIDE;
  const double tauc = rs_yield_limit(pl, ustar);
  if (p_norm < fmin(g, tauc) * (1.0 - 1e-12)) return RS_STATE_INSIDE;
  return g <= tauc ? RS_STATE_AT_BOUND : RS_STATE_AT_YIELD;
}

static void put(rs_law_out *o, int row, int var, double v)
{
  o->jac[row][var] = v;
  o->present[row][var] = 1;
}

void rs_contact_law(const rs_plasticity *pl, const rs_law_in *in, int jac, rs_law_out *out)
{
  const int nc = in->ncomp; /* 1: the interval projection */
  const int Rf = rs_law_row_f(0), Rpl = rs_law_row_pl(nc, 0), Rs = rs_law_row_star(nc);
  const int P = rs_law_var_p(0), VS = rs_law_var_vs(nc, 0), FL = rs_law_var_flow(nc, 0);
  const int DUS = rs_law_var_dustar(nc), US = rs_law_var_ustar(nc);
  const double p = in->p[0], vs = in->vs[0], flow = in->flow[0], r = in->r, g = in->g;
  const double tauc = rs_yield_limit(pl, in->ustar);
  unsigned char br = 0;
  int slip = 0, yield = 0;
  double arg_pl = 0.0, arg_f = 0.0;
  if (!in->in_contact) {
    br = RS_BRANCH_EXTERIOR;
    out->R[Rf] = p;
    out->R[Rpl] = r * flow;
  } else {
    /* Both projections active at once: slip and flow with |p| = g = tau_c. With
     * hardening (or softening) the yield row fixes u* and the flow follows from the
     * u* row: a legitimate state (a cell that has just hardened up to g). Without it
     * (k_tau = 0, or on the floor tau_c_min) the split between slip and flow is
     * undetermined (singular Jacobian): the lower bound decides, slip where
     * g <= tau_c, flow where tau_c < g. On the boundary of that region the choice
     * agrees with the plain projections, so F stays continuous there. */
    arg_f = p - r * vs;
    arg_pl = p + r * flow;
    slip = fabs(arg_f) > g;
    yield = fabs(arg_pl) > tauc;
    if (slip && yield && !(rs_yield_slope(pl, in->ustar) > 0.0 && g > pl->tau_c0)) {
      if (g <= tauc)
        yield = 0;
      else
        slip = 0;
    }
    if (slip) br |= RS_BRANCH_SLIP;
    out->R[Rf] = slip ? p - g * sign_of(arg_f) : r * vs;
    /* The plain projection, also when the cell slips as well (hardened up to the
     * bound): p = tau_c sign(p + r Du_pl/Dt) is what makes the flow parallel to p
     * (lambda >= 0). Taking the slip's direction here instead admitted spurious zeros
     * with p = -g and the flow opposite to p (negative plastic power) next to the
     * trailing edge: steady states the transient never reaches (the Table-1 contact at
     * xi = -1 %: F_x/F_n 0.1385 instead of 0.1350). */
    if (yield) br |= RS_BRANCH_YIELD;
    out->R[Rpl] = yield ? p - tauc * sign_of(arg_pl) : -r * flow;
  }
  out->R[Rs] = r * (in->dustar - fabs(flow));
  out->branch = br;
  out->pins_p = 0;
  if (!jac) return;

  memset(out->present, 0, sizeof out->present);
  /* Friction row: 1 on p at the bound or outside the contact, r on v_s otherwise. */
  if (br & (RS_BRANCH_EXTERIOR | RS_BRANCH_SLIP))
    put(out, Rf, P, 1.0);
  else
    put(out, Rf, VS, r);
  /* Plasticity row: p - tau_c(u*) sign at the yield limit (the u* term kept when it is
   * zero: the pattern follows the branches), r Du_pl/Dt outside, -r Du_pl/Dt inside. */
  if (br & RS_BRANCH_YIELD) {
    const double slope = rs_yield_slope(pl, in->ustar);
    put(out, Rpl, P, 1.0);
    put(out, Rpl, US, -sign_of(arg_pl) * slope);
    out->pins_p = slope == 0.0;
  } else {
    put(out, Rpl, FL, (br & RS_BRANCH_EXTERIOR) ? r : -r);
  }
  /* Hardening row: d|m|/dm is the sign of m, or the direction of p where m = 0
   * (model.md §9: not 0, which would make cells that slip and harden singular). */
  const double sig = flow != 0.0 ? sign_of(flow) : sign_of(p);
  put(out, Rs, FL, -r * sig);
  put(out, Rs, DUS, r);
}
