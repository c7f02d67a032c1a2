/* libFuzzer target for the pipeline file parser (effects/pipeline.c, effects.h). Each parse must
 * finish without crash, leak or undefined behaviour; a failure leaves a zeroed pipeline and a
 * message "pipe.txt:LINE: ..." with err.line >= 1; a pipeline that parses keeps its promises: a
 * root (node 0, parent -1, no labels of its own), parents before their children, valid names
 * (unique, not root), valid styles (never lines) and settings, chains within
 * PNPR_EFFECT_CHAIN_MAX with every set parameter finite and within its table's range, label lists
 * sorted without repeats and at most 16777216 in all, and pnpr_effect_pipeline_node_of agreeing
 * with a brute-force search of the lists. */
#include <pointnpr/effects.h>

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int valid_name(const char *s)
{
    size_t n = strnlen(s, 64);
    return n >= 1 && n <= 63 &&
           strspn(s, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_.-") == n;
}

static int has_label(const pnpr_effect_node *n, uint32_t label)
{
    size_t lo = 0, hi = n->label_count;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (n->labels[mid] == label) return 1;
        if (n->labels[mid] < label) lo = mid + 1;
        else hi = mid;
    }
    return 0;
}

/* The node that should draw `label`: the last one listing it, else 0. */
static size_t brute_node_of(const pnpr_effect_pipeline *p, uint32_t label)
{
    size_t found = 0;
    for (size_t i = 1; i < p->count; i++)
        if (has_label(&p->nodes[i], label)) found = i;
    return found;
}

static void check_chain(const pnpr_effect_chain *c)
{
    if (c->count < 0 || c->count > PNPR_EFFECT_CHAIN_MAX) abort();
    for (int k = 0; k < c->count; k++) {
        const pnpr_effect *e = &c->effects[k];
        int n;
        const pnpr_effect_param_info *info = pnpr_effect_params(e->kind, &n);
        if (!info || (n < 32 && (e->set >> n) != 0)) abort();
        for (int j = 0; j < n; j++) {
            float v = pnpr_effect_param(e, j);
            if (!isfinite(v) || v < info[j].min || v > info[j].max) abort();
        }
    }
}

static void check_node(const pnpr_effect_pipeline *p, size_t i)
{
    const pnpr_effect_node *n = &p->nodes[i];
    if (i == 0 ? (n->parent != -1 || strcmp(n->name, "root") || n->label_count || n->labels)
               : (n->parent < 0 || (size_t)n->parent >= i || !valid_name(n->name) || !strcmp(n->name, "root")))
        abort();
    for (size_t j = 0; j < i; j++)
        if (!strcmp(p->nodes[j].name, n->name)) abort();
    if ((unsigned)n->style >= PNPR_STYLE_COUNT_ || n->style == PNPR_STYLE_LINES) abort();
    if (!(n->point_scale == 0 || (n->point_scale >= 0.05f && n->point_scale <= 20.0f))) abort();
    if ((n->per_label != 0 && n->per_label != 1) || (n->inpaint != 0 && n->inpaint != 1)) abort();
    if (!(n->inpaint_opts.threshold > 0 && n->inpaint_opts.threshold <= 1) || n->inpaint_opts.radius < 1 ||
        n->inpaint_opts.radius > PNPR_INPAINT_RADIUS_MAX)
        abort();
    check_chain(&n->chain);
    if (n->label_count && !n->labels) abort();
    /* every pair of a list up to 65536 labels, else 65536 pairs spread over it (a list of 16777216
     * labels checked in full takes seconds under the sanitizers) */
    size_t step = n->label_count / 65536 + 1;
    for (size_t k = 1; k < n->label_count; k += step)
        if (n->labels[k] <= n->labels[k - 1]) abort();
}

/* node_of at up to 16 labels of each list and their neighbours, and at both ends of the range. */
static void check_node_of(const pnpr_effect_pipeline *p)
{
    const uint32_t ends[2] = {0, UINT32_MAX};
    for (int k = 0; k < 2; k++)
        if (pnpr_effect_pipeline_node_of(p, ends[k]) != brute_node_of(p, ends[k])) abort();
    for (size_t i = 1; i < p->count; i++) {
        const pnpr_effect_node *n = &p->nodes[i];
        size_t step = n->label_count / 16 + 1;
        for (size_t k = 0; k < n->label_count; k += step) {
            uint32_t l = n->labels[k];
            size_t got = pnpr_effect_pipeline_node_of(p, l);
            if (got < i || got != brute_node_of(p, l)) abort();
            if (pnpr_effect_pipeline_node_of(p, l + 1) != brute_node_of(p, l + 1)) abort();
            if (pnpr_effect_pipeline_node_of(p, l - 1) != brute_node_of(p, l - 1)) abort();
        }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    pnpr_effect_pipeline p;
    pnpr_error err;
    memset(&err, 0, sizeof err);
    if (pnpr_effect_pipeline_parse((const char *)data, size, "pipe.txt", &p, &err) != PNPR_OK) {
        pnpr_effect_pipeline zero;
        memset(&zero, 0, sizeof zero);
        if (memcmp(&p, &zero, sizeof p) != 0 || strncmp(err.message, "pipe.txt:", 9) != 0 || err.line < 1) abort();
        return 0;
    }
    if (p.count < 1 || !p.nodes || (unsigned)p.layering >= PNPR_LAYERING_COUNT_) abort();
    uint64_t labels = 0;
    for (size_t i = 0; i < p.count; i++) {
        check_node(&p, i);
        labels += p.nodes[i].label_count;
    }
    if (labels > ((uint64_t)1 << 24)) abort();
    check_node_of(&p);
    pnpr_effect_pipeline_free(&p);
    if (p.nodes || p.count) abort();
    return 0;
}
