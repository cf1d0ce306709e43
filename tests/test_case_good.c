/* Valid case files: every key read as written, defaults filled in, k_rel
 * converted, --set overrides (also creating keys), the resolved print-out,
 * yaml_text that loads back to the same case, and cases derived with typed overrides
 * equal to the cases loaded with the same --set (values, print-out and messages).
 *
 * Usage: test_case_good GOOD_INPUTS_DIR WORK_DIR   (WORK_DIR: scratch files) */
#define _POSIX_C_SOURCE 200809L
#include "io/case.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures = 0;
static const char *good_dir, *work_dir;

#define CHECK(cond)                                                                                \
  do {                                                                                             \
    if (!(cond)) {                                                                                 \
      printf("FAIL %s:%d: %s\n", __FILE__, __LINE__, #cond);                                       \
      failures++;                                                                                  \
    }                                                                                              \
  } while (0)

static const char *in_dir(const char *dir, const char *name, char *buf, size_t len)
{
  snprintf(buf, len, "%s/%s", dir, name);
  return buf;
}

/* Load a good input; a failure is reported and leaves c zeroed. */
static int load(rs_case *c, const char *name, const char *const *sets, int nsets)
{
  char path[1024];
  rs_msg msg = {{0}};
  int status = rs_case_load(c, in_dir(good_dir, name, path, sizeof path), sets, nsets, &msg);
  if (status != RS_OK) {
    printf("FAIL loading %s: status %d: %s\n", name, status, msg.text);
    failures++;
  }
  return status;
}

static int same_history(const rs_history *a, const rs_history *b)
{
  if (a->kind != b->kind || a->n != b->n) return 0;
  switch (a->kind) {
  case RS_HISTORY_CONSTANT: return a->value == b->value;
  case RS_HISTORY_RAMP:
    return a->from == b->from && a->to == b->to && a->start == b->start &&
           a->duration == b->duration;
  case RS_HISTORY_SINE:
    return a->mean == b->mean && a->amplitude == b->amplitude && a->frequency == b->frequency &&
           a->phase == b->phase;
  default:
    for (size_t i = 0; i < a->n; i++)
      if (a->t[i] != b->t[i] || a->v[i] != b->v[i]) return 0;
    return 1;
  }
}

/* Every resolved value equal (not source_path/yaml_text). */
static int same_case(const rs_case *a, const rs_case *b)
{
  return !strcmp(a->title, b->title) && a->dimension == b->dimension &&
         same_history(&a->normal_load, &b->normal_load) && a->radius == b->radius &&
         a->normal_solution == b->normal_solution && a->reference_length == b->reference_length &&
         a->cells == b->cells && a->extent == b->extent &&
         a->grid_from_range == b->grid_from_range && a->x_range[0] == b->x_range[0] &&
         a->x_range[1] == b->x_range[1] && a->shear_modulus == b->shear_modulus &&
         a->poisson_ratio == b->poisson_ratio && a->mu == b->mu &&
         a->layer_thickness == b->layer_thickness &&
         a->layer_shear_modulus == b->layer_shear_modulus &&
         a->has_plasticity == b->has_plasticity && a->tau_c0 == b->tau_c0 && a->k_tau == b->k_tau &&
         a->tau_c_min == b->tau_c_min && same_history(&a->velocity, &b->velocity) &&
         same_history(&a->creepage, &b->creepage) &&
         same_history(&a->shift_velocity, &b->shift_velocity) && a->mode == b->mode &&
         a->end_time == b->end_time && a->rolled_distance == b->rolled_distance &&
         a->output_interval == b->output_interval && a->initial_state == b->initial_state &&
         a->rtol == b->rtol && a->atol == b->atol && a->max_order == b->max_order &&
         a->scaling == b->scaling && a->max_steps == b->max_steps &&
         !strcmp(a->output_file, b->output_file) && a->fields == b->fields;
}

static void test_full(void)
{
  rs_case c;
  if (load(&c, "full.yaml", NULL, 0) != RS_OK) return;
  CHECK(!strcmp(c.title, "Carter 2D rolling with local plasticity, k_rel = 0.6"));
  CHECK(c.dimension == 2);
  CHECK(c.normal_load.kind == RS_HISTORY_CONSTANT && c.normal_load.value == 178.9);
  CHECK(c.radius == 500.0 && c.reference_length == 200.0);
  CHECK(c.normal_solution == RS_NORMAL_HERTZ);
  CHECK(c.cells == 120 && c.extent == 1.1);
  CHECK(c.shear_modulus == 82000.0 && c.poisson_ratio == 0.28);
  CHECK(c.mu == 0.3);
  CHECK(c.layer_thickness == 0.01 && c.layer_shear_modulus == 5.0);
  CHECK(c.has_plasticity == 1 && c.tau_c0 == 35.0 && c.k_tau == 123000.0 && c.tau_c_min == 2.5);
  CHECK(c.velocity.kind == RS_HISTORY_CONSTANT && c.velocity.value == 30000.0);
  CHECK(c.creepage.kind == RS_HISTORY_RAMP && c.creepage.from == 0.0 && c.creepage.to == -0.01 &&
        c.creepage.start == 0.0 && c.creepage.duration == 0.05);
  CHECK(c.shift_velocity.value == 0.0);
  CHECK(c.mode == RS_MODE_TRANSIENT && c.end_time == 0.0004 && c.rolled_distance < 0);
  CHECK(c.output_interval == 2.0e-6 && c.initial_state == RS_START_STEADY);
  CHECK(c.rtol == 1.0e-5 && c.atol == 1.0e-8 && c.max_order == 4);
  CHECK(c.scaling == RS_SCALING_DIFFERENCE && c.max_steps == 5000);
  CHECK(!strcmp(c.output_file, "results/full.nc"));
  CHECK(c.fields == (RS_FIELD_PX | RS_FIELD_PN | RS_FIELD_SLIP | RS_FIELD_UPL | RS_FIELD_USTAR |
                     RS_FIELD_TAUC | RS_FIELD_REGIME));
  CHECK(c.source_path && strstr(c.source_path, "full.yaml"));
  CHECK(c.yaml_text && strstr(c.yaml_text, "sweep:") && strstr(c.yaml_text, "k_tau: 123000.0"));
  rs_case_free(&c);
  CHECK(c.yaml_text == NULL && c.title == NULL);
}

static void test_minimal_defaults(void)
{
  rs_case c;
  if (load(&c, "minimal.yaml", NULL, 0) != RS_OK) return;
  CHECK(!strcmp(c.title, ""));
  CHECK(c.dimension == 2 && c.normal_load.kind == RS_HISTORY_CONSTANT &&
        c.normal_load.value == 178.9);
  CHECK(c.radius == 500.0 && c.normal_solution == RS_NORMAL_DISCRETE &&
        c.reference_length == 200.0);
  CHECK(c.cells == 100 && c.extent == 1.05);
  CHECK(c.shear_modulus == 82000.0 && c.poisson_ratio == 0.28 && c.mu == 0.5);
  CHECK(c.layer_thickness == 0.0 && c.layer_shear_modulus == 1.0);
  CHECK(c.has_plasticity == 0);
  CHECK(c.velocity.value == 30000.0 && c.creepage.kind == RS_HISTORY_CONSTANT &&
        c.creepage.value == -0.0004 && c.shift_velocity.value == 0.0);
  CHECK(c.mode == RS_MODE_TRANSIENT && c.end_time == 0.0004 && c.rolled_distance < 0 &&
        c.output_interval == 1.0e-6 && c.initial_state == RS_START_REST);
  CHECK(c.rtol == 0.0 && c.atol == 1.0e-9 && c.max_order == 5); /* rtol 0: auto */
  CHECK(c.scaling == RS_SCALING_AUTO && c.max_steps == 1000000);
  CHECK(!strcmp(c.output_file, "results/minimal.nc"));
  CHECK(c.fields == 0x7fu);
  rs_case_free(&c);
}

static void test_k_rel(void)
{
  rs_case c;
  if (load(&c, "k_rel.yaml", NULL, 0) != RS_OK) return;
  /* k_tau = G*k_rel/(1 - k_rel) = 82000*0.6/0.4 = 123000, exact in binary */
  CHECK(c.has_plasticity == 1);
  CHECK(c.k_tau == 123000.0);
  CHECK(c.tau_c_min == 0.1 * 35.0); /* null = the default 0.1*tau_c0 */
  rs_case_free(&c);
}

static void test_histories(void)
{
  rs_case c;
  if (load(&c, "histories.yaml", NULL, 0) != RS_OK) return;
  /* table: (0, 100), (0.0002, 200), (0.0004, 150) */
  CHECK(c.normal_load.kind == RS_HISTORY_TABLE && c.normal_load.n == 3);
  CHECK(fabs(rs_history_eval(&c.normal_load, 0.0001) - 150.0) < 1e-9);
  CHECK(fabs(rs_history_eval(&c.normal_load, 0.0003) - 175.0) < 1e-9);
  CHECK(c.velocity.kind == RS_HISTORY_STEPS && rs_history_eval(&c.velocity, 0.0003) == 20000.0);
  CHECK(c.creepage.kind == RS_HISTORY_SINE && c.creepage.frequency == 50.0);
  CHECK(fabs(rs_history_eval(&c.creepage, 0.005) - (-0.001)) < 1e-15); /* quarter period */
  rs_case_free(&c);

  if (load(&c, "rolled.yaml", NULL, 0) != RS_OK) return;
  CHECK(c.rolled_distance == 9.0 && fabs(c.end_time - 0.0003) < 1e-18);
  rs_case_free(&c);

  if (load(&c, "shift.yaml", NULL, 0) != RS_OK) return;
  CHECK(c.velocity.value == 0.0 && c.shift_velocity.value == 10.0);
  rs_case_free(&c);

  /* grid.x_range: stored as given, printed back, extent not used */
  if (load(&c, "x_range.yaml", NULL, 0) != RS_OK) return;
  CHECK(c.grid_from_range == 1 && c.x_range[0] == -1.25 && c.x_range[1] == 1.15 && c.cells == 80);
  char *text = NULL;
  size_t len = 0;
  FILE *mem = open_memstream(&text, &len);
  rs_case_print(&c, mem);
  fclose(mem);
  CHECK(strstr(text, "grid.x_range: [-1.25, 1.15]  # mm") != NULL);
  CHECK(strstr(text, "grid.extent: null") != NULL);
  free(text);
  rs_case_free(&c);
}

static void test_sets(void)
{
  rs_case c;
  const char *sets[] = {"grid.cells=200",     "rolling.creepage=-0.001", "output.fields=[px,pn]",
                        "plasticity.k_tau=0", "solver.scaling=self",     "title=changed"};
  if (load(&c, "full.yaml", sets, 6) != RS_OK) return;
  CHECK(c.cells == 200);
  CHECK(c.creepage.kind == RS_HISTORY_CONSTANT && c.creepage.value == -0.001);
  CHECK(c.fields == (RS_FIELD_PX | RS_FIELD_PN));
  CHECK(c.k_tau == 0.0 && c.scaling == RS_SCALING_SELF && !strcmp(c.title, "changed"));
  CHECK(strstr(c.yaml_text, "cells: 200") && strstr(c.yaml_text, "creepage: -0.001"));
  rs_case_free(&c);

  /* keys absent from the file: parent mappings are created */
  const char *create[] = {"layer.thickness=0.2",
                          "rolling.creepage={ramp: {from: 0, to: -0.01, start: 0, duration: 0.05}}",
                          "plasticity.k_rel=0.6", "simulation.rolled_distance=9"};
  if (load(&c, "minimal.yaml", create, 4) != RS_OK) return;
  CHECK(c.layer_thickness == 0.2);
  CHECK(c.creepage.kind == RS_HISTORY_RAMP && c.creepage.to == -0.01 &&
        c.creepage.duration == 0.05);
  CHECK(c.has_plasticity == 1 && c.k_tau == 123000.0);
  CHECK(fabs(c.end_time - 0.0003) < 1e-18);
  rs_case_free(&c);

  /* null = not given: switch from end_time to rolled_distance (3 mm at 30000 mm/s) */
  const char *distance[] = {"simulation.end_time=null", "simulation.rolled_distance=3"};
  if (load(&c, "full.yaml", distance, 2) != RS_OK) return;
  CHECK(c.rolled_distance == 3.0 && fabs(c.end_time - 1e-4) < 1e-18);
  rs_case_free(&c);

  /* solver.rtol: auto (stored as 0, resolved per run) and back to a number */
  const char *rtol_auto[] = {"solver.rtol=auto"};
  if (load(&c, "full.yaml", rtol_auto, 1) != RS_OK) return;
  CHECK(c.rtol == 0.0);
  rs_case_free(&c);
  const char *rtol_number[] = {"solver.rtol=3e-3"};
  if (load(&c, "minimal.yaml", rtol_number, 1) != RS_OK) return;
  CHECK(c.rtol == 3e-3);
  rs_case_free(&c);

  /* plasticity=null switches the block off */
  const char *off[] = {"plasticity=null"};
  if (load(&c, "full.yaml", off, 1) != RS_OK) return;
  CHECK(c.has_plasticity == 0);
  rs_case_free(&c);
}

static void expect_set_error(const char *set, const char *want)
{
  char path[1024];
  rs_case c;
  rs_msg msg = {{0}};
  const char *sets[] = {set};
  int status = rs_case_load(&c, in_dir(good_dir, "full.yaml", path, sizeof path), sets, 1, &msg);
  if (status != RS_ERR_INPUT || !strstr(msg.text, want)) {
    printf("FAIL --set %s: status %d, message \"%s\", want \"%s\"\n", set, status, msg.text, want);
    failures++;
  }
  CHECK(c.yaml_text == NULL && c.title == NULL);
}

static void test_set_errors(void)
{
  expect_set_error("rolling.creepage=x", "--set rolling.creepage: expected a number, got \"x\"");
  expect_set_error("contact.radiu=3", "--set contact.radiu: unknown key");
  expect_set_error("nosuchsection.key=3", "--set nosuchsection.key: nosuchsection: unknown key");
  expect_set_error("grid.cells", "--set grid.cells: expected KEY=VALUE");
  expect_set_error("grid.cells=1", "--set grid.cells: must be >= 2");
  expect_set_error("rolling.creepage={ramp: {from: 0, to: a, duration: 1}}",
                   "--set rolling.creepage: rolling.creepage.ramp.to: expected a number");
  expect_set_error("contact.radius.x=1", "--set contact.radius.x: contact.radius is not a mapping");
  expect_set_error("output.fields=[px, bogus]", "--set output.fields: unknown field \"bogus\"");
  expect_set_error("plasticity.k_rel=0.5", "plasticity.k_rel: give plasticity.k_tau");
  expect_set_error("grid.cells={a: [1", "--set grid.cells: cannot read");
}

static void test_file_errors(void)
{
  char path[1024];
  rs_case c;
  rs_msg msg = {{0}};
  int status =
      rs_case_load(&c, in_dir(good_dir, "does_not_exist.yaml", path, sizeof path), NULL, 0, &msg);
  CHECK(status == RS_ERR_INPUT && strstr(msg.text, "cannot open case file ") &&
        strstr(msg.text, "does_not_exist.yaml: No such file or directory"));

  FILE *f = fopen(in_dir(work_dir, "case_empty.yaml", path, sizeof path), "w");
  CHECK(f != NULL);
  if (f) fclose(f); /* zero bytes */
  status = rs_case_load(&c, path, NULL, 0, &msg);
  char where[1100];
  snprintf(where, sizeof where, "%s:1: ", path);
  CHECK(status == RS_ERR_INPUT && !strncmp(msg.text, where, strlen(where)) &&
        strstr(msg.text, "empty"));

  status = rs_case_load(&c, NULL, NULL, 0, &msg);
  CHECK(status == RS_ERR_INPUT);
}

static void test_print(void)
{
  rs_case c;
  if (load(&c, "k_rel.yaml", NULL, 0) != RS_OK) return;
  char *text = NULL;
  size_t len = 0;
  FILE *out = open_memstream(&text, &len);
  CHECK(out != NULL);
  if (!out) {
    rs_case_free(&c);
    return;
  }
  rs_case_print(&c, out);
  fclose(out);
  const char *want[] = {"\nplasticity.k_tau: 123000  # N/mm^3\n",
                        "\nplasticity.tau_c_min: 3.5  # N/mm^2\n",
                        "\nsimulation.end_time: 0.0004  # s\n",
                        "\nmaterial.shear_modulus: 82000  # N/mm^2\n",
                        "\ncontact.normal_load: 178.9  # N/mm\n",
                        "\nsolver.scaling: auto\n",
                        "\nsolver.rtol: auto  # 1 (0.06 dx/a within [1e-6, 3e-3])\n",
                        "\nsolver.max_steps: 1000000",
                        "\noutput.file: \"results/k_rel.nc\"\n",
                        "\noutput.fields: [px, pn, slip, upl, ustar, tauc, regime]\n"};
  for (size_t i = 0; i < sizeof want / sizeof want[0]; i++)
    if (!strstr(text, want[i])) {
      printf("FAIL rs_case_print: no line \"%s\" in:\n%s\n", want[i] + 1, text);
      failures++;
    }
  free(text);
  rs_case_free(&c);
}

/* yaml_text written to a file and loaded again gives the same case. */
static void round_trip(const char *name, const char *const *sets, int nsets)
{
  rs_case a, b;
  if (load(&a, name, sets, nsets) != RS_OK) return;
  char path[1024];
  snprintf(path, sizeof path, "%s/roundtrip_%s", work_dir, name);
  FILE *f = fopen(path, "w");
  CHECK(f != NULL);
  if (!f) {
    rs_case_free(&a);
    return;
  }
  fputs(a.yaml_text, f);
  fclose(f);
  rs_msg msg = {{0}};
  int status = rs_case_load(&b, path, NULL, 0, &msg);
  if (status != RS_OK) {
    printf("FAIL reloading yaml_text of %s: %s\n--- yaml_text:\n%s", name, msg.text, a.yaml_text);
    failures++;
    rs_case_free(&a);
    return;
  }
  if (!strcmp(a.output_file, "results/minimal.nc")) /* the default follows the file name */
    CHECK(!strcmp(b.output_file, "results/roundtrip_minimal.nc"));
  else
    CHECK(!strcmp(a.output_file, b.output_file));
  char *keep = a.output_file;
  a.output_file = b.output_file;
  if (!same_case(&a, &b)) {
    printf("FAIL round trip of %s: values differ\n--- yaml_text:\n%s", name, a.yaml_text);
    failures++;
  }
  a.output_file = keep;
  CHECK(!strcmp(a.yaml_text, b.yaml_text)); /* emitting is idempotent */
  rs_case_free(&a);
  rs_case_free(&b);
}

/* rs_case_print of a case, malloc'ed. */
static char *printed(const rs_case *c)
{
  char *text = NULL;
  size_t len = 0;
  FILE *out = open_memstream(&text, &len);
  if (!out) return NULL;
  rs_case_print(c, out);
  fclose(out);
  return text;
}

/* The case file `name` with `sets`, then the overrides given two ways: as one more --set
 * KEY=%.17g each (the document path) and as typed overrides of the loaded case
 * (rs_case_derive): the same status, the same message on error, else the same values and
 * the same print-out but for the --set line, which lists the overrides in both. */
static void expect_derived(const char *name, const char *const *sets, int nsets,
                           const char *const *keys, const double *values, int nov)
{
  char path[1024], assign[8][128];
  const char *all[16];
  rs_case_override ov[8];
  for (int i = 0; i < nsets; i++) all[i] = sets[i];
  for (int i = 0; i < nov; i++) {
    snprintf(assign[i], sizeof assign[i], "%s=%.17g", keys[i], values[i]);
    all[nsets + i] = assign[i];
    ov[i] = (rs_case_override){rs_case_key_index(keys[i]), values[i]};
    CHECK(ov[i].key >= 0 && rs_case_key_numeric(ov[i].key));
  }
  in_dir(good_dir, name, path, sizeof path);
  rs_case want, base, got;
  rs_msg mw = {{0}}, mb = {{0}}, mg = {{0}};
  const int sw = rs_case_load(&want, path, all, nsets + nov, &mw);
  if (rs_case_load(&base, path, sets, nsets, &mb) != RS_OK) {
    printf("FAIL loading %s: %s\n", name, mb.text);
    failures++;
    if (sw == RS_OK) rs_case_free(&want);
    return;
  }
  const int sg = rs_case_derive(&base, ov, nov, &got, &mg);
  if (sg != sw || (sw != RS_OK && strcmp(mw.text, mg.text))) {
    printf("FAIL %s with %s...: --set gives %d \"%s\", the typed override %d \"%s\"\n", name,
           assign[0], sw, mw.text, sg, mg.text);
    failures++;
  } else if (sw == RS_OK) {
    char *a = printed(&want), *b = printed(&got);
    CHECK(same_case(&want, &got) && got.source == NULL && got.yaml_text == NULL);
    CHECK(!strcmp(want.source_path, got.source_path));
    /* the --set line: "KEY=%.17g" against the override's shortest text, both read back the
     * same; the rest of the print-out is the same text */
    const char *la = a ? strstr(a, "# changed with --set") : NULL;
    const char *lb = b ? strstr(b, "# changed with --set") : NULL;
    CHECK(a && b && (la != NULL) == (lb != NULL));
    if (a && b && la && lb) {
      CHECK(la - a == lb - b && !strncmp(a, b, (size_t)(la - a)));
      CHECK(!strcmp(strchr(la, '\n'), strchr(lb, '\n')));
    } else if (a && b) {
      CHECK(!strcmp(a, b));
    }
    free(a);
    free(b);
  }
  if (sw == RS_OK) rs_case_free(&want);
  if (sg == RS_OK) rs_case_free(&got);
  rs_case_free(&base);
}

static void test_derive(void)
{
  const char *creep[] = {"rolling.creepage"};
  expect_derived("minimal.yaml", NULL, 0, creep, (const double[]){-0.003}, 1);
  expect_derived("full.yaml", NULL, 0, creep, (const double[]){-2.0020020020020022e-05}, 1);
  const char *tau[] = {"plasticity.tau_c0"};
  expect_derived("full.yaml", NULL, 0, tau, (const double[]){50.0}, 1);
  /* a key under a missing section creates it, as --set does: then the hardening is missing */
  expect_derived("minimal.yaml", NULL, 0, tau, (const double[]){50.0}, 1);
  const char *nu[] = {"material.poisson_ratio"};
  expect_derived("full.yaml", NULL, 0, nu, (const double[]){0.6}, 1);
  expect_derived("full.yaml", NULL, 0, nu, (const double[]){0.30000000000000004}, 1);
  const char *order[] = {"solver.max_order"}, *steps[] = {"solver.max_steps"};
  expect_derived("full.yaml", NULL, 0, order, (const double[]){2.5}, 1);
  expect_derived("full.yaml", NULL, 0, order, (const double[]){3.0}, 1);
  expect_derived("full.yaml", NULL, 0, steps, (const double[]){77.0}, 1);
  /* a history replaced by a number; the tau_c_min rule against a new tau_c0 */
  const char *load[] = {"contact.normal_load"};
  expect_derived("histories.yaml", NULL, 0, load, (const double[]){150.0}, 1);
  expect_derived("full.yaml", NULL, 0, tau, (const double[]){2.0}, 1);
  /* several overrides after --set assignments; the last of a key twice wins */
  const char *sets[] = {"simulation.end_time=null", "simulation.rolled_distance=3"};
  const char *two[] = {"rolling.velocity", "contact.normal_load", "rolling.velocity"};
  expect_derived("full.yaml", sets, 2, two, (const double[]){20000.0, 160.0, 15000.0}, 3);
  expect_derived("full.yaml", sets, 2, two, (const double[]){20000.0, -1.0, 15000.0}, 3);
}

int main(int argc, char **argv)
{
  if (argc != 3) {
    fprintf(stderr, "usage: %s GOOD_INPUTS_DIR WORK_DIR\n", argv[0]);
    return 2;
  }
  good_dir = argv[1];
  work_dir = argv[2];
  test_full();
  test_minimal_defaults();
  test_k_rel();
  test_histories();
  test_sets();
  test_set_errors();
  test_file_errors();
  test_print();
  test_derive();
  round_trip("full.yaml", NULL, 0);
  const char *sets[] = {"grid.cells=64",
                        "rolling.creepage={steps: [[0, -0.001], [0.0001, -0.002]]}",
                        "title=with --set", "solver.max_steps=77",
                        "contact.normal_load={sine: {mean: 150, amplitude: 20, frequency: 1000}}"};
  round_trip("full.yaml", sets, 5);
  const char *create[] = {"layer.thickness=0.2", "plasticity.k_rel=-0.3",
                          "output.file=results/x.nc", "simulation.rolled_distance=3"};
  round_trip("minimal.yaml", create, 4);
  round_trip("minimal.yaml", NULL, 0);
  round_trip("x_range.yaml", NULL, 0);
  if (failures) {
    printf("%d failure(s)\n", failures);
    return 1;
  }
  printf("all case checks passed\n");
  return 0;
}
