/* The case file as a YAML document (libyaml's document API): parsing with
 * file:line for every node, --set KEY=VALUE edits (each remembers the nodes it
 * created, so messages can point at the --set), and emission of the document
 * as run (the netCDF `case` attribute). */
#define _POSIX_C_SOURCE 200809L
#include "io/case_internal.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- loading */

int rs_case_doc_read(const char *path, char **buf, size_t *len, rs_msg *msg)
{
  FILE *f = fopen(path, "rb");
  if (!f)
    return rs_msg_set(msg, RS_ERR_INPUT, "cannot open case file %s: %s", path, strerror(errno));
  size_t cap = 4096, n = 0;
  char *b = malloc(cap);
  int status = RS_OK;
  while (b) {
    n += fread(b + n, 1, cap - n - 1, f);
    if (ferror(f)) {
      status = rs_msg_set(msg, RS_ERR_INPUT, "cannot read case file %s: %s", path, strerror(errno));
      break;
    }
    if (feof(f)) break;
    if (cap - n - 1 == 0) {
      char *bigger = cap < ((size_t)1 << 30) ? realloc(b, 2 * cap) : NULL;
      if (!bigger) {
        free(b);
        b = NULL;
        break;
      }
      b = bigger;
      cap *= 2;
    }
  }
  fclose(f);
  if (!b) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory reading case file %s", path);
  if (status != RS_OK) {
    free(b);
    return status;
  }
  b[n] = '\0';
  *buf = b;
  *len = n;
  return RS_OK;
}

/* Message for a failed yaml_parser_load; `text` is the input (reader errors only
 * give a byte offset). */
static int parser_error(const yaml_parser_t *p, const char *where, const char *text, size_t len,
                        rs_msg *msg)
{
  if (p->error == YAML_MEMORY_ERROR)
    return rs_msg_set(msg, RS_ERR_INTERNAL, "%s: out of memory while parsing YAML", where);
  const char *problem = p->problem ? p->problem : "unknown error";
  if (p->error == YAML_READER_ERROR) {
    size_t line = 1;
    for (size_t i = 0; i < p->problem_offset && i < len; i++) line += text[i] == '\n';
    return rs_msg_set(msg, RS_ERR_INPUT, "%s:%zu: not readable as YAML text: %s (byte 0x%02x)",
                      where, line, problem, (unsigned)p->problem_value & 0xffu);
  }
  if (p->context)
    return rs_msg_set(msg, RS_ERR_INPUT, "%s:%zu: YAML syntax error: %s (%s at line %zu)", where,
                      p->problem_mark.line + 1, problem, p->context, p->context_mark.line + 1);
  return rs_msg_set(msg, RS_ERR_INPUT, "%s:%zu: YAML syntax error: %s", where,
                    p->problem_mark.line + 1, problem);
}

int rs_case_doc_parse(rs_case_doc *d, const char *path, const char *text, size_t len, rs_msg *msg)
{
  memset(d, 0, sizeof *d);
  d->path = path;
  d->msg = msg;
  const char *slash = strrchr(path, '/');
  d->dir = slash ? strndup(path, (size_t)(slash - path) + 1) : strdup("");
  if (!d->dir) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");

  int status = RS_OK;
  yaml_parser_t parser;
  if (!yaml_parser_initialize(&parser))
    return rs_msg_set(msg, RS_ERR_INTERNAL, "cannot initialize the YAML parser");
  yaml_parser_set_input_string(&parser, (const unsigned char *)text, len);
  if (!yaml_parser_load(&parser, &d->doc)) {
    status = parser_error(&parser, path, text, len, msg);
  } else {
    d->has_doc = 1;
    yaml_node_t *root = yaml_document_get_root_node(&d->doc);
    yaml_document_t extra;
    char got[96];
    if (!root) {
      status = rs_msg_set(msg, RS_ERR_INPUT,
                          "%s:1: the case file is empty (expected sections such as contact:, "
                          "grid:, material:)",
                          path);
    } else if (root->type != YAML_MAPPING_NODE) {
      status = rs_case_error(d, root, NULL,
                             "the case file must be a mapping of sections (contact:, grid:, ...), "
                             "got %s",
                             rs_case_describe(root, got, sizeof got));
    } else if (!yaml_parser_load(&parser, &extra)) {
      status = parser_error(&parser, path, text, len, msg);
    } else {
      yaml_node_t *second = yaml_document_get_root_node(&extra);
      if (second)
        status = rs_msg_set(msg, RS_ERR_INPUT,
                            "%s:%zu: a second YAML document (after ---); a case file holds one",
                            path, second->start_mark.line + 1);
      yaml_document_delete(&extra);
    }
  }
  yaml_parser_delete(&parser);
  return status;
}

void rs_case_doc_free(rs_case_doc *d)
{
  if (d->has_doc) yaml_document_delete(&d->doc);
  d->has_doc = 0;
  for (int i = 0; i < d->nsets; i++) free(d->sets[i].key);
  free(d->sets);
  free(d->dir);
  d->sets = NULL;
  d->dir = NULL;
  d->nsets = 0;
}

yaml_node_t *rs_case_doc_root(rs_case_doc *d)
{
  return d->has_doc ? yaml_document_get_root_node(&d->doc) : NULL;
}

/* ------------------------------------------------------------------ --set */

/* Copy node `index` of `src` (and everything under it) into the case document;
 * returns the new index, 0 when out of memory. */
static int copy_node(yaml_document_t *dst, yaml_document_t *src, int index)
{
  yaml_node_t *n = yaml_document_get_node(src, index);
  if (!n) return 0;
  switch (n->type) {
  case YAML_SCALAR_NODE:
    return yaml_document_add_scalar(dst, n->tag, n->data.scalar.value, (int)n->data.scalar.length,
                                    n->data.scalar.style);
  case YAML_SEQUENCE_NODE: {
    int seq = yaml_document_add_sequence(dst, n->tag, n->data.sequence.style);
    size_t count = (size_t)(n->data.sequence.items.top - n->data.sequence.items.start);
    for (size_t i = 0; seq && i < count; i++) {
      int item =
          copy_node(dst, src, yaml_document_get_node(src, index)->data.sequence.items.start[i]);
      if (!item || !yaml_document_append_sequence_item(dst, seq, item)) return 0;
    }
    return seq;
  }
  case YAML_MAPPING_NODE: {
    int map = yaml_document_add_mapping(dst, n->tag, n->data.mapping.style);
    size_t count = (size_t)(n->data.mapping.pairs.top - n->data.mapping.pairs.start);
    for (size_t i = 0; map && i < count; i++) {
      yaml_node_pair_t pair = yaml_document_get_node(src, index)->data.mapping.pairs.start[i];
      int key = copy_node(dst, src, pair.key);
      int value = key ? copy_node(dst, src, pair.value) : 0;
      if (!value || !yaml_document_append_mapping_pair(dst, map, key, value)) return 0;
    }
    return map;
  }
  default: return 0;
  }
}

/* Parse a --set VALUE as a YAML node and copy it into the case document. */
static int add_set_value(rs_case_doc *d, const char *key, const char *value, int *index)
{
  yaml_parser_t parser;
  yaml_document_t vdoc;
  if (!yaml_parser_initialize(&parser))
    return rs_msg_set(d->msg, RS_ERR_INTERNAL, "cannot initialize the YAML parser");
  yaml_parser_set_input_string(&parser, (const unsigned char *)value, strlen(value));
  int status = RS_OK;
  if (!yaml_parser_load(&parser, &vdoc)) {
    status = parser.error == YAML_MEMORY_ERROR ? RS_ERR_INTERNAL : RS_ERR_INPUT;
    status = rs_msg_set(d->msg, status, "--set %s: cannot read \"%s\" as a YAML value: %s", key,
                        value, parser.problem ? parser.problem : "syntax error");
  } else {
    if (yaml_document_get_root_node(&vdoc))
      *index = copy_node(&d->doc, &vdoc, 1);
    else /* an empty VALUE is null, as in "key:" */
      *index = yaml_document_add_scalar(&d->doc, NULL, (yaml_char_t *)"null", 4,
                                        YAML_PLAIN_SCALAR_STYLE);
    if (!*index) status = rs_msg_set(d->msg, RS_ERR_INTERNAL, "out of memory");
    yaml_document_delete(&vdoc);
  }
  yaml_parser_delete(&parser);
  return status;
}

/* Index of the value of `name` in mapping `map`, or 0; *pair_index gets the pair. */
static int find_pair(rs_case_doc *d, int map, const char *name, size_t *pair_index)
{
  yaml_node_t *m = yaml_document_get_node(&d->doc, map);
  size_t count = (size_t)(m->data.mapping.pairs.top - m->data.mapping.pairs.start);
  for (size_t i = 0; i < count; i++) {
    yaml_node_t *k = yaml_document_get_node(&d->doc, m->data.mapping.pairs.start[i].key);
    if (k && k->type == YAML_SCALAR_NODE && !strcmp((const char *)k->data.scalar.value, name)) {
      *pair_index = i;
      return m->data.mapping.pairs.start[i].value;
    }
  }
  return 0;
}

int rs_case_doc_set(rs_case_doc *d, const char *assignment)
{
  const char *eq = strchr(assignment, '=');
  if (!eq || eq == assignment)
    return rs_msg_set(d->msg, RS_ERR_INPUT,
                      "--set %s: expected KEY=VALUE with a dotted key, e.g. --set grid.cells=200",
                      assignment);
  rs_case_set_origin *grown = realloc(d->sets, (size_t)(d->nsets + 1) * sizeof *grown);
  if (!grown) return rs_msg_set(d->msg, RS_ERR_INTERNAL, "out of memory");
  d->sets = grown;
  rs_case_set_origin *origin = &d->sets[d->nsets];
  origin->first_node = origin->end_node = 0;
  origin->key = strndup(assignment, (size_t)(eq - assignment));
  if (!origin->key) return rs_msg_set(d->msg, RS_ERR_INTERNAL, "out of memory");
  d->nsets++;
  const char *key = origin->key;
  size_t keylen = strlen(key);
  if (key[0] == '.' || key[keylen - 1] == '.' || strstr(key, ".."))
    return rs_msg_set(d->msg, RS_ERR_INPUT, "--set %s: empty component in the dotted key", key);

  origin->first_node = (int)(d->doc.nodes.top - d->doc.nodes.start) + 1;
  origin->end_node = origin->first_node;
  int value = 0;
  int status = add_set_value(d, key, eq + 1, &value);
  if (status != RS_OK) return status;

  /* Walk the dotted key from the root, creating missing (or null) mappings. */
  int map = 1;
  d->sweep_node = 0;
  char part[256];
  for (const char *p = key;;) {
    /* Under sweep: the keys are dotted case keys themselves (sweep.rolling.creepage is
     * the key "rolling.creepage" of the sweep: mapping). */
    const char *dot = map != 1 && d->sweep_node == map ? NULL : strchr(p, '.');
    size_t len = dot ? (size_t)(dot - p) : strlen(p);
    if (len >= sizeof part) return rs_msg_set(d->msg, RS_ERR_INPUT, "--set %s: key too long", key);
    memcpy(part, p, len);
    part[len] = '\0';
    yaml_node_t *m = yaml_document_get_node(&d->doc, map);
    if (m->type != YAML_MAPPING_NODE)
      return rs_msg_set(d->msg, RS_ERR_INPUT, "--set %s: %.*s is not a mapping (line %zu of %s)",
                        key, (int)(p - key - 1), key, m->start_mark.line + 1, d->path);
    size_t pair = 0;
    int next = find_pair(d, map, part, &pair);
    if (!dot) { /* the last component: replace or add the value */
      if (next)
        yaml_document_get_node(&d->doc, map)->data.mapping.pairs.start[pair].value = value;
      else {
        int k = yaml_document_add_scalar(&d->doc, NULL, (yaml_char_t *)part, (int)len,
                                         YAML_PLAIN_SCALAR_STYLE);
        if (!k || !yaml_document_append_mapping_pair(&d->doc, map, k, value))
          return rs_msg_set(d->msg, RS_ERR_INTERNAL, "out of memory");
      }
      break;
    }
    if (!next || rs_case_is_null(yaml_document_get_node(&d->doc, next))) {
      int created = yaml_document_add_mapping(&d->doc, NULL, YAML_ANY_MAPPING_STYLE);
      if (!created) return rs_msg_set(d->msg, RS_ERR_INTERNAL, "out of memory");
      if (next)
        yaml_document_get_node(&d->doc, map)->data.mapping.pairs.start[pair].value = created;
      else {
        int k = yaml_document_add_scalar(&d->doc, NULL, (yaml_char_t *)part, (int)len,
                                         YAML_PLAIN_SCALAR_STYLE);
        if (!k || !yaml_document_append_mapping_pair(&d->doc, map, k, created))
          return rs_msg_set(d->msg, RS_ERR_INTERNAL, "out of memory");
      }
      next = created;
    }
    if (map == 1 && !strcmp(part, "sweep")) d->sweep_node = next;
    map = next;
    p = dot + 1;
  }
  origin->end_node = (int)(d->doc.nodes.top - d->doc.nodes.start) + 1;
  return RS_OK;
}

/* --------------------------------------------------------------- emission */

typedef struct text_sink {
  char *text;
  size_t len, cap;
} text_sink;

static int sink_write(void *data, unsigned char *buffer, size_t size)
{
  text_sink *s = data;
  if (s->len + size + 1 > s->cap) {
    size_t cap = s->cap ? s->cap : 1024;
    while (s->len + size + 1 > cap) cap *= 2;
    char *grown = realloc(s->text, cap);
    if (!grown) return 0;
    s->text = grown;
    s->cap = cap;
  }
  memcpy(s->text + s->len, buffer, size);
  s->len += size;
  s->text[s->len] = '\0';
  return 1;
}

int rs_case_doc_emit(rs_case_doc *d, char **text)
{
  yaml_emitter_t emitter;
  text_sink sink = {NULL, 0, 0};
  if (!yaml_emitter_initialize(&emitter))
    return rs_msg_set(d->msg, RS_ERR_INTERNAL, "cannot initialize the YAML emitter");
  yaml_emitter_set_output(&emitter, sink_write, &sink);
  yaml_emitter_set_unicode(&emitter, 1);
  yaml_emitter_set_width(&emitter, -1);
  yaml_emitter_set_indent(&emitter, 2);
  yaml_node_t *root = yaml_document_get_root_node(&d->doc);
  if (root && root->type == YAML_MAPPING_NODE) /* a file "{}" plus --set: print as a block */
    root->data.mapping.style = YAML_BLOCK_MAPPING_STYLE;
  int ok = yaml_emitter_open(&emitter);
  if (ok) {
    d->has_doc = 0; /* yaml_emitter_dump destroys the document, even on failure */
    ok = yaml_emitter_dump(&emitter, &d->doc) && yaml_emitter_close(&emitter) &&
         yaml_emitter_flush(&emitter);
  }
  yaml_emitter_delete(&emitter);
  if (!ok || !sink.text) {
    free(sink.text);
    return rs_msg_set(d->msg, RS_ERR_INTERNAL, "cannot write the case as YAML text");
  }
  *text = sink.text;
  return RS_OK;
}
