/* Clouds in tiles (tiles.h) against the in-memory run, on a generated 2.5D scan with known
 * features: a terrain of ridges and steps, colour regions, points in random order. Every tile's
 * core points that it certifies must have exactly the in-memory results (bit for bit: normals
 * with a viewpoint, degree, class, confidence, direction, spacing), every point must be certified
 * with the automatic halo, and the merge must give the whole cloud back in input order. Also: the
 * plan's partition, the merge's refusals, the reader's filter on inputs it does not take, and a
 * folder of tiles joined one at a time. */
#include "testutil.h"

#include <pointnpr/features.h>
#include <pointnpr/io.h>
#include <pointnpr/options.h>
#include <pointnpr/props.h>
#include <pointnpr/tiles.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SIDE 190 /* SIDE^2 points over [0, 10]^2 */

static double height(double x, double y)
{
    double ridge = 0.8 - 0.6 * fabs(x - 3.3);       /* a roof ridge along y at x = 3.3 */
    double step = y > 6.1 ? 0.5 : 0;                /* a step across x */
    return fmax(ridge, 0) + step + 0.05 * sin(x * 1.7) * cos(y * 1.3);
}

enum { SCENE_JITTERED, SCENE_GEOREF, SCENE_LATTICE };

/* GEOREF: world coordinates offset by (5e5, 4.2e6, 100), kept as doubles (written as double).
 * LATTICE: no jitter: every neighbourhood has ties, which the kNN orders by input index. */
static void make_scene(pnpr_cloud *c, int kind)
{
    const double jitter = kind == SCENE_LATTICE ? 0 : 0.4;
    const size_t n = (size_t)SIDE * SIDE;
    pnpr_test_rng rng = {12345};
    CHECK_STATUS(pnpr_cloud_alloc(c, n), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(c), PNPR_OK);
    size_t *order = malloc(n * sizeof *order);
    for (size_t i = 0; i < n; i++) order[i] = i;
    for (size_t i = n - 1; i > 0; i--) { /* random file order */
        size_t j = (size_t)(pnpr_test_uniform(&rng) * (double)(i + 1));
        size_t t = order[i]; order[i] = order[j]; order[j] = t;
    }
    for (size_t i = 0; i < n; i++) {
        size_t g = order[i];
        double x = 10.0 * ((double)(g % SIDE) + jitter * pnpr_test_uniform(&rng)) / SIDE;
        double y = 10.0 * ((double)(g / SIDE) + jitter * pnpr_test_uniform(&rng)) / SIDE;
        c->xyz[3 * i] = (float)x;
        c->xyz[3 * i + 1] = (float)y;
        c->xyz[3 * i + 2] = (float)height(x, y);
        int red = (x - 7) * (x - 7) + (y - 3) * (y - 3) < 2.0; /* a red disc on grey */
        c->rgb[3 * i] = red ? 200 : 120;
        c->rgb[3 * i + 1] = red ? 40 : 120;
        c->rgb[3 * i + 2] = red ? 40 : 120;
    }
    free(order);
    if (kind != SCENE_GEOREF) return;
    double *w = malloc(3 * n * sizeof *w);
    const double off[3] = {5e5, 4.2e6, 100};
    for (size_t i = 0; i < 3 * n; i++) w[i] = (double)c->xyz[i] + off[i % 3];
    CHECK_STATUS(pnpr_cloud_alloc_src_xyz(c), PNPR_OK);
    memcpy(c->src_xyz, w, 3 * n * sizeof *w);
    c->src_coord_type = PNPR_TYPE_FLOAT64;
    CHECK_STATUS(pnpr_cloud_set_world(c, w), PNPR_OK);
    free(w);
}

static pnpr_features_options feature_options(int viewpoint)
{
    pnpr_features_options fo = pnpr_features_defaults();
    fo.threshold = 0.3f;
    fo.has_viewpoint = viewpoint;
    fo.viewpoint[0] = 5;
    fo.viewpoint[1] = 5;
    fo.viewpoint[2] = 50;
    fo.threads = 2;
    return fo;
}

/* Point i of a against point j of b: every property bit for bit, dithering points as none;
 * normals too when `normals` (else up to their sign). */
static int same_point(const pnpr_cloud *a, size_t i, const pnpr_cloud *b, size_t j, int normals)
{
    float flip[3] = {-b->normal[3 * j], -b->normal[3 * j + 1], -b->normal[3 * j + 2]};
    if (memcmp(a->xyz + 3 * i, b->xyz + 3 * j, 12) ||
        (memcmp(a->normal + 3 * i, b->normal + 3 * j, 12) && (normals || memcmp(a->normal + 3 * i, flip, 12))))
        return 0;
    for (size_t p = 0; p < a->prop_count; p++) {
        const pnpr_property *pa = &a->props[p], *pb = pnpr_cloud_find_property(b, pa->name);
        if (!pb) return 0;
        size_t sz = pnpr_type_size(pa->type);
        const uint8_t *va = (const uint8_t *)pa->data + i * sz, *vb = (const uint8_t *)pb->data + j * sz;
        if (!strcmp(pa->name, PNPR_PROP_FEATURE_CLASS)) {
            if ((*va == PNPR_CLASS_DITHER ? 0 : *va) != (*vb == PNPR_CLASS_DITHER ? 0 : *vb)) return 0;
        } else if (memcmp(va, vb, sz)) {
            if (getenv("TILES_DEBUG")) fprintf(stderr, "%s differs\n", pa->name);
            return 0;
        }
    }
    return 1;
}

static const char *scratch(const char *name, char *buf, size_t cap)
{
    snprintf(buf, cap, "%s/tiles_%s", PNPR_TEST_SCRATCH, name);
    return buf;
}

/* Runs every tile of the plan as a job would, writing tile files; checks each tile's certified
 * core points against the in-memory cloud `ref`; returns the points certified. */
static size_t run_tiles(const char *in, const pnpr_tile_plan *plan, const pnpr_cloud *ref, char (*paths)[512], int seams)
{
    size_t certified = 0, wrong = 0;
    for (size_t t = 0; t < plan->count; t++) {
        pnpr_cloud c = {0};
        uint8_t *core = NULL;
        pnpr_error err = {0};
        CHECK_STATUS(pnpr_tile_read(in, &plan->grid, &plan->tiles[t], plan->halo, NULL, &c, &core, &err), PNPR_OK);
        pnpr_features_options fo = feature_options(!seams);
        pnpr_features_stats stats;
        CHECK_STATUS(pnpr_compute_features(&c, &fo, &stats), PNPR_OK);
        double box[4];
        pnpr_tile_box(&plan->grid, &plan->tiles[t], plan->halo, box);
        uint8_t *exact = malloc(c.count + 1);
        size_t uncertain = 99;
        CHECK_STATUS(pnpr_tile_certify(&c, core, box, stats.k_used, 2, exact, &uncertain), PNPR_OK);
        const uint32_t *src = pnpr_cloud_find_property(&c, PNPR_PROP_SOURCE_INDEX)->data;
        size_t cores = 0, sure = 0;
        for (size_t i = 0; i < c.count; i++) {
            if (!core[i]) continue;
            cores++;
            if (!exact[i]) continue;
            sure++;
            wrong += !same_point(ref, src[i], &c, i, !seams);
        }
        certified += sure;
        CHECK(cores == plan->tiles[t].points && uncertain == cores - sure);
        if (seams) { /* the halo stays, marked, for the merge's seams */
            pnpr_property *tc = NULL;
            CHECK_STATUS(pnpr_cloud_add_property(&c, PNPR_PROP_TILE_CORE, PNPR_TYPE_UINT8, &tc), PNPR_OK);
            memcpy(tc->data, core, c.count);
        } else {
            CHECK_STATUS(pnpr_cloud_keep(&c, core, NULL), PNPR_OK);
        }
        snprintf(paths[t], sizeof paths[t], "%s/tiles_part%02zu.ply", PNPR_TEST_SCRATCH, t);
        CHECK_STATUS(pnpr_write_file(paths[t], &c, NULL, &err), PNPR_OK);
        free(exact);
        free(core);
        pnpr_cloud_free(&c);
    }
    CHECK_MSG(wrong == 0, "%zu certified points differ from the in-memory run", wrong);
    return certified;
}

/* seams: without a viewpoint: each tile orients its normals by its own propagation and the merge
 * makes them agree (their halos kept); the merged normals must still equal the run in memory. */
static void test_tiles_equal(int kind, int seams)
{
    static const char *const names[] = {"scene.ply", "georef.ply", "lattice.ply"};
    const int georef = kind == SCENE_GEOREF;
    char in[512], out[512];
    pnpr_cloud scene = {0}, ref = {0}, merged = {0};
    pnpr_error err = {0};
    make_scene(&scene, kind);
    CHECK_STATUS(pnpr_write_file(scratch(names[kind], in, sizeof in), &scene, NULL, &err), PNPR_OK);
    CHECK_STATUS(pnpr_read_file(in, NULL, &ref, &err), PNPR_OK);
    pnpr_features_options fo = feature_options(!seams);
    CHECK_STATUS(pnpr_compute_features(&ref, &fo, NULL), PNPR_OK);

    pnpr_tile_plan_options po = {0};
    po.tile_points = 6000;
    pnpr_tile_plan plan;
    CHECK_STATUS(pnpr_tile_plan_make(in, &po, &plan, &err), PNPR_OK);
    uint64_t sum = 0, most = 0;
    for (size_t t = 0; t < plan.count; t++) {
        sum += plan.tiles[t].points;
        if (plan.tiles[t].points > most) most = plan.tiles[t].points;
    }
    CHECK(plan.points == scene.count && sum == scene.count);
    CHECK_MSG(plan.count >= 6 && most <= 6000, "%zu tiles, largest %llu", plan.count, (unsigned long long)most);
    /* spacing of a 190 x 190 jittered grid over 10 x 10: 10/190; the origin: the box's centre */
    CHECK_NEAR(plan.spacing, 10.0 / SIDE, 0.15 * 10.0 / SIDE);
    for (int a = 0; a < 3 && georef; a++) CHECK(plan.grid.origin[a] == ref.origin[a]);
    CHECK(georef ? ref.origin[1] > 4.2e6 : ref.origin[1] == 0); /* float files: no origin, floats as read */

    char (*paths)[512] = calloc(plan.count, sizeof *paths);
    size_t certified = run_tiles(in, &plan, &ref, paths, seams);
    CHECK_MSG(certified == scene.count, "%zu of %zu points certified with the automatic halo", certified, scene.count);

    const char **list = malloc(plan.count * sizeof *list);
    for (size_t t = 0; t < plan.count; t++) list[t] = paths[t];
    if (seams) { /* tile 2 as if its propagation had chosen the other sign: the seams turn it back */
        pnpr_cloud t2 = {0};
        CHECK_STATUS(pnpr_read_file(paths[2], NULL, &t2, &err), PNPR_OK);
        for (size_t i = 0; i < 3 * t2.count; i++) t2.normal[i] = -t2.normal[i];
        CHECK_STATUS(pnpr_write_file(paths[2], &t2, NULL, &err), PNPR_OK);
        pnpr_cloud_free(&t2);
        CHECK_STATUS(pnpr_tile_merge(list, plan.count, plan.points, 0, scratch("unseamed.ply", out, sizeof out), NULL, &err),
                     PNPR_OK);
        CHECK_STATUS(pnpr_read_file(out, NULL, &merged, &err), PNPR_OK);
        size_t turned = 0;
        for (size_t i = 0; i < merged.count && i < ref.count; i++) turned += !same_point(&ref, i, &merged, i, 1);
        CHECK_MSG(turned == plan.tiles[2].points, "without seams: %zu points turned, tile 2 has %llu", turned,
                  (unsigned long long)plan.tiles[2].points);
        pnpr_cloud_free(&merged);
    }
    CHECK_STATUS(pnpr_tile_merge(list, plan.count, plan.points, seams, scratch("merged.ply", out, sizeof out), NULL, &err),
                 PNPR_OK);
    CHECK_STATUS(pnpr_read_file(out, NULL, &merged, &err), PNPR_OK);
    size_t differ = merged.count == ref.count ? 0 : 1;
    for (size_t i = 0; i < merged.count && i < ref.count; i++) differ += !same_point(&ref, i, &merged, i, 1);
    size_t signs = 0;
    for (size_t i = 0; i < merged.count && i < ref.count; i++) signs += !same_point(&ref, i, &merged, i, 0);
    CHECK_MSG(differ == 0, "%zu merged points differ (seams %d; %zu also up to sign)", differ, seams, signs);
    CHECK(pnpr_cloud_find_property(&merged, PNPR_PROP_SOURCE_INDEX) == NULL);

    /* a missing tile, a tile twice: refused, the result not written */
    remove(out);
    CHECK_STATUS(pnpr_tile_merge(list, plan.count - 1, plan.points, seams, out, NULL, &err), PNPR_ERR_FORMAT);
    CHECK(strstr(err.message, "is in no tile") != NULL);
    list[1] = list[0];
    CHECK_STATUS(pnpr_tile_merge(list, plan.count, plan.points, seams, out, NULL, &err), PNPR_ERR_FORMAT);
    CHECK(strstr(err.message, "comes twice") != NULL);
    FILE *f = fopen(out, "rb");
    CHECK(f == NULL);
    if (f) fclose(f);
    CHECK(pnpr_test_temporaries(PNPR_TEST_SCRATCH, "tiles_merged.ply") == 0);
    free(list);
    free(paths);
    pnpr_tile_plan_free(&plan);
    pnpr_cloud_free(&scene);
    pnpr_cloud_free(&ref);
    pnpr_cloud_free(&merged);
}

/* --tiles under a memory limit: tiles of at most pnpr_tile_points_for_memory points, which falls
 * with the limit in proportion, and none below 1000 points. */
static void test_memory_limit(void)
{
    char in[512];
    pnpr_error err = {0};
    const size_t limit = 2u << 20;
    uint64_t per2m = pnpr_tile_points_for_memory(limit, 15, 16), per4m = pnpr_tile_points_for_memory(2 * limit, 15, 16);
    /* a tile's job takes about 200 to 400 bytes a point (cloud, features, certification, halo) */
    CHECK_MSG(per2m > limit / 400 && per2m < limit / 200, "%llu points in 2 MiB", (unsigned long long)per2m);
    CHECK(per4m >= 2 * per2m - 1 && per4m <= 2 * per2m + 1);
    CHECK(pnpr_tile_points_for_memory(100000, 15, 16) == 0);
    pnpr_tile_plan_options po = {0};
    po.memory_limit = limit;
    pnpr_tile_plan plan;
    CHECK_STATUS(pnpr_tile_plan_make(scratch("scene.ply", in, sizeof in), &po, &plan, &err), PNPR_OK);
    uint64_t most = 0;
    for (size_t t = 0; t < plan.count; t++) most = plan.tiles[t].points > most ? plan.tiles[t].points : most;
    /* the scene's file: 15 bytes a point (float x y z, rgb) and its header */
    CHECK(plan.tile_points == per2m);
    CHECK_MSG(plan.count >= 4 && most <= per2m, "%zu tiles, largest %llu, at most %llu", plan.count,
              (unsigned long long)most, (unsigned long long)per2m);
    pnpr_tile_plan_free(&plan);
    po.memory_limit = 50000;
    CHECK_STATUS(pnpr_tile_plan_make(in, &po, &plan, &err), PNPR_ERR_OUT_OF_MEMORY);
    CHECK(strstr(err.message, "leaves no room") != NULL);
}

/* One point at 1e7 beside the 10 x 10 scene: the plan's grid still covers the scene (cells under a
 * tenth of a unit, not 1e7 / 256), so the tiles keep their size; the far point goes to an edge
 * tile, which does not certify it. */
static void test_far_outlier(void)
{
    char in[512];
    pnpr_cloud scene = {0}, c = {0};
    pnpr_error err = {0};
    make_scene(&scene, SCENE_JITTERED);
    CHECK_STATUS(pnpr_cloud_alloc(&c, scene.count + 1), PNPR_OK);
    memcpy(c.xyz, scene.xyz, 3 * scene.count * sizeof(float));
    c.xyz[3 * scene.count] = c.xyz[3 * scene.count + 1] = 1e7f;
    CHECK_STATUS(pnpr_write_file(scratch("far.ply", in, sizeof in), &c, NULL, &err), PNPR_OK);
    pnpr_tile_plan_options po = {0};
    po.tile_points = 6000;
    pnpr_tile_plan plan;
    CHECK_STATUS(pnpr_tile_plan_make(in, &po, &plan, &err), PNPR_OK);
    uint64_t most = 0;
    for (size_t t = 0; t < plan.count; t++) most = plan.tiles[t].points > most ? plan.tiles[t].points : most;
    CHECK_MSG(plan.grid.cell[0] < 0.1 && plan.count >= 6 && most <= 6000, "cell %g, %zu tiles, largest %llu",
              plan.grid.cell[0], plan.count, (unsigned long long)most);
    CHECK_NEAR(plan.spacing, 10.0 / SIDE, 0.15 * 10.0 / SIDE);
    pnpr_tile_plan_free(&plan);
    pnpr_cloud_free(&scene);
    pnpr_cloud_free(&c);
}

/* A halo of nothing: the points near a tile's edge cannot be certified, and are not. */
static void test_small_halo(void)
{
    char in[512];
    pnpr_error err = {0};
    pnpr_tile_plan_options po = {0};
    po.tile_points = 6000;
    po.halo = 1e-9;
    pnpr_tile_plan plan;
    CHECK_STATUS(pnpr_tile_plan_make(scratch("scene.ply", in, sizeof in), &po, &plan, &err), PNPR_OK);
    pnpr_cloud c = {0};
    uint8_t *core = NULL;
    CHECK_STATUS(pnpr_tile_read(in, &plan.grid, &plan.tiles[0], plan.halo, NULL, &c, &core, &err), PNPR_OK);
    pnpr_features_options fo = feature_options(1);
    pnpr_features_stats stats;
    CHECK_STATUS(pnpr_compute_features(&c, &fo, &stats), PNPR_OK);
    double box[4];
    pnpr_tile_box(&plan.grid, &plan.tiles[0], plan.halo, box);
    size_t uncertain = 0;
    CHECK_STATUS(pnpr_tile_certify(&c, core, box, stats.k_used, 1, NULL, &uncertain), PNPR_OK);
    /* at least the points within one spacing of the tile's inner edges */
    CHECK_MSG(uncertain > plan.tiles[0].points / 20 && uncertain < plan.tiles[0].points,
              "%zu of %llu uncertain", uncertain, (unsigned long long)plan.tiles[0].points);
    free(core);
    pnpr_cloud_free(&c);
    pnpr_tile_plan_free(&plan);
}

static int keep_all(void *user, uint64_t index, const double p[3])
{
    (void)user;
    (void)p;
    return index % 2 == 0;
}

/* The filter on an ascii PLY and on other formats: refused with a message; on binary PLY the
 * even points; an empty file plans one tile. */
static void test_filter_inputs(void)
{
    char path[512];
    pnpr_cloud c = {0}, r = {0};
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_test_plane(&c, 5, 4, 0.1, NULL), PNPR_OK);
    pnpr_write_options wo = {0};
    wo.encoding = PNPR_PLY_ASCII;
    CHECK_STATUS(pnpr_write_file(scratch("ascii.ply", path, sizeof path), &c, &wo, &err), PNPR_OK);
    pnpr_read_options ro = {0};
    ro.keep = keep_all;
    CHECK_STATUS(pnpr_read_file(path, &ro, &r, &err), PNPR_ERR_UNSUPPORTED);
    CHECK(strstr(err.message, "binary") != NULL && r.count == 0);
    CHECK_STATUS(pnpr_write_file(scratch("plane.pcd", path, sizeof path), &c, NULL, &err), PNPR_OK);
    CHECK_STATUS(pnpr_read_file(path, &ro, &r, &err), PNPR_ERR_UNSUPPORTED);
    CHECK_STATUS(pnpr_write_file(scratch("plane.ply", path, sizeof path), &c, NULL, &err), PNPR_OK);
    CHECK_STATUS(pnpr_read_file(path, &ro, &r, &err), PNPR_OK);
    CHECK(r.count == 10 && r.xyz[3] == c.xyz[6] && r.xyz[3 * 9 + 1] == c.xyz[3 * 18 + 1]);
    pnpr_cloud_free(&r);
    pnpr_cloud_free(&c);
    /* lists before the vertices (then a fixed element): where the vertices start is not known */
    static const char lists_first[] = "ply\nformat binary_little_endian 1.0\nelement face 1\n"
                                      "property list uchar int vertex_indices\nelement extra 1\nproperty uchar a\n"
                                      "element vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n"
                                      "\1\0\0\0\0\7\0\0\200\77\0\0\0\100\0\0\100\100";
    CHECK_STATUS(pnpr_read_ply_memory(lists_first, sizeof lists_first - 1, NULL, &r, &err), PNPR_OK);
    CHECK(r.count == 1 && r.xyz[0] == 1 && r.xyz[1] == 2 && r.xyz[2] == 3);
    pnpr_cloud_free(&r);
    CHECK_STATUS(pnpr_read_ply_memory(lists_first, sizeof lists_first - 1, &ro, &r, &err), PNPR_ERR_UNSUPPORTED);
    pnpr_tile_plan plan;
    CHECK_STATUS(pnpr_write_file(scratch("empty.ply", path, sizeof path), &c, NULL, &err), PNPR_OK);
    CHECK_STATUS(pnpr_tile_plan_make(path, NULL, &plan, &err), PNPR_OK);
    CHECK(plan.points == 0 && plan.count == 1 && plan.halo == 0);
    pnpr_tile_plan_free(&plan);
}

/* ---- a folder of tiles joined one at a time (pnpr_join_ply) ---------------------------------- */

typedef struct index_range { uint64_t begin, end; } index_range;

static int keep_range(void *user, uint64_t index, const double p[3])
{
    (void)p;
    const index_range *r = user;
    return index >= r->begin && index < r->end;
}

static unsigned char *file_bytes(const char *path, size_t *r_size)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    pnpr_mem_sink m = {0};
    unsigned char buf[65536];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, f)) > 0) CHECK(pnpr_mem_sink_write(&m, buf, n) == 0);
    fclose(f);
    *r_size = m.size;
    return m.data;
}

/* Where a PLY's body starts: after "end_header" on a line of its own (a property line may end in
 * "end_header" too). */
static size_t header_end(const unsigned char *b, size_t n)
{
    for (size_t i = 0; i + 12 <= n; i++)
        if (!memcmp(b + i, "\nend_header\n", 12)) return i + 12;
    return 0;
}

/* Three parts of the georeferenced scene (one empty) joined: the records equal those of the parts
 * joined in memory and written, the header has the padding line more, the world coordinates read
 * back are the scene's. Refused, naming the input, with the target left as it was: other
 * properties, faces, an unreadable input; a device as the output. */
static void test_join(void)
{
    char whole[512], parts[3][512], out[512], other[512], mesh[512];
    pnpr_cloud c = {0}, part = {0}, joined = {0}, back = {0};
    pnpr_error err = {0};
    make_scene(&c, SCENE_GEOREF);
    CHECK_STATUS(pnpr_write_file(scratch("join_whole.ply", whole, sizeof whole), &c, NULL, &err), PNPR_OK);
    const index_range ranges[3] = {{0, 12000}, {12000, 12000}, {12000, c.count}};
    const char *inputs[4];
    for (int i = 0; i < 3; i++) {
        char name[32];
        snprintf(name, sizeof name, "join_part%d.ply", i);
        pnpr_read_options ro = {0};
        ro.keep = keep_range;
        ro.keep_user = (void *)&ranges[i];
        CHECK_STATUS(pnpr_read_file(whole, &ro, &part, &err), PNPR_OK);
        CHECK(part.count == ranges[i].end - ranges[i].begin);
        CHECK_STATUS(pnpr_write_file(scratch(name, parts[i], sizeof parts[i]), &part, NULL, &err), PNPR_OK);
        CHECK_STATUS(pnpr_cloud_append(&joined, &part), PNPR_OK);
        pnpr_cloud_free(&part);
        inputs[i] = parts[i];
    }
    pnpr_mem_sink mem = {0};
    CHECK_STATUS(pnpr_write_ply_stream(pnpr_mem_sink_write, &mem, &joined, NULL, &err), PNPR_OK);
    uint64_t points = 0;
    CHECK_STATUS(pnpr_join_ply(inputs, 3, scratch("join_out.ply", out, sizeof out), NULL, &points, &err), PNPR_OK);
    size_t n = 0;
    unsigned char *b = file_bytes(out, &n);
    size_t hm = header_end(mem.data, mem.size), hj = b ? header_end(b, n) : 0;
    CHECK(points == c.count && hm > 0 && hj > hm);
    CHECK_MSG(b && n - hj == mem.size - hm && !memcmp(b + hj, mem.data + hm, n - hj), "joined records differ from in memory");
    /* the header: the in-memory one with the padding comment before the element */
    const char *pad = b ? strstr((const char *)b, "comment joined: room for the count") : NULL;
    CHECK(pad != NULL && (size_t)(pad - (const char *)b) < hj);
    if (pad) {
        size_t at = (size_t)(pad - (const char *)b), len = (size_t)(strchr(pad, '\n') + 1 - pad);
        CHECK(hj - len == hm && !memcmp(b, mem.data, at) && !memcmp(b + at + len, mem.data + at, hm - at));
    }
    CHECK_STATUS(pnpr_read_file(out, NULL, &back, &err), PNPR_OK);
    size_t off = 0;
    for (size_t i = 0; i < c.count && back.count == c.count; i++) {
        double w[3], v[3];
        pnpr_cloud_world(&c, i, w);
        pnpr_cloud_world(&back, i, v);
        off += memcmp(w, v, sizeof w) != 0;
    }
    CHECK_MSG(back.count == c.count && off == 0, "%zu of %zu points moved", off, back.count);
    pnpr_cloud_free(&back);
    /* refusals: the target keeps its bytes and nothing else is left */
    pnpr_cloud plane = {0};
    CHECK_STATUS(pnpr_test_plane(&plane, 4, 4, 0.1, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_normals(&plane), PNPR_OK);
    CHECK_STATUS(pnpr_write_file(scratch("join_other.ply", other, sizeof other), &plane, NULL, &err), PNPR_OK);
    FILE *f = fopen(scratch("join_mesh.ply", mesh, sizeof mesh), "w");
    CHECK(f != NULL);
    if (f) {
        fputs("ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
              "property uchar red\nproperty uchar green\nproperty uchar blue\nelement face 1\n"
              "property list uchar int vertex_indices\nend_header\n0 0 0 1 2 3\n1 0 0 1 2 3\n0 1 0 1 2 3\n3 0 1 2\n", f);
        fclose(f);
    }
    const char *bad[3][2] = {{parts[0], other}, {parts[0], mesh}, {parts[0], "/nonexistent/tile.ply"}};
    for (int k = 0; k < 3; k++) {
        err.message[0] = '\0';
        CHECK_STATUS(pnpr_join_ply(bad[k], 2, out, NULL, &points, &err), k == 2 ? PNPR_ERR_IO : PNPR_ERR_UNSUPPORTED);
        CHECK_MSG(strstr(err.message, bad[k][1]) != NULL, "the message names %s: %s", bad[k][1], err.message);
        size_t n2 = 0;
        unsigned char *b2 = file_bytes(out, &n2);
        CHECK(b2 && n2 == n && !memcmp(b2, b, n) && points == 0);
        free(b2);
    }
    /* a property named end_header (its line ends as the header does) and one after it */
    char prop_parts[2][512];
    const char *prop_inputs[2] = {prop_parts[0], prop_parts[1]};
    pnpr_cloud pj = {0};
    for (int i = 0; i < 2; i++) {
        pnpr_cloud pc = {0};
        CHECK_STATUS(pnpr_test_plane(&pc, 3 + i, 3, 0.1, NULL), PNPR_OK);
        CHECK_STATUS(pnpr_cloud_add_property(&pc, "end_header", PNPR_TYPE_FLOAT32, NULL), PNPR_OK);
        CHECK_STATUS(pnpr_cloud_add_property(&pc, "q", PNPR_TYPE_UINT8, NULL), PNPR_OK);
        pnpr_property *q = pnpr_cloud_find_property(&pc, "q");
        for (size_t k = 0; q && k < pc.count; k++) ((uint8_t *)q->data)[k] = (uint8_t)(10 * i + k);
        char name[32];
        snprintf(name, sizeof name, "join_prop%d.ply", i);
        CHECK_STATUS(pnpr_write_file(scratch(name, prop_parts[i], sizeof prop_parts[i]), &pc, NULL, &err), PNPR_OK);
        CHECK_STATUS(pnpr_cloud_append(&pj, &pc), PNPR_OK);
        pnpr_cloud_free(&pc);
    }
    pnpr_mem_sink pm = {0};
    CHECK_STATUS(pnpr_write_ply_stream(pnpr_mem_sink_write, &pm, &pj, NULL, &err), PNPR_OK);
    CHECK_STATUS(pnpr_join_ply(prop_inputs, 2, out, NULL, &points, &err), PNPR_OK);
    size_t np = 0;
    unsigned char *bp = file_bytes(out, &np);
    size_t hp = bp ? header_end(bp, np) : 0, hpm = header_end(pm.data, pm.size);
    CHECK_MSG(points == 21 && bp && np - hp == pm.size - hpm && !memcmp(bp + hp, pm.data + hpm, np - hp),
              "a property named end_header: %llu points", (unsigned long long)points);
    free(bp);
    free(pm.data);
    pnpr_cloud_free(&pj);
    /* an input without points (a text file has no columns then) is skipped */
    char empty_xyz[512], normals_xyz[512];
    f = fopen(scratch("join_empty.xyz", empty_xyz, sizeof empty_xyz), "w");
    if (f) fclose(f);
    f = fopen(scratch("join_normals.xyz", normals_xyz, sizeof normals_xyz), "w");
    if (f) {
        fputs("0 0 0 0 0 1\n1 0 0 0 0 1\n", f);
        fclose(f);
    }
    const char *with_empty[2] = {empty_xyz, normals_xyz};
    pnpr_join_options jo = {0};
    jo.read.columns = "x,y,z,nx,ny,nz";
    CHECK_STATUS(pnpr_join_ply(with_empty, 2, out, &jo, &points, &err), PNPR_OK);
    CHECK(points == 2);
    CHECK_STATUS(pnpr_read_file(out, NULL, &back, &err), PNPR_OK);
    CHECK(back.count == 2 && back.normal && back.normal[2] == 1);
    pnpr_cloud_free(&back);
    CHECK_STATUS(pnpr_join_ply(inputs, 3, "/dev/null", NULL, NULL, &err), PNPR_ERR_UNSUPPORTED);
    CHECK(strstr(err.message, "regular file") != NULL);
    /* an input as the output: refused before anything is read, the input as it was */
    size_t n0 = 0, n1 = 0;
    unsigned char *b0 = file_bytes(parts[2], &n0);
    CHECK(pnpr_join_ply(inputs, 3, parts[2], NULL, NULL, &err) != PNPR_OK && strstr(err.message, parts[2]) != NULL);
    unsigned char *b1 = file_bytes(parts[2], &n1);
    CHECK(b0 && b1 && n0 == n1 && !memcmp(b0, b1, n0));
    free(b0);
    free(b1);
    CHECK_STATUS(pnpr_join_ply(inputs, 0, out, NULL, NULL, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_join_ply(NULL, 2, out, NULL, NULL, &err), PNPR_ERR_INVALID_ARGUMENT);
    free(b);
    free(mem.data);
    pnpr_cloud_free(&plane);
    pnpr_cloud_free(&joined);
    pnpr_cloud_free(&c);
}

int main(void)
{
    test_tiles_equal(SCENE_JITTERED, 0);
    test_tiles_equal(SCENE_GEOREF, 0);
    test_tiles_equal(SCENE_LATTICE, 0);
    test_tiles_equal(SCENE_JITTERED, 1);
    test_memory_limit();
    test_far_outlier();
    test_small_halo();
    test_filter_inputs();
    test_join();
    return pnpr_test_finish("test_tiles");
}
