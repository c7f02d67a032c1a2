/* libFuzzer target for the style map parser (core/style_map.c, `render --style-map`). Each parse
 * must finish without crash, leak or undefined behaviour; a failure leaves a zeroed map and a
 * message "NAME:LINE: ..." with err.line set; a map that parses has at most one entry per 4 bytes
 * of text (a label, a space, a style name of at least 5 letters: no count is trusted), valid
 * styles only, and its entries printed as "LABEL STYLE" lines parse back to the same map. */
#include <pointnpr/style.h>

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int valid_style(pnpr_style s)
{
    return (unsigned)s < PNPR_STYLE_COUNT_;
}

/* The map printed back as a style map file (NULL when out of memory). */
static char *print_map(const pnpr_style_map *m, size_t *r_size)
{
    size_t cap = 64 + 32 * m->count, n = 0;
    char *t = malloc(cap);
    if (!t) return NULL;
    if (m->have_default) n += (size_t)snprintf(t + n, cap - n, "* %s\n", pnpr_style_name(m->default_style));
    for (size_t i = 0; i < m->count; i++)
        n += (size_t)snprintf(t + n, cap - n, "%u %s # entry\n", (unsigned)m->entries[i].label,
                              pnpr_style_name(m->entries[i].style));
    *r_size = n;
    return t;
}

static void check_round_trip(const pnpr_style_map *m)
{
    size_t n = 0;
    char *t = print_map(m, &n);
    if (!t) return;
    pnpr_style_map back;
    pnpr_error err;
    if (pnpr_style_map_parse(t, n, "back", &back, &err) != PNPR_OK || back.count != m->count ||
        back.have_default != m->have_default || (m->have_default && back.default_style != m->default_style))
        abort();
    for (size_t i = 0; i < m->count; i++)
        if (back.entries[i].label != m->entries[i].label || back.entries[i].style != m->entries[i].style) abort();
    pnpr_style_map_free(&back);
    free(t);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    pnpr_style_map map;
    pnpr_error err;
    memset(&err, 0, sizeof err);
    if (pnpr_style_map_parse((const char *)data, size, "map.txt", &map, &err) != PNPR_OK) {
        pnpr_style_map zero;
        memset(&zero, 0, sizeof zero);
        if (memcmp(&map, &zero, sizeof map) != 0 || strncmp(err.message, "map.txt:", 8) != 0 || err.line < 1) abort();
        return 0;
    }
    if (map.count > size / 4 || (map.have_default && !valid_style(map.default_style))) abort();
    for (size_t i = 0; i < map.count; i++)
        if (!valid_style(map.entries[i].style)) abort();
    check_round_trip(&map);
    pnpr_style_map_free(&map);
    return 0;
}
