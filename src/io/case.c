/* rs_case_load: read a case file (case_yaml.c), apply --set, fill the keys
 * (case_keys.c), then the rules that involve several keys and the derived values:
 *   k_tau = G*k_rel/(1 - k_rel),  tau_c_min = 0.1*tau_c0 by default,
 *   end_time = rolled_distance/V when the rolled distance is given. */
#define _POSIX_C_SOURCE 200809L
#include "io/case_internal.h"
#include "io/profile.h"
#include "physics/elastic2d.h" /* RS_PI */
#include "physics/normal.h"    /* rs_hertz2d */
#include "physics/normal3d.h"  /* rs_hertz3d */

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void set_defaults(rs_case_input *in)
{
  rs_case *c = &in->c;
  c->dimension = 2;
  c->normal_load.kind = RS_HISTORY_CONSTANT;
  c->normal_load.value = 178.9;
  in->radius = (rs_case_vec){1, {500.0, 0.0}};
  c->normal_solution = RS_NORMAL_DISCRETE;
  c->reference_length = 200.0;
  in->cells = (rs_case_vec){1, {100, 0}};
  in->extent = (rs_case_vec){1, {1.05, 0.0}};
  c->shear_modulus = 82000.0;
  c->poisson_ratio = 0.28;
  c->mu = 0.5;
  c->friction.memory_distance = 0.0;
  c->friction.memory_velocity = 1.0;
  c->layer_thickness = 0.0;
  c->layer_shear_modulus = 1.0;
  c->tau_c0 = 35.0;
  c->k_tau = 123000.0;
  c->tau_c_min = NAN; /* 0.1*tau_c0 unless given */
  c->velocity.kind = RS_HISTORY_CONSTANT;
  c->velocity.value = 30000.0;
  c->creepage.kind = RS_HISTORY_CONSTANT;
  c->creepage.value = -0.0004;
  c->shift_velocity.kind = RS_HISTORY_CONSTANT;
  c->shift_velocity.value = 0.0;
  c->lateral_creepage = c->spin = c->tangential_force_y =
      (rs_history){.kind = RS_HISTORY_CONSTANT, .value = 0.0};
  in->force_n = 1;
  c->mode = RS_MODE_TRANSIENT;
  c->end_time = 0.0004;
  c->rolled_distance = -1.0;
  c->output_interval = 1.0e-6;
  c->initial_state = RS_START_REST;
  c->rtol = 0.0; /* auto */
  c->atol = 1.0e-9;
  c->max_order = 5;
  c->threads = 1;
  c->scaling = RS_SCALING_AUTO;
  c->max_steps = 1000000;
  c->fields = RS_FIELD_PX | RS_FIELD_PN | RS_FIELD_SLIP | RS_FIELD_UPL | RS_FIELD_USTAR |
              RS_FIELD_TAUC | RS_FIELD_REGIME;
  in->k_rel = NAN;
  c->error_estimate = 1;
  c->rig.recovery = 1.0;
  c->rig.average_window = 0.5;
  /* temperature: steel unless given */
  in->t_conductivity = (rs_case_vec){1, {50e-3, 0.0}};
  in->t_heat_capacity = (rs_case_vec){1, {450.0, 0.0}};
  in->t_density = (rs_case_vec){1, {7.85e-6, 0.0}};
  in->t_disc_mass = (rs_case_vec){1, {0.0, 0.0}};
  c->temperature.plastic_heat_fraction = 1.0;
  c->temperature.kernel_tolerance = 1e-3;
}

typedef struct resolver {
  const rs_case_doc *d;
  const yaml_node_t **where;
  const int *sorted; /* the key table's indices by path (binary search) */
} resolver;

/* Index of a key in the table (all paths given here are keys). */
static int key_of(const resolver *r, const char *path)
{
  size_t lo = 0, hi = rs_case_nkeys;
  while (lo < hi) {
    const size_t mid = lo + (hi - lo) / 2;
    const int cmp = strcmp(rs_case_keys[r->sorted[mid]].path, path);
    if (cmp == 0) return r->sorted[mid];
    if (cmp < 0)
      lo = mid + 1;
    else
      hi = mid;
  }
  return -1;
}

/* The value node of a key (NULL when not given). */
static const yaml_node_t *given(const resolver *r, const char *path)
{
  const int i = key_of(r, path);
  return i < 0 ? NULL : r->where[i];
}

/* Range of a history's values over the simulated interval [0, end_time]; forces in the
 * dimension's unit. */
static int check_history(const resolver *r, const char *path, const rs_history *h, const rs_case *c)
{
  const double end_time = c->end_time;
  rs_case_key spec_dim = rs_case_keys[key_of(r, path)];
  const rs_case_key *spec = &spec_dim;
  spec_dim.unit = rs_case_key_unit_in(spec->unit, c->dimension);
  const yaml_node_t *n = given(r, path);
  double lo = rs_history_min(h, 0.0, end_time), big = rs_history_max_abs(h, 0.0, end_time);
  const char *sp = *spec->unit ? " " : "";
  const int open = spec->flags & RS_KEY_LO_OPEN;
  if (h->kind == RS_HISTORY_CONSTANT) return rs_case_check_range(r->d, n, spec, path, h->value);
  if (open ? !(lo > spec->lo) : lo < spec->lo)
    return rs_case_error(r->d, n, path,
                         "must be %s %g%s%s at all times in [0, %g] s, reaches %g%s%s",
                         open ? ">" : ">=", spec->lo, sp, spec->unit, end_time, lo, sp, spec->unit);
  if (big > spec->hi)
    return rs_case_error(r->d, n, path, "reaches %g%s%s in [0, %g] s: unreasonably large (a typo?)",
                         big, sp, spec->unit, end_time);
  return RS_OK;
}

static int resolve_plasticity(const resolver *r, rs_case *c, double k_rel)
{
  const yaml_node_t *block = given(r, "plasticity");
  const yaml_node_t *k_tau = given(r, "plasticity.k_tau"),
                    *k_rel_node = given(r, "plasticity.k_rel");
  c->has_plasticity = block != NULL;
  if (!c->has_plasticity) {
    c->tau_c_min = 0.1 * c->tau_c0;
    return RS_OK;
  }
  if (k_tau && k_rel_node)
    return rs_case_error(r->d, k_rel_node, "plasticity.k_rel",
                         "give plasticity.k_tau (N/mm^3) or plasticity.k_rel, not both");
  if (!k_tau && !k_rel_node)
    return rs_case_error(r->d, block, "plasticity",
                         "give the hardening: plasticity.k_tau (N/mm^3) or plasticity.k_rel "
                         "(k_tau = G*k_rel/(1 - k_rel), k_rel < 1)");
  if (k_rel_node)
    c->k_tau = c->shear_modulus * k_rel / (1.0 - k_rel);
  else if (!(c->k_tau > -c->shear_modulus))
    return rs_case_error(
        r->d, k_tau, "plasticity.k_tau",
        "softening must be milder than -G = %g N/mm^3 (that is, k_rel < 1), got %g",
        -c->shear_modulus, c->k_tau);
  const yaml_node_t *floor_node = given(r, "plasticity.tau_c_min");
  if (!floor_node)
    c->tau_c_min = 0.1 * c->tau_c0;
  else if (c->tau_c_min > c->tau_c0)
    return rs_case_error(r->d, floor_node, "plasticity.tau_c_min",
                         "must be <= plasticity.tau_c0 = %g N/mm^2, got %g", c->tau_c0,
                         c->tau_c_min);
  return RS_OK;
}

/* temperature: the block's presence turns it on; one number is both bodies' value. */
static int resolve_temperature(const resolver *r, rs_case_input *in)
{
  rs_thermal_params *t = &in->c.temperature;
  const yaml_node_t *block = given(r, "temperature");
  t->on = block != NULL;
  if (!t->on) return RS_OK;
  if (!given(r, "temperature.bulk"))
    return rs_case_error(r->d, block, "temperature",
                         "give temperature.bulk: [T1, T2] (degC), the bulk temperature of each "
                         "body (one number: both)");
  const rs_case_vec *v[4] = {&in->t_bulk, &in->t_conductivity, &in->t_heat_capacity,
                             &in->t_density};
  double *dst[4] = {t->bulk, t->conductivity, t->heat_capacity, t->density};
  for (int k = 0; k < 4; k++) {
    dst[k][0] = v[k]->v[0];
    dst[k][1] = v[k]->n == 2 ? v[k]->v[1] : v[k]->v[0];
  }
  t->disc_mass[0] = in->t_disc_mass.v[0];
  t->disc_mass[1] = in->t_disc_mass.n == 2 ? in->t_disc_mass.v[1] : in->t_disc_mass.v[0];
  /* the discs' cooling and bulk heating act between the contacts of a twin-disc rig */
  const char *rig_keys[2] = {"temperature.convection", "temperature.disc_mass"};
  const int rig_on[2] = {t->convection > 0.0, t->disc_mass[0] > 0.0 || t->disc_mass[1] > 0.0};
  for (int k = 0; k < 2; k++)
    if (rig_on[k] && (!in->c.rig.on || in->c.mode != RS_MODE_TRANSIENT))
      return rs_case_error(r->d, given(r, rig_keys[k]), rig_keys[k],
                           "acts between the contacts of a twin-disc rig: it needs a twin_disc: "
                           "block and simulation.mode: transient (give 0 or leave it out)");
  return RS_OK;
}

static int resolve_time(const resolver *r, rs_case *c)
{
  const yaml_node_t *end = given(r, "simulation.end_time");
  const yaml_node_t *dist = given(r, "simulation.rolled_distance");
  if (end && dist)
    return rs_case_error(
        r->d, dist, "simulation.rolled_distance",
        "give simulation.end_time (s) or simulation.rolled_distance (mm), not both "
        "(null means not given)");
  if (dist) {
    if (!rs_history_is_constant(&c->velocity) || !(rs_history_eval(&c->velocity, 0.0) > 0))
      return rs_case_error(r->d, dist, "simulation.rolled_distance",
                           "needs a constant rolling.velocity > 0 mm/s; give simulation.end_time "
                           "instead");
    c->end_time = c->rolled_distance / rs_history_eval(&c->velocity, 0.0);
    if (!(c->end_time > 0 && c->end_time <= 1e6))
      return rs_case_error(r->d, dist, "simulation.rolled_distance",
                           "gives end_time = %g s, outside (0, 1e6] s", c->end_time);
  }
  if (c->end_time / c->output_interval > 1e8)
    return rs_case_error(r->d, given(r, "simulation.output_interval"), "simulation.output_interval",
                         "%g s over end_time %g s would store %.3g records (at most 1e8)",
                         c->output_interval, c->end_time, c->end_time / c->output_interval);
  return RS_OK;
}

/* The twin_disc: block sets the contact and rolling inputs (docs/model.md §8): line load
 * q = F/b, R = (1/R1 + 1/R2)^-1, V = 2 pi rpm/60 R1 (or the mean surface speed of
 * the two discs), creepage = -slip of the protocol (a table with a jump at the start
 * of each held step), end time = revolutions x 2 pi R1/V. */
static int resolve_twin_disc(const resolver *r, rs_case *c)
{
  const yaml_node_t *block = given(r, "twin_disc");
  rs_twin_disc *rig = &c->rig;
  rig->on = block != NULL;
  if (!block) return RS_OK;
  static const char *const owned[] = {"contact.normal_load",      "contact.radius",
                                      "rolling.velocity",         "rolling.creepage",
                                      "rolling.tangential_force", "rolling.shift_velocity",
                                      "simulation.end_time",      "simulation.rolled_distance"};
  for (size_t i = 0; i < sizeof owned / sizeof *owned; i++)
    if (given(r, owned[i]))
      return rs_case_error(r->d, given(r, owned[i]), owned[i],
                           "is set by the twin_disc: block (disc radii, width, force, speed and "
                           "protocol): remove it");
  const int three = c->dimension == 3;
  if (three && given(r, "contact.curvature"))
    return rs_case_error(r->d, given(r, "contact.curvature"), "contact.curvature",
                         "is set by the twin_disc: block (disc and crown radii): remove it");
  static const char *const required[] = {"twin_disc.radius_1", "twin_disc.radius_2",
                                         "twin_disc.normal_force", "twin_disc.width"};
  for (size_t i = 0; i < sizeof required / sizeof *required - (size_t)three; i++)
    if (!given(r, required[i]))
      return rs_case_error(r->d, block, required[i],
                           three ? "missing (a crowned twin_disc: block needs radius_1, "
                                   "radius_2, normal_force and a crown radius)"
                                 : "missing (the twin_disc: block needs "
                                   "radius_1, radius_2, width, normal_force)");
  const yaml_node_t *crown1 = given(r, "twin_disc.crown_radius_1"),
                    *crown2 = given(r, "twin_disc.crown_radius_2");
  if (three && given(r, "twin_disc.width"))
    return rs_case_error(r->d, given(r, "twin_disc.width"), "twin_disc.width",
                         "crowned discs (contact.dimension: 3) touch in an ellipse set by the "
                         "crown radii and carry normal_force in N; the width is for flat discs "
                         "(2D line load): remove it");
  if (three && !crown1 && !crown2)
    return rs_case_error(r->d, block, "twin_disc.crown_radius_1",
                         "missing: a 3D rig needs crowned discs (crown_radius_1 and/or "
                         "crown_radius_2, mm; a disc without one is flat across); flat discs "
                         "make a line contact: contact.dimension: 2");
  if (c->mode != RS_MODE_TRANSIENT)
    return rs_case_error(r->d, given(r, "simulation.mode"), "simulation.mode",
                         "a twin_disc: run is transient (many revolutions); remove mode: steady");
  const yaml_node_t *rpm = given(r, "twin_disc.rpm"), *rpm1 = given(r, "twin_disc.rpm_1"),
                    *rpm2 = given(r, "twin_disc.rpm_2"), *proto = given(r, "twin_disc.protocol"),
                    *revs = given(r, "twin_disc.revolutions");
  const double two_pi = 2.0 * RS_PI;
  double V;
  if (rpm) {
    if (rpm1 || rpm2)
      return rs_case_error(r->d, rpm1 ? rpm1 : rpm2, rpm1 ? "twin_disc.rpm_1" : "twin_disc.rpm_2",
                           "give twin_disc.rpm with a protocol, or the disc speeds rpm_1 and "
                           "rpm_2 with revolutions, not both");
    if (!proto)
      return rs_case_error(r->d, block, "twin_disc.protocol",
                           "missing: with twin_disc.rpm give the slip protocol, a list of "
                           "{slip: S, revolutions: N} or {ramp_to: S, revolutions: N}");
    if (revs)
      return rs_case_error(r->d, revs, "twin_disc.revolutions",
                           "the protocol's steps give the revolutions; remove it");
    V = two_pi * rig->rpm / 60.0 * rig->radius_1;
  } else {
    if (!rpm1 || !rpm2)
      return rs_case_error(r->d, block, rpm1 ? "twin_disc.rpm_2" : "twin_disc.rpm_1",
                           "missing: give twin_disc.rpm (rolling speed) and a protocol, or both "
                           "disc speeds rpm_1 and rpm_2 and the revolutions");
    if (proto)
      return rs_case_error(r->d, proto, "twin_disc.protocol",
                           "with the disc speeds rpm_1 and rpm_2 the slip is fixed: give "
                           "twin_disc.rpm instead of rpm_1/rpm_2 to run a protocol");
    if (!revs)
      return rs_case_error(r->d, block, "twin_disc.revolutions",
                           "missing: how many revolutions of disc 1 to run");
    const double v1 = two_pi * rig->rpm_1 / 60.0 * rig->radius_1,
                 v2 = two_pi * rig->rpm_2 / 60.0 * rig->radius_2;
    V = 0.5 * (v1 + v2);
    free(rig->steps);
    if (!(rig->steps = calloc(1, sizeof *rig->steps)))
      return rs_msg_set(r->d->msg, RS_ERR_INTERNAL, "out of memory");
    rig->nsteps = 1;
    rig->steps[0] = (rs_rig_step){(v1 - v2) / V, (v1 - v2) / V, rig->revolutions};
    if (!(fabs(rig->steps[0].slip_end) < 1.0))
      return rs_case_error(r->d, rpm2, "twin_disc.rpm_2",
                           "gives slip %g: not a fraction in (-1, 1)", rig->steps[0].slip_end);
  }
  rig->revolution_time = two_pi * rig->radius_1 / V;
  rs_history_free(&c->normal_load);
  c->normal_load =
      (rs_history){.kind = RS_HISTORY_CONSTANT,
                   .value = three ? rig->normal_force : rig->normal_force / rig->width};
  c->radius = 1.0 / (1.0 / rig->radius_1 + 1.0 / rig->radius_2);
  if (three) /* transverse curvatures add; a flat disc has none */
    c->radius_y = 1.0 / ((crown1 ? 1.0 / rig->crown_radius_1 : 0.0) +
                         (crown2 ? 1.0 / rig->crown_radius_2 : 0.0));
  rs_history_free(&c->velocity);
  c->velocity = (rs_history){.kind = RS_HISTORY_CONSTANT, .value = V};
  /* creepage table: two points per step (a jump where a held step starts elsewhere) */
  rs_history *h = &c->creepage;
  rs_history_free(h);
  h->kind = RS_HISTORY_TABLE;
  h->t = malloc(2 * rig->nsteps * sizeof *h->t);
  h->v = malloc(2 * rig->nsteps * sizeof *h->v);
  if (!h->t || !h->v) return rs_msg_set(r->d->msg, RS_ERR_INTERNAL, "out of memory");
  double t = 0.0, revolutions = 0.0;
  h->n = 0;
  for (size_t i = 0; i < rig->nsteps; i++) {
    const rs_rig_step *st = &rig->steps[i];
    if (h->n == 0 || h->v[h->n - 1] != -st->slip_start) {
      h->t[h->n] = t;
      h->v[h->n++] = -st->slip_start;
    }
    revolutions += st->revolutions;
    t = revolutions * rig->revolution_time;
    h->t[h->n] = t;
    h->v[h->n++] = -st->slip_end;
  }
  c->end_time = t;
  if (!given(r, "simulation.output_interval")) /* the record count is checked in resolve_time */
    c->output_interval = rig->revolution_time / 20.0;
  return RS_OK;
}

/* Prescribed tangential force instead of creepage (docs/model.md §6): exactly one of the
 * two; below full sliding; from rest it must start at zero (no traction at rest). */
static int resolve_force(const resolver *r, rs_case *c)
{
  const yaml_node_t *force = given(r, "rolling.tangential_force");
  c->force_control = force != NULL;
  if (!force) return RS_OK;
  if (given(r, "rolling.creepage"))
    return rs_case_error(r->d, force, "rolling.tangential_force",
                         "give rolling.creepage or rolling.tangential_force, not both (with a "
                         "prescribed force the creepage is computed)");
  int status = check_history(r, "rolling.tangential_force", &c->tangential_force, c);
  if (status == RS_OK && c->dimension == 3)
    status = check_history(r, "rolling.tangential_force", &c->tangential_force_y, c);
  if (status != RS_OK) return status;
  const char *unit = c->dimension == 3 ? "N" : "N/mm";
  double fmax = rs_history_max_abs(&c->tangential_force, 0.0, c->end_time), f0 = 0.0;
  if (c->dimension == 3) { /* |F| = |(F_x, F_y)|, sampled over the run */
    fmax = 0.0;
    for (int k = 0; k <= 2000; k++) {
      const double t = c->end_time * k / 2000.0;
      fmax = fmax > hypot(rs_history_eval(&c->tangential_force, t),
                          rs_history_eval(&c->tangential_force_y, t))
                 ? fmax
                 : hypot(rs_history_eval(&c->tangential_force, t),
                         rs_history_eval(&c->tangential_force_y, t));
    }
    f0 = hypot(rs_history_eval(&c->tangential_force, 0.0),
               rs_history_eval(&c->tangential_force_y, 0.0));
  } else {
    f0 = fabs(rs_history_eval(&c->tangential_force, 0.0));
  }
  const double limit = c->mu * rs_history_min(&c->normal_load, 0.0, c->end_time);
  if (!(fmax < limit))
    return rs_case_error(r->d, force, "rolling.tangential_force",
                         "reaches %g %s, not below the friction limit mu F_n = %g %s (full "
                         "sliding: no creepage gives that force)",
                         fmax, unit, limit, unit);
  if (c->mode == RS_MODE_TRANSIENT && c->initial_state == RS_START_REST && f0 != 0.0)
    return rs_case_error(r->d, force, "rolling.tangential_force",
                         "is %g %s at t = 0, but the run starts at rest without traction: "
                         "let it start at 0 (e.g. a ramp) or use simulation.initial_state: steady",
                         f0, unit);
  return RS_OK;
}

/* The grid: grid.extent (Hertz half-widths) or grid.x_range (mm, explicit edges), not
 * both; explicit edges must hold the Hertz contact [-a, a] of the largest load. */
static int resolve_grid(const resolver *r, rs_case *c)
{
  const yaml_node_t *range = given(r, "grid.x_range"), *extent = given(r, "grid.extent");
  const yaml_node_t *yrange = given(r, "grid.y_range");
  c->grid_from_range = range != NULL;
  const yaml_node_t *align = given(r, "grid.align_edges");
  if (align && c->align_edges) {
    if (c->dimension == 3)
      return rs_case_error(r->d, align, "grid.align_edges",
                           "is for 2D contact: in 3D the ellipse's edge crosses the cells at "
                           "every angle");
    if (range)
      return rs_case_error(r->d, align, "grid.align_edges",
                           "sets the grid's extent itself: give grid.extent, not grid.x_range");
    if (c->cells % 4 != 0)
      return rs_case_error(r->d, align, "grid.align_edges",
                           "needs grid.cells divisible by 4 (the error estimate's grids of 1/2 "
                           "and 1/4 the cells must be aligned too), not %d",
                           c->cells);
    /* a/dx = cells/(2 extent), made the nearest multiple of 4 that keeps the extent above 1
     * (the Hertz contact inside the grid) */
    long k = 4L * lround(c->cells / (8.0 * c->extent));
    if (2 * k >= c->cells) k -= 4;
    if (k < 4)
      return rs_case_error(r->d, align, "grid.align_edges",
                           "%d cells over +-%g a are too few to put the contact edges on cell "
                           "faces (at least 4 cells per Hertz half-width a)",
                           c->cells, c->extent);
    c->extent = c->cells / (2.0 * (double)k);
  }
  if (yrange && !range)
    return rs_case_error(r->d, yrange, "grid.y_range",
                         "give grid.x_range and grid.y_range together (mm), or grid.extent");
  if (!range) return RS_OK;
  if (extent)
    return rs_case_error(r->d, range, "grid.x_range",
                         "give grid.extent (Hertz half-widths) or grid.x_range (mm), not both");
  if (c->dimension == 3) {
    if (!yrange)
      return rs_case_error(r->d, range, "grid.y_range",
                           "missing: a 3D grid given in mm needs grid.x_range and grid.y_range");
    rs_hertz_ellipse hz;
    rs_msg tmp;
    if (rs_hertz3d(rs_history_max_abs(&c->normal_load, 0.0, c->end_time), 0.5 / c->radius,
                   0.5 / c->radius_y, c->shear_modulus, c->poisson_ratio, &hz, &tmp) != RS_OK)
      return rs_case_error(r->d, range, "grid.x_range", "%s", tmp.text);
    if (c->x_range[0] > -hz.a || c->x_range[1] < hz.a)
      return rs_case_error(r->d, range, "grid.x_range",
                           "[%g, %g] mm does not hold the Hertz ellipse along x, [%g, %g] mm (a = "
                           "%g mm at the largest load): the contact would be cut off",
                           c->x_range[0], c->x_range[1], -hz.a, hz.a, hz.a);
    if (c->y_range[0] > -hz.b || c->y_range[1] < hz.b)
      return rs_case_error(r->d, yrange, "grid.y_range",
                           "[%g, %g] mm does not hold the Hertz ellipse along y, [%g, %g] mm (b = "
                           "%g mm at the largest load): the contact would be cut off",
                           c->y_range[0], c->y_range[1], -hz.b, hz.b, hz.b);
    return RS_OK;
  }
  double a, p0;
  rs_hertz2d(rs_history_max_abs(&c->normal_load, 0.0, c->end_time), c->radius, c->shear_modulus,
             c->poisson_ratio, &a, &p0);
  if (c->x_range[0] > -a || c->x_range[1] < a)
    return rs_case_error(r->d, range, "grid.x_range",
                         "[%g, %g] mm does not hold the Hertz contact [%g, %g] mm (a = %g mm at "
                         "the largest load): the contact would be cut off",
                         c->x_range[0], c->x_range[1], -a, a, a);
  return RS_OK;
}

/* grid.accuracy (docs/case-file.md): the grid refined until the error estimate of a steady
 * single run's forces is below it, so it needs the estimate and a steady run of one point. */
static int resolve_accuracy(const resolver *r, rs_case *c)
{
  const yaml_node_t *acc = given(r, "grid.accuracy");
  if (!acc || !(c->accuracy > 0.0)) return RS_OK;
  if (c->mode != RS_MODE_STEADY)
    return rs_case_error(r->d, acc, "grid.accuracy",
                         "applies to steady runs (simulation.mode: steady): a transient run "
                         "keeps its grid");
  if (!c->error_estimate)
    return rs_case_error(r->d, acc, "grid.accuracy",
                         "needs the error estimate: remove output.error_estimate: false");
  if (c->force_control)
    return rs_case_error(r->d, acc, "grid.accuracy",
                         "not with a prescribed rolling.tangential_force (the error estimate "
                         "is of the forces at prescribed creepages)");
  if (given(r, "sweep") || given(r, "fit"))
    return rs_case_error(r->d, acc, "grid.accuracy",
                         "applies to single runs (rollsim run), not to a case with a %s: block; "
                         "sweep points get their error estimates on the case's grid",
                         given(r, "sweep") ? "sweep" : "fit");
  return RS_OK;
}

/* A key that is one number in 2D and a pair [x, y] in 3D (contact.radius, grid.cells,
 * grid.extent), given with the count the dimension needs. */
static int check_count(const resolver *r, const char *key, const rs_case_vec *v, int want)
{
  const yaml_node_t *n = given(r, key);
  if (!n || v->n == want) return RS_OK;
  return rs_case_error(r->d, n, key,
                       want == 2 ? "a 3D contact (contact.dimension: 3) takes a list of two [x, y]"
                                 : "a 2D contact takes one number; lists [x, y] are for "
                                   "contact.dimension: 3");
}

/* The keys whose form depends on contact.dimension (docs/case-file.md): radius or
 * curvature, cells, extent, ranges, the lateral creepage and spin, the force pair. */
static int resolve_dimension(const resolver *r, rs_case_input *in)
{
  rs_case *c = &in->c;
  const int three = c->dimension == 3, want = three ? 2 : 1;
  int status;
  if ((status = check_count(r, "contact.radius", &in->radius, want)) != RS_OK ||
      (status = check_count(r, "grid.cells", &in->cells, want)) != RS_OK ||
      (status = check_count(r, "grid.extent", &in->extent, want)) != RS_OK)
    return status;
  if (!three) {
    static const char *const only3d[] = {"contact.curvature",        "grid.y_range",
                                         "rolling.lateral_creepage", "rolling.spin",
                                         "twin_disc.crown_radius_1", "twin_disc.crown_radius_2"};
    for (size_t k = 0; k < sizeof only3d / sizeof *only3d; k++)
      if (given(r, only3d[k]))
        return rs_case_error(r->d, given(r, only3d[k]), only3d[k],
                             "is for 3D contact (contact.dimension: 3)");
    if (in->force_n == 2)
      return rs_case_error(r->d, given(r, "rolling.tangential_force"), "rolling.tangential_force",
                           "a 2D contact takes one force (N/mm); [Fx, Fy] is for "
                           "contact.dimension: 3");
    c->radius = in->radius.v[0];
    c->cells = (int)in->cells.v[0];
    c->extent = in->extent.v[0];
    return RS_OK;
  }
  const yaml_node_t *rad = given(r, "contact.radius"), *cur = given(r, "contact.curvature");
  if (rad && cur)
    return rs_case_error(r->d, cur, "contact.curvature",
                         "give contact.radius [Rx, Ry] (mm) or contact.curvature [A, B] (1/mm), "
                         "not both");
  if (cur && in->curvature.n != 2)
    return rs_case_error(r->d, cur, "contact.curvature", "expected a list of two [A, B] (1/mm)");
  if (!rad && !cur && !given(r, "twin_disc"))
    return rs_case_error(r->d, given(r, "contact.dimension"), "contact.radius",
                         "missing: a 3D contact needs contact.radius [Rx, Ry] (mm) or "
                         "contact.curvature [A, B] (1/mm), gap h = x^2/(2Rx) + y^2/(2Ry)");
  c->radius = cur ? 0.5 / in->curvature.v[0] : in->radius.v[0];
  c->radius_y = cur ? 0.5 / in->curvature.v[1] : in->radius.v[1];
  /* defaults of a 3D grid: 40 x 40 cells over +-1.1 a, +-1.1 b */
  c->cells = given(r, "grid.cells") ? (int)in->cells.v[0] : 40;
  c->cells_y = given(r, "grid.cells") ? (int)in->cells.v[1] : 40;
  c->extent = given(r, "grid.extent") ? in->extent.v[0] : 1.1;
  c->extent_y = given(r, "grid.extent") ? in->extent.v[1] : 1.1;
  if (c->force_control || given(r, "rolling.tangential_force")) {
    if (in->force_n != 2)
      return rs_case_error(r->d, given(r, "rolling.tangential_force"), "rolling.tangential_force",
                           "a 3D contact takes both components [Fx, Fy] (N)");
    if (given(r, "rolling.lateral_creepage"))
      return rs_case_error(r->d, given(r, "rolling.lateral_creepage"), "rolling.lateral_creepage",
                           "give rolling.lateral_creepage or rolling.tangential_force, not both "
                           "(with prescribed forces both creepages are computed)");
  }
  return RS_OK;
}

/* results/<case file name without .yaml>.nc */
static char *default_output_file(const char *path)
{
  const char *base = strrchr(path, '/');
  base = base ? base + 1 : path;
  size_t len = strlen(base);
  if (len > 5 && !strcmp(base + len - 5, ".yaml"))
    len -= 5;
  else if (len > 4 && !strcmp(base + len - 4, ".yml"))
    len -= 4;
  char *file = malloc(len + sizeof "results/.nc");
  if (file) snprintf(file, len + sizeof "results/.nc", "results/%.*s.nc", (int)len, base);
  return file;
}

/* The friction law (docs/case-file.md): each law's own keys, none of another
 * law's; lists of one or two terms of equal length; a positive coefficient at rest. Stored
 * in c->friction; c->mu becomes mu(0) for the velocity-dependent laws (the coefficient at
 * rest: warnings, the summary's F_x/(mu F_n)). */
static int resolve_friction(const resolver *r, rs_case_input *in)
{
  rs_case *c = &in->c;
  rs_friction *f = &c->friction;
  static const char *const keys[] = {
      "friction.mu",        "friction.mu_kinetic", "friction.mu_excess", "friction.half_velocity",
      "friction.mu_static", "friction.A",          "friction.B"};
  /* owner[k]: bit per law (coulomb 1, linear 2, exponential 4, rational 8, polach 16) */
  static const unsigned owner[] = {1, 14, 14, 14, 16, 16, 16};
  const char *law = rs_friction_name(f->kind);
  const yaml_node_t *law_node = given(r, "friction.law");
  for (int k = 0; k < 7; k++) {
    const yaml_node_t *n = given(r, keys[k]);
    if (n && !(owner[k] & (1u << f->kind)))
      return rs_case_error(r->d, n, keys[k],
                           "belongs to %s, not to friction.law: %s (remove it, or set it to null "
                           "when switching the law with --set)",
                           owner[k] == 1    ? "the Coulomb law"
                           : owner[k] == 16 ? "the Polach law"
                                            : "the linear, exponential and rational laws",
                           law);
    if (!n && (owner[k] & (1u << f->kind)) && f->kind != RS_FRICTION_COULOMB)
      return rs_case_error(r->d, law_node, keys[k], "is required by friction.law: %s", law);
  }
  /* friction memory: a state of the velocity-dependent laws only */
  static const char *const memory_keys[] = {"friction.memory_distance", "friction.memory_velocity"};
  for (int k = 0; k < 2 && f->kind == RS_FRICTION_COULOMB; k++)
    if (given(r, memory_keys[k]))
      return rs_case_error(r->d, given(r, memory_keys[k]), memory_keys[k],
                           "is friction memory of a velocity-dependent law; with friction.law: "
                           "coulomb mu is constant and has no memory (remove it, or choose "
                           "friction.law: linear, exponential, rational or polach)");
  if (f->kind == RS_FRICTION_COULOMB) return RS_OK;
  if (f->kind != RS_FRICTION_POLACH) {
    if (in->mu_excess.n != in->half_velocity.n)
      return rs_case_error(r->d, given(r, "friction.half_velocity"), "friction.half_velocity",
                           "has %d value%s but friction.mu_excess has %d: one half velocity per "
                           "term",
                           in->half_velocity.n, in->half_velocity.n == 1 ? "" : "s",
                           in->mu_excess.n);
    f->terms = in->mu_excess.n;
    for (int i = 0; i < f->terms; i++) {
      f->mu_excess[i] = in->mu_excess.v[i];
      f->half_velocity[i] = in->half_velocity.v[i];
    }
  }
  const double mu0 = rs_friction_mu(f, 0.0);
  if (!(mu0 > 0.0))
    return rs_case_error(r->d, law_node, "friction.law",
                         "%s gives mu = %g at rest: the coefficient of friction must be > 0", law,
                         mu0);
  /* 2D and 3D alike (3D: the disk law with g = mu p_n, mu the memory state) */
  if (c->mode == RS_MODE_TRANSIENT && !rs_friction_has_memory(f))
    return rs_case_error(
        r->d, law_node, "friction.law",
        "%s needs simulation.mode: steady. A falling friction law without friction memory makes "
        "the transient ill-posed (the rate of a slipping traction grows without bound: the time "
        "step collapses); friction memory makes it well-posed: set friction.memory_distance > 0 "
        "mm",
        law);
  if (given(r, "rolling.tangential_force"))
    return rs_case_error(r->d, given(r, "rolling.tangential_force"), "rolling.tangential_force",
                         "is not available with friction.law: %s (prescribe rolling.creepage)",
                         law);
  if (c->rig.on && rs_friction_has_memory(f))
    return rs_case_error(r->d, given(r, "friction.memory_distance"), "friction.memory_distance",
                         "is not available in a twin_disc: run: the memory state is not carried "
                         "around the discs (material would re-enter the contact fresh at every "
                         "revolution)");
  c->mu = mu0;
  return RS_OK;
}

/* friction.temperature_table and plasticity.tau_c0_table (docs/model.md §18): with a
 * temperature. */
static int resolve_temperature_table(const resolver *r, const rs_case *c, const char *key)
{
  const yaml_node_t *n = given(r, key);
  if (!n) return RS_OK;
  if (!c->temperature.on)
    return rs_case_error(r->d, n, key,
                         "needs a temperature: block (the contact temperature it is read at)");
  return RS_OK;
}

static int resolve_temperature_tables(const resolver *r, const rs_case *c)
{
  int status = resolve_temperature_table(r, c, "friction.temperature_table");
  if (status == RS_OK && c->mu_table.n && rs_friction_has_memory(&c->friction))
    return rs_case_error(r->d, given(r, "friction.temperature_table"), "friction.temperature_table",
                         "is not available with friction memory (friction.memory_distance > 0)");
  if (status == RS_OK) status = resolve_temperature_table(r, c, "plasticity.tau_c0_table");
  if (status == RS_OK && c->tau_c0_table.n && !c->has_plasticity)
    return rs_case_error(r->d, given(r, "plasticity.tau_c0_table"), "plasticity.tau_c0_table",
                         "needs plasticity (a plasticity: block with its hardening)");
  return status;
}

static int resolve(const rs_case_doc *d, rs_case_input *in, const yaml_node_t **where,
                   const int *sorted)
{
  resolver r = {d, where, sorted};
  rs_case *c = &in->c;
  int status;
  if ((status = resolve_dimension(&r, in)) != RS_OK) return status;
  if ((status = resolve_plasticity(&r, c, in->k_rel)) != RS_OK ||
      (status = resolve_twin_disc(&r, c)) != RS_OK || (status = resolve_time(&r, c)) != RS_OK ||
      (status = resolve_temperature(&r, in)) != RS_OK)
    return status;
  const rs_history *hs[] = {&c->normal_load,    &c->velocity,         &c->creepage,
                            &c->shift_velocity, &c->lateral_creepage, &c->spin};
  const char *names[] = {"contact.normal_load",    "rolling.velocity",         "rolling.creepage",
                         "rolling.shift_velocity", "rolling.lateral_creepage", "rolling.spin"};
  for (int i = 0; i < 6; i++)
    if ((status = check_history(&r, names[i], hs[i], c)) != RS_OK) return status;
  if ((status = resolve_friction(&r, in)) != RS_OK ||
      (status = resolve_temperature_tables(&r, c)) != RS_OK ||
      (status = resolve_force(&r, c)) != RS_OK || (status = resolve_grid(&r, c)) != RS_OK)
    return status;
  if (c->mode == RS_MODE_STEADY && !(rs_history_min(&c->velocity, 0.0, c->end_time) > 0))
    return rs_case_error(d, given(&r, "rolling.velocity"), "rolling.velocity",
                         "velocity 0 mm/s (pure shift) needs simulation.mode: transient; steady "
                         "mode is for rolling (V > 0)");
  /* transient runs estimate their errors only when asked (companion runs: docs/case-file.md) */
  if (c->mode == RS_MODE_TRANSIENT && !given(&r, "output.error_estimate")) c->error_estimate = 0;
  /* the companion grids of the error estimate solve the case without the temperature coupling */
  const char *table = c->mu_table.n       ? "friction.temperature_table"
                      : c->tau_c0_table.n ? "plasticity.tau_c0_table"
                                          : NULL;
  if (table && given(&r, "grid.accuracy"))
    return rs_case_error(d, given(&r, "grid.accuracy"), "grid.accuracy",
                         "is not available with %s (the error estimate does not include the "
                         "temperature coupling)",
                         table);
  if (table && c->error_estimate && given(&r, "output.error_estimate"))
    return rs_case_error(d, given(&r, "output.error_estimate"), "output.error_estimate",
                         "is not available with %s (the estimate does not include the "
                         "temperature coupling): leave it out or give false",
                         table);
  if (table) c->error_estimate = 0;
  if ((status = resolve_accuracy(&r, c)) != RS_OK) return status;
  if (c->output_file && !*c->output_file)
    return rs_case_error(d, given(&r, "output.file"), "output.file", "empty file name");
  if (!c->output_file && !(c->output_file = default_output_file(d->path)))
    return rs_msg_set(d->msg, RS_ERR_INTERNAL, "out of memory");
  if (!c->title && !(c->title = strdup("")))
    return rs_msg_set(d->msg, RS_ERR_INTERNAL, "out of memory");
  c->has_sweep = given(&r, "sweep") != NULL;
  c->has_profiles = given(&r, "profiles") != NULL;
  return RS_OK;
}

/* "KEY=VALUE, KEY=VALUE" of the --set assignments, then the typed overrides (their keys
 * and values as text). */
static char *join_sets(char *const *sets, int nsets, const rs_case_override *ov,
                       const char (*values)[32], int nov)
{
  size_t len = 1;
  for (int i = 0; i < nsets; i++) len += strlen(sets[i]) + 2;
  for (int i = 0; i < nov; i++) len += strlen(rs_case_keys[ov[i].key].path) + strlen(values[i]) + 3;
  char *text = malloc(len);
  if (!text) return NULL;
  size_t used = 0;
  text[0] = '\0';
  for (int i = 0; i < nsets; i++)
    used += (size_t)snprintf(text + used, len - used, "%s%s", i ? ", " : "", sets[i]);
  for (int i = 0; i < nov; i++)
    used += (size_t)snprintf(text + used, len - used, "%s%s=%s", used ? ", " : "",
                             rs_case_keys[ov[i].key].path, values[i]);
  return text;
}

/* Deep copy of the parsed keys (before the cross-key rules, which change them). */
static int input_copy(rs_case_input *dst, const rs_case_input *src)
{
  *dst = *src;
  rs_case *c = &dst->c;
  const rs_case *s = &src->c;
  c->title = c->output_file = NULL;
  c->normal_load = c->velocity = c->creepage = c->tangential_force = c->tangential_force_y =
      c->lateral_creepage = c->spin = c->shift_velocity = c->mu_table = c->tau_c0_table =
          (rs_history){0};
  c->rig.steps = NULL;
  int ok = (!s->title || (c->title = strdup(s->title))) &&
           (!s->output_file || (c->output_file = strdup(s->output_file)));
  ok = ok && rs_history_copy(&c->normal_load, &s->normal_load) == RS_OK &&
       rs_history_copy(&c->velocity, &s->velocity) == RS_OK &&
       rs_history_copy(&c->creepage, &s->creepage) == RS_OK &&
       rs_history_copy(&c->tangential_force, &s->tangential_force) == RS_OK &&
       rs_history_copy(&c->tangential_force_y, &s->tangential_force_y) == RS_OK &&
       rs_history_copy(&c->lateral_creepage, &s->lateral_creepage) == RS_OK &&
       rs_history_copy(&c->spin, &s->spin) == RS_OK &&
       rs_history_copy(&c->shift_velocity, &s->shift_velocity) == RS_OK &&
       rs_history_copy(&c->mu_table, &s->mu_table) == RS_OK &&
       rs_history_copy(&c->tau_c0_table, &s->tau_c0_table) == RS_OK;
  if (ok && s->rig.nsteps > 0) {
    c->rig.steps = malloc(s->rig.nsteps * sizeof *c->rig.steps);
    ok = c->rig.steps != NULL;
    if (ok) memcpy(c->rig.steps, s->rig.steps, s->rig.nsteps * sizeof *c->rig.steps);
  }
  if (!ok) rs_case_free(c);
  return ok ? RS_OK : RS_ERR_INTERNAL;
}

static void source_free(struct rs_case_source *src)
{
  if (!src) return;
  rs_case_doc_free(&src->doc);
  rs_case_free(&src->in.c);
  free(src->where);
  free(src->sorted);
  for (int i = 0; i < src->nsets; i++) free(src->sets[i]);
  free(src->sets);
  free(src->text);
  free(src->path);
  free(src);
}

/* The case file read and parsed, the --set assignments applied to the document. */
static int source_load(struct rs_case_source **out, const char *path, const char *const *sets,
                       int nsets, rs_msg *msg)
{
  *out = NULL;
  struct rs_case_source *src = calloc(1, sizeof *src);
  if (!src) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  src->where = calloc(rs_case_nkeys, sizeof *src->where);
  src->sorted = malloc(rs_case_nkeys * sizeof *src->sorted);
  src->path = strdup(path);
  src->sets = calloc((size_t)(nsets > 0 ? nsets : 1), sizeof *src->sets);
  int status = src->where && src->sorted && src->path && src->sets
                   ? RS_OK
                   : rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  for (size_t i = 0; status == RS_OK && i < rs_case_nkeys; i++) { /* insertion sort by path */
    size_t k = i;
    while (k > 0 && strcmp(rs_case_keys[src->sorted[k - 1]].path, rs_case_keys[i].path) > 0) {
      src->sorted[k] = src->sorted[k - 1];
      k--;
    }
    src->sorted[k] = (int)i;
  }
  for (int i = 0; status == RS_OK && i < nsets; i++, src->nsets++)
    if (!(src->sets[i] = strdup(sets[i])))
      status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  set_defaults(&src->in);
  if (status == RS_OK) status = rs_case_doc_read(src->path, &src->text, &src->len, msg);
  if (status == RS_OK) status = rs_case_doc_parse(&src->doc, src->path, src->text, src->len, msg);
  for (int i = 0; status == RS_OK && i < nsets; i++) status = rs_case_doc_set(&src->doc, sets[i]);
  if (status == RS_OK) status = rs_case_parse(&src->doc, &src->in, src->where);
  src->doc.msg = NULL;
  if (status != RS_OK) {
    source_free(src);
    return status;
  }
  *out = src;
  return RS_OK;
}

rs_case_doc rs_case_source_doc(const rs_case *c, rs_msg *msg)
{
  rs_case_doc d = c->source->doc;
  d.msg = msg;
  return d;
}

int rs_case_refuse_profiles(const rs_case *c, rs_msg *msg)
{
  if (!c->has_profiles) return RS_OK;
  if (!c->source)
    return rs_msg_set(msg, RS_ERR_INPUT, "profiles: fits on wheel-rail profiles are not built yet");
  rs_case_doc d = rs_case_source_doc(c, msg);
  yaml_node_t *root = rs_case_doc_root(&d);
  return rs_case_error(&d, root ? rs_case_lookup(&d, root, "profiles") : NULL, "profiles",
                       "fits on wheel-rail profiles are not built yet: `rollsim run` runs every "
                       "contact patch at the block's wheelset position, `rollsim sweep` solves "
                       "them along a path of positions");
}

/* The case of `src` with typed overrides: each value as a plain scalar node outside the
 * document (its text reads back to the same double), parsed as the key's value from the
 * file would be, its node (and that of a section it creates) named "--set KEY" in
 * messages; then the cross-key rules. */
static int source_case(const struct rs_case_source *src, const rs_case_override *ov, int nov,
                       rs_case *c, rs_msg *msg)
{
  memset(c, 0, sizeof *c);
  rs_case_input in;
  const yaml_node_t **where = malloc(rs_case_nkeys * sizeof *where);
  yaml_node_t *nodes = nov > 0 ? calloc(2 * (size_t)nov, sizeof *nodes) : NULL;
  rs_case_override_origin *origins = nov > 0 ? calloc(2 * (size_t)nov, sizeof *origins) : NULL;
  char(*texts)[32] = nov > 0 ? calloc((size_t)nov, sizeof *texts) : NULL;
  int status = RS_OK;
  if (!where || (nov > 0 && (!nodes || !origins || !texts)) || input_copy(&in, &src->in) != RS_OK) {
    free(where);
    free(nodes);
    free(origins);
    free(texts);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  }
  memcpy(where, src->where, rs_case_nkeys * sizeof *where);
  rs_case_doc d = src->doc;
  d.msg = msg;
  d.overrides = origins;
  d.noverrides = 0;
  for (int i = 0; status == RS_OK && i < nov; i++) {
    const int k = ov[i].key;
    if (!rs_case_key_numeric(k)) {
      status = rs_msg_set(msg, RS_ERR_INTERNAL, "%s: not a numeric case key", rs_case_key_name(k));
      break;
    }
    const rs_case_key *spec = &rs_case_keys[k];
    yaml_node_t *n = &nodes[2 * i];
    rs_case_fmt(ov[i].value, texts[i], sizeof texts[i]);
    n->type = YAML_SCALAR_NODE;
    n->data.scalar.value = (yaml_char_t *)texts[i];
    n->data.scalar.length = strlen(texts[i]);
    n->data.scalar.style = YAML_PLAIN_SCALAR_STYLE;
    origins[d.noverrides++] = (rs_case_override_origin){n, spec->path};
    /* a key under a section that is not given creates it, as --set does */
    int section = k;
    while (section > 0 && rs_case_keys[section].kind != RS_KEY_SECTION) section--;
    if (strchr(spec->path, '.') && rs_case_keys[section].kind == RS_KEY_SECTION &&
        !where[section]) {
      yaml_node_t *m = &nodes[2 * i + 1];
      m->type = YAML_MAPPING_NODE;
      origins[d.noverrides++] = (rs_case_override_origin){m, spec->path};
      where[section] = m;
    }
    where[k] = n;
    status = rs_case_parse_value(&d, spec, n, &in);
  }
  if (status == RS_OK) status = resolve(&d, &in, where, src->sorted);
  if (status == RS_OK && !(in.c.source_path = strdup(src->path)))
    status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  if (status == RS_OK && src->nsets + nov > 0 &&
      !(in.c.overrides = join_sets(src->sets, src->nsets, ov, (const char(*)[32])texts, nov)))
    status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  free(where);
  free(nodes);
  free(origins);
  free(texts);
  if (status != RS_OK) {
    rs_case_free(&in.c);
    return status;
  }
  *c = in.c;
  return RS_OK;
}

int rs_case_load(rs_case *c, const char *path, const char *const *sets, int nsets, rs_msg *msg)
{
  memset(c, 0, sizeof *c);
  if (!path) return rs_msg_set(msg, RS_ERR_INPUT, "no case file given");
  struct rs_case_source *src;
  int status = source_load(&src, path, sets, nsets, msg);
  if (status != RS_OK) return status;
  status = source_case(src, NULL, 0, c, msg);
  /* The YAML as run: the document emitted (which consumes it) from a second parse. */
  rs_case_doc d;
  memset(&d, 0, sizeof d);
  if (status == RS_OK) status = rs_case_doc_parse(&d, src->path, src->text, src->len, msg);
  for (int i = 0; status == RS_OK && i < nsets; i++) status = rs_case_doc_set(&d, sets[i]);
  if (status == RS_OK) status = rs_case_doc_emit(&d, &c->yaml_text);
  rs_case_doc_free(&d);
  if (status == RS_OK && c->has_profiles) {
    rs_case_doc pd = src->doc;
    pd.msg = msg;
    status = rs_case_profiles_read(&pd, &c->profiles);
  }
  if (status != RS_OK) {
    rs_case_free(c);
    source_free(src);
    return status;
  }
  c->source = src;
  return RS_OK;
}

int rs_case_derive(const rs_case *base, const rs_case_override *ov, int nov, rs_case *c,
                   rs_msg *msg)
{
  memset(c, 0, sizeof *c);
  if (!base->source)
    return rs_msg_set(msg, RS_ERR_INTERNAL, "rs_case_derive: the base case was not loaded");
  return source_case(base->source, ov, nov, c, msg);
}

void rs_case_free(rs_case *c)
{
  if (!c) return;
  free(c->source_path);
  free(c->yaml_text);
  free(c->title);
  free(c->overrides);
  free(c->output_file);
  rs_history_free(&c->normal_load);
  rs_history_free(&c->velocity);
  rs_history_free(&c->creepage);
  rs_history_free(&c->tangential_force);
  rs_history_free(&c->tangential_force_y);
  rs_history_free(&c->lateral_creepage);
  rs_history_free(&c->spin);
  free(c->rig.steps);
  rs_history_free(&c->shift_velocity);
  rs_history_free(&c->mu_table);
  rs_history_free(&c->tau_c0_table);
  rs_wheel_rail_free(c->profiles);
  source_free(c->source);
  memset(c, 0, sizeof *c);
}

/* ------------------------------------------------------------------ print */

static void print_history(const rs_history *h, FILE *out)
{
  char a[32], b[32], e[32], f[32];
  switch (h->kind) {
  case RS_HISTORY_CONSTANT: fprintf(out, "%s", rs_case_fmt(h->value, a, sizeof a)); break;
  case RS_HISTORY_RAMP:
    fprintf(out, "{ramp: {from: %s, to: %s, start: %s, duration: %s}}", rs_case_fmt(h->from, a, 32),
            rs_case_fmt(h->to, b, 32), rs_case_fmt(h->start, e, 32),
            rs_case_fmt(h->duration, f, 32));
    break;
  case RS_HISTORY_SINE:
    fprintf(out, "{sine: {mean: %s, amplitude: %s, frequency: %s, phase: %s}}",
            rs_case_fmt(h->mean, a, 32), rs_case_fmt(h->amplitude, b, 32),
            rs_case_fmt(h->frequency, e, 32), rs_case_fmt(h->phase, f, 32));
    break;
  case RS_HISTORY_STEPS:
    fprintf(out, "{steps: [");
    for (size_t i = 0; i < h->n; i++)
      fprintf(out, "%s[%s, %s]", i ? ", " : "", rs_case_fmt(h->t[i], a, 32),
              rs_case_fmt(h->v[i], b, 32));
    fprintf(out, "]}");
    break;
  case RS_HISTORY_TABLE:
    fprintf(out, "{table: %zu points, t = %s .. %s s}", h->n, rs_case_fmt(h->t[0], a, 32),
            rs_case_fmt(h->t[h->n - 1], b, 32));
    break;
  }
}

/* Keys of the time axis: meaningless for a steady case, so `check` leaves them out. */
static int steady_skips(const char *path)
{
  static const char *const time_keys[] = {"simulation.end_time", "simulation.rolled_distance",
                                          "simulation.output_interval", "simulation.initial_state",
                                          NULL};
  for (int i = 0; time_keys[i]; i++)
    if (!strcmp(path, time_keys[i])) return 1;
  return 0;
}

/* Whether a friction.* key belongs to the law. */
static int friction_key_used(const char *path, rs_friction_kind kind)
{
  if (!strcmp(path, "friction.mu")) return 1; /* printed as mu at rest otherwise */
  const int polach = kind == RS_FRICTION_POLACH, coulomb = kind == RS_FRICTION_COULOMB;
  if (!strncmp(path, "friction.memory_", 16)) return !coulomb;
  if (!strcmp(path, "friction.mu_static") || !strcmp(path, "friction.A") ||
      !strcmp(path, "friction.B"))
    return polach;
  return !polach && !coulomb; /* mu_kinetic, mu_excess, half_velocity */
}

void rs_case_print(const rs_case *c, FILE *out)
{
  const int three = c->dimension == 3;
  rs_case_input in = {
      .c = *c,
      .k_rel = c->k_tau / (c->shear_modulus + c->k_tau),
      .radius = {three ? 2 : 1, {c->radius, c->radius_y}},
      .curvature = {2, {0.5 / c->radius, three ? 0.5 / c->radius_y : 0.0}},
      .cells = {three ? 2 : 1, {c->cells, c->cells_y}},
      .extent = {three ? 2 : 1, {c->extent, c->extent_y}},
      .force_n = three ? 2 : 1,
      .mu_excess = {c->friction.terms, {c->friction.mu_excess[0], c->friction.mu_excess[1]}},
      .half_velocity = {c->friction.terms,
                        {c->friction.half_velocity[0], c->friction.half_velocity[1]}},
      .t_bulk = {2, {c->temperature.bulk[0], c->temperature.bulk[1]}},
      .t_conductivity = {2, {c->temperature.conductivity[0], c->temperature.conductivity[1]}},
      .t_heat_capacity = {2, {c->temperature.heat_capacity[0], c->temperature.heat_capacity[1]}},
      .t_density = {2, {c->temperature.density[0], c->temperature.density[1]}},
      .t_disc_mass = {2, {c->temperature.disc_mass[0], c->temperature.disc_mass[1]}}};
  char num[32];
  for (size_t i = 0; i < rs_case_nkeys; i++) {
    const rs_case_key *k = &rs_case_keys[i];
    const void *field = k->offset == RS_KEY_NO_FIELD ? NULL : (const char *)&in + k->offset;
    int plastic = !strncmp(k->path, "plasticity", 10);
    if (plastic && !c->has_plasticity) {
      if (k->kind == RS_KEY_SECTION)
        fprintf(out, "plasticity: none  # purely elastic (no plasticity block)\n");
      continue;
    }
    if (!strncmp(k->path, "temperature", 11) && !c->temperature.on) {
      if (k->kind == RS_KEY_SECTION)
        fprintf(out, "temperature: none  # no surface temperature (no temperature block)\n");
      continue;
    }
    if (!strncmp(k->path, "twin_disc", 9) && !c->rig.on) {
      if (k->kind == RS_KEY_SECTION) fprintf(out, "twin_disc: none  # no rig mode\n");
      continue;
    }
    if (!strncmp(k->path, "twin_disc.", 10) && (k->flags & RS_KEY_NULLABLE) &&
        k->kind == RS_KEY_NUMBER && *(const double *)field == 0.0) {
      fprintf(out, "%s: null  # not given\n", k->path);
      continue;
    }
    if (c->mode == RS_MODE_STEADY && steady_skips(k->path)) {
      if (!strcmp(k->path, "simulation.end_time"))
        fprintf(out, "# steady rolling: no time axis (simulation.end_time, rolled_distance, "
                     "output_interval and initial_state do not apply)\n");
      continue;
    }
    if (k->kind == RS_KEY_PROTOCOL) {
      fprintf(out, "%s: ", k->path);
      rs_case_print_protocol(&c->rig, out);
      fprintf(out, "  # slip s = (V1 - V2)/V, revolutions of disc 1\n");
      continue;
    }
    if (k->kind == RS_KEY_SECTION || k->kind == RS_KEY_OPAQUE) continue;
    if (!strcmp(k->path, "rolling.tangential_force") && !c->force_control) {
      fprintf(out, "%s: null  # %s (not given: the creepage is prescribed)\n", k->path,
              three ? "N" : "N/mm");
      continue;
    }
    if (!strcmp(k->path, "rolling.tangential_force") && three) {
      fprintf(out, "%s: [", k->path);
      print_history(&c->tangential_force, out);
      fprintf(out, ", ");
      print_history(&c->tangential_force_y, out);
      fprintf(out, "]  # N\n");
      continue;
    }
    if (!three &&
        (!strcmp(k->path, "contact.curvature") || !strcmp(k->path, "grid.y_range") ||
         !strcmp(k->path, "rolling.lateral_creepage") || !strcmp(k->path, "rolling.spin"))) {
      fprintf(out, "%s: null  # 3D contact only\n", k->path);
      continue;
    }
    if (!strcmp(k->path, "contact.curvature")) {
      fprintf(out, "%s: null  # 1/mm (contact.radius gives A = 1/(2 Rx), B = 1/(2 Ry))\n", k->path);
      continue;
    }
    if (!strcmp(k->path, "grid.y_range")) {
      char lo[32], hi[32];
      if (c->grid_from_range)
        fprintf(out, "%s: [%s, %s]  # mm\n", k->path, rs_case_fmt(c->y_range[0], lo, sizeof lo),
                rs_case_fmt(c->y_range[1], hi, sizeof hi));
      else
        fprintf(out, "%s: null  # mm (not given: grid.extent)\n", k->path);
      continue;
    }
    if (!strcmp(k->path, "rolling.creepage") && c->force_control) {
      fprintf(out, "%s: null  # 1 (computed: the tangential force is prescribed)\n", k->path);
      continue;
    }
    if (!strcmp(k->path, "grid.x_range")) {
      char lo[32], hi[32];
      if (c->grid_from_range)
        fprintf(out, "%s: [%s, %s]  # mm\n", k->path, rs_case_fmt(c->x_range[0], lo, sizeof lo),
                rs_case_fmt(c->x_range[1], hi, sizeof hi));
      else
        fprintf(out, "%s: null  # mm (not given: grid.extent)\n", k->path);
      continue;
    }
    if (k->kind == RS_KEY_TTABLE) {
      const rs_history *h = field;
      if (h->n == 0) {
        fprintf(out, "%s: null  # not given\n", k->path);
        continue;
      }
      fprintf(out, "%s: {%s: [", k->path, k->choices[0]);
      for (size_t j = 0; j < h->n; j++)
        fprintf(out, "%s%s", j ? ", " : "", rs_case_fmt(h->t[j], num, sizeof num));
      fprintf(out, "], %s: [", k->choices[1]);
      for (size_t j = 0; j < h->n; j++)
        fprintf(out, "%s%s", j ? ", " : "", rs_case_fmt(h->v[j], num, sizeof num));
      fprintf(out, "]}  # degC, %s\n", *k->unit ? k->unit : "1");
      continue;
    }
    if (!strncmp(k->path, "friction.", 9) && strcmp(k->path, "friction.law") &&
        !friction_key_used(k->path, c->friction.kind)) {
      fprintf(out, "%s: null  # not used by friction.law: %s\n", k->path,
              rs_friction_name(c->friction.kind));
      continue;
    }
    if (!strcmp(k->path, "friction.mu") && c->friction.kind != RS_FRICTION_COULOMB) {
      fprintf(out, "%s: null  # mu at rest = %s (from the law)\n", k->path,
              rs_case_fmt(c->mu, num, sizeof num));
      continue;
    }
    if (!strcmp(k->path, "grid.extent") && c->grid_from_range) {
      fprintf(out, "%s: null  # Hertz half-widths (not given: grid.x_range)\n", k->path);
      continue;
    }
    if (!strcmp(k->path, "solver.rtol") && c->rtol == 0.0) {
      fprintf(out, "%s: auto  # 1 (0.06 dx/a within [1e-6, 3e-3])\n", k->path);
      continue;
    }
    if (!strcmp(k->path, "grid.accuracy") && !(c->accuracy > 0.0)) {
      fprintf(out, "%s: null  # not given: the case's grid as it is\n", k->path);
      continue;
    }
    if (!strcmp(k->path, "simulation.rolled_distance") && c->rolled_distance < 0) {
      fprintf(out, "%s: null  # mm (not given)\n", k->path);
      continue;
    }
    fprintf(out, "%s: ", k->path);
    switch (k->kind) {
    case RS_KEY_NUMBER:
      fprintf(out, "%s", rs_case_fmt(*(const double *)field, num, sizeof num));
      break;
    case RS_KEY_VECTOR: {
      const rs_case_vec *v = field;
      if (v->n == 1) {
        fprintf(out, "%s", rs_case_fmt(v->v[0], num, sizeof num));
      } else {
        char second[32];
        fprintf(out, "[%s, %s]", rs_case_fmt(v->v[0], num, sizeof num),
                rs_case_fmt(v->v[1], second, sizeof second));
      }
      break;
    }
    case RS_KEY_INTEGER: fprintf(out, "%d", *(const int *)field); break;
    case RS_KEY_LONG: fprintf(out, "%ld", *(const long *)field); break;
    case RS_KEY_TEXT:
      fputc('"', out);
      for (const char *s = *(char *const *)field; s && *s; s++) {
        if (*s == '"' || *s == '\\') fputc('\\', out);
        fputc(*s, out);
      }
      fputc('"', out);
      break;
    case RS_KEY_CHOICE: fprintf(out, "%s", k->choices[field ? *(const int *)field : 0]); break;
    case RS_KEY_HISTORY: print_history(field, out); break;
    case RS_KEY_FIELDS: {
      int first = 1;
      fputc('[', out);
      for (int b = 0; rs_case_field_names[b]; b++)
        if (c->fields & (1u << b)) {
          fprintf(out, "%s%s", first ? "" : ", ", rs_case_field_names[b]);
          first = 0;
        }
      fputc(']', out);
      break;
    }
    default: break;
    }
    if (*k->unit)
      fprintf(out, "  # %s", rs_case_key_unit_in(k->unit, c->dimension));
    else if (k->kind == RS_KEY_NUMBER || k->kind == RS_KEY_HISTORY)
      fprintf(out, "  # 1");
    if (k->flags & RS_KEY_DERIVED) fprintf(out, " (= k_tau/(G + k_tau))");
    fputc('\n', out);
    if (!strcmp(k->path, "title") && c->overrides)
      fprintf(out, "# changed with --set (the title is the case file's): %s\n", c->overrides);
  }
}
