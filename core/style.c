/* Styles: names, needs and defaults (include/pointnpr/style.h). */
#include <pointnpr/style.h>

#include "internal.h"

#include <string.h>
#include <strings.h>

static const char *const style_names[PNPR_STYLE_COUNT_] = {"points", "sketchy", "lines", "stipple", "cartoon", "painterly", "brush", "hierarchy"};

const char *pnpr_style_name(pnpr_style s)
{
    return (unsigned)s < PNPR_STYLE_COUNT_ ? style_names[s] : "";
}

pnpr_status pnpr_style_from_name(const char *name, pnpr_style *r_style)
{
    if (!name || !r_style) return PNPR_ERR_INVALID_ARGUMENT;
    for (int i = 0; i < PNPR_STYLE_COUNT_; i++)
        if (!strcasecmp(name, style_names[i])) { *r_style = (pnpr_style)i; return PNPR_OK; }
    return PNPR_ERR_NOT_FOUND;
}

const char *pnpr_style_list(char *buf, size_t cap, const char *sep, uint32_t skip)
{
    return pnpr_join_names(buf, cap, sep, style_names, PNPR_STYLE_COUNT_, skip);
}

int pnpr_style_needs_features(pnpr_style s)
{
    return s == PNPR_STYLE_SKETCHY || s == PNPR_STYLE_STIPPLE || s == PNPR_STYLE_PAINTERLY;
}

/* Outlines by default: the line drawing and the cartoon are first of all outlines; the other
 * styles draw none unless asked (`outline` 1; the sketch reads well with a 1.5 px one, but the
 * outline passes would cost it more than issue 11's frame-time budget on llvmpipe:
 * docs/benchmarks.md). */
int pnpr_style_outline_default(pnpr_style s, float *r_width)
{
    /* points, sketchy, lines, stipple, cartoon, painterly, brush, hierarchy (which draws its own
     * silhouettes): on by default; width when drawn */
    static const int on[PNPR_STYLE_COUNT_] = {0, 0, 1, 0, 1, 0, 0, 0};
    static const float width[PNPR_STYLE_COUNT_] = {2, 1.5f, 2.5f, 1.5f, 2.5f, 2, 2, 2};
    int valid = (unsigned)s < PNPR_STYLE_COUNT_;
    if (r_width) *r_width = valid ? width[s] : 0;
    return valid && on[s];
}
