/* Sorting floats and their median, and sorting 32-bit indices (internal.h): one comparator for
 * every qsort of floats, one for every qsort of uint32_t. */
#include "internal.h"

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

float pnpr_median_float(float *v, size_t n)
{
    qsort(v, n, sizeof *v, pnpr_cmp_float);
    return v[n / 2];
}
