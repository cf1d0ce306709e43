/* The wheel-rail contact of a case's profiles: block for `rollsim check` (docs/case-file.md
 * "profiles:", docs/model.md §20). */
#ifndef ROLLSIM_WHEEL_RAIL_H
#define ROLLSIM_WHEEL_RAIL_H

#include <stdio.h>

#include "io/case.h"
#include "base/status.h"

/* With profiles.vertical_load: the patches, the load sharing and each patch's normal
 * solution, printed as `key: value  # comment` lines. Nothing without it. */
int rs_wheel_rail_print(const rs_case *c, FILE *out, rs_msg *msg);
/* 1 when the case's contact comes from its profiles (profiles.vertical_load given): the
 * contact: block's derived values (Hertz, the grid) do not describe it. */
int rs_wheel_rail_given(const rs_case *c);

#endif
