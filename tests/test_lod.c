/* A PLY file ordered for drawing (pointnpr/lod.h): the runs' ranks, the writer's order against
 * the points' own cells and source indices (carried as a property), the same file whatever the
 * chunks, every point kept, the ranges' reads equal to a pass over every point, and the header
 * and index's lies refused. */
#include "testutil.h"

#include <pointnpr/io.h>
#include <pointnpr/lod.h>
#include <pointnpr/props.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DIR PNPR_TEST_SCRATCH "/lod"

/* The runs hold halves: run j > 0 about 2^(j-L) of the points, run 0 2^(1-L); ranks in range. */
static void test_runs(void)
{
    const int n = 1 << 20;
    int count[PNPR_LOD_LEVELS] = {0};
    for (int i = 0; i < n; i++) {
        int j = pnpr_lod_run_of((uint64_t)i);
        CHECK(j >= 0 && j < PNPR_LOD_LEVELS);
        count[j]++;
        double r = pnpr_lod_rank((uint64_t)i * 7919u, j);
        CHECK(r >= pnpr_lod_run_low(j) && r < pnpr_lod_run_high(j));
    }
    CHECK_NEAR(count[15] / (double)n, 0.5, 0.003);
    CHECK_NEAR(count[14] / (double)n, 0.25, 0.003);
    CHECK_NEAR(count[10] / (double)n, 1.0 / 64, 0.001);
    CHECK_NEAR(count[0] / (double)n, 1.0 / 32768, 20.0 / n);
    CHECK(pnpr_lod_run_low(0) == 0 && pnpr_lod_run_high(0) == ldexp(1, 1 - PNPR_LOD_LEVELS));
    CHECK(pnpr_lod_run_low(15) == 0.5 && pnpr_lod_run_high(15) == 1.0);
}

/* A georeferenced scene: a 120 x 80 grid of double points around (5e5, 4.2e6, 100) on a slope,
 * with colours, a source index ("idx") and an intensity; duplicates, points with NaN and Inf,
 * a far outlier. */
static size_t make_scene(pnpr_cloud *c)
{
    const size_t grid = 120 * 80, n = grid + 40;
    CHECK_STATUS(pnpr_cloud_alloc(c, n), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(c), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_add_property(c, "idx", PNPR_TYPE_UINT32, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_add_property(c, "intensity", PNPR_TYPE_UINT16, NULL), PNPR_OK);
    double *w = malloc(3 * n * sizeof *w);
    pnpr_test_rng rng = {77};
    for (size_t i = 0; i < n; i++) {
        size_t g = i < grid ? i : i % 17; /* 40 more: duplicates of the first points */
        double x = 5e5 + 0.5 * (double)(g % 120) + 0.1 * pnpr_test_uniform(&rng);
        double y = 4.2e6 + 0.5 * (double)(g / 120);
        w[3 * i] = x;
        w[3 * i + 1] = y;
        w[3 * i + 2] = 100 + 0.2 * (x - 5e5);
        if (i >= grid) memcpy(w + 3 * i, w + 3 * g, 3 * sizeof *w);
        ((uint32_t *)c->props[0].data)[i] = (uint32_t)i;
        ((uint16_t *)c->props[1].data)[i] = (uint16_t)(i * 31);
        for (int k = 0; k < 3; k++) c->rgb[3 * i + (size_t)k] = (uint8_t)(i * (size_t)(k + 3));
    }
    w[3 * 5] = NAN;          /* point 5: NaN x */
    w[3 * 6 + 2] = INFINITY; /* point 6: Inf z */
    w[3 * 7] = 5e5 + 3e4;    /* point 7: 30 km east */
    CHECK_STATUS(pnpr_cloud_set_world(c, w), PNPR_OK);
    free(w);
    return n;
}

static void write_input(const char *path, const pnpr_cloud *c)
{
    pnpr_write_options wo = {0};
    wo.force_double = 1;
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_write_file(path, c, &wo, &err), PNPR_OK);
}

static int same_file(const char *a, const char *b)
{
    FILE *fa = fopen(a, "rb"), *fb = fopen(b, "rb");
    int same = fa && fb, ca, cb;
    while (same && (ca = fgetc(fa)) == (cb = fgetc(fb)) && ca != EOF) {}
    same = same && ca == cb;
    if (fa) fclose(fa);
    if (fb) fclose(fb);
    return same;
}

/* The order: every vertex in its cell's run, by its source index's run, file order within a run;
 * every point kept once with its properties. */
static void check_order(const pnpr_lod *l, const pnpr_cloud *in, const pnpr_cloud *out)
{
    CHECK(out->count == in->count && l->points == in->count);
    const pnpr_property *idx = pnpr_cloud_find_property(out, "idx"), *it = pnpr_cloud_find_property(out, "intensity");
    CHECK(idx && it);
    if (!idx || !it) return;
    const uint32_t *src = idx->data;
    uint8_t *seen = calloc(in->count, 1);
    size_t cursor = 0, bad = 0;
    for (size_t v = 0; v < out->count; v++) {
        double p[3], q[3];
        pnpr_cloud_world(out, v, p);
        uint32_t s = src[v];
        CHECK(s < in->count && !seen[s]);
        if (s >= in->count || seen[s]) continue;
        seen[s] = 1;
        pnpr_cloud_world(in, s, q);
        int j = pnpr_lod_run_at(l, v, &cursor);
        size_t cell = cursor / PNPR_LOD_LEVELS;
        bad += !(memcmp(p, q, sizeof p) == 0 || (isnan(p[0]) && isnan(q[0]))) ||
               ((const uint16_t *)it->data)[v] != (uint16_t)(s * 31) || memcmp(out->rgb + 3 * v, in->rgb + 3 * s, 3) ||
               j != pnpr_lod_run_of(s) || cell != pnpr_lod_cell(l, p) ||
               (v > 0 && l->start[cursor] < v && src[v - 1] > s); /* file order within a run */
    }
    CHECK_MSG(bad == 0, "%zu points out of place or changed", bad);
    free(seen);
    /* NaN, Inf and the far outlier in the last cell: 3 of them, each in its run */
    double p[3];
    for (size_t i = 5; i <= 7; i++) {
        pnpr_cloud_world(in, i, p);
        CHECK(pnpr_lod_cell(l, p) == l->cells);
    }
    CHECK(pnpr_lod_cell_points(l, l->cells) == 3);
}

typedef struct ranked {
    const pnpr_lod *l;
    size_t cursor, visited;
    const double *cell_share; /* a point's share: its cell's x a fraction by its coordinates */
    uint8_t *kept;
} ranked;

static double point_share(const ranked *r, const double p[3])
{
    uint32_t k = pnpr_lod_cell(r->l, p);
    double f = isfinite(p[0] + p[1]) ? 0.5 + 0.5 * fabs(sin(p[0] * 3.1 + p[1])) : 1;
    return r->cell_share[k] * f;
}

static int keep_ranked(void *user, uint64_t v, const double p[3])
{
    ranked *r = user;
    r->visited++;
    int kept = pnpr_lod_rank(v, pnpr_lod_run_at(r->l, v, &r->cursor)) < point_share(r, p);
    if (kept) r->kept[v] = 1;
    return kept;
}

/* The ranges of random cell shares read exactly the points a pass over every point keeps, and
 * visit only the points of the ranges. */
static void check_ranges(const char *path, const pnpr_lod *l)
{
    const size_t cells = (size_t)l->cells + 1;
    double *share = malloc(cells * sizeof *share);
    uint64_t *ranges = malloc(2 * cells * sizeof *ranges);
    uint8_t *runs = malloc(cells), *a = calloc(l->points, 1), *b = calloc(l->points, 1);
    pnpr_test_rng rng = {5};
    for (size_t k = 0; k < cells; k++) {
        double u = pnpr_test_uniform(&rng);
        share[k] = u < 0.1 ? 0 : u < 0.2 ? 1 : pow(2.0, -14.0 * pnpr_test_uniform(&rng));
    }
    size_t m = pnpr_lod_ranges(l, share, ranges, runs), in_ranges = 0;
    for (size_t g = 0; g < m; g++) {
        CHECK(ranges[2 * g] < ranges[2 * g + 1] && (g == 0 || ranges[2 * g] > ranges[2 * g - 1]));
        in_ranges += (size_t)(ranges[2 * g + 1] - ranges[2 * g]);
    }
    for (size_t k = 0; k < cells; k++) /* the runs read: those whose lower bound is below the share */
        CHECK(runs[k] == 0 ? share[k] == 0 : share[k] > pnpr_lod_run_low(runs[k] - 1) &&
                                                 (runs[k] == PNPR_LOD_LEVELS || share[k] <= pnpr_lod_run_low(runs[k])));
    ranked ra = {l, 0, 0, share, a}, rb = {l, 0, 0, share, b};
    pnpr_read_options ro = {0};
    ro.keep = keep_ranked;
    ro.keep_user = &ra;
    ro.ranges = ranges;
    ro.range_count = m;
    pnpr_cloud ca = {0}, cb = {0};
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_read_file(path, &ro, &ca, &err), PNPR_OK);
    ro.keep_user = &rb;
    ro.ranges = NULL;
    CHECK_STATUS(pnpr_read_file(path, &ro, &cb, &err), PNPR_OK);
    CHECK(ra.visited == in_ranges && rb.visited == l->points);
    CHECK(ca.count == cb.count && ca.count > 100 && ca.count < l->points / 2);
    CHECK(memcmp(a, b, l->points) == 0);
    printf("ranges: %zu of %zu cells' runs, %zu of %llu points visited, %zu kept\n", m, cells, in_ranges,
           (unsigned long long)l->points, ca.count);
    /* ranges out of order or beyond the vertices, refused before keep sees a point; ranges
     * without keep */
    uint64_t bad[4] = {10, 20, 15, 30}, beyond[2] = {0, l->points + 1};
    ro.ranges = bad;
    ro.range_count = 2;
    ra.visited = 0;
    ro.keep_user = &ra;
    pnpr_cloud none = {0};
    CHECK_STATUS(pnpr_read_file(path, &ro, &none, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK(ra.visited == 0);
    ro.keep = NULL;
    CHECK_STATUS(pnpr_read_file(path, &ro, &none, &err), PNPR_ERR_INVALID_ARGUMENT);
    ro.keep = keep_ranked;
    ro.ranges = beyond;
    ro.range_count = 1;
    CHECK_STATUS(pnpr_read_file(path, &ro, &none, &err), PNPR_ERR_INVALID_ARGUMENT);
    pnpr_cloud_free(&ca);
    pnpr_cloud_free(&cb);
    free(share);
    free(ranges);
    free(runs);
    free(a);
    free(b);
}

static void test_write(void)
{
    pnpr_cloud in = {0}, out = {0};
    make_scene(&in);
    write_input(DIR "/scene.ply", &in);
    pnpr_lod_options o = {0};
    pnpr_error err = {0};
    uint64_t points = 0;
    CHECK_STATUS(pnpr_lod_write(DIR "/scene.ply", DIR "/scene_lod.ply", &o, &points, &err), PNPR_OK);
    CHECK(points == in.count);
    o.memory = 40000; /* chunks of about 400 points: whole cells, many passes */
    o.max_passes = 5;  /* refused before writing */
    CHECK_STATUS(pnpr_lod_write(DIR "/scene.ply", DIR "/scene_lod2.ply", &o, &points, &err), PNPR_ERR_OUT_OF_MEMORY);
    CHECK_MSG(strstr(err.message, "give more memory") != NULL && pnpr_test_temporaries(DIR, "scene_lod2.ply") == 0,
              "%s", err.message);
    o.max_passes = 0;
    CHECK_STATUS(pnpr_lod_write(DIR "/scene.ply", DIR "/scene_lod2.ply", &o, &points, &err), PNPR_OK);
    CHECK(same_file(DIR "/scene_lod.ply", DIR "/scene_lod2.ply"));
    pnpr_lod l = {0};
    CHECK_STATUS(pnpr_lod_open(DIR "/scene_lod.ply", &l, &err), PNPR_OK);
    /* the grid over the 60 x 40 x 12 m of the scene, not the outlier 30 km away */
    CHECK(l.cells == l.n[0] * l.n[1] * l.n[2] && l.cells <= 9640 / 8 && l.cells > 9640 / 16);
    CHECK(l.side * l.n[0] >= 59.5 && l.side * (l.n[0] - 1) < 60.2 && l.side * l.n[1] >= 39.5);
    printf("grid %u x %u x %u of %g\n", l.n[0], l.n[1], l.n[2], l.side);
    CHECK_STATUS(pnpr_read_file(DIR "/scene_lod.ply", NULL, &out, &err), PNPR_OK); /* an ordinary PLY too */
    check_order(&l, &in, &out);
    check_ranges(DIR "/scene_lod.ply", &l);
    /* never over its input */
    CHECK_STATUS(pnpr_lod_write(DIR "/scene.ply", DIR "/scene.ply", &o, &points, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK(pnpr_test_temporaries(DIR, "scene.ply") == 0);
    pnpr_lod_free(&l);
    pnpr_cloud_free(&in);
    pnpr_cloud_free(&out);
}

/* A uniform sample for viewing (pnpr_lod_read_sample): of the ordered file, the points whose
 * rank is below the share, reading part of it; of the ordinary file, by the hash of the index;
 * every point when asked for more. */
static void test_sample(void)
{
    const double share = 2000.0 / 9640.0;
    for (int ordered = 0; ordered < 2; ordered++) {
        const char *path = ordered ? DIR "/scene_lod.ply" : DIR "/scene.ply";
        pnpr_cloud c = {0}, all = {0};
        pnpr_error err = {0};
        uint64_t total = 0;
        int used = -1;
        CHECK_STATUS(pnpr_lod_read_sample(path, 2000, NULL, &c, &total, &used, &err), PNPR_OK);
        CHECK(total == 9640 && used == ordered);
        CHECK_MSG(c.count > 1800 && c.count < 2200, "%zu points for 2000", c.count);
        CHECK_STATUS(pnpr_read_file(path, NULL, &all, &err), PNPR_OK);
        pnpr_lod l = {0};
        if (ordered) CHECK_STATUS(pnpr_lod_open(path, &l, &err), PNPR_OK);
        size_t cursor = 0, j = 0, bad = 0;
        const pnpr_property *a = pnpr_cloud_find_property(&all, "idx"), *b = pnpr_cloud_find_property(&c, "idx");
        for (size_t v = 0; a && b && v < all.count; v++) /* the kept ones, in file order */
            if (pnpr_lod_kept(ordered ? &l : NULL, v, &cursor, share))
                bad += j >= c.count || ((const uint32_t *)a->data)[v] != ((const uint32_t *)b->data)[j++];
        CHECK_MSG(a && b && bad == 0 && j == c.count, "%zu of %zu differ", bad, j);
        pnpr_cloud_free(&c);
        CHECK_STATUS(pnpr_lod_read_sample(path, 20000, NULL, &c, &total, &used, &err), PNPR_OK);
        CHECK(c.count == 9640);
        pnpr_cloud_free(&c);
        pnpr_cloud_free(&all);
        pnpr_lod_free(&l);
    }
}

/* A sample by a view (pnpr_lod_read_view): of both files, exactly the points whose rank is below
 * their share by the solved view (the ranges miss none), about the count asked, kept in proportion
 * to the share (near points more than far ones), none out of view; progress over both passes, and
 * a cancel. */
typedef struct progress_log {
    double last;
    int reports, backwards, cancel_at;
} progress_log;

static int log_progress(void *user, const char *stage, double f)
{
    progress_log *g = user;
    g->backwards += f < g->last || strcmp(stage, "sample") != 0;
    g->last = f;
    return g->cancel_at && ++g->reports >= g->cancel_at;
}

typedef struct count_log {
    int first, all; /* reports below 0.5 (the first of two passes), all reports */
} count_log;

static int count_progress(void *user, const char *stage, double f)
{
    (void)stage;
    count_log *n = user;
    n->first += f < 0.5;
    n->all++;
    return 0;
}

static void test_view(void)
{
    const double eye[3] = {5e5 + 20, 4.2e6 + 20, 120}, target[3] = {5e5 + 50, 4.2e6 + 20, 108};
    double c_of[2] = {0, 0};
    for (int ordered = 0; ordered < 2; ordered++) {
        const char *path = ordered ? DIR "/scene_lod.ply" : DIR "/scene.ply";
        pnpr_view_sample v;
        CHECK_STATUS(pnpr_view_sample_init(&v, eye, target, 50, 640, 480), PNPR_OK);
        pnpr_cloud c = {0}, all = {0};
        pnpr_error err = {0};
        pnpr_lod_read_info info;
        progress_log g = {0, 0, 0, 0};
        pnpr_read_options ro = {0};
        ro.progress = (pnpr_progress){log_progress, &g};
        CHECK_STATUS(pnpr_lod_read_view(path, &v, 1500, &ro, &c, &info, &err), PNPR_OK);
        CHECK_MSG(info.total == 9640 && info.ordered == ordered && g.backwards == 0 && g.last > 0.99, "%llu %d %d %g", (unsigned long long)info.total, info.ordered, g.backwards, g.last);
        CHECK_MSG(c.count > 1300 && c.count < 1700, "%zu points for 1500", c.count);
        CHECK_MSG(info.in_view > 3000 && info.in_view < 8000, "%llu in view", (unsigned long long)info.in_view);
        CHECK(ordered ? info.visited < 9640 / 2 : info.visited == 9640);
        c_of[ordered] = v.c;
        printf("view, %s file: %zu kept of %llu in view, %llu visited, c %g\n", ordered ? "ordered" : "ordinary", c.count,
               (unsigned long long)info.in_view, (unsigned long long)info.visited, v.c);
        /* the rule over every point */
        CHECK_STATUS(pnpr_read_file(path, NULL, &all, &err), PNPR_OK);
        pnpr_lod l = {0};
        if (ordered) CHECK_STATUS(pnpr_lod_open(path, &l, &err), PNPR_OK);
        size_t cursor = 0, j = 0, bad = 0, unseen = 0;
        double mid_share = 0, mid_kept = 0, near_kept = 0, near = 0;
        const pnpr_property *a = pnpr_cloud_find_property(&all, "idx"), *b = pnpr_cloud_find_property(&c, "idx");
        for (size_t i = 0; a && b && i < all.count; i++) {
            double w[3];
            pnpr_cloud_world(&all, i, w);
            double share = pnpr_view_sample_share(&v, w);
            int kept = pnpr_lod_kept(ordered ? &l : NULL, i, &cursor, share);
            if (kept) bad += j >= c.count || ((const uint32_t *)a->data)[i] != ((const uint32_t *)b->data)[j++];
            unseen += kept && !(share > 0);
            if (share > 0.05 && share < 0.5) { mid_share += share; mid_kept += kept; }
            if (share >= 1) { near++; near_kept += kept; }
        }
        CHECK_MSG(a && b && bad == 0 && j == c.count && unseen == 0, "%zu of %zu differ, %zu unseen", bad, j, unseen);
        CHECK_MSG(mid_share > 100 && fabs(mid_kept / mid_share - 1) < 0.15, "kept %g for shares summing to %g", mid_kept,
                  mid_share);
        CHECK_MSG(near > 50 && near_kept == near, "%g of %g near points", near_kept, near);
        pnpr_cloud_free(&c);
        pnpr_cloud_free(&all);
        pnpr_lod_free(&l);
        /* none asked: none kept; a cancel in the first pass and in the second */
        CHECK_STATUS(pnpr_lod_read_view(path, &v, 0, NULL, &c, &info, &err), PNPR_OK);
        CHECK(c.count == 0 && info.in_view <= info.total);
        int first = 0, reports = 0; /* the reports of the first pass, of both */
        {
            count_log n = {0, 0};
            ro.progress = (pnpr_progress){count_progress, &n};
            CHECK_STATUS(pnpr_lod_read_view(path, &v, 1500, &ro, &c, &info, &err), PNPR_OK);
            pnpr_cloud_free(&c);
            first = n.first;
            reports = n.all;
            ro.progress = (pnpr_progress){log_progress, &g};
        }
        CHECK_MSG(first >= 2 && reports > first + 1, "%d reports, %d in the first pass", reports, first);
        const int at[2] = {2, first + 1};
        for (int k = 0; k < 2; k++) {
            g = (progress_log){0, 0, 0, at[k]};
            CHECK_STATUS(pnpr_lod_read_view(path, &v, 1500, &ro, &c, &info, &err), PNPR_ERR_CANCELLED);
            CHECK(c.count == 0 && (k == 0 ? g.last < 0.5 : g.last >= 0.5));
            pnpr_cloud_free(&c);
        }
        /* no view, a point filter of the caller's */
        pnpr_view_sample none = {0};
        CHECK_STATUS(pnpr_lod_read_view(path, &none, 10, NULL, &c, NULL, &err), PNPR_ERR_INVALID_ARGUMENT);
        ro.keep = keep_ranked;
        CHECK_STATUS(pnpr_lod_read_view(path, &v, 10, &ro, &c, NULL, &err), PNPR_ERR_INVALID_ARGUMENT);
    }
    /* the stored spacing of a sample grows by 1/sqrt of each point's share; the estimate of the
     * whole cloud's mean weighs each point by 1/share */
    {
        pnpr_view_sample v;
        CHECK_STATUS(pnpr_view_sample_init(&v, eye, target, 50, 640, 480), PNPR_OK);
        pnpr_cloud c = {0}, all = {0};
        pnpr_error err = {0};
        CHECK_STATUS(pnpr_lod_read_view(DIR "/scene_lod.ply", &v, 1500, NULL, &c, NULL, &err), PNPR_OK);
        CHECK_STATUS(pnpr_cloud_add_property(&c, PNPR_PROP_POINT_SPACING, PNPR_TYPE_FLOAT32, NULL), PNPR_OK);
        pnpr_property *sp = pnpr_cloud_find_property(&c, PNPR_PROP_POINT_SPACING);
        double sum = 0, weight = 0;
        for (size_t i = 0; i < c.count; i++) {
            ((float *)sp->data)[i] = 0.5f + 0.25f * (float)(i % 3);
            double w[3];
            pnpr_cloud_world(&c, i, w);
            double share = pnpr_view_sample_share(&v, w);
            sum += ((float *)sp->data)[i] / share;
            weight += 1 / share;
        }
        float tone = pnpr_lod_grow_spacing(&c, &v, 1);
        CHECK_MSG(fabsf(tone - (float)(sum / weight)) < 1e-4f && tone > 0.5f && tone < 1.0f, "tone radius %g", tone);
        size_t bad = 0, grown = 0;
        for (size_t i = 0; i < c.count; i++) {
            double w[3];
            pnpr_cloud_world(&c, i, w);
            double share = pnpr_view_sample_share(&v, w), want = (0.5 + 0.25 * (double)(i % 3)) / sqrt(share < 1 ? share : 1);
            bad += fabs(((float *)sp->data)[i] - want) > 1e-5 * want;
            grown += share < 1;
        }
        CHECK_MSG(bad == 0 && grown > c.count / 2, "%zu wrong, %zu grown of %zu", bad, grown, c.count);
        /* uniform: 1/4 doubles every spacing; no stored spacing: 0, nothing changed */
        float before = ((float *)sp->data)[0];
        pnpr_lod_grow_spacing(&c, NULL, 0.25);
        CHECK(fabsf(((float *)sp->data)[0] - 2 * before) < 1e-6f);
        CHECK(pnpr_lod_grow_spacing(&all, NULL, 0.5) == 0);
        pnpr_cloud_free(&c);
    }
    /* the order's estimate of c against the pass over every point */
    CHECK_MSG(fabs(c_of[1] / c_of[0] - 1) < 0.1, "c %g ordered, %g ordinary", c_of[1], c_of[0]);
}

/* Empty, one point, only NaN: a file with one cell (and the non-finite one), opened again. */
static void test_small(void)
{
    for (int kind = 0; kind < 3; kind++) {
        pnpr_cloud c = {0};
        size_t n = kind == 0 ? 0 : kind == 1 ? 1 : 3;
        CHECK_STATUS(pnpr_cloud_alloc(&c, n), PNPR_OK);
        for (size_t i = 0; i < 3 * n; i++) c.xyz[i] = kind == 2 ? NAN : 1.5f;
        write_input(DIR "/small.ply", &c);
        pnpr_error err = {0};
        uint64_t points = 99;
        CHECK_STATUS(pnpr_lod_write(DIR "/small.ply", DIR "/small_lod.ply", NULL, &points, &err), PNPR_OK);
        CHECK(points == n);
        pnpr_lod l = {0};
        CHECK_STATUS(pnpr_lod_open(DIR "/small_lod.ply", &l, &err), PNPR_OK);
        CHECK(l.cells == 1 && l.points == n);
        CHECK(l.start[PNPR_LOD_LEVELS] == (kind == 2 ? 0 : n)); /* the non-finite points in cell 1 */
        pnpr_lod_free(&l);
        pnpr_cloud_free(&c);
    }
    /* an ascii input cannot be read by ranges */
    FILE *f = fopen(DIR "/ascii.ply", "w");
    fputs("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 3\n", f);
    fclose(f);
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_lod_write(DIR "/ascii.ply", DIR "/ascii_lod.ply", NULL, NULL, &err), PNPR_ERR_UNSUPPORTED);
    CHECK_MSG(strstr(err.message, "ascii.ply") != NULL, "%s", err.message);
}

/* The header and index's lies: each refused with what is wrong (FORMAT), an ordinary PLY and
 * another version UNSUPPORTED. */
static void test_lies(void)
{
    const char *head = "ply\nformat binary_little_endian 1.0\ncomment pnpr_lod %s\nelement vertex %d\nproperty float x\n"
                       "property float y\nproperty float z\nelement pnpr_lod_run %d\nproperty uint count\nend_header\n";
    struct {
        const char *grid;
        int vertices, runs, sum, truncate;
        pnpr_status st;
        const char *says;
    } c[] = {
        {"1 levels 16 grid 1 1 1 side 1 origin 0 0 0", 2, 32, 2, 0, PNPR_OK, ""},
        {"1 levels 16 grid 1 1 1 side 1 origin 0 0 0", 2, 32, 3, 0, PNPR_ERR_FORMAT, "index counts 3 points"},
        {"1 levels 16 grid 1 1 1 side 1 origin 0 0 0", 2, 32, 2, 1, PNPR_ERR_FORMAT, "truncated"},
        {"1 levels 16 grid 1 1 1 side 1 origin 0 0 0", 2, 48, 2, 0, PNPR_ERR_FORMAT, "48 runs where its grid has 32"},
        {"1 levels 16 grid 200 200 1 side 1 origin 0 0 0", 2, 32, 2, 0, PNPR_ERR_FORMAT, "not 1 to 32768"},
        {"1 levels 16 grid 1 1 1 side nan origin 0 0 0", 2, 32, 2, 0, PNPR_ERR_FORMAT, "not 1 to 32768"},
        {"1 levels 16 grid 1 1 1 side 1 origin 0 0", 2, 32, 2, 0, PNPR_ERR_FORMAT, "is not"},
        {"2 levels 16 grid 1 1 1 side 1 origin 0 0 0", 2, 32, 2, 0, PNPR_ERR_UNSUPPORTED, "version 2"},
        {"1 levels 16 grid 4294967297 1 1 side 1 origin 0 0 0", 2, 32, 2, 0, PNPR_ERR_FORMAT, "is not"},
        {"1 levels 4294967312 grid 1 1 1 side 1 origin 0 0 0", 2, 32, 2, 0, PNPR_ERR_FORMAT, "is not"},
        {"1 levels 16 grid 1 1 1 side 1e308 origin 1e308 0 0", 2, 32, 2, 0, PNPR_ERR_FORMAT, "finite corners"},
    };
    for (size_t t = 0; t < sizeof c / sizeof c[0]; t++) {
        char h[512];
        int len = snprintf(h, sizeof h, head, c[t].grid, c[t].vertices, c[t].runs);
        size_t size = (size_t)len + 12u * (size_t)c[t].vertices + 4u * (size_t)c[t].runs;
        unsigned char *d = calloc(size, 1);
        memcpy(d, h, (size_t)len);
        d[(size_t)len + 12u * (size_t)c[t].vertices] = (unsigned char)c[t].sum; /* all in run 0 of cell 0 */
        pnpr_lod l = {0};
        pnpr_error err = {0};
        CHECK_STATUS(pnpr_lod_parse(d, size - (c[t].truncate ? 3 : 0), &l, &err), c[t].st);
        CHECK_MSG(strstr(err.message, c[t].says) != NULL, "case %zu: %s", t, err.message);
        if (c[t].st == PNPR_OK) CHECK(l.points == 2 && l.start[1] == 2 && l.start[32] == 2);
        pnpr_lod_free(&l);
        free(d);
    }
    /* the data ends inside the runs' property line (a read past its end, found by a review under ASan) */
    const char *cut = "ply\nformat binary_little_endian 1.0\ncomment pnpr_lod 1 levels 16 grid 1 1 1 side 1 origin 0 0 0\n"
                      "element vertex 0\nproperty float x\nelement pnpr_lod_run 32\nproperty int \n";
    char *heap = malloc(strlen(cut));
    memcpy(heap, cut, strlen(cut));
    pnpr_lod lc = {0};
    pnpr_error ec = {0};
    CHECK_STATUS(pnpr_lod_parse(heap, strlen(cut), &lc, &ec), PNPR_ERR_FORMAT);
    free(heap);
    const char *plain = "ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\nend_header\n";
    pnpr_lod l = {0};
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_lod_parse(plain, strlen(plain), &l, &err), PNPR_ERR_UNSUPPORTED);
    const char *ascii = "ply\nformat ascii 1.0\ncomment pnpr_lod 1 levels 16 grid 1 1 1 side 1 origin 0 0 0\n"
                        "element vertex 0\nproperty float x\nelement pnpr_lod_run 32\nproperty uint count\nend_header\n";
    CHECK_STATUS(pnpr_lod_parse(ascii, strlen(ascii), &l, &err), PNPR_ERR_FORMAT);
    CHECK_MSG(strstr(err.message, "little-endian") != NULL, "%s", err.message);
}

/* A mesh is refused, naming its faces, not written without them. A grid of 400 x 400 points in
 * rows: the stride sample (every 2nd point once 100 000 are kept) never sees an odd column, the
 * last among them; the grid covers the whole box all the same (no far outlier): nothing outside. */
static void test_faces_and_box(void)
{
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_cloud_alloc(&c, 3), PNPR_OK);
    for (int i = 0; i < 9; i++) c.xyz[i] = (float)(i % 4);
    c.faces.count = 1;
    c.faces.offset = malloc(2 * sizeof(uint32_t));
    c.faces.index = malloc(3 * sizeof(uint32_t));
    c.faces.offset[0] = 0;
    c.faces.offset[1] = 3;
    for (uint32_t k = 0; k < 3; k++) c.faces.index[k] = k;
    write_input(DIR "/mesh.ply", &c);
    pnpr_cloud_free(&c);
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_lod_write(DIR "/mesh.ply", DIR "/mesh_lod.ply", NULL, NULL, &err), PNPR_ERR_UNSUPPORTED);
    CHECK_MSG(strstr(err.message, "holds 1 face besides its points") != NULL, "%s", err.message);

    const size_t side = 400;
    CHECK_STATUS(pnpr_cloud_alloc(&c, side * side), PNPR_OK);
    for (size_t i = 0; i < side * side; i++) {
        c.xyz[3 * i] = (float)(i % side) * 0.01f;
        c.xyz[3 * i + 1] = (float)(i / side) * 0.01f;
        c.xyz[3 * i + 2] = 0.1f * sinf((float)i);
    }
    write_input(DIR "/rows.ply", &c);
    pnpr_cloud_free(&c);
    CHECK_STATUS(pnpr_lod_write(DIR "/rows.ply", DIR "/rows_lod.ply", NULL, NULL, &err), PNPR_OK);
    pnpr_lod l = {0};
    CHECK_STATUS(pnpr_lod_open(DIR "/rows_lod.ply", &l, &err), PNPR_OK);
    CHECK_MSG(pnpr_lod_cell_points(&l, l.cells) == 0, "%u points outside the grid", pnpr_lod_cell_points(&l, l.cells));
    pnpr_lod_free(&l);
}

int main(void)
{
    if (system("rm -rf '" DIR "' && mkdir -p '" DIR "'") != 0) return 1;
    test_runs();
    test_write();
    test_sample();
    test_view();
    test_small();
    test_lies();
    test_faces_and_box();
    return pnpr_test_finish("test_lod");
}
