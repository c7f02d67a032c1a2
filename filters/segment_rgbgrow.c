/* Colour region growing, the clustering stroke-based splatting uses (after Zhan, Liang & Xiao,
 * "Color-based segmentation of point clouds", 2009):
 *  1. growing: an unlabelled point starts a region (points in array order); a breadth-first
 *     growth adds each neighbour (k nearest within `distance`) whose RGB colour differs from the
 *     colour of the point it is reached from by less than point_distance;
 *  2. merging: adjacent regions whose mean colours are similar merge (Zhan et al. compare mean
 *     RGB; we compare mean CIE L*a*b*, delta E < region_distance, closest pair first);
 *  3. regions smaller than min_size merge into the adjacent region of closest mean colour.
 * Steps 2-3 are pnpr_segment_merge_regions over the same neighbour graph. */
#include <pointnpr/segment.h>
#include <pointnpr/options.h>
#include <pointnpr/knn.h>

#include "../core/internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "../core/vec3.h"


pnpr_status pnpr_segment_rgbgrow(const float *xyz, const uint8_t *rgb, size_t count,
                                 const pnpr_rgbgrow_options *opts, uint32_t *r_labels,
                                 pnpr_segment_info *r_info)
{
    double t0 = pnpr_now();
    if (r_info) { memset(r_info, 0, sizeof *r_info); r_info->invalid_segment = PNPR_LABEL_NONE; }
    if (!count) return PNPR_OK;
    if (!xyz || !rgb || !r_labels || count >= 0x7FFFFFFFu) return PNPR_ERR_INVALID_ARGUMENT;
    pnpr_rgbgrow_options o = opts ? *opts : (pnpr_rgbgrow_options){0};
    if (!(o.distance >= 0) || isinf(o.distance)) return PNPR_ERR_INVALID_ARGUMENT;
    size_t table_count;
    const pnpr_option_desc *table = pnpr_rgbgrow_option_table(&table_count);
    pnpr_option_fill_defaults(table, table_count, &o); /* zeros -> the table's defaults (options.h) */
    size_t k = o.k > PNPR_SEGMENT_K_MAX ? PNPR_SEGMENT_K_MAX : o.k;
    const pnpr_rgbgrow_options d = pnpr_rgbgrow_defaults();
    double pd = o.point_distance > 0 ? o.point_distance : d.point_distance;
    double rd = o.region_distance > 0 ? o.region_distance : (o.region_distance < 0 ? 0 : d.region_distance);
    uint32_t min_size = o.min_size;
    pnpr_kdtree *tree = NULL;
    uint32_t *knn = NULL, *queue = NULL;
    float *d2 = NULL;
    pnpr_status st = pnpr_kdtree_build_threads(xyz, count, 0, o.threads, &tree);
    if (st != PNPR_OK) return st;
    size_t nvalid = pnpr_kdtree_size(tree);
    if (!nvalid) { pnpr_kdtree_free(tree); st = pnpr_segment_finish(xyz, count, r_labels, r_info); goto out; }
    if (k > nvalid) k = nvalid;
    float dist = o.distance > 0 ? o.distance
                                : (float)pnpr_option_find(table, table_count, "radius")->auto_scale *
                                      pnpr_segment_median_spacing(tree, xyz, count);
    knn = malloc(count * k * sizeof *knn);
    d2 = malloc(count * k * sizeof *d2);
    queue = malloc(count * sizeof *queue);
    if (!knn || !d2 || !queue) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
    pnpr_knn_options ko = {o.threads, o.progress, 0};
    if ((st = pnpr_knn_self(tree, count, k, &ko, knn, d2)) != PNPR_OK) goto done;
    float r2 = dist * dist;
    for (size_t i = 0; i < count * k; i++) if (!(d2[i] <= r2)) knn[i] = PNPR_INDEX_NONE;
    free(d2);
    d2 = NULL;

    for (size_t i = 0; i < count; i++) r_labels[i] = PNPR_LABEL_NONE;
    uint32_t nreg = 0;
    double pd2 = pd * pd;
    for (size_t s = 0; s < count; s++) {
        if (r_labels[s] != PNPR_LABEL_NONE || !pnpr_finite3f(xyz + 3 * s)) continue;
        size_t head = 0, tail = 0;
        queue[tail++] = (uint32_t)s;
        r_labels[s] = nreg;
        while (head < tail) {
            uint32_t p = queue[head++];
            const uint32_t *row = knn + (size_t)p * k;
            const uint8_t *cp = rgb + 3 * (size_t)p;
            for (size_t r = 0; r < k; r++) {
                uint32_t q = row[r];
                if (q == PNPR_INDEX_NONE || r_labels[q] != PNPR_LABEL_NONE) continue;
                const uint8_t *cq = rgb + 3 * (size_t)q;
                double dr = (double)cp[0] - cq[0], dg = (double)cp[1] - cq[1], db = (double)cp[2] - cq[2];
                if (dr * dr + dg * dg + db * db < pd2) { r_labels[q] = nreg; queue[tail++] = q; }
            }
        }
        nreg++;
        if ((nreg & 0x3FF) == 0 && pnpr_progress_report(&o.progress, "grow", (double)s / (double)count)) {
            st = PNPR_ERR_CANCELLED;
            goto done;
        }
    }
    for (size_t i = 0; i < count; i++) if (r_labels[i] == PNPR_LABEL_NONE) r_labels[i] = nreg; /* invalid */
    if (pnpr_progress_report(&o.progress, "merge", 0.0)) { st = PNPR_ERR_CANCELLED; goto done; }
    pnpr_region_graph graph = {knn, k, k};
    if ((st = pnpr_segment_merge_regions(rgb, count, &graph, (float)rd, min_size, r_labels, &nreg)) != PNPR_OK) goto done;
    pnpr_progress_report(&o.progress, "merge", 1.0);
    st = pnpr_segment_finish(xyz, count, r_labels, r_info);
done:
    pnpr_kdtree_free(tree);
    free(knn); free(d2); free(queue);
out:
    if (r_info) r_info->seconds = pnpr_now() - t0;
    return st;
}
