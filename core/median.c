/* Sorting floats and their median (internal.h): one comparator for every qsort of floats. */
#include "internal.h"

#include <stdlib.h>

int pnpr_cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return x < y ? -1 : x > y;
}

float pnpr_median_float(float *v, size_t n)
{
    qsort(v, n, sizeof *v, pnpr_cmp_float);
    return v[n / 2];
}
