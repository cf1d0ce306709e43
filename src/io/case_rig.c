/* The twin_disc: protocol (interfaces: README "Twin-disc rig"): a list of steps,
 *   - {slip: 0.01, revolutions: 20}      slip held for 20 revolutions of disc 1
 *   - {ramp_to: 0.03, revolutions: 300}  slip ramped linearly from the previous value
 * The slip is the rig's s = (V1 - V2)/V (a fraction: 0.03 = 3 %). */
#include <math.h>
#include <stdlib.h>

#include "io/case_internal.h"

int rs_case_protocol(const rs_case_doc *d, const yaml_node_t *n, const char *key, rs_twin_disc *rig)
{
  char got[96];
  static const char *const allowed[] = {"slip", "ramp_to", "revolutions", NULL};
  if (n->type != YAML_SEQUENCE_NODE || n->data.sequence.items.top == n->data.sequence.items.start)
    return rs_case_error(d, n, key,
                         "expected a non-empty list of steps {slip: S, revolutions: N} or "
                         "{ramp_to: S, revolutions: N}, got %s",
                         rs_case_describe(n, got, sizeof got));
  const size_t count = (size_t)(n->data.sequence.items.top - n->data.sequence.items.start);
  free(rig->steps);
  rig->nsteps = 0;
  if (!(rig->steps = calloc(count, sizeof *rig->steps)))
    return rs_msg_set(d->msg, RS_ERR_INTERNAL, "out of memory");
  double previous = 0.0;
  for (size_t i = 0; i < count; i++) {
    const yaml_node_t *item =
        yaml_document_get_node((yaml_document_t *)&d->doc, n->data.sequence.items.start[i]);
    if (!item || item->type != YAML_MAPPING_NODE)
      return rs_case_error(d, item, key,
                           "step %zu: expected {slip: S, revolutions: N} or "
                           "{ramp_to: S, revolutions: N}, got %s",
                           i + 1, rs_case_describe(item, got, sizeof got));
    int status = rs_case_check_mapping(d, item, key, allowed);
    if (status != RS_OK) return status;
    const yaml_node_t *held = rs_case_lookup(d, item, "slip"),
                      *ramp = rs_case_lookup(d, item, "ramp_to"),
                      *revs = rs_case_lookup(d, item, "revolutions");
    if (!!held == !!ramp)
      return rs_case_error(d, item, key,
                           "step %zu: give slip (held) or ramp_to (ramped from the "
                           "previous slip), one of the two",
                           i + 1);
    if (!revs)
      return rs_case_error(d, item, key, "step %zu: give its length in revolutions of disc 1",
                           i + 1);
    rs_rig_step *st = &rig->steps[i];
    double slip;
    if ((status = rs_case_number(d, held ? held : ramp, key, &slip)) != RS_OK ||
        (status = rs_case_number(d, revs, key, &st->revolutions)) != RS_OK)
      return status;
    if (!(fabs(slip) < 1.0))
      return rs_case_error(d, held ? held : ramp, key,
                           "step %zu: slip %g is not a fraction in (-1, 1) (0.03 = 3 %%)", i + 1,
                           slip);
    if (!(st->revolutions > 0.0 && st->revolutions <= 1e7))
      return rs_case_error(d, revs, key, "step %zu: revolutions must be in (0, 1e7], got %g", i + 1,
                           st->revolutions);
    st->slip_start = held ? slip : previous;
    st->slip_end = slip;
    previous = slip;
    rig->nsteps = i + 1;
  }
  return RS_OK;
}

void rs_case_print_protocol(const rs_twin_disc *rig, FILE *out)
{
  char a[32], b[32];
  fputc('[', out);
  for (size_t i = 0; i < rig->nsteps; i++) {
    const rs_rig_step *st = &rig->steps[i];
    if (st->slip_start == st->slip_end)
      fprintf(out, "%s{slip: %s, revolutions: %s}", i ? ", " : "", rs_case_fmt(st->slip_end, a, 32),
              rs_case_fmt(st->revolutions, b, 32));
    else
      fprintf(out, "%s{ramp_to: %s, revolutions: %s}", i ? ", " : "",
              rs_case_fmt(st->slip_end, a, 32), rs_case_fmt(st->revolutions, b, 32));
  }
  fputc(']', out);
}
