/* Chi & Lee's sphere hierarchy without GL (include/pointnpr/hierarchy.h), known answers: the tree's
 * invariants (children inside their parents' spheres, every point in exactly one leaf and inside
 * it, leaf ranges, eq. 5 at every node, normal cones), the packed nodes, the region levels equal to the region
 * adjacency graph's cut at each level, degenerate clouds; the traversal: screen-space density
 * kept within 20% when the camera distance doubles, the smooth transition's continuity against
 * plain level switching, silhouettes on a sphere's outline, region borders on a colour border,
 * the abstraction and importance controls, view-independent strokes, truncation, bad input. */
#include "testutil.h"

#include <pointnpr/hierarchy.h>
#include <pointnpr/options.h>

#include "../filters/sphere_internal.h" /* pnpr_sphere_noise, pnpr_perlin3 */

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- scenes and cameras ----------------------------------------------------------------------- */

/* A unit sphere, red above z = 0 and blue below. */
static void two_colour_sphere(pnpr_cloud *c, size_t n)
{
    CHECK_STATUS(pnpr_test_sphere(c, n, 1.0, NULL, 7), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(c), PNPR_OK);
    for (size_t i = 0; i < c->count; i++) {
        int up = c->xyz[3 * i + 2] > 0;
        c->rgb[3 * i] = up ? 200 : 30;
        c->rgb[3 * i + 1] = 40;
        c->rgb[3 * i + 2] = up ? 30 : 200;
    }
}

typedef struct cam { float view[16], proj[16]; pnpr_hier_view v; } cam;

/* Looking down -z from (0, 0, dist) at the origin, vertical fov 40 degrees, w x h pixels. */
static void camera_at(cam *k, double dist, int w, int h)
{
    memset(k, 0, sizeof *k);
    k->view[0] = k->view[5] = k->view[10] = k->view[15] = 1;
    k->view[14] = (float)-dist;
    double f = 1.0 / tan(20.0 * 3.14159265358979 / 180.0), nearp = 0.01, farp = 100;
    k->proj[0] = (float)(f * h / w);
    k->proj[5] = (float)f;
    k->proj[10] = (float)((farp + nearp) / (nearp - farp));
    k->proj[11] = -1;
    k->proj[14] = (float)(2 * farp * nearp / (nearp - farp));
    k->v = (pnpr_hier_view){k->view, k->proj, w, h, (float)(f * h / 2), 0, NULL};
}

static double dist3(const float *a, const float *b)
{
    double d[3] = {(double)a[0] - b[0], (double)a[1] - b[1], (double)a[2] - b[2]};
    return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/* ---- the tree --------------------------------------------------------------------------------- */

static void check_invariants(const pnpr_sphere_tree *t, const pnpr_cloud *c)
{
    size_t bad_extent = 0, bad_inside = 0, bad_range = 0, bad_s = 0, bad_cone = 0, leaves = 0;
    for (size_t i = 0; i < t->node_count; i++) {
        const pnpr_sphere_node *n = &t->nodes[i];
        uint32_t end = pnpr_sphere_leaf_end(t, (uint32_t)i);
        bad_extent += !(n->extent <= n->radius);
        for (uint32_t l = n->leaf_begin; l < end && l < t->leaf_count; l++) {
            const pnpr_sphere_node *f = &t->nodes[t->leaves[l]];
            bad_extent += dist3(n->centre, f->centre) + f->radius > n->extent * (1 + 1e-5) + 1e-6 && end - n->leaf_begin <= 4096;
        }
        if (n->child[0] == PNPR_INDEX_NONE) {
            leaves++;
            bad_s += n->dissimilarity != 0;
            continue;
        }
        double s = 0;
        for (int k = 0; k < 2; k++) {
            const pnpr_sphere_node *ch = &t->nodes[n->child[k]];
            CHECK(ch->parent == i);
            bad_inside += dist3(n->centre, ch->centre) + ch->radius > n->radius * (1 + 1e-5) + 1e-6;
            s += ch->dissimilarity;
            float pn[3], cn[3];
            pnpr_sphere_normal(n, pn);
            pnpr_sphere_normal(ch, cn);
            double nn = (double)pn[0] * cn[0] + (double)pn[1] * cn[1] + (double)pn[2] * cn[2];
            if (cn[0] != 0 || cn[1] != 0 || cn[2] != 0) /* 16-bit normals: 1e-4 radians */
                bad_cone += acos(fmin(1.0, fabs(nn))) > pnpr_sphere_cone(n) + 1e-3;
        }
        bad_s += !(n->dissimilarity >= s - 1e-3 * (1 + s)); /* S includes the children's S */
        bad_range += n->leaf_begin != t->nodes[n->child[0]].leaf_begin ||
                     pnpr_sphere_leaf_end(t, n->child[0]) != t->nodes[n->child[1]].leaf_begin ||
                     end != pnpr_sphere_leaf_end(t, n->child[1]) || end <= n->leaf_begin;
    }
    CHECK_MSG(bad_extent == 0, "%zu extents miss a leaf", bad_extent);
    CHECK_MSG(bad_inside == 0, "%zu children stick out of their parents", bad_inside);
    CHECK_MSG(bad_range == 0, "%zu leaf ranges are not the children's", bad_range);
    CHECK_MSG(bad_s == 0, "%zu nodes break eq. 5", bad_s);
    CHECK_MSG(bad_cone == 0, "%zu normal cones miss a child", bad_cone);
    CHECK(leaves == t->leaf_count);
    CHECK(t->nodes[t->root].leaf_begin == 0 && pnpr_sphere_leaf_end(t, t->root) == t->leaf_count);
    CHECK(pnpr_sphere_leaf_end(t, (uint32_t)t->node_count) == 0 && pnpr_sphere_leaf_end(NULL, 0) == 0);
    CHECK(t->node_count == 2 * t->leaf_count - 1);
    /* leaves: a permutation of the leaf nodes, each holding its rank */
    size_t bad_leaf = 0, bad_point = 0;
    for (size_t l = 0; l < t->leaf_count; l++) {
        const pnpr_sphere_node *n = &t->nodes[t->leaves[l]];
        bad_leaf += n->child[0] != PNPR_INDEX_NONE || n->leaf_begin != l || pnpr_sphere_leaf_end(t, t->leaves[l]) != l + 1;
    }
    /* every point in exactly one leaf (point_leaf is a function) and inside its sphere */
    for (size_t i = 0; i < c->count; i++) {
        uint32_t l = t->point_leaf[i];
        if (l == PNPR_INDEX_NONE || l >= t->leaf_count) { bad_point++; continue; }
        const pnpr_sphere_node *n = &t->nodes[t->leaves[l]];
        bad_point += dist3(n->centre, c->xyz + 3 * i) > n->radius * (1 + 1e-5) || dist3(n->centre, c->xyz + 3 * i) > t->spacing * 1.0001;
    }
    CHECK_MSG(bad_leaf == 0, "%zu bad leaves", bad_leaf);
    CHECK_MSG(bad_point == 0, "%zu points outside their leaf", bad_point);
}

/* The region of each leaf at merge level th, from the tree: its highest ancestor within its region
 * (the covariance nodes below merge_first) or among the merges of level <= th (levels never
 * decrease upwards). */
static void tree_cut(const pnpr_sphere_tree *t, float th, uint32_t *r_labels)
{
    for (size_t l = 0; l < t->leaf_count; l++) {
        uint32_t i = t->leaves[l];
        for (uint32_t p = t->nodes[i].parent; p != PNPR_INDEX_NONE; p = t->nodes[p].parent) {
            if (p >= t->merge_first && t->merge_level[p - t->merge_first] > th) break;
            i = p;
        }
        r_labels[l] = i;
    }
}

/* Region levels equal the RAG cut: JSEG + the hierarchy run here on the tree's leaves (the same
 * calls the build makes, on the same inputs) and cut with pnpr_segment_hierarchy_cut. */
static void test_region_levels(void)
{
    pnpr_cloud c = {0};
    pnpr_test_rng rng = {11};
    CHECK_STATUS(pnpr_test_plane(&c, 120, 120, 0.01, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(&c), PNPR_OK);
    for (size_t i = 0; i < c.count; i++) { /* four colour blocks plus noise */
        int q = (c.xyz[3 * i] > 0.0f) + 2 * (c.xyz[3 * i + 1] > 0.0f);
        for (int k = 0; k < 3; k++)
            c.rgb[3 * i + k] = (uint8_t)(40 + 50 * ((q + k) % 4) + (int)(pnpr_test_uniform(&rng) * 10));
    }
    pnpr_sphere_tree t;
    pnpr_sphere_tree_options o = {0};
    o.k = 12;
    CHECK_STATUS(pnpr_sphere_tree_build(&c, &o, &t, NULL, NULL), PNPR_OK);
    check_invariants(&t, &c);
    CHECK_MSG(t.region_count >= 4, "%u regions", t.region_count);
    /* the leaves' own segmentation, independently */
    size_t L = t.leaf_count;
    float *xyz = malloc(3 * L * sizeof *xyz);
    uint8_t *rgb = malloc(3 * L);
    uint32_t *seg = malloc(L * sizeof *seg), *cut = malloc(L * sizeof *cut), *mine = malloc(L * sizeof *mine);
    for (size_t l = 0; l < L; l++) {
        const pnpr_sphere_node *n = &t.nodes[t.leaves[l]];
        memcpy(xyz + 3 * l, n->centre, 3 * sizeof(float));
        memcpy(rgb + 3 * l, n->colour, 3);
        seg[l] = n->region;
    }
    /* the tree's regions are a partition consistent with its leaves' segment ids */
    pnpr_segment_merge *mg = malloc(t.region_count * sizeof *mg);
    uint32_t nm = 0, S = t.region_count, nseg;
    pnpr_kdtree *kt = NULL;
    CHECK_STATUS(pnpr_kdtree_build(xyz, L, 0, &kt), PNPR_OK);
    uint32_t *knn = malloc(L * 12 * sizeof *knn);
    CHECK_STATUS(pnpr_knn_self(kt, L, 12, NULL, knn, NULL), PNPR_OK);
    pnpr_region_graph g = {knn, 12, 12};
    CHECK_STATUS(pnpr_segment_hierarchy(rgb, L, &g, seg, S, NULL, mg, &nm), PNPR_OK);
    CHECK(nm == S - 1);
    size_t checked = 0;
    for (uint32_t m = 0; m < nm; m += (nm > 8 ? nm / 8 : 1)) {
        float th = mg[m].level;
        CHECK_STATUS(pnpr_segment_hierarchy_cut(seg, L, S, mg, nm, 0, th, cut, &nseg), PNPR_OK);
        tree_cut(&t, th, mine);
        pnpr_segment_score sc;
        CHECK_STATUS(pnpr_segment_score_labels(cut, mine, L, &sc), PNPR_OK);
        CHECK_MSG(sc.ari > 0.999999 && sc.result_segments == nseg, "level %g: ARI %g, %u vs %u regions", th, sc.ari,
                  sc.result_segments, nseg);
        checked++;
    }
    CHECK(checked >= 1);
    pnpr_kdtree_free(kt);
    free(knn); free(mg); free(xyz); free(rgb); free(seg); free(cut); free(mine);
    pnpr_sphere_tree_free(&t);
    pnpr_cloud_free(&c);
}

static void test_sphere_tree(void)
{
    pnpr_cloud c = {0};
    two_colour_sphere(&c, 20000);
    pnpr_sphere_tree t;
    pnpr_sphere_tree_stats st;
    CHECK_STATUS(pnpr_sphere_tree_build(&c, NULL, &t, &st, NULL), PNPR_OK);
    check_invariants(&t, &c);
    /* uniform resampling at 1.5 median spacings keeps about 1 / 1.5^2 of a surface's points */
    CHECK_MSG(t.leaf_count > c.count / 4 && t.leaf_count < c.count * 3 / 4, "%zu leaves of %zu", t.leaf_count, c.count);
    CHECK(st.leaves == t.leaf_count && st.regions == t.region_count && st.nodes == t.node_count);
    CHECK(t.region_count >= 2 && t.border_count > 0);
    /* borders lie on the equator */
    size_t off = 0;
    for (size_t i = 0; i < t.border_count; i++) {
        const pnpr_sphere_node *a = &t.nodes[t.leaves[t.border[2 * i]]];
        off += fabs(a->centre[2]) > 4 * t.spacing;
    }
    CHECK_MSG(off * 10 < t.border_count, "%zu of %zu border leaves off the equator", off, t.border_count);
    /* normals of a sphere: radial */
    size_t bad_n = 0;
    for (size_t l = 0; l < t.leaf_count; l++) {
        const pnpr_sphere_node *n = &t.nodes[t.leaves[l]];
        double r = sqrt(n->centre[0] * n->centre[0] + n->centre[1] * n->centre[1] + n->centre[2] * n->centre[2]);
        float nn[3], nd[3];
        pnpr_sphere_normal(n, nn);
        pnpr_sphere_dir(n, nd);
        double d = fabs(nn[0] * n->centre[0] + nn[1] * n->centre[1] + nn[2] * n->centre[2]) / r;
        bad_n += d < 0.95;
        /* directions: unit and tangent (16-bit: within 1e-4) */
        double dd = nd[0] * nd[0] + nd[1] * nd[1] + nd[2] * nd[2];
        double dn = nd[0] * nn[0] + nd[1] * nn[1] + nd[2] * nn[2];
        bad_n += fabs(dd - 1) > 1e-3 || fabs(dn) > 1e-3;
    }
    CHECK_MSG(bad_n < t.leaf_count / 100, "%zu leaves with a bad normal or direction", bad_n);
    /* the root's colour is the mean; the two halves' colours differ: S(root) > 0 */
    CHECK(t.nodes[t.root].dissimilarity > 0);
    pnpr_sphere_tree_free(&t);
    CHECK(t.nodes == NULL && t.root == PNPR_INDEX_NONE);
    pnpr_cloud_free(&c);
}

/* The packed nodes (64 bytes) against known answers: a flat plane of one colour, z = 0. Its
 * normals are (0, 0, +-1) exactly, its cones and curvatures 0, every colour the plane's bytes; the
 * float readers give unit vectors; a leaf's noise is the Perlin noise at its centre. */
static void test_packed(void)
{
    CHECK(sizeof(pnpr_sphere_node) == 64);
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_test_plane(&c, 80, 80, 0.01, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(&c), PNPR_OK);
    for (size_t i = 0; i < c.count; i++) {
        c.rgb[3 * i] = 10;
        c.rgb[3 * i + 1] = 201;
        c.rgb[3 * i + 2] = 99;
    }
    pnpr_sphere_tree t;
    CHECK_STATUS(pnpr_sphere_tree_build(&c, NULL, &t, NULL, NULL), PNPR_OK);
    size_t bad_normal = 0, bad_colour = 0, bad_flat = 0, bad_unit = 0;
    for (size_t i = 0; i < t.node_count; i++) {
        const pnpr_sphere_node *n = &t.nodes[i];
        bad_normal += n->normal[0] != 0 || n->normal[1] != 0 || abs(n->normal[2]) != PNPR_SPHERE_UNIT;
        bad_colour += n->colour[0] != 10 || n->colour[1] != 201 || n->colour[2] != 99;
        bad_flat += n->cone > 1 || n->curvature > 1 || pnpr_sphere_cone(n) > 1e-4f || pnpr_sphere_curvature(n) > 1e-4f;
        float nf[3], df[3], col[3];
        pnpr_sphere_normal(n, nf);
        pnpr_sphere_dir(n, df);
        pnpr_sphere_colour(n, col);
        bad_unit += fabsf(nf[2]) != 1.0f || fabs(sqrt((double)df[0] * df[0] + (double)df[1] * df[1] + (double)df[2] * df[2]) - 1) > 1e-6 ||
                    fabsf(df[2]) > 1e-4f || col[1] != 201.0f;
    }
    CHECK_MSG(bad_normal == 0 && bad_colour == 0 && bad_flat == 0 && bad_unit == 0,
              "packed: %zu normals, %zu colours, %zu cones or curvatures, %zu read back wrong", bad_normal, bad_colour,
              bad_flat, bad_unit);
    /* the noise is a function of the centre alone, in -1..1, and not constant over the plane */
    const pnpr_sphere_node *a = &t.nodes[t.leaves[0]], *b = &t.nodes[t.leaves[t.leaf_count - 1]];
    double f = 1.0 / (10.0 * t.spacing);
    CHECK(pnpr_sphere_noise(&t, a) == pnpr_perlin3(a->centre[0] * f, a->centre[1] * f, a->centre[2] * f));
    CHECK(pnpr_sphere_noise(&t, a) != pnpr_sphere_noise(&t, b) && fabsf(pnpr_sphere_noise(&t, b)) <= 1.0f);
    pnpr_sphere_tree_free(&t);
    CHECK(t.merge_level == NULL);
    pnpr_cloud_free(&c);
}

static void test_degenerate(void)
{
    pnpr_cloud c = {0};
    pnpr_sphere_tree t;
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_sphere_tree_build(&c, NULL, &t, NULL, NULL), PNPR_OK); /* empty */
    CHECK(t.root == PNPR_INDEX_NONE && t.leaf_count == 0);
    cam k;
    camera_at(&k, 3, 64, 64);
    pnpr_hier_counts cnt;
    CHECK_STATUS(pnpr_sphere_tree_traverse(&t, &k.v, NULL, NULL, 0, &cnt), PNPR_OK);
    CHECK(cnt.strokes[PNPR_HIER_PAINT] == 0);
    pnpr_sphere_tree_free(&t);
    /* one point, then 100 duplicates of it plus NaNs: one leaf; NaN points in no leaf */
    CHECK_STATUS(pnpr_cloud_alloc(&c, 103), PNPR_OK);
    for (size_t i = 0; i < 103; i++) {
        c.xyz[3 * i] = 0.5f; c.xyz[3 * i + 1] = -0.25f; c.xyz[3 * i + 2] = 1.0f;
    }
    c.xyz[3 * 101] = NAN;
    c.xyz[3 * 102 + 1] = INFINITY;
    CHECK_STATUS(pnpr_sphere_tree_build(&c, NULL, &t, NULL, NULL), PNPR_OK);
    CHECK(t.leaf_count == 1 && t.root == t.leaves[0] && t.node_count == 1);
    CHECK(t.point_leaf[0] == 0 && t.point_leaf[100] == 0 && t.point_leaf[101] == PNPR_INDEX_NONE &&
          t.point_leaf[102] == PNPR_INDEX_NONE);
    k.view[14] = -3; /* the point at z = 1 is 2 in front */
    CHECK_STATUS(pnpr_sphere_tree_traverse(&t, &k.v, NULL, NULL, 0, &cnt), PNPR_OK);
    CHECK(cnt.strokes[PNPR_HIER_PAINT] + cnt.strokes[PNPR_HIER_SILHOUETTE] == 1);
    pnpr_sphere_tree_free(&t);
    /* georeferenced: origin 1e7, small offsets: the tree keeps the origin, works in offsets */
    pnpr_cloud_free(&c);
    double off[3] = {5e6, 1e7, 300};
    CHECK_STATUS(pnpr_test_plane(&c, 60, 60, 0.05, off), PNPR_OK);
    CHECK_STATUS(pnpr_sphere_tree_build(&c, NULL, &t, NULL, NULL), PNPR_OK);
    check_invariants(&t, &c);
    CHECK(t.origin[1] == c.origin[1] && !t.has_rgb);
    pnpr_sphere_tree_free(&t);
    /* options out of range: refused with a message */
    pnpr_sphere_tree_options o = {0};
    o.k = 1000;
    CHECK_STATUS(pnpr_sphere_tree_build(&c, &o, &t, NULL, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "k") != NULL);
    CHECK(t.nodes == NULL && t.root == PNPR_INDEX_NONE);
    o.k = 0;
    o.leaf_factor = 1000;
    CHECK_STATUS(pnpr_sphere_tree_build(&c, &o, &t, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_sphere_tree_build(NULL, NULL, &t, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_sphere_tree_build(&c, NULL, NULL, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    pnpr_cloud_free(&c);
}

/* ---- the traversal ---------------------------------------------------------------------------- */

static size_t run(const pnpr_sphere_tree *t, const cam *k, const pnpr_hier_params *p, pnpr_hier_stroke **buf,
                  pnpr_hier_counts *cnt)
{
    CHECK_STATUS(pnpr_sphere_tree_traverse(t, &k->v, p, NULL, 0, cnt), PNPR_OK);
    size_t n = cnt->strokes[0] + cnt->strokes[1] + cnt->strokes[2];
    *buf = realloc(*buf, (n ? n : 1) * sizeof **buf);
    CHECK_STATUS(pnpr_sphere_tree_traverse(t, &k->v, p, *buf, n, cnt), PNPR_OK);
    CHECK(!cnt->truncated);
    return n;
}

/* A colourless n x n plane of spacing h (centred on the origin) and its tree. */
static void plane_scene(pnpr_cloud *c, pnpr_sphere_tree *t, size_t n, double h)
{
    CHECK_STATUS(pnpr_test_plane(c, n, n, h, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_sphere_tree_build(c, NULL, t, NULL, NULL), PNPR_OK);
}

/* Strokes per projected pixel of a plane seen from d and 2d: the view-dependent rule keeps it. */
static void test_density(void)
{
    pnpr_cloud c = {0};
    pnpr_sphere_tree t;
    plane_scene(&c, &t, 200, 0.005);
    pnpr_hier_stroke *buf = NULL;
    pnpr_hier_counts cnt;
    double dens[2];
    for (int i = 0; i < 2; i++) {
        double d = 2.5 * (1 + i);
        cam k;
        camera_at(&k, d, 640, 480);
        k.view[12] = k.view[13] = -0.5f; /* the plane's centre on the axis */
        run(&t, &k, NULL, &buf, &cnt);
        double side = 1.0 * k.v.pixels_per_unit / d;
        dens[i] = cnt.weighted / (side * side);
        CHECK(cnt.strokes[PNPR_HIER_SILHOUETTE] == 0); /* a plane facing the camera */
    }
    CHECK_MSG(fabs(dens[1] / dens[0] - 1) <= 0.2, "density %g vs %g strokes/px^2", dens[0], dens[1]);
    free(buf);
    pnpr_sphere_tree_free(&t);
    pnpr_cloud_free(&c);
}

/* Strokes of frame b that were not in frame a: alpha >= 0.25 and no stroke of a within 1.5 px
 * with a radius within 25%. */
static size_t popped(const pnpr_hier_stroke *a, size_t na, const pnpr_hier_stroke *b, size_t nb, double px_per_unit)
{
    size_t n = 0;
    for (size_t i = 0; i < nb; i++) {
        if (b[i].rgba[3] < 64) continue;
        double rb = sqrt(b[i].v[0] * b[i].v[0] + b[i].v[1] * b[i].v[1] + b[i].v[2] * b[i].v[2]);
        int found = 0;
        for (size_t j = 0; j < na && !found; j++) {
            double ra = sqrt(a[j].v[0] * a[j].v[0] + a[j].v[1] * a[j].v[1] + a[j].v[2] * a[j].v[2]);
            found = dist3(a[j].pos, b[i].pos) * px_per_unit <= 1.5 && fabs(ra - rb) <= 0.25 * rb;
        }
        n += !found;
    }
    return n;
}

/* A slow zoom: the smooth transition makes at most half the pops of plain level switching (in
 * practice none: a split parent's children start where it was, the one that is not G invisible). */
static void test_smooth_transition(void)
{
    pnpr_cloud c = {0};
    pnpr_sphere_tree t;
    plane_scene(&c, &t, 100, 0.01);
    size_t pops[2] = {0, 0};
    for (int plain = 0; plain < 2; plain++) {
        pnpr_hier_params p = {0};
        p.no_smooth = plain;
        p.stroke_px = 40;
        pnpr_hier_stroke *prev = NULL, *cur = NULL;
        size_t nprev = 0;
        for (int f = 0; f < 40; f++) {
            double d = 3.0 * pow(0.5, f / 39.0); /* 3 -> 1.5 */
            cam k;
            camera_at(&k, d, 320, 240);
            k.view[12] = k.view[13] = -0.5f;
            pnpr_hier_counts cnt;
            size_t n = run(&t, &k, &p, &cur, &cnt);
            if (f > 0) pops[plain] += popped(prev, nprev, cur, n, k.v.pixels_per_unit / d);
            pnpr_hier_stroke *sw = prev; prev = cur; cur = sw;
            nprev = n;
        }
        free(prev); free(cur);
    }
    CHECK_MSG(pops[1] > 50 && pops[0] * 2 <= pops[1], "pops: smooth %zu, plain %zu", pops[0], pops[1]);
    pnpr_sphere_tree_free(&t);
    pnpr_cloud_free(&c);
}

/* The two-colour sphere, its tree, a camera 4 radii away. */
static void sphere_scene(pnpr_cloud *c, pnpr_sphere_tree *t, cam *k)
{
    two_colour_sphere(c, 20000);
    CHECK_STATUS(pnpr_sphere_tree_build(c, NULL, t, NULL, NULL), PNPR_OK);
    camera_at(k, 4, 400, 400);
}

/* Silhouette strokes of a sphere seen from 4 radii: on its outline all around. */
static void test_silhouettes(void)
{
    pnpr_cloud c = {0};
    pnpr_sphere_tree t;
    cam k;
    sphere_scene(&c, &t, &k);
    pnpr_hier_stroke *buf = NULL;
    pnpr_hier_counts cnt;
    size_t n = run(&t, &k, NULL, &buf, &cnt);
    size_t ns = cnt.strokes[PNPR_HIER_SILHOUETTE], np = cnt.strokes[PNPR_HIER_PAINT], on = 0;
    double outline = k.v.pixels_per_unit * 1.0 / sqrt(16.0 - 1.0);
    int bins[36] = {0};
    for (size_t i = np; i < np + ns; i++) {
        const float *p = buf[i].pos;
        double z = 4.0 - p[2], x = p[0] * k.v.pixels_per_unit / z, y = p[1] * k.v.pixels_per_unit / z;
        double r = sqrt(x * x + y * y);
        on += r >= 0.9 * outline && r <= 1.03 * outline;
        bins[(int)((atan2(y, x) + 3.14159265) / (2 * 3.14159266) * 36) % 36]++;
        /* the paint map's silhouettes: the node's colour darkened to 0.3 (at most 0.3 x 255), about
         * 85% opaque, 2.5 px wide */
        CHECK(buf[i].rgba[0] <= 77 && buf[i].rgba[1] <= 77 && buf[i].rgba[2] <= 77 &&
              buf[i].rgba[3] <= 217);
        double wv = sqrt(buf[i].v[0] * buf[i].v[0] + buf[i].v[1] * buf[i].v[1] + buf[i].v[2] * buf[i].v[2]);
        CHECK_NEAR(wv * k.v.pixels_per_unit / z, 1.25, 0.01); /* half of 2.5 px */
    }
    CHECK_MSG(ns > 30 && on * 10 >= ns * 9, "%zu of %zu silhouette strokes on the outline (%g px)", on, ns, outline);
    int empty = 0;
    for (int b = 0; b < 36; b++) empty += bins[b] == 0;
    CHECK_MSG(empty == 0, "%d of 36 directions without a silhouette", empty);
    /* none without the band */
    pnpr_hier_params p = {0};
    p.silhouette_deg = -1;
    run(&t, &k, &p, &buf, &cnt);
    CHECK(cnt.strokes[PNPR_HIER_SILHOUETTE] == 0 && cnt.strokes[PNPR_HIER_PAINT] >= np);
    (void)n;
    free(buf);
    pnpr_sphere_tree_free(&t);
    pnpr_cloud_free(&c);
}

/* Borders on the colour border, none when off or when every region is merged; the abstraction
 * and importance controls; view-independent strokes; truncation; bad input. */
static void test_controls(void)
{
    pnpr_cloud c = {0};
    pnpr_sphere_tree t;
    cam k;
    sphere_scene(&c, &t, &k);
    pnpr_hier_stroke *buf = NULL;
    pnpr_hier_counts cnt;
    pnpr_hier_params p = {0};
    p.border_level = 1e-6f;
    size_t n = run(&t, &k, &p, &buf, &cnt), nb = cnt.strokes[PNPR_HIER_BORDER], off = 0;
    for (size_t i = n - nb; i < n; i++) off += fabs(buf[i].pos[2]) > 4 * t.spacing;
    CHECK_MSG(nb > 20 && off * 10 < nb, "%zu border strokes, %zu off the equator", nb, off);
    p.border_level = 1e9f;
    run(&t, &k, &p, &buf, &cnt);
    CHECK(cnt.strokes[PNPR_HIER_BORDER] == 0);
    /* abstraction: 1 keeps the root only; negative makes every leaf a region node */
    p = (pnpr_hier_params){0};
    p.abstraction = 1;
    run(&t, &k, &p, &buf, &cnt);
    CHECK(cnt.region_nodes == 1);
    p.abstraction = -1;
    run(&t, &k, &p, &buf, &cnt);
    CHECK_MSG(cnt.region_nodes == t.leaf_count, "%zu region nodes, %zu leaves", cnt.region_nodes, t.leaf_count);
    /* importance: white everywhere = no abstraction where colours differ (S > 0); black = none */
    uint8_t *map = malloc(64 * 64);
    memset(map, 255, 64 * 64);
    p = (pnpr_hier_params){0};
    p.abstraction = 1;
    p.importance = map;
    p.importance_w = p.importance_h = 64;
    run(&t, &k, &p, &buf, &cnt);
    size_t white = cnt.region_nodes;
    p.importance = NULL;
    p.abstraction = 1e-30f;
    run(&t, &k, &p, &buf, &cnt);
    CHECK_MSG(white == cnt.region_nodes && white > 1, "white map: %zu region nodes, no abstraction: %zu", white,
              cnt.region_nodes);
    memset(map, 0, 64 * 64);
    p.importance = map;
    p.abstraction = 1;
    run(&t, &k, &p, &buf, &cnt);
    CHECK(cnt.region_nodes == 1);
    free(map);
    /* view-independent: the same strokes from 3 and 6 */
    p = (pnpr_hier_params){0};
    p.stroke_radius = 4 * t.spacing;
    size_t counts[2];
    for (int i = 0; i < 2; i++) {
        camera_at(&k, 3.0 * (1 + i), 400, 400);
        run(&t, &k, &p, &buf, &cnt);
        counts[i] = cnt.strokes[PNPR_HIER_PAINT] + cnt.strokes[PNPR_HIER_SILHOUETTE];
    }
    CHECK_MSG(counts[0] == counts[1] && counts[0] > 100, "%zu vs %zu", counts[0], counts[1]);
    /* truncation keeps the counts and fills the buffer */
    camera_at(&k, 4, 400, 400);
    n = run(&t, &k, NULL, &buf, &cnt);
    pnpr_hier_counts small;
    CHECK_STATUS(pnpr_sphere_tree_traverse(&t, &k.v, NULL, buf, n / 2, &small), PNPR_OK);
    CHECK(small.truncated && small.strokes[0] == cnt.strokes[0] && small.strokes[1] == cnt.strokes[1]);
    /* bad input */
    p = (pnpr_hier_params){0};
    p.stroke_px = 1000;
    CHECK_STATUS(pnpr_sphere_tree_traverse(&t, &k.v, &p, NULL, 0, &cnt), PNPR_ERR_INVALID_ARGUMENT);
    p.stroke_px = 0;
    p.importance = (const uint8_t *)"x";
    CHECK_STATUS(pnpr_sphere_tree_traverse(&t, &k.v, &p, NULL, 0, &cnt), PNPR_ERR_INVALID_ARGUMENT);
    pnpr_hier_view v = k.v;
    v.pixels_per_unit = NAN;
    CHECK_STATUS(pnpr_sphere_tree_traverse(&t, &v, NULL, NULL, 0, &cnt), PNPR_ERR_INVALID_ARGUMENT);
    v = k.v;
    v.width = 0;
    CHECK_STATUS(pnpr_sphere_tree_traverse(&t, &v, NULL, NULL, 0, &cnt), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_sphere_tree_traverse(&t, NULL, NULL, NULL, 0, &cnt), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_sphere_tree_traverse(&t, &k.v, NULL, NULL, 5, &cnt), PNPR_ERR_INVALID_ARGUMENT);
    free(buf);
    pnpr_sphere_tree_free(&t);
    pnpr_cloud_free(&c);
}

int main(void)
{
    test_sphere_tree();
    test_region_levels();
    test_packed();
    test_degenerate();
    test_density();
    test_smooth_transition();
    test_silhouettes();
    test_controls();
    return pnpr_test_finish("test_hierarchy");
}
