/* History values in the case file (interfaces.md "Histories"): a number, or one of
 *   {ramp: {from, to, start, duration}}   {steps: [[t, v], ...]}
 *   {sine: {mean, amplitude, frequency, phase}}   {table: file.csv}
 * A table is two columns time,value (an optional header line, # comments), its
 * path relative to the case file's directory. */
#define _POSIX_C_SOURCE 200809L
#include "io/case_internal.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct history_param {
  const char *name;
  int required;
  double fallback;
  size_t offset; /* into rs_history */
} history_param;

/* Parse the keyed parameters of a ramp or sine mapping. */
static int parse_params(const rs_case_doc *d, const yaml_node_t *map, const char *key,
                        const history_param *params, size_t count, const char *needs, rs_history *h)
{
  const char *names[8];
  for (size_t i = 0; i < count; i++) names[i] = params[i].name;
  names[count] = NULL;
  int status = rs_case_check_mapping(d, map, key, names);
  if (status != RS_OK) return status;
  for (size_t i = 0; i < count; i++) {
    char sub[320];
    snprintf(sub, sizeof sub, "%s.%s", key, params[i].name);
    const yaml_node_t *n = rs_case_lookup(d, map, params[i].name);
    double *field = (double *)((char *)h + params[i].offset);
    if (!n) {
      if (params[i].required) return rs_case_error(d, map, sub, "missing: %s", needs);
      *field = params[i].fallback;
    } else if ((status = rs_case_number(d, n, sub, field)) != RS_OK)
      return status;
  }
  return RS_OK;
}

static int parse_ramp(const rs_case_doc *d, const yaml_node_t *n, const char *key, rs_history *h)
{
  static const history_param params[] = {
      {"from", 1, 0, offsetof(rs_history, from)},
      {"to", 1, 0, offsetof(rs_history, to)},
      {"start", 0, 0.0, offsetof(rs_history, start)},
      {"duration", 1, 0, offsetof(rs_history, duration)},
  };
  h->kind = RS_HISTORY_RAMP;
  int status = parse_params(d, n, key, params, 4,
                            "a ramp needs from, to and duration (s); start defaults to 0 s", h);
  if (status != RS_OK) return status;
  if (!(h->duration > 0))
    return rs_case_error(d, rs_case_lookup(d, n, "duration"), key,
                         "duration must be > 0 s, got %g (use steps for a jump)", h->duration);
  return RS_OK;
}

static int parse_sine(const rs_case_doc *d, const yaml_node_t *n, const char *key, rs_history *h)
{
  static const history_param params[] = {
      {"mean", 1, 0, offsetof(rs_history, mean)},
      {"amplitude", 1, 0, offsetof(rs_history, amplitude)},
      {"frequency", 1, 0, offsetof(rs_history, frequency)},
      {"phase", 0, 0.0, offsetof(rs_history, phase)},
  };
  h->kind = RS_HISTORY_SINE;
  int status =
      parse_params(d, n, key, params, 4,
                   "a sine needs mean, amplitude and frequency (Hz); phase (rad) defaults to 0", h);
  if (status != RS_OK) return status;
  if (!(h->frequency >= 0 && h->frequency <= 1e9))
    return rs_case_error(d, rs_case_lookup(d, n, "frequency"), key,
                         "frequency must be in [0, 1e9] Hz, got %g", h->frequency);
  if (fabs(h->phase) > 1e6)
    return rs_case_error(d, rs_case_lookup(d, n, "phase"), key,
                         "phase %g rad is unreasonably large (it is in radians)", h->phase);
  return RS_OK;
}

static int alloc_points(const rs_case_doc *d, rs_history *h, size_t n)
{
  h->t = malloc((n ? n : 1) * sizeof *h->t);
  h->v = malloc((n ? n : 1) * sizeof *h->v);
  if (!h->t || !h->v) return rs_msg_set(d->msg, RS_ERR_INTERNAL, "out of memory");
  return RS_OK;
}

static int parse_steps(const rs_case_doc *d, const yaml_node_t *n, const char *key, rs_history *h)
{
  char got[96];
  h->kind = RS_HISTORY_STEPS;
  if (n->type != YAML_SEQUENCE_NODE || n->data.sequence.items.top == n->data.sequence.items.start)
    return rs_case_error(d, n, key, "steps: expected a non-empty list of [time, value], got %s",
                         rs_case_describe(n, got, sizeof got));
  size_t count = (size_t)(n->data.sequence.items.top - n->data.sequence.items.start);
  int status = alloc_points(d, h, count);
  if (status != RS_OK) return status;
  for (size_t i = 0; i < count; i++) {
    const yaml_node_t *pt =
        yaml_document_get_node((yaml_document_t *)&d->doc, n->data.sequence.items.start[i]);
    if (!pt || pt->type != YAML_SEQUENCE_NODE ||
        pt->data.sequence.items.top - pt->data.sequence.items.start != 2)
      return rs_case_error(d, pt, key, "steps: entry %zu: expected [time, value], got %s", i + 1,
                           rs_case_describe(pt, got, sizeof got));
    yaml_node_item_t *it = pt->data.sequence.items.start;
    if ((status = rs_case_number(d, yaml_document_get_node((yaml_document_t *)&d->doc, it[0]), key,
                                 &h->t[i])) != RS_OK ||
        (status = rs_case_number(d, yaml_document_get_node((yaml_document_t *)&d->doc, it[1]), key,
                                 &h->v[i])) != RS_OK)
      return status;
    h->n = i + 1;
    if (i > 0 && !(h->t[i] > h->t[i - 1]))
      return rs_case_error(d, pt, key,
                           "steps: times must be strictly increasing, entry %zu has t = %g s after "
                           "t = %g s",
                           i + 1, h->t[i], h->t[i - 1]);
  }
  return RS_OK;
}

/* One "time,value" line (comma, semicolon, tab or blanks between); 1 if parsed. */
static int parse_csv_line(const char *s, double *t, double *v)
{
  char *end;
  *t = strtod(s, &end);
  if (end == s) return 0;
  s = end;
  while (*s == ' ' || *s == '\t') s++;
  if (*s == ',' || *s == ';') s++;
  *v = strtod(s, &end);
  if (end == s) return 0;
  for (s = end; *s; s++)
    if (!isspace((unsigned char)*s)) return 0;
  return 1;
}

static int read_table(const rs_case_doc *d, const yaml_node_t *n, const char *key, rs_history *h)
{
  char got[96];
  if (n->type != YAML_SCALAR_NODE || rs_case_is_null(n))
    return rs_case_error(d, n, key, "table: expected a CSV file name, got %s",
                         rs_case_describe(n, got, sizeof got));
  const char *name = (const char *)n->data.scalar.value;
  size_t len = strlen(d->dir) + strlen(name) + 1;
  char *path = malloc(len);
  if (!path) return rs_msg_set(d->msg, RS_ERR_INTERNAL, "out of memory");
  snprintf(path, len, "%s%s", name[0] == '/' ? "" : d->dir, name);
  h->kind = RS_HISTORY_TABLE;
  FILE *f = fopen(path, "r");
  int status = RS_OK;
  if (!f) {
    status = rs_case_error(d, n, key, "cannot open table %s: %s", path, strerror(errno));
    free(path);
    return status;
  }
  char *line = NULL;
  size_t cap = 0, capacity = 0, lineno = 0;
  int seen_content = 0;
  while (status == RS_OK && getline(&line, &cap, f) >= 0) {
    lineno++;
    char *s = line;
    while (isspace((unsigned char)*s)) s++;
    if (!*s || *s == '#') continue;
    double t, v;
    if (!parse_csv_line(s, &t, &v)) {
      if (!seen_content++) /* a header line */
        continue;
      s[strcspn(s, "\r\n")] = '\0';
      status =
          rs_case_error(d, n, key, "table %s:%zu: expected two numbers time,value, got \"%.40s\"",
                        path, lineno, s);
      break;
    }
    seen_content = 1;
    if (!isfinite(t) || !isfinite(v)) {
      status = rs_case_error(d, n, key, "table %s:%zu: time and value must be finite numbers", path,
                             lineno);
      break;
    }
    if (h->n > 0 && !(t > h->t[h->n - 1])) {
      status = rs_case_error(d, n, key,
                             "table %s:%zu: times must be strictly increasing, t = %g s after %g s",
                             path, lineno, t, h->t[h->n - 1]);
      break;
    }
    if (h->n == capacity) {
      capacity = capacity ? 2 * capacity : 64;
      double *tt = realloc(h->t, capacity * sizeof *tt);
      if (tt) h->t = tt;
      double *vv = tt ? realloc(h->v, capacity * sizeof *vv) : NULL;
      if (vv) h->v = vv;
      if (!tt || !vv) {
        status = rs_msg_set(d->msg, RS_ERR_INTERNAL, "out of memory");
        break;
      }
    }
    h->t[h->n] = t;
    h->v[h->n] = v;
    h->n++;
  }
  if (status == RS_OK && ferror(f))
    status = rs_case_error(d, n, key, "cannot read table %s: %s", path, strerror(errno));
  if (status == RS_OK && h->n == 0)
    status = rs_case_error(d, n, key, "table %s has no time,value rows", path);
  free(line);
  fclose(f);
  free(path);
  return status;
}

int rs_case_history(const rs_case_doc *d, const yaml_node_t *n, const char *key, const char *unit,
                    rs_history *h)
{
  char got[96], sub[256];
  (void)unit;
  memset(h, 0, sizeof *h);
  if (n && n->type == YAML_SCALAR_NODE) {
    h->kind = RS_HISTORY_CONSTANT;
    return rs_case_number(d, n, key, &h->value);
  }
  if (!n || n->type != YAML_MAPPING_NODE ||
      n->data.mapping.pairs.top - n->data.mapping.pairs.start != 1)
    return rs_case_error(d, n, key,
                         "expected a number or one of {ramp: ...}, {steps: ...}, {sine: ...}, "
                         "{table: ...}; got %s%s",
                         rs_case_describe(n, got, sizeof got),
                         n && n->type == YAML_MAPPING_NODE ? " with more or less than one key"
                                                           : "");
  static const char *const forms[] = {"ramp", "steps", "sine", "table", NULL};
  int status = rs_case_check_mapping(d, n, key, forms);
  if (status != RS_OK) return status;
  const yaml_node_pair_t *pair = n->data.mapping.pairs.start;
  const yaml_node_t *k = yaml_document_get_node((yaml_document_t *)&d->doc, pair->key);
  const yaml_node_t *v = yaml_document_get_node((yaml_document_t *)&d->doc, pair->value);
  const char *form = (const char *)k->data.scalar.value;
  snprintf(sub, sizeof sub, "%s.%s", key, form);
  if (!strcmp(form, "ramp")) return parse_ramp(d, v, sub, h);
  if (!strcmp(form, "sine")) return parse_sine(d, v, sub, h);
  if (!strcmp(form, "steps")) return parse_steps(d, v, key, h);
  return read_table(d, v, key, h);
}
