/* The CLI's own option tables: the options that are not members of a library options struct
 * (those come from the library's tables, options.h, via cli_table_option). One entry per option:
 * its name, the kind of value, the member of the command's options struct it sets, its range or
 * its choices, and its help; one parser (cli_opts_parse) and one usage printer (cli_opts_usage)
 * serve every command, so a range or a message is written once. */
#ifndef PNPR_CLI_OPTS_H
#define PNPR_CLI_OPTS_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

typedef enum cli_kind {
    CLI_FLAG = 0, /* no value: the int member becomes 1 */
    CLI_INT,      /* an integer in [min, max] into an int member */
    CLI_UINT,     /* an integer in [min, max] (within 0..2^32-1) into a uint32_t member */
    CLI_NUMBER,   /* a finite number in [min, max] into a double member (min_excl: (min, max]) */
    CLI_TEXT,     /* the value itself into a const char * member */
    CLI_CHOICE,   /* one of `choices` (case-insensitive) into an int member: its index */
    CLI_LIST,     /* `count` comma-separated finite numbers into a double array member */
    CLI_CUSTOM,   /* parse(member, cmd, value): 1 taken, 0 refused (after saying why) */
    CLI_FLAG_CUSTOM /* no value: parse(member, cmd, NULL) as CLI_CUSTOM */
} cli_kind;

/* The value of max that means "no upper bound". */
#define CLI_UNBOUNDED 1e300

typedef struct cli_opt {
    const char *name;             /* "--threads" */
    const char *alias;            /* "-o", or NULL */
    cli_kind kind;
    size_t offset;                /* offsetof(the command's options struct, member) */
    double min, max;              /* CLI_INT, CLI_UINT, CLI_NUMBER: the range */
    int min_excl;                 /* CLI_NUMBER: min itself is refused */
    int count;                    /* CLI_LIST: how many numbers */
    const char *const *choices;   /* CLI_CHOICE: NULL-terminated */
    int (*parse)(void *member, const char *cmd, const char *value); /* CLI_CUSTOM */
    const char *metavar;          /* "N", "FILE" (NULL for flags and choices) */
    const char *help;             /* one line */
} cli_opt;

#define CLI_COUNT(t) (sizeof(t) / sizeof((t)[0]))

/* argv[*i] is one of the table's options: parses its value into the struct at opts (advancing *i)
 * and returns 1; not one of them: 0; a missing or bad value: prints "pointnpr CMD: --NAME wants
 * ..., got 'V'" and returns -1. */
int cli_opts_parse(const cli_opt *t, size_t n, void *opts, const char *cmd, int argc, char **argv, int *i);
/* The usage lines of the table's entries: "  --threads N          worker threads (in 1..1024)". */
void cli_opts_usage(FILE *f, const cli_opt *t, size_t n);
/* The entry called `name` ("--threads"), or NULL. */
const cli_opt *cli_opts_find(const cli_opt *t, size_t n, const char *name);
/* A continuation of a usage entry: text wrapped at 90 columns, indented under the help. */
void cli_usage_more(FILE *f, const char *text);
/* The index of v in choices (case-insensitive), or -1. */
int cli_choice_index(const char *const *choices, const char *v);
/* argv[i] = a, taken by no table: the input when it is the first operand (*in still NULL),
 * else says why not (an unknown option, with the usage; a second input) and returns 2; 0 ok. */
int cli_operand(const char *cmd, const char *a, const char **in, void (*usage)(FILE *f));

/* The options every file-writing command shares: -o/--output, --quiet, --help. */
typedef struct cli_common {
    const char *out;
    int quiet, help;
} cli_common;
extern const cli_opt cli_common_opts[3];

/* Worker threads: the one range of every command's --threads (core.h's PNPR_THREADS_MAX). */
#define CLI_THREADS_OPT(type, member)                                                                               \
    {"--threads", NULL, CLI_INT, offsetof(type, member), 1, PNPR_THREADS_MAX, 0, 0, NULL, NULL, "N",               \
     "worker threads, one per core when not given"}

/* --ascii: the point-cloud writers' ascii PLY (features, segment). */
#define CLI_ASCII_OPT(type, member)                                                                                 \
    {"--ascii", NULL, CLI_FLAG, offsetof(type, member), 0, 0, 0, 0, NULL, NULL, NULL,                                \
     "write ascii PLY (default binary little endian)"}

/* The drawing's style, sketch variant and outline switch, shared by render, animate and explain:
 * --style NAME (pnpr_style_from_name, any case) into a pnpr_style member; --sketch a|b|c into a
 * pnpr_sketch_variant member (a directional, b non-directional, c all); --outline on|off into
 * an int member (1 on, -1 off, 0 stays: the style's default). */
int cli_parse_style(void *member, const char *cmd, const char *value);
int cli_parse_on_off(void *member, const char *cmd, const char *value);
int cli_parse_sketch(void *member, const char *cmd, const char *value);
#define CLI_STYLE_OPT(type, member)                                                                                 \
    {"--style", NULL, CLI_CUSTOM, offsetof(type, member), 0, 0, 0, 0, NULL, cli_parse_style, "S",                    \
     "the drawing style (docs/rendering.md)"}
#define CLI_SKETCH_OPT(type, member)                                                                                \
    {"--sketch", NULL, CLI_CUSTOM, offsetof(type, member), 0, 0, 0, 0, NULL, cli_parse_sketch, "a|b|c",              \
     "sketchy variant of the paper's figure 9: a (directional strokes), b (+ non-directional hatches), "            \
     "c (+ dithering hatches; default)"}
#define CLI_OUTLINE_OPT(type, member, help)                                                                         \
    {"--outline", NULL, CLI_CUSTOM, offsetof(type, member), 0, 0, 0, 0, NULL, cli_parse_on_off, "on|off", help}

#endif
