/* The unit of a case key in the spelling of UDUNITS-2 (the units library CF names),
 * for netCDF `units` attributes: the key table (case_keys.c) spells units for
 * messages ("N/mm^2", "Hertz half-widths"); here every unit that is not a physical
 * unit (a count, a multiple of the Hertz half-width, a plain number) becomes "1". */
#include "io/case_internal.h"

#include <string.h>

const char *rs_case_key_units(const char *key)
{
  const int i = key ? rs_case_key_index(key) : -1;
  if (i < 0) return NULL;
  const char *unit = rs_case_keys[i].unit;
  if (!*unit || !strcmp(unit, "Hertz half-widths") || !strcmp(unit, "steps")) return "1";
  return unit;
}

const char *rs_case_key_unit_note(const char *key)
{
  const int i = key ? rs_case_key_index(key) : -1;
  if (i < 0) return "";
  const char *unit = rs_case_keys[i].unit;
  return !strcmp(unit, "Hertz half-widths") ? "in Hertz half-widths a" : "";
}
