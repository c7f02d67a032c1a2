/* Profile lines (PointWorks section 5.2 and figure 6): directional points -> neighbourhood graph ->
 * shift -> merge -> minimum spanning forest -> spur pruning -> chains -> corners -> B-splines.
 * The formulas and default parameters (h = spacing):
 *  - spacing h: median distance from a directional point to its nearest distinct directional
 *    point (a sample of up to 20 000 points), unless given;
 *  - shift (noise reduction, figure 6c): each point moves half-way towards the mean of the
 *    directional points within 2h, but only across its feature direction d (the component of the
 *    move along d is removed, so lines do not shrink); 4 iterations collapse a feature band a few
 *    points wide onto its axis;
 *  - merge: points within merge_tol (h) of a not-yet-merged point form one node at their mean
 *    position, with their sign-aligned mean direction;
 *  - graph edges: each node to its 8 nearest nodes within connect_radius R (3h); an edge e between
 *    nodes a, b weighs |e| * (1 + beta * (1 - (|e^.d_a| + |e^.d_b|) / 2)), beta = 4: an edge along
 *    both directions costs its length, one across them up to 5x. Edges that run across both
 *    directions (|e^.d| < 0.5, i.e. > 60 degrees, at both ends) are not added: they would join
 *    parallel features;
 *  - minimum spanning forest: Kruskal, edges sorted by weight, union-find: O(E log E);
 *  - spurs: a leaf branch shorter than min_length (5h) that ends at a junction is removed;
 *  - chains: maximal paths between nodes whose degree is not 2; isolated chains (two leaf ends)
 *    shorter than min_length are dropped; an isolated chain whose ends are within R of each other
 *    and which is at least 3R long is closed (a ring the spanning tree had to cut);
 *  - corners: PointWorks classifies the points near a corner as non-directional, so lines stop
 *    short of corners. Two chain ends whose end tangents (over the last 3h) point at a common point
 *    (the rays pass within 2h of each other, each at most 10h ahead, at an angle over 30 degrees)
 *    vote for that point; votes within 2h of each other are one corner (their mean) and every
 *    end that voted for it is extended to it. Two ends facing each other across a gap (opposite
 *    tangents within 25 degrees, each end ahead of the other, at most 12h apart: a stretch of
 *    edge where noise hid the directional points) vote for the gap's midpoint the same way;
 *  - each chain is fitted and sampled by lines_spline.c. */
#include "lines_internal.h"

#include <pointnpr/features.h>
#include <pointnpr/knn.h>
#include <pointnpr/options.h>

#include "../core/internal.h"
#include "kdtree_internal.h"

#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#define RADIUS_CAP PNPR_LINES_NEIGHBOURS_MAX
#define GRAPH_SLOTS 9     /* a node and its 8 nearest: at most 9 edges each (8 unless nodes coincide) */
#define LINES_CHUNK 4096  /* points or nodes per parallel chunk */

int pnpr_lines_buf_push(pnpr_lines_buf *b, const double p[3])
{
    if (!b->ok) return 0;
    if (b->n == b->cap) {
        size_t cap = b->cap ? 2 * b->cap : 256;
        double *np = realloc(b->p, 3 * cap * sizeof *np);
        if (!np) { b->ok = 0; return 0; }
        b->p = np;
        b->cap = cap;
    }
    memcpy(b->p + 3 * b->n++, p, 3 * sizeof(double));
    return 1;
}

void pnpr_lines_free(pnpr_polylines *l)
{
    if (!l) return;
    free(l->offset);
    free(l->xyz);
    free(l->closed);
    memset(l, 0, sizeof *l);
}

static double dist3(const float *a, const float *b)
{
    double d[3] = {(double)a[0] - b[0], (double)a[1] - b[1], (double)a[2] - b[2]};
    return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

typedef struct edge { float w; uint32_t a, b; } edge;

static int cmp_edge(const void *x, const void *y)
{
    const edge *a = x, *b = y;
    if (a->w != b->w) return a->w < b->w ? -1 : 1;
    if (a->a != b->a) return a->a < b->a ? -1 : 1;
    return a->b < b->b ? -1 : (a->b > b->b);
}

static uint32_t find(uint32_t *parent, uint32_t x)
{
    while (parent[x] != x) { parent[x] = parent[parent[x]]; x = parent[x]; }
    return x;
}

typedef struct chain {
    size_t first, count; /* node ids in `chain_nodes` */
    int closed;
    int end_leaf[2];     /* the first/last node is a leaf of the forest */
    double ext[2][3];    /* corner extension of each end */
    int has_ext[2];
} chain;

/* End point and tangent (pointing outwards) of a chain end, over about 3h. */
static void end_tangent(const float *pos, const uint32_t *nodes, size_t count, int end, double h,
                        double r_e[3], double r_t[3])
{
    size_t i0 = end ? count - 1 : 0;
    const float *e = pos + 3 * (size_t)nodes[i0];
    const float *q = e;
    for (size_t s = 1; s < count; s++) {
        q = pos + 3 * (size_t)nodes[end ? count - 1 - s : s];
        if (dist3(e, q) >= 3 * h) break;
    }
    double t[3] = {(double)e[0] - q[0], (double)e[1] - q[1], (double)e[2] - q[2]};
    double l = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    for (int a = 0; a < 3; a++) { r_e[a] = e[a]; r_t[a] = l > 0 ? t[a] / l : 0; }
}

pnpr_status pnpr_lines_check_options(const pnpr_lines_options *o, pnpr_error *err)
{
    size_t n;
    const pnpr_option_desc *table = pnpr_lines_option_table(&n);
    return pnpr_option_check(table, n, o, err);
}

/* What the stages share: the parameters, the points, the nodes, the forest and the chains. */
typedef struct lines_ctx {
    const pnpr_lines_options *opts;
    pnpr_lines_stats *stats;
    double h, R, tol_merge, beta, min_len, tol_sample;
    int shifts;
    size_t n;                  /* valid input points: pos, dir (unit) */
    float *pos, *dir;
    size_t n_nodes;            /* merged nodes: npos, ndir */
    float *npos, *ndir;
    pnpr_kdtree *tree;         /* over pos, then over npos */
    edge *edges;               /* graph edges, then (prefix) the forest's */
    size_t n_edges, n_forest;
    uint32_t *deg;             /* forest degree per node */
    uint32_t *adj_off, *adj;   /* CSR: forest edges per node */
    uint8_t *alive;            /* forest edge not pruned */
    chain *chains;
    uint32_t *chain_nodes;
    uint32_t *at;      /* input point i is at c->pos[at[i]] (tree order: tree_order) */
    size_t n_chains;
} lines_ctx;

static void lines_ctx_free(lines_ctx *c)
{
    pnpr_kdtree_free(c->tree);
    free(c->pos); free(c->dir); free(c->npos); free(c->ndir); free(c->deg);
    free(c->adj_off); free(c->adj); free(c->alive); free(c->edges); free(c->chains); free(c->chain_nodes); free(c->at);
}

/* Input points [begin, end) copied, their directions normalised; an invalid one (non-finite
 * position, zero or non-finite direction) gets a NaN position. */
typedef struct collect_job { float *pos, *dir; const float *xyz, *d; } collect_job;

static void collect_range(void *ctx, size_t begin, size_t end)
{
    const collect_job *j = ctx;
    for (size_t i = begin; i < end; i++) {
        const float *p = j->xyz + 3 * i, *d = j->d + 3 * i;
        double l = sqrt((double)d[0] * d[0] + (double)d[1] * d[1] + (double)d[2] * d[2]);
        int ok = isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]) && l > 0 && isfinite(l);
        for (int a = 0; a < 3; a++) {
            j->pos[3 * i + a] = ok ? p[a] : NAN;
            j->dir[3 * i + a] = ok ? (float)(d[a] / l) : 0.0f;
        }
    }
}

/* The valid input points (finite position, non-zero direction), directions normalised, in input
 * order (copied in parallel, then the invalid ones squeezed out). */
static pnpr_status lines_collect(lines_ctx *c, const float *xyz_in, const float *dir_in, size_t m)
{
    c->pos = malloc((m ? m : 1) * 3 * sizeof *c->pos);
    c->dir = malloc((m ? m : 1) * 3 * sizeof *c->dir);
    if (!c->pos || !c->dir) return PNPR_ERR_OUT_OF_MEMORY;
    collect_job job = {c->pos, c->dir, xyz_in, dir_in};
    pnpr_status st = pnpr_parallel_for(m, LINES_CHUNK, c->opts->threads, collect_range, &job, NULL, NULL);
    if (st != PNPR_OK) return st;
    size_t n = 0;
    for (size_t i = 0; i < m; i++) {
        if (isnan(c->pos[3 * i])) continue;
        if (n != i) {
            memcpy(c->pos + 3 * n, c->pos + 3 * i, 3 * sizeof *c->pos);
            memcpy(c->dir + 3 * n, c->dir + 3 * i, 3 * sizeof *c->dir);
        }
        n++;
    }
    c->n = n;
    c->stats->directional_points = n;
    return PNPR_OK;
}

/* Points and directions (n of each) put into the order of the kd-tree `tree` over them, which
 * the tree then reports; r_at (may be NULL) receives where each point went. Later passes walk
 * them in space-filling order, their neighbours close in memory, whatever order they came in. */
typedef struct order_job { const uint32_t *old; const float *pos, *dir; float *p2, *d2; uint32_t *at; } order_job;

static void order_range(void *ctx, size_t begin, size_t end)
{
    const order_job *j = ctx;
    for (size_t p = begin; p < end; p++) {
        size_t o = j->old[p];
        memcpy(j->p2 + 3 * p, j->pos + 3 * o, 3 * sizeof *j->p2);
        memcpy(j->d2 + 3 * p, j->dir + 3 * o, 3 * sizeof *j->d2);
        if (j->at) j->at[o] = (uint32_t)p;
    }
}

static pnpr_status tree_order(pnpr_kdtree *tree, float **pos, float **dir, size_t n, int threads, uint32_t *r_at)
{
    uint32_t *old = malloc((n ? n : 1) * sizeof *old);
    float *p2 = malloc((n ? n : 1) * 3 * sizeof *p2), *d2 = malloc((n ? n : 1) * 3 * sizeof *d2);
    pnpr_status st = old && p2 && d2 ? pnpr_kdtree_renumber(tree, old) : PNPR_ERR_OUT_OF_MEMORY;
    order_job job = {old, *pos, *dir, p2, d2, r_at};
    if (st == PNPR_OK) st = pnpr_parallel_for(n, LINES_CHUNK, threads, order_range, &job, NULL, NULL);
    if (st == PNPR_OK) {
        free(*pos); *pos = p2; p2 = NULL;
        free(*dir); *dir = d2; d2 = NULL;
    }
    free(old); free(p2); free(d2);
    return st;
}

/* A length option: its value, else its table default, a multiple of h (options.h). */
static double length_or_auto(const pnpr_option_desc *table, size_t n, const char *name, float v, double h)
{
    return v > 0 ? v : pnpr_option_find(table, n, name)->auto_scale * h;
}

/* The parameters that follow from the spacing h (the options, else the table's defaults). */
static void lines_parameters(lines_ctx *c, double h)
{
    pnpr_lines_options o = *c->opts;
    size_t n;
    const pnpr_option_desc *table = pnpr_lines_option_table(&n);
    pnpr_option_fill_defaults(table, n, &o);
    c->h = h;
    c->R = length_or_auto(table, n, "radius", o.connect_radius, h);
    c->tol_merge = length_or_auto(table, n, "merge-tol", o.merge_tol, h);
    c->shifts = o.shift_iterations < 0 ? 0 : o.shift_iterations;
    c->beta = o.direction_weight;
    c->min_len = length_or_auto(table, n, "min-length", o.min_length, h);
    c->tol_sample = length_or_auto(table, n, "sample-tol", o.sample_tol, h);
}

/* Points [begin, end) of one shift into c->npos (each reads the tree and c->pos only). */
static void shift_range(void *ctx, size_t begin, size_t end)
{
    lines_ctx *c = ctx;
    uint32_t nb[RADIUS_CAP];
    const float *pos = c->pos;
    for (size_t i = begin; i < end; i++) {
        const float *p = pos + 3 * i, *d = c->dir + 3 * i;
        size_t got = pnpr_kdtree_radius_first(c->tree, p, (float)(2 * c->h), nb, RADIUS_CAP);
        double mean[3] = {0, 0, 0};
        for (size_t r = 0; r < got; r++)
            for (int a = 0; a < 3; a++) mean[a] += pos[3 * (size_t)nb[r] + a];
        double mv[3];
        for (int a = 0; a < 3; a++) mv[a] = got ? mean[a] / (double)got - p[a] : 0.0;
        double along = mv[0] * d[0] + mv[1] * d[1] + mv[2] * d[2];
        for (int a = 0; a < 3; a++) c->npos[3 * i + a] = (float)(p[a] + 0.5 * (mv[a] - along * d[a]));
    }
}

/* 1. shift across the feature direction towards the neighbours' mean (c->npos: scratch), the
 * points in parallel (each independent of the others within an iteration). */
static pnpr_status lines_shift(lines_ctx *c)
{
    const size_t n = c->n;
    float *pos = c->pos;
    for (int it = 0; it < c->shifts; it++) {
        pnpr_status st = pnpr_parallel_for(n, LINES_CHUNK, c->opts->threads, shift_range, c, NULL, NULL);
        if (st != PNPR_OK) return st;
        memcpy(pos, c->npos, n * 3 * sizeof *pos);
        pnpr_kdtree_free(c->tree);
        c->tree = NULL;
        st = pnpr_kdtree_build_threads(pos, n, 0, c->opts->threads, &c->tree);
        if (st != PNPR_OK) return st;
        if (pnpr_progress_report(&c->opts->progress, "lines: shift", (it + 1.0) / (c->shifts + 1.0)))
            return PNPR_ERR_CANCELLED;
    }
    return PNPR_OK;
}

/* Node n_nodes from seed i and the points nb[0, got) within tol_merge of it not merged yet. */
static void merge_node(lines_ctx *c, size_t i, const uint32_t *nb, size_t got, uint32_t *cluster, size_t n_nodes)
{
    const float *pos = c->pos, *dir = c->dir, *d0 = dir + 3 * i;
    double m[3] = {pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]}, dsum[3] = {d0[0], d0[1], d0[2]};
    size_t cnt = 1;
    cluster[i] = (uint32_t)n_nodes;
    for (size_t r = 0; r < got; r++) {
        uint32_t j = nb[r];
        if (cluster[j] != PNPR_INDEX_NONE) continue; /* merged already (or i itself) */
        cluster[j] = (uint32_t)n_nodes;
        const float *dj = dir + 3 * (size_t)j;
        double s = dj[0] * d0[0] + dj[1] * d0[1] + dj[2] * d0[2] < 0 ? -1.0 : 1.0;
        for (int a = 0; a < 3; a++) { m[a] += pos[3 * (size_t)j + a]; dsum[a] += s * dj[a]; }
        cnt++;
    }
    double dl = sqrt(dsum[0] * dsum[0] + dsum[1] * dsum[1] + dsum[2] * dsum[2]);
    for (int a = 0; a < 3; a++) {
        c->npos[3 * n_nodes + a] = (float)(m[a] / (double)cnt);
        c->ndir[3 * n_nodes + a] = dl > 0 ? (float)(dsum[a] / dl) : d0[a];
    }
}

/* 2. merge points closer than tol_merge into nodes (npos, ndir), greedily in input order (each
 * point's node depends on the ones before: in tree order, which leaves each leaf's points
 * unsorted, a line of points would be cut into nodes anew inside every leaf); the tree then
 * holds the nodes, numbered in its order for the graph and the chains. */
static pnpr_status lines_merge(lines_ctx *c)
{
    uint32_t nb[RADIUS_CAP];
    const size_t n = c->n;
    uint32_t *cluster = malloc(n * sizeof *cluster);
    c->ndir = malloc(n * 3 * sizeof *c->ndir);
    if (!cluster || !c->ndir) { free(cluster); return PNPR_ERR_OUT_OF_MEMORY; }
    for (size_t i = 0; i < n; i++) cluster[i] = PNPR_INDEX_NONE;
    size_t n_nodes = 0;
    for (size_t r = 0; r < n; r++) {
        size_t i = c->at[r];
        if (cluster[i] != PNPR_INDEX_NONE) continue;
        size_t got = pnpr_kdtree_radius_first(c->tree, c->pos + 3 * i, (float)c->tol_merge, nb, RADIUS_CAP);
        merge_node(c, i, nb, got, cluster, n_nodes++);
    }
    free(cluster);
    c->n_nodes = n_nodes;
    c->stats->merged_nodes = n_nodes;
    pnpr_kdtree_free(c->tree);
    c->tree = NULL;
    pnpr_status st = pnpr_kdtree_build_threads(c->npos, n_nodes, 0, c->opts->threads, &c->tree);
    return st == PNPR_OK ? tree_order(c->tree, &c->npos, &c->ndir, n_nodes, c->opts->threads, NULL) : st;
}

/* The graph edges of nodes [begin, end): node a's in c->edges[a * GRAPH_SLOTS ...], their
 * count in c->deg[a] (scratch here: the forest's degrees come later). */
static void graph_range(void *ctx, size_t begin, size_t end)
{
    lines_ctx *c = ctx;
    const float *npos = c->npos, *ndir = c->ndir;
    for (size_t a = begin; a < end; a++) {
        uint32_t idx[GRAPH_SLOTS];
        float d2[GRAPH_SLOTS];
        size_t got = pnpr_kdtree_knn(c->tree, npos + 3 * a, GRAPH_SLOTS, idx, d2), m = 0;
        const float *pa = npos + 3 * a, *da = ndir + 3 * a;
        edge *out = c->edges + a * GRAPH_SLOTS;
        for (size_t r = 0; r < got; r++) {
            uint32_t b = idx[r];
            if (b == a || d2[r] > c->R * c->R) continue;
            const float *pb = npos + 3 * (size_t)b, *db = ndir + 3 * (size_t)b;
            double e[3] = {(double)pb[0] - pa[0], (double)pb[1] - pa[1], (double)pb[2] - pa[2]};
            double len = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
            if (!(len > 0)) continue;
            double ca = fabs(e[0] * da[0] + e[1] * da[1] + e[2] * da[2]) / len;
            double cb = fabs(e[0] * db[0] + e[1] * db[1] + e[2] * db[2]) / len;
            if (ca < 0.5 && cb < 0.5) continue;
            edge ed = {(float)(len * (1 + c->beta * (1 - 0.5 * (ca + cb)))), (uint32_t)(a < b ? a : b),
                       (uint32_t)(a < b ? b : a)};
            out[m++] = ed;
        }
        c->deg[a] = (uint32_t)m;
    }
}

/* 3. graph edges: each node to its 8 nearest within R, weighed by length and direction; the nodes
 * in parallel, each into slots of its own, then packed in node order (the same edges in the same
 * order whatever the threads). */
static pnpr_status lines_graph(lines_ctx *c)
{
    size_t nn = c->n_nodes;
    c->edges = malloc((nn ? nn * GRAPH_SLOTS : 1) * sizeof *c->edges);
    c->deg = malloc((nn ? nn : 1) * sizeof *c->deg);
    if (!c->edges || !c->deg) return PNPR_ERR_OUT_OF_MEMORY;
    pnpr_status st = pnpr_parallel_for(nn, LINES_CHUNK, c->opts->threads, graph_range, c, NULL, NULL);
    if (st != PNPR_OK) return st;
    size_t m = 0;
    for (size_t a = 0; a < nn; a++)
        for (uint32_t r = 0; r < c->deg[a]; r++) c->edges[m++] = c->edges[a * GRAPH_SLOTS + r];
    c->n_edges = m;
    free(c->deg);
    c->deg = NULL;
    return PNPR_OK;
}

/* Merges the sorted runs a[0, na) and b[0, nb) into out (a first among equal edges). */
static void merge_runs(const edge *a, size_t na, const edge *b, size_t nb, edge *out)
{
    size_t i = 0, j = 0;
    while (i < na && j < nb) *out++ = cmp_edge(b + j, a + i) < 0 ? b[j++] : a[i++];
    while (i < na) *out++ = a[i++];
    while (j < nb) *out++ = b[j++];
}

/* How many of the first k edges merge_runs writes come from a: the least i with b[k-i-1] < a[i]. */
static size_t co_rank(const edge *a, size_t na, const edge *b, size_t nb, size_t k)
{
    size_t lo = k > nb ? k - nb : 0, hi = k < na ? k : na;
    while (lo < hi) {
        size_t i = lo + (hi - lo) / 2, j = k - i;
        if (j > 0 && i < na && cmp_edge(b + j - 1, a + i) >= 0) lo = i + 1;
        else hi = i;
    }
    return lo;
}

/* One pass of pairwise merges of sorted parts (width w parts per run), each merge cut into `per`
 * pieces of equal output that run in parallel: piece x of the merge of runs [lo, mid) and
 * [mid, hi) writes dst[lo + len * q / per, lo + len * (q + 1) / per) from the inputs that co_rank
 * finds, so the result is that of one merge whatever the threads. */
typedef struct sort_job { edge *e; const edge *src; edge *dst; size_t n, parts, w, per; } sort_job;

static void merge_pieces(void *ctx, size_t begin, size_t end)
{
    const sort_job *j = ctx;
    for (size_t x = begin; x < end; x++) {
        size_t p = x / j->per * 2 * j->w, q = x % j->per;
        size_t mid = p + j->w < j->parts ? p + j->w : j->parts, pe = p + 2 * j->w < j->parts ? p + 2 * j->w : j->parts;
        size_t lo = j->n * p / j->parts, m = j->n * mid / j->parts, hi = j->n * pe / j->parts, len = hi - lo;
        const edge *a = j->src + lo, *b = j->src + m;
        size_t na = m - lo, nb = hi - m, k0 = len * q / j->per, k1 = len * (q + 1) / j->per;
        size_t i0 = co_rank(a, na, b, nb, k0), i1 = co_rank(a, na, b, nb, k1);
        merge_runs(a + i0, i1 - i0, b + (k0 - i0), (k1 - i1) - (k0 - i0), j->dst + lo + k0);
    }
}

static void sort_parts(void *ctx, size_t begin, size_t end)
{
    const sort_job *j = ctx;
    for (size_t p = begin; p < end; p++) {
        size_t lo = j->n * p / j->parts, hi = j->n * (p + 1) / j->parts;
        qsort(j->e + lo, hi - lo, sizeof *j->e, cmp_edge);
    }
}

/* The edges sorted by cmp_edge: up to 8 parts (a power of two, one per thread) sorted in
 * parallel, then merged pairwise, each merge in parallel pieces. cmp_edge is a total order, so
 * the result is that of one qsort whatever the threads. */
static pnpr_status sort_edges(edge *e, size_t n, int threads)
{
    int t = threads > 0 ? threads : pnpr_default_threads();
    size_t parts = 1;
    while (parts < 8 && parts * 2 <= (size_t)t && n / (parts * 2) >= 4096) parts *= 2;
    edge *tmp = parts > 1 ? malloc(n * sizeof *tmp) : NULL;
    if (!tmp) { qsort(e, n, sizeof *e, cmp_edge); return PNPR_OK; } /* one part, or no memory for two */
    sort_job job = {e, e, tmp, n, parts, 1, 1};
    pnpr_status st = pnpr_parallel_for(parts, 1, t, sort_parts, &job, NULL, NULL);
    for (; st == PNPR_OK && job.w < parts; job.w *= 2) {
        size_t merges = (parts + 2 * job.w - 1) / (2 * job.w);
        job.per = (size_t)t / merges > 1 ? (size_t)t / merges : 1;
        st = pnpr_parallel_for(merges * job.per, 1, t, merge_pieces, &job, NULL, NULL);
        edge *x = (edge *)job.src;
        job.src = job.dst;
        job.dst = x;
    }
    if (st == PNPR_OK && job.src != e) memcpy(e, job.src, n * sizeof *e);
    free(tmp);
    return st;
}

/* 4. minimum spanning forest (Kruskal; duplicates of an edge are skipped by union-find): the
 * forest's edges become the prefix of c->edges. */
static pnpr_status lines_forest(lines_ctx *c)
{
    pnpr_status st = sort_edges(c->edges, c->n_edges, c->opts->threads);
    if (st != PNPR_OK) return st;
    c->stats->graph_edges = c->n_edges;
    uint32_t *parent = malloc((c->n_nodes ? c->n_nodes : 1) * sizeof *parent);
    if (!parent) return PNPR_ERR_OUT_OF_MEMORY;
    for (size_t i = 0; i < c->n_nodes; i++) parent[i] = (uint32_t)i;
    for (size_t e = 0; e < c->n_edges; e++) {
        uint32_t ra = find(parent, c->edges[e].a), rb = find(parent, c->edges[e].b);
        if (ra == rb) continue;
        parent[ra] = rb;
        c->edges[c->n_forest++] = c->edges[e];
    }
    c->stats->forest_edges = c->n_forest;
    c->deg = parent; /* reused: union-find is done */
    return PNPR_OK;
}

/* The forest's adjacency (CSR over its edges) and degrees; every edge alive. */
static pnpr_status lines_adjacency(lines_ctx *c)
{
    const size_t nn = c->n_nodes, nf = c->n_forest;
    c->adj_off = calloc(nn + 1, sizeof *c->adj_off);
    c->adj = malloc((2 * nf + 1) * sizeof *c->adj);
    c->alive = malloc(nf + 1);
    uint32_t *fill = calloc(nn ? nn : 1, sizeof *fill);
    if (!c->adj_off || !c->adj || !c->alive || !fill) { free(fill); return PNPR_ERR_OUT_OF_MEMORY; }
    const edge *edges = c->edges;
    memset(c->deg, 0, nn * sizeof *c->deg);
    for (size_t e = 0; e < nf; e++) { c->deg[edges[e].a]++; c->deg[edges[e].b]++; c->alive[e] = 1; }
    for (size_t i = 0; i < nn; i++) c->adj_off[i + 1] = c->adj_off[i] + c->deg[i];
    for (size_t e = 0; e < nf; e++) {
        c->adj[c->adj_off[edges[e].a] + fill[edges[e].a]++] = (uint32_t)e;
        c->adj[c->adj_off[edges[e].b] + fill[edges[e].b]++] = (uint32_t)e;
    }
    free(fill);
    return PNPR_OK;
}

/* The other end of forest edge e from node v. */
static uint32_t other_end(const lines_ctx *c, uint32_t e, uint32_t v)
{
    return c->edges[e].a == v ? c->edges[e].b : c->edges[e].a;
}

/* The first alive edge at v other than `not_e` (and, with `used`, not used); PNPR_INDEX_NONE. */
static uint32_t next_edge(const lines_ctx *c, uint32_t v, uint32_t not_e, const uint8_t *used)
{
    for (uint32_t k = c->adj_off[v]; k < c->adj_off[v + 1]; k++) {
        uint32_t e = c->adj[k];
        if (c->alive[e] && e != not_e && !(used && used[e])) return e;
    }
    return PNPR_INDEX_NONE;
}

/* 5. prune spurs: leaf branches shorter than min_len that end at a junction. */
static void lines_prune(lines_ctx *c)
{
    uint32_t *deg = c->deg;
    for (size_t leaf = 0; leaf < c->n_nodes; leaf++) {
        if (deg[leaf] != 1) continue;
        uint32_t v = (uint32_t)leaf, prev_e = PNPR_INDEX_NONE;
        double len = 0;
        size_t steps = 0;
        for (;;) {
            uint32_t next_e = next_edge(c, v, prev_e, NULL);
            if (next_e == PNPR_INDEX_NONE) break;
            uint32_t w = other_end(c, next_e, v);
            len += dist3(c->npos + 3 * (size_t)v, c->npos + 3 * (size_t)w);
            prev_e = next_e;
            v = w;
            steps++;
            if (deg[v] != 2 || len >= c->min_len) break;
        }
        if (deg[v] >= 3 && len < c->min_len) { /* remove the branch leaf .. v */
            uint32_t u = (uint32_t)leaf, pe = PNPR_INDEX_NONE;
            for (size_t s = 0; s < steps; s++) {
                uint32_t ne = next_edge(c, u, pe, NULL);
                if (ne == PNPR_INDEX_NONE) break;
                uint32_t w = other_end(c, ne, u);
                c->alive[ne] = 0;
                deg[u]--; deg[w]--;
                pe = ne;
                u = w;
            }
        }
    }
}

/* 6. chains between nodes of degree != 2. */
static pnpr_status lines_chains(lines_ctx *c)
{
    const uint32_t *deg = c->deg;
    c->chain_nodes = malloc((2 * c->n_forest + c->n_nodes + 1) * sizeof *c->chain_nodes);
    c->chains = malloc((c->n_forest + 1) * sizeof *c->chains);
    uint8_t *used = calloc(c->n_forest + 1, 1);
    if (!c->chain_nodes || !c->chains || !used) { free(used); return PNPR_ERR_OUT_OF_MEMORY; }
    size_t cn = 0;
    for (size_t s = 0; s < c->n_nodes; s++) {
        if (deg[s] == 2 || deg[s] == 0) continue;
        for (uint32_t k = c->adj_off[s]; k < c->adj_off[s + 1]; k++) {
            uint32_t e = c->adj[k];
            if (!c->alive[e] || used[e]) continue;
            chain *ch = &c->chains[c->n_chains];
            memset(ch, 0, sizeof *ch);
            ch->first = cn;
            c->chain_nodes[cn++] = (uint32_t)s;
            uint32_t v = (uint32_t)s;
            for (;;) {
                used[e] = 1;
                v = other_end(c, e, v);
                c->chain_nodes[cn++] = v;
                if (deg[v] != 2) break;
                uint32_t ne = next_edge(c, v, PNPR_INDEX_NONE, used);
                if (ne == PNPR_INDEX_NONE) break;
                e = ne;
            }
            ch->count = cn - ch->first;
            ch->end_leaf[0] = deg[s] == 1;
            ch->end_leaf[1] = deg[v] == 1;
            c->n_chains++;
        }
    }
    free(used);
    return PNPR_OK;
}

/* Drops short isolated chains, closes rings. */
static void lines_trim_chains(lines_ctx *c)
{
    for (size_t ci = 0; ci < c->n_chains; ci++) {
        chain *ch = &c->chains[ci];
        const uint32_t *nodes = c->chain_nodes + ch->first;
        double len = 0;
        for (size_t i = 1; i < ch->count; i++)
            len += dist3(c->npos + 3 * (size_t)nodes[i - 1], c->npos + 3 * (size_t)nodes[i]);
        if (ch->end_leaf[0] && ch->end_leaf[1]) {
            if (len < c->min_len) { ch->count = 0; continue; }
            if (len >= 3 * c->R && dist3(c->npos + 3 * (size_t)nodes[0], c->npos + 3 * (size_t)nodes[ch->count - 1]) <= c->R)
                ch->closed = 1;
        }
    }
}

/* Where two chain ends (end point + outward tangent, 6 doubles each) vote for a corner: their
 * tangent rays meet (or the ends face each other across a gap); returns 1 and the point. */
static int end_pair_vote(const double *e1, const double *e2, double h, double r_vote[3])
{
    const double *t1 = e1 + 3, *t2 = e2 + 3;
    double w0[3] = {e1[0] - e2[0], e1[1] - e2[1], e1[2] - e2[2]};
    if (w0[0] * w0[0] + w0[1] * w0[1] + w0[2] * w0[2] > 144 * h * h) return 0;
    double b = t1[0] * t2[0] + t1[1] * t2[1] + t1[2] * t2[2];
    if (b < -0.9) { /* facing each other across a gap? */
        double wl = sqrt(w0[0] * w0[0] + w0[1] * w0[1] + w0[2] * w0[2]);
        double a1 = -(t1[0] * w0[0] + t1[1] * w0[1] + t1[2] * w0[2]); /* e2 ahead of e1 */
        double a2 = t2[0] * w0[0] + t2[1] * w0[1] + t2[2] * w0[2];    /* e1 ahead of e2 */
        if (!(wl > 0 && a1 >= 0.9 * wl && a2 >= 0.9 * wl)) return 0;
        for (int a = 0; a < 3; a++) r_vote[a] = 0.5 * (e1[a] + e2[a]);
        return 1;
    }
    if (fabs(b) > 0.866) return 0; /* nearly parallel: not a corner */
    double d = t1[0] * w0[0] + t1[1] * w0[1] + t1[2] * w0[2];
    double e = t2[0] * w0[0] + t2[1] * w0[1] + t2[2] * w0[2];
    double den = 1 - b * b;
    double s = (b * e - d) / den, u = (e - b * d) / den;
    if (s < -h || u < -h || s > 10 * h || u > 10 * h) return 0;
    double c1[3], c2[3], gap = 0;
    for (int a = 0; a < 3; a++) {
        c1[a] = e1[a] + s * t1[a];
        c2[a] = e2[a] + u * t2[a];
        gap += (c1[a] - c2[a]) * (c1[a] - c2[a]);
    }
    if (gap > 4 * h * h) return 0;
    for (int a = 0; a < 3; a++) r_vote[a] = 0.5 * (c1[a] + c2[a]);
    return 1;
}

/* Votes (x, y, z, corner id; -1 = not clustered yet) within 2h of each other are one corner, their
 * mean; every end that voted for it (eref: chain * 2 + end, through vpair) is extended to it. */
static void cluster_votes(lines_ctx *c, double *votes, const uint32_t *vpair, size_t nv, const uint32_t *eref)
{
    const double h = c->h;
    for (size_t v = 0; v < nv; v++) {
        if (votes[4 * v + 3] >= 0) continue;
        double m[3] = {0, 0, 0};
        size_t cnt = 0;
        for (size_t w = v; w < nv; w++) {
            if (votes[4 * w + 3] >= 0) continue;
            double dd = 0;
            for (int a = 0; a < 3; a++) dd += (votes[4 * w + a] - votes[4 * v + a]) * (votes[4 * w + a] - votes[4 * v + a]);
            if (dd > 4 * h * h) continue;
            votes[4 * w + 3] = (double)v;
            for (int a = 0; a < 3; a++) m[a] += votes[4 * w + a];
            cnt++;
        }
        for (int a = 0; a < 3; a++) m[a] /= (double)cnt;
        for (size_t w = v; w < nv; w++) {
            if (votes[4 * w + 3] != (double)v) continue;
            for (int pe = 0; pe < 2; pe++) {
                uint32_t ref = eref[vpair[2 * w + pe]];
                chain *ch = &c->chains[ref / 2];
                if (ch->has_ext[ref % 2]) continue;
                ch->has_ext[ref % 2] = 1;
                memcpy(ch->ext[ref % 2], m, sizeof m);
            }
        }
        c->stats->corners++;
    }
}

/* The votes of the pairs of chain ends (ep: k ends, position and tangent), at most cap of them.
 * Only ends within 12h of each other can vote (end_pair_vote's first test): each end's partners
 * come from a kd-tree over the ends (a radius a little larger, so that float rounding loses
 * none), those after it in ascending order, so the votes are those of the loop over all k^2 / 2
 * pairs in the same order, in O(k log k). */
static pnpr_status end_pairs(lines_ctx *c, const double *ep, size_t k, size_t cap, double *votes, uint32_t *vpair,
                             size_t *r_nv)
{
    size_t nv = 0, nb_cap = 64;
    float *ef = malloc((k ? k : 1) * 3 * sizeof *ef);
    uint32_t *nb = malloc(nb_cap * sizeof *nb);
    pnpr_kdtree *tree = NULL;
    pnpr_status st = ef && nb ? PNPR_OK : PNPR_ERR_OUT_OF_MEMORY;
    for (size_t i = 0; st == PNPR_OK && i < k; i++)
        for (int a = 0; a < 3; a++) ef[3 * i + a] = (float)ep[6 * i + a];
    if (st == PNPR_OK) st = pnpr_kdtree_build(ef, k, 0, &tree);
    const float radius = (float)(12 * c->h * (1 + 1e-3));
    for (size_t i = 0; st == PNPR_OK && i < k && nv < cap; i++) {
        size_t got = pnpr_kdtree_radius(tree, ef + 3 * i, radius, nb, nb_cap);
        if (got > nb_cap) {
            uint32_t *more = realloc(nb, got * sizeof *nb);
            if (!more) { st = PNPR_ERR_OUT_OF_MEMORY; break; }
            nb = more;
            nb_cap = got;
            got = pnpr_kdtree_radius(tree, ef + 3 * i, radius, nb, nb_cap);
        }
        qsort(nb, got, sizeof *nb, pnpr_cmp_u32);
        for (size_t r = 0; r < got && nv < cap; r++) {
            size_t j = nb[r];
            if (j <= i || !end_pair_vote(ep + 6 * i, ep + 6 * j, c->h, votes + 4 * nv)) continue;
            votes[4 * nv + 3] = -1;
            vpair[2 * nv] = (uint32_t)i;
            vpair[2 * nv + 1] = (uint32_t)j;
            nv++;
        }
    }
    pnpr_kdtree_free(tree);
    free(ef);
    free(nb);
    *r_nv = nv;
    return st;
}

/* 7. corners: chain ends whose tangents meet. */
static pnpr_status lines_corners(lines_ctx *c)
{
    size_t ne = 0;
    for (size_t ci = 0; ci < c->n_chains; ci++)
        for (int end = 0; end < 2; end++)
            ne += c->chains[ci].count >= 2 && !c->chains[ci].closed && c->chains[ci].end_leaf[end];
    double *ep = malloc((ne + 1) * 6 * sizeof *ep);
    uint32_t *eref = malloc((ne + 1) * sizeof *eref);
    double *votes = malloc((ne * 8 + 1) * 4 * sizeof *votes); /* x y z, corner id */
    uint32_t *vpair = malloc((ne * 8 + 1) * 2 * sizeof *vpair);
    pnpr_status st = ep && eref && votes && vpair ? PNPR_OK : PNPR_ERR_OUT_OF_MEMORY;
    size_t k = 0, nv = 0;
    for (size_t ci = 0; st == PNPR_OK && ci < c->n_chains; ci++)
        for (int end = 0; end < 2; end++) {
            const chain *ch = &c->chains[ci];
            if (ch->count < 2 || ch->closed || !ch->end_leaf[end]) continue;
            end_tangent(c->npos, c->chain_nodes + ch->first, ch->count, end, c->h, ep + 6 * k, ep + 6 * k + 3);
            eref[k++] = (uint32_t)(2 * ci + (size_t)end);
        }
    if (st == PNPR_OK) st = end_pairs(c, ep, k, ne * 8, votes, vpair, &nv);
    if (st == PNPR_OK) cluster_votes(c, votes, vpair, nv, eref);
    free(ep); free(eref); free(votes); free(vpair);
    return st;
}

/* Adds the length of the polyline p[0..n) (closed: with the segment back to the start) to *acc,
 * segment by segment. */
static void add_polyline_length(const double *p, size_t n, int closed, double *acc)
{
    double len = *acc;
    for (size_t i = 1; i < n; i++) {
        const double *a = p + 3 * (i - 1), *b = p + 3 * i;
        len += sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
    }
    if (closed) {
        const double *a = p + 3 * (n - 1), *b = p;
        len += sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
    }
    *acc = len;
}

/* The fitted polyline of each chain (fit_range), joined in chain order by lines_fit. */
typedef struct fit_job {
    lines_ctx *c;
    pnpr_lines_buf *out;       /* one per chain */
    _Atomic int failed;        /* an allocation failed */
} fit_job;

/* Chains [begin, end): each one's nodes (and corner extensions) fitted into job->out[ci]. */
static void fit_range(void *ctx, size_t begin, size_t end)
{
    fit_job *job = ctx;
    const lines_ctx *c = job->c;
    pnpr_lines_buf q = {NULL, 0, 0, 1};
    for (size_t ci = begin; ci < end; ci++) {
        const chain *ch = &c->chains[ci];
        if (ch->count < 2) continue;
        q.n = 0;
        if (ch->has_ext[0]) pnpr_lines_buf_push(&q, ch->ext[0]);
        for (size_t i = 0; i < ch->count; i++) {
            const float *p = c->npos + 3 * (size_t)c->chain_nodes[ch->first + i];
            double dp[3] = {p[0], p[1], p[2]};
            pnpr_lines_buf_push(&q, dp);
        }
        if (ch->has_ext[1]) pnpr_lines_buf_push(&q, ch->ext[1]);
        if (!q.ok || !pnpr_lines_fit_chain(q.p, q.n, ch->closed, c->h, c->tol_sample, &job->out[ci])) job->failed = 1;
    }
    free(q.p);
}

/* 8. a B-spline per chain (with its corner extensions; lines_spline.c), the chains in parallel;
 * the polylines in chain order. */
static pnpr_status lines_fit(lines_ctx *c, pnpr_polylines *r_lines)
{
    size_t nc = c->n_chains, total = 0;
    r_lines->offset = malloc((nc + 2) * sizeof *r_lines->offset);
    r_lines->closed = malloc(nc + 1);
    fit_job job = {c, calloc(nc ? nc : 1, sizeof(pnpr_lines_buf)), 0};
    pnpr_status st = r_lines->offset && r_lines->closed && job.out ? PNPR_OK : PNPR_ERR_OUT_OF_MEMORY;
    for (size_t ci = 0; ci < nc && job.out; ci++) job.out[ci].ok = 1;
    if (st == PNPR_OK) st = pnpr_parallel_for(nc, 64, c->opts->threads, fit_range, &job, NULL, NULL);
    if (st == PNPR_OK && job.failed) st = PNPR_ERR_OUT_OF_MEMORY;
    for (size_t ci = 0; st == PNPR_OK && ci < nc; ci++) total += job.out[ci].n >= 2 ? job.out[ci].n : 0;
    if (st == PNPR_OK && !(r_lines->xyz = malloc((total ? total : 1) * 3 * sizeof *r_lines->xyz))) st = PNPR_ERR_OUT_OF_MEMORY;
    if (st == PNPR_OK) {
        size_t at = 0;
        r_lines->offset[0] = 0;
        for (size_t ci = 0; ci < nc; ci++) {
            const pnpr_lines_buf *o = &job.out[ci];
            if (o->n < 2) continue;
            for (size_t i = 0; i < 3 * o->n; i++) r_lines->xyz[3 * at + i] = (float)o->p[i];
            add_polyline_length(o->p, o->n, c->chains[ci].closed, &c->stats->total_length);
            at += o->n;
            r_lines->closed[r_lines->count] = (uint8_t)c->chains[ci].closed;
            r_lines->offset[++r_lines->count] = at;
        }
    }
    c->stats->chains = r_lines->count;
    for (size_t ci = 0; job.out && ci < nc; ci++) free(job.out[ci].p);
    free(job.out);
    return st;
}

/* The stages after the spacing is known; times and progress in the stats. */
static pnpr_status lines_run(lines_ctx *c, pnpr_polylines *r_lines)
{
    double t0 = pnpr_now();
    c->npos = malloc(c->n * 3 * sizeof *c->npos);
    if (!c->npos) return PNPR_ERR_OUT_OF_MEMORY;
    pnpr_status st = lines_shift(c);
    if (st == PNPR_OK) st = lines_merge(c);
    if (st == PNPR_OK) st = lines_graph(c);
    c->stats->seconds_graph = pnpr_now() - t0;
    t0 = pnpr_now();
    if (st == PNPR_OK) st = lines_forest(c);
    c->stats->seconds_mst = pnpr_now() - t0;
    t0 = pnpr_now();
    if (st == PNPR_OK && pnpr_progress_report(&c->opts->progress, "lines: tree", 0.5)) st = PNPR_ERR_CANCELLED;
    if (st == PNPR_OK) st = lines_adjacency(c);
    if (st == PNPR_OK) lines_prune(c);
    if (st == PNPR_OK) st = lines_chains(c);
    if (st == PNPR_OK) lines_trim_chains(c);
    if (st == PNPR_OK && !c->opts->no_corners) st = lines_corners(c);
    if (st == PNPR_OK) st = lines_fit(c, r_lines);
    c->stats->seconds_fit = pnpr_now() - t0;
    if (st == PNPR_OK) pnpr_progress_report(&c->opts->progress, "lines: fit", 1.0);
    return st;
}

pnpr_status pnpr_profile_lines_points(const float *xyz_in, const float *dir_in, size_t m,
                                      const double origin[3], const pnpr_lines_options *opts,
                                      pnpr_polylines *r_lines, pnpr_lines_stats *r_stats)
{
    static const pnpr_lines_options defaults;
    pnpr_lines_stats local;
    if (!r_stats) r_stats = &local;
    memset(r_stats, 0, sizeof *r_stats);
    if (!r_lines) return PNPR_ERR_INVALID_ARGUMENT;
    memset(r_lines, 0, sizeof *r_lines);
    if (origin) memcpy(r_lines->origin, origin, sizeof r_lines->origin);
    if (!opts) opts = &defaults;
    if (m && (!xyz_in || !dir_in)) return PNPR_ERR_INVALID_ARGUMENT;
    if (m >= 0x7FFFFFFFu) return PNPR_ERR_UNSUPPORTED;
    if (pnpr_lines_check_options(opts, NULL) != PNPR_OK) return PNPR_ERR_INVALID_ARGUMENT;

    lines_ctx c;
    memset(&c, 0, sizeof c);
    c.opts = opts;
    c.stats = r_stats;
    pnpr_status st = lines_collect(&c, xyz_in, dir_in, m);
    if (st == PNPR_OK && c.n >= 2) st = pnpr_kdtree_build_threads(c.pos, c.n, 0, opts->threads, &c.tree);
    /* the points in tree order for the shifts; c.at keeps the input order for the merge */
    if (st == PNPR_OK && c.n >= 2) st = (c.at = malloc(c.n * sizeof *c.at)) ? tree_order(c.tree, &c.pos, &c.dir, c.n, opts->threads, c.at)
                                                                             : PNPR_ERR_OUT_OF_MEMORY;
    double h = 0;
    if (st == PNPR_OK && c.n >= 2) h = opts->spacing > 0 ? opts->spacing : pnpr_kdtree_median_spacing(c.tree, 0);
    if (st == PNPR_OK && h > 0) { /* else fewer than 2 points, or all coincide: no line */
        r_stats->spacing_used = (float)h;
        lines_parameters(&c, h);
        st = lines_run(&c, r_lines);
    }
    if (st == PNPR_OK && !r_lines->offset) { /* no lines: a valid empty result */
        r_lines->offset = calloc(1, sizeof *r_lines->offset);
        r_lines->closed = malloc(1);
        r_lines->xyz = malloc(3 * sizeof *r_lines->xyz);
        if (!r_lines->offset || !r_lines->closed || !r_lines->xyz) st = PNPR_ERR_OUT_OF_MEMORY;
    }
    if (st != PNPR_OK) {
        double o[3];
        memcpy(o, r_lines->origin, sizeof o);
        pnpr_lines_free(r_lines);
        memcpy(r_lines->origin, o, sizeof o);
    }
    lines_ctx_free(&c);
    return st;
}

pnpr_status pnpr_profile_lines(const pnpr_cloud *cloud, const pnpr_lines_options *opts,
                               pnpr_polylines *r_lines, pnpr_lines_stats *r_stats)
{
    if (!cloud || !r_lines || (cloud->count && !cloud->xyz)) return PNPR_ERR_INVALID_ARGUMENT;
    const pnpr_property *cls = pnpr_cloud_find_property(cloud, PNPR_PROP_FEATURE_CLASS);
    const pnpr_property *dx = pnpr_cloud_find_property(cloud, PNPR_PROP_FEATURE_DIR_X);
    const pnpr_property *dy = pnpr_cloud_find_property(cloud, PNPR_PROP_FEATURE_DIR_Y);
    const pnpr_property *dz = pnpr_cloud_find_property(cloud, PNPR_PROP_FEATURE_DIR_Z);
    if (!cls || !dx || !dy || !dz) {
        memset(r_lines, 0, sizeof *r_lines);
        return PNPR_ERR_NOT_FOUND;
    }
    size_t m = 0;
    for (size_t i = 0; i < cloud->count; i++) m += pnpr_type_get(cls->type, cls->data, i) == PNPR_CLASS_DIRECTIONAL;
    float *p = malloc((m ? m : 1) * 3 * sizeof *p), *d = malloc((m ? m : 1) * 3 * sizeof *d);
    if (!p || !d) { free(p); free(d); memset(r_lines, 0, sizeof *r_lines); return PNPR_ERR_OUT_OF_MEMORY; }
    size_t j = 0;
    for (size_t i = 0; i < cloud->count; i++) {
        if (pnpr_type_get(cls->type, cls->data, i) != PNPR_CLASS_DIRECTIONAL) continue;
        memcpy(p + 3 * j, cloud->xyz + 3 * i, 3 * sizeof(float));
        d[3 * j] = (float)pnpr_type_get(dx->type, dx->data, i);
        d[3 * j + 1] = (float)pnpr_type_get(dy->type, dy->data, i);
        d[3 * j + 2] = (float)pnpr_type_get(dz->type, dz->data, i);
        j++;
    }
    pnpr_status st = pnpr_profile_lines_points(p, d, m, cloud->origin, opts, r_lines, r_stats);
    free(p);
    free(d);
    return st;
}
