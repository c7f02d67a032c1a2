/* The CLI's option tables (cli_opts.h): one parser and one usage printer for every command. */
#include "cli.h"
#include "cli_opts.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

const cli_opt cli_common_opts[3] = {
    {"--output", "-o", CLI_TEXT, offsetof(cli_common, out), 0, 0, 0, 0, NULL, NULL, "OUT", "the output file"},
    {"--quiet", NULL, CLI_FLAG, offsetof(cli_common, quiet), 0, 0, 0, 0, NULL, NULL, NULL, "no progress or summary"},
    {"--help", "-h", CLI_FLAG, offsetof(cli_common, help), 0, 0, 0, 0, NULL, NULL, NULL, "this text"},
};

const cli_opt *cli_opts_find(const cli_opt *t, size_t n, const char *name)
{
    for (size_t k = 0; k < n; k++)
        if (!strcmp(t[k].name, name) || (t[k].alias && !strcmp(t[k].alias, name))) return &t[k];
    return NULL;
}

int cli_choice_index(const char *const *choices, const char *v)
{
    for (int c = 0; choices && choices[c]; c++)
        if (!strcasecmp(choices[c], v)) return c;
    return -1;
}

/* "in 1..1024", "in (0, 1]", ">= 1", "> 0" */
static void range_text(const cli_opt *o, char *buf, size_t cap)
{
    if (o->max >= CLI_UNBOUNDED) snprintf(buf, cap, "%s %.10g", o->min_excl ? ">" : ">=", o->min);
    else if (o->kind == CLI_INT || o->kind == CLI_UINT) snprintf(buf, cap, "in %.10g..%.10g", o->min, o->max);
    else snprintf(buf, cap, "in %s%.10g, %.10g]", o->min_excl ? "(" : "[", o->min, o->max);
}

/* "a, b or c" */
static void choices_text(const char *const *choices, char *buf, size_t cap)
{
    size_t len = 0, n = 0;
    while (choices[n]) n++;
    buf[0] = 0;
    for (size_t c = 0; c < n && len < cap; c++)
        len += (size_t)snprintf(buf + len, cap - len, "%s%s", c == 0 ? "" : c + 1 == n ? " or " : ", ", choices[c]);
}

static int refuse(const cli_opt *o, const char *cmd, const char *v)
{
    char want[256];
    if (o->kind == CLI_CHOICE) choices_text(o->choices, want, sizeof want);
    else if (o->kind == CLI_LIST) snprintf(want, sizeof want, "%d comma-separated numbers (%s)", o->count, o->metavar);
    else {
        char range[64];
        range_text(o, range, sizeof range);
        snprintf(want, sizeof want, "%s %s", o->kind == CLI_NUMBER ? "a number" : "an integer", range);
    }
    fprintf(stderr, "pointnpr %s: %s wants %s, got '%s'\n", cmd, o->name, want, v);
    return -1;
}

static int take_value(const cli_opt *o, void *member, const char *cmd, const char *v)
{
    double x;
    int c;
    switch (o->kind) {
    case CLI_INT:
        if (!cli_parse_number(v, o->min, o->max, &x) || x != floor(x)) return refuse(o, cmd, v);
        *(int *)member = (int)x;
        return 1;
    case CLI_UINT:
        if (!cli_parse_number(v, o->min, o->max, &x) || x != floor(x) || x < 0 || x > 4294967295.0)
            return refuse(o, cmd, v);
        *(uint32_t *)member = (uint32_t)x;
        return 1;
    case CLI_NUMBER:
        if (!cli_parse_number(v, o->min, o->max, &x) || (o->min_excl && x == o->min)) return refuse(o, cmd, v);
        *(double *)member = x;
        return 1;
    case CLI_TEXT: *(const char **)member = v; return 1;
    case CLI_CHOICE:
        if ((c = cli_choice_index(o->choices, v)) < 0) return refuse(o, cmd, v);
        *(int *)member = c;
        return 1;
    case CLI_LIST: return cli_parse_list(v, o->count, (double *)member) ? 1 : refuse(o, cmd, v);
    case CLI_CUSTOM: return o->parse(member, cmd, v) ? 1 : -1;
    case CLI_FLAG:
    case CLI_FLAG_CUSTOM: break;
    }
    return -1;
}

int cli_opts_parse(const cli_opt *t, size_t n, void *opts, const char *cmd, int argc, char **argv, int *i)
{
    const cli_opt *o = cli_opts_find(t, n, argv[*i]);
    if (!o) return 0;
    void *member = (char *)opts + o->offset;
    if (o->kind == CLI_FLAG) { *(int *)member = 1; return 1; }
    if (o->kind == CLI_FLAG_CUSTOM) return o->parse(member, cmd, NULL) ? 1 : -1;
    if (*i + 1 >= argc) {
        fprintf(stderr, "pointnpr %s: %s needs a value (%s)\n", cmd, o->name, o->metavar ? o->metavar : "see --help");
        return -1;
    }
    int r = take_value(o, member, cmd, argv[*i + 1]);
    if (r > 0) (*i)++;
    return r;
}

/* Writes text word by word after a usage line's left column (at `indent`), breaking lines before
 * `width` columns onto continuation lines at the same indent. */
static void wrap(FILE *f, const char *text, int indent, int width)
{
    int col = indent - 1;
    while (*text) {
        while (*text == ' ') text++;
        int len = 0;
        while (text[len] && text[len] != ' ') len++;
        if (!len) break;
        if (col > indent - 1 && col + 1 + len > width) {
            fprintf(f, "\n%*s", indent - 1, "");
            col = indent - 1;
        }
        fputc(' ', f);
        for (int c = 0; c < len; c++) fputc(text[c] == '\x1f' ? ' ' : text[c], f); /* a space that never breaks */
        col += 1 + len;
        text += len;
    }
    fputc('\n', f);
}

void cli_opts_usage(FILE *f, const cli_opt *t, size_t n)
{
    for (size_t k = 0; k < n; k++) {
        const cli_opt *o = &t[k];
        char left[80], extra[256] = "";
        if (o->kind == CLI_CHOICE) {
            size_t len = 0;
            char names[200] = "";
            for (int c = 0; o->choices[c] && len < sizeof names; c++)
                len += (size_t)snprintf(names + len, sizeof names - len, "%s%s", c ? "|" : "", o->choices[c]);
            snprintf(left, sizeof left, "%s%s%s %s", o->alias ? o->alias : "", o->alias ? ", " : "", o->name, names);
        } else
            snprintf(left, sizeof left, "%s%s%s%s%s", o->alias ? o->alias : "", o->alias ? ", " : "", o->name,
                     o->metavar ? " " : "", o->metavar ? o->metavar : "");
        if (o->kind == CLI_INT || o->kind == CLI_UINT || o->kind == CLI_NUMBER) {
            char range[64];
            range_text(o, range, sizeof range);
            snprintf(extra, sizeof extra, " (%s)", range);
            for (char *c = extra + 1; *c; c++)
                if (*c == ' ') *c = '\x1f'; /* the range stays on one line */
        }
        if (strlen(left) > 20) fprintf(f, "  %s\n%22s", left, "");
        else fprintf(f, "  %-20s", left);
        char text[512];
        snprintf(text, sizeof text, "%s%s", o->help, extra);
        wrap(f, text, 23, 90);
    }
}

int cli_operand(const char *cmd, const char *a, const char **in, void (*usage)(FILE *f))
{
    if (a[0] == '-' && a[1]) {
        fprintf(stderr, "pointnpr %s: unknown option or missing value: %s\n", cmd, a);
        if (usage) usage(stderr);
        return 2;
    }
    if (*in) {
        fprintf(stderr, "pointnpr %s: more than one input given ('%s')\n", cmd, a);
        return 2;
    }
    *in = a;
    return 0;
}

int cli_parse_sketch(void *member, const char *cmd, const char *v)
{
    static const pnpr_sketch_variant variants[3] = {PNPR_SKETCH_DIRECTIONAL, PNPR_SKETCH_NONDIRECTIONAL, PNPR_SKETCH_ALL};
    if ((v[0] | 0x20) >= 'a' && (v[0] | 0x20) <= 'c' && !v[1]) {
        *(pnpr_sketch_variant *)member = variants[(v[0] | 0x20) - 'a'];
        return 1;
    }
    fprintf(stderr, "pointnpr %s: --sketch wants a, b or c, got '%s'\n", cmd, v);
    return 0;
}

void cli_usage_more(FILE *f, const char *text)
{
    fprintf(f, "%22s", "");
    wrap(f, text, 23, 90);
}

int cli_parse_style(void *member, const char *cmd, const char *v)
{
    pnpr_style s;
    if (pnpr_style_from_name(v, &s) == PNPR_OK) { *(pnpr_style *)member = s; return 1; }
    char names[160];
    fprintf(stderr, "pointnpr %s: --style wants one of %s, got '%s'\n", cmd, pnpr_style_list(names, sizeof names, ", ", 0), v);
    return 0;
}

int cli_parse_on_off(void *member, const char *cmd, const char *v)
{
    if (!strcasecmp(v, "on") || !strcasecmp(v, "off")) { *(int *)member = !strcasecmp(v, "on") ? 1 : -1; return 1; }
    fprintf(stderr, "pointnpr %s: --outline wants on or off, got '%s'\n", cmd, v);
    return 0;
}
