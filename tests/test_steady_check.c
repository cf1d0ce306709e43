/* The physical check of steady solutions (rs_model_check_steady, issue: steady plastic
 * solves that are not steady states) on the paper's Table-1 contact at xi = -1 %:
 *  - a wrong steady state, stored in tests/data/meierhofer_spurious_state.csv (what the
 *    solver returned before the yield row was mended: p_x = -g at cell 4 with the plastic
 *    flow opposite to p_x), is refused, and the message names the cell and the condition;
 *  - the same state given to the steady solver as its start is corrected: the result
 *    passes the check and equals the solution from rest (two independent starts of a
 *    piecewise-linear system with a unique zero: to 1e-9 of F_x);
 *  - the solution from rest passes the check (its tolerance, 1e-6 of the largest bound,
 *    is 1e4 times Newton's 1e-10) and no cell carries a traction against the creepage.
 * Usage: test_steady_check tests/data/meierhofer_spurious_state.csv */
#include <stdlib.h>

#include "physics/model.h"
#include "solve/steady.h"
#include "test_support.h"

static int read_state(const char *path, const rs_model *m, double *y)
{
  FILE *f = fopen(path, "r");
  if (!f) return 0;
  char line[512];
  int n = 0;
  while (fgets(line, sizeof line, f)) {
    double x, px, upl, us;
    if (line[0] == '#' || sscanf(line, "%lf,%lf,%lf,%lf", &x, &px, &upl, &us) != 4) continue;
    if (n >= m->grid.n || fabs(x - m->grid.x[n]) > 1e-12) break;
    y[rs_at_p(&m->lay, 0, n)] = px;
    y[rs_at_upl(&m->lay, 0, n)] = upl;
    y[rs_at_ustar(&m->lay, n)] = us;
    n++;
  }
  fclose(f);
  return n == m->grid.n;
}

static double fx_of(const rs_model *m, const double *y)
{
  double fx = 0.0;
  for (int i = 0; i < m->grid.n; i++) fx += y[i] * m->grid.dx;
  return fx;
}

int main(int argc, char **argv)
{
  if (argc != 2) return 2;
  rs_case c;
  ts_table1_case(&c, 100, 200.0, 0.0387, -0.01);
  rs_model m;
  rs_msg msg = {{0}};
  if (rs_model_from_case(&m, &c, &msg) != RS_OK) return 1;
  double *spurious = calloc((size_t)m.lay.neq, sizeof(double));
  double *y = calloc((size_t)m.lay.neq, sizeof(double)),
         *ys = calloc((size_t)m.lay.neq, sizeof(double));
  rs_work w;
  rs_work_create(&w, &m);
  rs_steady *s = NULL;
  rs_stats st = {0};
  const rs_inputs in0 = ts_inputs(&m, 0.0);
  if (!read_state(argv[1], &m, spurious)) {
    printf("FAIL cannot read %s for this grid\n", argv[1]);
    return 1;
  }

  /* The stored wrong state is refused, naming cell 4 and the flow against p_x. */
  const int refused = rs_model_check_steady(&m, &w, &in0, spurious, &msg);
  printf("check of the stored state: %s\n", msg.text);
  ts_check_true("stored wrong state refused (RS_ERR_SOLVER: exit code 3)",
                refused == RS_ERR_SOLVER);
  ts_check_true("message names cell 4", strstr(msg.text, "cell 4 ") != NULL);
  ts_check_true("message names the flow opposite to the traction",
                strstr(msg.text, "plastic flow opposite to the traction") != NULL);

  /* Solution from rest: passes, no traction against the creepage (xi < 0: p_x >= 0). */
  if (rs_steady_create(&s, &m, NULL, &msg) != RS_OK ||
      rs_steady_solve(s, 0.0, ys, &st, &msg) != RS_OK) {
    printf("FAIL steady from rest: %s\n", msg.text);
    return 1;
  }
  ts_check_true("solution from rest passes the check",
                rs_model_check_steady(&m, &w, &in0, ys, &msg) == RS_OK);
  int reversed = 0;
  for (int i = 0; i < m.grid.n; i++) reversed += ys[i] < 0.0;
  ts_check("cells with p_x < 0 (from rest)", reversed, 0, 0);

  /* The wrong state as Newton's start: corrected to the same solution. */
  memcpy(y, spurious, (size_t)m.lay.neq * sizeof(double));
  rs_stats st2 = {0};
  const int status = rs_steady_solve(s, 0.0, y, &st2, &msg);
  ts_check_true("steady solve from the wrong state succeeds", status == RS_OK);
  ts_check_true("its result passes the check",
                rs_model_check_steady(&m, &w, &in0, y, &msg) == RS_OK);
  const double fx_rest = fx_of(&m, ys), fx_spur = fx_of(&m, y);
  ts_check("F_x from the wrong start / F_x from rest", fx_spur / fx_rest, 1.0, 1e-9);
  printf("F_x/F_n: stored %.6f, corrected %.6f, from rest %.6f (Newton iterations %ld)\n",
         fx_of(&m, spurious) / c.normal_load.value, fx_spur / c.normal_load.value,
         fx_rest / c.normal_load.value, st2.nonlin_iters);

  rs_steady_free(s);
  rs_work_free(&w);
  rs_model_free(&m);
  free(spurious);
  free(y);
  free(ys);
  return ts_failures ? 1 : 0;
}
