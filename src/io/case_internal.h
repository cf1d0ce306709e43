/* Internal to the case-file module: the YAML document with the origin of every
 * node (file line or --set), typed values read from nodes, and the key table.
 *   case_yaml.c     read and parse the file, apply --set, emit the document as run
 *   case_values.c   node -> number/text/choice with file:line messages
 *   case_keys.c     the table of keys and the walk that fills an rs_case
 *   case_history.c  history values (number, ramp, steps, sine, CSV table)
 *   case.c          rs_case_load/derive/free/print, cross-key rules, derived values */
#ifndef ROLLSIM_CASE_INTERNAL_H
#define ROLLSIM_CASE_INTERNAL_H

#include <stddef.h>
#include <yaml.h>

#include "io/case.h"

/* ---- case_yaml.c: the document ---- */

typedef struct rs_case_set_origin {
  int first_node, end_node; /* nodes [first_node, end_node) were created by this --set */
  char *key;                /* its dotted key */
} rs_case_set_origin;

/* A node standing for a typed override (rs_case_derive): not in the document; messages
 * about it read "--set KEY: ...". */
typedef struct rs_case_override_origin {
  const yaml_node_t *node;
  const char *key;
} rs_case_override_origin;

typedef struct rs_case_doc {
  yaml_document_t doc;
  int has_doc;
  const char *path; /* the case file as given */
  char *dir;        /* its directory (tables are relative to it), "" for the cwd */
  rs_case_set_origin *sets;
  int nsets;
  const rs_case_override_origin *overrides; /* typed overrides being applied, or NULL */
  int noverrides;
  int sweep_node; /* scratch of rs_case_doc_set: the sweep: mapping while walking a key */
  rs_msg *msg;
} rs_case_doc;

/* The case file's text (NUL-terminated), and the document parsed from it. */
int rs_case_doc_read(const char *path, char **text, size_t *len, rs_msg *msg);
int rs_case_doc_parse(rs_case_doc *d, const char *path, const char *text, size_t len, rs_msg *msg);
/* Apply one --set KEY=VALUE (VALUE parsed as YAML), creating missing parent mappings. */
int rs_case_doc_set(rs_case_doc *d, const char *assignment);
/* Emit the (modified) document as YAML text. Consumes the document. */
int rs_case_doc_emit(rs_case_doc *d, char **text);
void rs_case_doc_free(rs_case_doc *d);
yaml_node_t *rs_case_doc_root(rs_case_doc *d);

/* ---- case_values.c: reading nodes ---- */

/* Error about `node` (NULL: the document root) and dotted `key` (may be NULL):
 *   "case.yaml:12: key: what"  or  "--set key: what". Returns RS_ERR_INPUT. */
int rs_case_error(const rs_case_doc *d, const yaml_node_t *node, const char *key, const char *fmt,
                  ...) __attribute__((format(printf, 4, 5)));

int rs_case_is_null(const yaml_node_t *n);
/* Short description of a node for "got ..." (writes into buf). */
const char *rs_case_describe(const yaml_node_t *n, char *buf, size_t len);
/* Scalar conversions; on error they set the message (with key and unit) and return RS_ERR_INPUT. */
int rs_case_number(const rs_case_doc *d, const yaml_node_t *n, const char *key, double *out);
int rs_case_text(const rs_case_doc *d, const yaml_node_t *n, const char *key, char **out);
int rs_case_choice(const rs_case_doc *d, const yaml_node_t *n, const char *key,
                   const char *const *choices, int *out);
/* Keys of a mapping node are plain scalars listed in `allowed` (NULL-terminated), each once. */
int rs_case_check_mapping(const rs_case_doc *d, const yaml_node_t *map, const char *key,
                          const char *const *allowed);
/* Value node of `name` in a mapping, or NULL. */
yaml_node_t *rs_case_lookup(const rs_case_doc *d, const yaml_node_t *map, const char *name);
/* Format a double so that it reads back exactly, shortest of %.15g / %.17g. */
const char *rs_case_fmt(double x, char *buf, size_t len);

/* ---- case_keys.c: the key table and the parsing of the document into a case ---- */

typedef enum rs_case_key_kind {
  RS_KEY_SECTION,  /* a mapping of keys */
  RS_KEY_OPAQUE,   /* a mapping accepted as is (sweep:, handled elsewhere) */
  RS_KEY_NUMBER,   /* double */
  RS_KEY_INTEGER,  /* int */
  RS_KEY_LONG,     /* long */
  RS_KEY_TEXT,     /* char * */
  RS_KEY_CHOICE,   /* int (an enum), one of `choices` */
  RS_KEY_HISTORY,  /* rs_history */
  RS_KEY_FIELDS,   /* unsigned mask of RS_FIELD_* */
  RS_KEY_PROTOCOL, /* rs_twin_disc steps: a list of {slip|ramp_to, revolutions} (case_rig.c) */
  RS_KEY_RANGE,    /* double[2]: [lo, hi] with lo < hi, each within the key's range */
  RS_KEY_VECTOR,   /* rs_case_vec: a number or a list of two (2D / 3D), each within range */
  RS_KEY_TTABLE    /* rs_history (kind table): {temperature: [...], <choices[1]>: [...]}, the
                      temperatures strictly increasing, the values within range */
} rs_case_key_kind;

enum {
  RS_KEY_LO_OPEN = 1 << 0,   /* lo excluded */
  RS_KEY_HI_OPEN = 1 << 1,   /* hi excluded */
  RS_KEY_NULLABLE = 1 << 2,  /* null = the default */
  RS_KEY_DERIVED = 1 << 3,   /* not stored as given (k_rel), printed from the case */
  RS_KEY_HI_ABSURD = 1 << 4, /* hi is a sanity bound, not a physical one */
  RS_KEY_WHOLE = 1 << 5,     /* RS_KEY_VECTOR of whole numbers */
  RS_KEY_AUTO = 1 << 7,      /* RS_KEY_NUMBER that may be `auto` (stored as 0) */
  RS_KEY_XY = 1 << 6,        /* RS_KEY_HISTORY that may be a list [x, y] of two histories (3D),
                                the second into the rs_history after the field */
  RS_KEY_BODIES = 1 << 8     /* RS_KEY_VECTOR of one value per body [body 1, body 2] (one
                                number: both bodies) instead of [x, y] */
};
#define RS_KEY_NO_FIELD ((size_t)-1) /* accepted and checked, nothing to store (friction.law) */

/* A number or a list of two (keys whose value is one number in 2D and two in 3D). */
typedef struct rs_case_vec {
  int n; /* values given: 1 or 2 */
  double v[2];
} rs_case_vec;

/* The case being built: the public case plus what is given but not stored as such
 * (resolved into the case by dimension in case.c). */
typedef struct rs_case_input {
  rs_case c;
  double k_rel;
  rs_case_vec radius, curvature, cells, extent;
  rs_case_vec mu_excess, half_velocity; /* friction: one or two terms */
  int force_n; /* rolling.tangential_force: 1 history, or 2 ([Fx, Fy], 3D) */
  rs_case_vec t_bulk, t_conductivity, t_heat_capacity, t_density; /* temperature: per body */
  rs_case_vec t_disc_mass;                                        /* temperature.disc_mass */
} rs_case_input;

typedef struct rs_case_key {
  const char *path; /* dotted key */
  rs_case_key_kind kind;
  size_t offset; /* into rs_case_input */
  const char *unit;
  double lo, hi; /* allowed range of numbers and integers (RS_KEY_*_OPEN in flags) */
  unsigned flags;
  const char *const *choices;
} rs_case_key;

extern const rs_case_key rs_case_keys[];
extern const size_t rs_case_nkeys;
extern const char *const rs_case_field_names[]; /* bit i of the mask, NULL-terminated */

/* Parse the document into `in` (defaults already set); where[i] is the value node of
 * rs_case_keys[i] when given (NULL otherwise). */
int rs_case_parse(rs_case_doc *d, rs_case_input *in, const yaml_node_t **where);
/* A key's unit in a contact of `dimension`: forces given per width in 2D ("N/mm") are
 * totals in 3D ("N"); other units as they are. */
const char *rs_case_key_unit_in(const char *unit, int dimension);
/* Parse the value node n of key `spec` into `in` (as rs_case_parse does for each key). */
int rs_case_parse_value(const rs_case_doc *d, const rs_case_key *spec, const yaml_node_t *n,
                        rs_case_input *in);
/* Check a number against the key's range (message with the key and unit). */
int rs_case_check_range(const rs_case_doc *d, const yaml_node_t *n, const rs_case_key *spec,
                        const char *key, double x);

/* ---- case.c: a loaded case file, the source of derived cases ---- */

/* What rs_case_load keeps in the case (rs_case.source): the document after --set (for
 * messages and the sweep: and fit: blocks) and the keys parsed from it before the
 * cross-key rules, to which rs_case_derive applies typed overrides. Read-only once
 * loaded: cases are derived from it on several threads at once. */
struct rs_case_source {
  char *path; /* the case file as given */
  char *text; /* its text */
  size_t len;
  char **sets; /* the --set assignments [nsets] */
  int nsets;
  rs_case_doc doc;           /* the document after --set (doc.msg unused: each use sets its own) */
  rs_case_input in;          /* the keys as parsed, before the cross-key rules */
  const yaml_node_t **where; /* [rs_case_nkeys] value nodes of the given keys */
  int *sorted;               /* [rs_case_nkeys] the key table's indices by path */
};

/* The document of a loaded case for reading, its messages into msg. */
rs_case_doc rs_case_source_doc(const rs_case *c, rs_msg *msg);

/* ---- case_history.c: a history node (number, ramp, steps, sine, table) ---- */
int rs_case_history(const rs_case_doc *d, const yaml_node_t *n, const char *key, const char *unit,
                    rs_history *h);

/* ---- case_profiles.c: the profiles: block (read by rs_case_load only) ---- */
int rs_case_profiles_read(const rs_case_doc *d, struct rs_wheel_rail **out);

/* ---- case_rig.c: the twin_disc: block ---- */
int rs_case_protocol(const rs_case_doc *d, const yaml_node_t *n, const char *key,
                     rs_twin_disc *rig);
void rs_case_print_protocol(const rs_twin_disc *rig, FILE *out);
#endif
