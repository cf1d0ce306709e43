#define _POSIX_C_SOURCE 200809L
/* The sweep: block of a case file (study/sweep.h): dotted keys mapped to value
 * lists or {linspace: [from, to, n]}, checked against the key table and by deriving
 * the case with each value. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/case_internal.h"
#include "io/case_sweep.h"
#include "io/profile.h"

void rs_sweep_free(rs_sweep *s)
{
  for (int i = 0; i < s->naxes; i++) {
    free(s->axes[i].key);
    free(s->axes[i].values);
  }
  free(s->axes);
  memset(s, 0, sizeof *s);
}

static int read_values(const rs_case_doc *d, const yaml_node_t *v, const char *key,
                       rs_sweep_axis *ax)
{
  char ctx[256];
  snprintf(ctx, sizeof ctx, "sweep.%s", key);
  if (v->type == YAML_MAPPING_NODE) {
    static const char *const allowed[] = {"linspace", NULL};
    if (rs_case_check_mapping(d, v, ctx, allowed) != RS_OK) return RS_ERR_INPUT;
    const yaml_node_t *ls = rs_case_lookup(d, v, "linspace");
    if (!ls || ls->type != YAML_SEQUENCE_NODE ||
        ls->data.sequence.items.top - ls->data.sequence.items.start != 3)
      return rs_case_error(d, ls ? ls : v, ctx, "linspace needs [from, to, count]");
    double a, b, cnt;
    yaml_node_item_t *it = ls->data.sequence.items.start;
    yaml_document_t *doc = (yaml_document_t *)&d->doc;
    if (rs_case_number(d, yaml_document_get_node(doc, it[0]), ctx, &a) ||
        rs_case_number(d, yaml_document_get_node(doc, it[1]), ctx, &b) ||
        rs_case_number(d, yaml_document_get_node(doc, it[2]), ctx, &cnt))
      return RS_ERR_INPUT;
    if (!(cnt >= 1 && cnt <= 100000 && cnt == floor(cnt)))
      return rs_case_error(d, ls, ctx, "linspace count must be a whole number in 1..100000, got %g",
                           cnt);
    ax->n = (int)cnt;
    ax->values = malloc((size_t)ax->n * sizeof *ax->values);
    if (!ax->values) return rs_msg_set(d->msg, RS_ERR_INTERNAL, "out of memory");
    for (int k = 0; k < ax->n; k++) ax->values[k] = ax->n == 1 ? a : a + (b - a) * k / (ax->n - 1);
    return RS_OK;
  }
  if (v->type != YAML_SEQUENCE_NODE)
    return rs_case_error(d, v, ctx, "expected a list of values or {linspace: [from, to, count]}");
  const int n = (int)(v->data.sequence.items.top - v->data.sequence.items.start);
  if (n < 1) return rs_case_error(d, v, ctx, "empty list of values");
  ax->n = n;
  ax->values = malloc((size_t)n * sizeof *ax->values);
  if (!ax->values) return rs_msg_set(d->msg, RS_ERR_INTERNAL, "out of memory");
  for (int k = 0; k < n; k++) {
    const yaml_node_t *item =
        yaml_document_get_node((yaml_document_t *)&d->doc, v->data.sequence.items.start[k]);
    if (rs_case_number(d, item, ctx, &ax->values[k]) != RS_OK) return RS_ERR_INPUT;
  }
  return RS_OK;
}

/* The axis of KEY in a sweep on profiles: a wheelset position key, each value checked by
 * placing the wheelset there (a copy of the block: the case's keeps its values). */
static int position_axis(const rs_case_doc *d, const rs_case *c, const yaml_node_t *k,
                         const yaml_node_t *v, const char *key, rs_sweep *s)
{
  const char *name = !strncmp(key, "profiles.", 9) ? key + 9 : "";
  if (!rs_wheel_rail_position_key(name))
    return rs_case_error(d, k, "sweep",
                         "%s: a sweep on profiles is a path of wheelset positions and varies "
                         "profiles.lateral_displacement, profiles.yaw and "
                         "profiles.wheel_angular_velocity only",
                         key);
  if (!c->profiles || !(c->profiles->vertical_load > 0))
    return rs_case_error(d, k, "sweep",
                         "%s: a sweep on profiles needs profiles.vertical_load (the wheel load)",
                         key);
  for (int j = 0; j < s->naxes; j++)
    if (!strcmp(s->axes[j].key, key)) return rs_case_error(d, k, "sweep", "%s is swept twice", key);
  rs_sweep_axis *ax = &s->axes[s->naxes];
  ax->key_index = -1;
  if (!(ax->key = strdup(key))) return rs_msg_set(d->msg, RS_ERR_INTERNAL, "out of memory");
  s->naxes++;
  int status = read_values(d, v, key, ax);
  if (status == RS_OK && s->naxes > 1 && ax->n != s->axes[0].n)
    return rs_case_error(d, v, "sweep",
                         "%s has %d values and %s %d: a sweep on profiles takes the k-th value of "
                         "every key for its k-th wheelset position, so the lists need one length",
                         key, ax->n, s->axes[0].key, s->axes[0].n);
  rs_wheel_rail w = *c->profiles;
  char ctx[256];
  snprintf(ctx, sizeof ctx, "sweep.%s", key);
  for (int i = 0; status == RS_OK && i < ax->n; i++) {
    rs_msg inner = {{0}};
    if (rs_wheel_rail_set(&w, name, ax->values[i], &inner) != RS_OK)
      status = rs_case_error(d, v, ctx, "%s", inner.text);
  }
  s->npoints = (size_t)ax->n;
  return status;
}

int rs_sweep_load(rs_sweep *s, const rs_case *c, rs_msg *msg)
{
  memset(s, 0, sizeof *s);
  if (!c->source) return rs_msg_set(msg, RS_ERR_INTERNAL, "rs_sweep_load: the case was not loaded");
  const char *path = c->source->path;
  rs_case_doc d = rs_case_source_doc(c, msg);
  int status = RS_OK;
  const yaml_node_t *root = rs_case_doc_root(&d);
  const yaml_node_t *sw = root ? rs_case_lookup(&d, root, "sweep") : NULL;
  if (!sw || rs_case_is_null(sw))
    status =
        rs_msg_set(msg, RS_ERR_INPUT, "%s: the case has no sweep: block (use rollsim run)", path);
  if (status == RS_OK && sw->type != YAML_MAPPING_NODE)
    status = rs_case_error(&d, sw, "sweep", "expected a mapping of dotted keys to value lists");
  if (status == RS_OK) {
    const int n = (int)(sw->data.mapping.pairs.top - sw->data.mapping.pairs.start);
    s->axes = calloc((size_t)(n > 0 ? n : 1), sizeof *s->axes);
    if (!s->axes) status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
    if (status == RS_OK && n == 0) status = rs_case_error(&d, sw, "sweep", "no keys to sweep");
    s->npoints = 1;
    for (int i = 0; status == RS_OK && i < n; i++) {
      const yaml_node_pair_t *pr = &sw->data.mapping.pairs.start[i];
      const yaml_node_t *k = yaml_document_get_node(&d.doc, pr->key);
      const yaml_node_t *v = yaml_document_get_node(&d.doc, pr->value);
      if (k->type != YAML_SCALAR_NODE) {
        status = rs_case_error(&d, k, "sweep", "keys must be dotted case keys");
        break;
      }
      const char *key = (const char *)k->data.scalar.value;
      if (rs_case_is_null(v)) /* KEY: null (e.g. --set sweep.KEY=null): not swept */
        continue;
      if (c->has_profiles) {
        s->positions = 1;
        if ((status = position_axis(&d, c, k, v, key, s)) != RS_OK) break;
        continue;
      }
      const int idx = rs_case_key_index(key);
      if (!rs_case_key_numeric(idx)) {
        status = rs_case_error(&d, k, "sweep", "%s is not a numeric case key", key);
        break;
      }
      if (c->tau_c0_table.n && !strcmp(key, "plasticity.tau_c0")) {
        status = rs_case_error(&d, k, "sweep",
                               "plasticity.tau_c0 is not swept with plasticity.tau_c0_table (the "
                               "table gives tau_c0 at each temperature): sweep without the table");
        break;
      }
      for (int j = 0; j < s->naxes; j++)
        if (s->axes[j].key_index == idx)
          status = rs_case_error(&d, k, "sweep", "%s is swept twice", key);
      if (status != RS_OK) break;
      rs_sweep_axis *ax = &s->axes[s->naxes];
      ax->key = strdup(key);
      ax->key_index = idx;
      if (!ax->key) {
        status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
        break;
      }
      s->naxes++;
      status = read_values(&d, v, key, ax);
      s->npoints *= (size_t)ax->n;
    }
    if (status == RS_OK && s->naxes == 0)
      status = rs_case_error(&d, sw, "sweep", "no keys to sweep (every key is null)");
  }
  /* Every value must give a valid case: the case derived with it. */
  char num[64];
  for (int a = 0; status == RS_OK && !s->positions && a < s->naxes; a++)
    for (int k = 0; status == RS_OK && k < s->axes[a].n; k++) {
      const rs_case_override ov = {s->axes[a].key_index, s->axes[a].values[k]};
      rs_case pc;
      rs_msg inner;
      status = rs_case_derive(c, &ov, 1, &pc, &inner);
      if (status == RS_OK)
        rs_case_free(&pc);
      else
        rs_msg_set(msg, status, "%s: sweep: %s = %s: %s", path, s->axes[a].key,
                   rs_case_fmt(s->axes[a].values[k], num, sizeof num), inner.text);
    }
  if (status != RS_OK) rs_sweep_free(s);
  return status;
}
