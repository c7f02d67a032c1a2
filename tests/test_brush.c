/* Stroke-based splatting without GL (include/pointnpr/brush.h), known answers: Householder frames
 * (orthonormal, right-handed, continuous away from -e_x, the defined frames at the singularity),
 * the Gaussian-sum textures of the presets, the preprocessing on a grid (size = sqrt 2 h for k 8:
 * mean (1 + sqrt 2) h / 2 plus std (sqrt 2 - 1) h / 2), clusters of two colours, normals within a
 * cluster, degenerate clouds, the cluster shapes, bad options. */
#include "testutil.h"

#include <pointnpr/brush.h>
#include <pointnpr/options.h>
#include <pointnpr/plan.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

static double dot3(const float *a, const float *b) { return (double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2]; }

static void check_frame(const float n[3])
{
    float t[3], b[3];
    pnpr_householder_frame(n, t, b);
    CHECK_NEAR(dot3(t, t), 1, 1e-5);
    CHECK_NEAR(dot3(b, b), 1, 1e-5);
    CHECK_NEAR(dot3(t, b), 0, 1e-5);
    CHECK_NEAR(dot3(t, n), 0, 1e-5);
    CHECK_NEAR(dot3(b, n), 0, 1e-5);
    /* right-handed: t x b = n */
    float c[3] = {t[1] * b[2] - t[2] * b[1], t[2] * b[0] - t[0] * b[2], t[0] * b[1] - t[1] * b[0]};
    CHECK_NEAR(dot3(c, n), 1, 1e-5);
}

static void random_unit(pnpr_test_rng *rng, float n[3])
{
    double x = pnpr_test_normal(rng), y = pnpr_test_normal(rng), z = pnpr_test_normal(rng), l = sqrt(x * x + y * y + z * z);
    n[0] = (float)(x / l); n[1] = (float)(y / l); n[2] = (float)(z / l);
}

static void test_householder(void)
{
    pnpr_test_rng rng = {42};
    for (int i = 0; i < 2000; i++) {
        float n[3];
        random_unit(&rng, n);
        check_frame(n);
    }
    const float axes[6][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, -1, 0}, {0, 0, -1}, {-0.999f, 0.0447f, 0}};
    for (int i = 0; i < 6; i++) {
        float l = (float)sqrt(dot3(axes[i], axes[i])), n[3] = {axes[i][0] / l, axes[i][1] / l, axes[i][2] / l};
        check_frame(n);
    }
    /* n = e_x: H is the reflection through the plane x = 0 ... t = e_y, b = e_z */
    float t[3], b[3];
    pnpr_householder_frame((const float[3]){1, 0, 0}, t, b);
    CHECK_NEAR(t[1], 1, 1e-6);
    CHECK_NEAR(b[2], 1, 1e-6);
    /* the singular direction -e_x: the documented frame (e_z, e_y) */
    pnpr_householder_frame((const float[3]){-1, 0, 0}, t, b);
    CHECK(t[0] == 0 && t[1] == 0 && t[2] == 1 && b[0] == 0 && b[1] == 1 && b[2] == 0);
    /* zero and non-finite normals: (e_y, e_z) */
    pnpr_householder_frame((const float[3]){0, 0, 0}, t, b);
    CHECK(t[1] == 1 && b[2] == 1);
    pnpr_householder_frame((const float[3]){NAN, 0, 1}, t, b);
    CHECK(t[1] == 1 && b[2] == 1);
    /* continuity: normals 0.5 degrees apart, both at least 30 degrees from -e_x, give tangents
     * within 2 degrees (the frame turns at most by the angle times 1/cos^2(half the angle to -e_x)) */
    double worst = 0;
    for (int i = 0; i < 5000; i++) {
        float n[3], m[3], d[3], t2[3], b2[3];
        random_unit(&rng, n);
        if (n[0] < -0.866f) continue;
        random_unit(&rng, d);
        double k = dot3(d, n);
        for (int a = 0; a < 3; a++) d[a] -= (float)(k * n[a]);
        double dl = sqrt(dot3(d, d)), ang = 0.5 * 3.14159265358979 / 180;
        for (int a = 0; a < 3; a++) m[a] = (float)(n[a] * cos(ang) + d[a] / dl * sin(ang));
        if (m[0] < -0.866f) continue;
        pnpr_householder_frame(n, t, b);
        pnpr_householder_frame(m, t2, b2);
        double c = dot3(t, t2) / sqrt(dot3(t, t) * dot3(t2, t2));
        double deg = acos(c > 1 ? 1 : c) * 180 / 3.14159265358979;
        if (deg > worst) worst = deg;
    }
    CHECK_MSG(worst < 2.0, "tangents of normals 0.5 deg apart differ by %.3f deg", worst);
    /* near the singularity the frame turns fast: 0.5 degrees there turn it by much more */
    float n1[3] = {-0.99999f, 0.00447f, 0}, n2[3] = {-0.99999f, 0, 0.00447f}, t2[3], b2[3];
    pnpr_householder_frame(n1, t, b);
    pnpr_householder_frame(n2, t2, b2);
    CHECK(dot3(t, t2) < 0.5);
}

static uint8_t texel(const uint8_t *a, int w, double u, double v)
{
    int x = (int)(u * w), y = (int)(v * w);
    return a[y * w + x];
}

static void test_textures(void)
{
    size_t np;
    const pnpr_brush_preset *p = pnpr_brush_presets(&np);
    CHECK(np == PNPR_BRUSH_PRESET_COUNT);
    uint32_t idx = 99;
    CHECK_STATUS(pnpr_brush_preset_find("Bristle", &idx), PNPR_OK);
    CHECK(idx < np && !strcmp(p[idx].name, "bristle"));
    CHECK_STATUS(pnpr_brush_preset_find("sponge", &idx), PNPR_ERR_NOT_FOUND);
    enum { W = 64 };
    uint8_t a[W * W], b[W * W];
    /* round (fig. 4 b): A = 8 saturates the centre; the border is faded out */
    CHECK_STATUS(pnpr_brush_preset_find("round", &idx), PNPR_OK);
    CHECK_STATUS(pnpr_brush_texture(&p[idx].shape, 0, W, W, a), PNPR_OK);
    CHECK(texel(a, W, 0.5, 0.5) == 255);
    CHECK(a[0] == 0 && a[W - 1] == 0 && a[W * W - 1] == 0);
    CHECK(texel(a, W, 0.05, 0.5) < 10); /* 0.45 from the centre: beyond the dab */
    /* bristle (fig. 4 c): three filaments along u (rows dev = 0.38 apart), paper between them */
    CHECK_STATUS(pnpr_brush_preset_find("bristle", &idx), PNPR_OK);
    CHECK_STATUS(pnpr_brush_texture(&p[idx].shape, 3, W, W, a), PNPR_OK);
    int on = texel(a, W, 0.5, 0.5), off = texel(a, W, 0.5, 0.31);
    CHECK_MSG(on > 150 && off < on / 2, "bristle: filament %d, between filaments %d", on, off);
    /* the variant seeds the randomness alone */
    CHECK_STATUS(pnpr_brush_texture(&p[idx].shape, 3, W, W, b), PNPR_OK);
    CHECK(!memcmp(a, b, sizeof a));
    CHECK_STATUS(pnpr_brush_texture(&p[idx].shape, 4, W, W, b), PNPR_OK);
    CHECK(memcmp(a, b, sizeof a) != 0);
    /* bad shapes and sizes */
    pnpr_brush_shape s = p[0].shape;
    CHECK_STATUS(pnpr_brush_texture(&s, 0, 0, W, a), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_brush_texture(&s, 0, 2048, 4, a), PNPR_ERR_INVALID_ARGUMENT);
    s.gaussians = 7;
    CHECK_STATUS(pnpr_brush_texture(&s, 0, W, W, a), PNPR_ERR_INVALID_ARGUMENT);
    s = p[0].shape;
    s.lambda = NAN;
    CHECK_STATUS(pnpr_brush_texture(&s, 0, W, W, a), PNPR_ERR_INVALID_ARGUMENT);
    s = p[0].shape;
    s.sigma_y = 0;
    CHECK_STATUS(pnpr_brush_texture(&s, 0, W, W, a), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_brush_texture(NULL, 0, W, W, a), PNPR_ERR_INVALID_ARGUMENT);
}

/* A plane grid of nx x ny points (point j * nx + i at column i, row j), spacing h, the left half
 * of the columns red and the right half blue. */
static void two_colour_plane(pnpr_cloud *c, size_t nx, size_t ny, double h)
{
    CHECK_STATUS(pnpr_test_plane(c, nx, ny, h, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(c), PNPR_OK);
    for (size_t i = 0; i < c->count; i++) {
        int left = i % nx < nx / 2;
        uint8_t *p = c->rgb + 3 * i;
        p[0] = left ? 220 : 20; p[1] = 30; p[2] = left ? 20 : 220;
    }
}

static void test_prepare_grid(void)
{
    const double h = 0.01;
    pnpr_cloud c = {0};
    two_colour_plane(&c, 30, 20, h);
    pnpr_brush_stats st;
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_brush_prepare(&c, NULL, &st, &err), PNPR_OK);
    CHECK(pnpr_brush_cloud_ready(&c));
    CHECK_MSG(st.clusters == 2, "%zu clusters", st.clusters);
    CHECK(st.normals_computed == 1);
    const pnpr_property *ps = pnpr_cloud_find_property(&c, PNPR_PROP_BRUSH_SIZE);
    const pnpr_property *pc = pnpr_cloud_find_property(&c, PNPR_PROP_BRUSH_CLUSTER);
    CHECK(ps && ps->type == PNPR_TYPE_FLOAT32 && pc && pc->type == PNPR_TYPE_UINT32);
    const float *size = ps->data;
    const uint32_t *cl = pc->data;
    size_t interior = 0;
    for (size_t i = 0; i < c.count; i++) {
        size_t col = i % 30, row = i / 30;
        CHECK(cl[i] == cl[col < 15 ? 0 : 29]); /* point 0 is left, point 29 right */
        CHECK_NEAR(fabs(c.normal[3 * i + 2]), 1, 1e-4);
        if (col >= 3 && col <= 26 && row >= 3 && row <= 16) {
            CHECK_NEAR(size[i], sqrt(2.0) * h, 1e-6);
            interior++;
        }
    }
    CHECK(cl[0] != cl[29]);
    CHECK(interior == 24 * 14);
    /* a given eps: mean + eps */
    pnpr_brush_options o = {0};
    o.eps = (float)(0.5 * h);
    CHECK_STATUS(pnpr_brush_prepare(&c, &o, NULL, &err), PNPR_OK);
    size = pnpr_cloud_find_property(&c, PNPR_PROP_BRUSH_SIZE)->data;
    CHECK_NEAR(size[5 * 30 + 10], (1 + sqrt(2.0)) / 2 * h + 0.5 * h, 1e-6);
    /* bad options name themselves */
    o = (pnpr_brush_options){0};
    o.k = PNPR_BRUSH_K_MAX + 1;
    memset(&err, 0, sizeof err);
    CHECK_STATUS(pnpr_brush_prepare(&c, &o, NULL, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_MSG(strstr(err.message, "brush") && strstr(err.message, "k"), "message: %s", err.message);
    o = (pnpr_brush_options){0};
    o.normal_radius = NAN;
    CHECK_STATUS(pnpr_brush_prepare(&c, &o, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    pnpr_cloud_free(&c);
}

/* The normals of a cluster do not lean over a fold into the other cluster: two half planes at 90
 * degrees (an L in the xz plane), one red and one blue, meet at the fold; within the cluster a
 * point next to the fold still gets its own plane's normal. */
static void test_normals_per_cluster(void)
{
    const double h = 0.01;
    const size_t nx = 12, ny = 10, n = 2 * nx * ny;
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_cloud_alloc(&c, n), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(&c), PNPR_OK);
    size_t i = 0;
    for (size_t y = 0; y < ny; y++)
        for (size_t x = 0; x < nx; x++, i++) { /* floor: z = 0, x >= 0 */
            c.xyz[3 * i] = (float)(x * h); c.xyz[3 * i + 1] = (float)(y * h); c.xyz[3 * i + 2] = 0;
            c.rgb[3 * i] = 220; c.rgb[3 * i + 1] = 30; c.rgb[3 * i + 2] = 20;
        }
    for (size_t y = 0; y < ny; y++)
        for (size_t z = 1; z <= nx; z++, i++) { /* wall: x = -h/2, z > 0 */
            c.xyz[3 * i] = (float)(-0.5 * h); c.xyz[3 * i + 1] = (float)(y * h); c.xyz[3 * i + 2] = (float)(z * h);
            c.rgb[3 * i] = 20; c.rgb[3 * i + 1] = 30; c.rgb[3 * i + 2] = 220;
        }
    CHECK_STATUS(pnpr_brush_prepare(&c, NULL, NULL, NULL), PNPR_OK);
    size_t y5 = 5 * nx;
    CHECK_NEAR(fabs(c.normal[3 * y5 + 2]), 1, 1e-3);               /* floor point at the fold */
    CHECK_NEAR(fabs(c.normal[3 * (nx * ny + y5)]), 1, 1e-3);       /* wall point at the fold */
    pnpr_cloud_free(&c);
}

static void test_degenerate(void)
{
    pnpr_cloud c = {0};
    pnpr_brush_stats st;
    CHECK_STATUS(pnpr_brush_prepare(&c, NULL, &st, NULL), PNPR_OK); /* empty */
    CHECK(st.clusters == 0);
    CHECK_STATUS(pnpr_brush_prepare(NULL, NULL, NULL, NULL), PNPR_ERR_INVALID_ARGUMENT);
    /* one point; then duplicates and a NaN point: no size, no normal, no crash */
    CHECK_STATUS(pnpr_cloud_alloc(&c, 1), PNPR_OK);
    CHECK_STATUS(pnpr_brush_prepare(&c, NULL, &st, NULL), PNPR_OK);
    CHECK(((const float *)pnpr_cloud_find_property(&c, PNPR_PROP_BRUSH_SIZE)->data)[0] == 0);
    CHECK_STATUS(pnpr_cloud_alloc(&c, 12), PNPR_OK); /* all at the origin, the last NaN */
    c.xyz[33] = NAN;
    CHECK_STATUS(pnpr_brush_prepare(&c, NULL, &st, NULL), PNPR_OK);
    const float *size = pnpr_cloud_find_property(&c, PNPR_PROP_BRUSH_SIZE)->data;
    for (size_t i = 0; i < 12; i++) CHECK(size[i] == 0 && c.normal[3 * i + 2] == 0);
    /* the cloud's normals are kept unless asked */
    pnpr_cloud_free(&c);
    CHECK_STATUS(pnpr_test_plane(&c, 8, 8, 1, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_normals(&c), PNPR_OK);
    for (size_t i = 0; i < c.count; i++) c.normal[3 * i] = 1;
    CHECK_STATUS(pnpr_brush_prepare(&c, NULL, &st, NULL), PNPR_OK);
    CHECK(st.normals_computed == 0 && c.normal[0] == 1);
    pnpr_brush_options o = {0};
    o.recompute_normals = 1;
    CHECK_STATUS(pnpr_brush_prepare(&c, &o, &st, NULL), PNPR_OK);
    CHECK(st.normals_computed == 1 && fabs(c.normal[2]) > 0.999f);
    /* far coordinates: sizes relative to the origin's offsets stay exact */
    double off[3] = {5e6, 4e6, 300};
    CHECK_STATUS(pnpr_test_plane(&c, 10, 10, 0.05, off), PNPR_OK);
    CHECK_STATUS(pnpr_brush_prepare(&c, NULL, NULL, NULL), PNPR_OK);
    size = pnpr_cloud_find_property(&c, PNPR_PROP_BRUSH_SIZE)->data;
    CHECK_NEAR(size[5 * 10 + 5], sqrt(2.0) * 0.05, 1e-5);
    pnpr_cloud_free(&c);
}

static void test_cluster_shapes(void)
{
    /* cluster 7: a strip of 40 x 2 points (long); cluster 3: a 10 x 10 square; cluster 9: 5 points
     * in a square pattern (small: two layers); one NaN point */
    enum { N = 80 + 100 + 5 + 1 };
    float xyz[3 * N];
    uint32_t cl[N];
    size_t i = 0;
    for (int y = 0; y < 2; y++)
        for (int x = 0; x < 40; x++, i++) { xyz[3 * i] = (float)x; xyz[3 * i + 1] = (float)y; xyz[3 * i + 2] = 0; cl[i] = 7; }
    for (int y = 0; y < 10; y++)
        for (int x = 0; x < 10; x++, i++) { xyz[3 * i] = 100.0f + (float)x; xyz[3 * i + 1] = (float)y; xyz[3 * i + 2] = 0; cl[i] = 3; }
    const float five[5][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {0.5f, 0.5f}};
    for (int k = 0; k < 5; k++, i++) { xyz[3 * i] = 200 + five[k][0]; xyz[3 * i + 1] = five[k][1]; xyz[3 * i + 2] = 0; cl[i] = 9; }
    xyz[3 * i] = NAN; xyz[3 * i + 1] = 0; xyz[3 * i + 2] = 0; cl[i] = 3;
    float stretch[N];
    uint8_t layers[N];
    CHECK_STATUS(pnpr_brush_cluster_shapes(xyz, cl, N, 64, stretch, layers), PNPR_OK);
    CHECK(stretch[0] == PNPR_BRUSH_STRETCH_MAX && layers[0] == 1);   /* 40 x 2: capped */
    CHECK_NEAR(stretch[80], 1, 1e-4);                                  /* square */
    CHECK(layers[80] == 1);
    CHECK_NEAR(stretch[180], 1, 1e-4);
    CHECK(layers[180] == 2);                                           /* 5 < 64 points */
    CHECK(stretch[N - 1] == 1 && layers[N - 1] == 1);                  /* NaN point */
    CHECK_STATUS(pnpr_brush_cluster_shapes(NULL, cl, N, 64, stretch, layers), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_brush_cluster_shapes(NULL, NULL, 0, 64, NULL, NULL), PNPR_OK);
}

/* The plan asks for the brush stage until the cloud carries its outputs. */
static void test_plan(void)
{
    pnpr_cloud c = {0};
    two_colour_plane(&c, 10, 10, 0.1);
    pnpr_plan_request req = {0};
    req.styles = 1u << PNPR_STYLE_BRUSH;
    pnpr_plan p;
    CHECK_STATUS(pnpr_plan_make(&req, &c, &p), PNPR_OK);
    CHECK(p.brush == 1 && p.brush_why != NULL && p.want == 0);
    CHECK_STATUS(pnpr_brush_prepare(&c, NULL, NULL, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_plan_make(&req, &c, &p), PNPR_OK);
    CHECK(p.brush == 0);
    req.styles = 1u << PNPR_STYLE_POINTS;
    pnpr_cloud_free(&c);
    two_colour_plane(&c, 10, 10, 0.1);
    CHECK_STATUS(pnpr_plan_make(&req, &c, &p), PNPR_OK);
    CHECK(p.brush == 0);
    pnpr_cloud_free(&c);
    char buf[64];
    CHECK(!strcmp(pnpr_brush_preset_list(buf, sizeof buf, " | "), "bristle | flat | round"));
    CHECK(!strcmp(pnpr_brush_preset_list(buf, 9, ", "), "bristle,")); /* truncated to fit */
    CHECK(!strcmp(pnpr_style_list(buf, sizeof buf, ",", 1u << PNPR_STYLE_LINES | 1u << PNPR_STYLE_POINTS),
                  "sketchy,stipple,cartoon,painterly,brush,hierarchy"));
    CHECK(!strcmp(pnpr_style_list(buf, 1, ",", 0), ""));
    pnpr_style s;
    CHECK_STATUS(pnpr_style_from_name("Brush", &s), PNPR_OK);
    CHECK(s == PNPR_STYLE_BRUSH && !strcmp(pnpr_style_name(s), "brush"));
    CHECK(pnpr_style_outline_default(PNPR_STYLE_BRUSH, NULL) == 0);
}

int main(void)
{
    test_householder();
    test_textures();
    test_prepare_grid();
    test_normals_per_cluster();
    test_degenerate();
    test_cluster_shapes();
    test_plan();
    return pnpr_test_finish("test_brush");
}
