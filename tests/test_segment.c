/* Segmentation: generated scenes of touching coloured primitives with known object labels,
 * scored by the adjusted Rand index (ARI) and over/under-segmentation counts; every source
 * (jseg, hierarchy, components, rgbgrow, labels) and defined results for degenerate input. */
#include "testutil.h"

#include <pointnpr/segment.h>
#include <pointnpr/knn.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- scene generator ------------------------------------------------------------------------ */

typedef struct scene {
    size_t n, cap;
    float *xyz;
    uint8_t *rgb;
    uint32_t *truth;
} scene;

static void scene_add(scene *s, double x, double y, double z, const int col[3], uint32_t obj,
                      double pos_sigma, double col_sigma, pnpr_test_rng *rng)
{
    if (s->n == s->cap) {
        s->cap = s->cap ? 2 * s->cap : 4096;
        s->xyz = realloc(s->xyz, 3 * s->cap * sizeof *s->xyz);
        s->rgb = realloc(s->rgb, 3 * s->cap);
        s->truth = realloc(s->truth, s->cap * sizeof *s->truth);
        if (!s->xyz || !s->rgb || !s->truth) abort();
    }
    s->xyz[3 * s->n] = (float)(x + pos_sigma * pnpr_test_normal(rng));
    s->xyz[3 * s->n + 1] = (float)(y + pos_sigma * pnpr_test_normal(rng));
    s->xyz[3 * s->n + 2] = (float)(z + pos_sigma * pnpr_test_normal(rng));
    for (int c = 0; c < 3; c++) {
        double v = col[c] + col_sigma * pnpr_test_normal(rng);
        s->rgb[3 * s->n + c] = (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v + 0.5);
    }
    s->truth[s->n] = obj;
    s->n++;
}

static void scene_free(scene *s) { free(s->xyz); free(s->rgb); free(s->truth); memset(s, 0, sizeof *s); }

/* Grey ground plane; red cube standing on it; blue sphere resting on the plane and touching the
 * cube; green cylinder touching the cube's other side. Spacing h; 4 objects, labels 0..3. */
static void make_scene(scene *s, double h, double pos_sigma, double col_sigma, uint64_t seed)
{
    static const int grey[3] = {140, 140, 140}, red[3] = {200, 40, 40}, blue[3] = {40, 60, 200},
                     green[3] = {40, 170, 60};
    pnpr_test_rng rng = {seed};
    memset(s, 0, sizeof *s);
    const double PI = 3.14159265358979323846;
    /* plane [-1,1]^2 at z = 0, minus the cube's footprint */
    for (double x = -1; x <= 1 + 1e-9; x += h)
        for (double y = -1; y <= 1 + 1e-9; y += h) {
            if (x > -0.5 && x < 0.1 && y > -0.3 && y < 0.3) continue;
            scene_add(s, x, y, 0, grey, 0, pos_sigma, col_sigma, &rng);
        }
    /* cube [-0.5,0.1] x [-0.3,0.3] x [0,0.6]: four sides and the top */
    int m = (int)(0.6 / h + 0.5);
    for (int i = 0; i <= m; i++)
        for (int j = 0; j <= m; j++) {
            double u = -0.5 + 0.6 * i / m, v = 0.6 * j / m, w = -0.3 + 0.6 * i / m;
            if (j > 0) {
                scene_add(s, u, -0.3, v, red, 1, pos_sigma, col_sigma, &rng);
                scene_add(s, u, 0.3, v, red, 1, pos_sigma, col_sigma, &rng);
                if (i > 0 && i < m) {
                    scene_add(s, -0.5, w, v, red, 1, pos_sigma, col_sigma, &rng);
                    scene_add(s, 0.1, w, v, red, 1, pos_sigma, col_sigma, &rng);
                }
            }
            if (i > 0 && i < m && j > 0 && j < m)
                scene_add(s, u, -0.3 + 0.6 * j / m, 0.6, red, 1, pos_sigma, col_sigma, &rng);
        }
    /* sphere r 0.35 at (0.45 + h, 0, 0.35): Fibonacci points */
    double r = 0.35;
    size_t ns = (size_t)(4 * PI * r * r / (h * h));
    for (size_t i = 0; i < ns; i++) {
        double z = 1 - 2 * (i + 0.5) / ns, rr = sqrt(1 - z * z), phi = i * PI * (3 - sqrt(5.0));
        scene_add(s, 0.45 + h + r * rr * cos(phi), r * rr * sin(phi), 0.35 + r * z, blue, 2, pos_sigma, col_sigma, &rng);
    }
    /* cylinder r 0.2, height 0.8 at (-0.2, 0.5 + h): side and top */
    double cr = 0.2;
    int nr = (int)(2 * PI * cr / h), nz = (int)(0.8 / h);
    for (int a = 0; a < nr; a++)
        for (int b = 1; b <= nz; b++) {
            double t = 2 * PI * a / nr;
            scene_add(s, -0.2 + cr * cos(t), 0.5 + h + cr * sin(t), 0.8 * b / nz, green, 3, pos_sigma, col_sigma, &rng);
        }
    for (double x = -cr; x <= cr; x += h)
        for (double y = -cr; y <= cr; y += h)
            if (x * x + y * y < (cr - h / 2) * (cr - h / 2))
                scene_add(s, -0.2 + x, 0.5 + h + y, 0.8, green, 3, pos_sigma, col_sigma, &rng);
}

static pnpr_segment_score score(const scene *s, const uint32_t *labels)
{
    pnpr_segment_score sc;
    CHECK_STATUS(pnpr_segment_score_labels(s->truth, labels, s->n, &sc), PNPR_OK);
    return sc;
}

static void check_labels_range(const uint32_t *labels, size_t n, uint32_t S)
{
    size_t bad = 0;
    uint8_t *seen = calloc(S ? S : 1, 1);
    for (size_t i = 0; i < n; i++) {
        if (labels[i] >= S) bad++;
        else seen[labels[i]] = 1;
    }
    size_t unused = 0;
    for (uint32_t l = 0; l < S; l++) unused += !seen[l];
    CHECK_MSG(bad == 0 && unused == 0, "%zu labels out of 0..%u, %zu labels unused", bad, S ? S - 1 : 0, unused);
    free(seen);
}

/* ---- tests ---------------------------------------------------------------------------------- */

static void test_score(void)
{
    uint32_t a[6] = {0, 0, 1, 1, 2, 2}, b[6] = {5, 5, 7, 7, 9, 9}, c[6] = {0, 0, 0, 0, 0, 0};
    pnpr_segment_score sc;
    CHECK_STATUS(pnpr_segment_score_labels(a, b, 6, &sc), PNPR_OK);
    CHECK_NEAR(sc.ari, 1.0, 1e-12);
    CHECK(sc.over_segmented == 0 && sc.under_segmented == 0);
    CHECK_STATUS(pnpr_segment_score_labels(a, c, 6, &sc), PNPR_OK);
    CHECK_NEAR(sc.ari, 0.0, 1e-12);
    CHECK(sc.under_segmented == 1);
    CHECK_STATUS(pnpr_segment_score_labels(c, a, 6, &sc), PNPR_OK);
    CHECK(sc.over_segmented == 1);
    CHECK_STATUS(pnpr_segment_score_labels(c, c, 6, &sc), PNPR_OK);
    CHECK_NEAR(sc.ari, 1.0, 1e-12);
    CHECK_STATUS(pnpr_segment_score_labels(a, a, 1, &sc), PNPR_OK);
    CHECK_NEAR(sc.ari, 1.0, 1e-12);
    /* a known value: {0,0,0,1,1,1} vs {0,0,1,1,2,2}: ARI = (1 - 6*3/15) / (4 - 6*3/15) / ... */
    uint32_t x[6] = {0, 0, 0, 1, 1, 1}, y[6] = {0, 0, 1, 1, 2, 2};
    CHECK_STATUS(pnpr_segment_score_labels(x, y, 6, &sc), PNPR_OK);
    /* sum_ij = 2, sum_a = 6, sum_b = 3, total 15: expected 1.2, max 4.5 -> 0.8 / 3.3 */
    CHECK_NEAR(sc.ari, 0.8 / 3.3, 1e-12);
}

static void test_values_and_compact(void)
{
    float v[7] = {3.5f, 1.0f, NAN, 3.5f, -2.0f, 1.0f, NAN};
    uint32_t l[7], s = 0;
    CHECK_STATUS(pnpr_segment_from_values(PNPR_TYPE_FLOAT32, v, 7, l, &s), PNPR_OK);
    CHECK(s == 4);
    CHECK(l[0] == 2 && l[1] == 1 && l[2] == 3 && l[3] == 2 && l[4] == 0 && l[5] == 1 && l[6] == 3);
    uint32_t c[5] = {70, 3, 70, 9, 3};
    CHECK_STATUS(pnpr_segment_compact(c, 5, &s), PNPR_OK);
    CHECK(s == 3 && c[0] == 0 && c[1] == 1 && c[2] == 0 && c[3] == 2 && c[4] == 1);
    uint8_t rgb[9] = {10, 20, 30, 30, 40, 50, 200, 0, 0};
    uint32_t lab[3] = {0, 0, 1}, sizes[2];
    float mean[6];
    CHECK_STATUS(pnpr_segment_mean_colors(rgb, lab, 3, 2, mean, sizes), PNPR_OK);
    CHECK(sizes[0] == 2 && sizes[1] == 1);
    CHECK_NEAR(mean[0], 20, 1e-5); CHECK_NEAR(mean[2], 40, 1e-5); CHECK_NEAR(mean[3], 200, 1e-5);
    float labc[3];
    pnpr_rgb_to_lab((const uint8_t[3]){255, 255, 255}, labc);
    CHECK_NEAR(labc[0], 100, 0.01); CHECK_NEAR(labc[1], 0, 0.01); CHECK_NEAR(labc[2], 0, 0.01);
}

static void test_jseg_scene(void)
{
    scene s;
    make_scene(&s, 0.02, 0.001, 4, 11);
    uint32_t *labels = malloc(s.n * sizeof *labels);
    pnpr_segment_info info;
    CHECK_STATUS(pnpr_segment_jseg(s.xyz, s.rgb, s.n, NULL, labels, &info), PNPR_OK);
    check_labels_range(labels, s.n, info.segment_count);
    pnpr_segment_score sc = score(&s, labels);
    printf("jseg clean scene (%zu points): ARI %.4f, %u segments (truth %u), over %u, under %u, "
           "classes %u, mean J %.3f, seeds %u, grown %u, %.3f s\n",
           s.n, sc.ari, sc.result_segments, sc.truth_segments, sc.over_segmented, sc.under_segmented,
           info.classes, info.mean_j, info.seed_regions, info.grown_regions, info.seconds);
    CHECK_MSG(sc.ari >= 0.9, "clean scene ARI %.4f", sc.ari);
    CHECK(info.invalid_segment == PNPR_LABEL_NONE && info.valid_points == s.n);

    /* the hierarchy over these regions, cut at the true object count and by threshold */
    uint32_t S = info.segment_count;
    pnpr_segment_merge *merges = malloc((S > 1 ? S - 1 : 1) * sizeof *merges);
    size_t k = 10;
    uint32_t *knn = malloc(s.n * k * sizeof *knn), *cut = malloc(s.n * sizeof *cut);
    pnpr_kdtree *tree = NULL;
    CHECK_STATUS(pnpr_kdtree_build(s.xyz, s.n, 0, &tree), PNPR_OK);
    CHECK_STATUS(pnpr_knn_self(tree, s.n, k, NULL, knn, NULL), PNPR_OK);
    pnpr_kdtree_free(tree);
    pnpr_region_graph graph = {knn, k, k};
    uint32_t nm = 0, cs = 0;
    CHECK_STATUS(pnpr_segment_hierarchy(s.rgb, s.n, &graph, labels, S, NULL, merges, &nm), PNPR_OK);
    CHECK(nm == S - 1);
    for (uint32_t i = 1; i < nm; i++) CHECK(merges[i].level >= merges[i - 1].level);
    CHECK(nm == 0 || merges[nm - 1].size == s.n);
    CHECK_STATUS(pnpr_segment_hierarchy_cut(labels, s.n, S, merges, nm, 4, 0, cut, &cs), PNPR_OK);
    CHECK(cs == 4);
    check_labels_range(cut, s.n, cs);
    sc = score(&s, cut);
    printf("jseg clean scene, hierarchy cut at 4 segments: ARI %.4f, over %u, under %u\n", sc.ari, sc.over_segmented, sc.under_segmented);
    CHECK_MSG(sc.ari >= 0.9, "hierarchy cut ARI %.4f", sc.ari);
    CHECK_STATUS(pnpr_segment_hierarchy_cut(labels, s.n, S, merges, nm, 1, 0, cut, &cs), PNPR_OK);
    CHECK(cs == 1);
    CHECK_STATUS(pnpr_segment_hierarchy_cut(labels, s.n, S, merges, nm, 0, 1e-6f, cut, &cs), PNPR_OK);
    CHECK(cs >= 1 && cs <= S);
    CHECK_STATUS(pnpr_segment_hierarchy_cut(labels, s.n, S, merges, nm, 0, 10.0f, cut, &cs), PNPR_OK);
    CHECK(cs == 1);
    /* rgbgrow on the same scene */
    CHECK_STATUS(pnpr_segment_rgbgrow(s.xyz, s.rgb, s.n, NULL, cut, &info), PNPR_OK);
    check_labels_range(cut, s.n, info.segment_count);
    sc = score(&s, cut);
    printf("rgbgrow clean scene: ARI %.4f, %u segments, over %u, under %u, %.3f s\n", sc.ari, sc.result_segments,
           sc.over_segmented, sc.under_segmented, info.seconds);
    CHECK_MSG(sc.ari >= 0.9, "rgbgrow clean ARI %.4f", sc.ari);
    /* determinism: one thread and many give the same labels */
    pnpr_jseg_options jo = {0};
    jo.threads = 1;
    CHECK_STATUS(pnpr_segment_jseg(s.xyz, s.rgb, s.n, &jo, cut, &info), PNPR_OK);
    CHECK(memcmp(cut, labels, s.n * sizeof *cut) == 0);
    free(merges); free(knn); free(cut);
    scene_free(&s);
    free(labels);

    /* noisy scene: stronger position and colour noise */
    make_scene(&s, 0.02, 0.004, 20, 12);
    labels = malloc(s.n * sizeof *labels);
    CHECK_STATUS(pnpr_segment_jseg(s.xyz, s.rgb, s.n, NULL, labels, &info), PNPR_OK);
    sc = score(&s, labels);
    printf("jseg noisy scene (%zu points): ARI %.4f, %u segments, over %u, under %u, classes %u, %.3f s\n",
           s.n, sc.ari, sc.result_segments, sc.over_segmented, sc.under_segmented, info.classes, info.seconds);
    CHECK_MSG(sc.ari >= 0.7, "noisy scene ARI %.4f", sc.ari);
    CHECK_STATUS(pnpr_segment_rgbgrow(s.xyz, s.rgb, s.n, NULL, labels, &info), PNPR_OK);
    sc = score(&s, labels);
    printf("rgbgrow noisy scene: ARI %.4f, %u segments, over %u, under %u, %.3f s\n", sc.ari, sc.result_segments,
           sc.over_segmented, sc.under_segmented, info.seconds);
    scene_free(&s);
    free(labels);
}

static int cancel_now(void *user, const char *stage, double fraction)
{
    (void)user; (void)stage; (void)fraction;
    return 1;
}

static void test_components(void)
{
    /* three spheres 1 apart plus two far outliers */
    pnpr_cloud c = {0};
    scene s = {0};
    pnpr_test_rng rng = {5};
    static const int col[3] = {100, 100, 100};
    for (uint32_t b = 0; b < 3; b++) {
        CHECK_STATUS(pnpr_test_sphere(&c, 800, 0.3, (double[3]){b * 1.0, 0, 0}, 7 + b), PNPR_OK);
        for (size_t i = 0; i < c.count; i++)
            scene_add(&s, c.xyz[3 * i] + c.origin[0], c.xyz[3 * i + 1] + c.origin[1], c.xyz[3 * i + 2] + c.origin[2], col, b, 0, 0, &rng);
    }
    pnpr_cloud_free(&c);
    scene_add(&s, 5, 5, 5, col, 2, 0, 0, &rng); /* truth: its nearest sphere */
    scene_add(&s, -5, 5, 5, col, 0, 0, 0, &rng);
    uint32_t *labels = malloc(s.n * sizeof *labels);
    pnpr_segment_info info;
    pnpr_components_options co = {0};
    CHECK_STATUS(pnpr_segment_components(s.xyz, s.n, &co, labels, &info), PNPR_OK);
    CHECK_MSG(info.segment_count >= 5, "automatic distance: %u segments", info.segment_count);
    co.distance = 0.15f;
    CHECK_STATUS(pnpr_segment_components(s.xyz, s.n, &co, labels, &info), PNPR_OK);
    CHECK_MSG(info.segment_count == 5, "components: %u segments, expected 5", info.segment_count);
    co.min_size = 10;
    CHECK_STATUS(pnpr_segment_components(s.xyz, s.n, &co, labels, &info), PNPR_OK);
    CHECK_MSG(info.segment_count == 3, "components with min size: %u segments, expected 3", info.segment_count);
    pnpr_segment_score sc = score(&s, labels);
    CHECK_NEAR(sc.ari, 1.0, 1e-9);
    co.distance = 2.0f;
    CHECK_STATUS(pnpr_segment_components(s.xyz, s.n, &co, labels, &info), PNPR_OK);
    CHECK(info.segment_count == 1);
    co.distance = NAN;
    CHECK_STATUS(pnpr_segment_components(s.xyz, s.n, &co, labels, &info), PNPR_ERR_INVALID_ARGUMENT);
    scene_free(&s);
    free(labels);
}

static void test_degenerate(void)
{
    pnpr_segment_info info;
    uint32_t labels[400];
    /* empty cloud */
    CHECK_STATUS(pnpr_segment_jseg(NULL, NULL, 0, NULL, NULL, &info), PNPR_OK);
    CHECK(info.segment_count == 0);
    CHECK_STATUS(pnpr_segment_components(NULL, 0, NULL, NULL, &info), PNPR_OK);
    CHECK_STATUS(pnpr_segment_rgbgrow(NULL, NULL, 0, NULL, NULL, &info), PNPR_OK);
    /* a single point */
    float p1[3] = {1, 2, 3};
    uint8_t c1[3] = {9, 9, 9};
    labels[0] = 77;
    CHECK_STATUS(pnpr_segment_jseg(p1, c1, 1, NULL, labels, &info), PNPR_OK);
    CHECK(info.segment_count == 1 && labels[0] == 0);
    CHECK_STATUS(pnpr_segment_components(p1, 1, NULL, labels, &info), PNPR_OK);
    CHECK(info.segment_count == 1 && labels[0] == 0);
    CHECK_STATUS(pnpr_segment_rgbgrow(p1, c1, 1, NULL, labels, &info), PNPR_OK);
    CHECK(info.segment_count == 1 && labels[0] == 0);
    /* no colours: jseg and rgbgrow refuse */
    CHECK_STATUS(pnpr_segment_jseg(p1, NULL, 1, NULL, labels, &info), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_segment_rgbgrow(p1, NULL, 1, NULL, labels, &info), PNPR_ERR_INVALID_ARGUMENT);
    /* uniform colour plane (with colour noise): one segment */
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_test_plane(&c, 20, 20, 0.05, (double[3]){0, 0, 0}), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(&c), PNPR_OK);
    pnpr_test_rng rng = {3};
    for (size_t i = 0; i < 3 * c.count; i++) c.rgb[i] = (uint8_t)(120 + 6 * pnpr_test_uniform(&rng));
    CHECK_STATUS(pnpr_segment_jseg(c.xyz, c.rgb, c.count, NULL, labels, &info), PNPR_OK);
    CHECK_MSG(info.segment_count == 1, "uniform plane: %u jseg segments", info.segment_count);
    CHECK_STATUS(pnpr_segment_rgbgrow(c.xyz, c.rgb, c.count, NULL, labels, &info), PNPR_OK);
    CHECK_MSG(info.segment_count == 1, "uniform plane: %u rgbgrow segments", info.segment_count);
    /* k and classes larger than the cloud */
    pnpr_jseg_options jo = {0};
    jo.k = 256; jo.classes = 255;
    CHECK_STATUS(pnpr_segment_jseg(c.xyz, c.rgb, 10, &jo, labels, &info), PNPR_OK);
    check_labels_range(labels, 10, info.segment_count);
    /* NaN coordinates: one last segment of their own */
    c.xyz[3 * 5] = NAN; c.xyz[3 * 17 + 2] = INFINITY;
    CHECK_STATUS(pnpr_segment_jseg(c.xyz, c.rgb, c.count, NULL, labels, &info), PNPR_OK);
    CHECK(info.segment_count == 2 && info.invalid_segment == 1 && labels[5] == 1 && labels[17] == 1 && labels[0] == 0);
    CHECK(info.valid_points == c.count - 2);
    CHECK_STATUS(pnpr_segment_components(c.xyz, c.count, NULL, labels, &info), PNPR_OK);
    CHECK(info.segment_count == 2 && labels[5] == 1);
    CHECK_STATUS(pnpr_segment_rgbgrow(c.xyz, c.rgb, c.count, NULL, labels, &info), PNPR_OK);
    CHECK(info.segment_count == 2 && labels[5] == 1);
    for (size_t i = 0; i < c.count; i++) c.xyz[3 * i] = NAN;
    CHECK_STATUS(pnpr_segment_jseg(c.xyz, c.rgb, c.count, NULL, labels, &info), PNPR_OK);
    CHECK(info.segment_count == 1 && info.valid_points == 0 && labels[0] == 0);
    pnpr_cloud_free(&c);
    /* duplicated points: 200 copies of one position, half red and half blue */
    float dup[3 * 200];
    uint8_t dcol[3 * 200];
    for (int i = 0; i < 200; i++) {
        dup[3 * i] = 0.5f; dup[3 * i + 1] = -1; dup[3 * i + 2] = 2;
        dcol[3 * i] = i < 100 ? 255 : 0; dcol[3 * i + 1] = 0; dcol[3 * i + 2] = i < 100 ? 0 : 255;
    }
    float jmap[200];
    jo = (pnpr_jseg_options){0};
    jo.r_j = jmap;
    CHECK_STATUS(pnpr_segment_jseg(dup, dcol, 200, &jo, labels, &info), PNPR_OK);
    check_labels_range(labels, 200, info.segment_count);
    int finite = 1;
    for (int i = 0; i < 200; i++) finite &= isfinite(jmap[i]) && jmap[i] >= 0;
    CHECK(finite);
    CHECK_STATUS(pnpr_segment_components(dup, 200, NULL, labels, &info), PNPR_OK);
    CHECK(info.segment_count == 1);
    CHECK_STATUS(pnpr_segment_rgbgrow(dup, dcol, 200, NULL, labels, &info), PNPR_OK);
    check_labels_range(labels, 200, info.segment_count);
    /* cancel */
    scene s;
    make_scene(&s, 0.05, 0, 0, 1);
    uint32_t *big = malloc(s.n * sizeof *big);
    jo = (pnpr_jseg_options){0};
    jo.progress.fn = cancel_now;
    CHECK_STATUS(pnpr_segment_jseg(s.xyz, s.rgb, s.n, &jo, big, &info), PNPR_ERR_CANCELLED);
    free(big);
    scene_free(&s);
}

int main(void)
{
    test_degenerate();
    test_components();
    test_score();
    test_values_and_compact();
    test_jseg_scene();
    return pnpr_test_finish("test_segment");
}
