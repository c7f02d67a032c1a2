/* Consistent normal orientation.
 *
 * With a viewpoint (scanner position): every normal is flipped to face it.
 * Without: propagation over the kNN graph in the spirit of Hoppe et al. 1992: starting from the
 * highest unvisited point (its normal turned to +z; a horizontal normal is turned away from the
 * cloud's centre), visit next the unvisited neighbour whose normal is most parallel to the
 * normal it is reached from (priority 1 - |n_i . n_j|, a Prim-like traversal of the minimum
 * spanning tree), flipping each normal to agree with its parent. Priorities are quantised to
 * 256 buckets, so the queue costs O(1) per operation (a bucket queue) instead of a heap's
 * O(log n); equal-bucket ties are taken in LIFO order. Zero normals are skipped (left as is).
 * Points the kNN graph cannot reach from an earlier seed start a new component. */
#include <pointnpr/features.h>
#include <pointnpr/knn.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define BUCKETS 256
#define VISITED 0xFFFFu
#define UNSEEN 0xFFFEu

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

static int cmp_z_desc(const void *a, const void *b, const float *xyz)
{
    float za = xyz[3 * (size_t)*(const uint32_t *)a + 2], zb = xyz[3 * (size_t)*(const uint32_t *)b + 2];
    return za < zb ? 1 : (za > zb ? -1 : 0);
}

/* Sort helper without qsort_r (not C11): a simple merge sort by z descending. */
static void sort_by_z(uint32_t *ids, uint32_t *tmp, size_t n, const float *xyz)
{
    for (size_t width = 1; width < n; width *= 2) {
        for (size_t lo = 0; lo < n; lo += 2 * width) {
            size_t mid = lo + width < n ? lo + width : n, hi = lo + 2 * width < n ? lo + 2 * width : n;
            size_t a = lo, b = mid, o = lo;
            while (a < mid && b < hi) tmp[o++] = cmp_z_desc(&ids[b], &ids[a], xyz) < 0 ? ids[b++] : ids[a++];
            while (a < mid) tmp[o++] = ids[a++];
            while (b < hi) tmp[o++] = ids[b++];
        }
        memcpy(ids, tmp, n * sizeof *ids);
    }
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
    uint32_t *parent = malloc((count ? count : 1) * sizeof *parent);
    uint32_t *ids = malloc((count ? count : 1) * sizeof *ids);
    uint32_t *tmp = malloc((count ? count : 1) * sizeof *tmp);
    bucket q[BUCKETS];
    memset(q, 0, sizeof q);
    pnpr_status st = PNPR_OK;
    if (!state || !parent || !ids || !tmp) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }

    /* seeds: valid points with a normal, highest first; centre for horizontal seed normals */
    size_t m = 0;
    double centre[3] = {0, 0, 0};
    for (size_t i = 0; i < count; i++) {
        const float *p = xyz + 3 * i;
        state[i] = VISITED;
        if (!nonzero(normals + 3 * i) || !isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) continue;
        state[i] = UNSEEN;
        ids[m++] = (uint32_t)i;
        centre[0] += p[0]; centre[1] += p[1]; centre[2] += p[2];
    }
    if (m) { centre[0] /= (double)m; centre[1] /= (double)m; centre[2] /= (double)m; }
    sort_by_z(ids, tmp, m, xyz);
    free(tmp);
    tmp = NULL;

    for (size_t s = 0; s < m; s++) {
        uint32_t seed = ids[s];
        if (state[seed] == VISITED) continue;
        float *ns = normals + 3 * (size_t)seed;
        const float *ps = xyz + 3 * (size_t)seed;
        double up = ns[2];
        if (fabs(up) < 1e-6) /* horizontal: away from the centre */
            up = ns[0] * (ps[0] - centre[0]) + ns[1] * (ps[1] - centre[1]) + ns[2] * (ps[2] - centre[2]);
        if (up < 0) { ns[0] = -ns[0]; ns[1] = -ns[1]; ns[2] = -ns[2]; }
        parent[seed] = seed;
        state[seed] = 0;
        if (!bucket_push(&q[0], seed)) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
        size_t lowest = 0;
        for (;;) {
            while (lowest < BUCKETS && q[lowest].n == 0) lowest++;
            if (lowest == BUCKETS) break;
            uint32_t i = q[lowest].items[--q[lowest].n];
            if (state[i] != lowest) continue; /* stale entry: visited or re-offered cheaper */
            state[i] = VISITED;
            float *ni = normals + 3 * (size_t)i;
            const float *np = normals + 3 * (size_t)parent[i];
            if (ni[0] * np[0] + ni[1] * np[1] + ni[2] * np[2] < 0) { ni[0] = -ni[0]; ni[1] = -ni[1]; ni[2] = -ni[2]; }
            const uint32_t *row = knn + (size_t)i * k;
            for (size_t r = 0; r < k; r++) {
                uint32_t j = row[r];
                if (j == PNPR_INDEX_NONE || state[j] == VISITED) continue;
                const float *nj = normals + 3 * (size_t)j;
                double c = fabs((double)ni[0] * nj[0] + (double)ni[1] * nj[1] + (double)ni[2] * nj[2]);
                int b = (int)((1.0 - (c > 1.0 ? 1.0 : c)) * (BUCKETS - 1) + 0.5);
                if (state[j] != UNSEEN && state[j] <= b) continue;
                state[j] = (uint16_t)b;
                parent[j] = i;
                if (!bucket_push(&q[b], j)) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
                if ((size_t)b < lowest) lowest = (size_t)b;
            }
        }
    }
done:
    for (int b = 0; b < BUCKETS; b++) free(q[b].items);
    free(state); free(parent); free(ids); free(tmp);
    return st;
}
