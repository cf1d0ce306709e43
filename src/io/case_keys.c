/* The case-file keys (docs/case-file.md): one table giving each key's type, field, unit
 * and allowed range, and the walk of the document that fills an rs_case from it.
 * Cross-key rules and derived values are in case.c. */
#include "io/case_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

_Static_assert(sizeof(rs_mode) == sizeof(int) && sizeof(rs_scaling) == sizeof(int) &&
                   sizeof(rs_normal_solution) == sizeof(int) &&
                   sizeof(rs_initial_state) == sizeof(int) &&
                   sizeof(rs_friction_kind) == sizeof(int),
               "choice keys are stored through int *");

static const char *const normal_solution_names[] = {"discrete", "hertz", NULL};
static const char *const mode_names[] = {"transient", "steady", NULL};
static const char *const initial_state_names[] = {"rest", "steady", NULL};
static const char *const scaling_names[] = {"auto", "difference", "self", NULL};
static const char *const bool_names[] = {"false", "true", NULL};
static const char *const law_names[] = {"coulomb",  "linear", "exponential",
                                        "rational", "polach", NULL};
static const char *const mu_table_columns[] = {"temperature", "mu", NULL};
static const char *const tau_table_columns[] = {"temperature", "tau_c0", NULL};
static const char *const coupling_names[] = {"newton", "fixed_point", NULL};
const char *const rs_case_field_names[] = {"px",    "pn",   "slip",   "upl",
                                           "ustar", "tauc", "regime", NULL};

#define F(member) offsetof(rs_case_input, member)
#define BIG       1e12 /* sanity bound on moduli, loads, lengths: larger is surely a typo */

const rs_case_key rs_case_keys[] = {
    {"title", RS_KEY_TEXT, F(c.title), "", 0, 0, RS_KEY_NULLABLE, NULL},

    {"contact", RS_KEY_SECTION, 0, "", 0, 0, 0, NULL},
    {"contact.dimension", RS_KEY_INTEGER, F(c.dimension), "", 2, 3, 0, NULL},
    {"contact.normal_load", RS_KEY_HISTORY, F(c.normal_load), "N/mm", 0, BIG,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD, NULL},
    {"contact.radius", RS_KEY_VECTOR, F(radius), "mm", 0, 1e9,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"contact.curvature", RS_KEY_VECTOR, F(curvature), "1/mm", 0, 1e9,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"contact.normal_solution", RS_KEY_CHOICE, F(c.normal_solution), "", 0, 0, 0,
     normal_solution_names},
    {"contact.reference_length", RS_KEY_NUMBER, F(c.reference_length), "mm", 0, 1e9,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD, NULL},

    {"grid", RS_KEY_SECTION, 0, "", 0, 0, 0, NULL},
    {"grid.cells", RS_KEY_VECTOR, F(cells), "", 2, 100000, RS_KEY_WHOLE, NULL},
    {"grid.extent", RS_KEY_VECTOR, F(extent), "Hertz semi-axes", 1, 1000,
     RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"grid.x_range", RS_KEY_RANGE, F(c.x_range), "mm", -1e9, 1e9,
     RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"grid.y_range", RS_KEY_RANGE, F(c.y_range), "mm", -1e9, 1e9,
     RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"grid.align_edges", RS_KEY_CHOICE, F(c.align_edges), "", 0, 0, 0, bool_names},
    {"grid.accuracy", RS_KEY_NUMBER, F(c.accuracy), "", 0, 1,
     RS_KEY_LO_OPEN | RS_KEY_HI_OPEN | RS_KEY_NULLABLE, NULL},

    {"material", RS_KEY_SECTION, 0, "", 0, 0, 0, NULL},
    {"material.shear_modulus", RS_KEY_NUMBER, F(c.shear_modulus), "N/mm^2", 0, BIG,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD, NULL},
    {"material.poisson_ratio", RS_KEY_NUMBER, F(c.poisson_ratio), "", -1, 0.5,
     RS_KEY_LO_OPEN | RS_KEY_HI_OPEN, NULL},

    {"friction", RS_KEY_SECTION, 0, "", 0, 0, 0, NULL},
    {"friction.law", RS_KEY_CHOICE, F(c.friction.kind), "", 0, 0, RS_KEY_NULLABLE, law_names},
    {"friction.mu", RS_KEY_NUMBER, F(c.mu), "", 0, 1000,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"friction.mu_kinetic", RS_KEY_NUMBER, F(c.friction.mu_kinetic), "", 0, 10,
     RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"friction.mu_excess", RS_KEY_VECTOR, F(mu_excess), "", 0, 10,
     RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"friction.half_velocity", RS_KEY_VECTOR, F(half_velocity), "mm/s", 0, 1e12,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"friction.mu_static", RS_KEY_NUMBER, F(c.friction.mu_static), "", 0, 10,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"friction.A", RS_KEY_NUMBER, F(c.friction.polach_a), "", 0, 1, RS_KEY_NULLABLE, NULL},
    {"friction.B", RS_KEY_NUMBER, F(c.friction.polach_b), "s/mm", 0, 1e6,
     RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"friction.temperature_table", RS_KEY_TTABLE, F(c.mu_table), "", 0, 1000,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, mu_table_columns},
    {"friction.memory_distance", RS_KEY_NUMBER, F(c.friction.memory_distance), "mm", 0, 1e6,
     RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"friction.memory_velocity", RS_KEY_NUMBER, F(c.friction.memory_velocity), "mm/s", 0, 1e12,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},

    {"layer", RS_KEY_SECTION, 0, "", 0, 0, 0, NULL},
    {"layer.thickness", RS_KEY_NUMBER, F(c.layer_thickness), "mm", 0, 1e9, RS_KEY_HI_ABSURD, NULL},
    {"layer.shear_modulus", RS_KEY_NUMBER, F(c.layer_shear_modulus), "N/mm^2", 0, BIG,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD, NULL},

    {"plasticity", RS_KEY_SECTION, 0, "", 0, 0, 0, NULL},
    {"plasticity.tau_c0", RS_KEY_NUMBER, F(c.tau_c0), "N/mm^2", 0, BIG,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD, NULL},
    {"plasticity.k_tau", RS_KEY_NUMBER, F(c.k_tau), "N/mm^3", -1e15, 1e15,
     RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"plasticity.k_rel", RS_KEY_NUMBER, F(k_rel), "", -1e6, 1,
     RS_KEY_HI_OPEN | RS_KEY_DERIVED | RS_KEY_NULLABLE, NULL},
    {"plasticity.tau_c_min", RS_KEY_NUMBER, F(c.tau_c_min), "N/mm^2", 0, BIG,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"plasticity.tau_c0_table", RS_KEY_TTABLE, F(c.tau_c0_table), "N/mm^2", 0, BIG,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, tau_table_columns},

    {"rolling", RS_KEY_SECTION, 0, "", 0, 0, 0, NULL},
    {"rolling.velocity", RS_KEY_HISTORY, F(c.velocity), "mm/s", 0, 1e9, RS_KEY_HI_ABSURD, NULL},
    {"rolling.creepage", RS_KEY_HISTORY, F(c.creepage), "", -10, 10,
     RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"rolling.lateral_creepage", RS_KEY_HISTORY, F(c.lateral_creepage), "", -10, 10,
     RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"rolling.spin", RS_KEY_HISTORY, F(c.spin), "1/mm", -1e3, 1e3,
     RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"rolling.tangential_force", RS_KEY_HISTORY, F(c.tangential_force), "N/mm", -BIG, BIG,
     RS_KEY_HI_ABSURD | RS_KEY_NULLABLE | RS_KEY_XY, NULL},
    {"rolling.shift_velocity", RS_KEY_HISTORY, F(c.shift_velocity), "mm/s", -1e9, 1e9,
     RS_KEY_HI_ABSURD, NULL},

    {"twin_disc", RS_KEY_SECTION, 0, "", 0, 0, 0, NULL},
    {"twin_disc.radius_1", RS_KEY_NUMBER, F(c.rig.radius_1), "mm", 0, BIG,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD, NULL},
    {"twin_disc.radius_2", RS_KEY_NUMBER, F(c.rig.radius_2), "mm", 0, BIG,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD, NULL},
    {"twin_disc.crown_radius_1", RS_KEY_NUMBER, F(c.rig.crown_radius_1), "mm", 0, BIG,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"twin_disc.crown_radius_2", RS_KEY_NUMBER, F(c.rig.crown_radius_2), "mm", 0, BIG,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"twin_disc.width", RS_KEY_NUMBER, F(c.rig.width), "mm", 0, BIG,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD, NULL},
    {"twin_disc.normal_force", RS_KEY_NUMBER, F(c.rig.normal_force), "N", 0, BIG,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD, NULL},
    {"twin_disc.rpm", RS_KEY_NUMBER, F(c.rig.rpm), "1/min", 0, 1e7,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"twin_disc.rpm_1", RS_KEY_NUMBER, F(c.rig.rpm_1), "1/min", 0, 1e7,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"twin_disc.rpm_2", RS_KEY_NUMBER, F(c.rig.rpm_2), "1/min", 0, 1e7,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"twin_disc.revolutions", RS_KEY_NUMBER, F(c.rig.revolutions), "", 0, 1e7,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"twin_disc.protocol", RS_KEY_PROTOCOL, F(c.rig), "", 0, 0, RS_KEY_NULLABLE, NULL},
    {"twin_disc.recovery", RS_KEY_NUMBER, F(c.rig.recovery), "", 0, 1, 0, NULL},
    {"twin_disc.average_window", RS_KEY_NUMBER, F(c.rig.average_window), "", 0, 1, RS_KEY_LO_OPEN,
     NULL},

    {"temperature", RS_KEY_SECTION, 0, "", 0, 0, 0, NULL},
    {"temperature.bulk", RS_KEY_VECTOR, F(t_bulk), "degC", -273.15, 1e4,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD | RS_KEY_BODIES, NULL},
    {"temperature.conductivity", RS_KEY_VECTOR, F(t_conductivity), "W/(mm K)", 0, 100,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD | RS_KEY_BODIES | RS_KEY_NULLABLE, NULL},
    {"temperature.heat_capacity", RS_KEY_VECTOR, F(t_heat_capacity), "J/(kg K)", 0, 1e6,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD | RS_KEY_BODIES | RS_KEY_NULLABLE, NULL},
    {"temperature.density", RS_KEY_VECTOR, F(t_density), "kg/mm^3", 0, 1e-3,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD | RS_KEY_BODIES | RS_KEY_NULLABLE, NULL},
    {"temperature.plastic_heat_fraction", RS_KEY_NUMBER, F(c.temperature.plastic_heat_fraction), "",
     0, 1, RS_KEY_NULLABLE, NULL},
    {"temperature.kernel_tolerance", RS_KEY_NUMBER, F(c.temperature.kernel_tolerance), "", 1e-8,
     0.1, RS_KEY_NULLABLE, NULL},
    {"temperature.convection", RS_KEY_NUMBER, F(c.temperature.convection), "W/(mm^2 K)", 0, 1,
     RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"temperature.disc_mass", RS_KEY_VECTOR, F(t_disc_mass), "kg", 0, 1e4,
     RS_KEY_HI_ABSURD | RS_KEY_BODIES | RS_KEY_NULLABLE, NULL},
    {"temperature.coupling", RS_KEY_CHOICE, F(c.temperature_coupling), "", 0, 0, RS_KEY_NULLABLE,
     coupling_names},

    {"simulation", RS_KEY_SECTION, 0, "", 0, 0, 0, NULL},
    {"simulation.mode", RS_KEY_CHOICE, F(c.mode), "", 0, 0, 0, mode_names},
    {"simulation.end_time", RS_KEY_NUMBER, F(c.end_time), "s", 0, 1e6,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"simulation.rolled_distance", RS_KEY_NUMBER, F(c.rolled_distance), "mm", 0, BIG,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD | RS_KEY_NULLABLE, NULL},
    {"simulation.output_interval", RS_KEY_NUMBER, F(c.output_interval), "s", 0, 1e6,
     RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD, NULL},
    {"simulation.initial_state", RS_KEY_CHOICE, F(c.initial_state), "", 0, 0, 0,
     initial_state_names},

    {"solver", RS_KEY_SECTION, 0, "", 0, 0, 0, NULL},
    {"solver.rtol", RS_KEY_NUMBER, F(c.rtol), "", 0, 1,
     RS_KEY_LO_OPEN | RS_KEY_HI_OPEN | RS_KEY_AUTO, NULL},
    {"solver.atol", RS_KEY_NUMBER, F(c.atol), "N/mm^2", 0, BIG, RS_KEY_LO_OPEN | RS_KEY_HI_ABSURD,
     NULL},
    {"solver.max_order", RS_KEY_INTEGER, F(c.max_order), "", 1, 5, 0, NULL},
    {"solver.threads", RS_KEY_INTEGER, F(c.threads), "", 1, 2, 0, NULL},
    {"solver.scaling", RS_KEY_CHOICE, F(c.scaling), "", 0, 0, 0, scaling_names},
    {"solver.max_steps", RS_KEY_LONG, F(c.max_steps), "steps", 1, 1e15, RS_KEY_HI_ABSURD, NULL},

    {"output", RS_KEY_SECTION, 0, "", 0, 0, 0, NULL},
    {"output.file", RS_KEY_TEXT, F(c.output_file), "", 0, 0, RS_KEY_NULLABLE, NULL},
    {"output.fields", RS_KEY_FIELDS, F(c.fields), "", 0, 0, 0, NULL},
    {"output.error_estimate", RS_KEY_CHOICE, F(c.error_estimate), "", 0, 0, 0, bool_names},

    {"sweep", RS_KEY_OPAQUE, 0, "", 0, 0, 0, NULL},
    {"fit", RS_KEY_OPAQUE, 0, "", 0, 0, 0, NULL},
    {"profiles", RS_KEY_OPAQUE, 0, "", 0, 0, 0, NULL}, /* read by case_profiles.c */
};
const size_t rs_case_nkeys = sizeof rs_case_keys / sizeof rs_case_keys[0];

int rs_case_key_index(const char *path)
{
  for (size_t i = 0; i < rs_case_nkeys; i++)
    if (!strcmp(rs_case_keys[i].path, path)) return (int)i;
  return -1;
}

const char *rs_case_key_unit_in(const char *unit, int dimension)
{
  return dimension == 3 && !strcmp(unit, "N/mm") ? "N" : unit;
}

const char *rs_case_key_name(int key)
{
  return key >= 0 && (size_t)key < rs_case_nkeys ? rs_case_keys[key].path : "";
}

int rs_case_key_numeric(int key)
{
  if (key < 0 || (size_t)key >= rs_case_nkeys) return 0;
  const rs_case_key_kind k = rs_case_keys[key].kind;
  return k == RS_KEY_NUMBER || k == RS_KEY_INTEGER || k == RS_KEY_LONG || k == RS_KEY_HISTORY;
}

rs_rolling_input rs_case_key_rolling(int key)
{
  if (key < 0 || (size_t)key >= rs_case_nkeys || rs_case_keys[key].kind != RS_KEY_HISTORY)
    return RS_ROLLING_NONE;
  const size_t at = rs_case_keys[key].offset;
  return at == F(c.creepage)           ? RS_ROLLING_CREEPAGE
         : at == F(c.velocity)         ? RS_ROLLING_VELOCITY
         : at == F(c.shift_velocity)   ? RS_ROLLING_SHIFT_VELOCITY
         : at == F(c.lateral_creepage) ? RS_ROLLING_LATERAL_CREEPAGE
         : at == F(c.spin)             ? RS_ROLLING_SPIN
                                       : RS_ROLLING_NONE;
}

int rs_case_check_range(const rs_case_doc *d, const yaml_node_t *n, const rs_case_key *spec,
                        const char *key, double x)
{
  const char *sp = *spec->unit ? " " : "";
  char got[32];
  if (spec->flags & RS_KEY_LO_OPEN ? !(x > spec->lo) : !(x >= spec->lo))
    return rs_case_error(d, n, key, "must be %s %g%s%s, got %s",
                         spec->flags & RS_KEY_LO_OPEN ? ">" : ">=", spec->lo, sp, spec->unit,
                         rs_case_fmt(x, got, sizeof got));
  if (spec->flags & RS_KEY_HI_OPEN ? !(x < spec->hi) : !(x <= spec->hi))
    return rs_case_error(d, n, key, "must be %s %g%s%s, got %s%s",
                         spec->flags & RS_KEY_HI_OPEN ? "<" : "<=", spec->hi, sp, spec->unit,
                         rs_case_fmt(x, got, sizeof got),
                         spec->flags & RS_KEY_HI_ABSURD ? " (unreasonably large: a typo?)" : "");
  return RS_OK;
}

/* output.fields: a list of distinct names from rs_case_field_names. */
static int parse_fields(const rs_case_doc *d, const yaml_node_t *n, const char *key, unsigned *mask)
{
  char got[96], names[128] = "";
  if (n->type != YAML_SEQUENCE_NODE)
    return rs_case_error(d, n, key, "expected a list such as [px, pn, slip], got %s",
                         rs_case_describe(n, got, sizeof got));
  *mask = 0;
  for (yaml_node_item_t *it = n->data.sequence.items.start; it < n->data.sequence.items.top; it++) {
    const yaml_node_t *item = yaml_document_get_node((yaml_document_t *)&d->doc, *it);
    int i = 0;
    if (item && item->type == YAML_SCALAR_NODE)
      for (; rs_case_field_names[i]; i++)
        if (!strcmp((const char *)item->data.scalar.value, rs_case_field_names[i])) break;
    if (!item || item->type != YAML_SCALAR_NODE || !rs_case_field_names[i]) {
      for (int j = 0; rs_case_field_names[j]; j++)
        strcat(strcat(names, j ? ", " : ""), rs_case_field_names[j]);
      return rs_case_error(d, item, key, "unknown field %s (fields are %s)",
                           rs_case_describe(item, got, sizeof got), names);
    }
    if (*mask & (1u << i))
      return rs_case_error(d, item, key, "%s is listed twice", rs_case_field_names[i]);
    *mask |= 1u << i;
  }
  return RS_OK;
}

/* [lo, hi]: two numbers in the key's range, lo < hi. */
static int parse_range(const rs_case_doc *d, const yaml_node_t *n, const rs_case_key *spec,
                       double *out)
{
  char got[96];
  const yaml_node_t *item[2] = {NULL, NULL};
  if (n->type == YAML_SEQUENCE_NODE &&
      n->data.sequence.items.top - n->data.sequence.items.start == 2)
    for (int k = 0; k < 2; k++)
      item[k] = yaml_document_get_node((yaml_document_t *)&d->doc, n->data.sequence.items.start[k]);
  if (!item[0] || !item[1])
    return rs_case_error(d, n, spec->path, "expected [lo, hi] (%s), got %s", spec->unit,
                         rs_case_describe(n, got, sizeof got));
  for (int k = 0; k < 2; k++) {
    int status = rs_case_number(d, item[k], spec->path, &out[k]);
    if (status == RS_OK) status = rs_case_check_range(d, item[k], spec, spec->path, out[k]);
    if (status != RS_OK) return status;
  }
  if (!(out[1] > out[0]))
    return rs_case_error(d, n, spec->path, "expected [lo, hi] with lo < hi, got [%g, %g] %s",
                         out[0], out[1], spec->unit);
  return RS_OK;
}

/* A property against temperature (RS_KEY_TTABLE): {temperature: [T...], <value>: [v...]}, the
 * two lists of equal length >= 2, the temperatures (degC) strictly increasing, every value within
 * the key's range; stored as a table history (t: temperature, v: value). */
static int parse_ttable(const rs_case_doc *d, const yaml_node_t *n, const rs_case_key *spec,
                        rs_history *h)
{
  char got[96], sub[2][320];
  const char *const *col = spec->choices;
  if (n->type != YAML_MAPPING_NODE)
    return rs_case_error(d, n, spec->path,
                         "expected a mapping {%s: [degC, ...], %s: [...]}, got %s", col[0], col[1],
                         rs_case_describe(n, got, sizeof got));
  int status = rs_case_check_mapping(d, n, spec->path, col);
  if (status != RS_OK) return status;
  const yaml_node_t *list[2];
  size_t count[2];
  for (int k = 0; k < 2; k++) {
    snprintf(sub[k], sizeof sub[k], "%s.%s", spec->path, col[k]);
    list[k] = rs_case_lookup(d, n, col[k]);
    if (!list[k])
      return rs_case_error(d, n, spec->path,
                           "missing: give %s: [...] and %s: [...] of equal length", col[0], col[1]);
    if (list[k]->type != YAML_SEQUENCE_NODE)
      return rs_case_error(d, list[k], sub[k], "expected a list of numbers, got %s",
                           rs_case_describe(list[k], got, sizeof got));
    count[k] = (size_t)(list[k]->data.sequence.items.top - list[k]->data.sequence.items.start);
  }
  if (count[0] < 2)
    return rs_case_error(d, list[0], sub[0], "expected at least 2 temperatures (degC), got %zu",
                         count[0]);
  if (count[1] != count[0])
    return rs_case_error(d, list[1], sub[1],
                         "has %zu values for %zu temperatures: give one per "
                         "temperature",
                         count[1], count[0]);
  rs_history_free(h);
  h->kind = RS_HISTORY_TABLE;
  h->t = malloc(count[0] * sizeof *h->t);
  h->v = malloc(count[0] * sizeof *h->v);
  if (!h->t || !h->v) return rs_msg_set(d->msg, RS_ERR_INTERNAL, "out of memory");
  for (size_t i = 0; i < count[0]; i++) {
    const yaml_node_t *nt =
        yaml_document_get_node((yaml_document_t *)&d->doc, list[0]->data.sequence.items.start[i]);
    const yaml_node_t *nv =
        yaml_document_get_node((yaml_document_t *)&d->doc, list[1]->data.sequence.items.start[i]);
    if ((status = rs_case_number(d, nt, sub[0], &h->t[i])) != RS_OK ||
        (status = rs_case_number(d, nv, sub[1], &h->v[i])) != RS_OK ||
        (status = rs_case_check_range(d, nv, spec, sub[1], h->v[i])) != RS_OK)
      return status;
    h->n = i + 1;
    if (!(h->t[i] > -273.15 && h->t[i] < 1e5))
      return rs_case_error(d, nt, sub[0],
                           "temperature %g degC: must be above -273.15 degC (and "
                           "below 1e5)",
                           h->t[i]);
    if (i > 0 && !(h->t[i] > h->t[i - 1]))
      return rs_case_error(d, nt, sub[0],
                           "temperatures must be strictly increasing: %g degC after %g degC",
                           h->t[i], h->t[i - 1]);
  }
  return RS_OK;
}

/* A number, or a list of two (3D); whole numbers when RS_KEY_WHOLE; each in range. */
static int parse_vector(const rs_case_doc *d, const yaml_node_t *n, const rs_case_key *spec,
                        rs_case_vec *out)
{
  char got[96];
  const yaml_node_t *item[2] = {n, NULL};
  int count = 1;
  if (n->type == YAML_SEQUENCE_NODE) {
    count = (int)(n->data.sequence.items.top - n->data.sequence.items.start);
    if (count < 1 || count > 2)
      return rs_case_error(d, n, spec->path,
                           spec->flags & RS_KEY_BODIES
                               ? "expected a number (both bodies) or a list of two [body 1, body "
                                 "2] (%s), got %s"
                               : "expected a number (2D) or a list of two [x, y] (3D)%.0s, got %s",
                           spec->unit, rs_case_describe(n, got, sizeof got));
    for (int k = 0; k < count; k++)
      item[k] = yaml_document_get_node((yaml_document_t *)&d->doc, n->data.sequence.items.start[k]);
  }
  for (int k = 0; k < count; k++) {
    int status = rs_case_number(d, item[k], spec->path, &out->v[k]);
    if (status == RS_OK && (spec->flags & RS_KEY_WHOLE) && out->v[k] != floor(out->v[k]))
      status = rs_case_error(d, item[k], spec->path, "expected a whole number, got %s",
                             (const char *)item[k]->data.scalar.value);
    if (status == RS_OK) status = rs_case_check_range(d, item[k], spec, spec->path, out->v[k]);
    if (status != RS_OK) return status;
  }
  out->n = count;
  return RS_OK;
}

/* A history, or (RS_KEY_XY) a list of two histories [x, y] (3D): the second into `second`;
 * *count 1 or 2. */
static int parse_history_xy(const rs_case_doc *d, const yaml_node_t *n, const rs_case_key *spec,
                            rs_history *h, rs_history *second, int *count)
{
  char got[96];
  if (!(spec->flags & RS_KEY_XY) || n->type != YAML_SEQUENCE_NODE) {
    if (spec->flags & RS_KEY_XY) *count = 1;
    rs_history_free(h);
    return rs_case_history(d, n, spec->path, spec->unit, h);
  }
  if (n->data.sequence.items.top - n->data.sequence.items.start != 2)
    return rs_case_error(d, n, spec->path,
                         "expected one value (2D) or a list of two [x, y] (3D), got %s",
                         rs_case_describe(n, got, sizeof got));
  for (int k = 0; k < 2; k++) {
    const yaml_node_t *item =
        yaml_document_get_node((yaml_document_t *)&d->doc, n->data.sequence.items.start[k]);
    rs_history *dst = k ? second : h;
    rs_history_free(dst);
    const int status = rs_case_history(d, item, spec->path, spec->unit, dst);
    if (status != RS_OK) return status;
  }
  *count = 2;
  return RS_OK;
}

int rs_case_parse_value(const rs_case_doc *d, const rs_case_key *spec, const yaml_node_t *n,
                        rs_case_input *in)
{
  void *field = spec->offset == RS_KEY_NO_FIELD ? NULL : (char *)in + spec->offset;
  double x = 0;
  int status, choice = 0;
  switch (spec->kind) {
  case RS_KEY_NUMBER:
    if ((spec->flags & RS_KEY_AUTO) && n->type == YAML_SCALAR_NODE &&
        n->data.scalar.style == YAML_PLAIN_SCALAR_STYLE &&
        !strcmp((const char *)n->data.scalar.value, "auto")) {
      *(double *)field = 0.0;
      return RS_OK;
    }
    if ((spec->flags & RS_KEY_AUTO) && rs_case_number(d, n, spec->path, &x) != RS_OK) {
      char got[96];
      return rs_case_error(d, n, spec->path, "expected a number or auto, got %s",
                           rs_case_describe(n, got, sizeof got));
    }
    if ((status = rs_case_number(d, n, spec->path, &x)) != RS_OK ||
        (status = rs_case_check_range(d, n, spec, spec->path, x)) != RS_OK)
      return status;
    *(double *)field = x;
    return RS_OK;
  case RS_KEY_INTEGER:
  case RS_KEY_LONG:
    if ((status = rs_case_number(d, n, spec->path, &x)) != RS_OK) return status;
    if (x != floor(x))
      return rs_case_error(d, n, spec->path, "expected a whole number, got %s",
                           (const char *)n->data.scalar.value);
    if ((status = rs_case_check_range(d, n, spec, spec->path, x)) != RS_OK) return status;
    if (spec->kind == RS_KEY_INTEGER)
      *(int *)field = (int)x;
    else
      *(long *)field = (long)x;
    return RS_OK;
  case RS_KEY_TEXT: return rs_case_text(d, n, spec->path, (char **)field);
  case RS_KEY_CHOICE:
    if ((status = rs_case_choice(d, n, spec->path, spec->choices, &choice)) != RS_OK) return status;
    if (field) *(int *)field = choice;
    return RS_OK;
  case RS_KEY_HISTORY:
    return parse_history_xy(d, n, spec, (rs_history *)field, &in->c.tangential_force_y,
                            &in->force_n);
  case RS_KEY_FIELDS: return parse_fields(d, n, spec->path, (unsigned *)field);
  case RS_KEY_PROTOCOL: return rs_case_protocol(d, n, spec->path, (rs_twin_disc *)field);
  case RS_KEY_RANGE: return parse_range(d, n, spec, (double *)field);
  case RS_KEY_VECTOR: return parse_vector(d, n, spec, (rs_case_vec *)field);
  case RS_KEY_TTABLE: return parse_ttable(d, n, spec, (rs_history *)field);
  case RS_KEY_SECTION:
  case RS_KEY_OPAQUE: break;
  }
  return rs_msg_set(d->msg, RS_ERR_INTERNAL, "%s: not a value key", spec->path);
}

/* The names of the keys directly under `section` ("" for the top level). */
static void child_names(const char *section, const char **names, size_t max)
{
  size_t len = strlen(section), count = 0;
  for (size_t i = 0; i < rs_case_nkeys && count + 1 < max; i++) {
    const char *p = rs_case_keys[i].path;
    if (len == 0 && !strchr(p, '.'))
      names[count++] = p;
    else if (len && !strncmp(p, section, len) && p[len] == '.')
      names[count++] = p + len + 1;
  }
  names[count] = NULL;
}

/* Parse the keys of mapping `map` (the top level when section is ""). */
static int parse_mapping(rs_case_doc *d, const char *section, const yaml_node_t *map,
                         rs_case_input *in, const yaml_node_t **where)
{
  const char *names[64];
  child_names(section, names, 64);
  int status = rs_case_check_mapping(d, map, *section ? section : NULL, names);
  if (status != RS_OK) return status;
  size_t len = strlen(section);
  for (size_t i = 0; i < rs_case_nkeys; i++) {
    const rs_case_key *spec = &rs_case_keys[i];
    if (len ? strncmp(spec->path, section, len) || spec->path[len] != '.'
            : !!strchr(spec->path, '.'))
      continue;
    const yaml_node_t *n = rs_case_lookup(d, map, spec->path + (len ? len + 1 : 0));
    if (!n) continue;
    char got[96];
    switch (spec->kind) {
    case RS_KEY_SECTION:
      if (rs_case_is_null(n)) /* "plasticity:" with nothing under it: as if absent */
        continue;
      where[i] = n;
      if ((status = parse_mapping(d, spec->path, n, in, where)) != RS_OK) return status;
      break;
    case RS_KEY_OPAQUE:
      if (rs_case_is_null(n)) continue;
      if (n->type != YAML_MAPPING_NODE)
        return rs_case_error(d, n, spec->path, "expected a mapping of %s, got %s",
                             strcmp(spec->path, "profiles")
                                 ? "dotted keys to value lists"
                                 : "profile keys (rail: FILE, wheel: FILE, ...)",
                             rs_case_describe(n, got, sizeof got));
      where[i] = n;
      break;
    default:
      if ((spec->flags & RS_KEY_NULLABLE) && rs_case_is_null(n)) continue; /* null: the default */
      where[i] = n;
      if ((status = rs_case_parse_value(d, spec, n, in)) != RS_OK) return status;
    }
  }
  return RS_OK;
}

int rs_case_parse(rs_case_doc *d, rs_case_input *in, const yaml_node_t **where)
{
  return parse_mapping(d, "", rs_case_doc_root(d), in, where);
}
