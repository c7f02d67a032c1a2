/* Connected components at a distance threshold (the "CC" segment source of Wegen et al.):
 * points closer than `distance` (<=) are connected; components are the classes of the
 * transitive closure (union-find over the kd-tree, sequential, deterministic:
 * pnpr_kdtree_components, whose cost does not grow with the distance).
 *
 * Choices: distance 0 = 3 x the median nearest-neighbour distance, measured on a stride sample of
 * at most 10000 points (coincident neighbours skipped; a cloud of coincident points gets
 * distance 0, which connects exactly the coincident points). Components smaller than min_size
 * are not dropped (every point keeps a label): each of their points joins the component of its
 * nearest point in a kept component; when no component is large enough, all are kept. */
#include <pointnpr/segment.h>
#include <pointnpr/options.h>
#include <pointnpr/knn.h>

#include "../core/internal.h"
#include "kdtree_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "../core/vec3.h"

/* The distance from p to its nearest distinct point among its 8 nearest (the tree's points,
 * itself included); 0 when all 8 coincide with it. One rule for the cloud in memory and in
 * tiles (segment_tiles.c). */
float pnpr_segment_nn_distinct(const pnpr_kdtree *tree, const float p[3], float *r_eighth)
{
    uint32_t idx[8];
    float dist2[8];
    size_t n = pnpr_kdtree_knn(tree, p, 8, idx, dist2);
    if (r_eighth) *r_eighth = n == 8 ? sqrtf(dist2[7]) : INFINITY;
    for (size_t r = 0; r < n; r++)
        if (dist2[r] > 0) return sqrtf(dist2[r]);
    return 0;
}

float pnpr_segment_median_spacing(const pnpr_kdtree *tree, const float *xyz, size_t count)
{
    size_t step = count / PNPR_SEGMENT_SPACING_SAMPLE + 1, m = 0;
    float *d = malloc((count / step + 1) * sizeof *d);
    if (!d) return 0;
    for (size_t i = 0; i < count; i += step) {
        if (!pnpr_finite3f(xyz + 3 * i)) continue;
        float nn = pnpr_segment_nn_distinct(tree, xyz + 3 * i, NULL);
        if (nn > 0) d[m++] = nn;
    }
    float med = 0;
    if (m) med = pnpr_median_float(d, m);
    free(d);
    return med;
}

float pnpr_components_distance(const pnpr_components_options *opts, float median_spacing)
{
    if (opts && opts->distance > 0) return opts->distance;
    size_t n;
    const pnpr_option_desc *table = pnpr_components_option_table(&n);
    return (float)pnpr_option_find(table, n, "radius")->auto_scale * median_spacing;
}

pnpr_status pnpr_segment_components(const float *xyz, size_t count, const pnpr_components_options *opts,
                                    uint32_t *r_labels, pnpr_segment_info *r_info)
{
    double t0 = pnpr_now();
    if (r_info) { memset(r_info, 0, sizeof *r_info); r_info->invalid_segment = PNPR_LABEL_NONE; }
    if (!count) return PNPR_OK;
    if (!xyz || !r_labels || count >= 0x7FFFFFFFu) return PNPR_ERR_INVALID_ARGUMENT;
    pnpr_components_options o = opts ? *opts : (pnpr_components_options){0};
    if (!(o.distance >= 0) || isinf(o.distance)) return PNPR_ERR_INVALID_ARGUMENT;
    pnpr_kdtree *tree = NULL, *kept_tree = NULL;
    uint32_t *size = NULL, *kept = NULL;
    float *kept_xyz = NULL;
    pnpr_status st = pnpr_kdtree_build_threads(xyz, count, 0, o.threads, &tree);
    if (st != PNPR_OK) return st;
    float dist = pnpr_components_distance(&o, o.distance > 0 ? 0 : pnpr_segment_median_spacing(tree, xyz, count));
    size = calloc(count, sizeof *size);
    if (!size) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
    if ((st = pnpr_kdtree_components(tree, count, dist, &o.progress, r_labels)) != PNPR_OK) goto done;
    size_t nkept = 0;
    for (size_t i = 0; i < count; i++)
        if (pnpr_finite3f(xyz + 3 * i)) size[r_labels[i]]++;
    if (o.min_size > 1) {
        for (size_t i = 0; i < count; i++)
            if (pnpr_finite3f(xyz + 3 * i) && size[r_labels[i]] >= o.min_size) nkept++;
        size_t nvalid = 0;
        for (size_t i = 0; i < count; i++) nvalid += (size_t)pnpr_finite3f(xyz + 3 * i);
        if (nkept && nkept < nvalid) {
            kept = malloc(nkept * sizeof *kept);
            kept_xyz = malloc(3 * nkept * sizeof *kept_xyz);
            if (!kept || !kept_xyz) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
            size_t m = 0;
            for (size_t i = 0; i < count; i++)
                if (pnpr_finite3f(xyz + 3 * i) && size[r_labels[i]] >= o.min_size) {
                    kept[m] = (uint32_t)i;
                    memcpy(kept_xyz + 3 * m, xyz + 3 * i, 3 * sizeof(float));
                    m++;
                }
            if ((st = pnpr_kdtree_build_threads(kept_xyz, nkept, 0, o.threads, &kept_tree)) != PNPR_OK) goto done;
            for (size_t i = 0; i < count; i++) {
                if (!pnpr_finite3f(xyz + 3 * i) || size[r_labels[i]] >= o.min_size) continue;
                uint32_t nn;
                if (pnpr_kdtree_knn(kept_tree, xyz + 3 * i, 1, &nn, NULL) == 1)
                    r_labels[i] = r_labels[kept[nn]];
            }
        }
    }
    pnpr_progress_report(&o.progress, "components", 1.0);
    st = pnpr_segment_finish(xyz, count, r_labels, r_info);
done:
    pnpr_kdtree_free(tree);
    pnpr_kdtree_free(kept_tree);
    free(size); free(kept); free(kept_xyz);
    if (r_info) r_info->seconds = pnpr_now() - t0;
    return st;
}
