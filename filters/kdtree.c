/* kd-tree with kNN and radius queries (see include/pointnpr/knn.h).
 *
 * Layout: nodes in an array, built top-down; the left child of node i is i+1, the right child is
 * stored explicitly. Leaves hold a contiguous range of the reordered point array, so a leaf scan
 * touches consecutive memory. Queries keep the k best candidates in a sorted list and
 * descend into the nearer child first, skipping the far child when the splitting plane is
 * farther than the current k-th distance. */
#include <pointnpr/knn.h>

#include "../core/internal.h"
#include "kdtree_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "../core/vec3.h"

#define LEAF_SIZE 12

typedef struct node {
    float split;      /* leaves: unused */
    uint32_t right;   /* index of right child; 0 for a leaf */
    uint32_t begin, end; /* point range [begin, end) */
    uint8_t axis;
} node;

struct pnpr_kdtree {
    size_t count;
    float *pts;      /* 3*count, in tree order */
    uint32_t *index; /* original index of each tree-order point */
    node *nodes;
    size_t node_count;
};

static void swap_pt(pnpr_kdtree *t, size_t a, size_t b)
{
    float tmp[3];
    memcpy(tmp, t->pts + 3 * a, sizeof tmp);
    memcpy(t->pts + 3 * a, t->pts + 3 * b, sizeof tmp);
    memcpy(t->pts + 3 * b, tmp, sizeof tmp);
    uint32_t ti = t->index[a]; t->index[a] = t->index[b]; t->index[b] = ti;
}

/* Quickselect: afterwards the point at position k has the k-th smallest coordinate on `axis`
 * within [lo, hi), smaller-or-equal ones before it, greater-or-equal after. Median-of-three
 * pivots; ranges of equal values are handled by the three-way partition. */
static void select_kth(pnpr_kdtree *t, size_t lo, size_t hi, size_t k, int axis)
{
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        float a = t->pts[3 * lo + axis], b = t->pts[3 * mid + axis], c = t->pts[3 * (hi - 1) + axis];
        float pivot = a < b ? (b < c ? b : (a < c ? c : a)) : (a < c ? a : (b < c ? c : b));
        /* three-way partition: [lo,lt) < pivot, [lt,gt) == pivot, [gt,hi) > pivot */
        size_t lt = lo, i = lo, gt = hi;
        while (i < gt) {
            float v = t->pts[3 * i + axis];
            if (v < pivot) swap_pt(t, lt++, i++);
            else if (v > pivot) swap_pt(t, i, --gt);
            else i++;
        }
        if (k < lt) hi = lt;
        else if (k >= gt) lo = gt;
        else return;
    }
}

/* Every range of more than LEAF_SIZE points is split at its median position, so the tree's
 * shape depends on the point count alone: leaves(m) = leaves(m/2) + leaves(m - m/2). The two
 * halves of m differ by at most one, so carrying the pair (leaves(m), leaves(m+1)) down the
 * halvings costs O(log m). A full binary tree has 2 * leaves - 1 nodes. */
static void leaves_pair(size_t m, size_t *r_lm, size_t *r_lm1)
{
    if (m + 1 <= LEAF_SIZE) { *r_lm = 1; *r_lm1 = 1; return; }
    if (m <= LEAF_SIZE) { /* m fits, m+1 splits into two leaves */
        *r_lm = 1; *r_lm1 = 2; return;
    }
    size_t a = m / 2, la, la1;
    leaves_pair(a, &la, &la1);
    if (m % 2 == 0) { *r_lm = 2 * la; *r_lm1 = la + la1; } /* m = (a,a),   m+1 = (a,a+1) */
    else { *r_lm = la + la1; *r_lm1 = 2 * la1; }            /* m = (a,a+1), m+1 = (a+1,a+1) */
}

static size_t subtree_nodes(size_t m)
{
    size_t l, l1;
    leaves_pair(m, &l, &l1);
    return 2 * l - 1;
}

/* Builds the subtree of points [begin, end) into node `id` and the ids after it (preorder:
 * left child id+1, right child id+1+nodes(left)). Subtrees below `par_depth` are queued in
 * `tasks` instead, when tasks is not NULL. */
typedef struct build_task { size_t begin, end; uint32_t id; } build_task;

static void build_rec(pnpr_kdtree *t, size_t begin, size_t end, uint32_t id, int depth,
                      int par_depth, build_task *tasks, size_t *ntasks)
{
    if (tasks && depth == par_depth) {
        tasks[*ntasks].begin = begin; tasks[*ntasks].end = end; tasks[*ntasks].id = id;
        (*ntasks)++;
        return;
    }
    node *nd = &t->nodes[id];
    memset(nd, 0, sizeof *nd);
    nd->begin = (uint32_t)begin;
    nd->end = (uint32_t)end;
    if (end - begin <= LEAF_SIZE) return;

    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = begin; i < end; i++)
        for (int a = 0; a < 3; a++) {
            float v = t->pts[3 * i + a];
            if (v < lo[a]) lo[a] = v;
            if (v > hi[a]) hi[a] = v;
        }
    int axis = 0;
    for (int a = 1; a < 3; a++)
        if (hi[a] - lo[a] > hi[axis] - lo[axis]) axis = a;
    size_t mid = begin + (end - begin) / 2;
    /* Coincident points are still split (by position in the array) so that leaves stay small
     * and a cloud of exact duplicates is not one huge leaf. */
    if (hi[axis] > lo[axis]) select_kth(t, begin, end, mid, axis);
    nd->axis = (uint8_t)axis;
    nd->split = t->pts[3 * mid + axis];
    nd->right = (uint32_t)(id + 1 + subtree_nodes(mid - begin));
    uint32_t right = nd->right;
    build_rec(t, begin, mid, id + 1, depth + 1, par_depth, tasks, ntasks);
    build_rec(t, mid, end, right, depth + 1, par_depth, tasks, ntasks);
}

typedef struct build_job { pnpr_kdtree *t; const build_task *tasks; } build_job;

static void build_range(void *ctx, size_t begin, size_t end)
{
    build_job *j = ctx;
    for (size_t i = begin; i < end; i++)
        build_rec(j->t, j->tasks[i].begin, j->tasks[i].end, j->tasks[i].id, 0, -1, NULL, NULL);
}

pnpr_status pnpr_kdtree_build(const float *xyz, size_t count, size_t stride_bytes,
                              pnpr_kdtree **r_tree)
{
    return pnpr_kdtree_build_threads(xyz, count, stride_bytes, 0, r_tree);
}

pnpr_status pnpr_kdtree_build_threads(const float *xyz, size_t count, size_t stride_bytes,
                                      int threads, pnpr_kdtree **r_tree)
{
    if (!r_tree) return PNPR_ERR_INVALID_ARGUMENT;
    *r_tree = NULL;
    if ((count && !xyz) || count >= PNPR_INDEX_NONE) return PNPR_ERR_INVALID_ARGUMENT;
    if (stride_bytes == 0) stride_bytes = 3 * sizeof(float);
    pnpr_kdtree *t = calloc(1, sizeof *t);
    if (!t) return PNPR_ERR_OUT_OF_MEMORY;
    t->pts = malloc((count ? count : 1) * 3 * sizeof(float));
    t->index = malloc((count ? count : 1) * sizeof(uint32_t));
    if (!t->pts || !t->index) { pnpr_kdtree_free(t); return PNPR_ERR_OUT_OF_MEMORY; }
    size_t n = 0;
    for (size_t i = 0; i < count; i++) {
        const float *p = (const float *)((const char *)xyz + i * stride_bytes);
        if (!pnpr_finite3f(p)) continue;
        memcpy(t->pts + 3 * n, p, 3 * sizeof(float));
        t->index[n++] = (uint32_t)i;
    }
    t->count = n;
    t->node_count = subtree_nodes(n);
    t->nodes = malloc(t->node_count * sizeof *t->nodes);
    if (!t->nodes) { pnpr_kdtree_free(t); return PNPR_ERR_OUT_OF_MEMORY; }
    /* The top levels sequentially, just enough of them for one subtree per thread (at most 16:
     * halves split at the median are equal in size), then the subtrees in parallel. On 2 threads
     * only the root's split is sequential: 1M random points built in 0.150 s instead of 0.169 s with
     * the 4 sequential levels before (0.280 s on one thread). The tree is the same either way. */
    enum { PAR_DEPTH_MAX = 4 };
    int par_depth = 0, nt = threads > 0 ? threads : pnpr_default_threads();
    while (par_depth < PAR_DEPTH_MAX && (1 << par_depth) < nt) par_depth++;
    build_task tasks[1 << PAR_DEPTH_MAX];
    size_t ntasks = 0;
    build_rec(t, 0, n, 0, 0, par_depth, tasks, &ntasks);
    build_job j = {t, tasks};
    pnpr_status st = pnpr_parallel_for(ntasks, 1, threads, build_range, &j, NULL, "kd-tree");
    if (st != PNPR_OK) { pnpr_kdtree_free(t); return st; }
    *r_tree = t;
    return PNPR_OK;
}

pnpr_status pnpr_kdtree_detach(pnpr_kdtree *t, float **r_points, uint32_t **r_indices)
{
    if (!t || !r_points || !r_indices) return PNPR_ERR_INVALID_ARGUMENT;
    *r_points = t->pts;
    *r_indices = t->index;
    t->pts = NULL;
    t->index = NULL;
    pnpr_kdtree_free(t);
    return PNPR_OK;
}

void pnpr_kdtree_free(pnpr_kdtree *t)
{
    if (!t) return;
    free(t->pts);
    free(t->index);
    free(t->nodes);
    free(t);
}

pnpr_status pnpr_kdtree_renumber(pnpr_kdtree *t, uint32_t *r_old)
{
    if (!t || (t->count && !r_old)) return PNPR_ERR_INVALID_ARGUMENT;
    memcpy(r_old, t->index, t->count * sizeof *r_old);
    for (size_t p = 0; p < t->count; p++) t->index[p] = (uint32_t)p;
    return PNPR_OK;
}

size_t pnpr_kdtree_size(const pnpr_kdtree *t)
{
    return t ? t->count : 0;
}

/* The k best candidates (dist2, idx) so far. Up to BEST_SORTED_MAX of them are kept sorted
 * ascending by (distance, id): an offer shifts the worse ones up by one. For the k of normals and
 * spacings this costs less than a heap's sifts and its final sort: the kNN of the 1M-point
 * benchmark cloud on one thread took 1.27 s instead of 1.61 s at k = 16, 4.4 s instead of 6.7 s at
 * k = 64 and 25.6 s instead of 28.9 s at k = 256. A larger k keeps a max-heap by distance (root =
 * the worst), whose O(log k) offer wins at some point beyond, and sorts it at the end.
 * Ties: the input index orders points at an equal distance, so on exact grids (the generated
 * test scenes, quantised LAS coordinates) the k-th ring is cut the same way at the origin and at
 * 1e7, and the same in a tile of the cloud as in the whole. Results are deterministic either way. */
enum { BEST_SORTED_MAX = PNPR_KNN_SORTED_MAX };

typedef struct best {
    float *d;
    uint32_t *i;
    size_t n, k;
    const uint32_t *map; /* tree position -> reported id; NULL = report tree positions */
    const uint32_t *key; /* reported id -> its input index, for ties; NULL = the id is one */
} best;

/* Equal distances are ordered by input index whatever the ids are, so that a cloud and any subset
 * of it in the same order (a tile, tiles.h) list tied neighbours alike. */
static uint32_t tie_key(const best *h, uint32_t id)
{
    return h->key ? h->key[id] : id;
}

/* Puts (d, idx) at the root's place and sifts it down among the first h->n entries. */
static void sift_down(best *h, float d, uint32_t idx)
{
    size_t c = 0;
    for (;;) {
        size_t l = 2 * c + 1, r = l + 1, m = c;
        float md = d;
        if (l < h->n && h->d[l] > md) { m = l; md = h->d[l]; }
        if (r < h->n && h->d[r] > md) { m = r; }
        if (m == c) break;
        h->d[c] = h->d[m]; h->i[c] = h->i[m];
        c = m;
    }
    h->d[c] = d; h->i[c] = idx;
}

static void heap_offer(best *h, float d, uint32_t idx)
{
    if (h->n == h->k) { sift_down(h, d, idx); return; }
    size_t c = h->n++;
    while (c > 0 && d > h->d[(c - 1) / 2]) {
        size_t p = (c - 1) / 2;
        h->d[c] = h->d[p]; h->i[c] = h->i[p];
        c = p;
    }
    h->d[c] = d; h->i[c] = idx;
}

/* Callers offer only what best_takes accepts: when full, the worst is dropped. */
static void best_offer(best *h, float d, uint32_t idx)
{
    if (h->k > BEST_SORTED_MAX) { heap_offer(h, d, idx); return; }
    size_t c = h->n < h->k ? h->n++ : h->k - 1;
    while (c > 0 && (h->d[c - 1] > d || (h->d[c - 1] == d && tie_key(h, h->i[c - 1]) > tie_key(h, idx)))) {
        h->d[c] = h->d[c - 1]; h->i[c] = h->i[c - 1];
        c--;
    }
    h->d[c] = d; h->i[c] = idx;
}

static float best_bound(const best *h)
{
    return h->n < h->k ? INFINITY : h->d[h->k > BEST_SORTED_MAX ? 0 : h->k - 1];
}

/* Whether (d, id) enters: nearer than the k-th, or (sorted list) as near with a smaller input index. */
static int best_takes(const best *h, float d, uint32_t id)
{
    float b = best_bound(h);
    return d < b || (d == b && h->k <= BEST_SORTED_MAX && tie_key(h, id) < tie_key(h, h->i[h->k - 1]));
}

/* The heap's contents ascending (pop the worst to the end); a sorted list already is. */
static void best_finish(best *h)
{
    if (h->k <= BEST_SORTED_MAX) return;
    size_t n = h->n;
    while (h->n > 1) {
        float d = h->d[0]; uint32_t i = h->i[0];
        size_t last = --h->n;
        sift_down(h, h->d[last], h->i[last]); /* the last element, from the root */
        h->d[last] = d; h->i[last] = i;
    }
    h->n = n;
}

/* Descends near child first; `rd` is the squared distance from q to the node's cell, kept
 * incrementally per axis (Arya & Mount): the far child's cell distance replaces this axis'
 * offset with the distance to the splitting plane, so pruning uses the whole box, not just the
 * last plane. */
static void knn_rec(const pnpr_kdtree *t, uint32_t id, const float q[3], best *h, float rd, float off[3])
{
    const node *nd = &t->nodes[id];
    if (nd->right == 0) {
        for (uint32_t p = nd->begin; p < nd->end; p++) {
            float d = pnpr_dist2f(t->pts + 3 * p, q);
            uint32_t pid = h->map ? h->map[p] : p;
            if (best_takes(h, d, pid)) best_offer(h, d, pid);
        }
        return;
    }
    const int axis = nd->axis;
    float diff = q[axis] - nd->split;
    uint32_t near_c = diff < 0 ? id + 1 : nd->right, far_c = diff < 0 ? nd->right : id + 1;
    knn_rec(t, near_c, q, h, rd, off);
    float old = off[axis];
    float rd_far = rd - old * old + diff * diff;
    /* a far cell at exactly the bound may hold a tie with a smaller input index (sorted list):
     * visited, so that the k-th place does not depend on the tree; but not at distance 0, where
     * clusters of exact duplicates would visit each other's leaves (their cut stays the tree's:
     * pnpr_tile_certify knows) */
    float bound = best_bound(h);
    if (rd_far < bound || (rd_far == bound && bound > 0 && h->k <= BEST_SORTED_MAX)) {
        off[axis] = diff;
        knn_rec(t, far_c, q, h, rd_far, off);
        off[axis] = old;
    }
}

static size_t knn_query(const pnpr_kdtree *t, const float q[3], size_t k, uint32_t *r_idx,
                        float *r_dist2, int tree_order)
{
    if (!r_idx || k == 0) return 0;
    for (size_t j = 0; j < k; j++) {
        r_idx[j] = PNPR_INDEX_NONE;
        if (r_dist2) r_dist2[j] = INFINITY;
    }
    if (!t || t->count == 0 || !q || !pnpr_finite3f(q)) return 0;
    size_t kk = k < t->count ? k : t->count;
    /* r_idx doubles as the list's index storage; distances need their own buffer. */
    float stack_d[64];
    float *d = r_dist2 ? r_dist2 : (kk <= 64 ? stack_d : malloc(kk * sizeof(float)));
    if (!d) return 0;
    best h = {d, r_idx, 0, kk, tree_order ? NULL : t->index, tree_order ? t->index : NULL};
    float off[3] = {0, 0, 0};
    knn_rec(t, 0, q, &h, 0.0f, off);
    best_finish(&h);
    if (!r_dist2 && d != stack_d) free(d);
    return h.n;
}

size_t pnpr_kdtree_knn(const pnpr_kdtree *t, const float q[3], size_t k, uint32_t *r_idx,
                       float *r_dist2)
{
    return knn_query(t, q, k, r_idx, r_dist2, 0);
}

static size_t radius_rec(const pnpr_kdtree *t, uint32_t id, const float q[3], float r2,
                         uint32_t *r_idx, size_t cap, size_t found)
{
    const node *nd = &t->nodes[id];
    if (nd->right == 0) {
        for (uint32_t p = nd->begin; p < nd->end; p++) {
            if (pnpr_dist2f(t->pts + 3 * p, q) <= r2) {
                if (found < cap) r_idx[found] = t->index[p];
                found++;
            }
        }
        return found;
    }
    float diff = q[nd->axis] - nd->split;
    if (diff <= 0 || diff * diff <= r2) found = radius_rec(t, id + 1, q, r2, r_idx, cap, found);
    if (diff >= 0 || diff * diff <= r2) found = radius_rec(t, nd->right, q, r2, r_idx, cap, found);
    return found;
}

size_t pnpr_kdtree_radius(const pnpr_kdtree *t, const float q[3], float radius,
                          uint32_t *r_idx, size_t cap)
{
    if (!t || t->count == 0 || !q || !pnpr_finite3f(q) || !(radius >= 0) || !isfinite(radius)) return 0;
    if (!r_idx) cap = 0;
    return radius_rec(t, 0, q, radius * radius, r_idx, cap, 0);
}

/* radius_rec that stops once `cap` points are found (the same first ones, in the same order). */
static size_t radius_first_rec(const pnpr_kdtree *t, uint32_t id, const float q[3], float r2, uint32_t *r_idx,
                               size_t cap, size_t found)
{
    const node *nd = &t->nodes[id];
    if (nd->right == 0) {
        for (uint32_t p = nd->begin; p < nd->end && found < cap; p++) {
            if (pnpr_dist2f(t->pts + 3 * p, q) <= r2) r_idx[found++] = t->index[p];
        }
        return found;
    }
    float diff = q[nd->axis] - nd->split;
    if (found < cap && (diff <= 0 || diff * diff <= r2)) found = radius_first_rec(t, id + 1, q, r2, r_idx, cap, found);
    if (found < cap && (diff >= 0 || diff * diff <= r2)) found = radius_first_rec(t, nd->right, q, r2, r_idx, cap, found);
    return found;
}

size_t pnpr_kdtree_radius_first(const pnpr_kdtree *t, const float q[3], float radius, uint32_t *r_idx, size_t cap)
{
    if (!t || t->count == 0 || !q || !pnpr_finite3f(q) || !(radius >= 0) || !isfinite(radius) || !r_idx || !cap) return 0;
    return radius_first_rec(t, 0, q, radius * radius, r_idx, cap, 0);
}

typedef struct self_job {
    const pnpr_kdtree *tree;
    size_t k;
    uint32_t *idx;
    float *dist2;
    int tree_order;
} self_job;

static void self_range(void *ctx, size_t begin, size_t end)
{
    self_job *j = ctx;
    for (size_t p = begin; p < end; p++) {
        size_t row = j->tree_order ? p : j->tree->index[p];
        knn_query(j->tree, j->tree->pts + 3 * p, j->k, j->idx + row * j->k, j->dist2 ? j->dist2 + row * j->k : NULL,
                  j->tree_order);
    }
}

/* Rows of points left out of the tree (NaN/Inf) are "none". */
static void fill_none(uint32_t *idx, float *dist2, size_t k)
{
    for (size_t r = 0; r < k; r++) {
        idx[r] = PNPR_INDEX_NONE;
        if (dist2) dist2[r] = INFINITY;
    }
}

pnpr_status pnpr_knn_self(const pnpr_kdtree *tree, size_t count, size_t k, const pnpr_knn_options *opts,
                          uint32_t *r_idx, float *r_dist2)
{
    if (!tree || (count && !r_idx) || k == 0 || count < tree->count) return PNPR_ERR_INVALID_ARGUMENT;
    if (count && k > SIZE_MAX / sizeof(float) / count) return PNPR_ERR_INVALID_ARGUMENT;
    static const pnpr_knn_options defaults;
    if (!opts) opts = &defaults;
    if (opts->tree_order) count = tree->count;
    if (tree->count < count) { /* some points were left out: mark their rows first */
        uint8_t *in = calloc(count, 1);
        if (!in) return PNPR_ERR_OUT_OF_MEMORY;
        for (size_t p = 0; p < tree->count; p++) in[tree->index[p]] = 1;
        for (size_t i = 0; i < count; i++)
            if (!in[i]) fill_none(r_idx + i * k, r_dist2 ? r_dist2 + i * k : NULL, k);
        free(in);
    }
    self_job j = {tree, k, r_idx, r_dist2, opts->tree_order};
    return pnpr_parallel_for(tree->count, 4096, opts->threads, self_range, &j, &opts->progress, "knn");
}

typedef struct knn_job {
    const pnpr_kdtree *tree;
    const char *xyz;
    size_t stride, k;
    uint32_t *idx;
    float *dist2;
} knn_job;

static void knn_range(void *ctx, size_t begin, size_t end)
{
    knn_job *j = ctx;
    for (size_t i = begin; i < end; i++)
        pnpr_kdtree_knn(j->tree, (const float *)(j->xyz + i * j->stride), j->k, j->idx + i * j->k,
                        j->dist2 ? j->dist2 + i * j->k : NULL);
}

pnpr_status pnpr_knn_all(const pnpr_kdtree *tree, const float *query_xyz, size_t query_count,
                         size_t query_stride_bytes, size_t k, const pnpr_knn_options *opts,
                         uint32_t *r_idx, float *r_dist2)
{
    if (!tree || (query_count && (!query_xyz || !r_idx)) || k == 0) return PNPR_ERR_INVALID_ARGUMENT;
    if (query_count && k > SIZE_MAX / sizeof(float) / query_count) return PNPR_ERR_INVALID_ARGUMENT;
    static const pnpr_knn_options defaults;
    if (!opts) opts = &defaults;
    knn_job j = {tree, (const char *)query_xyz, query_stride_bytes ? query_stride_bytes : 3 * sizeof(float),
                 k, r_idx, r_dist2};
    return pnpr_parallel_for(query_count, 4096, opts->threads, knn_range, &j, &opts->progress, "knn");
}

float pnpr_kdtree_median_spacing(const pnpr_kdtree *t, size_t max_samples)
{
    if (!t || t->count < 2) return 0;
    if (max_samples == 0) max_samples = 20000;
    size_t step = t->count > max_samples ? t->count / max_samples : 1, ns = 0;
    float *d = malloc((t->count / step + 1) * sizeof *d);
    if (!d) return 0;
    for (size_t p = 0; p < t->count; p += step) {
        uint32_t idx[8];
        float d2[8];
        size_t got = knn_query(t, t->pts + 3 * p, 8, idx, d2, 1);
        for (size_t r = 0; r < got; r++)
            if (d2[r] > 0) { d[ns++] = sqrtf(d2[r]); break; }
    }
    float h = 0;
    if (ns) h = pnpr_median_float(d, ns);
    free(d);
    return h;
}

/* ---- connected components at a distance (kdtree_internal.h) ---------------------------------- */

typedef struct cc {
    const pnpr_kdtree *t;
    float r2;
    float *box;      /* 6 floats per node: lo xyz, hi xyz */
    uint32_t *rep;   /* per node: a point whose component holds the whole node, or NONE */
    uint32_t *parent; /* union-find over tree positions */
} cc;

static uint32_t cc_find(uint32_t *parent, uint32_t x)
{
    while (parent[x] != x) { parent[x] = parent[parent[x]]; x = parent[x]; }
    return x;
}

static void cc_union(uint32_t *parent, uint32_t a, uint32_t b)
{
    a = cc_find(parent, a);
    b = cc_find(parent, b);
    if (a != b) parent[a < b ? b : a] = a < b ? a : b;
}

/* Node boxes bottom-up: children have larger ids than their parent (preorder). */
static void cc_boxes(const pnpr_kdtree *t, float *box)
{
    for (size_t id = t->node_count; id-- > 0;) {
        const node *nd = &t->nodes[id];
        float *b = box + 6 * id;
        for (int a = 0; a < 3; a++) { b[a] = INFINITY; b[3 + a] = -INFINITY; }
        if (nd->right == 0) {
            for (uint32_t p = nd->begin; p < nd->end; p++)
                for (int a = 0; a < 3; a++) {
                    b[a] = fminf(b[a], t->pts[3 * p + a]);
                    b[3 + a] = fmaxf(b[3 + a], t->pts[3 * p + a]);
                }
            continue;
        }
        const float *l = box + 6 * (id + 1), *r = box + 6 * (size_t)nd->right;
        for (int a = 0; a < 3; a++) { b[a] = fminf(l[a], r[a]); b[3 + a] = fmaxf(l[3 + a], r[3 + a]); }
    }
}

/* Squared distances from q to the nearest and the farthest point of a box, with the float
 * formula of the point test (rounding is monotone, so near <= and far >= every point's value). */
static void cc_box_d2(const float *b, const float q[3], float *r_near, float *r_far)
{
    float n = 0, f = 0;
    for (int a = 0; a < 3; a++) {
        float lo = b[a] - q[a], hi = b[3 + a] - q[a];
        float gap = lo > 0 ? lo : (hi < 0 ? -hi : 0.0f), far = fmaxf(fabsf(lo), fabsf(hi));
        n += gap * gap;
        f += far * far;
    }
    *r_near = n;
    *r_far = f;
}

/* Leaf: joins the points within reach; marks the leaf when all its points share a component. */
static void cc_leaf(cc *c, uint32_t id, const float q[3], uint32_t p)
{
    const node *nd = &c->t->nodes[id];
    const float *pts = c->t->pts;
    for (uint32_t j = nd->begin; j < nd->end; j++) {
        if (pnpr_dist2f(pts + 3 * j, q) <= c->r2) cc_union(c->parent, p, j);
    }
    uint32_t root = cc_find(c->parent, nd->begin), same = 1;
    for (uint32_t j = nd->begin + 1; j < nd->end && same; j++) same = cc_find(c->parent, j) == root;
    if (same) c->rep[id] = nd->begin;
}

static void cc_rec(cc *c, uint32_t id, const float q[3], uint32_t p)
{
    float near, far;
    cc_box_d2(c->box + 6 * (size_t)id, q, &near, &far);
    if (!(near <= c->r2)) return;
    uint32_t rep = c->rep[id];
    if (rep != PNPR_INDEX_NONE && cc_find(c->parent, rep) == cc_find(c->parent, p)) return;
    const node *nd = &c->t->nodes[id];
    if (far <= c->r2) { /* every point of the node is within reach */
        if (rep != PNPR_INDEX_NONE) { cc_union(c->parent, p, rep); return; }
        for (uint32_t j = nd->begin; j < nd->end; j++) cc_union(c->parent, p, j);
        c->rep[id] = p;
        return;
    }
    if (nd->right == 0) { cc_leaf(c, id, q, p); return; }
    cc_rec(c, id + 1, q, p);
    cc_rec(c, nd->right, q, p);
    uint32_t rl = c->rep[id + 1], rr = c->rep[nd->right];
    if (c->rep[id] == PNPR_INDEX_NONE && rl != PNPR_INDEX_NONE && rr != PNPR_INDEX_NONE &&
        cc_find(c->parent, rl) == cc_find(c->parent, rr))
        c->rep[id] = rl;
}

pnpr_status pnpr_kdtree_components(const pnpr_kdtree *t, size_t count, float distance,
                                   const pnpr_progress *progress, uint32_t *r_labels)
{
    if (!t || (count && !r_labels) || count < t->count || !(distance >= 0)) return PNPR_ERR_INVALID_ARGUMENT;
    for (size_t i = 0; i < count; i++) r_labels[i] = (uint32_t)i;
    if (t->count == 0) return PNPR_OK;
    cc c = {t, distance * distance, malloc(6 * t->node_count * sizeof(float)),
            malloc(t->node_count * sizeof(uint32_t)), malloc(t->count * sizeof(uint32_t))};
    pnpr_status st = PNPR_OK;
    if (!c.box || !c.rep || !c.parent) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
    cc_boxes(t, c.box);
    for (size_t id = 0; id < t->node_count; id++) c.rep[id] = PNPR_INDEX_NONE;
    for (size_t p = 0; p < t->count; p++) c.parent[p] = (uint32_t)p;
    for (size_t p = 0; p < t->count; p++) { /* tree order: neighbouring queries share nodes */
        cc_rec(&c, 0, t->pts + 3 * p, (uint32_t)p);
        if ((p & 0x3FFF) == 0 && pnpr_progress_report(progress, "components", (double)p / (double)t->count)) {
            st = PNPR_ERR_CANCELLED;
            goto done;
        }
    }
    for (size_t p = 0; p < t->count; p++) r_labels[t->index[p]] = t->index[cc_find(c.parent, (uint32_t)p)];
done:
    free(c.box); free(c.rep); free(c.parent);
    return st;
}
