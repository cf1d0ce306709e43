/* Prints the case-file key table (src/io/case_keys.c), one key a line:
 *   dotted.key <TAB> kind <TAB> unit <TAB> choice,choice,...
 * for the check that docs/case-file.md documents exactly these keys. */
#include <stdio.h>

#include "io/case_internal.h"

int main(void)
{
  static const char *const kinds[] = {"section", "opaque", "number",  "integer", "long",
                                      "text",    "choice", "history", "fields",  "protocol",
                                      "range",   "vector", "ttable"};
  /* one name per rs_case_key_kind: a kind added there must be named here */
  _Static_assert(sizeof kinds / sizeof kinds[0] == RS_KEY_TTABLE + 1, "a key kind has no name");
  for (size_t i = 0; i < rs_case_nkeys; i++) {
    const rs_case_key *k = &rs_case_keys[i];
    printf("%s\t%s\t%s\t", k->path, kinds[k->kind], k->unit);
    const char *const *c = k->kind == RS_KEY_FIELDS ? rs_case_field_names : k->choices;
    for (int j = 0; c && c[j]; j++) printf("%s%s", j ? "," : "", c[j]);
    putchar('\n');
  }
  return 0;
}
