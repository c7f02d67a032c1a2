/* The table-writing macros shared by the options tables (filters/options_table.c,
 * core/options_render.c; not installed). */
#ifndef PNPR_OPTIONS_INTERNAL_H
#define PNPR_OPTIONS_INTERNAL_H

#include <pointnpr/options.h>

#include <stddef.h>

#define UNB PNPR_OPTION_UNBOUNDED
#define EXCL PNPR_OPTION_MIN_EXCLUSIVE
#define NEG_OFF PNPR_OPTION_NEGATIVE_OFF
#define ZERO_VALUE PNPR_OPTION_ZERO_IS_VALUE
/* name, struct, member, type, default, min, max, flags, auto scale, auto text, help */
#define OPT(group, S, name, m, type, def, lo, hi, flags, scale, atext, help)                                          \
    { name, #m, group, PNPR_OPTION_##type, offsetof(S, m), def, lo, hi, flags, scale, atext, help }
#define COUNT(t) (sizeof(t) / sizeof((t)[0]))

#endif
