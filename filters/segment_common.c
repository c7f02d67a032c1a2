/* Segment utilities shared by every segment source: labels imported from per-point values,
 * renumbering, mean colours, sRGB -> CIE L*a*b*, and the comparison with ground truth
 * (adjusted Rand index of Hubert & Arabie, over/under-segmentation counts).
 *
 * Everything works on arbitrary uint32 labels by sorting (no assumption on the label range), so
 * O(n log n) time and 8 bytes per point of scratch. */
#include <pointnpr/props.h>
#include <pointnpr/segment.h>

#include "../core/internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

pnpr_status pnpr_segment_compact(uint32_t *io_labels, size_t count, uint32_t *r_segment_count)
{
    if (r_segment_count) *r_segment_count = 0;
    if (count && !io_labels) return PNPR_ERR_INVALID_ARGUMENT;
    if (count >= 0xFFFFFFFFu) return PNPR_ERR_INVALID_ARGUMENT;
    if (!count) return PNPR_OK;
    /* (value, index) sorted: the first entry of each value run is its first appearance. */
    uint64_t *key = malloc(count * sizeof *key);
    if (!key) return PNPR_ERR_OUT_OF_MEMORY;
    for (size_t i = 0; i < count; i++) key[i] = (uint64_t)io_labels[i] << 32 | (uint64_t)i;
    qsort(key, count, sizeof *key, pnpr_cmp_u64);
    /* mark first appearances: first[i] = 1 where point i is the first of its value */
    uint8_t *first = calloc(count, 1);
    if (!first) { free(key); return PNPR_ERR_OUT_OF_MEMORY; }
    for (size_t r = 0; r < count; r++)
        if (r == 0 || (key[r] >> 32) != (key[r - 1] >> 32)) first[key[r] & 0xFFFFFFFFu] = 1;
    /* new id of a value = number of first appearances before its own, in point order */
    uint32_t *id_at = malloc(count * sizeof *id_at); /* id of the value first seen at point i */
    if (!id_at) { free(key); free(first); return PNPR_ERR_OUT_OF_MEMORY; }
    uint32_t s = 0;
    for (size_t i = 0; i < count; i++) id_at[i] = first[i] ? s++ : PNPR_LABEL_NONE;
    size_t r = 0;
    while (r < count) {
        uint32_t v = (uint32_t)(key[r] >> 32);
        uint32_t id = id_at[key[r] & 0xFFFFFFFFu];
        for (; r < count && (uint32_t)(key[r] >> 32) == v; r++) io_labels[key[r] & 0xFFFFFFFFu] = id;
    }
    free(key); free(first); free(id_at);
    if (r_segment_count) *r_segment_count = s;
    return PNPR_OK;
}

pnpr_status pnpr_segment_finish(const float *xyz, size_t count, uint32_t *io_labels,
                                pnpr_segment_info *r_info)
{
    if (count && !io_labels) return PNPR_ERR_INVALID_ARGUMENT;
    if (count >= 0xFFFFFFFFu) return PNPR_ERR_INVALID_ARGUMENT;
    size_t valid = 0;
    for (size_t i = 0; i < count; i++) {
        const float *p = xyz ? xyz + 3 * i : NULL;
        if (!p || (isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]))) valid++;
    }
    uint32_t s = 0;
    pnpr_status st = PNPR_OK;
    if (valid == count) {
        st = pnpr_segment_compact(io_labels, count, &s);
    } else if (valid) {
        uint32_t *tmp = malloc(valid * sizeof *tmp);
        if (!tmp) return PNPR_ERR_OUT_OF_MEMORY;
        size_t m = 0;
        for (size_t i = 0; i < count; i++) {
            const float *p = xyz + 3 * i;
            if (isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2])) tmp[m++] = io_labels[i];
        }
        st = pnpr_segment_compact(tmp, valid, &s);
        m = 0;
        for (size_t i = 0; i < count && st == PNPR_OK; i++) {
            const float *p = xyz + 3 * i;
            io_labels[i] = isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]) ? tmp[m++] : s;
        }
        free(tmp);
    } else {
        for (size_t i = 0; i < count; i++) io_labels[i] = 0;
    }
    if (st != PNPR_OK) return st;
    if (r_info) {
        r_info->valid_points = valid;
        r_info->invalid_segment = valid < count ? s : PNPR_LABEL_NONE;
        r_info->segment_count = s + (valid < count ? 1 : 0);
    }
    return PNPR_OK;
}

pnpr_status pnpr_segment_from_values(pnpr_type type, const void *values, size_t count,
                                     uint32_t *r_labels, uint32_t *r_segment_count)
{
    if (r_segment_count) *r_segment_count = 0;
    if (count && (!values || !r_labels || !pnpr_type_size(type))) return PNPR_ERR_INVALID_ARGUMENT;
    if (!count) return PNPR_OK;
    double *sorted = malloc(count * sizeof *sorted);
    if (!sorted) return PNPR_ERR_OUT_OF_MEMORY;
    size_t m = 0, nan = 0;
    for (size_t i = 0; i < count; i++) {
        double v = pnpr_type_get(type, values, i);
        if (isnan(v)) nan++;
        else sorted[m++] = v;
    }
    qsort(sorted, m, sizeof *sorted, cmp_double);
    size_t u = 0;
    for (size_t i = 0; i < m; i++)
        if (u == 0 || sorted[i] != sorted[u - 1]) sorted[u++] = sorted[i];
    for (size_t i = 0; i < count; i++) {
        double v = pnpr_type_get(type, values, i);
        if (isnan(v)) { r_labels[i] = (uint32_t)u; continue; }
        size_t lo = 0, hi = u; /* first index with sorted[idx] >= v */
        while (lo < hi) {
            size_t mid = lo + (hi - lo) / 2;
            if (sorted[mid] < v) lo = mid + 1; else hi = mid;
        }
        r_labels[i] = (uint32_t)lo;
    }
    free(sorted);
    if (r_segment_count) *r_segment_count = (uint32_t)(u + (nan ? 1 : 0));
    return PNPR_OK;
}

pnpr_status pnpr_segment_mean_colors(const uint8_t *rgb, const uint32_t *labels, size_t count,
                                     uint32_t segment_count, float *r_rgb, uint32_t *r_sizes)
{
    if (count && !labels) return PNPR_ERR_INVALID_ARGUMENT;
    if (!segment_count) return PNPR_OK;
    double *sum = calloc((size_t)segment_count * 4, sizeof *sum);
    if (!sum) return PNPR_ERR_OUT_OF_MEMORY;
    for (size_t i = 0; i < count; i++) {
        uint32_t l = labels[i];
        if (l >= segment_count) continue;
        double *s = sum + 4 * (size_t)l;
        if (rgb) { s[0] += rgb[3 * i]; s[1] += rgb[3 * i + 1]; s[2] += rgb[3 * i + 2]; }
        s[3] += 1;
    }
    for (uint32_t l = 0; l < segment_count; l++) {
        const double *s = sum + 4 * (size_t)l;
        if (r_rgb)
            for (int c = 0; c < 3; c++) r_rgb[3 * (size_t)l + c] = s[3] > 0 ? (float)(s[c] / s[3]) : 0.0f;
        if (r_sizes) r_sizes[l] = (uint32_t)s[3];
    }
    free(sum);
    return PNPR_OK;
}

pnpr_status pnpr_segment_add_colors(pnpr_cloud *cloud, const float *mean_rgb, uint32_t segment_count)
{
    if (!cloud || (cloud->count && (!cloud->label || (segment_count && !mean_rgb)))) return PNPR_ERR_INVALID_ARGUMENT;
    static const char *const names[3] = {PNPR_PROP_SEG_RED, PNPR_PROP_SEG_GREEN, PNPR_PROP_SEG_BLUE};
    for (int c = 0; c < 3; c++) {
        pnpr_property *p = NULL;
        pnpr_status st = pnpr_cloud_add_property(cloud, names[c], PNPR_TYPE_UINT8, &p);
        if (st != PNPR_OK) return st;
        uint8_t *d = p->data;
        for (size_t i = 0; i < cloud->count; i++) {
            uint32_t l = cloud->label[i];
            d[i] = l < segment_count ? (uint8_t)(mean_rgb[3 * (size_t)l + c] + 0.5f) : 0;
        }
    }
    return PNPR_OK;
}

static double srgb_linear(double c)
{
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

static double lab_f(double t)
{
    const double d = 6.0 / 29.0;
    return t > d * d * d ? cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
}

void pnpr_rgb_to_lab(const uint8_t rgb[3], float r_lab[3])
{
    double r = srgb_linear(rgb[0] / 255.0), g = srgb_linear(rgb[1] / 255.0), b = srgb_linear(rgb[2] / 255.0);
    /* sRGB -> XYZ (D65), normalised by the D65 white */
    double x = (0.4124564 * r + 0.3575761 * g + 0.1804375 * b) / 0.95047;
    double y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
    double z = (0.0193339 * r + 0.1191920 * g + 0.9503041 * b) / 1.08883;
    double fx = lab_f(x), fy = lab_f(y), fz = lab_f(z);
    r_lab[0] = (float)(116 * fy - 16);
    r_lab[1] = (float)(500 * (fx - fy));
    r_lab[2] = (float)(200 * (fy - fz));
}

static double pairs2(double n) { return n * (n - 1) / 2; }

pnpr_status pnpr_segment_score_labels(const uint32_t *truth, const uint32_t *result, size_t count,
                                      pnpr_segment_score *r_score)
{
    if (!r_score || (count && (!truth || !result))) return PNPR_ERR_INVALID_ARGUMENT;
    memset(r_score, 0, sizeof *r_score);
    r_score->ari = 1.0;
    if (!count) return PNPR_OK;
    uint32_t *t = malloc(count * sizeof *t), *r = malloc(count * sizeof *r);
    uint64_t *key = malloc(count * sizeof *key);
    pnpr_status st = PNPR_ERR_OUT_OF_MEMORY;
    uint32_t *tsize = NULL, *rsize = NULL, *tover = NULL, *runder = NULL;
    uint32_t nt = 0, nr = 0;
    if (!t || !r || !key) goto done;
    memcpy(t, truth, count * sizeof *t);
    memcpy(r, result, count * sizeof *r);
    if ((st = pnpr_segment_compact(t, count, &nt)) != PNPR_OK) goto done;
    if ((st = pnpr_segment_compact(r, count, &nr)) != PNPR_OK) goto done;
    st = PNPR_ERR_OUT_OF_MEMORY;
    tsize = calloc(nt, sizeof *tsize); rsize = calloc(nr, sizeof *rsize);
    tover = calloc(nt, sizeof *tover); runder = calloc(nr, sizeof *runder);
    if (!tsize || !rsize || !tover || !runder) goto done;
    for (size_t i = 0; i < count; i++) {
        tsize[t[i]]++; rsize[r[i]]++;
        key[i] = (uint64_t)t[i] << 32 | r[i];
    }
    qsort(key, count, sizeof *key, pnpr_cmp_u64);
    double sum_ij = 0, sum_a = 0, sum_b = 0;
    for (size_t i = 0; i < count;) {
        size_t j = i;
        while (j < count && key[j] == key[i]) j++;
        double nij = (double)(j - i);
        uint32_t a = (uint32_t)(key[i] >> 32), b = (uint32_t)(key[i] & 0xFFFFFFFFu);
        sum_ij += pairs2(nij);
        if (nij >= 0.1 * tsize[a]) {
            if (nij > 0.5 * rsize[b]) tover[a]++;
            runder[b]++;
        }
        i = j;
    }
    for (uint32_t a = 0; a < nt; a++) {
        sum_a += pairs2(tsize[a]);
        if (tover[a] >= 2) r_score->over_segmented++;
    }
    for (uint32_t b = 0; b < nr; b++) {
        sum_b += pairs2(rsize[b]);
        if (runder[b] >= 2) r_score->under_segmented++;
    }
    double total = pairs2((double)count);
    double expected = total > 0 ? sum_a * sum_b / total : 0;
    double maxi = 0.5 * (sum_a + sum_b);
    double den = maxi - expected;
    /* identical trivial partitions (one point, all-in-one vs all-in-one, singletons vs singletons)
     * give den = 0: they agree perfectly, ARI 1 */
    r_score->ari = fabs(den) > 1e-12 * (total > 1 ? total : 1) ? (sum_ij - expected) / den : 1.0;
    r_score->truth_segments = nt;
    r_score->result_segments = nr;
    st = PNPR_OK;
done:
    free(t); free(r); free(key); free(tsize); free(rsize); free(tover); free(runder);
    return st;
}
