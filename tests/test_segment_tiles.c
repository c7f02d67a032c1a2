/* Connected components in tiles (tiles.h, filters/segment_tiles.c) against the run in memory, on
 * generated scenes with known components: islands of points on a georeferenced plane (double
 * coordinates around (5e5, 4.2e6)), a thin snake that crosses every tile (one component), a few
 * lone points and points with NaN coordinates, in random file order; a vertical wall, whose
 * spacing the plan (2.5D) underestimates, so that the automatic distance needs several reaches,
 * with NaN and coincident points among its samples (terms that do not count); and far points in
 * a line across a seam of the edge tiles (off the plan's grid).
 * The labels, their numbering and the mean colours must be the run in memory's, bit for bit. */
#include "testutil.h"

#include <pointnpr/io.h>
#include <pointnpr/knn.h>
#include <pointnpr/props.h>
#include <pointnpr/segment.h>
#include <pointnpr/tiles.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define ISLANDS 12   /* 3 x 4 squares of side 1.5 on a 10 x 12 plane */
#define LONE 5       /* lone points, far from everything */
#define INVALID 3    /* points with a NaN coordinate */
#define TILES_MAX 256

enum { SCENE_ISLANDS, SCENE_WALL, SCENE_EDGE };
#define EDGE 13 /* far points in a line at x + 1e4 (under 0.1 %: off the plan's grid, in edge tiles) */

/* The scene's points (world coordinates) in random order; colours by component. */
static void make_scene(pnpr_cloud *c, int kind, size_t *r_components)
{
    pnpr_test_rng rng = {777};
    const double off[3] = {5e5, 4.2e6, 100};
    size_t n = kind == SCENE_WALL ? 20000 : 0;
    if (kind != SCENE_WALL) n = ISLANDS * 900 + 3000 + LONE + INVALID + (kind == SCENE_EDGE ? EDGE : 0);
    double *w = malloc(3 * n * sizeof *w);
    uint8_t *rgb = malloc(3 * n);
    size_t m = 0;
    if (kind == SCENE_WALL) { /* a wall 8 long, 4 high, at y = 0: spacing about 0.04 in x and z */
        for (; m < n; m++) { /* a jittered 200 x 100 grid: no gap of 3 median spacings */
            double x = 0.04 * ((double)(m % 200) + 0.3 * pnpr_test_uniform(&rng));
            double z = 0.04 * ((double)(m / 200) + 0.3 * pnpr_test_uniform(&rng));
            double p[3] = {x, 0.001 * pnpr_test_uniform(&rng), z};
            memcpy(w + 3 * m, p, sizeof p);
            rgb[3 * m] = (uint8_t)(x * 30);
            rgb[3 * m + 1] = 90;
            rgb[3 * m + 2] = (uint8_t)(z * 50);
            if (m % 7 == 3) p[1] = NAN, memcpy(w + 3 * m, p, sizeof p); /* samples without a term */
            if (m >= 10000 && m < 10040) w[3 * m] = 4, w[3 * m + 1] = 0, w[3 * m + 2] = 2; /* 40 coincide */
        }
        *r_components = 2; /* the wall, and the points with a NaN coordinate */
    } else {
        for (int k = 0; k < ISLANDS; k++) /* a jittered 30 x 30 grid of spacing 0.05 */
            for (int i = 0; i < 900; i++, m++) {
                w[3 * m] = 0.75 + 3.0 * (k % 3) + 0.05 * ((i % 30) + 0.3 * pnpr_test_uniform(&rng));
                w[3 * m + 1] = 0.75 + 3.0 * (k / 3) + 0.05 * ((i / 30) + 0.3 * pnpr_test_uniform(&rng));
                w[3 * m + 2] = 0.01 * pnpr_test_uniform(&rng);
                rgb[3 * m] = (uint8_t)(20 * k + (i & 7));
                rgb[3 * m + 1] = (uint8_t)(250 - 20 * k);
                rgb[3 * m + 2] = (uint8_t)i;
            }
        for (int i = 0; i < 3000; i++, m++) { /* the snake: x from 0 to 10, y zig-zagging over 0..12 */
            double x = 10.0 * i / 3000.0, y = 0.2 + 11.6 * fabs(fmod(x, 2.0) - 1.0);
            w[3 * m] = x;
            w[3 * m + 1] = y;
            w[3 * m + 2] = 0.5; /* above the islands: crossing them does not join them */
            rgb[3 * m] = rgb[3 * m + 1] = rgb[3 * m + 2] = (uint8_t)(i % 251);
        }
        for (int i = 0; i < LONE; i++, m++) {
            double p[3] = {0.3 + 2.1 * i, 11.9, -3.0};
            memcpy(w + 3 * m, p, sizeof p);
            memset(rgb + 3 * m, 200, 3);
        }
        for (int i = 0; kind == SCENE_EDGE && i < EDGE; i++, m++) { /* across the middle rows' seam */
            double p[3] = {1e4, 5.2 + 1.6 * i / (EDGE - 1), i == 0 ? 3000 : 0}; /* the first far in z too */
            memcpy(w + 3 * m, p, sizeof p);
            memset(rgb + 3 * m, 60, 3);
        }
        for (int i = 0; i < INVALID; i++, m++) {
            double p[3] = {1, NAN, 2};
            memcpy(w + 3 * m, p, sizeof p);
            memset(rgb + 3 * m, 10 * i, 3);
        }
        *r_components = ISLANDS + 1 + LONE + 1 + 2 * (kind == SCENE_EDGE); /* the edge line and its z point, at 0.2 */
    }
    for (size_t i = n - 1; i > 0; i--) { /* random file order */
        size_t j = (size_t)(pnpr_test_uniform(&rng) * (double)(i + 1));
        for (int a = 0; a < 3; a++) {
            double t = w[3 * i + a]; w[3 * i + a] = w[3 * j + a]; w[3 * j + a] = t;
            uint8_t u = rgb[3 * i + a]; rgb[3 * i + a] = rgb[3 * j + a]; rgb[3 * j + a] = u;
        }
    }
    for (size_t i = 0; i < 3 * n; i++) w[i] += off[i % 3];
    CHECK_STATUS(pnpr_cloud_alloc(c, n), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(c), PNPR_OK);
    memcpy(c->rgb, rgb, 3 * n);
    CHECK_STATUS(pnpr_cloud_alloc_src_xyz(c), PNPR_OK);
    memcpy(c->src_xyz, w, 3 * n * sizeof *w);
    c->src_coord_type = PNPR_TYPE_FLOAT64;
    CHECK_STATUS(pnpr_cloud_set_world(c, w), PNPR_OK);
    free(w);
    free(rgb);
}

static const char *scratch(const char *name, char *buf, size_t cap)
{
    snprintf(buf, cap, "%s/segtiles_%s", PNPR_TEST_SCRATCH, name);
    return buf;
}

/* The run in memory (read with `origin`, NULL: its own): labels and the distance (`given`, or
 * the automatic one when 0). */
static void in_memory(const char *path, const double *origin, float given, pnpr_cloud *c, float *r_distance,
                      uint32_t *r_segments)
{
    pnpr_error err = {0};
    pnpr_read_options ro = {0};
    ro.origin = origin;
    CHECK_STATUS(pnpr_read_file(path, &ro, c, &err), PNPR_OK);
    pnpr_kdtree *tree = NULL;
    CHECK_STATUS(pnpr_kdtree_build(c->xyz, c->count, 0, &tree), PNPR_OK);
    pnpr_components_options o = {0};
    o.distance = given;
    *r_distance = pnpr_components_distance(&o, pnpr_segment_median_spacing(tree, c->xyz, c->count));
    pnpr_kdtree_free(tree);
    CHECK_STATUS(pnpr_cloud_alloc_labels(c), PNPR_OK);
    pnpr_segment_info info;
    CHECK_STATUS(pnpr_segment_components(c->xyz, c->count, &o, c->label, &info), PNPR_OK);
    *r_segments = info.segment_count;
    float *mean = malloc(3 * (info.segment_count + 1) * sizeof *mean);
    CHECK_STATUS(pnpr_segment_mean_colors(c->rgb, c->label, c->count, info.segment_count, mean, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_segment_add_colors(c, mean, info.segment_count), PNPR_OK);
    free(mean);
}

/* Every tile as `pointnpr segment --tile-grid` does it: its components, the halo marked. */
static void run_jobs(const char *in, const pnpr_tile_plan *plan, float distance, char (*paths)[512])
{
    for (size_t t = 0; t < plan->count; t++) {
        pnpr_cloud c = {0};
        uint8_t *core = NULL;
        pnpr_error err = {0};
        CHECK_STATUS(pnpr_tile_read(in, &plan->grid, &plan->tiles[t], plan->halo, NULL, &c, &core, &err), PNPR_OK);
        CHECK_STATUS(pnpr_tile_components_job(&c, core, distance, 2, NULL), PNPR_OK);
        snprintf(paths[t], sizeof paths[t], "%s/segtiles_part%03zu.ply", PNPR_TEST_SCRATCH, t);
        CHECK_STATUS(pnpr_write_file(paths[t], &c, NULL, &err), PNPR_OK);
        free(core);
        pnpr_cloud_free(&c);
    }
}

/* Points of a and b equal in labels and every property, in order. */
static size_t differing(const pnpr_cloud *a, const pnpr_cloud *b)
{
    if (a->count != b->count || a->prop_count != b->prop_count || !b->label) return a->count + 1;
    size_t bad = 0;
    for (size_t i = 0; i < a->count; i++) {
        int same = a->label[i] == b->label[i] && !memcmp(a->rgb + 3 * i, b->rgb + 3 * i, 3);
        for (size_t p = 0; p < a->prop_count && same; p++)
            same = !strcmp(a->props[p].name, b->props[p].name) &&
                   ((const uint8_t *)a->props[p].data)[i] == ((const uint8_t *)b->props[p].data)[i];
        bad += !same;
    }
    return bad;
}

static void test_equal(int kind, uint64_t tile_points, size_t min_tiles, float given)
{
    char in[512], out[512];
    pnpr_cloud scene = {0};
    size_t expected;
    make_scene(&scene, kind, &expected);
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_write_file(scratch("in.ply", in, sizeof in), &scene, NULL, &err), PNPR_OK);
    pnpr_cloud_free(&scene);

    pnpr_tile_plan_options po = {0};
    pnpr_tile_plan plan;
    /* under a memory limit, tiles as large as a components job may take */
    po.memory_limit = 4u << 20;
    po.job_bytes = PNPR_TILE_COMPONENTS_BYTES;
    CHECK_STATUS(pnpr_tile_plan_make(in, &po, &plan, &err), PNPR_OK);
    size_t rec = 3 * sizeof(double) + 3; /* the scene's records: double x, y, z and colours */
    uint64_t want = (uint64_t)((double)po.memory_limit / ((double)(rec + po.job_bytes) * (1 + PNPR_TILE_HALO_SHARE)));
    CHECK_MSG(plan.tile_points == want, "%llu points a tile under 4 MiB, want %llu", (unsigned long long)plan.tile_points,
              (unsigned long long)want);
    pnpr_tile_plan_free(&plan);
    po.memory_limit = 0;
    po.tile_points = tile_points;
    CHECK_STATUS(pnpr_tile_plan_make(in, &po, &plan, &err), PNPR_OK);
    CHECK_MSG(plan.count >= min_tiles && plan.count <= TILES_MAX, "%zu tiles", plan.count);
    /* far points leave the plan's grid; its origin is still the run in memory's (the centre of the
     * points that are not far outliers), to the bit */
    double side = fmax(plan.grid.cell[0] * plan.grid.cells[0], plan.grid.cell[1] * plan.grid.cells[1]);
    CHECK_MSG(side < 100 && plan.record_bytes == rec, "grid side %g (the far line at x + 1e4 lies off it), %zu bytes a "
              "point", side, plan.record_bytes);
    pnpr_cloud mem = {0};
    float distance = 0;
    uint32_t segments = 0;
    in_memory(in, NULL, given, &mem, &distance, &segments);
    CHECK_MSG(!memcmp(mem.origin, plan.grid.origin, sizeof mem.origin), "origin in memory %.17g %.17g %.17g, plan "
              "%.17g %.17g %.17g", mem.origin[0], mem.origin[1], mem.origin[2], plan.grid.origin[0], plan.grid.origin[1],
              plan.grid.origin[2]);
    CHECK_MSG(segments == expected, "%u components in memory, the scene has %zu", segments, expected);
    float tiled = -1;
    pnpr_components_options to = {0};
    to.distance = given;
    CHECK_STATUS(pnpr_tile_components_distance(in, &plan, &to, 0, &tiled, &err), PNPR_OK);
    CHECK_MSG(tiled == distance, "distance in tiles %.9g, in memory %.9g", (double)tiled, (double)distance);
    if (kind == SCENE_WALL) { /* a round may read what the memory holds: 64 KiB is too little */
        float small = -1;
        CHECK_STATUS(pnpr_tile_components_distance(in, &plan, NULL, 64 << 10, &small, &err), PNPR_ERR_OUT_OF_MEMORY);
        CHECK(strstr(err.message, "give --radius") != NULL && strstr(err.message, in) != NULL);
    }
    plan.halo = pnpr_tile_components_halo(&plan.grid, tiled);
    CHECK(plan.halo > tiled);

    char(*paths)[512] = calloc(plan.count, sizeof *paths);
    const char **list = calloc(plan.count, sizeof *list);
    run_jobs(in, &plan, tiled, paths);
    for (size_t t = 0; t < plan.count; t++) list[t] = paths[t];
    uint32_t S = 0;
    CHECK_STATUS(pnpr_tile_merge_segments(list, plan.count, plan.points, scratch("out.ply", out, sizeof out), NULL, &S,
                                          &err), PNPR_OK);
    CHECK_MSG(S == segments, "%u segments in tiles, %u in memory", S, segments);
    pnpr_cloud merged = {0};
    CHECK_STATUS(pnpr_read_file(out, NULL, &merged, &err), PNPR_OK);
    size_t bad = differing(&mem, &merged);
    CHECK_MSG(bad == 0, "%zu of %zu points differ from the run in memory", bad, mem.count);

    if (kind == SCENE_ISLANDS && plan.count >= 2) {
        /* the halos join the tiles: without them (halo 0) the snake breaks at every seam */
        plan.halo = 0;
        run_jobs(in, &plan, tiled, paths);
        CHECK_STATUS(pnpr_tile_merge_segments(list, plan.count, plan.points, out, NULL, &S, &err), PNPR_OK);
        CHECK_MSG(S > segments, "%u segments without halos", S);
        /* a tile missing, a tile twice, not a tile of segment: refused, naming it */
        CHECK_STATUS(pnpr_tile_merge_segments(list, plan.count - 1, plan.points, out, NULL, &S, &err), PNPR_ERR_FORMAT);
        CHECK(strstr(err.message, "in no tile") != NULL);
        list[1] = list[0];
        CHECK_STATUS(pnpr_tile_merge_segments(list, plan.count, plan.points, out, NULL, &S, &err), PNPR_ERR_FORMAT);
        CHECK(strstr(err.message, "twice") != NULL);
        list[1] = in;
        CHECK_STATUS(pnpr_tile_merge_segments(list, plan.count, plan.points, out, NULL, &S, &err), PNPR_ERR_FORMAT);
        CHECK(strstr(err.message, "not a tile") != NULL && strstr(err.message, in) != NULL);
        /* a lying tile: a label beyond its points (would ask for 4e9 components) */
        list[1] = paths[1];
        pnpr_cloud lie = {0};
        CHECK_STATUS(pnpr_read_file(paths[1], NULL, &lie, &err), PNPR_OK);
        uint32_t *own = pnpr_cloud_find_property(&lie, PNPR_PROP_TILE_COMPONENT)->data;
        static const uint32_t lies[2] = {4000000000u, 0xFFFFFFFFu}; /* the second wraps to 0 components + 1 */
        for (int l = 0; l < 2; l++) {
            for (size_t i = lie.count; i-- > 0;)
                if (lie.xyz[3 * i] == lie.xyz[3 * i]) { own[i] = lies[l]; break; }
            CHECK_STATUS(pnpr_write_file(paths[1], &lie, NULL, &err), PNPR_OK);
            CHECK_STATUS(pnpr_tile_merge_segments(list, plan.count, plan.points, out, NULL, &S, &err), PNPR_ERR_FORMAT);
            CHECK_MSG(strstr(err.message, "labels beyond its points") != NULL && strstr(err.message, paths[1]) != NULL,
                      "%s", err.message);
        }
        pnpr_cloud_free(&lie);
        /* the plain merge refuses a segment tile: it would write each tile's own components */
        CHECK_STATUS(pnpr_tile_merge(list + 2, plan.count - 2, plan.points, 0, out, NULL, &err), PNPR_ERR_FORMAT);
        CHECK(strstr(err.message, "merge-tiles --segments") != NULL);
        /* the result refused is the one merged before, untouched */
        pnpr_cloud again = {0};
        CHECK_STATUS(pnpr_read_file(out, NULL, &again, &err), PNPR_OK);
        CHECK(again.count == mem.count);
        pnpr_cloud_free(&again);
    }
    for (size_t t = 0; t < plan.count; t++) remove(paths[t]);
    free(paths);
    free(list);
    pnpr_cloud_free(&merged);
    pnpr_cloud_free(&mem);
    pnpr_tile_plan_free(&plan);
    remove(in);
    remove(out);
}

/* An explicit distance is taken as given; a halo too small for it is the caller's to refuse. */
static void test_given_distance(void)
{
    pnpr_tile_plan plan;
    memset(&plan, 0, sizeof plan);
    pnpr_components_options o = {0};
    o.distance = 0.25f;
    float d = 0;
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_tile_components_distance("/nonexistent.ply", &plan, &o, 0, &d, &err), PNPR_OK);
    CHECK(d == 0.25f);
    CHECK_STATUS(pnpr_tile_components_distance(NULL, &plan, NULL, 0, &d, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_tile_components_distance("/nonexistent.ply", &plan, NULL, 0, &d, &err), PNPR_ERR_IO);
}

int main(void)
{
    test_equal(SCENE_ISLANDS, 1500, 8, 0);
    test_equal(SCENE_WALL, 3000, 4, 0);
    test_equal(SCENE_EDGE, 1500, 8, 0.2f);
    test_given_distance();
    return pnpr_test_finish("test_segment_tiles");
}
