/* Continuous resolution queue (no GL): the order is a permutation grouped by class and shuffled
 * inside each group, the same for the same seed, different for another seed; the per-group split
 * of a frame's budget is exact. */
#include "testutil.h"

#include <pointnpr/crq.h>

#include <stdlib.h>
#include <string.h>

static int is_permutation(const uint32_t *o, size_t n)
{
    char *seen = calloc(n ? n : 1, 1);
    int ok = seen != NULL;
    for (size_t i = 0; ok && i < n; i++) {
        if (o[i] >= n || seen[o[i]]) ok = 0;
        else seen[o[i]] = 1;
    }
    free(seen);
    return ok;
}

int main(void)
{
    enum { N = 10000 };
    uint32_t *a = malloc(N * sizeof *a), *b = malloc(N * sizeof *b), *c = malloc(N * sizeof *c);
    uint8_t *group = malloc(N);
    CHECK(a && b && c && group);
    if (!a || !b || !c || !group) return pnpr_test_finish("test_crq");

    /* one group: a permutation, deterministic, seed-dependent, not the identity */
    size_t starts[8];
    CHECK_STATUS(pnpr_crq_order(N, NULL, 1, 42, a, starts), PNPR_OK);
    CHECK_STATUS(pnpr_crq_order(N, NULL, 1, 42, b, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_crq_order(N, NULL, 1, 43, c, NULL), PNPR_OK);
    CHECK(is_permutation(a, N));
    CHECK(is_permutation(c, N));
    CHECK(memcmp(a, b, N * sizeof *a) == 0);
    CHECK(memcmp(a, c, N * sizeof *a) != 0);
    size_t fixed = 0, first_half = 0;
    for (size_t i = 0; i < N; i++) {
        fixed += a[i] == i;
        first_half += i < N / 10 && a[i] < N / 2;
    }
    CHECK_MSG(fixed < 20, "%zu fixed points", fixed);
    /* a random prefix is spread over the input: ~half of the first 10% come from the first half */
    CHECK_MSG(first_half > N / 20 - 150 && first_half < N / 20 + 150, "%zu", first_half);
    CHECK(starts[0] == 0 && starts[1] == N && starts[2] == N);

    /* groups: contiguous, each a shuffle of its members, unknown groups last */
    for (size_t i = 0; i < N; i++) group[i] = (uint8_t)(i % 7 == 0 ? 2 : i % 3 == 0 ? 0 : i % 11 == 0 ? 9 : 1);
    CHECK_STATUS(pnpr_crq_order(N, group, 4, 7, a, starts), PNPR_OK);
    CHECK(is_permutation(a, N));
    for (size_t g = 0; g <= 4; g++) {
        for (size_t q = starts[g]; q < starts[g + 1]; q++) {
            size_t gg = group[a[q]] > 4 ? 4 : group[a[q]];
            if (gg != g) { CHECK_MSG(0, "point %u of group %zu at queue position %zu of group %zu", a[q], gg, q, g); break; }
        }
    }
    CHECK(starts[5] == N);
    CHECK(starts[4] - starts[3] == 0); /* group 3 has no members */
    CHECK(starts[5] - starts[4] > 0);  /* value 9 went to the "other" group */
    /* a group's order does not depend on the other groups' members */
    uint8_t *g2 = malloc(N);
    CHECK(g2 != NULL);
    if (g2) {
        memcpy(g2, group, N);
        CHECK_STATUS(pnpr_crq_order(N, g2, 4, 7, b, NULL), PNPR_OK);
        CHECK(memcmp(a, b, N * sizeof *a) == 0);
        free(g2);
    }

    /* split: exact totals, proportional, never more than a group holds */
    size_t sizes[4] = {10, 0, 333, 7}, draw[4];
    for (size_t total = 0; total <= 360; total++) {
        pnpr_crq_split(sizes, 4, total, draw);
        size_t sum = 0;
        for (int g = 0; g < 4; g++) { sum += draw[g]; CHECK(draw[g] <= sizes[g]); }
        CHECK_MSG(sum == (total < 350 ? total : 350), "total %zu sum %zu", total, sum);
        CHECK(draw[1] == 0);
    }
    pnpr_crq_split(sizes, 4, 35, draw);
    CHECK(draw[0] == 1 && draw[2] == 33 && draw[3] == 1);

    /* degenerate */
    CHECK_STATUS(pnpr_crq_order(0, NULL, 1, 1, NULL, starts), PNPR_OK);
    CHECK(starts[0] == 0 && starts[1] == 0);
    CHECK_STATUS(pnpr_crq_order(5, NULL, 1, 1, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_crq_order(1, NULL, 1, 1, a, NULL), PNPR_OK);
    CHECK(a[0] == 0);

    free(a); free(b); free(c); free(group);
    return pnpr_test_finish("test_crq");
}
