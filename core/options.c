/* Working with the options tables of options.h: find, get/set, defaults, range checks, text.
 * The tables themselves are in filters/options_table.c and core/options_render.c. */
#include <pointnpr/options.h>

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

const pnpr_option_desc *pnpr_option_find(const pnpr_option_desc *table, size_t count, const char *name)
{
    for (size_t i = 0; table && name && i < count; i++)
        if (!strcmp(table[i].name, name)) return &table[i];
    return NULL;
}

double pnpr_option_get(const pnpr_option_desc *d, const void *opts)
{
    const char *p = (const char *)opts + d->offset;
    switch (d->type) {
    case PNPR_OPTION_INT: { int v; memcpy(&v, p, sizeof v); return v; }
    case PNPR_OPTION_UINT: { uint32_t v; memcpy(&v, p, sizeof v); return v; }
    case PNPR_OPTION_FLOAT: { float v; memcpy(&v, p, sizeof v); return v; }
    default: { double v; memcpy(&v, p, sizeof v); return v; }
    }
}

void pnpr_option_set(const pnpr_option_desc *d, void *opts, double value)
{
    char *p = (char *)opts + d->offset;
    switch (d->type) {
    case PNPR_OPTION_INT: { int v = (int)value; memcpy(p, &v, sizeof v); break; }
    case PNPR_OPTION_UINT: { uint32_t v = (uint32_t)value; memcpy(p, &v, sizeof v); break; }
    case PNPR_OPTION_FLOAT: { float v = (float)value; memcpy(p, &v, sizeof v); break; }
    default: memcpy(p, &value, sizeof value); break;
    }
}

void pnpr_option_set_defaults(const pnpr_option_desc *table, size_t count, void *opts)
{
    for (size_t i = 0; i < count; i++)
        pnpr_option_set(&table[i], opts, (table[i].flags & PNPR_OPTION_STYLE_DEFAULT) ? 0 : table[i].def);
}

void pnpr_option_fill_defaults(const pnpr_option_desc *table, size_t count, void *opts)
{
    for (size_t i = 0; i < count; i++)
        if (!(table[i].flags & (PNPR_OPTION_ZERO_IS_VALUE | PNPR_OPTION_STYLE_DEFAULT)) &&
            pnpr_option_get(&table[i], opts) == 0)
            pnpr_option_set(&table[i], opts, table[i].def);
}

static int is_integer_type(const pnpr_option_desc *d)
{
    return d->type == PNPR_OPTION_INT || d->type == PNPR_OPTION_UINT;
}

/* The largest value the member can hold when the table says "unbounded". */
static double type_max(const pnpr_option_desc *d)
{
    return d->type == PNPR_OPTION_INT ? (double)INT32_MAX : d->type == PNPR_OPTION_UINT ? (double)UINT32_MAX : HUGE_VAL;
}

static double range_max(const pnpr_option_desc *d)
{
    return d->max >= PNPR_OPTION_UNBOUNDED ? type_max(d) : d->max;
}

/* A float member holds the float nearest to the value given: compared in float precision, so that
 * the float nearest to a bound (0.34f > 0.34) is that bound. */
static double in_precision(const pnpr_option_desc *d, double v)
{
    return d->type == PNPR_OPTION_FLOAT && fabs(v) <= FLT_MAX ? (double)(float)v : v;
}

int pnpr_option_in_range(const pnpr_option_desc *d, double value)
{
    if (!isfinite(value)) return 0;
    value = in_precision(d, value);
    double lo = in_precision(d, d->min);
    if (value > in_precision(d, range_max(d))) return 0;
    if (is_integer_type(d) && value != floor(value)) return 0;
    return (d->flags & PNPR_OPTION_MIN_EXCLUSIVE) ? value > lo : value >= lo;
}

void pnpr_option_range_text(const pnpr_option_desc *d, char *buf, size_t cap)
{
    const int excl = (d->flags & PNPR_OPTION_MIN_EXCLUSIVE) != 0;
    if (d->max >= PNPR_OPTION_UNBOUNDED) snprintf(buf, cap, "%s %g", excl ? ">" : ">=", d->min);
    else if (is_integer_type(d)) snprintf(buf, cap, "in %g..%g", d->min, d->max);
    else snprintf(buf, cap, "in %s%g, %g]", excl ? "(" : "[", d->min, d->max);
}

void pnpr_option_default_text(const pnpr_option_desc *d, char *buf, size_t cap)
{
    if (d->def != 0 || !d->auto_text) snprintf(buf, cap, "%g", d->def);
    else if (d->auto_scale != 0 && d->auto_scale != 1) snprintf(buf, cap, "%g%s", d->auto_scale, d->auto_text);
    else snprintf(buf, cap, "%s", d->auto_text);
}

static pnpr_status option_error(const pnpr_option_desc *d, double v, pnpr_error *err)
{
    char range[64], def[64];
    pnpr_option_range_text(d, range, sizeof range);
    pnpr_option_default_text(d, def, sizeof def);
    if (d->flags & PNPR_OPTION_ZERO_IS_VALUE)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "%s: %s %g is not %s", d->group, d->field, v, range);
    return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "%s: %s %g is not %s (0 = %s%s)", d->group, d->field, v,
                          range, def, (d->flags & PNPR_OPTION_NEGATIVE_OFF) ? ", negative = none" : "");
}

pnpr_status pnpr_option_check(const pnpr_option_desc *table, size_t count, const void *opts, pnpr_error *err)
{
    for (size_t i = 0; opts && i < count; i++) {
        const pnpr_option_desc *d = &table[i];
        double v = pnpr_option_get(d, opts);
        if (v == 0 && !(d->flags & PNPR_OPTION_ZERO_IS_VALUE)) continue;
        if (v < 0 && isfinite(v) && (d->flags & PNPR_OPTION_NEGATIVE_OFF)) continue;
        if (!pnpr_option_in_range(d, v)) return option_error(d, v, err);
    }
    return PNPR_OK;
}
