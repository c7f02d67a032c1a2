/* Chi & Lee's multiscale segmented sphere hierarchy (sec. 3.2, fig. 4; include/pointnpr/hierarchy.h):
 *  - leaves: uniform spheres resampled from the points (sphere_leaves.c);
 *  - regions: 3D JSEG on the leaves (pnpr_segment_jseg with the leaves' mean colours); colourless
 *    clouds: geometric regions by covariance splitting (pnpr_segment_covariance_split), since
 *    JSEG needs colour; or the cloud's own labels (use_labels: the segment stage's output);
 *  - below each region: a covariance splitting tree (Pauly et al.) down to single leaves: split by
 *    the plane through the centroid normal to the direction of greatest variation; a split that
 *    leaves less than an eighth on one side becomes the median split along that direction, so the
 *    depth stays O(log n). The paper also stops on a curvature-variation threshold; we split to the
 *    leaves always, because the stroke traversal needs every scale (docs/hierarchy.md);
 *  - above the regions: the region adjacency graph's merges by e_ij (eq. 4, pnpr_segment_hierarchy),
 *    one node per merge; parts the graph does not connect are joined by colour there.
 * A parent's sphere is the smallest sphere holding its two children's spheres (QSplat's bounding
 * spheres); its colour, curvature, normal and direction are the leaf-count-weighted means of its
 * children's (axial vectors sign-aligned first); its normal cone holds theirs; S (eq. 5) is the sum
 * over its children of the CIE76 colour difference plus the child's S. */
#include "sphere_internal.h"

#include <pointnpr/options.h>

#include "../core/internal.h"
#include "../core/vec3.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static uint32_t new_node(sphere_build *b)
{
    sphere_work *n = &b->nodes[b->count];
    memset(n, 0, sizeof *n);
    n->parent = n->child[0] = n->child[1] = PNPR_INDEX_NONE;
    return (uint32_t)b->count++;
}

static double vdist(const float a[3], const float b[3])
{
    double d[3] = {(double)a[0] - b[0], (double)a[1] - b[1], (double)a[2] - b[2]};
    return sqrt(pnpr_dot3(d, d));
}

/* p's centre: the centroid of its leaves (children weighted by their leaf counts); its radius: the
 * smallest sphere around it holding both children's spheres, grown by a rounding margin. */
static void bound_spheres(const sphere_work *a, const sphere_work *b, double wa, double wb,
                          sphere_work *p)
{
    for (int k = 0; k < 3; k++) p->centre[k] = (float)((wa * a->centre[k] + wb * b->centre[k]) / (wa + wb));
    double r = fmax(vdist(p->centre, a->centre) + a->radius, vdist(p->centre, b->centre) + b->radius);
    p->radius = (float)(r * (1.0 + 1e-6)) + 1e-30f;
}

double pnpr_sphere_colour_distance(const float a[3], const float b[3])
{
    uint8_t ca[3], cb[3];
    for (int k = 0; k < 3; k++) {
        ca[k] = (uint8_t)lrintf(fminf(fmaxf(a[k], 0.0f), 255.0f));
        cb[k] = (uint8_t)lrintf(fminf(fmaxf(b[k], 0.0f), 255.0f));
    }
    float la[3], lb[3];
    pnpr_rgb_to_lab(ca, la);
    pnpr_rgb_to_lab(cb, lb);
    return sqrt((double)(la[0] - lb[0]) * (la[0] - lb[0]) + (double)(la[1] - lb[1]) * (la[1] - lb[1]) +
                (double)(la[2] - lb[2]) * (la[2] - lb[2]));
}

/* Axial mean of two unit vectors weighted wa, wb (b's sign aligned with a's). */
static void axial_mean(const float a[3], const float b[3], double wa, double wb, double r[3])
{
    double s = (double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2] < 0 ? -1.0 : 1.0;
    for (int k = 0; k < 3; k++) r[k] = wa * a[k] + s * wb * b[k];
}

static double folded_angle(const float a[3], const float b[3])
{
    double d = fabs((double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2]);
    return acos(d > 1 ? 1 : d);
}

/* Node p's attributes from its two children. */
static void aggregate(sphere_work *nodes, uint32_t pi)
{
    sphere_work *p = &nodes[pi], *a = &nodes[p->child[0]], *b = &nodes[p->child[1]];
    double wa = a->leaf_end - a->leaf_begin, wb = b->leaf_end - b->leaf_begin, w = wa + wb;
    bound_spheres(a, b, wa, wb, p);
    for (int k = 0; k < 3; k++) p->colour[k] = (float)((wa * a->colour[k] + wb * b->colour[k]) / w);
    p->curvature = (float)((wa * a->curvature + wb * b->curvature) / w);
    double n[3], d[3];
    axial_mean(a->normal, b->normal, wa, wb, n);
    if (pnpr_normalize3(n) < 1e-9) n[0] = n[1] = n[2] = 0;
    for (int k = 0; k < 3; k++) p->normal[k] = (float)n[k];
    double cone = 0;
    for (int i = 0; i < 2; i++) {
        const sphere_work *c = i ? b : a;
        double ang = pnpr_dot3(n, n) > 0 && c->normal[0] * c->normal[0] + c->normal[1] * c->normal[1] + c->normal[2] * c->normal[2] > 0
                         ? folded_angle(p->normal, c->normal) + c->cone
                         : 1.5707963;
        if (ang > cone) cone = ang;
    }
    p->cone = (float)(cone > 1.5707963 ? 1.5707963 : cone);
    axial_mean(a->dir, b->dir, wa, wb, d);
    pnpr_sphere_tangent(p->normal, d, p->dir);
    if (pnpr_dot3(n, n) == 0) memcpy(p->dir, (wa >= wb ? a : b)->dir, sizeof p->dir);
    p->dissimilarity = (float)(pnpr_sphere_colour_distance(p->colour, a->colour) + a->dissimilarity +
                               pnpr_sphere_colour_distance(p->colour, b->colour) + b->dissimilarity);
}

static uint32_t make_parent(sphere_build *b, uint32_t c0, uint32_t c1, uint8_t kind)
{
    uint32_t p = new_node(b);
    sphere_work *n = &b->nodes[p];
    n->child[0] = c0;
    n->child[1] = c1;
    n->kind = kind;
    b->nodes[c0].parent = b->nodes[c1].parent = p;
    /* leaf ranges are final only after the depth-first ordering; counts are right already */
    n->leaf_begin = 0;
    n->leaf_end = (b->nodes[c0].leaf_end - b->nodes[c0].leaf_begin) + (b->nodes[c1].leaf_end - b->nodes[c1].leaf_begin);
    aggregate(b->nodes, p);
    return p;
}

typedef struct proj_item { float t; uint32_t leaf; } proj_item;

static int cmp_proj(const void *a, const void *b)
{
    const proj_item *x = a, *y = b;
    int by_t = (x->t > y->t) - (x->t < y->t);
    return by_t ? by_t : (x->leaf > y->leaf) - (x->leaf < y->leaf);
}

/* Splits leaves[0..n) into [0, m) and [m, n) (covariance splitting); returns m. */
static size_t split_leaves(const sphere_build *b, uint32_t *leaves, size_t n, proj_item *tmp)
{
    double m[3] = {0, 0, 0}, cov[3][3] = {{0}};
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) m[k] += b->nodes[leaves[i]].centre[k];
    for (int k = 0; k < 3; k++) m[k] /= (double)n;
    for (size_t i = 0; i < n; i++) {
        double d[3];
        for (int k = 0; k < 3; k++) d[k] = b->nodes[leaves[i]].centre[k] - m[k];
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++) cov[r][c] += d[r] * d[c];
    }
    double w[3], v[3][3];
    pnpr_eigen_sym3(cov, w, v);
    size_t below = 0;
    for (size_t i = 0; i < n; i++) {
        const float *c = b->nodes[leaves[i]].centre;
        tmp[i].t = (float)((c[0] - m[0]) * v[2][0] + (c[1] - m[1]) * v[2][1] + (c[2] - m[2]) * v[2][2]);
        tmp[i].leaf = leaves[i];
        below += tmp[i].t < 0;
    }
    size_t lo = n / 8 ? n / 8 : 1;
    qsort(tmp, n, sizeof *tmp, cmp_proj);
    for (size_t i = 0; i < n; i++) leaves[i] = tmp[i].leaf;
    return below < lo ? lo : below > n - lo ? n - lo : below;
}

/* The covariance splitting tree over leaves[0..n) (n >= 1); returns its top node. */
static uint32_t split_tree(sphere_build *b, uint32_t *leaves, size_t n, proj_item *tmp)
{
    if (n == 1) return leaves[0];
    size_t m = split_leaves(b, leaves, n, tmp);
    uint32_t a = split_tree(b, leaves, m, tmp), c = split_tree(b, leaves + m, n - m, tmp);
    return make_parent(b, a, c, PNPR_SPHERE_STROKE);
}

/* The region tops: covariance trees of every region (leaves grouped by label). */
static pnpr_status region_trees(sphere_build *b, const uint32_t *label, uint32_t S, uint32_t *r_top)
{
    size_t L = b->leaves;
    uint32_t *start = calloc((size_t)S + 1, sizeof *start), *order = malloc(L * sizeof *order);
    proj_item *tmp = malloc(L * sizeof *tmp);
    if (!start || !order || !tmp) { free(start); free(order); free(tmp); return PNPR_ERR_OUT_OF_MEMORY; }
    for (size_t l = 0; l < L; l++) {
        start[label[l] + 1]++;
        b->nodes[l].region = label[l];
    }
    for (uint32_t s = 0; s < S; s++) start[s + 1] += start[s];
    uint32_t *fill = r_top; /* borrowed as cursors, then overwritten with the tops */
    for (uint32_t s = 0; s < S; s++) fill[s] = start[s];
    for (size_t l = 0; l < L; l++) order[fill[label[l]]++] = (uint32_t)l;
    for (uint32_t s = 0; s < S; s++) {
        size_t n = start[s + 1] - start[s], first = b->count;
        r_top[s] = n ? split_tree(b, order + start[s], n, tmp) : PNPR_INDEX_NONE;
        for (size_t i = first; i < b->count; i++) b->nodes[i].region = s;
        if (n) {
            b->nodes[r_top[s]].kind = b->nodes[r_top[s]].kind == PNPR_SPHERE_LEAF ? PNPR_SPHERE_LEAF : PNPR_SPHERE_REGION;
            b->nodes[r_top[s]].region = s;
        }
    }
    free(start); free(order); free(tmp);
    return PNPR_OK;
}

/* The merge nodes over the region tops; returns the root. */
static uint32_t merge_nodes(sphere_build *b, uint32_t *top, uint32_t S, const pnpr_segment_merge *mg, uint32_t nm)
{
    float level = 0;
    for (uint32_t i = 0; i < nm; i++) {
        uint32_t p = make_parent(b, top[mg[i].a], top[mg[i].b], PNPR_SPHERE_REGION);
        level = level > mg[i].level ? level : mg[i].level;
        b->nodes[p].level = level;
        b->nodes[p].region = S + i;
        top[S + i] = p;
    }
    /* what the graph left apart (empty regions, parts not joined): chained at the top level */
    uint32_t root = PNPR_INDEX_NONE, id = S + nm;
    for (uint32_t s = 0; s < S + nm; s++) {
        uint32_t t = top[s];
        if (t == PNPR_INDEX_NONE || b->nodes[t].parent != PNPR_INDEX_NONE) continue;
        if (root == PNPR_INDEX_NONE) { root = t; continue; }
        root = make_parent(b, root, t, PNPR_SPHERE_REGION);
        b->nodes[root].level = level;
        b->nodes[root].region = id++;
    }
    return root;
}

enum { EXTENT_EXACT_MAX = 4096 };

/* Every node's extent: exact over its leaves up to EXTENT_EXACT_MAX of them (the stroke nodes),
 * from its children's above (nodes near the root, drawn only at very coarse settings). */
static void extents(sphere_work *nodes, size_t count, const uint32_t *leaves)
{
    for (size_t i = 0; i < count; i++) {
        sphere_work *n = &nodes[i];
        if (n->child[0] == PNPR_INDEX_NONE) { n->extent = n->radius; continue; }
        double e = 0;
        if (n->leaf_end - n->leaf_begin <= EXTENT_EXACT_MAX) {
            for (uint32_t l = n->leaf_begin; l < n->leaf_end; l++) {
                const sphere_work *f = &nodes[leaves[l]];
                e = fmax(e, vdist(n->centre, f->centre) + f->radius);
            }
        } else {
            for (int c = 0; c < 2; c++) e = fmax(e, vdist(n->centre, nodes[n->child[c]].centre) + nodes[n->child[c]].extent);
        }
        n->extent = (float)fmin(e, (double)n->radius);
    }
}

/* Depth-first leaf order: every node's leaves become one range of tree->leaves. */
static pnpr_status order_leaves(const sphere_build *b, uint32_t root, uint32_t *leaves, uint32_t *r_rank)
{
    uint32_t *stack = malloc(b->count * sizeof *stack);
    if (!stack) return PNPR_ERR_OUT_OF_MEMORY;
    size_t top = 0;
    uint32_t next = 0;
    stack[top++] = root;
    while (top) {
        uint32_t i = stack[--top];
        sphere_work *n = &b->nodes[i];
        if (n->child[0] == PNPR_INDEX_NONE) {
            r_rank[i] = next;
            leaves[next++] = i;
            continue;
        }
        stack[top++] = n->child[1];
        stack[top++] = n->child[0];
    }
    free(stack);
    /* ranges bottom-up: children are created before their parents */
    for (size_t i = 0; i < b->count; i++) {
        sphere_work *n = &b->nodes[i];
        if (n->child[0] == PNPR_INDEX_NONE) {
            n->leaf_begin = i < b->leaves ? r_rank[i] : 0;
            n->leaf_end = n->leaf_begin + 1;
        } else {
            n->leaf_begin = b->nodes[n->child[0]].leaf_begin;
            n->leaf_end = b->nodes[n->child[1]].leaf_end;
        }
    }
    return PNPR_OK;
}

/* The leaves' regions into label (b->leaves entries); *r_S. rgb: the leaves' colours as bytes. */
static pnpr_status leaf_regions(const pnpr_cloud *c, const sphere_build *b, const uint32_t *seed, const float *lxyz,
                                const uint8_t *rgb, const pnpr_sphere_tree_options *o, uint32_t *label, uint32_t *r_S)
{
    size_t L = b->leaves;
    if (o->use_labels && c->label) {
        for (size_t l = 0; l < L; l++) label[l] = c->label[seed[l]];
        return pnpr_segment_compact(label, L, r_S);
    }
    if (!c->rgb) {
        memset(label, 0, L * sizeof *label);
        return pnpr_segment_covariance_split(lxyz, L, label, 1, o->max_variation, 0, label, r_S);
    }
    pnpr_jseg_options jo = o->jseg;
    jo.threads = o->threads;
    jo.progress = o->progress;
    pnpr_segment_info info;
    pnpr_status st = pnpr_segment_jseg(lxyz, rgb, L, &jo, label, &info);
    *r_S = st == PNPR_OK ? info.segment_count : 0;
    return st;
}

/* The region adjacency graph's merges over the leaves' regions (r_merges: S entries). */
static pnpr_status region_merges(const sphere_build *b, const uint32_t *knn, size_t k, const uint8_t *rgb,
                                 const uint32_t *label, uint32_t S, const pnpr_sphere_tree_options *o,
                                 pnpr_segment_merge *r_merges, uint32_t *r_nm)
{
    pnpr_region_graph g = {knn, k, k};
    pnpr_hierarchy_options ho = o->merge;
    ho.progress = o->progress;
    return pnpr_segment_hierarchy(rgb, b->leaves, &g, label, S, &ho, r_merges, r_nm);
}

/* Leaf pairs adjacent across regions (leaf-order indices). */
static pnpr_status border_pairs(pnpr_sphere_tree *t, const uint32_t *knn, size_t k, const uint32_t *label,
                                const uint32_t *rank)
{
    size_t n = 0, L = t->leaf_count;
    for (int pass = 0; pass < 2; pass++) {
        n = 0;
        for (size_t i = 0; i < L; i++)
            for (size_t j = 1; j < k; j++) {
                uint32_t q = knn[i * k + j];
                if (q == PNPR_INDEX_NONE || q <= i || label[q] == label[i]) continue;
                if (pass) {
                    t->border[2 * n] = rank[i];
                    t->border[2 * n + 1] = rank[q];
                }
                n++;
            }
        if (!pass && !(t->border = malloc((n ? 2 * n : 1) * sizeof *t->border))) return PNPR_ERR_OUT_OF_MEMORY;
    }
    t->border_count = n;
    return PNPR_OK;
}

static pnpr_status check_options(const pnpr_sphere_tree_options *opts, pnpr_sphere_tree_options *o, pnpr_error *err)
{
    *o = opts ? *opts : (pnpr_sphere_tree_options){0};
    size_t n;
    const pnpr_option_desc *t = pnpr_sphere_tree_option_table(&n);
    pnpr_status st = pnpr_option_check(t, n, o, err);
    if (st == PNPR_OK) pnpr_option_fill_defaults(t, n, o);
    return st;
}

/* The leaf spacing: the option, or leaf_factor x the median point spacing (1 when all coincide). */
static pnpr_status leaf_spacing(const pnpr_cloud *c, const pnpr_sphere_tree_options *o, float *r)
{
    if (o->spacing > 0) { *r = o->spacing; return PNPR_OK; }
    pnpr_kdtree *tree = NULL;
    pnpr_status st = pnpr_kdtree_build_threads(c->xyz, c->count, 0, o->threads, &tree);
    if (st != PNPR_OK) return st;
    float m = pnpr_kdtree_median_spacing(tree, 0);
    pnpr_kdtree_free(tree);
    *r = m > 0 && isfinite(m) ? m * o->leaf_factor : 1.0f;
    return PNPR_OK;
}

/* Leaves: seeds, nodes, the point assignment, their kNN rows (k per leaf) and shapes. */
static pnpr_status build_leaves(const pnpr_cloud *c, const pnpr_sphere_tree_options *o, sphere_build *b,
                                uint32_t *seed, float **r_lxyz, uint32_t **r_knn)
{
    pnpr_status st = pnpr_sphere_pick_leaves(c->xyz, c->count, b->spacing, seed, &b->leaves);
    if (st != PNPR_OK) return st;
    size_t L = b->leaves;
    b->cap = 2 * L + 1;
    b->nodes = malloc(b->cap * sizeof *b->nodes);
    float *lxyz = malloc((L ? 3 * L : 1) * sizeof *lxyz);
    uint32_t *knn = malloc((L ? L : 1) * o->k * sizeof *knn);
    *r_lxyz = lxyz;
    *r_knn = knn;
    if (!b->nodes || !lxyz || !knn) return PNPR_ERR_OUT_OF_MEMORY;
    for (size_t l = 0; l < L; l++) {
        sphere_work *n = &b->nodes[new_node(b)];
        memcpy(n->centre, c->xyz + 3 * (size_t)seed[l], sizeof n->centre);
        memcpy(lxyz + 3 * l, n->centre, sizeof n->centre);
        n->radius = 0.5f * b->spacing;
        n->leaf_end = 1;
    }
    pnpr_kdtree *lt = NULL;
    pnpr_knn_options ko = {o->threads, o->progress, 0};
    if ((st = pnpr_kdtree_build_threads(lxyz, L, 0, o->threads, &lt)) == PNPR_OK &&
        (st = pnpr_sphere_assign(c, lt, b, o->threads, &o->progress)) == PNPR_OK &&
        (st = pnpr_knn_self(lt, L, o->k, &ko, knn, NULL)) == PNPR_OK)
        st = pnpr_sphere_leaf_shape(b, knn, o->k, o->feature_fraction, o->threads, &o->progress);
    pnpr_kdtree_free(lt);
    return st;
}

/* Everything above the leaves, then the tree's arrays. */
static pnpr_status build_above(const pnpr_cloud *c, const pnpr_sphere_tree_options *o, sphere_build *b,
                               const uint32_t *seed, const float *lxyz, const uint32_t *knn, pnpr_sphere_tree *t)
{
    size_t L = b->leaves;
    uint32_t S = 0, nm = 0;
    uint32_t *label = malloc(L * sizeof *label), *rank = malloc(L * sizeof *rank);
    uint8_t *rgb = malloc(3 * L); /* the leaves' colours as bytes: JSEG's and the merges' input */
    pnpr_segment_merge *mg = NULL;
    uint32_t *top = NULL;
    if (rgb)
        for (size_t i = 0; i < 3 * L; i++) rgb[i] = (uint8_t)lrintf(b->nodes[i / 3].colour[i % 3]);
    pnpr_status st = !label || !rank || !rgb ? PNPR_ERR_OUT_OF_MEMORY : leaf_regions(c, b, seed, lxyz, rgb, o, label, &S);
    if (st == PNPR_OK && !(mg = malloc(((size_t)S + 1) * sizeof *mg))) st = PNPR_ERR_OUT_OF_MEMORY;
    if (st == PNPR_OK && !(top = malloc((2 * (size_t)S + 1) * sizeof *top))) st = PNPR_ERR_OUT_OF_MEMORY;
    if (st == PNPR_OK) st = region_merges(b, knn, o->k, rgb, label, S, o, mg, &nm);
    if (st == PNPR_OK) st = region_trees(b, label, S, top);
    if (st == PNPR_OK && !pnpr_progress_report(&o->progress, "tree", 0.5)) {
        t->merge_first = (uint32_t)b->count;
        t->root = merge_nodes(b, top, S, mg, nm);
        t->region_count = S;
        t->leaf_count = L;
        if (!(t->leaves = malloc(L * sizeof *t->leaves))) st = PNPR_ERR_OUT_OF_MEMORY;
        if (st == PNPR_OK) st = order_leaves(b, t->root, t->leaves, rank);
        if (st == PNPR_OK) extents(b->nodes, b->count, t->leaves);
        if (st == PNPR_OK) st = border_pairs(t, knn, o->k, label, rank);
    } else if (st == PNPR_OK) {
        st = PNPR_ERR_CANCELLED;
    }
    for (size_t i = 0; st == PNPR_OK && i < c->count; i++)
        if (b->point_leaf[i] != PNPR_INDEX_NONE) b->point_leaf[i] = rank[b->point_leaf[i]];
    free(label); free(rank); free(rgb); free(mg); free(top);
    return st;
}

float pnpr_sphere_noise(const pnpr_sphere_tree *t, const pnpr_sphere_node *n)
{
    double f = 1.0 / (10.0 * (t->spacing > 0 ? t->spacing : 1.0f));
    return pnpr_perlin3(n->centre[0] * f, n->centre[1] * f, n->centre[2] * f);
}

static int16_t pack_unit(float x)
{
    float v = x * PNPR_SPHERE_UNIT;
    if (!(v == v)) return 0; /* NaN: unknown, as zero */
    return (int16_t)lrintf(v > PNPR_SPHERE_UNIT ? PNPR_SPHERE_UNIT : v < -PNPR_SPHERE_UNIT ? -PNPR_SPHERE_UNIT : v);
}

/* x in [0, top] as a fraction in 1/65535 of top, rounded (up: never below x) */
static uint16_t pack_fraction(double x, double top, int up)
{
    double v = x / top * 65535.0;
    v = up ? ceil(v) : floor(v + 0.5);
    return (uint16_t)(v > 65535 ? 65535 : v >= 0 ? v : 0); /* NaN: 0 */
}

/* w packed into r. r may lie over w's own bytes or earlier nodes' (in place, first to last). */
static void pack_node(const sphere_work *w, pnpr_sphere_node *r)
{
    sphere_work c = *w;
    pnpr_sphere_node p;
    memcpy(p.centre, c.centre, sizeof p.centre);
    p.radius = c.radius;
    p.extent = c.extent;
    p.dissimilarity = c.dissimilarity;
    for (int k = 0; k < 3; k++) {
        p.normal[k] = pack_unit(c.normal[k]);
        p.dir[k] = pack_unit(c.dir[k]);
        p.colour[k] = (uint8_t)lrintf(fminf(fmaxf(c.colour[k], 0.0f), 255.0f));
    }
    p.cone = pack_fraction(c.cone, 1.5707963267948966, 1);
    p.curvature = pack_fraction(c.curvature, 1.0, 0);
    p.kind = c.kind;
    p.parent = c.parent;
    p.child[0] = c.child[0];
    p.child[1] = c.child[1];
    p.leaf_begin = c.leaf_begin;
    p.region = c.region;
    memcpy(r, &p, sizeof p);
}

/* The built nodes packed in place (a packed node is smaller: node i's bytes lie over work nodes
 * 0 .. i only, read already), the merges' levels kept beside them. */
_Static_assert(sizeof(pnpr_sphere_node) == 64 && sizeof(pnpr_sphere_node) <= sizeof(sphere_work), "the packed node");

static pnpr_status pack_tree(sphere_build *b, pnpr_sphere_tree *t)
{
    size_t merges = b->count > t->merge_first ? b->count - t->merge_first : 0;
    if (!(t->merge_level = malloc((merges ? merges : 1) * sizeof *t->merge_level))) return PNPR_ERR_OUT_OF_MEMORY;
    for (size_t m = 0; m < merges; m++) t->merge_level[m] = b->nodes[t->merge_first + m].level;
    pnpr_sphere_node *packed = (pnpr_sphere_node *)(void *)b->nodes;
    for (size_t i = 0; i < b->count; i++) pack_node(&b->nodes[i], &packed[i]);
    void *shrunk = realloc(b->nodes, (b->count ? b->count : 1) * sizeof *packed);
    t->nodes = shrunk ? shrunk : packed; /* a failed shrink keeps the larger block */
    b->nodes = NULL;
    t->node_count = b->count;
    return PNPR_OK;
}

/* a packed unit vector as floats, unit length again (0 stays 0) */
static void unpack_unit(const int16_t v[3], float r[3])
{
    double d[3] = {v[0], v[1], v[2]};
    pnpr_normalize3(d);
    for (int k = 0; k < 3; k++) r[k] = (float)d[k];
}

void pnpr_sphere_normal(const pnpr_sphere_node *n, float r[3])
{
    unpack_unit(n->normal, r);
}

void pnpr_sphere_dir(const pnpr_sphere_node *n, float r[3])
{
    unpack_unit(n->dir, r);
}

void pnpr_sphere_colour(const pnpr_sphere_node *n, float r[3])
{
    for (int k = 0; k < 3; k++) r[k] = n->colour[k];
}

float pnpr_sphere_cone(const pnpr_sphere_node *n)
{
    return (float)(n->cone * (1.5707963267948966 / 65535.0));
}

float pnpr_sphere_curvature(const pnpr_sphere_node *n)
{
    return n->curvature / 65535.0f;
}

uint32_t pnpr_sphere_leaf_end(const pnpr_sphere_tree *t, uint32_t i)
{
    if (!t || i >= t->node_count) return 0;
    for (size_t depth = 0; t->nodes[i].child[1] != PNPR_INDEX_NONE && depth < t->node_count; depth++) i = t->nodes[i].child[1];
    return t->nodes[i].leaf_begin + 1;
}

pnpr_status pnpr_sphere_tree_build(const pnpr_cloud *cloud, const pnpr_sphere_tree_options *opts,
                                   pnpr_sphere_tree *r_tree, pnpr_sphere_tree_stats *r_stats, pnpr_error *err)
{
    double t0 = pnpr_now();
    if (r_stats) memset(r_stats, 0, sizeof *r_stats);
    if (!r_tree) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "hierarchy: no tree to fill");
    memset(r_tree, 0, sizeof *r_tree);
    r_tree->root = PNPR_INDEX_NONE;
    if (!cloud || (cloud->count && !cloud->xyz))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "hierarchy: no cloud or no coordinates");
    if (cloud->count >= 0x7FFFFFFFu)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "hierarchy: too many points (%zu)", cloud->count);
    pnpr_sphere_tree_options o;
    pnpr_status st = check_options(opts, &o, err);
    if (st != PNPR_OK) return st;
    sphere_build b = {0};
    memcpy(r_tree->origin, cloud->origin, sizeof r_tree->origin);
    r_tree->has_rgb = cloud->rgb != NULL;
    uint32_t *seed = malloc((cloud->count ? cloud->count : 1) * sizeof *seed), *knn = NULL;
    float *lxyz = NULL;
    b.point_leaf = malloc((cloud->count ? cloud->count : 1) * sizeof *b.point_leaf);
    if (!seed || !b.point_leaf) st = PNPR_ERR_OUT_OF_MEMORY;
    if (st == PNPR_OK) st = leaf_spacing(cloud, &o, &b.spacing);
    if (st == PNPR_OK) st = build_leaves(cloud, &o, &b, seed, &lxyz, &knn);
    r_tree->spacing = b.spacing;
    if (st == PNPR_OK && b.leaves) st = build_above(cloud, &o, &b, seed, lxyz, knn, r_tree);
    if (st == PNPR_OK && b.leaves == 0)
        for (size_t i = 0; i < cloud->count; i++) b.point_leaf[i] = PNPR_INDEX_NONE;
    free(seed); free(lxyz); free(knn);
    r_tree->point_leaf = b.point_leaf;
    r_tree->point_count = cloud->count;
    if (st == PNPR_OK) st = pack_tree(&b, r_tree);
    free(b.nodes); /* only after a failure: the packed nodes are the tree's */
    if (st != PNPR_OK) {
        pnpr_sphere_tree_free(r_tree);
        r_tree->root = PNPR_INDEX_NONE;
        if (err && !err->message[0]) pnpr_error_set(err, st, "hierarchy: %s", pnpr_status_string(st));
        return st;
    }
    pnpr_progress_report(&o.progress, "tree", 1.0);
    if (r_stats) {
        r_stats->leaves = r_tree->leaf_count;
        r_stats->nodes = r_tree->node_count;
        r_stats->regions = r_tree->region_count;
        r_stats->border_pairs = r_tree->border_count;
        r_stats->seconds = pnpr_now() - t0;
    }
    return PNPR_OK;
}

void pnpr_sphere_tree_free(pnpr_sphere_tree *t)
{
    if (!t) return;
    free(t->nodes); free(t->leaves); free(t->point_leaf); free(t->border); free(t->merge_level);
    memset(t, 0, sizeof *t);
    t->root = PNPR_INDEX_NONE;
}

/* ---- Perlin's gradient noise -------------------------------------------------------------- */

static uint32_t lattice_hash(int64_t x, int64_t y, int64_t z)
{
    uint64_t h = (uint64_t)x * 0x8DA6B343u ^ (uint64_t)y * 0xD8163841u ^ (uint64_t)z * 0xCB1AB31Fu;
    h ^= h >> 31; h *= 0x7FB5D329728EA185ull; h ^= h >> 27;
    return (uint32_t)h;
}

static double grad(uint32_t h, double x, double y, double z)
{
    /* the 12 edge directions of a cube (Perlin 2002), by the hash's low bits */
    switch (h % 12u) {
    case 0: return x + y;   case 1: return -x + y;  case 2: return x - y;   case 3: return -x - y;
    case 4: return x + z;   case 5: return -x + z;  case 6: return x - z;   case 7: return -x - z;
    case 8: return y + z;   case 9: return -y + z;  case 10: return y - z;  default: return -y - z;
    }
}

static double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }

float pnpr_perlin3(double x, double y, double z)
{
    if (!isfinite(x) || !isfinite(y) || !isfinite(z) || fabs(x) > 1e15 || fabs(y) > 1e15 || fabs(z) > 1e15) return 0.0f;
    double fx = floor(x), fy = floor(y), fz = floor(z);
    int64_t ix = (int64_t)fx, iy = (int64_t)fy, iz = (int64_t)fz;
    double p[3] = {x - fx, y - fy, z - fz}, u = fade(p[0]), v = fade(p[1]), w = fade(p[2]);
    double c[2][2][2];
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++)
            for (int d = 0; d < 2; d++)
                c[a][b][d] = grad(lattice_hash(ix + a, iy + b, iz + d), p[0] - a, p[1] - b, p[2] - d);
    double x00 = c[0][0][0] + u * (c[1][0][0] - c[0][0][0]), x10 = c[0][1][0] + u * (c[1][1][0] - c[0][1][0]);
    double x01 = c[0][0][1] + u * (c[1][0][1] - c[0][0][1]), x11 = c[0][1][1] + u * (c[1][1][1] - c[0][1][1]);
    double y0 = x00 + v * (x10 - x00), y1 = x01 + v * (x11 - x01);
    double r = y0 + w * (y1 - y0);
    return (float)(r < -1 ? -1 : r > 1 ? 1 : r);
}
