/* Pipeline files (effects.h; Wegen et al. section 4.2): a tree of nodes, each a group of segment
 * labels with its own rasterisation and effect chain, parsed from memory so that the parser is
 * fuzzed (tests/fuzz_pipeline.c). Errors name NAME:LINE.
 *
 * Format. Plain text, one statement per line; '#' starts a comment (to the end of the line);
 * blank lines are ignored; a line holds at most 1023 characters (a '\r' before the '\n' is not
 * counted and is dropped, so CRLF files parse the same; a NUL byte ends a line's content). Tokens
 * are separated by spaces and tabs. Keywords, effect, parameter, style, preset and layering names
 * ignore case; node names do not.
 *
 * Statements before the first `node` line configure the root: node 0, named "root", which draws
 * every label that no node lists. Root defaults: style points, size 0 (the renderer's default),
 * per_label off, inpaint on with threshold=PNPR_INPAINT_THRESHOLD radius=PNPR_INPAINT_RADIUS,
 * an empty chain; layering inpainted.
 *
 *   layering inpainted|fragment|none
 *       Global compositing mode (pipeline.layering), allowed anywhere; the last one counts.
 *   node NAME [parent PARENT] [labels SPEC...]
 *       Starts a new node, which the following statements configure. NAME: 1..63 characters of
 *       A-Z a-z 0-9 _ . -, unique, not "root". PARENT: the name of an earlier node or root (the
 *       default). SPEC (the rest of the line): labels N (0..4294967295) and ranges A-B (A <= B,
 *       at most 16777216 labels per range), separated by commas and/or blanks (empty items
 *       between commas are skipped), at least one. The node stores its labels sorted and
 *       deduplicated. At most 16777216 labels are listed in a file (counted as written, ranges
 *       in full, repeats included) and at most 65536 nodes (root included). A node starts as a copy of its parent's configuration (style, size,
 *       per_label, inpaint and its options, chain) as it stands at the `node` line.
 *       A label listed by several nodes belongs to the last of them.
 *   style NAME          The node's rasterisation style (pnpr_style_from_name), not `lines`.
 *   size X              point_scale, a number in 0.05..20.
 *   per_label on|off    One layer per label instead of one for the node.
 *   inpaint off         No depth inpainting for the node's layers.
 *   inpaint [on] [threshold=T] [radius=R]
 *                       Inpainting on; T in (0, 1], R an integer in 1..PNPR_INPAINT_RADIUS_MAX;
 *                       options not named keep their inherited values.
 *   EFFECT [PARAM=VALUE...]
 *                       EFFECT a name of pnpr_effect_from_name. When the node's chain (inherited
 *                       or not) has an effect of that kind, its last one gets the parameters set
 *                       (its position and other parameters kept); else the effect is appended.
 *                       VALUE: a finite number within the parameter's range (pnpr_effect_params);
 *                       a parameter named twice takes the last value.
 *   +EFFECT [PARAM=VALUE...]
 *                       Always appends the effect (another instance).
 *   no EFFECT           Removes every effect of that kind from the chain.
 *   clear               Empties the chain.
 *   preset NAME         Appends the chain of a preset (pnpr_effect_preset_find).
 *   A chain holds at most PNPR_EFFECT_CHAIN_MAX effects: more is an error. */
#include "effects_internal.h"

#include "../core/internal.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define PIPE_LINE_MAX 1023
#define PIPE_LABELS_MAX ((uint64_t)1 << 24)
#define PIPE_NODES_MAX 65536
#define PIPE_LABEL_ITEMS_MAX 512 /* items on one line of PIPE_LINE_MAX characters: "1,2,..." */

typedef struct label_range {
    uint32_t a, b;
} label_range;

typedef struct parser {
    pnpr_effect_pipeline *p;
    size_t cap;          /* nodes allocated */
    int32_t *hash;       /* node indices by name (open addressing, -1 = empty) */
    size_t hash_cap;     /* a power of two, > 2 * node count */
    size_t cur;          /* the node that configuration statements apply to */
    uint64_t labels;     /* labels listed so far */
    const char *name;
    long line;
    pnpr_error *err;
} parser;

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static pnpr_status fail(parser *ps, const char *fmt, ...)
{
    char what[448];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    pnpr_status st = pnpr_error_set(ps->err, PNPR_ERR_FORMAT, "%s:%ld: %s", ps->name, ps->line, what);
    if (ps->err) ps->err->line = ps->line;
    return st;
}

static pnpr_status out_of_memory(parser *ps)
{
    pnpr_status st = pnpr_error_set(ps->err, PNPR_ERR_OUT_OF_MEMORY, "%s:%ld: out of memory", ps->name, ps->line);
    if (ps->err) ps->err->line = ps->line;
    return st;
}

/* Appends ", s" (or "s" first) to the NUL-terminated list in buf. */
static void list_add(char *buf, size_t cap, const char *s)
{
    size_t n = strlen(buf);
    if (n + 1 < cap) snprintf(buf + n, cap - n, "%s%s", n ? ", " : "", s);
}

/* The next blank-separated token of *cur (NUL-terminated in place), NULL at the end. */
static char *next_token(char **cur)
{
    char *s = *cur + strspn(*cur, " \t");
    if (!*s) { *cur = s; return NULL; }
    char *e = s + strcspn(s, " \t");
    if (*e) *e++ = '\0';
    *cur = e;
    return s;
}

static pnpr_status no_more(parser *ps, char **cur, const char *statement)
{
    char *t = next_token(cur);
    return t ? fail(ps, "unexpected '%.64s' after %s", t, statement) : PNPR_OK;
}

/* A number: the whole token, as strtof reads it (finiteness is the caller's check). */
static int parse_float(const char *s, float *r_v)
{
    char *end;
    *r_v = strtof(s, &end);
    return end != s && *end == '\0';
}

/* Decimal digits only, value at most 4294967295 (leading zeros allowed). */
static int parse_u32(const char *s, size_t len, uint32_t *r_v)
{
    uint64_t v = 0;
    if (len == 0) return 0;
    for (size_t i = 0; i < len; i++) {
        if (s[i] < '0' || s[i] > '9') return 0;
        v = 10 * v + (uint64_t)(s[i] - '0');
        if (v > 0xFFFFFFFFull) return 0;
    }
    *r_v = (uint32_t)v;
    return 1;
}

/* ---- node names ---- */

static size_t name_hash(const char *s)
{
    uint64_t h = 1469598103934665603ull;
    for (; *s; s++) h = (h ^ (unsigned char)*s) * 1099511628211ull;
    return (size_t)(h ^ (h >> 29));
}

/* The slot of `name`: holding its node, or the empty slot where it would go. */
static int32_t *hash_slot(const parser *ps, const char *name)
{
    size_t mask = ps->hash_cap - 1;
    for (size_t i = name_hash(name) & mask;; i = (i + 1) & mask) {
        int32_t *slot = &ps->hash[i];
        if (*slot < 0 || !strcmp(ps->p->nodes[*slot].name, name)) return slot;
    }
}

/* Enters nodes[idx] (its name set) into the table, growing it first when needed. */
static pnpr_status hash_add(parser *ps, size_t idx)
{
    if (2 * (idx + 1) >= ps->hash_cap) {
        size_t cap = ps->hash_cap ? 2 * ps->hash_cap : 64;
        int32_t *h = malloc(cap * sizeof *h);
        if (!h) return out_of_memory(ps);
        free(ps->hash);
        ps->hash = h;
        ps->hash_cap = cap;
        for (size_t i = 0; i < cap; i++) h[i] = -1;
        for (size_t i = 0; i < idx; i++) *hash_slot(ps, ps->p->nodes[i].name) = (int32_t)i;
    }
    *hash_slot(ps, ps->p->nodes[idx].name) = (int32_t)idx;
    return PNPR_OK;
}

static int valid_node_name(const char *s)
{
    size_t n = strlen(s);
    return n >= 1 && n <= 63 &&
           strspn(s, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_.-") == n;
}

/* ---- labels ---- */

static int range_cmp(const void *x, const void *y)
{
    const label_range *a = x, *b = y;
    return a->a < b->a ? -1 : a->a > b->a;
}

/* Reads "N" or "A-B" (len characters at s) into *r. */
static pnpr_status parse_item(parser *ps, const char *s, size_t len, label_range *r)
{
    const char *dash = memchr(s, '-', len);
    size_t la = dash ? (size_t)(dash - s) : len;
    if (!parse_u32(s, la, &r->a) || (dash && !parse_u32(dash + 1, len - la - 1, &r->b)))
        return fail(ps, "bad label '%.*s' (want an integer in 0..4294967295 or a range A-B)", (int)(len < 64 ? len : 64), s);
    if (!dash) r->b = r->a;
    if (r->b < r->a) return fail(ps, "reversed range '%.*s' (want A-B with A <= B)", (int)len, s);
    uint64_t n = (uint64_t)r->b - r->a + 1;
    if (n > PIPE_LABELS_MAX)
        return fail(ps, "range '%.*s' covers %llu labels, more than %llu", (int)len, s, (unsigned long long)n,
                    (unsigned long long)PIPE_LABELS_MAX);
    ps->labels += n;
    if (ps->labels > PIPE_LABELS_MAX)
        return fail(ps, "too many labels: more than %llu in the file", (unsigned long long)PIPE_LABELS_MAX);
    return PNPR_OK;
}

/* Sorts and merges ranges[0..n) and expands them into the node's sorted, unique label array. */
static pnpr_status store_labels(parser *ps, pnpr_effect_node *node, label_range *ranges, size_t n)
{
    qsort(ranges, n, sizeof *ranges, range_cmp);
    size_t m = 0;
    for (size_t i = 1; i < n; i++) {
        if ((uint64_t)ranges[i].a <= (uint64_t)ranges[m].b + 1) {
            if (ranges[i].b > ranges[m].b) ranges[m].b = ranges[i].b;
        } else {
            ranges[++m] = ranges[i];
        }
    }
    size_t total = 0;
    for (size_t i = 0; i <= m; i++) total += (size_t)(ranges[i].b - ranges[i].a) + 1;
    if (!(node->labels = malloc(total * sizeof *node->labels))) return out_of_memory(ps);
    size_t k = 0;
    for (size_t i = 0; i <= m; i++)
        for (uint64_t v = ranges[i].a; v <= ranges[i].b; v++) node->labels[k++] = (uint32_t)v;
    node->label_count = total;
    return PNPR_OK;
}

/* The rest of a node line after `labels`: items separated by commas and blanks. */
static pnpr_status parse_labels(parser *ps, pnpr_effect_node *node, char **cur)
{
    label_range ranges[PIPE_LABEL_ITEMS_MAX];
    size_t n = 0;
    for (char *tok; (tok = next_token(cur)) != NULL;) {
        for (char *s = tok; *s;) {
            size_t len = strcspn(s, ",");
            if (len) {
                if (n == PIPE_LABEL_ITEMS_MAX) return fail(ps, "more than %d label items on one line", PIPE_LABEL_ITEMS_MAX);
                pnpr_status st = parse_item(ps, s, len, &ranges[n++]);
                if (st != PNPR_OK) return st;
            }
            s += len + (s[len] == ',');
        }
    }
    if (n == 0) return fail(ps, "'labels' wants at least one label or range A-B");
    return store_labels(ps, node, ranges, n);
}

/* ---- statements ---- */

static pnpr_status st_node(parser *ps, char **cur)
{
    pnpr_effect_pipeline *p = ps->p;
    const char *name = next_token(cur);
    if (!name) return fail(ps, "'node' wants a name: node NAME [parent PARENT] [labels SPEC...]");
    if (!valid_node_name(name))
        return fail(ps, "node name '%.64s' must be 1..63 characters of A-Z a-z 0-9 _ . -", name);
    if (!strcmp(name, "root")) return fail(ps, "'root' names the root node; choose another name");
    if (*hash_slot(ps, name) >= 0) return fail(ps, "node '%s' is defined twice", name);
    if (p->count == PIPE_NODES_MAX) return fail(ps, "more than %d nodes", PIPE_NODES_MAX);
    if (p->count == ps->cap) {
        size_t cap = 2 * ps->cap;
        pnpr_effect_node *nodes = realloc(p->nodes, cap * sizeof *nodes);
        if (!nodes) return out_of_memory(ps);
        p->nodes = nodes;
        ps->cap = cap;
    }
    size_t parent = 0, idx = p->count;
    char *tok = next_token(cur);
    if (tok && !strcasecmp(tok, "parent")) {
        const char *pn = next_token(cur);
        if (!pn) return fail(ps, "'parent' wants the name of an earlier node");
        int32_t found = *hash_slot(ps, pn);
        if (found < 0) return fail(ps, "unknown parent '%.64s' (a parent must be defined before its children)", pn);
        parent = (size_t)found;
        tok = next_token(cur);
    }
    pnpr_effect_node *node = &p->nodes[idx];
    *node = p->nodes[parent];
    snprintf(node->name, sizeof node->name, "%s", name);
    node->parent = (int)parent;
    node->labels = NULL;
    node->label_count = 0;
    p->count++;
    pnpr_status st = hash_add(ps, idx);
    if (st != PNPR_OK) return st;
    ps->cur = idx;
    if (!tok) return PNPR_OK;
    if (strcasecmp(tok, "labels"))
        return fail(ps, "unexpected '%.64s' in a node line (want 'parent PARENT' then 'labels SPEC...')", tok);
    return parse_labels(ps, node, cur);
}

static pnpr_status st_layering(parser *ps, char **cur)
{
    const char *t = next_token(cur);
    if (!t || pnpr_layering_from_name(t, &ps->p->layering) != PNPR_OK)
        return fail(ps, "'layering' wants inpainted, fragment or none");
    return no_more(ps, cur, "the layering mode");
}

static pnpr_status st_style(parser *ps, char **cur)
{
    const char *t = next_token(cur);
    pnpr_style s;
    if (!t || pnpr_style_from_name(t, &s) != PNPR_OK) {
        char names[160];
        pnpr_style_list(names, sizeof names, ", ", 1u << PNPR_STYLE_LINES);
        return t ? fail(ps, "unknown style '%.64s' (%s)", t, names) : fail(ps, "'style' wants a style (%s)", names);
    }
    if (s == PNPR_STYLE_LINES) return fail(ps, "the lines style cannot be a segment layer (profile lines have no labels)");
    ps->p->nodes[ps->cur].style = s;
    return no_more(ps, cur, "the style");
}

static pnpr_status st_size(parser *ps, char **cur)
{
    const char *t = next_token(cur);
    float v;
    if (!t || !parse_float(t, &v) || !(v >= 0.05f && v <= 20.0f))
        return fail(ps, "'size' wants a number in 0.05..20, got '%.64s'", t ? t : "");
    ps->p->nodes[ps->cur].point_scale = v;
    return no_more(ps, cur, "the size");
}

static pnpr_status st_per_label(parser *ps, char **cur)
{
    const char *t = next_token(cur);
    int on = t && !strcasecmp(t, "on");
    if (!t || (!on && strcasecmp(t, "off"))) return fail(ps, "'per_label' wants on or off");
    ps->p->nodes[ps->cur].per_label = on;
    return no_more(ps, cur, "per_label");
}

static pnpr_status st_inpaint(parser *ps, char **cur)
{
    pnpr_effect_node *node = &ps->p->nodes[ps->cur];
    char *t = next_token(cur);
    if (t && !strcasecmp(t, "off")) {
        node->inpaint = 0;
        return no_more(ps, cur, "'inpaint off'");
    }
    if (t && !strcasecmp(t, "on")) t = next_token(cur);
    node->inpaint = 1;
    for (; t; t = next_token(cur)) {
        char *eq = strchr(t, '=');
        if (eq) *eq = '\0';
        float v;
        if (eq && !strcasecmp(t, "threshold")) {
            if (!parse_float(eq + 1, &v) || !(v > 0 && v <= 1))
                return fail(ps, "inpaint threshold=%.64s: want a number in (0, 1]", eq + 1);
            node->inpaint_opts.threshold = v;
        } else if (eq && !strcasecmp(t, "radius")) {
            uint32_t r;
            if (!parse_u32(eq + 1, strlen(eq + 1), &r) || r < 1 || r > PNPR_INPAINT_RADIUS_MAX)
                return fail(ps, "inpaint radius=%.64s: want an integer in 1..%d", eq + 1, PNPR_INPAINT_RADIUS_MAX);
            node->inpaint_opts.radius = (int)r;
        } else {
            return fail(ps, "unexpected '%.64s' after inpaint (want off, or threshold=T radius=R)", t);
        }
    }
    return PNPR_OK;
}

static pnpr_status st_clear(parser *ps, char **cur)
{
    ps->p->nodes[ps->cur].chain.count = 0;
    return no_more(ps, cur, "clear");
}

static pnpr_status effect_kind(parser *ps, const char *t, pnpr_effect_kind *r_kind)
{
    if (t && pnpr_effect_from_name(t, r_kind) == PNPR_OK) return PNPR_OK;
    char names[256] = "";
    for (int i = 0; i < PNPR_EFFECT_COUNT_; i++) list_add(names, sizeof names, pnpr_effect_name((pnpr_effect_kind)i));
    return fail(ps, "unknown effect '%.64s' (%s)", t ? t : "", names);
}

static pnpr_status st_no(parser *ps, char **cur)
{
    pnpr_effect_kind kind;
    pnpr_status st = effect_kind(ps, next_token(cur), &kind);
    if (st != PNPR_OK) return st;
    pnpr_effect_chain *c = &ps->p->nodes[ps->cur].chain;
    int n = 0;
    for (int i = 0; i < c->count; i++)
        if (c->effects[i].kind != kind) c->effects[n++] = c->effects[i];
    c->count = n;
    return no_more(ps, cur, "the effect");
}

static pnpr_status st_preset(parser *ps, char **cur)
{
    const char *t = next_token(cur);
    const pnpr_effect_preset *pr = t ? pnpr_effect_preset_find(t) : NULL;
    if (!pr) {
        char names[256] = "";
        int n;
        const pnpr_effect_preset *all = pnpr_effect_presets(&n);
        for (int i = 0; i < n; i++) list_add(names, sizeof names, all[i].name);
        return fail(ps, "unknown preset '%.64s' (%s)", t ? t : "", names);
    }
    pnpr_effect_chain *c = &ps->p->nodes[ps->cur].chain;
    if (pr->chain.count > PNPR_EFFECT_CHAIN_MAX - c->count)
        return fail(ps, "preset %s makes the chain longer than %d effects", pr->name, PNPR_EFFECT_CHAIN_MAX);
    for (int i = 0; i < pr->chain.count; i++) c->effects[c->count++] = pr->chain.effects[i];
    return no_more(ps, cur, "the preset");
}

/* PARAM=VALUE tokens of an effect into e (kind set). */
static pnpr_status effect_params(parser *ps, char **cur, pnpr_effect *e)
{
    int count;
    const pnpr_effect_param_info *info = pnpr_effect_params(e->kind, &count);
    const char *fx = pnpr_effect_name(e->kind);
    for (char *t; (t = next_token(cur)) != NULL;) {
        char *eq = strchr(t, '=');
        if (!eq) return fail(ps, "%s: want PARAM=VALUE, got '%.64s'", fx, t);
        *eq = '\0';
        int i = 0;
        while (i < count && strcasecmp(t, info[i].name)) i++;
        if (i == count) {
            char names[320] = "";
            for (int k = 0; k < count; k++) list_add(names, sizeof names, info[k].name);
            return fail(ps, "%s has no parameter '%.64s' (%s)", fx, t, names);
        }
        float v;
        if (!parse_float(eq + 1, &v) || !isfinite(v) || !(v >= info[i].min && v <= info[i].max))
            return fail(ps, "%s %s=%.64s: want a finite number in %g..%g", fx, info[i].name, eq + 1,
                        (double)info[i].min, (double)info[i].max);
        e->params[i] = v;
        e->set |= 1u << i;
    }
    return PNPR_OK;
}

/* EFFECT or +EFFECT with parameters: overrides the last effect of its kind, else appends. */
static pnpr_status st_effect(parser *ps, const char *word, char **cur)
{
    int append = word[0] == '+';
    pnpr_effect e;
    memset(&e, 0, sizeof e);
    pnpr_status st = effect_kind(ps, word + append, &e.kind);
    if (st == PNPR_OK) st = effect_params(ps, cur, &e);
    if (st != PNPR_OK) return st;
    pnpr_effect_chain *c = &ps->p->nodes[ps->cur].chain;
    int last = -1;
    for (int i = 0; !append && i < c->count; i++)
        if (c->effects[i].kind == e.kind) last = i;
    if (last >= 0) {
        pnpr_effect *o = &c->effects[last];
        for (int i = 0; i < PNPR_EFFECT_PARAMS_MAX; i++)
            if ((e.set >> i) & 1u) o->params[i] = e.params[i];
        o->set |= e.set;
        return PNPR_OK;
    }
    if (c->count == PNPR_EFFECT_CHAIN_MAX)
        return fail(ps, "%s makes the chain longer than %d effects", pnpr_effect_name(e.kind), PNPR_EFFECT_CHAIN_MAX);
    c->effects[c->count++] = e;
    return PNPR_OK;
}

typedef pnpr_status (*statement_fn)(parser *ps, char **cur);

static const struct {
    const char *word;
    statement_fn fn;
} statements[] = {
    {"node", st_node},       {"layering", st_layering}, {"style", st_style}, {"size", st_size},
    {"per_label", st_per_label}, {"inpaint", st_inpaint}, {"no", st_no},   {"clear", st_clear},
    {"preset", st_preset},
};

static pnpr_status parse_statement(parser *ps, char *line)
{
    char *hash = strchr(line, '#');
    if (hash) *hash = '\0';
    char *cur = line, *word = next_token(&cur);
    if (!word) return PNPR_OK;
    for (size_t i = 0; i < sizeof statements / sizeof statements[0]; i++)
        if (!strcasecmp(word, statements[i].word)) return statements[i].fn(ps, &cur);
    pnpr_effect_kind kind;
    if (pnpr_effect_from_name(word + (word[0] == '+'), &kind) != PNPR_OK) {
        char names[256] = "";
        for (int i = 0; i < PNPR_EFFECT_COUNT_; i++) list_add(names, sizeof names, pnpr_effect_name((pnpr_effect_kind)i));
        return fail(ps, "unknown statement or effect '%.64s' (statements: layering, node, style, size, per_label, "
                        "inpaint, no, clear, preset; effects: %s)", word, names);
    }
    return st_effect(ps, word, &cur);
}

/* ---- entry points ---- */

void pnpr_effect_pipeline_free(pnpr_effect_pipeline *pipeline)
{
    if (!pipeline) return;
    for (size_t i = 0; i < pipeline->count; i++) free(pipeline->nodes[i].labels);
    free(pipeline->nodes);
    memset(pipeline, 0, sizeof *pipeline);
}

static pnpr_status add_root(parser *ps)
{
    pnpr_effect_pipeline *p = ps->p;
    ps->cap = 16;
    if (!(p->nodes = calloc(ps->cap, sizeof *p->nodes))) return out_of_memory(ps);
    pnpr_effect_node *root = &p->nodes[0];
    snprintf(root->name, sizeof root->name, "root");
    root->parent = -1;
    root->style = PNPR_STYLE_POINTS;
    root->inpaint = 1;
    root->inpaint_opts.threshold = PNPR_INPAINT_THRESHOLD;
    root->inpaint_opts.radius = PNPR_INPAINT_RADIUS;
    p->count = 1;
    p->layering = PNPR_LAYERING_INPAINTED;
    return hash_add(ps, 0);
}

/* The next line into buf (PIPE_LINE_MAX + 3 bytes), its '\r\n' or '\n' dropped: 1, 0 at the end,
 * -1 when longer than PIPE_LINE_MAX characters. */
static int read_line(const char *text, size_t size, size_t *pos, char *buf, size_t cap)
{
    size_t start = *pos;
    int got = pnpr_text_line(text, size, pos, buf, cap);
    if (got <= 0) return got;
    size_t len = *pos - start - (text[*pos - 1] == '\n');
    if (len && text[start + len - 1] == '\r') buf[--len] = '\0';
    return len > PIPE_LINE_MAX ? -1 : 1;
}

pnpr_status pnpr_effect_pipeline_parse(const char *text, size_t size, const char *name,
                                       pnpr_effect_pipeline *r_pipeline, pnpr_error *err)
{
    if (r_pipeline) memset(r_pipeline, 0, sizeof *r_pipeline);
    if (!r_pipeline || (!text && size) || !name) return PNPR_ERR_INVALID_ARGUMENT;
    parser ps = {.p = r_pipeline, .name = name, .err = err};
    pnpr_status st = add_root(&ps);
    char line[PIPE_LINE_MAX + 3];
    size_t pos = 0;
    for (int got; st == PNPR_OK && (got = read_line(text, size, &pos, line, sizeof line)) != 0;) {
        ps.line++;
        st = got < 0 ? fail(&ps, "line longer than %d characters", PIPE_LINE_MAX) : parse_statement(&ps, line);
    }
    free(ps.hash);
    if (st != PNPR_OK) pnpr_effect_pipeline_free(r_pipeline);
    return st;
}

size_t pnpr_effect_pipeline_node_of(const pnpr_effect_pipeline *pipeline, uint32_t label)
{
    if (!pipeline) return 0;
    for (size_t i = pipeline->count; i-- > 1;) {
        const pnpr_effect_node *n = &pipeline->nodes[i];
        if (!n->label_count || label < n->labels[0] || label > n->labels[n->label_count - 1]) continue;
        size_t lo = 0, hi = n->label_count;
        while (lo < hi) {
            size_t mid = lo + (hi - lo) / 2;
            if (n->labels[mid] < label) lo = mid + 1;
            else hi = mid;
        }
        if (n->labels[lo] == label) return i;
    }
    return 0;
}
