/* Region adjacency graph (RAG): merging of similar / small regions, and the region hierarchy of
 * Chi & Lee (sec. 3.2, eq. 4 and Fig. 4).
 *
 * The graph: regions are the segments of a labelling; two regions are adjacent when some point of
 * one has a point of the other among its first k nearest neighbours (kNN rows as pnpr_knn_self
 * writes them; the kNN relation is not symmetric, either direction counts).
 *
 * One engine serves three uses. It keeps, per region, the point count and the sums of the
 * colours (RGB in 0..1 and CIE L*a*b*), so means are exact after any number of merges; a
 * union-find maps merged regions to their representative; a binary heap holds candidate pairs
 * with the version numbers of both regions when the pair was pushed (a pair is stale once either
 * region has merged; stale pairs are skipped when popped: "lazy deletion"). After a merge the
 * new region's neighbour list is the union of both lists (representatives, deduplicated) and a
 * pair with every neighbour is pushed at its new cost — except for "hub" regions of more than 256
 * neighbours, whose older pairs are re-evaluated lazily when popped (see merge()).
 *
 *  colour merge  cost = CIE76 delta E of the mean L*a*b* colours; only pairs below the bound
 *  size merge    cost = delta E, pushed only while one region is smaller than min_size
 *  hierarchy     cost = e_ij (eq. 4): d_HSI if both regions are smaller than alpha x the mean
 *                size, else epsilon x d_HSI. d_HSI is the Euclidean distance in the HSI double
 *                cone's cylinder coordinates (S cos H, S sin H, I) of the mean RGB colours (the
 *                paper: "distance in the HSI color space between two mean colors"):
 *                  I = (R+G+B)/3, S = 1 - min(R,G,B)/I (0 for black), H = atan2(sqrt3 (G-B), 2R-G-B)
 *                  d^2 = (I1-I2)^2 + S1^2 + S2^2 - 2 S1 S2 cos(H1-H2), in [0, sqrt 5].
 *                Size_mean is the mean size of the INPUT regions (fixed while merging; the paper
 *                does not say whether it follows the merges). The paper's rule, read literally,
 *                makes every pair that involves a large region 20x cheaper, so small fragments
 *                are absorbed by their large neighbours first and pairs of small regions merge
 *                last (small details survive to the coarse levels). Ties break by the smaller
 *                region ids, so the hierarchy is deterministic.
 *                The paper merges "until one node"; a graph with several connected components
 *                cannot, so the remaining roots (if at most JOIN_MAX) are then made mutually
 *                adjacent and merged by the same rule (documented option no_join).
 *
 * The hierarchy is a list of merges (node S+i = merge i), a binary tree over the regions. A
 * level is a prefix of that list: by segment count (the first S-N merges) or by a threshold on
 * the monotone `level` (running maximum of d_HSI), so levels nest. */
#include <pointnpr/segment.h>
#include <pointnpr/options.h>
#include <pointnpr/knn.h>

#include "../core/internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define JOIN_MAX 1024

enum { MODE_COLOR, MODE_SMALL, MODE_HIER };

typedef struct heap_entry {
    double cost;
    uint32_t a, b, va, vb;
} heap_entry;

typedef struct u32vec {
    uint32_t *v;
    uint32_t n, cap;
} u32vec;

typedef struct rag {
    uint32_t S;
    uint32_t *parent, *version, *node;
    uint32_t *clean_n; /* per region: list length after its last deduplication (0 = never: exact) */
    double *size;
    double *sum; /* 6 per region: r g b (0..1), L a b */
    u32vec *adj;
    heap_entry *heap;
    size_t heap_n, heap_cap;
    int mode;
    double max_distance, min_size, small_size, epsilon;
} rag;

static uint32_t find(uint32_t *parent, uint32_t x)
{
    while (parent[x] != x) { parent[x] = parent[parent[x]]; x = parent[x]; }
    return x;
}

static int vec_push(u32vec *v, uint32_t x)
{
    if (v->n == v->cap) {
        uint32_t cap = v->cap ? v->cap * 2 : 4;
        uint32_t *p = realloc(v->v, (size_t)cap * sizeof *p);
        if (!p) return 0;
        v->v = p; v->cap = cap;
    }
    v->v[v->n++] = x;
    return 1;
}

static int heap_less(const heap_entry *x, const heap_entry *y)
{
    if (x->cost != y->cost) return x->cost < y->cost;
    if (x->a != y->a) return x->a < y->a;
    return x->b < y->b;
}

static int heap_push(rag *g, heap_entry e)
{
    if (g->heap_n == g->heap_cap) {
        size_t cap = g->heap_cap ? g->heap_cap * 2 : 1024;
        heap_entry *p = realloc(g->heap, cap * sizeof *p);
        if (!p) return 0;
        g->heap = p; g->heap_cap = cap;
    }
    size_t i = g->heap_n++;
    while (i > 0) {
        size_t up = (i - 1) / 2;
        if (!heap_less(&e, &g->heap[up])) break;
        g->heap[i] = g->heap[up];
        i = up;
    }
    g->heap[i] = e;
    return 1;
}

static heap_entry heap_pop(rag *g)
{
    heap_entry top = g->heap[0], last = g->heap[--g->heap_n];
    size_t i = 0, n = g->heap_n;
    for (;;) {
        size_t c = 2 * i + 1;
        if (c >= n) break;
        if (c + 1 < n && heap_less(&g->heap[c + 1], &g->heap[c])) c++;
        if (!heap_less(&g->heap[c], &last)) break;
        g->heap[i] = g->heap[c];
        i = c;
    }
    if (n) g->heap[i] = last;
    return top;
}

static void hsi(const double *s, double size, double r_out[3])
{
    double r = s[0] / size, gr = s[1] / size, b = s[2] / size;
    double in = (r + gr + b) / 3;
    double mn = r < gr ? (r < b ? r : b) : (gr < b ? gr : b);
    double sat = in > 1e-12 ? 1 - mn / in : 0;
    double h = atan2(sqrt(3.0) * (gr - b), 2 * r - gr - b);
    r_out[0] = sat * cos(h); r_out[1] = sat * sin(h); r_out[2] = in;
}

static double hsi_distance(const rag *g, uint32_t a, uint32_t b)
{
    double x[3], y[3];
    hsi(g->sum + 6 * (size_t)a, g->size[a], x);
    hsi(g->sum + 6 * (size_t)b, g->size[b], y);
    return sqrt((x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) + (x[2] - y[2]) * (x[2] - y[2]));
}

static double lab_distance(const rag *g, uint32_t a, uint32_t b)
{
    const double *x = g->sum + 6 * (size_t)a + 3, *y = g->sum + 6 * (size_t)b + 3;
    double d2 = 0;
    for (int c = 0; c < 3; c++) {
        double d = x[c] / g->size[a] - y[c] / g->size[b];
        d2 += d * d;
    }
    return sqrt(d2);
}

/* Pushes the pair (a, b) (representatives) if the mode wants it. */
static int push_pair(rag *g, uint32_t a, uint32_t b)
{
    if (a > b) { uint32_t t = a; a = b; b = t; }
    double cost;
    if (g->mode == MODE_COLOR) {
        cost = lab_distance(g, a, b);
        if (!(cost < g->max_distance)) return 1;
    } else if (g->mode == MODE_SMALL) {
        if (!(g->size[a] < g->min_size || g->size[b] < g->min_size)) return 1;
        cost = lab_distance(g, a, b);
    } else {
        cost = hsi_distance(g, a, b);
        if (!(g->size[a] < g->small_size && g->size[b] < g->small_size)) cost *= g->epsilon;
    }
    heap_entry e = {cost, a, b, g->version[a], g->version[b]};
    return heap_push(g, e);
}

static void rag_free(rag *g)
{
    if (g->adj)
        for (uint32_t i = 0; i < g->S; i++) free(g->adj[i].v);
    free(g->adj); free(g->parent); free(g->version); free(g->node); free(g->size); free(g->sum); free(g->clean_n);
    free(g->heap);
    memset(g, 0, sizeof *g);
}

static pnpr_status rag_build(rag *g, const uint8_t *rgb, size_t count, const pnpr_region_graph *graph,
                             const uint32_t *labels, uint32_t S)
{
    memset(g, 0, sizeof *g);
    g->S = S;
    g->parent = malloc((size_t)S * sizeof *g->parent);
    g->version = calloc(S, sizeof *g->version);
    g->node = malloc((size_t)S * sizeof *g->node);
    g->size = calloc(S, sizeof *g->size);
    g->sum = calloc((size_t)S * 6, sizeof *g->sum);
    g->adj = calloc(S, sizeof *g->adj);
    g->clean_n = calloc(S, sizeof *g->clean_n);
    if (!g->parent || !g->version || !g->node || !g->size || !g->sum || !g->adj || !g->clean_n) return PNPR_ERR_OUT_OF_MEMORY;
    for (uint32_t i = 0; i < S; i++) { g->parent[i] = i; g->node[i] = i; }
    for (size_t i = 0; i < count; i++) {
        uint32_t l = labels[i];
        if (l >= S) continue;
        double *s = g->sum + 6 * (size_t)l;
        g->size[l] += 1;
        if (rgb) {
            float lab[3];
            pnpr_rgb_to_lab(rgb + 3 * i, lab);
            for (int c = 0; c < 3; c++) { s[c] += rgb[3 * i + c] / 255.0; s[3 + c] += lab[c]; }
        }
    }
    /* adjacency: canonical (min, max) pairs, sorted and deduplicated in blocks to bound memory */
    size_t cap = 1 << 16, n = 0;
    uint64_t *e = malloc(cap * sizeof *e);
    if (!e) return PNPR_ERR_OUT_OF_MEMORY;
    size_t kk = graph->k < graph->k_stride ? graph->k : graph->k_stride;
    for (size_t i = 0; i < count; i++) {
        uint32_t li = labels[i];
        if (li >= S) continue;
        const uint32_t *row = graph->knn + i * graph->k_stride;
        for (size_t r = 0; r < kk; r++) {
            uint32_t j = row[r];
            if (j == PNPR_INDEX_NONE || j >= count) continue;
            uint32_t lj = labels[j];
            if (lj >= S || lj == li) continue;
            if (n == cap) {
                qsort(e, n, sizeof *e, pnpr_cmp_u64);
                size_t u = 0;
                for (size_t q = 0; q < n; q++) if (!u || e[q] != e[u - 1]) e[u++] = e[q];
                n = u;
                if (n > cap / 2) {
                    uint64_t *p = realloc(e, cap * 2 * sizeof *e);
                    if (!p) { free(e); return PNPR_ERR_OUT_OF_MEMORY; }
                    e = p; cap *= 2;
                }
            }
            uint32_t a = li < lj ? li : lj, b = li < lj ? lj : li;
            e[n++] = (uint64_t)a << 32 | b;
        }
    }
    qsort(e, n, sizeof *e, pnpr_cmp_u64);
    for (size_t q = 0; q < n; q++) {
        if (q && e[q] == e[q - 1]) continue;
        uint32_t a = (uint32_t)(e[q] >> 32), b = (uint32_t)e[q];
        if (!vec_push(&g->adj[a], b) || !vec_push(&g->adj[b], a)) { free(e); return PNPR_ERR_OUT_OF_MEMORY; }
    }
    free(e);
    return PNPR_OK;
}

/* Pushes the pairs of every region with its neighbours (each pair once). */
static pnpr_status push_all(rag *g)
{
    for (uint32_t a = 0; a < g->S; a++) {
        if (find(g->parent, a) != a || g->size[a] <= 0) continue;
        for (uint32_t q = 0; q < g->adj[a].n; q++) {
            uint32_t b = find(g->parent, g->adj[a].v[q]);
            if (b > a && !push_pair(g, a, b)) return PNPR_ERR_OUT_OF_MEMORY;
        }
    }
    return PNPR_OK;
}

/* Replaces the ids of a's neighbour list by their representatives, drops a itself, sorts and
 * deduplicates. */
static void clean_list(rag *g, uint32_t a)
{
    u32vec *va = &g->adj[a];
    uint32_t u = 0;
    for (uint32_t q = 0; q < va->n; q++) {
        uint32_t r = find(g->parent, va->v[q]);
        if (r != a) va->v[u++] = r;
    }
    va->n = u;
    qsort(va->v, va->n, sizeof *va->v, pnpr_cmp_u32);
    u = 0;
    for (uint32_t q = 0; q < va->n; q++) if (!u || va->v[q] != va->v[u - 1]) va->v[u++] = va->v[q];
    va->n = u;
}

/* Merges b into a (both representatives); returns the new representative.
 * Regions with up to HUB neighbours are kept exact: the merged list is cleaned and a pair with
 * every neighbour is pushed at its new cost. A region that outgrows that ("hub": a large region
 * absorbing thousands of small noisy fragments) would make every merge cost O(degree log degree)
 * and flood the heap; for it only the pairs with the absorbed region's neighbours are pushed, its
 * list is cleaned when it has doubled, and its older pairs are re-evaluated when they are popped
 * (run() re-pushes a popped pair whose versions changed at its current cost). */
#define HUB 256
static uint32_t merge(rag *g, uint32_t a, uint32_t b, int *ok)
{
    if (g->adj[a].n < g->adj[b].n) { uint32_t t = a; a = b; b = t; }
    g->parent[b] = a;
    g->size[a] += g->size[b];
    for (int c = 0; c < 6; c++) g->sum[6 * (size_t)a + c] += g->sum[6 * (size_t)b + c];
    g->version[a]++;
    g->version[b]++;
    u32vec *va = &g->adj[a], vb = g->adj[b];
    memset(&g->adj[b], 0, sizeof g->adj[b]);
    for (uint32_t q = 0; q < vb.n; q++)
        if (!vec_push(va, vb.v[q])) { free(vb.v); *ok = 0; return a; }
    if (va->n <= HUB && !g->clean_n[a]) {
        free(vb.v);
        clean_list(g, a);
        for (uint32_t q = 0; q < va->n; q++)
            if (!push_pair(g, a, va->v[q])) { *ok = 0; return a; }
        return a;
    }
    /* hub: new pairs for b's former neighbours only; clean the list when it has doubled */
    if (!g->clean_n[a] || va->n > 2 * g->clean_n[a]) {
        clean_list(g, a);
        g->clean_n[a] = va->n ? va->n : 1;
    }
    for (uint32_t q = 0; q < vb.n; q++) {
        uint32_t r = find(g->parent, vb.v[q]);
        if (r != a && !push_pair(g, a, r)) { free(vb.v); *ok = 0; return a; }
    }
    free(vb.v);
    return a;
}

/* Pops pairs until the heap is empty; records merges when r_merges is not NULL. */
static pnpr_status run(rag *g, pnpr_segment_merge *r_merges, uint32_t *io_merge_count,
                       const pnpr_progress *progress)
{
    uint32_t m = io_merge_count ? *io_merge_count : 0;
    double level = m && r_merges ? r_merges[m - 1].level : 0;
    while (g->heap_n) {
        heap_entry e = heap_pop(g);
        if (find(g->parent, e.a) != e.a || find(g->parent, e.b) != e.b) continue;
        if (g->version[e.a] != e.va || g->version[e.b] != e.vb) {
            /* a pair of a hub is kept up to date lazily: re-evaluate it now */
            if ((g->clean_n[e.a] || g->clean_n[e.b]) && !push_pair(g, e.a, e.b)) return PNPR_ERR_OUT_OF_MEMORY;
            continue;
        }
        double dist = g->mode == MODE_HIER ? hsi_distance(g, e.a, e.b) : e.cost;
        uint32_t na = g->node[e.a], nb = g->node[e.b];
        int ok = 1;
        uint32_t r = merge(g, e.a, e.b, &ok);
        if (!ok) return PNPR_ERR_OUT_OF_MEMORY;
        if (r_merges) {
            if (dist > level) level = dist;
            pnpr_segment_merge *mg = &r_merges[m];
            mg->a = na < nb ? na : nb;
            mg->b = na < nb ? nb : na;
            mg->size = (uint32_t)g->size[r];
            mg->cost = (float)e.cost;
            mg->distance = (float)dist;
            mg->level = (float)level;
            g->node[r] = g->S + m;
        }
        m++;
        if ((m & 1023) == 0 && pnpr_progress_report(progress, "hierarchy", g->S > 1 ? (double)m / (g->S - 1) : 1))
            return PNPR_ERR_CANCELLED;
    }
    if (io_merge_count) *io_merge_count = m;
    return PNPR_OK;
}

/* Renumbers: representatives -> 0..S'-1 by first appearance, labels >= S after them in their
 * order (merged labels are < S' <= S, so the second pass sees only the original extras). */
static void relabel(rag *g, uint32_t *labels, size_t count, uint32_t *io_S)
{
    uint32_t S = g->S, next = 0;
    uint32_t *map = g->version; /* reused: version numbers are no longer needed */
    for (uint32_t i = 0; i < S; i++) map[i] = PNPR_LABEL_NONE;
    for (size_t i = 0; i < count; i++) {
        if (labels[i] >= S) continue;
        uint32_t r = find(g->parent, labels[i]);
        if (map[r] == PNPR_LABEL_NONE) map[r] = next++;
        labels[i] = map[r];
    }
    for (size_t i = 0; i < count; i++)
        if (labels[i] >= S && labels[i] != PNPR_LABEL_NONE) labels[i] = next + (labels[i] - S);
    *io_S = next;
}

pnpr_status pnpr_segment_merge_regions(const uint8_t *rgb, size_t count, const pnpr_region_graph *graph,
                                       float max_distance, uint32_t min_size, uint32_t *io_labels,
                                       uint32_t *io_segment_count)
{
    if (!io_segment_count || (count && (!io_labels || !graph || !graph->knn))) return PNPR_ERR_INVALID_ARGUMENT;
    uint32_t S = *io_segment_count;
    if (S <= 1 || (!(max_distance > 0) && min_size <= 1)) return PNPR_OK;
    rag g;
    pnpr_status st = rag_build(&g, rgb, count, graph, io_labels, S);
    if (st == PNPR_OK && max_distance > 0) {
        g.mode = MODE_COLOR;
        g.max_distance = max_distance;
        if ((st = push_all(&g)) == PNPR_OK) st = run(&g, NULL, NULL, NULL);
    }
    if (st == PNPR_OK && min_size > 1) {
        g.mode = MODE_SMALL;
        g.min_size = min_size;
        g.heap_n = 0;
        if ((st = push_all(&g)) == PNPR_OK) st = run(&g, NULL, NULL, NULL);
    }
    if (st == PNPR_OK) relabel(&g, io_labels, count, io_segment_count);
    rag_free(&g);
    return st;
}

pnpr_status pnpr_segment_hierarchy(const uint8_t *rgb, size_t count, const pnpr_region_graph *graph,
                                   const uint32_t *labels, uint32_t segment_count,
                                   const pnpr_hierarchy_options *opts, pnpr_segment_merge *r_merges,
                                   uint32_t *r_merge_count)
{
    if (!r_merge_count) return PNPR_ERR_INVALID_ARGUMENT;
    *r_merge_count = 0;
    if (segment_count <= 1) return PNPR_OK;
    if (!r_merges || !rgb || (count && (!labels || !graph || !graph->knn))) return PNPR_ERR_INVALID_ARGUMENT;
    pnpr_hierarchy_options o = opts ? *opts : (pnpr_hierarchy_options){0};
    const pnpr_hierarchy_options d = pnpr_hierarchy_defaults(); /* options.h */
    double alpha = o.alpha > 0 ? o.alpha : d.alpha, eps = o.epsilon > 0 ? o.epsilon : d.epsilon;
    rag g;
    pnpr_status st = rag_build(&g, rgb, count, graph, labels, segment_count);
    if (st != PNPR_OK) { rag_free(&g); return st; }
    double total = 0;
    uint32_t nonempty = 0;
    for (uint32_t i = 0; i < segment_count; i++) if (g.size[i] > 0) { total += g.size[i]; nonempty++; }
    g.mode = MODE_HIER;
    g.epsilon = eps;
    g.small_size = nonempty ? alpha * total / nonempty : 0;
    uint32_t m = 0;
    if ((st = push_all(&g)) == PNPR_OK) st = run(&g, r_merges, &m, &o.progress);
    if (st == PNPR_OK && !o.no_join) {
        /* join the disconnected parts: make the remaining roots mutually adjacent */
        uint32_t *roots = malloc((size_t)segment_count * sizeof *roots), nr = 0;
        if (!roots) st = PNPR_ERR_OUT_OF_MEMORY;
        for (uint32_t i = 0; st == PNPR_OK && i < segment_count; i++)
            if (find(g.parent, i) == i && g.size[i] > 0) roots[nr++] = i;
        if (st == PNPR_OK && nr > 1 && nr <= JOIN_MAX) {
            for (uint32_t a = 0; a < nr && st == PNPR_OK; a++)
                for (uint32_t b = 0; b < nr; b++)
                    if (a != b && !vec_push(&g.adj[roots[a]], roots[b])) { st = PNPR_ERR_OUT_OF_MEMORY; break; }
            if (st == PNPR_OK) st = push_all(&g);
            if (st == PNPR_OK) st = run(&g, r_merges, &m, &o.progress);
        }
        free(roots);
    }
    rag_free(&g);
    *r_merge_count = st == PNPR_OK ? m : 0;
    if (st == PNPR_OK) pnpr_progress_report(&o.progress, "hierarchy", 1.0);
    return st;
}

pnpr_status pnpr_segment_hierarchy_cut(const uint32_t *labels, size_t count, uint32_t segment_count,
                                       const pnpr_segment_merge *merges, uint32_t merge_count,
                                       uint32_t target_segments, float threshold,
                                       uint32_t *r_labels, uint32_t *r_segment_count)
{
    if (!r_segment_count || (count && (!labels || !r_labels)) || (merge_count && !merges))
        return PNPR_ERR_INVALID_ARGUMENT;
    if (merge_count >= segment_count && merge_count) return PNPR_ERR_INVALID_ARGUMENT;
    uint32_t m = 0;
    while (m < merge_count) {
        if (target_segments > 0 && segment_count - (m + 1) < target_segments) break;
        if (threshold > 0 && !(merges[m].level <= threshold)) break;
        if (target_segments == 0 && !(threshold > 0)) break;
        m++;
    }
    uint32_t nodes = segment_count + m;
    uint32_t *parent = malloc(((size_t)nodes + 1) * sizeof *parent);
    if (!parent) return PNPR_ERR_OUT_OF_MEMORY;
    for (uint32_t i = 0; i < nodes; i++) parent[i] = i;
    for (uint32_t i = 0; i < m; i++) {
        if (merges[i].a >= segment_count + i || merges[i].b >= segment_count + i) { free(parent); return PNPR_ERR_INVALID_ARGUMENT; }
        parent[merges[i].a] = segment_count + i;
        parent[merges[i].b] = segment_count + i;
    }
    /* resolve each leaf to its top node (parents point upwards, so no cycles) */
    for (uint32_t i = 0; i < segment_count; i++) {
        uint32_t r = i;
        while (parent[r] != r) r = parent[r];
        parent[i] = r;
    }
    /* number the top nodes by first appearance; points outside the hierarchy form one last segment */
    uint32_t *id = malloc(((size_t)nodes + 1) * sizeof *id);
    if (!id) { free(parent); return PNPR_ERR_OUT_OF_MEMORY; }
    for (uint32_t i = 0; i < nodes; i++) id[i] = PNPR_LABEL_NONE;
    uint32_t next = 0;
    int extra = 0;
    for (size_t i = 0; i < count; i++) {
        if (labels[i] >= segment_count) { extra = 1; continue; }
        uint32_t top = parent[labels[i]];
        if (id[top] == PNPR_LABEL_NONE) id[top] = next++;
    }
    for (size_t i = 0; i < count; i++)
        r_labels[i] = labels[i] < segment_count ? id[parent[labels[i]]] : next;
    free(parent);
    free(id);
    *r_segment_count = next + (extra ? 1 : 0);
    return PNPR_OK;
}
