/* Consistent normal orientation.
 *
 * With a viewpoint (scanner position): every normal is flipped to face it.
 * Without: propagation over the kNN graph in the spirit of Hoppe et al. 1992: from a seed, visit
 * next the unvisited neighbour whose normal is most parallel to that of a visited point
 * (priority 1 - |n_i . n_j|, a Prim-like traversal of the minimum spanning tree), flipping each
 * normal to agree with the visited point that offered it its best priority. Priorities are
 * quantised to 256 buckets, so the queue costs O(1) per operation (a bucket queue) instead of a
 * heap's O(log n); equal-bucket ties are taken in LIFO order. Each connected component then
 * gets its global sign from its highest point, whose normal must face up (+z; a horizontal one
 * faces away from the cloud's centre). Zero normals are skipped (left as is). Seeds are taken in
 * array order (kd-tree order in the pipeline). Memory: 6 bytes/point plus the queue. */
#include <pointnpr/features.h>
#include <pointnpr/knn.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define BUCKETS 256
#define VISITED 0xFFFFu
#define UNSEEN 0xFFFEu
#define FLIP 0xFFFDu

static int nonzero(const float *n)
{
    return n[0] != 0.0f || n[1] != 0.0f || n[2] != 0.0f;
}

typedef struct bucket {
    uint32_t *items;
    size_t n, cap;
} bucket;

static int bucket_push(bucket *b, uint32_t v)
{
    if (b->n == b->cap) {
        size_t cap = b->cap ? 2 * b->cap : 256;
        uint32_t *p = realloc(b->items, cap * sizeof *p);
        if (!p) return 0;
        b->items = p;
        b->cap = cap;
    }
    b->items[b->n++] = v;
    return 1;
}

pnpr_status pnpr_orient_normals(const float *xyz, size_t count, const uint32_t *knn, size_t k,
                                const double *viewpoint, float *normals)
{
    if (count && (!xyz || !normals)) return PNPR_ERR_INVALID_ARGUMENT;
    if (viewpoint) {
        for (size_t i = 0; i < count; i++) {
            const float *p = xyz + 3 * i;
            float *n = normals + 3 * i;
            double d = n[0] * (viewpoint[0] - p[0]) + n[1] * (viewpoint[1] - p[1]) + n[2] * (viewpoint[2] - p[2]);
            if (d < 0) { n[0] = -n[0]; n[1] = -n[1]; n[2] = -n[2]; }
        }
        return PNPR_OK;
    }
    if (count && (!knn || k == 0)) return PNPR_ERR_INVALID_ARGUMENT;

    uint16_t *state = malloc((count ? count : 1) * sizeof *state); /* bucket of best offer, or flag */
    uint32_t *comp = malloc((count ? count : 1) * sizeof *comp);    /* component -> its seed */
    bucket q[BUCKETS];
    memset(q, 0, sizeof q);
    pnpr_status st = PNPR_OK;
    if (!state || !comp) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }

    double centre[3] = {0, 0, 0};
    size_t m = 0;
    for (size_t i = 0; i < count; i++) {
        const float *p = xyz + 3 * i;
        state[i] = VISITED;
        comp[i] = PNPR_INDEX_NONE;
        if (!nonzero(normals + 3 * i) || !isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) continue;
        state[i] = UNSEEN;
        centre[0] += p[0]; centre[1] += p[1]; centre[2] += p[2];
        m++;
    }
    if (m) { centre[0] /= (double)m; centre[1] /= (double)m; centre[2] /= (double)m; }

    /* propagation: a neighbour's normal is flipped to agree with the visited point that offers it
     * the best (lowest) bucket so far, so it leaves the queue agreeing with its best parent */
    for (size_t seed = 0; seed < count; seed++) {
        if (state[seed] != UNSEEN) continue;
        state[seed] = 0;
        if (!bucket_push(&q[0], (uint32_t)seed)) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
        size_t lowest = 0;
        uint32_t top = (uint32_t)seed; /* the component's highest point */
        for (;;) {
            while (lowest < BUCKETS && q[lowest].n == 0) lowest++;
            if (lowest == BUCKETS) break;
            uint32_t i = q[lowest].items[--q[lowest].n];
            if (state[i] != lowest) continue; /* stale entry: visited or re-offered cheaper */
            state[i] = VISITED;
            comp[i] = (uint32_t)seed;
            if (xyz[3 * (size_t)i + 2] > xyz[3 * (size_t)top + 2]) top = i;
            float *ni = normals + 3 * (size_t)i;
            const uint32_t *row = knn + (size_t)i * k;
            for (size_t r = 0; r < k; r++) {
                uint32_t j = row[r];
                if (j == PNPR_INDEX_NONE || state[j] == VISITED) continue;
                float *nj = normals + 3 * (size_t)j;
                double d = (double)ni[0] * nj[0] + (double)ni[1] * nj[1] + (double)ni[2] * nj[2];
                double c = fabs(d);
                int b = (int)((1.0 - (c > 1.0 ? 1.0 : c)) * (BUCKETS - 1) + 0.5);
                if (state[j] != UNSEEN && state[j] <= b) continue;
                state[j] = (uint16_t)b;
                if (d < 0) { nj[0] = -nj[0]; nj[1] = -nj[1]; nj[2] = -nj[2]; }
                if (!bucket_push(&q[b], j)) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
                if ((size_t)b < lowest) lowest = (size_t)b;
            }
        }
        /* the component's sign: its highest point faces up (a horizontal one: away from the
         * centre); the seed's slot in `state` remembers the decision for the flip pass */
        const float *nt = normals + 3 * (size_t)top, *pt = xyz + 3 * (size_t)top;
        double up = nt[2];
        if (fabs(up) < 1e-6)
            up = nt[0] * (pt[0] - centre[0]) + nt[1] * (pt[1] - centre[1]) + nt[2] * (pt[2] - centre[2]);
        state[seed] = up < 0 ? FLIP : VISITED;
    }
    for (size_t i = 0; i < count; i++) {
        if (comp[i] == PNPR_INDEX_NONE || state[comp[i]] != FLIP) continue;
        float *n = normals + 3 * i;
        n[0] = -n[0]; n[1] = -n[1]; n[2] = -n[2];
    }
done:
    for (int b = 0; b < BUCKETS; b++) free(q[b].items);
    free(state);
    free(comp);
    return st;
}
