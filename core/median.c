/* Sorting floats, selecting the k-th of floats or doubles and their median, and sorting 32-bit
 * indices (internal.h): one comparator for every qsort of floats, one for every qsort of uint32_t,
 * one for every qsort of uint64_t keys. */
#include "internal.h"

#include <stdint.h>
#include <stdlib.h>

int pnpr_cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return x < y ? -1 : x > y;
}

int pnpr_cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return x < y ? -1 : x > y;
}

int pnpr_cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* Quickselect (Hoare's FIND) with a three-way partition: v[k] ends as the k-th smallest, smaller
 * values before it, larger after. Values that compare neither less nor greater than the pivot (its
 * equals, NaN) join its band, so every round shrinks the range and duplicates cost nothing. The
 * pivot is the median of three positions drawn by a generator seeded with n (no global state):
 * expected O(n) on any input, O(n^2) only for data built against this very generator. It replaces
 * qsort for medians and quantiles: on a 1M-point cloud the spacing median alone was 10% of a
 * `render` (sorting, comparator calls). One body for floats and doubles. */
#define PNPR_SELECT(T, name)                                                                   \
    T name(T *v, size_t n, size_t k)                                                           \
    {                                                                                          \
        size_t lo = 0, hi = n; /* the k-th lies in [lo, hi) */                                 \
        uint64_t rng = 0x9E3779B97F4A7C15ull ^ (uint64_t)n;                                    \
        while (hi - lo > 1) {                                                                  \
            size_t span = hi - lo, c[3];                                                       \
            for (int t = 0; t < 3; t++) {                                                      \
                rng = rng * 6364136223846793005ull + 1442695040888963407ull;                   \
                c[t] = lo + (size_t)((rng >> 33) % span);                                      \
            }                                                                                  \
            T a = v[c[0]], b = v[c[1]], d = v[c[2]];                                           \
            T p = (a < b) ? (b < d ? b : (a < d ? d : a)) : (a < d ? a : (b < d ? d : b));    \
            size_t lt = lo, i = lo, gt = hi; /* [lo,lt) < p, [lt,i) = p, [gt,hi) > p */        \
            while (i < gt) {                                                                   \
                T x = v[i];                                                                    \
                if (x < p) { v[i++] = v[lt]; v[lt++] = x; }                                    \
                else if (x > p) { v[i] = v[--gt]; v[gt] = x; }                                 \
                else i++;                                                                      \
            }                                                                                  \
            if (k < lt) hi = lt;                                                               \
            else if (k >= gt) lo = gt;                                                         \
            else return v[k];                                                                  \
        }                                                                                      \
        return v[k];                                                                           \
    }
PNPR_SELECT(float, pnpr_select_float)
PNPR_SELECT(double, pnpr_select_double)
#undef PNPR_SELECT

float pnpr_median_float(float *v, size_t n)
{
    return pnpr_select_float(v, n, n / 2);
}
