/* 3D JSEG (Chi & Lee sec. 3.2, after Deng & Manjunath's JSEG) on an unorganised point cloud.
 *
 * 1. Quantisation. The paper uses the peer-group-filtering perceptual quantiser of Deng et al.;
 *    we use k-means in CIE L*a*b* (sRGB D65), which is perceptual too and simpler to reproduce:
 *    k-means++ initialisation from a seeded xorshift64* generator (deterministic), at most 20
 *    Lloyd iterations on a deterministic stride sample of at most SAMPLE_MAX points, then class
 *    centres closer than quant_distance (delta E) are merged (closest pair first, weighted
 *    means) — this plays the part of the paper's "threshold for color quantization" and makes a
 *    uniformly coloured cloud one class whatever `classes` is. Every point then takes the class
 *    of its nearest centre: the class map.
 * 2. J. For point p and its neighbourhood K (the k nearest points including p, optionally only
 *    those within radius), with positions relative to p in double:
 *      S_T = sum |P_k - m|^2,  S_W = sum_i sum_{k in K_i} |P_k - m_i|^2,  J = (S_T - S_W) / S_W.
 *    Defined results: fewer than 2 neighbours or S_T = 0 (coincident points) -> J = 0; one class
 *    -> S_W = S_T -> J = 0; S_W = 0 < S_T (every class collapsed onto one position, e.g.
 *    duplicated points of different colours) -> S_W is taken as 1e-6 S_T, J = 1e6 - 1.
 * 3. Seeds: points with J <= seed_factor * mean J (the paper: "below the mean J multiplied by a
 *    small constant"; <= so that a cloud where every J is 0 still has seeds), connected over the
 *    adjacency graph (the first ADJ_K neighbours of each point), components of at least
 *    seed_min_size points.
 * 4. Growing: the remaining points join regions in increasing J order (a heap keyed by (J, index),
 *    each point queued once, when a neighbour is labelled). A point joins, among the regions of its
 *    labelled neighbours, the one whose running mean L*a*b* colour is closest to its own colour.
 *    With grow_bound > 0, points with J >= grow_bound * mean J stop the growth (the paper's
 *    "user-selected bound"). Points never reached form regions of their own (connected
 *    components among themselves).
 * 5. Merging (the paper: "oversegmented regions whose size or color similarity is below a
 *    threshold to the neighboring clusters are then merged"): pnpr_segment_merge_regions with
 *    merge_distance (delta E of region means) then min_size.
 * The region hierarchy (eq. 4) is a separate call (pnpr_segment_hierarchy) over these regions. */
#include <pointnpr/segment.h>
#include <pointnpr/options.h>
#include <pointnpr/knn.h>

#include "../core/internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "../core/vec3.h"

#define SAMPLE_MAX 20000
#define ADJ_K 10
#define KMEANS_ITER 20


static uint64_t rng_next(uint64_t *s)
{
    uint64_t x = *s;
    x ^= x >> 12; x ^= x << 25; x ^= x >> 27;
    *s = x;
    return x * 0x2545F4914F6CDD1DULL;
}

static double rng_uniform(uint64_t *s) { return (double)(rng_next(s) >> 11) * (1.0 / 9007199254740992.0); }

static double d2lab(const float *a, const double *c)
{
    double x = a[0] - c[0], y = a[1] - c[1], z = a[2] - c[2];
    return x * x + y * y + z * z;
}

/* k-means++ then Lloyd on the sample; returns the number of centres (<= kc). */
static uint32_t kmeans(const float *lab, const uint32_t *sample, size_t ns, uint32_t kc, uint64_t seed,
                       double *centre, double *weight)
{
    uint64_t s = seed ? seed : 0x9E3779B97F4A7C15ULL;
    double *dmin = malloc(ns * sizeof *dmin);
    uint32_t *assign = malloc(ns * sizeof *assign);
    if (!dmin || !assign) { free(dmin); free(assign); return 0; }
    uint32_t c = 0;
    size_t first = (size_t)(rng_uniform(&s) * (double)ns);
    if (first >= ns) first = ns - 1;
    for (int a = 0; a < 3; a++) centre[a] = lab[3 * (size_t)sample[first] + a];
    c = 1;
    for (size_t i = 0; i < ns; i++) dmin[i] = d2lab(lab + 3 * (size_t)sample[i], centre);
    while (c < kc) {
        double total = 0;
        for (size_t i = 0; i < ns; i++) total += dmin[i];
        if (!(total > 1e-9)) break; /* every sample on a centre already: fewer classes */
        double t = rng_uniform(&s) * total, acc = 0;
        size_t pick = ns - 1;
        for (size_t i = 0; i < ns; i++) { acc += dmin[i]; if (acc > t) { pick = i; break; } }
        double *cc = centre + 3 * (size_t)c;
        for (int a = 0; a < 3; a++) cc[a] = lab[3 * (size_t)sample[pick] + a];
        for (size_t i = 0; i < ns; i++) {
            double d = d2lab(lab + 3 * (size_t)sample[i], cc);
            if (d < dmin[i]) dmin[i] = d;
        }
        c++;
    }
    for (int it = 0; it < KMEANS_ITER; it++) {
        int changed = 0;
        for (size_t i = 0; i < ns; i++) {
            const float *p = lab + 3 * (size_t)sample[i];
            uint32_t best = 0;
            double bd = d2lab(p, centre);
            for (uint32_t q = 1; q < c; q++) {
                double d = d2lab(p, centre + 3 * (size_t)q);
                if (d < bd) { bd = d; best = q; }
            }
            if (it == 0 || assign[i] != best) changed = 1;
            assign[i] = best;
        }
        if (!changed) break;
        for (uint32_t q = 0; q < c; q++) weight[q] = 0;
        double acc[3 * 256] = {0};
        for (size_t i = 0; i < ns; i++) {
            const float *p = lab + 3 * (size_t)sample[i];
            uint32_t q = assign[i];
            weight[q] += 1;
            for (int a = 0; a < 3; a++) acc[3 * q + a] += p[a];
        }
        for (uint32_t q = 0; q < c; q++)
            if (weight[q] > 0)
                for (int a = 0; a < 3; a++) centre[3 * q + a] = acc[3 * q + a] / weight[q];
    }
    for (uint32_t q = 0; q < c; q++) weight[q] = 0;
    for (size_t i = 0; i < ns; i++) weight[assign[i]] += 1;
    free(dmin); free(assign);
    /* drop empty centres */
    uint32_t u = 0;
    for (uint32_t q = 0; q < c; q++) {
        if (!(weight[q] > 0)) continue;
        for (int a = 0; a < 3; a++) centre[3 * u + a] = centre[3 * q + a];
        weight[u++] = weight[q];
    }
    return u;
}

/* Merges centres closer than dist (closest pair first, weighted means). */
static uint32_t merge_centres(double *centre, double *weight, uint32_t c, double dist)
{
    while (c > 1) {
        double best = INFINITY;
        uint32_t ba = 0, bb = 0;
        for (uint32_t a = 0; a < c; a++)
            for (uint32_t b = a + 1; b < c; b++) {
                double x = centre[3 * a] - centre[3 * b], y = centre[3 * a + 1] - centre[3 * b + 1],
                       z = centre[3 * a + 2] - centre[3 * b + 2];
                double d = sqrt(x * x + y * y + z * z);
                if (d < best) { best = d; ba = a; bb = b; }
            }
        if (!(best < dist)) break;
        double w = weight[ba] + weight[bb];
        for (int q = 0; q < 3; q++) centre[3 * ba + q] = (centre[3 * ba + q] * weight[ba] + centre[3 * bb + q] * weight[bb]) / w;
        weight[ba] = w;
        for (uint32_t q = bb; q + 1 < c; q++) {
            for (int a = 0; a < 3; a++) centre[3 * q + a] = centre[3 * (q + 1) + a];
            weight[q] = weight[q + 1];
        }
        c--;
    }
    return c;
}

typedef struct jseg_job {
    const float *xyz, *lab, *lab_in;
    float *lab_out;
    const double *centre;
    uint32_t classes;
    const uint32_t *knn;
    size_t k;
    uint8_t *cls;
    float *j;
    const uint8_t *valid;
} jseg_job;

/* Peer group filter (simplified from Deng et al.): a point's colour becomes the mean L*a*b* of
 * the half of its neighbourhood (itself included) closest to it in colour, so noise is smoothed
 * without blurring across colour edges (the other half lies across the edge). */
static void peer_range(void *ctx, size_t begin, size_t end)
{
    const jseg_job *jb = ctx;
    float dist[256];
    uint32_t idx[256];
    for (size_t i = begin; i < end; i++) {
        float *out = jb->lab_out + 3 * i;
        const float *c = jb->lab_in + 3 * i;
        out[0] = c[0]; out[1] = c[1]; out[2] = c[2];
        if (!jb->valid[i]) continue;
        const uint32_t *row = jb->knn + i * jb->k;
        size_t m = 0;
        for (size_t r = 0; r < jb->k; r++) {
            uint32_t x = row[r];
            if (x == PNPR_INDEX_NONE) continue;
            const float *q = jb->lab_in + 3 * (size_t)x;
            float d0 = q[0] - c[0], d1 = q[1] - c[1], d2 = q[2] - c[2];
            dist[m] = d0 * d0 + d1 * d1 + d2 * d2;
            idx[m++] = x;
        }
        size_t half = (m + 1) / 2;
        /* partial selection sort of the `half` closest (k <= 256, half <= 128) */
        double acc[3] = {0, 0, 0};
        for (size_t a = 0; a < half; a++) {
            size_t best = a;
            for (size_t b = a + 1; b < m; b++)
                if (dist[b] < dist[best] || (dist[b] == dist[best] && idx[b] < idx[best])) best = b;
            float td = dist[a]; dist[a] = dist[best]; dist[best] = td;
            uint32_t ti = idx[a]; idx[a] = idx[best]; idx[best] = ti;
            const float *q = jb->lab_in + 3 * (size_t)idx[a];
            acc[0] += q[0]; acc[1] += q[1]; acc[2] += q[2];
        }
        if (half) { out[0] = (float)(acc[0] / half); out[1] = (float)(acc[1] / half); out[2] = (float)(acc[2] / half); }
    }
}

static void classify_range(void *ctx, size_t begin, size_t end)
{
    const jseg_job *jb = ctx;
    for (size_t i = begin; i < end; i++) {
        if (!jb->valid[i]) { jb->cls[i] = 0; continue; }
        const float *p = jb->lab + 3 * i;
        uint32_t best = 0;
        double bd = d2lab(p, jb->centre);
        for (uint32_t q = 1; q < jb->classes; q++) {
            double d = d2lab(p, jb->centre + 3 * (size_t)q);
            if (d < bd) { bd = d; best = q; }
        }
        jb->cls[i] = (uint8_t)best;
    }
}

static void j_range(void *ctx, size_t begin, size_t end)
{
    const jseg_job *jb = ctx;
    uint8_t cid[256];
    double cn[256], cs[256][3], cq[256];
    for (size_t i = begin; i < end; i++) {
        jb->j[i] = 0.0f;
        if (!jb->valid[i]) continue;
        const uint32_t *row = jb->knn + i * jb->k;
        const float *pi = jb->xyz + 3 * i;
        uint32_t nc = 0;
        double n = 0, s[3] = {0, 0, 0}, q = 0;
        for (size_t r = 0; r < jb->k; r++) {
            uint32_t x = row[r];
            if (x == PNPR_INDEX_NONE) continue;
            const float *p = jb->xyz + 3 * (size_t)x;
            double d[3] = {(double)p[0] - pi[0], (double)p[1] - pi[1], (double)p[2] - pi[2]};
            double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            uint8_t c = jb->cls[x];
            uint32_t slot = 0;
            while (slot < nc && cid[slot] != c) slot++;
            if (slot == nc) { cid[nc] = c; cn[nc] = 0; cs[nc][0] = cs[nc][1] = cs[nc][2] = 0; cq[nc] = 0; nc++; }
            cn[slot] += 1; cq[slot] += dd;
            for (int a = 0; a < 3; a++) { cs[slot][a] += d[a]; s[a] += d[a]; }
            n += 1; q += dd;
        }
        if (n < 2 || nc < 2) continue;
        double st = q - (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]) / n, sw = 0;
        for (uint32_t c = 0; c < nc; c++)
            sw += cq[c] - (cs[c][0] * cs[c][0] + cs[c][1] * cs[c][1] + cs[c][2] * cs[c][2]) / cn[c];
        if (!(st > 0)) continue;
        if (sw < 1e-6 * st) sw = 1e-6 * st;
        double jv = (st - sw) / sw;
        jb->j[i] = (float)(jv > 0 ? jv : 0);
    }
}

typedef struct qitem { float j; uint32_t point, region; } qitem;

static int q_less(const qitem *a, const qitem *b)
{
    return a->j != b->j ? a->j < b->j : a->point < b->point;
}

static int q_push(qitem **h, size_t *n, size_t *cap, qitem it)
{
    if (*n == *cap) {
        size_t c = *cap ? *cap * 2 : 4096;
        qitem *p = realloc(*h, c * sizeof *p);
        if (!p) return 0;
        *h = p; *cap = c;
    }
    size_t i = (*n)++;
    while (i > 0) {
        size_t up = (i - 1) / 2;
        if (!q_less(&it, &(*h)[up])) break;
        (*h)[i] = (*h)[up];
        i = up;
    }
    (*h)[i] = it;
    return 1;
}

static qitem q_pop(qitem *h, size_t *n)
{
    qitem top = h[0], last = h[--*n];
    size_t i = 0;
    for (;;) {
        size_t c = 2 * i + 1;
        if (c >= *n) break;
        if (c + 1 < *n && q_less(&h[c + 1], &h[c])) c++;
        if (!q_less(&h[c], &last)) break;
        h[i] = h[c];
        i = c;
    }
    if (*n) h[i] = last;
    return top;
}

static uint32_t uf_find(uint32_t *parent, uint32_t x)
{
    while (parent[x] != x) { parent[x] = parent[parent[x]]; x = parent[x]; }
    return x;
}

/* Connected components of the points with mask[i] set, over the first ka neighbours; labels
 * components with ids from *io_next on into labels[] (only where mask is set and size >= min). */
static pnpr_status components(const uint8_t *mask, size_t count, const uint32_t *knn, size_t k, size_t ka,
                              uint32_t min_size, uint32_t *labels, uint32_t *io_next)
{
    uint32_t *parent = malloc(count * sizeof *parent), *size = calloc(count, sizeof *size);
    if (!parent || !size) { free(parent); free(size); return PNPR_ERR_OUT_OF_MEMORY; }
    for (size_t i = 0; i < count; i++) parent[i] = (uint32_t)i;
    for (size_t i = 0; i < count; i++) {
        if (!mask[i]) continue;
        const uint32_t *row = knn + i * k;
        for (size_t r = 0; r < ka; r++) {
            uint32_t x = row[r];
            if (x == PNPR_INDEX_NONE || !mask[x]) continue;
            uint32_t a = uf_find(parent, (uint32_t)i), b = uf_find(parent, x);
            if (a != b) parent[a < b ? b : a] = a < b ? a : b;
        }
    }
    for (size_t i = 0; i < count; i++) if (mask[i]) size[uf_find(parent, (uint32_t)i)]++;
    uint32_t *id = parent; /* roots get ids in place: reuse size[] as id map */
    for (size_t i = 0; i < count; i++) {
        if (!mask[i]) continue;
        uint32_t r = uf_find(id, (uint32_t)i);
        if (size[r] < min_size) continue;
        if (!(size[r] & 0x80000000u)) size[r] = 0x80000000u | (*io_next)++;
        labels[i] = size[r] & 0x7FFFFFFFu;
    }
    free(parent); free(size);
    return PNPR_OK;
}

/* One run's state, shared by the stages below. */
typedef struct jseg_ctx {
    const float *xyz;
    const uint8_t *rgb;
    size_t count, nvalid;
    const pnpr_jseg_options *o;
    size_t k, ka;        /* the neighbourhood size; the adjacency graph's (the first ka of each list) */
    uint8_t *valid;      /* finite points */
    uint32_t *knn;       /* count x k neighbour lists (PNPR_INDEX_NONE beyond the radius) */
    float *lab;          /* the peer-group filtered L*a*b* colours */
    uint8_t *cls;        /* the class map */
    float *jv;           /* J of each point */
    uint32_t *labels;    /* the result */
} jseg_ctx;

/* The neighbourhoods: the k nearest of every point (itself included), cut at the radius. */
static pnpr_status jseg_neighbours(jseg_ctx *c)
{
    const pnpr_jseg_options *o = c->o;
    pnpr_kdtree *tree = NULL;
    pnpr_status st = pnpr_kdtree_build_threads(c->xyz, c->count, 0, o->threads, &tree);
    if (st != PNPR_OK) return st;
    float *d2 = o->radius > 0 ? malloc(c->count * c->k * sizeof *d2) : NULL;
    c->knn = malloc(c->count * c->k * sizeof *c->knn);
    c->lab = malloc(3 * c->count * sizeof *c->lab);
    c->cls = malloc(c->count);
    c->jv = malloc(c->count * sizeof *c->jv);
    if (!c->knn || (o->radius > 0 && !d2) || !c->lab || !c->cls || !c->jv) st = PNPR_ERR_OUT_OF_MEMORY;
    pnpr_knn_options ko = {o->threads, o->progress, 0};
    if (st == PNPR_OK) st = pnpr_knn_self(tree, c->count, c->k, &ko, c->knn, d2);
    pnpr_kdtree_free(tree);
    if (st == PNPR_OK && d2) {
        float r2 = o->radius * o->radius;
        for (size_t i = 0; i < c->count * c->k; i++) if (!(d2[i] <= r2)) c->knn[i] = PNPR_INDEX_NONE;
    }
    free(d2);
    return st;
}

/* 1. Quantisation: L*a*b*, the peer group filter, k-means on a stride sample (kc centres at
 * most, merged closer than qdist), the class map. *r_classes = the classes left. */
static pnpr_status jseg_quantise(jseg_ctx *c, uint32_t kc, double qdist, uint32_t *r_classes)
{
    const pnpr_jseg_options *o = c->o;
    size_t count = c->count;
    float *lab_raw = malloc(3 * count * sizeof *lab_raw);
    if (!lab_raw) return PNPR_ERR_OUT_OF_MEMORY;
    for (size_t i = 0; i < count; i++) {
        if (c->valid[i]) pnpr_rgb_to_lab(c->rgb + 3 * i, lab_raw + 3 * i);
        else lab_raw[3 * i] = lab_raw[3 * i + 1] = lab_raw[3 * i + 2] = 0;
    }
    jseg_job pj = {c->xyz, NULL, lab_raw, c->lab, NULL, 0, c->knn, c->k, NULL, NULL, c->valid};
    pnpr_status st = pnpr_parallel_for(count, 2048, o->threads, peer_range, &pj, &o->progress, "quantise");
    free(lab_raw);
    if (st != PNPR_OK) return st;
    size_t step = (c->nvalid + SAMPLE_MAX - 1) / SAMPLE_MAX, ns = 0;
    uint32_t *sample = malloc((c->nvalid / step + 1) * sizeof *sample);
    if (!sample) return PNPR_ERR_OUT_OF_MEMORY;
    for (size_t i = 0, v = 0; i < count; i++)
        if (c->valid[i]) { if (v % step == 0) sample[ns++] = (uint32_t)i; v++; }
    double centre[3 * 256], weight[256];
    uint32_t classes = kmeans(c->lab, sample, ns, kc, o->seed, centre, weight);
    free(sample);
    if (!classes) return PNPR_ERR_OUT_OF_MEMORY;
    if (qdist > 0) classes = merge_centres(centre, weight, classes, qdist);
    *r_classes = classes;
    jseg_job jb = {c->xyz, c->lab, NULL, NULL, centre, classes, c->knn, c->k, c->cls, c->jv, c->valid};
    return pnpr_parallel_for(count, 4096, o->threads, classify_range, &jb, &o->progress, "quantise");
}

/* Queues the unlabelled adjacency neighbours of point i (region `region`) below the bound. */
static int jseg_queue_neighbours(const jseg_ctx *c, size_t i, uint32_t region, double bound, uint8_t *queued,
                                 qitem **heap, size_t *hn, size_t *hcap)
{
    const uint32_t *row = c->knn + i * c->k;
    for (size_t r = 0; r < c->ka; r++) {
        uint32_t x = row[r];
        if (x == PNPR_INDEX_NONE || queued[x] || c->labels[x] != PNPR_LABEL_NONE || !(c->jv[x] < bound)) continue;
        queued[x] = 1;
        if (!q_push(heap, hn, hcap, (qitem){c->jv[x], x, region})) return 0;
    }
    return 1;
}

/* Of the regions of x's labelled adjacency neighbours (and `best`, the one that queued it), the
 * one whose running mean colour (rsum: L*a*b* sums and count) is closest to x's. */
static uint32_t jseg_closest_region(const jseg_ctx *c, uint32_t x, uint32_t best, const double *rsum)
{
    const uint32_t *row = c->knn + (size_t)x * c->k;
    const float *col = c->lab + 3 * (size_t)x;
    const double *bs = rsum + 4 * (size_t)best;
    double bd = d2lab(col, (double[3]){bs[0] / bs[3], bs[1] / bs[3], bs[2] / bs[3]});
    for (size_t r = 0; r < c->ka; r++) {
        uint32_t y = row[r];
        if (y == PNPR_INDEX_NONE) continue;
        uint32_t l = c->labels[y];
        if (l == PNPR_LABEL_NONE || l == best) continue;
        const double *s = rsum + 4 * (size_t)l;
        double d = d2lab(col, (double[3]){s[0] / s[3], s[1] / s[3], s[2] / s[3]});
        if (d < bd || (d == bd && l < best)) { bd = d; best = l; }
    }
    return best;
}

/* 4. Growing: the unlabelled points join the nreg seed regions in increasing J order (below
 * grow_bound x mean J when bounded), each the closest region in colour among its labelled
 * neighbours'. */
static pnpr_status jseg_grow(jseg_ctx *c, uint32_t nreg, double mean_j)
{
    const pnpr_jseg_options *o = c->o;
    size_t count = c->count;
    uint8_t *queued = calloc(count, 1);
    double *rsum = calloc((size_t)(nreg ? nreg : 1) * 4, sizeof *rsum);
    qitem *heap = NULL;
    size_t hn = 0, hcap = 0, grown = 0;
    pnpr_status st = queued && rsum ? PNPR_OK : PNPR_ERR_OUT_OF_MEMORY;
    for (size_t i = 0; st == PNPR_OK && i < count; i++) {
        uint32_t l = c->labels[i];
        if (l == PNPR_LABEL_NONE) continue;
        for (int a = 0; a < 3; a++) rsum[4 * l + a] += c->lab[3 * i + a];
        rsum[4 * l + 3] += 1;
    }
    double bound = o->grow_bound > 0 ? o->grow_bound * mean_j : INFINITY;
    for (size_t i = 0; st == PNPR_OK && i < count; i++)
        if (c->labels[i] != PNPR_LABEL_NONE && !jseg_queue_neighbours(c, i, c->labels[i], bound, queued, &heap, &hn, &hcap))
            st = PNPR_ERR_OUT_OF_MEMORY;
    while (st == PNPR_OK && hn) {
        qitem it = q_pop(heap, &hn);
        uint32_t x = it.point;
        uint32_t best = jseg_closest_region(c, x, it.region, rsum);
        c->labels[x] = best;
        for (int a = 0; a < 3; a++) rsum[4 * (size_t)best + a] += c->lab[3 * (size_t)x + a];
        rsum[4 * (size_t)best + 3] += 1;
        if (!jseg_queue_neighbours(c, x, best, bound, queued, &heap, &hn, &hcap)) st = PNPR_ERR_OUT_OF_MEMORY;
        else if ((++grown & 0xFFFF) == 0 && pnpr_progress_report(&o->progress, "grow", (double)grown / (double)c->nvalid))
            st = PNPR_ERR_CANCELLED;
    }
    free(queued); free(rsum); free(heap);
    return st;
}

/* 2. J of every point, and its mean over the valid points. */
static pnpr_status jseg_j(jseg_ctx *c, double *r_mean_j)
{
    jseg_job jb = {c->xyz, c->lab, NULL, NULL, NULL, 0, c->knn, c->k, c->cls, c->jv, c->valid};
    pnpr_status st = pnpr_parallel_for(c->count, 2048, c->o->threads, j_range, &jb, &c->o->progress, "J");
    if (st != PNPR_OK) return st;
    double jsum = 0;
    for (size_t i = 0; i < c->count; i++) if (c->valid[i]) jsum += c->jv[i];
    *r_mean_j = jsum / (double)c->nvalid;
    return PNPR_OK;
}

/* 3. to 5.: the seed regions, growing, the points never reached as regions of their own, merging. */
static pnpr_status jseg_regions(jseg_ctx *c, double seed_factor, double mean_j, double merge_distance,
                                pnpr_segment_info *r_info)
{
    const pnpr_jseg_options *o = c->o;
    size_t count = c->count;
    uint32_t seed_min = o->seed_min_size ? o->seed_min_size : (uint32_t)c->k;
    uint32_t min_size = o->min_size ? o->min_size : (uint32_t)(c->k > c->nvalid / 1000 ? c->k : c->nvalid / 1000);
    uint8_t *mask = malloc(count);
    if (!mask) return PNPR_ERR_OUT_OF_MEMORY;
    double seed_thr = seed_factor * mean_j;
    for (size_t i = 0; i < count; i++) mask[i] = (uint8_t)(c->valid[i] && c->jv[i] <= seed_thr);
    uint32_t nreg = 0, seeds = 0, grown_regions = 0;
    pnpr_status st = components(mask, count, c->knn, c->k, c->ka, seed_min, c->labels, &nreg);
    seeds = nreg;
    if (st == PNPR_OK && pnpr_progress_report(&o->progress, "grow", 0.0)) st = PNPR_ERR_CANCELLED;
    if (st == PNPR_OK) st = jseg_grow(c, nreg, mean_j);
    if (st == PNPR_OK) { /* points never reached: regions of their own */
        for (size_t i = 0; i < count; i++) mask[i] = (uint8_t)(c->valid[i] && c->labels[i] == PNPR_LABEL_NONE);
        st = components(mask, count, c->knn, c->k, c->ka, 1, c->labels, &nreg);
        grown_regions = nreg;
    }
    free(mask);
    if (st == PNPR_OK && pnpr_progress_report(&o->progress, "grow", 1.0)) st = PNPR_ERR_CANCELLED;
    if (st != PNPR_OK) return st;
    /* 5. merging of similar and small regions; invalid points sit above every region */
    for (size_t i = 0; i < count; i++) if (!c->valid[i]) c->labels[i] = nreg;
    pnpr_region_graph graph = {c->knn, c->k, c->ka};
    if (pnpr_progress_report(&o->progress, "merge", 0.0)) return PNPR_ERR_CANCELLED;
    st = pnpr_segment_merge_regions(c->rgb, count, &graph, (float)merge_distance, min_size, c->labels, &nreg);
    if (st == PNPR_OK) st = pnpr_segment_finish(c->xyz, count, c->labels, r_info);
    if (st != PNPR_OK) return st;
    pnpr_progress_report(&o->progress, "merge", 1.0);
    if (r_info) {
        r_info->seed_regions = seeds;
        r_info->grown_regions = grown_regions;
    }
    return PNPR_OK;
}

pnpr_status pnpr_segment_jseg(const float *xyz, const uint8_t *rgb, size_t count,
                              const pnpr_jseg_options *opts, uint32_t *r_labels,
                              pnpr_segment_info *r_info)
{
    double t0 = pnpr_now();
    if (r_info) { memset(r_info, 0, sizeof *r_info); r_info->invalid_segment = PNPR_LABEL_NONE; }
    if (!count) return PNPR_OK;
    if (!xyz || !rgb || !r_labels || count >= 0x7FFFFFFFu) return PNPR_ERR_INVALID_ARGUMENT;
    pnpr_jseg_options o = opts ? *opts : (pnpr_jseg_options){0};
    size_t table_count;
    const pnpr_option_desc *table = pnpr_jseg_option_table(&table_count);
    pnpr_option_fill_defaults(table, table_count, &o); /* zeros -> the table's defaults (options.h) */
    uint32_t kc = o.classes > PNPR_JSEG_CLASSES_MAX ? PNPR_JSEG_CLASSES_MAX : o.classes;
    const pnpr_jseg_options def = pnpr_jseg_defaults();
    double qdist = o.quant_distance > 0 ? o.quant_distance : (o.quant_distance < 0 ? 0 : def.quant_distance); /* NaN */
    double seed_factor = o.seed_factor > 0 ? o.seed_factor : def.seed_factor; /* < 0: default */
    double merge_distance = o.merge_distance > 0 ? o.merge_distance : (o.merge_distance < 0 ? 0 : def.merge_distance);

    jseg_ctx c;
    memset(&c, 0, sizeof c);
    c.xyz = xyz;
    c.rgb = rgb;
    c.count = count;
    c.o = &o;
    c.labels = r_labels;
    c.k = o.k > PNPR_SEGMENT_K_MAX ? PNPR_SEGMENT_K_MAX : o.k;
    c.valid = malloc(count);
    if (!c.valid) return PNPR_ERR_OUT_OF_MEMORY;
    for (size_t i = 0; i < count; i++) {
        c.valid[i] = (uint8_t)pnpr_finite3f(xyz + 3 * i);
        c.nvalid += c.valid[i];
        r_labels[i] = PNPR_LABEL_NONE;
    }
    pnpr_status st = PNPR_OK;
    uint32_t classes = 0;
    double mean_j = 0;
    if (!c.nvalid) {
        st = pnpr_segment_finish(xyz, count, r_labels, r_info);
    } else {
        if (c.k > c.nvalid) c.k = c.nvalid;
        c.ka = c.k < ADJ_K ? c.k : ADJ_K;
        st = jseg_neighbours(&c);
        if (st == PNPR_OK) st = jseg_quantise(&c, kc, qdist, &classes);
        if (st == PNPR_OK) st = jseg_j(&c, &mean_j);
        if (st == PNPR_OK) st = jseg_regions(&c, seed_factor, mean_j, merge_distance, r_info);
        if (st == PNPR_OK) {
            if (o.r_j) memcpy(o.r_j, c.jv, count * sizeof *c.jv);
            if (o.r_class) memcpy(o.r_class, c.cls, count);
            if (r_info) {
                r_info->classes = classes;
                r_info->mean_j = (float)mean_j;
            }
        }
    }
    free(c.valid); free(c.knn); free(c.lab); free(c.cls); free(c.jv);
    if (r_info) r_info->seconds = pnpr_now() - t0;
    return st;
}
