/* Style map files (style.h, docs/rendering.md): "LABEL STYLE" and "* STYLE" lines, parsed from
 * memory so that the parser is fuzzed (tests/fuzz_stylemap.c). Errors name NAME:LINE. */
#include "internal.h"

#include <pointnpr/style.h>

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void pnpr_style_map_free(pnpr_style_map *map)
{
    if (!map) return;
    free(map->entries);
    memset(map, 0, sizeof *map);
}

static pnpr_status map_fail(pnpr_error *err, const char *name, long line, const char *what)
{
    pnpr_status st = pnpr_error_set(err, PNPR_ERR_FORMAT, "%s:%ld: %s", name, line, what);
    if (err) err->line = line;
    return st;
}

static pnpr_status map_add(pnpr_style_map *m, size_t *cap, uint32_t label, pnpr_style s, const char *name,
                           pnpr_error *err)
{
    if (m->count == *cap) {
        size_t c2 = *cap ? 2 * *cap : 16;
        pnpr_style_map_entry *e2 = realloc(m->entries, c2 * sizeof *e2);
        if (!e2) return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s: out of memory", name);
        m->entries = e2;
        *cap = c2;
    }
    m->entries[m->count].label = label;
    m->entries[m->count].style = s;
    m->count++;
    return PNPR_OK;
}

/* One line without its comment: blank, "* STYLE" or "LABEL STYLE". */
static pnpr_status map_line(pnpr_style_map *m, size_t *cap, char *line, long ln, const char *name, pnpr_error *err)
{
    char *hash = strchr(line, '#');
    if (hash) *hash = 0;
    char a[256], b[256], extra[2];
    int got = sscanf(line, "%255s %255s %1s", a, b, extra);
    if (got <= 0) return PNPR_OK; /* blank */
    pnpr_style s;
    if (got != 2) return map_fail(err, name, ln, "want 'LABEL STYLE' or '* STYLE'");
    if (pnpr_style_from_name(b, &s) != PNPR_OK) {
        char what[400], names[160];
        snprintf(what, sizeof what, "unknown style '%s' (%s)", b, pnpr_style_list(names, sizeof names, ", ", 0));
        return map_fail(err, name, ln, what);
    }
    if (!strcmp(a, "*")) {
        m->default_style = s;
        m->have_default = 1;
        return PNPR_OK;
    }
    char *end;
    errno = 0;
    unsigned long long v = strtoull(a, &end, 10);
    if (errno || end == a || *end || a[0] == '-' || v > 0xFFFFFFFFull) {
        char what[400];
        snprintf(what, sizeof what, "label '%s' is not an integer in 0..4294967295 or '*'", a);
        return map_fail(err, name, ln, what);
    }
    return map_add(m, cap, (uint32_t)v, s, name, err);
}

pnpr_status pnpr_style_map_parse(const char *text, size_t size, const char *name, pnpr_style_map *r_map,
                                 pnpr_error *err)
{
    if (!r_map || (!text && size) || !name) return PNPR_ERR_INVALID_ARGUMENT;
    memset(r_map, 0, sizeof *r_map);
    char line[1024];
    size_t pos = 0, cap = 0;
    long ln = 0;
    pnpr_status st = PNPR_OK;
    for (int got; st == PNPR_OK && (got = pnpr_text_line(text, size, &pos, line, sizeof line)) != 0;) {
        ln++;
        st = got < 0 ? map_fail(err, name, ln, "line longer than 1022 characters")
                     : map_line(r_map, &cap, line, ln, name, err);
    }
    if (st != PNPR_OK) pnpr_style_map_free(r_map);
    return st;
}
