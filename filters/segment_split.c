/* Covariance splitting within regions (Chi & Lee sec. 3.2, after Pauly et al. [29]): "each region
 * may cover a large area or contain several subregions of various curvature distributions;
 * therefore, we will perform further partitioning within each region using a covariance
 * splitting method. This splitting method splits the inputs along the direction of greatest
 * variation and sets user-specified thresholds for the curvature variations".
 *
 * Per region: if its surface variation s = lambda_0 / (lambda_0 + lambda_1 + lambda_2) (PCA of
 * its points, double, around the centroid) exceeds max_variation and it has at least 2 *
 * min_size points, it is split by the plane through its centroid perpendicular to the principal
 * eigenvector (the direction of greatest variation), and both halves are treated the same way
 * (an explicit stack, no recursion), at most PNPR_SPLIT_DEPTH_MAX times along any path, so the
 * cost is at most that many passes over the points however small min_size and max_variation are
 * (a centroid split of a skewed region may peel off few points at a time). Halves smaller than
 * min_size are not split off (the split is not made). The leaves are the output sub-regions,
 * numbered in order of first appearance; invalid points (label >= segment_count, or non-finite coordinates) keep a label of their own
 * after the others. Choices the paper leaves open: the split plane through the centroid (not a
 * median), the stop rule on surface variation (the paper: "curvature variations") and size. */
#include <pointnpr/features.h>
#include <pointnpr/options.h>
#include <pointnpr/segment.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct span { size_t begin, end; int depth; } span;

static double variation_and_axis(const float *xyz, const uint32_t *ids, size_t begin, size_t end,
                                 double r_c[3], double r_axis[3])
{
    double c[3] = {0, 0, 0}, cov[3][3] = {{0}};
    for (size_t i = begin; i < end; i++)
        for (int a = 0; a < 3; a++) c[a] += xyz[3 * (size_t)ids[i] + a];
    for (int a = 0; a < 3; a++) c[a] /= (double)(end - begin);
    for (size_t i = begin; i < end; i++) {
        const float *p = xyz + 3 * (size_t)ids[i];
        double d[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) cov[a][b] += d[a] * d[b];
    }
    double w[3], v[3][3];
    pnpr_eigen_sym3(cov, w, v);
    memcpy(r_c, c, sizeof c);
    memcpy(r_axis, v[2], sizeof v[2]);
    double tr = w[0] + w[1] + w[2];
    return tr > 0 ? w[0] / tr : 0;
}

pnpr_status pnpr_segment_covariance_split(const float *xyz, size_t count, const uint32_t *labels,
                                          uint32_t segment_count, float max_variation,
                                          uint32_t min_size, uint32_t *r_labels,
                                          uint32_t *r_segment_count)
{
    if (!r_segment_count || (count && (!xyz || !labels || !r_labels))) return PNPR_ERR_INVALID_ARGUMENT;
    pnpr_split_options so = {max_variation, min_size};
    size_t nt;
    const pnpr_option_desc *table = pnpr_split_option_table(&nt);
    if (pnpr_option_check(table, nt, &so, NULL) != PNPR_OK) return PNPR_ERR_INVALID_ARGUMENT;
    pnpr_option_fill_defaults(table, nt, &so); /* the zeros: the table's defaults (options.h) */
    max_variation = so.max_variation;
    min_size = so.min_size;
    *r_segment_count = 0;
    if (count >= PNPR_LABEL_NONE) return PNPR_ERR_UNSUPPORTED;
    /* points grouped by region (counting sort), invalid ones left out */
    size_t *start = calloc((size_t)segment_count + 2, sizeof *start);
    uint32_t *ids = malloc((count ? count : 1) * sizeof *ids), *leaf = malloc((count ? count : 1) * sizeof *leaf);
    span *stack = NULL;
    if (!start || !ids || !leaf) { free(start); free(ids); free(leaf); return PNPR_ERR_OUT_OF_MEMORY; }
    for (size_t i = 0; i < count; i++) {
        const float *p = xyz + 3 * i;
        int ok = labels[i] < segment_count && isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
        start[ok ? labels[i] + 1 : segment_count + 1]++;
    }
    for (uint32_t s = 0; s <= segment_count; s++) start[s + 1] += start[s];
    size_t valid = start[segment_count];
    {
        size_t *fill = malloc(((size_t)segment_count + 1) * sizeof *fill);
        if (!fill) { free(start); free(ids); free(leaf); return PNPR_ERR_OUT_OF_MEMORY; }
        memcpy(fill, start, ((size_t)segment_count + 1) * sizeof *fill);
        for (size_t i = 0; i < count; i++) {
            const float *p = xyz + 3 * i;
            if (labels[i] < segment_count && isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]))
                ids[fill[labels[i]]++] = (uint32_t)i;
        }
        free(fill);
    }
    /* split every region; leaf ids are provisional (then renumbered by first appearance) */
    size_t cap = 64, top = 0;
    uint32_t leaves = 0;
    stack = malloc(cap * sizeof *stack);
    pnpr_status st = stack ? PNPR_OK : PNPR_ERR_OUT_OF_MEMORY;
    for (uint32_t s = 0; st == PNPR_OK && s < segment_count; s++) {
        if (start[s + 1] == start[s]) continue;
        stack[top++] = (span){start[s], start[s + 1], 0};
        while (top && st == PNPR_OK) {
            span sp = stack[--top];
            size_t n = sp.end - sp.begin, mid = sp.begin;
            double c[3], axis[3];
            if (sp.depth < PNPR_SPLIT_DEPTH_MAX && n >= 2 * (size_t)min_size &&
                variation_and_axis(xyz, ids, sp.begin, sp.end, c, axis) > max_variation) {
                /* partition by the side of the plane through the centroid */
                size_t lo = sp.begin, hi = sp.end;
                while (lo < hi) {
                    const float *p = xyz + 3 * (size_t)ids[lo];
                    double side = (p[0] - c[0]) * axis[0] + (p[1] - c[1]) * axis[1] + (p[2] - c[2]) * axis[2];
                    if (side < 0) lo++;
                    else { uint32_t t = ids[lo]; ids[lo] = ids[--hi]; ids[hi] = t; }
                }
                mid = lo;
            }
            if (mid - sp.begin >= min_size && sp.end - mid >= min_size) {
                if (top + 2 > cap) {
                    span *ns = realloc(stack, 2 * cap * sizeof *ns);
                    if (!ns) { st = PNPR_ERR_OUT_OF_MEMORY; break; }
                    stack = ns;
                    cap *= 2;
                }
                stack[top++] = (span){mid, sp.end, sp.depth + 1};
                stack[top++] = (span){sp.begin, mid, sp.depth + 1};
            } else {
                for (size_t i = sp.begin; i < sp.end; i++) leaf[ids[i]] = leaves;
                leaves++;
            }
        }
    }
    free(stack);
    if (st == PNPR_OK) {
        /* renumber by first appearance; invalid points: one label after the others */
        uint32_t *map = malloc(((size_t)leaves + 1) * sizeof *map), next = 0;
        if (!map) st = PNPR_ERR_OUT_OF_MEMORY;
        else {
            for (uint32_t l = 0; l < leaves; l++) map[l] = PNPR_LABEL_NONE;
            uint8_t *valid_pt = calloc(count ? count : 1, 1);
            if (!valid_pt) st = PNPR_ERR_OUT_OF_MEMORY;
            else {
                for (size_t q = 0; q < valid; q++) valid_pt[ids[q]] = 1;
                for (size_t i = 0; i < count; i++) {
                    if (!valid_pt[i]) continue;
                    uint32_t l = leaf[i];
                    if (map[l] == PNPR_LABEL_NONE) map[l] = next++;
                    r_labels[i] = map[l];
                }
                int any_invalid = valid < count;
                for (size_t i = 0; i < count; i++) if (!valid_pt[i]) r_labels[i] = next;
                *r_segment_count = next + (any_invalid ? 1 : 0);
                free(valid_pt);
            }
            free(map);
        }
    }
    free(start); free(ids); free(leaf);
    return st;
}
