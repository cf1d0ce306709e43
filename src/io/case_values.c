/* Reading typed values from case-document nodes, with messages in the user's
 * terms: "case.yaml:12: plasticity.k_tau: expected a number, got \"abc\"", or
 * "--set rolling.creepage: ..." for a node that came from a --set. */
#define _POSIX_C_SOURCE 200809L
#include "io/case_internal.h"

#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* ----------------------------------------------------------------- errors */

int rs_case_error(const rs_case_doc *d, const yaml_node_t *node, const char *key, const char *fmt,
                  ...)
{
  char what[RS_MSG_LEN];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(what, sizeof what, fmt, ap);
  va_end(ap);
  if (!node && d->has_doc) node = yaml_document_get_root_node((yaml_document_t *)&d->doc);
  for (int i = 0; node && i < d->noverrides; i++)
    if (node == d->overrides[i].node) {
      const char *set = d->overrides[i].key;
      if (!key || strcmp(key, set) == 0)
        return rs_msg_set(d->msg, RS_ERR_INPUT, "--set %s: %s", set, what);
      return rs_msg_set(d->msg, RS_ERR_INPUT, "--set %s: %s: %s", set, key, what);
    }
  if (node) {
    int index = (int)(node - d->doc.nodes.start) + 1;
    for (int i = 0; i < d->nsets; i++) {
      const rs_case_set_origin *s = &d->sets[i];
      if (index >= s->first_node && index < s->end_node) {
        if (!key || strcmp(key, s->key) == 0)
          return rs_msg_set(d->msg, RS_ERR_INPUT, "--set %s: %s", s->key, what);
        return rs_msg_set(d->msg, RS_ERR_INPUT, "--set %s: %s: %s", s->key, key, what);
      }
    }
  }
  size_t line = node ? node->start_mark.line + 1 : 1;
  if (key) return rs_msg_set(d->msg, RS_ERR_INPUT, "%s:%zu: %s: %s", d->path, line, key, what);
  return rs_msg_set(d->msg, RS_ERR_INPUT, "%s:%zu: %s", d->path, line, what);
}

int rs_case_is_null(const yaml_node_t *n)
{
  if (!n) return 1;
  if (n->type != YAML_SCALAR_NODE || n->data.scalar.style != YAML_PLAIN_SCALAR_STYLE) return 0;
  const char *s = (const char *)n->data.scalar.value;
  return !*s || !strcmp(s, "~") || !strcmp(s, "null") || !strcmp(s, "Null") || !strcmp(s, "NULL");
}

const char *rs_case_describe(const yaml_node_t *n, char *buf, size_t len)
{
  if (!n || rs_case_is_null(n))
    snprintf(buf, len, "nothing (null)");
  else if (n->type == YAML_SEQUENCE_NODE)
    snprintf(buf, len,
             n->data.sequence.items.top == n->data.sequence.items.start ? "an empty list"
                                                                        : "a list");
  else if (n->type == YAML_MAPPING_NODE)
    snprintf(buf, len, "a mapping");
  else {
    const char *s = (const char *)n->data.scalar.value;
    size_t cut = strlen(s), max = len > 12 ? len - 12 : 0;
    if (cut > max) { /* cut at a UTF-8 character boundary */
      cut = max;
      while (cut > 0 && ((unsigned char)s[cut] & 0xc0) == 0x80) cut--;
    }
    snprintf(buf, len, "\"%.*s%s\"", (int)cut, s, cut < strlen(s) ? "..." : "");
  }
  return buf;
}

/* ------------------------------------------------------ scalar conversion */

int rs_case_number(const rs_case_doc *d, const yaml_node_t *n, const char *key, double *out)
{
  char got[96];
  if (!n || n->type != YAML_SCALAR_NODE || rs_case_is_null(n))
    return rs_case_error(d, n, key, "expected a number, got %s",
                         rs_case_describe(n, got, sizeof got));
  const char *s = (const char *)n->data.scalar.value;
  if (n->data.scalar.style != YAML_PLAIN_SCALAR_STYLE)
    return rs_case_error(d, n, key, "expected a number, got the quoted text %s",
                         rs_case_describe(n, got, sizeof got));
  const char *word = s + (*s == '+' || *s == '-');
  word += *word == '.';
  if (!strcasecmp(word, "inf") || !strcasecmp(word, "infinity") || !strcasecmp(word, "nan"))
    return rs_case_error(d, n, key, "must be a finite number, got %s", s);
  char *end;
  double x = strtod(s, &end);
  if (end == s || *end || strpbrk(s, "xXpP") || isspace((unsigned char)*s))
    return rs_case_error(d, n, key, "expected a number, got %s",
                         rs_case_describe(n, got, sizeof got));
  if (!isfinite(x))
    return rs_case_error(d, n, key, "%s is out of the range of double-precision numbers", s);
  *out = x;
  return RS_OK;
}

int rs_case_text(const rs_case_doc *d, const yaml_node_t *n, const char *key, char **out)
{
  char got[96];
  if (!n || n->type != YAML_SCALAR_NODE)
    return rs_case_error(d, n, key, "expected text, got %s", rs_case_describe(n, got, sizeof got));
  char *copy = strdup((const char *)n->data.scalar.value);
  if (!copy) return rs_msg_set(d->msg, RS_ERR_INTERNAL, "out of memory");
  free(*out);
  *out = copy;
  return RS_OK;
}

static void join_names(const char *const *names, char *buf, size_t len)
{
  buf[0] = '\0';
  for (size_t i = 0; names[i]; i++) {
    size_t used = strlen(buf);
    snprintf(buf + used, len - used, "%s%s", i ? ", " : "", names[i]);
  }
}

int rs_case_choice(const rs_case_doc *d, const yaml_node_t *n, const char *key,
                   const char *const *choices, int *out)
{
  char got[96], names[256];
  if (n && n->type == YAML_SCALAR_NODE && !rs_case_is_null(n))
    for (int i = 0; choices[i]; i++)
      if (!strcmp((const char *)n->data.scalar.value, choices[i])) {
        *out = i;
        return RS_OK;
      }
  rs_case_describe(n, got, sizeof got);
  if (!choices[1])
    return rs_case_error(d, n, key, "%s is the only choice implemented; got %s", choices[0], got);
  join_names(choices, names, sizeof names);
  return rs_case_error(d, n, key, "expected one of %s; got %s", names, got);
}

/* Levenshtein distance of short strings (for "did you mean"), capped. */
static size_t edit_distance(const char *a, const char *b)
{
  size_t la = strlen(a), lb = strlen(b), row[64];
  if (la >= 63 || lb >= 63) return 99;
  for (size_t j = 0; j <= lb; j++) row[j] = j;
  for (size_t i = 1; i <= la; i++) {
    size_t diag = row[0];
    row[0] = i;
    for (size_t j = 1; j <= lb; j++) {
      size_t up = row[j];
      size_t best = diag + (a[i - 1] != b[j - 1]);
      if (up + 1 < best) best = up + 1;
      if (row[j - 1] + 1 < best) best = row[j - 1] + 1;
      row[j] = best;
      diag = up;
    }
  }
  return row[lb];
}

int rs_case_check_mapping(const rs_case_doc *d, const yaml_node_t *map, const char *key,
                          const char *const *allowed)
{
  char got[96], path[256], names[512];
  if (!map || map->type != YAML_MAPPING_NODE)
    return rs_case_error(d, map, key, "expected a mapping of keys, got %s",
                         rs_case_describe(map, got, sizeof got));
  for (yaml_node_pair_t *p = map->data.mapping.pairs.start; p < map->data.mapping.pairs.top; p++) {
    const yaml_node_t *k = yaml_document_get_node((yaml_document_t *)&d->doc, p->key);
    if (!k || k->type != YAML_SCALAR_NODE || rs_case_is_null(k))
      return rs_case_error(d, k, key, "expected a key name, got %s",
                           rs_case_describe(k, got, sizeof got));
    const char *name = (const char *)k->data.scalar.value;
    snprintf(path, sizeof path, "%s%s%s", key ? key : "", key ? "." : "", name);
    const char *best = NULL;
    size_t best_distance = 3, i;
    for (i = 0; allowed[i] && strcmp(allowed[i], name); i++) {
      size_t dist = edit_distance(allowed[i], name);
      if (dist < best_distance) {
        best_distance = dist;
        best = allowed[i];
      }
    }
    if (!allowed[i]) {
      if (best)
        return rs_case_error(d, k, path, "unknown key; did you mean %s%s%s?", key ? key : "",
                             key ? "." : "", best);
      join_names(allowed, names, sizeof names);
      return rs_case_error(d, k, path, "unknown key (%s accepts: %s)", key ? key : "the case file",
                           names);
    }
    for (yaml_node_pair_t *q = map->data.mapping.pairs.start; q < p; q++) {
      const yaml_node_t *earlier = yaml_document_get_node((yaml_document_t *)&d->doc, q->key);
      if (earlier && earlier->type == YAML_SCALAR_NODE &&
          !strcmp((const char *)earlier->data.scalar.value, name))
        return rs_case_error(d, k, path, "given twice (first at line %zu)",
                             earlier->start_mark.line + 1);
    }
  }
  return RS_OK;
}

yaml_node_t *rs_case_lookup(const rs_case_doc *d, const yaml_node_t *map, const char *name)
{
  yaml_document_t *doc = (yaml_document_t *)&d->doc; /* libyaml's getters are not const */
  if (!map || map->type != YAML_MAPPING_NODE) return NULL;
  for (yaml_node_pair_t *p = map->data.mapping.pairs.start; p < map->data.mapping.pairs.top; p++) {
    yaml_node_t *k = yaml_document_get_node(doc, p->key);
    if (k && k->type == YAML_SCALAR_NODE && !strcmp((const char *)k->data.scalar.value, name))
      return yaml_document_get_node(doc, p->value);
  }
  return NULL;
}

const char *rs_case_fmt(double x, char *buf, size_t len)
{
  snprintf(buf, len, "%.15g", x);
  if (strtod(buf, NULL) != x) snprintf(buf, len, "%.17g", x);
  return buf;
}
