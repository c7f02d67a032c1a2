/* Continuous resolution queue (PointWorks section 4.4): the points of each group in a random
 * order fixed once; a frame draws a prefix of each group's queue. */
#include <pointnpr/crq.h>

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
