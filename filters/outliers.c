/* Far outliers (include/pointnpr/outliers.h): the robust centre (per-axis median) and extent
 * (a quantile of the distances from it) over a deterministic stride sample, then the far test
 * on every point, in double. */
#include <pointnpr/options.h>
#include <pointnpr/outliers.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "../core/internal.h"
#include "../core/vec3.h"

/* World coordinates from an array or from a cloud. */
typedef struct source {
    const double *world;
    const pnpr_cloud *cloud;
    size_t count;
    int is_sample; /* world is the stride sample itself: take every point */
} source;


/* World point i into w; returns whether it is finite. */
static int get_world(const source *s, size_t i, double w[3])
{
    if (s->world) memcpy(w, s->world + 3 * i, 3 * sizeof *w);
    else pnpr_cloud_world(s->cloud, i, w);
    return pnpr_finite3d(w);
}

static double distance(const double c[3], const double w[3])
{
    double d[3] = {w[0] - c[0], w[1] - c[1], w[2] - c[2]};
    return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/* Room for the sample: min(count, PNPR_OUTLIER_SAMPLES), at least 1. */
static size_t sample_cap(const source *s)
{
    return s->count < PNPR_OUTLIER_SAMPLES ? (s->count ? s->count : 1) : PNPR_OUTLIER_SAMPLES;
}

/* The finite points of a stride sample (at most sample_cap) into v (3 arrays of sample_cap
 * doubles, one per axis); returns how many. */
static size_t take_sample(const source *s, double *v)
{
    const size_t cap = sample_cap(s), step = s->is_sample ? 1 : s->count / PNPR_OUTLIER_SAMPLES + 1;
    size_t m = 0;
    for (size_t i = 0; i < s->count && m < cap; i += step) {
        double w[3];
        if (!get_world(s, i, w)) continue;
        for (int a = 0; a < 3; a++) v[(size_t)a * cap + m] = w[a];
        m++;
    }
    return m;
}

/* Robust centre and extent of the source into info (centre, extent, limit). */
static pnpr_status robust_frame(const source *s, double factor, pnpr_outlier_info *info)
{
    const size_t cap = sample_cap(s);
    double *v = malloc(4 * cap * sizeof *v);
    if (!v) return PNPR_ERR_OUT_OF_MEMORY;
    size_t m = take_sample(s, v);
    double *dist = v + 3 * cap;
    if (m > 0) {
        for (int a = 0; a < 3; a++) {
            double *axis = v + (size_t)a * cap;
            for (size_t i = 0; i < m; i++) dist[i] = axis[i]; /* keep the sample's rows intact */
            info->centre[a] = pnpr_select_double(dist, m, m / 2);
        }
        for (size_t i = 0; i < m; i++) {
            double w[3] = {v[i], v[cap + i], v[2 * cap + i]};
            dist[i] = distance(info->centre, w);
        }
        info->extent = pnpr_select_double(dist, m, (size_t)floor(PNPR_OUTLIER_QUANTILE * (double)(m - 1)));
    }
    info->limit = info->extent > 0 ? factor * info->extent : INFINITY;
    free(v);
    return PNPR_OK;
}

int pnpr_outlier_is_far(const pnpr_outlier_info *info, const double w[3])
{
    return info && w && pnpr_finite3d(w) && distance(info->centre, w) > info->limit;
}

static pnpr_status find_outliers(const source *s, const pnpr_outlier_options *opts, uint8_t *r_far,
                                 pnpr_outlier_info *r_info)
{
    pnpr_outlier_info local;
    pnpr_outlier_info *info = r_info ? r_info : &local;
    memset(info, 0, sizeof *info);
    size_t table_count;
    const pnpr_option_desc *table = pnpr_outlier_option_table(&table_count);
    pnpr_outlier_options o = opts ? *opts : pnpr_outlier_defaults();
    if (pnpr_option_check(table, table_count, &o, NULL) != PNPR_OK) return PNPR_ERR_INVALID_ARGUMENT;
    pnpr_option_fill_defaults(table, table_count, &o); /* 0 -> the table's default (options.h) */
    const double factor = o.factor;
    pnpr_status st = robust_frame(s, factor, info);
    if (st != PNPR_OK) return st;
    for (size_t i = 0; i < s->count; i++) {
        double w[3];
        int far = 0;
        if (get_world(s, i, w)) {
            const float *p = s->cloud ? s->cloud->xyz + 3 * i : NULL;
            int beyond = p && !(isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]));
            far = beyond || pnpr_outlier_is_far(info, w);
            info->finite++;
            info->beyond_float += (size_t)beyond;
            info->far += (size_t)far;
        }
        if (r_far) r_far[i] = (uint8_t)far;
    }
    return PNPR_OK;
}

pnpr_status pnpr_world_outliers(const double *world, size_t count, const pnpr_outlier_options *opts,
                                uint8_t *r_far, pnpr_outlier_info *r_info)
{
    if (count && !world) return PNPR_ERR_INVALID_ARGUMENT;
    source s = {world, NULL, count, 0};
    return find_outliers(&s, opts, r_far, r_info);
}

pnpr_status pnpr_outlier_frame_of_sample(const double *sample, size_t m, pnpr_outlier_info *r_info)
{
    if ((m && !sample) || m > PNPR_OUTLIER_SAMPLES || !r_info) return PNPR_ERR_INVALID_ARGUMENT;
    memset(r_info, 0, sizeof *r_info);
    source s = {sample, NULL, m, 1};
    size_t n;
    const pnpr_option_desc *table = pnpr_outlier_option_table(&n);
    pnpr_outlier_options o = pnpr_outlier_defaults();
    pnpr_option_fill_defaults(table, n, &o);
    return robust_frame(&s, o.factor, r_info);
}

pnpr_status pnpr_cloud_outliers(const pnpr_cloud *cloud, const pnpr_outlier_options *opts, uint8_t *r_far,
                                pnpr_outlier_info *r_info)
{
    if (!cloud || (cloud->count && !cloud->xyz)) return PNPR_ERR_INVALID_ARGUMENT;
    source s = {NULL, cloud, cloud->count, 0};
    return find_outliers(&s, opts, r_far, r_info);
}

pnpr_status pnpr_cloud_drop_outliers(pnpr_cloud *cloud, const pnpr_outlier_options *opts,
                                     pnpr_outlier_info *r_info)
{
    if (!cloud || (cloud->count && !cloud->xyz)) return PNPR_ERR_INVALID_ARGUMENT;
    uint8_t *keep = malloc(cloud->count ? cloud->count : 1);
    if (!keep) return PNPR_ERR_OUT_OF_MEMORY;
    pnpr_status st = pnpr_cloud_outliers(cloud, opts, keep, r_info);
    for (size_t i = 0; st == PNPR_OK && i < cloud->count; i++) keep[i] = !keep[i];
    if (st == PNPR_OK) st = pnpr_cloud_keep(cloud, keep, NULL);
    free(keep);
    return st;
}

size_t pnpr_cloud_inlier_bounds(const pnpr_cloud *cloud, float r_min[3], float r_max[3])
{
    pnpr_outlier_info oi;
    if (!cloud || pnpr_cloud_outliers(cloud, NULL, NULL, &oi) != PNPR_OK || oi.far == 0)
        return pnpr_cloud_bounds(cloud, r_min, r_max);
    size_t n = 0;
    for (int a = 0; a < 3; a++) { r_min[a] = INFINITY; r_max[a] = -INFINITY; }
    for (size_t i = 0; i < cloud->count; i++) {
        const float *p = cloud->xyz + 3 * i;
        double w[3];
        pnpr_cloud_world(cloud, i, w);
        if (!(isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2])) || pnpr_outlier_is_far(&oi, w)) continue;
        n++;
        for (int a = 0; a < 3; a++) {
            r_min[a] = fminf(r_min[a], p[a]);
            r_max[a] = fmaxf(r_max[a], p[a]);
        }
    }
    return n;
}
