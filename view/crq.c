/* Continuous resolution queue (PointWorks section 4.4): the points of each group in a random
 * order fixed once; a frame draws a prefix of each group's queue. */
#include <pointnpr/crq.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* splitmix64: small, fast, and the same sequence everywhere. */
static uint64_t crq_next(uint64_t *state)
{
    uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* Uniform integer in [0, n) without modulo bias (rejection of the short last bucket). */
static uint64_t crq_below(uint64_t *state, uint64_t n)
{
    uint64_t limit = UINT64_MAX - UINT64_MAX % n;
    uint64_t x;
    do x = crq_next(state); while (x >= limit);
    return x % n;
}

pnpr_status pnpr_crq_order(size_t count, const uint8_t *group, uint32_t group_count,
                           uint64_t seed, uint32_t *r_order, size_t *r_group_start)
{
    if ((count > 0 && !r_order) || count >= 0xFFFFFFFFu || group_count > 255)
        return PNPR_ERR_INVALID_ARGUMENT;
    size_t ngroups = (size_t)group_count + 1; /* + the "other" group */
    size_t start[257];
    memset(start, 0, sizeof start);
    /* counting sort by group, stable (input order inside a group before shuffling) */
    for (size_t i = 0; i < count; i++) {
        size_t g = group ? group[i] : 0;
        if (g > group_count) g = group_count;
        start[g + 1]++;
    }
    for (size_t g = 0; g < ngroups; g++) start[g + 1] += start[g];
    size_t fill[257];
    memcpy(fill, start, sizeof fill);
    for (size_t i = 0; i < count; i++) {
        size_t g = group ? group[i] : 0;
        if (g > group_count) g = group_count;
        r_order[fill[g]++] = (uint32_t)i;
    }
    /* Fisher-Yates inside each group; one generator per group so that a group's order does not
     * depend on the sizes of the groups before it. */
    for (size_t g = 0; g < ngroups && count > 0; g++) {
        uint64_t state = seed ^ (0xD1B54A32D192ED03ull * (uint64_t)(g + 1));
        uint32_t *q = r_order + start[g];
        size_t n = start[g + 1] - start[g];
        for (size_t i = n; i > 1; i--) {
            size_t j = (size_t)crq_below(&state, i);
            uint32_t t = q[i - 1];
            q[i - 1] = q[j];
            q[j] = t;
        }
    }
    if (r_group_start)
        for (size_t g = 0; g <= ngroups; g++) r_group_start[g] = start[g];
    return PNPR_OK;
}

void pnpr_crq_split(const size_t *group_size, size_t group_count, size_t total, size_t *r_draw)
{
    unsigned long long sum = 0;
    for (size_t g = 0; g < group_count; g++) sum += group_size[g];
    if (total >= sum) {
        for (size_t g = 0; g < group_count; g++) r_draw[g] = group_size[g];
        return;
    }
    size_t given = 0;
    for (size_t g = 0; g < group_count; g++) { /* floor(total * size / sum): fits 64 bits */
        r_draw[g] = (size_t)(((unsigned long long)total * group_size[g]) / sum);
        given += r_draw[g];
    }
    /* The remainders add up to less than group_count points: hand them out one per group,
     * largest remainder first, ties to the lower group. */
    while (given < total) {
        size_t best = group_count;
        unsigned long long best_rem = 0;
        for (size_t g = 0; g < group_count; g++) {
            unsigned long long base = ((unsigned long long)total * group_size[g]) / sum;
            if (r_draw[g] > base || r_draw[g] >= group_size[g]) continue;
            unsigned long long rem = ((unsigned long long)total * group_size[g]) % sum;
            if (best == group_count || rem > best_rem) { best = g; best_rem = rem; }
        }
        if (best == group_count) break;
        r_draw[best]++;
        given++;
    }
}

/* ---- per-cell queues (crq.h) ----------------------------------------------------------------- */

uint16_t pnpr_crq_key(size_t rank, size_t count, double offset)
{
    double k = floor(((double)rank + offset) * (double)PNPR_CRQ_KEYS / (double)count);
    return k >= PNPR_CRQ_KEYS - 1 ? (uint16_t)(PNPR_CRQ_KEYS - 1) : k <= 0 ? 0 : (uint16_t)k;
}

/* The queues' offsets: the golden-ratio sequence over the queues with points, group-major. */
static void cells_offsets(pnpr_crq_cells *q, uint64_t seed)
{
    uint64_t state = seed ^ 0x8BB84B93962EACC9ull;
    double s = (double)(crq_next(&state) >> 11) * 0x1.0p-53, m = 0;
    for (size_t i = 0; i < q->groups * q->cells; i++) {
        if (!q->count[i]) continue;
        double h = s + 0.6180339887498949 * m++;
        q->offset[i] = (float)(h - floor(h));
        if (!(q->offset[i] < 1.0f)) q->offset[i] = 0; /* (rounded up to 1) */
    }
}

void pnpr_crq_cells_free(pnpr_crq_cells *q)
{
    free(q->count);
    free(q->cum);
    free(q->offset);
    memset(q, 0, sizeof *q);
}

/* Keys of group g's points in queue order (into r_key), then the group sorted by them: a counting
 * sort moves the points through `tmp`; the sorted keys follow from the counts. */
static void cells_sort_group(pnpr_crq_cells *q, uint32_t *order, size_t a, size_t b, size_t g, pnpr_crq_cell_fn cell_of,
                             const void *user, uint32_t *seen, uint16_t *r_key, uint32_t *tmp)
{
    const uint32_t *count = q->count + g * q->cells;
    uint32_t *cum = q->cum + g * (size_t)(PNPR_CRQ_KEYS + 1);
    memset(seen, 0, q->cells * sizeof *seen);
    for (size_t i = a; i < b; i++) {
        uint32_t k = cell_of(user, order[i]);
        r_key[i] = pnpr_crq_key(seen[k]++, count[k], q->offset[g * q->cells + k]);
        cum[r_key[i] + 1]++;
    }
    for (size_t v = 0; v < PNPR_CRQ_KEYS; v++) cum[v + 1] += cum[v];
    for (size_t i = a; i < b; i++) tmp[cum[r_key[i]]++] = order[i]; /* stable: in queue order per key */
    for (size_t v = PNPR_CRQ_KEYS; v > 0; v--) cum[v] = cum[v - 1]; /* undo the fill: keys below v */
    cum[0] = 0;
    memcpy(order + a, tmp, (b - a) * sizeof *order);
    for (size_t v = 0; v < PNPR_CRQ_KEYS; v++)
        for (size_t i = cum[v]; i < cum[v + 1]; i++) r_key[a + i] = (uint16_t)v;
}

pnpr_status pnpr_crq_cells_make(uint32_t *order, const size_t *group_start, size_t groups, pnpr_crq_cell_fn cell_of,
                                const void *user, size_t cells, uint64_t seed, uint16_t *r_key, pnpr_crq_cells *r)
{
    memset(r, 0, sizeof *r);
    if (groups == 0 || cells == 0 || !cell_of) return PNPR_ERR_INVALID_ARGUMENT;
    size_t most = 0;
    for (size_t g = 0; g < groups; g++)
        if (group_start[g + 1] - group_start[g] > most) most = group_start[g + 1] - group_start[g];
    r->groups = groups;
    r->cells = cells;
    r->count = calloc(groups * cells, sizeof *r->count);
    r->cum = calloc(groups * (size_t)(PNPR_CRQ_KEYS + 1), sizeof *r->cum);
    r->offset = calloc(groups * cells, sizeof *r->offset);
    uint32_t *seen = malloc(cells * sizeof *seen), *tmp = malloc((most ? most : 1) * sizeof *tmp);
    pnpr_status st = r->count && r->cum && r->offset && seen && tmp ? PNPR_OK : PNPR_ERR_OUT_OF_MEMORY;
    for (size_t g = 0; st == PNPR_OK && g < groups; g++)
        for (size_t i = group_start[g]; i < group_start[g + 1]; i++) {
            uint32_t k = cell_of(user, order[i]);
            if (k >= cells) { st = PNPR_ERR_INVALID_ARGUMENT; break; }
            r->count[g * cells + k]++;
        }
    if (st == PNPR_OK) cells_offsets(r, seed);
    for (size_t g = 0; st == PNPR_OK && g < groups; g++)
        cells_sort_group(r, order, group_start[g], group_start[g + 1], g, cell_of, user, seen, r_key, tmp);
    free(seen);
    free(tmp);
    if (st != PNPR_OK) pnpr_crq_cells_free(r);
    return st;
}

/* The keys v a shader keeps under `end`: (float)v + 0.5f < end, as a count of the keys from 0. */
static size_t keys_below(float end)
{
    if (!(end > 0.5f)) return 0;
    size_t lo = 0, hi = PNPR_CRQ_KEYS; /* the first key not kept */
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if ((float)mid + 0.5f < end) lo = mid + 1;
        else hi = mid;
    }
    return lo;
}

size_t pnpr_crq_cells_prefix(const pnpr_crq_cells *q, size_t g, float end)
{
    if (!q->cum || g >= q->groups) return 0;
    return q->cum[g * (size_t)(PNPR_CRQ_KEYS + 1) + keys_below(end)];
}

size_t pnpr_crq_cells_drawn(const pnpr_crq_cells *q, const float *end, size_t stride)
{
    size_t drawn = 0;
    for (size_t k = 0; q->count && k < q->cells; k++) {
        size_t kept = keys_below(end[k * stride]);
        if (kept == 0) continue;
        for (size_t g = 0; g < q->groups; g++) {
            size_t c = q->count[g * q->cells + k];
            if (c == 0) continue;
            if (kept >= PNPR_CRQ_KEYS) { drawn += c; continue; }
            double h = q->offset[g * q->cells + k];
            size_t lo = 0, hi = c; /* the first rank whose key is not kept */
            while (lo < hi) {
                size_t mid = lo + (hi - lo) / 2;
                if (pnpr_crq_key(mid, c, h) < kept) lo = mid + 1;
                else hi = mid;
            }
            drawn += lo;
        }
    }
    return drawn;
}
