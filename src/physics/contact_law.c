/* The contact law of one cell (physics/contact_law.h): the interval projections of
 * docs/model.md §4 for one tangential component, the disk projections of §10 for two. */
#include "physics/contact_law.h"

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

/* The disk projections of docs/model.md §10 for two components: proj(z) = z min(1, b/|z|),
 * whose generalized Jacobian outside the disk is (b/|z|)(I - z^ z^T). */
static void disk_law(const rs_plasticity *pl, const rs_law_in *in, int jac, rs_law_out *out);

void rs_contact_law(const rs_plasticity *pl, const rs_law_in *in, int jac, rs_law_out *out)
{
  if (in->ncomp == 2) {
    disk_law(pl, in, jac, out);
    return;
  }
  const int nc = in->ncomp; /* 1: the interval projection */
  const int Rf = rs_law_row_f(0), Rpl = rs_law_row_pl(nc, 0), Rs = rs_law_row_star(nc);
  const int P = rs_law_var_p(0), VS = rs_law_var_vs(nc, 0), FL = rs_law_var_flow(nc, 0);
  const int DUS = rs_law_var_dustar(nc), US = rs_law_var_ustar(nc);
  const double p = in->p[0], vs = in->vs[0], flow = in->flow[0], r = in->r;
  double g = in->g, dg = 0.0; /* the bound and d g / d eta */
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
    if (in->memory) {
      g = in->mu * in->pn; /* the state, not the law: no dependence on v_s */
    } else if (in->friction && rs_friction_varies(in->friction)) {
      /* g = mu(eta) p_n, eta = -s v_s: the slip speed along the bound's direction s */
      const double eta = -sign_of(arg_f) * vs;
      g = rs_friction_eval(in->friction, eta, &dg) * in->pn;
      dg *= in->pn;
    }
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
  /* Friction memory: relaxation towards the law at the slip speed eta (smooth where slip
   * starts, |v_s| at a solution), over the distance d_c of sliding. */
  const int Rm = rs_law_row_mu(nc), MU = rs_law_var_mu(nc), DMU = rs_law_var_dmu(nc);
  double mlaw = 0.0, mslope = 0.0, speed = 0.0, dspeed = 0.0, deta = 0.0;
  if (in->memory) {
    const double dc = in->friction->memory_distance, s0 = in->friction->memory_velocity;
    out->R[Rm] = r * dc * in->dmu;
    if (in->in_contact) {
      deta = -sign_of(arg_f);
      mlaw = rs_friction_eval(in->friction, deta * vs, &mslope);
      speed = fabs(vs) > s0 ? fabs(vs) : s0;
      dspeed = fabs(vs) > s0 ? sign_of(vs) : 0.0;
      out->R[Rm] += r * speed * (in->mu - mlaw);
    }
  }
  out->branch = br;
  out->g = g;
  out->pins_p = 0;
  if (!jac) return;

  memset(out->present, 0, sizeof out->present); /* jac is set where present only */
  /* Friction row: 1 on p at the bound or outside the contact, r on v_s otherwise. At a
   * velocity-dependent bound, R_f = p - s g(eta) with eta = -s v_s also has
   * d R_f / d v_s = s^2 g'(eta) = g'(eta) (docs/model.md §11: dense through Du_el/Dt). */
  if (br & (RS_BRANCH_EXTERIOR | RS_BRANCH_SLIP))
    put(out, Rf, P, 1.0);
  else
    put(out, Rf, VS, r);
  if ((br & RS_BRANCH_SLIP) && in->memory)
    put(out, Rf, MU, -sign_of(arg_f) * in->pn); /* R_f = p - s mu p_n */
  else if ((br & RS_BRANCH_SLIP) && in->friction && rs_friction_varies(in->friction))
    put(out, Rf, VS, dg);
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
   * (docs/model.md §9: not 0, which would make cells that slip and harden singular). */
  const double sig = flow != 0.0 ? sign_of(flow) : sign_of(p);
  put(out, Rs, FL, -r * sig);
  put(out, Rs, DUS, r);
  /* Memory row: r d_c on Dmu/Dt; in the contact r max(|v_s|, s0) on mu and
   * r [max'(|v_s|) (mu - mu_law) - max(|v_s|, s0) mu_law'(eta) d eta/d v_s] on v_s (the
   * dense term through Du_el/Dt). */
  if (in->memory) {
    put(out, Rm, DMU, r * in->friction->memory_distance);
    if (!(br & RS_BRANCH_EXTERIOR)) {
      put(out, Rm, MU, r * speed);
      put(out, Rm, VS, r * (dspeed * (in->mu - mlaw) - speed * mslope * deta));
    }
  }
}

/* |(a, b)|. Not hypot(): the components are tractions, slip velocities and flows of
 * moderate size (no overflow or underflow of their squares), and glibc's hypot, which
 * guards against both, is slow enough to show in a 3D plastic run's profile. */
static inline double norm2(double a, double b) { return sqrt(a * a + b * b); }

static void disk_law(const rs_plasticity *pl, const rs_law_in *in, int jac, rs_law_out *out)
{
  enum { NC = 2 };
  const double r = in->r, tauc = rs_yield_limit(pl, in->ustar);
  const double rp = in->r_yield > 0.0 ? in->r_yield : r; /* the yield projection's */
  const double *p = in->p, *vs = in->vs, *m = in->flow;
  double g = in->g, dg = 0.0; /* the bound and d g / d eta */
  const double mnorm = norm2(m[0], m[1]), pnorm = norm2(p[0], p[1]);
  double z[NC], yv[NC];
  for (int c = 0; c < NC; c++) {
    z[c] = p[c] - r * vs[c];
    yv[c] = p[c] + rp * m[c];
  }
  const double zn = norm2(z[0], z[1]), yn = norm2(yv[0], yv[1]);
  /* Velocity-dependent friction: g = mu(eta) p_n with eta = -s.v_s, the
   * slip speed along the unit direction s = z/|z| of the projection's argument (|v_s| at a
   * solution, where v_s = -|v_s| s; below 0 the law's tangent, as in 1 component). w is
   * the part of v_s across s: eta depends on p and v_s through s as well, d eta/d p =
   * -w^T/|z| and d eta/d v_s = -s^T + r w^T/|z| (zero across s at a solution only). */
  /* With friction memory the bound is g = mu p_n with the state mu (no dependence on v_s);
   * eta, s and w then serve the memory row. */
  const int memory = in->memory && in->in_contact;
  const int varies =
      in->in_contact && !in->memory && in->friction && rs_friction_varies(in->friction);
  double s[NC] = {0.0, 0.0}, w[NC] = {0.0, 0.0}, eta = 0.0;
  if (varies || memory) {
    /* z = 0: no direction, the law at rest (no slip there anyway) */
    if (zn > 0.0) {
      for (int c = 0; c < NC; c++) s[c] = z[c] / zn;
      eta = -(s[0] * vs[0] + s[1] * vs[1]);
      for (int c = 0; c < NC; c++) w[c] = vs[c] + eta * s[c];
    }
  }
  if (varies) {
    g = rs_friction_eval(in->friction, eta, &dg) * in->pn;
    dg *= in->pn;
  } else if (memory) {
    g = in->mu * in->pn;
  }
  unsigned char br = 0;
  int slip = 0, yield = 0;
  if (!in->in_contact) {
    br = RS_BRANCH_EXTERIOR;
    for (int c = 0; c < NC; c++) {
      out->R[rs_law_row_f(c)] = p[c];
      out->R[rs_law_row_pl(NC, c)] = rp * m[c];
    }
  } else {
    slip = zn > g;
    yield = yn > tauc;
    /* both at once without hardening: the lower bound decides (see the 1-component law) */
    if (slip && yield && !(rs_yield_slope(pl, in->ustar) > 0.0 && g > pl->tau_c0)) {
      if (g <= tauc)
        yield = 0;
      else
        slip = 0;
    }
    if (slip) br |= RS_BRANCH_SLIP;
    if (yield) br |= RS_BRANCH_YIELD;
    for (int c = 0; c < NC; c++) {
      out->R[rs_law_row_f(c)] = slip ? p[c] - g * z[c] / zn : r * vs[c];
      out->R[rs_law_row_pl(NC, c)] = yield ? p[c] - tauc * yv[c] / yn : -rp * m[c];
    }
  }
  /* Hardening rate: the flow along p, m.p^, rather than |m|. The two agree at every
   * solution (the flow is parallel to p, or zero), but |m| has a cone at m = 0, where a
   * cell that has just hardened up to g sits (slip and yield both active, flow -> 0):
   * Newton's linearisation m^.m there follows the direction of the last iterate's small
   * flow, and semismooth Newton cycles between the slip and the slip + yield branch of
   * such cells (bench/RESULTS.md). m.p^ is smooth in m and p for p != 0; |m| where p = 0
   * (exterior). */
  const int along_p = pnorm > 0.0;
  const double mrate = along_p ? (m[0] * p[0] + m[1] * p[1]) / pnorm : mnorm;
  out->R[rs_law_row_star(NC)] = r * (in->dustar - mrate);
  /* Friction memory: the row of the 1-component law with eta = -s.v_s and |v_s| the norm */
  const int Rm = rs_law_row_mu(NC);
  const double vn = norm2(vs[0], vs[1]);
  double mlaw = 0.0, mslope = 0.0, speed = 0.0;
  if (in->memory) {
    const double dc = in->friction->memory_distance, s0 = in->friction->memory_velocity;
    out->R[Rm] = r * dc * in->dmu;
    if (in->in_contact) {
      mlaw = rs_friction_eval(in->friction, eta, &mslope);
      speed = vn > s0 ? vn : s0;
      out->R[Rm] += r * speed * (in->mu - mlaw);
    }
  }
  out->branch = br;
  out->g = g;
  out->pins_p = 0;
  if (!jac) return;

  memset(out->present, 0, sizeof out->present); /* jac is set where present only */
  for (int c = 0; c < NC; c++) {
    const int Rf = rs_law_row_f(c), Rpl = rs_law_row_pl(NC, c);
    /* friction rows */
    if (br & RS_BRANCH_EXTERIOR) {
      put(out, Rf, rs_law_var_p(c), 1.0);
    } else if (br & RS_BRANCH_SLIP) {
      /* R_f = p - g z/|z|: dR/dp = I - (g/|z|)(I - z^ z^T), dR/dv_s = r (g/|z|)(I - z^ z^T);
       * with g = g(eta) also - s g'(eta) d eta/d(p, v_s) (docs/model.md §11: dense through
       * Du_el/Dt): + s g' w^T/|z| on p and + s g' (s - r w/|z|)^T on v_s */
      for (int b = 0; b < NC; b++) {
        const double t = (g / zn) * ((b == c ? 1.0 : 0.0) - z[c] * z[b] / (zn * zn));
        double tp = 0.0, tv = 0.0;
        if (varies) {
          tp = s[c] * dg * w[b] / zn;
          tv = s[c] * dg * (s[b] - r * w[b] / zn);
        }
        const double jp = (b == c ? 1.0 : 0.0) - t, jv = r * t;
        put(out, Rf, rs_law_var_p(b), varies ? jp + tp : jp);
        put(out, Rf, rs_law_var_vs(NC, b), varies ? jv + tv : jv);
      }
      if (memory) put(out, Rf, rs_law_var_mu(NC), -in->pn * z[c] / zn); /* g = mu p_n */
    } else {
      put(out, Rf, rs_law_var_vs(NC, c), r);
    }
    /* plasticity rows */
    if (br & RS_BRANCH_YIELD) {
      /* R_pl = p - tau_c y/|y|, y = p + r m: dR/dp = I - (tau_c/|y|)(I - y^ y^T),
       * dR/dm = -r (tau_c/|y|)(I - y^ y^T), dR/du* = -tau_c' y^ */
      for (int b = 0; b < NC; b++) {
        const double t = (tauc / yn) * ((b == c ? 1.0 : 0.0) - yv[c] * yv[b] / (yn * yn));
        put(out, Rpl, rs_law_var_p(b), (b == c ? 1.0 : 0.0) - t);
        put(out, Rpl, rs_law_var_flow(NC, b), -rp * t);
      }
      put(out, Rpl, rs_law_var_ustar(NC), -rs_yield_slope(pl, in->ustar) * yv[c] / yn);
    } else {
      put(out, Rpl, rs_law_var_flow(NC, c), (br & RS_BRANCH_EXTERIOR) ? rp : -rp);
    }
  }
  /* hardening row: d(m.p^)/dm = p^, d(m.p^)/dp = (m - (m.p^) p^)^T/|p|; where p = 0,
   * d|m|/dm = m^ (docs/model.md §9) */
  const int Rs = rs_law_row_star(NC);
  for (int c = 0; c < NC; c++) {
    const double dir = along_p ? p[c] / pnorm : mnorm > 0.0 ? m[c] / mnorm : (c == 0 ? 1.0 : 0.0);
    put(out, Rs, rs_law_var_flow(NC, c), -r * dir);
    if (along_p) put(out, Rs, rs_law_var_p(c), -r * (m[c] - mrate * p[c] / pnorm) / pnorm);
  }
  put(out, Rs, rs_law_var_dustar(NC), r);
  /* Memory row: r d_c on Dmu/Dt; in the contact r max(|v_s|, s0) on mu, and through
   * eta = -s.v_s (d eta/d p = -w^T/|z|, d eta/d v_s = -s^T + r w^T/|z|) and |v_s|:
   * -r max(|v_s|, s0) mu_law'(eta) d eta on p, and
   * r [max'(|v_s|) v_s^T/|v_s| (mu - mu_law) - max(|v_s|, s0) mu_law'(eta) d eta/d v_s] on
   * v_s (dense through Du_el/Dt). */
  if (in->memory) {
    put(out, Rm, rs_law_var_dmu(NC), r * in->friction->memory_distance);
    if (!(br & RS_BRANCH_EXTERIOR)) {
      put(out, Rm, rs_law_var_mu(NC), r * speed);
      const double dmax = vn > in->friction->memory_velocity ? 1.0 / vn : 0.0;
      for (int b = 0; b < NC; b++) {
        const double wz = zn > 0.0 ? w[b] / zn : 0.0;
        put(out, Rm, rs_law_var_p(b), r * speed * mslope * wz);
        put(out, Rm, rs_law_var_vs(NC, b),
            r * (dmax * vs[b] * (in->mu - mlaw) - speed * mslope * (-s[b] + r * wz)));
      }
    }
  }
}
