/* Hertz line contact (docs/verification.md 1): the discrete pressure on 100 cells
 * gives a and p0 within 1 % and carries exactly the load.
 * a is estimated from the second moment of the pressure, which for the Hertz
 * ellipse is Int x^2 p dx / Int p dx = a^2/4; p0 from the largest pressure. */
#include "physics/model.h"
#include "physics/normal.h"
#include "test_support.h"

int main(void)
{
  rs_case c;
  ts_carter_case(&c, 100);
  rs_model m;
  rs_msg msg = {{0}};
  if (rs_model_from_case(&m, &c, &msg) != RS_OK) {
    printf("FAIL model: %s\n", msg.text);
    return 1;
  }
  double load = 0.0, second = 0.0, pmax = 0.0;
  for (int i = 0; i < m.grid.n; i++) {
    load += m.pn[i] * m.grid.dx;
    second += m.grid.x[i] * m.grid.x[i] * m.pn[i] * m.grid.dx;
    pmax = fmax(pmax, m.pn[i]);
  }
  const double a_est = 2.0 * sqrt(second / load);
  /* Example of docs/verification.md 1: q = 178.9 N/mm, R = 500 mm gives a = 1.000 mm. */
  ts_check("Hertz a (analytic, docs/verification.md example)", m.hertz_a, 1.000, 5e-4);
  ts_check("total load (exact by construction)", load, 178.9, 1e-10 * 178.9);
  ts_check("a from the discrete pressure, 1 %", a_est, m.hertz_a, 0.01 * m.hertz_a);
  ts_check("p0 from the discrete pressure, 1 %", pmax, m.hertz_p0, 0.01 * m.hertz_p0);
  /* Pressure profile: max deviation from the ellipse, relative to p0, inside |x| < 0.9 a. */
  double dev = 0.0;
  for (int i = 0; i < m.grid.n; i++)
    if (fabs(m.grid.x[i]) < 0.9 * m.hertz_a)
      dev = fmax(dev, fabs(m.pn[i] - m.hertz_p0 * sqrt(1 - pow(m.grid.x[i] / m.hertz_a, 2))));
  ts_check("pressure profile inside 0.9a, 1 % of p0", dev / m.hertz_p0, 0.0, 0.01);
  rs_model_free(&m);
  return ts_failures ? 1 : 0;
}
