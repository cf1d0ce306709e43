#define _POSIX_C_SOURCE 200809L
/* The fit: block of a case file (io/fit_spec.h): parameters (case keys with start and
 * bounds), the measurements' CSV (header row of column names; lines starting with '#'
 * are comments), the measured output and optional weights. Every error names
 * case.yaml:line: fit.KEY or data.csv:line: column; nothing is run before all is
 * checked (the case is derived once with each data row and the start values). */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/case_internal.h"
#include "io/fit_spec.h"

void rs_fit_free(rs_fit_spec *f)
{
  for (int i = 0; i < f->nparams; i++) free(f->params[i].key);
  free(f->params);
  for (int j = 0; j < f->ncols; j++) {
    free(f->columns[j]);
    if (f->input_keys) free(f->input_keys[j]);
  }
  free(f->columns);
  free(f->input_keys);
  free(f->roles);
  free(f->data_path);
  free(f->measured);
  free(f->weights);
  free(f->table);
  free(f->row_line);
  memset(f, 0, sizeof *f);
}

/* Value node of a dotted key "section.key" in the document, or NULL. */
static const yaml_node_t *find_dotted(const rs_case_doc *d, const yaml_node_t *root,
                                      const char *key)
{
  char section[128];
  const char *dot = strchr(key, '.');
  if (!dot || (size_t)(dot - key) >= sizeof section) return NULL;
  memcpy(section, key, (size_t)(dot - key));
  section[dot - key] = '\0';
  const yaml_node_t *s = rs_case_lookup(d, root, section);
  if (!s || s->type != YAML_MAPPING_NODE) return NULL;
  return rs_case_lookup(d, s, dot + 1);
}

static int read_param(const rs_case_doc *d, const yaml_node_t *root, const yaml_node_t *knode,
                      const yaml_node_t *v, rs_fit_param *p)
{
  const char *key = (const char *)knode->data.scalar.value;
  char ctx[256];
  snprintf(ctx, sizeof ctx, "fit.parameters.%s", key);
  const int idx = rs_case_key_index(key);
  if (idx < 0 || rs_case_keys[idx].kind != RS_KEY_NUMBER)
    return rs_case_error(d, knode, ctx, "%s is not a numeric case key (a parameter to fit)", key);
  const yaml_node_t *given = find_dotted(d, root, key);
  if (!given || rs_case_is_null(given))
    return rs_case_error(d, knode, ctx,
                         "the case does not use %s (not given in the case; a fitted parameter "
                         "must be one of its keys)",
                         key);
  const yaml_node_t *table = find_dotted(d, root, "plasticity.tau_c0_table");
  if (!strcmp(key, "plasticity.tau_c0") && table && !rs_case_is_null(table))
    return rs_case_error(d, knode, ctx,
                         "plasticity.tau_c0 is not fitted with plasticity.tau_c0_table (the table "
                         "gives tau_c0 at each temperature)");
  static const char *const allowed[] = {"start", "bounds", NULL};
  if (v->type != YAML_MAPPING_NODE)
    return rs_case_error(d, v, ctx, "expected {start: NUMBER, bounds: [LOW, HIGH]}");
  if (rs_case_check_mapping(d, v, ctx, allowed) != RS_OK) return RS_ERR_INPUT;
  const yaml_node_t *st = rs_case_lookup(d, v, "start"), *b = rs_case_lookup(d, v, "bounds");
  if (!st) return rs_case_error(d, v, ctx, "start missing");
  if (!b || b->type != YAML_SEQUENCE_NODE ||
      b->data.sequence.items.top - b->data.sequence.items.start != 2)
    return rs_case_error(d, b ? b : v, ctx, "bounds needs [LOW, HIGH]");
  yaml_document_t *doc = (yaml_document_t *)&d->doc;
  const yaml_node_t *lo = yaml_document_get_node(doc, b->data.sequence.items.start[0]);
  const yaml_node_t *hi = yaml_document_get_node(doc, b->data.sequence.items.start[1]);
  if (rs_case_number(d, st, ctx, &p->start) || rs_case_number(d, lo, ctx, &p->lo) ||
      rs_case_number(d, hi, ctx, &p->hi))
    return RS_ERR_INPUT;
  const rs_case_key *spec = &rs_case_keys[idx];
  if (rs_case_check_range(d, lo, spec, ctx, p->lo) || rs_case_check_range(d, hi, spec, ctx, p->hi))
    return RS_ERR_INPUT;
  if (!(p->lo < p->hi))
    return rs_case_error(d, b, ctx, "bounds reversed or empty: [%g, %g] (need LOW < HIGH)", p->lo,
                         p->hi);
  if (!(p->start >= p->lo && p->start <= p->hi))
    return rs_case_error(d, st, ctx, "start %g outside the bounds [%g, %g]", p->start, p->lo,
                         p->hi);
  p->key = strdup(key);
  p->unit = spec->unit;
  return p->key ? RS_OK : rs_msg_set(d->msg, RS_ERR_INTERNAL, "out of memory");
}

static char *trim(char *s)
{
  while (isspace((unsigned char)*s)) s++;
  char *e = s + strlen(s);
  while (e > s && isspace((unsigned char)e[-1])) *--e = '\0';
  return s;
}

/* Split a CSV line at commas in place; returns the number of fields (at most max). */
static int split(char *line, char **fields, int max)
{
  int n = 0;
  for (char *p = line;; p++) {
    char *c = strchr(p, ',');
    if (n < max) fields[n] = trim(p);
    n++;
    if (!c) break;
    *c = '\0';
    p = c;
  }
  return n;
}

/* The dotted case key an input column stands for (NULL: none). */
static const char *input_key(const char *name)
{
  if (!strcmp(name, "creepage")) return "rolling.creepage";
  if (!strcmp(name, "velocity")) return "rolling.velocity";
  if (!strcmp(name, "normal_load")) return "contact.normal_load";
  const int idx = rs_case_key_index(name);
  if (idx < 0) return NULL;
  const rs_case_key_kind k = rs_case_keys[idx].kind;
  return k == RS_KEY_NUMBER || k == RS_KEY_INTEGER || k == RS_KEY_HISTORY || k == RS_KEY_LONG
             ? name
             : NULL;
}

enum { MAX_COLS = 32 };

static int read_csv(rs_fit_spec *f, const char *path, rs_msg *msg)
{
  FILE *in = fopen(path, "r");
  if (!in) return rs_msg_set(msg, RS_ERR_INPUT, "%s: cannot open: %s", path, strerror(errno));
  char line[4096];
  int lineno = 0, status = RS_OK;
  size_t cap = 0;
  while (status == RS_OK && fgets(line, sizeof line, in)) {
    lineno++;
    char *s = trim(line);
    if (!*s || *s == '#') continue;
    char *fields[MAX_COLS];
    const int n = split(s, fields, MAX_COLS);
    if (n > MAX_COLS) {
      status = rs_msg_set(msg, RS_ERR_INPUT, "%s:%d: more than %d columns", path, lineno, MAX_COLS);
    } else if (!f->columns) { /* the header */
      f->ncols = n;
      f->columns = calloc((size_t)n, sizeof *f->columns);
      if (!f->columns) status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
      for (int j = 0; status == RS_OK && j < n; j++) {
        if (!*fields[j])
          status = rs_msg_set(msg, RS_ERR_INPUT, "%s:%d: empty column name (column %d)", path,
                              lineno, j + 1);
        for (int k = 0; status == RS_OK && k < j; k++)
          if (!strcmp(fields[k], fields[j]))
            status = rs_msg_set(msg, RS_ERR_INPUT, "%s:%d: column %s appears twice", path, lineno,
                                fields[j]);
        if (status == RS_OK && !(f->columns[j] = strdup(fields[j])))
          status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
      }
    } else if (n != f->ncols) {
      status = rs_msg_set(msg, RS_ERR_INPUT, "%s:%d: %d values, the header has %d columns (%s)",
                          path, lineno, n, f->ncols, n < f->ncols ? "a value missing" : "too many");
    } else {
      if (f->npoints == cap) {
        cap = cap ? 2 * cap : 64;
        double *t = realloc(f->table, cap * (size_t)f->ncols * sizeof *t);
        if (!t) {
          status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
          break;
        }
        f->table = t;
        int *rl = realloc(f->row_line, cap * sizeof *rl);
        if (!rl) {
          status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
          break;
        }
        f->row_line = rl;
      }
      f->row_line[f->npoints] = lineno;
      for (int j = 0; status == RS_OK && j < n; j++) {
        char *end;
        errno = 0;
        const double x = strtod(fields[j], &end);
        if (!*fields[j] || *end || errno == ERANGE || !isfinite(x))
          status = rs_msg_set(msg, RS_ERR_INPUT, "%s:%d: %s: expected a number, got \"%s\"", path,
                              lineno, f->columns[j], fields[j]);
        f->table[f->npoints * (size_t)f->ncols + (size_t)j] = x;
      }
      if (status == RS_OK) f->npoints++;
    }
  }
  fclose(in);
  if (status == RS_OK && !f->columns)
    status = rs_msg_set(msg, RS_ERR_INPUT, "%s: no header row (column names)", path);
  return status;
}

/* Roles of the columns and the kind of data; rows checked against the protocol. */
static int assign_columns(rs_fit_spec *f, const rs_case *c, rs_msg *msg)
{
  const char *path = f->data_path;
  f->roles = calloc((size_t)f->ncols, sizeof *f->roles);
  f->input_keys = calloc((size_t)f->ncols, sizeof *f->input_keys);
  if (!f->roles || !f->input_keys) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  f->measured_col = f->weight_col = -1;
  int ninputs = 0, rig_col = -1;
  f->kind = RS_FIT_STEADY;
  int has_measured = 0;
  for (int j = 0; j < f->ncols; j++) has_measured |= !strcmp(f->columns[j], f->measured);
  if (!has_measured)
    return rs_msg_set(msg, RS_ERR_INPUT, "%s:1: no column %s (fit.measured)", path, f->measured);
  for (int j = 0; j < f->ncols; j++) {
    const char *name = f->columns[j];
    if (!strcmp(name, f->measured)) {
      f->roles[j] = RS_FIT_COL_MEASURED;
      f->measured_col = j;
    } else if (f->weights && !strcmp(name, f->weights)) {
      f->roles[j] = RS_FIT_COL_WEIGHT;
      f->weight_col = j;
    } else if (!strcmp(name, "step") || !strcmp(name, "twin_disc.slip") ||
               !strcmp(name, "revolution")) {
      f->kind = name[0] == 's'   ? RS_FIT_RIG_STEP
                : name[0] == 'r' ? RS_FIT_RIG_REV
                                 : RS_FIT_RIG_SLIP;
      rig_col = j;
      ninputs++;
    } else {
      const char *key = input_key(name);
      if (!key)
        return rs_msg_set(
            msg, RS_ERR_INPUT,
            "%s:1: column %s: neither a numeric case key (an input), the measured "
            "output (fit.measured: %s), the weights, step, twin_disc.slip nor revolution",
            path, name, f->measured);
      if (!(f->input_keys[j] = strdup(key)))
        return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
      ninputs++;
    }
  }
  if (f->measured_col < 0)
    return rs_msg_set(msg, RS_ERR_INPUT, "%s:1: no column %s (fit.measured)", path, f->measured);
  if (f->weights && f->weight_col < 0)
    return rs_msg_set(msg, RS_ERR_INPUT, "%s:1: no column %s (fit.weights)", path, f->weights);
  if (ninputs == 0)
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "%s:1: no input column (a swept case key, step, revolution or "
                      "twin_disc.slip)",
                      path);
  if (rig_col >= 0 && ninputs > 1)
    return rs_msg_set(
        msg, RS_ERR_INPUT,
        "%s:1: %s: a twin-disc fit has one input column (step, twin_disc.slip or revolution)", path,
        f->columns[rig_col]);
  if (rig_col >= 0 && !c->rig.on)
    return rs_msg_set(msg, RS_ERR_INPUT, "%s:1: %s: the case has no twin_disc: block", path,
                      f->columns[rig_col]);
  if (rig_col < 0 && c->rig.on)
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "%s:1: a twin-disc case is fitted per protocol step: give a column step, "
                      "twin_disc.slip or revolution",
                      path);
  if (f->measured_col >= 0 && strcmp(f->measured, "traction_coefficient") &&
      strcmp(f->measured, "Fx"))
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "fit.measured: %s is not an output rollsim fits "
                      "(traction_coefficient or Fx)",
                      f->measured);
  if (rig_col >= 0 && strcmp(f->measured, "traction_coefficient"))
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "fit.measured: a twin-disc protocol is fitted to traction_coefficient");
  /* Rows: weights positive, protocol steps exist (a slip names one held step). */
  for (size_t i = 0; i < f->npoints; i++) {
    const double *row = f->table + i * (size_t)f->ncols;
    if (f->weight_col >= 0 && !(row[f->weight_col] > 0))
      return rs_msg_set(msg, RS_ERR_INPUT, "%s:%d: %s: a weight must be > 0, got %g", path,
                        f->row_line[i], f->weights, row[f->weight_col]);
    if (f->kind == RS_FIT_RIG_STEP) {
      const double s = row[rig_col];
      if (!(s >= 1 && s <= (double)c->rig.nsteps && s == floor(s)))
        return rs_msg_set(msg, RS_ERR_INPUT, "%s:%d: step: expected a protocol step 1..%zu, got %g",
                          path, f->row_line[i], c->rig.nsteps, s);
    } else if (f->kind == RS_FIT_RIG_REV) {
      const double v = row[rig_col], nrev = ceil(c->end_time / c->rig.revolution_time - 1e-9);
      if (!(v >= 1 && v <= nrev && v == floor(v)))
        return rs_msg_set(
            msg, RS_ERR_INPUT,
            "%s:%d: revolution: expected a revolution 1..%.0f of the protocol, got %g", path,
            f->row_line[i], nrev, v);
    } else if (f->kind == RS_FIT_RIG_SLIP) {
      int found = 0;
      for (size_t k = 0; k < c->rig.nsteps; k++)
        if (c->rig.steps[k].slip_start == row[rig_col] && c->rig.steps[k].slip_end == row[rig_col])
          found++;
      if (found != 1)
        return rs_msg_set(msg, RS_ERR_INPUT, "%s:%d: twin_disc.slip: %g %s (use a column step)",
                          path, f->row_line[i], row[rig_col],
                          found ? "is held in more than one protocol step"
                                : "is not the slip of a held protocol step");
    }
  }
  return RS_OK;
}

/* Every data row (steady inputs) and the start values give a valid case. */
static int check_cases(const rs_fit_spec *f, const rs_case *base, rs_msg *msg)
{
  rs_case_override *ov = calloc((size_t)(f->nparams + f->ncols), sizeof *ov);
  int status = ov ? RS_OK : rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  for (int k = 0; status == RS_OK && k < f->nparams; k++)
    ov[k] = (rs_case_override){rs_case_key_index(f->params[k].key), f->params[k].start};
  const size_t rows = f->kind == RS_FIT_STEADY ? f->npoints : 1;
  for (size_t i = 0; status == RS_OK && i < rows; i++) {
    int n = f->nparams;
    for (int j = 0; f->kind == RS_FIT_STEADY && j < f->ncols; j++)
      if (f->input_keys[j])
        ov[n++] = (rs_case_override){rs_case_key_index(f->input_keys[j]),
                                     f->table[i * (size_t)f->ncols + (size_t)j]};
    rs_case c;
    rs_msg inner;
    status = rs_case_derive(base, ov, n, &c, &inner);
    if (status == RS_OK)
      rs_case_free(&c);
    else if (f->kind == RS_FIT_STEADY)
      rs_msg_set(msg, status, "%s:%d: (with the start values): %s", f->data_path, f->row_line[i],
                 inner.text);
    else
      rs_msg_set(msg, status, "%s: fit: with the start values: %s", base->source->path, inner.text);
  }
  free(ov);
  return status;
}

int rs_fit_load(rs_fit_spec *f, const rs_case *c, rs_msg *msg)
{
  memset(f, 0, sizeof *f);
  if (!c->source) return rs_msg_set(msg, RS_ERR_INTERNAL, "rs_fit_load: the case was not loaded");
  const char *case_path = c->source->path;
  rs_case_doc d = rs_case_source_doc(c, msg);
  int status = RS_OK;
  const yaml_node_t *root = rs_case_doc_root(&d);
  const yaml_node_t *fit = root ? rs_case_lookup(&d, root, "fit") : NULL;
  if (!fit || rs_case_is_null(fit))
    status = rs_msg_set(msg, RS_ERR_INPUT, "%s: the case has no fit: block", case_path);
  static const char *const allowed[] = {"parameters", "data", "measured", "weights", NULL};
  if (status == RS_OK && fit->type != YAML_MAPPING_NODE)
    status = rs_case_error(&d, fit, "fit", "expected a mapping (parameters, data, measured)");
  if (status == RS_OK) status = rs_case_check_mapping(&d, fit, "fit", allowed);
  const yaml_node_t *pars = status == RS_OK ? rs_case_lookup(&d, fit, "parameters") : NULL;
  if (status == RS_OK && (!pars || pars->type != YAML_MAPPING_NODE ||
                          pars->data.mapping.pairs.top == pars->data.mapping.pairs.start))
    status = rs_case_error(&d, pars ? pars : fit, "fit.parameters",
                           "expected a mapping of case keys to {start, bounds}");
  if (status == RS_OK) {
    const int n = (int)(pars->data.mapping.pairs.top - pars->data.mapping.pairs.start);
    f->params = calloc((size_t)n, sizeof *f->params);
    if (!f->params) status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
    for (int i = 0; status == RS_OK && i < n; i++) {
      const yaml_node_pair_t *pr = &pars->data.mapping.pairs.start[i];
      const yaml_node_t *k = yaml_document_get_node(&d.doc, pr->key);
      const yaml_node_t *v = yaml_document_get_node(&d.doc, pr->value);
      if (k->type != YAML_SCALAR_NODE) {
        status = rs_case_error(&d, k, "fit.parameters", "keys must be dotted case keys");
        break;
      }
      for (int j = 0; j < f->nparams; j++)
        if (!strcmp(f->params[j].key, (const char *)k->data.scalar.value))
          status = rs_case_error(&d, k, "fit.parameters", "%s is given twice",
                                 (const char *)k->data.scalar.value);
      if (status == RS_OK) status = read_param(&d, root, k, v, &f->params[f->nparams]);
      if (status == RS_OK) f->nparams++;
    }
  }
  const yaml_node_t *data = status == RS_OK ? rs_case_lookup(&d, fit, "data") : NULL;
  const yaml_node_t *meas = status == RS_OK ? rs_case_lookup(&d, fit, "measured") : NULL;
  const yaml_node_t *wts = status == RS_OK ? rs_case_lookup(&d, fit, "weights") : NULL;
  char *data_name = NULL;
  if (status == RS_OK && !data)
    status = rs_case_error(&d, fit, "fit.data", "missing: the CSV file of measurements");
  if (status == RS_OK && !meas)
    status = rs_case_error(&d, fit, "fit.measured",
                           "missing: the output the measured column holds (traction_coefficient)");
  if (status == RS_OK) status = rs_case_text(&d, data, "fit.data", &data_name);
  if (status == RS_OK) status = rs_case_text(&d, meas, "fit.measured", &f->measured);
  if (status == RS_OK && wts && !rs_case_is_null(wts))
    status = rs_case_text(&d, wts, "fit.weights", &f->weights);
  if (status == RS_OK) {
    const size_t len = strlen(d.dir) + strlen(data_name) + 2;
    f->data_path = malloc(len);
    if (!f->data_path)
      status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
    else
      snprintf(f->data_path, len, "%s%s", data_name[0] == '/' ? "" : d.dir, data_name);
  }
  free(data_name);
  if (status == RS_OK) status = read_csv(f, f->data_path, msg);
  if (status == RS_OK) status = assign_columns(f, c, msg);
  if (status == RS_OK && f->npoints <= (size_t)f->nparams)
    status = rs_msg_set(msg, RS_ERR_INPUT,
                        "%s: %zu data points for %d parameters: a fit needs more points than "
                        "parameters",
                        f->data_path, f->npoints, f->nparams);
  if (status == RS_OK) status = check_cases(f, c, msg);
  if (status != RS_OK) rs_fit_free(f);
  return status;
}
