/* Creepages from the wheelset's motion (physics/wr_kinematics.h), against the closed forms of
 * rigid-body kinematics (x along the track, z up, the wheel of rolling radius r above its
 * contact point; all to 1e-14 of the creepage's scale, rounding only):
 *  - pure rolling (axle spin V/r): xi = eta = 0; spin 0 at a flat contact, -sin(delta)/r at a
 *    contact turned by delta (the conicity's spin);
 *  - braking with axle spin (1 - s) V/r: xi = s;
 *  - yaw psi with the wheel rolling along the track (axle spin V/(r cos psi) about the yawed
 *    axle): xi = 0, eta = -tan psi;
 *  - yaw rate psi' at a contact y_c off the centre line: xi = -psi' y_c / V, spin psi'
 * cos(delta)/V;
 *  - the mirror wheel (y_c -> -y_c, delta -> -delta): xi, spin of opposite sign;
 *  - a frame that is not orthonormal, or no rolling along it: RS_ERR_INPUT. */
#include <math.h>
#include <stdio.h>

#include "physics/wr_kinematics.h"

static int failures = 0;

static void near(const char *what, double got, double want, double tol)
{
  const int ok = fabs(got - want) <= tol;
  printf("%s %s: got %.17g, want %.17g\n", ok ? "ok  " : "FAIL", what, got, want);
  failures += !ok;
}

static rs_creepages at(const rs_wheelset_motion *w, double yc, double r, double delta)
{
  const double point[3] = {w->centre[0], w->centre[1] + yc, w->centre[2] - r};
  rs_contact_frame f;
  rs_wr_frame_from_angle(point, delta, &f);
  rs_creepages c = {0};
  rs_msg msg = {{0}};
  if (rs_wr_creepages(w, &f, &c, &msg) != RS_OK) {
    printf("FAIL %s\n", msg.text);
    failures++;
  }
  return c;
}

int main(void)
{
  const double V = 30000.0, r = 460.0, yc = 750.0, delta = 0.35, tol = 1e-14;
  rs_wheelset_motion w = {
      .velocity = {V, 0.0, 0.0}, .omega = {0.0, V / r, 0.0}, .centre = {10.0, -3.0, 460.0}};
  rs_creepages c = at(&w, 0.0, r, 0.0);
  near("pure rolling, flat: xi", c.xi, 0.0, tol);
  near("pure rolling, flat: eta", c.eta, 0.0, tol);
  near("pure rolling, flat: spin (1/mm)", c.phi, 0.0, tol / r);
  near("the rolling velocity is the wheelset's (mm/s)", c.v_roll, V, tol * V);
  c = at(&w, yc, r, delta);
  near("pure rolling at delta: xi", c.xi, 0.0, tol);
  near("pure rolling at delta: eta", c.eta, 0.0, tol);
  near("pure rolling at delta: spin = -sin(delta)/r", c.phi, -sin(delta) / r, tol / r);

  const double slip = 0.004;
  w.omega[1] = (1.0 - slip) * V / r;
  c = at(&w, yc, r, delta);
  near("braking: xi = s", c.xi, slip, tol);
  near("braking: eta", c.eta, 0.0, tol);

  const double psi = 0.012;
  w.omega[0] = -sin(psi) * V / (r * cos(psi));
  w.omega[1] = cos(psi) * V / (r * cos(psi));
  c = at(&w, 0.0, r, 0.0);
  near("yaw: xi", c.xi, 0.0, tol);
  near("yaw: eta = -tan psi", c.eta, -tan(psi), tol);

  const double rate = 0.8; /* rad/s */
  w.omega[0] = 0.0;
  w.omega[1] = V / r;
  w.omega[2] = rate;
  c = at(&w, yc, r, delta);
  near("yaw rate: xi = -psi' y_c / V", c.xi, -rate * yc / V, tol);
  near("yaw rate: spin = (psi' cos(delta) - (V/r) sin(delta)) / V", c.phi,
       (rate * cos(delta) - V / r * sin(delta)) / V, tol / r);
  rs_creepages m = at(&w, -yc, r, -delta);
  near("the mirror wheel: xi of opposite sign", m.xi, -c.xi, tol);
  near("the mirror wheel: the conicity's spin of opposite sign", m.phi - rate * cos(delta) / V,
       -(c.phi - rate * cos(delta) / V), tol / r);

  rs_contact_frame f;
  const double point[3] = {0.0, 0.0, 0.0};
  rs_wr_frame_from_angle(point, delta, &f);
  f.s[1] *= 1.001;
  rs_msg msg = {{0}};
  int status = rs_wr_creepages(&w, &f, &c, &msg);
  printf("%s a frame off by 1e-3 is refused: %s\n", status == RS_ERR_INPUT ? "ok  " : "FAIL",
         msg.text);
  failures += status != RS_ERR_INPUT;
  rs_wr_frame_from_angle(point, delta, &f);
  w.velocity[0] = 0.0;
  status = rs_wr_creepages(&w, &f, &c, &msg);
  printf("%s no rolling is refused: %s\n", status == RS_ERR_INPUT ? "ok  " : "FAIL", msg.text);
  failures += status != RS_ERR_INPUT;
  return failures ? 1 : 0;
}
