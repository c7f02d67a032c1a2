/* The analytic scene of `pointnpr bench quality` (bench/quality/), with known answers: ray casts
 * against ground, flat and gabled (and rotated) buildings, trunks, crowns and spheres; the crease
 * edges of the presets (counts, kinds, dihedral angles); the LiDAR scan (size, determinism, range
 * noise, density falling with range, ground sampled up to its border, occlusion shadows, colours,
 * metadata). */
#include "testutil.h"
#include "quality.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

/* A hand-made scene: ground [-10,10]^2, one building, one tree, one sphere, no scanners. */
static void small_scene(pnpr_quality_scene *s, double roof, double yaw)
{
    memset(s, 0, sizeof *s);
    s->has_ground = 1;
    s->ground_min[0] = s->ground_min[1] = -10;
    s->ground_max[0] = s->ground_max[1] = 10;
    s->building_count = 1;
    pnpr_quality_building *b = &s->building[0];
    b->half[0] = 2; b->half[1] = 1; b->wall_height = 3; b->roof_height = roof; b->yaw_deg = yaw;
    s->tree_count = 1;
    pnpr_quality_tree *t = &s->tree[0];
    t->base[0] = -5; t->base[1] = -5; t->trunk_radius = 0.5; t->trunk_height = 3.6;
    t->crown_centre_z = 5; t->crown_radius = 1.5;
    s->sphere_count = 1;
    s->sphere[0].centre[0] = 5; s->sphere[0].centre[1] = 5; s->sphere[0].centre[2] = 2; s->sphere[0].radius = 1;
    pnpr_quality_scene_edges(s);
}

static int cast(const pnpr_quality_scene *s, double ox, double oy, double oz, double dx, double dy, double dz,
                double t_max, pnpr_quality_hit *h)
{
    double o[3] = {ox, oy, oz}, d[3] = {dx, dy, dz};
    memset(h, 0, sizeof *h);
    return pnpr_quality_raycast(s, o, d, t_max, h);
}

static void test_raycast_flat(void)
{
    pnpr_quality_scene s;
    pnpr_quality_hit h;
    small_scene(&s, 0, 0);
    CHECK(cast(&s, 0, 0, 10, 0, 0, -1, 0, &h) && h.kind == PNPR_QUALITY_ROOF);
    CHECK_NEAR(h.t, 7, 1e-9);
    CHECK_NEAR(h.normal[2], 1, 1e-12);
    CHECK(cast(&s, -10, 0, 1, 2, 0, 0, 0, &h) && h.kind == PNPR_QUALITY_WALL); /* direction need not be unit */
    CHECK_NEAR(h.t, 8, 1e-9);
    CHECK_NEAR(h.normal[0], -1, 1e-12);
    CHECK(cast(&s, 5, -5, 10, 0, 0, -1, 0, &h) && h.kind == PNPR_QUALITY_GROUND);
    CHECK_NEAR(h.t, 10, 1e-9);
    CHECK(!cast(&s, 0, 0, 10, 0, 0, -1, 5, &h));            /* t_max before the roof */
    CHECK(!cast(&s, 15, 15, 10, 0, 0, -1, 0, &h));          /* outside the ground rectangle */
    CHECK(!cast(&s, 0, 0, 1, 0, 0, 1, 0, &h));              /* from inside the building, upwards */
    CHECK(!cast(&s, 0, 0, 10, 0, 0, 0, 0, &h));             /* zero direction */
    CHECK(!cast(&s, NAN, 0, 10, 0, 0, -1, 0, &h));          /* non-finite origin */
    CHECK(!cast(&s, -10, 1.5, 1, 1, 0, 0, 0, &h) || h.kind != PNPR_QUALITY_WALL); /* passes beside it */
}

static void test_raycast_gabled_rotated(void)
{
    pnpr_quality_scene s;
    pnpr_quality_hit h;
    small_scene(&s, 1, 0); /* ridge at z = 4 along x, pitch 45 degrees */
    CHECK(cast(&s, 0, 0.5, 10, 0, 0, -1, 0, &h) && h.kind == PNPR_QUALITY_ROOF);
    CHECK_NEAR(h.t, 6.5, 1e-9);                              /* z = 3 + 1 * (1 - 0.5) */
    CHECK_NEAR(h.normal[1], sqrt(0.5), 1e-12);
    CHECK_NEAR(h.normal[2], sqrt(0.5), 1e-12);
    CHECK(cast(&s, 0, -0.25, 10, 0, 0, -1, 0, &h));
    CHECK_NEAR(h.t, 6.25, 1e-9);
    CHECK(cast(&s, 1.9, 0, 10, 0, 0, -1, 0, &h));
    CHECK_NEAR(h.t, 6, 1e-9);                                /* the ridge */
    CHECK(cast(&s, 10, 0, 3.9, -1, 0, 0, 0, &h) && h.kind == PNPR_QUALITY_WALL); /* the gable wall */
    CHECK_NEAR(h.t, 8, 1e-9);
    small_scene(&s, 0, 90); /* footprint now +-1 in x, +-2 in y */
    CHECK(cast(&s, -10, 1.5, 1, 1, 0, 0, 0, &h) && h.kind == PNPR_QUALITY_WALL);
    CHECK_NEAR(h.t, 9, 1e-9);
    CHECK_NEAR(h.normal[0], -1, 1e-12);
    small_scene(&s, 0, 30); /* a ray along the rotated local x axis meets the gable wall at hx = 2 */
    double c = cos(PI / 6), sn = sin(PI / 6);
    CHECK(cast(&s, 10 * c, 10 * sn, 1, -c, -sn, 0, 0, &h) && h.kind == PNPR_QUALITY_WALL);
    CHECK_NEAR(h.t, 8, 1e-9);
    CHECK_NEAR(h.normal[0], c, 1e-12);
    CHECK_NEAR(h.normal[1], sn, 1e-12);
}

static void test_raycast_round(void)
{
    pnpr_quality_scene s;
    pnpr_quality_hit h;
    small_scene(&s, 0, 0);
    CHECK(cast(&s, 5, -5, 2, 0, 1, 0, 0, &h) && h.kind == PNPR_QUALITY_SPHERE && h.index == 0);
    CHECK_NEAR(h.t, 9, 1e-9);
    CHECK_NEAR(h.normal[1], -1, 1e-12);
    CHECK(cast(&s, -10, -5, 1, 1, 0, 0, 0, &h) && h.kind == PNPR_QUALITY_TRUNK);
    CHECK_NEAR(h.t, 4.5, 1e-9);
    CHECK_NEAR(h.normal[0], -1, 1e-12);
    CHECK(cast(&s, -10, -5, 5, 1, 0, 0, 0, &h) && h.kind == PNPR_QUALITY_CROWN);
    CHECK_NEAR(h.t, 3.5, 1e-9);
    CHECK(cast(&s, -5, -5, 20, 0, 0, -1, 0, &h) && h.kind == PNPR_QUALITY_CROWN); /* the crown hides the trunk */
    CHECK_NEAR(h.t, 13.5, 1e-9);
    CHECK(cast(&s, -10, -5, 3.8, 1, 0, 0, 0, &h) && h.kind == PNPR_QUALITY_CROWN); /* above the trunk's top */
}

static void count_kinds(const pnpr_quality_scene *s, int *n)
{
    memset(n, 0, 6 * sizeof *n);
    for (size_t i = 0; i < s->edge_count; i++) n[s->edge[i].kind]++;
}

static void test_edges(void)
{
    pnpr_quality_scene s;
    int n[6];
    small_scene(&s, 0, 0);
    count_kinds(&s, n);
    CHECK_MSG(s.edge_count == 12 && n[PNPR_QUALITY_EDGE_CORNER] == 4 && n[PNPR_QUALITY_EDGE_EAVE] == 4 &&
              n[PNPR_QUALITY_EDGE_FOOT] == 4, "flat box: %zu edges", s.edge_count);
    small_scene(&s, 1, 0);
    count_kinds(&s, n);
    CHECK_MSG(s.edge_count == 15 && n[PNPR_QUALITY_EDGE_RIDGE] == 1 && n[PNPR_QUALITY_EDGE_RAKE] == 4 &&
              n[PNPR_QUALITY_EDGE_EAVE] == 2, "gabled: %zu edges", s.edge_count);
    for (size_t i = 0; i < s.edge_count; i++) {
        const pnpr_quality_segment *e = &s.edge[i];
        if (e->kind == PNPR_QUALITY_EDGE_RIDGE) {
            CHECK_NEAR(e->angle_deg, 90, 1e-9); /* pitch 45 on both sides */
            CHECK_NEAR(e->a[2], 4, 1e-12);
            CHECK_NEAR(fabs(e->b[0] - e->a[0]), 4, 1e-12);
        }
        if (e->kind == PNPR_QUALITY_EDGE_EAVE) CHECK_NEAR(e->angle_deg, 45, 1e-9);
        if (e->kind == PNPR_QUALITY_EDGE_RAKE) CHECK_NEAR(hypot(e->b[1] - e->a[1], e->b[2] - e->a[2]), sqrt(2), 1e-12);
    }
    s.crease_angle_deg = 60; /* the 45-degree eaves are no creases any more */
    pnpr_quality_scene_edges(&s);
    CHECK_MSG(s.edge_count == 13, "crease angle 60: %zu edges", s.edge_count);
    pnpr_quality_scene_init(&s, PNPR_QUALITY_PRESET_SMALL);
    count_kinds(&s, n);
    /* a flat block (12) and two gabled houses (15 each) */
    CHECK_MSG(s.edge_count == 42 && n[PNPR_QUALITY_EDGE_RIDGE] == 2 && n[PNPR_QUALITY_EDGE_RAKE] == 8 &&
              n[PNPR_QUALITY_EDGE_EAVE] == 8 && n[PNPR_QUALITY_EDGE_CORNER] == 12 && n[PNPR_QUALITY_EDGE_FOOT] == 12,
              "small preset: %zu edges", s.edge_count);
    int rotated = 0, gabled = 0;
    for (int i = 0; i < s.building_count; i++) {
        rotated += fmod(fabs(s.building[i].yaw_deg), 90) != 0;
        gabled += s.building[i].roof_height > 0;
    }
    CHECK(rotated >= 1 && gabled >= 1 && s.tree_count >= 3 && s.sphere_count == 1 && s.scanner_count == 7);
}

/* Ground points per square metre in the half ring r0..r1 north of (x, y). */
static double ring_density(const pnpr_cloud *c, const pnpr_quality_scene *s, double x, double y, double r0, double r1)
{
    size_t n = 0;
    for (size_t i = 0; i < c->count; i++) {
        if (c->label[i] != PNPR_QUALITY_GROUND) continue;
        double w[3];
        pnpr_cloud_world(c, i, w);
        double d = hypot(w[0] - s->offset[0] - x, w[1] - s->offset[1] - y);
        n += d >= r0 && d < r1 && w[1] - s->offset[1] > y;
    }
    return (double)n / (0.5 * PI * (r1 * r1 - r0 * r0));
}

static size_t points_near(const pnpr_cloud *c, const pnpr_quality_scene *s, double x, double y, double r)
{
    size_t n = 0;
    for (size_t i = 0; i < c->count; i++) {
        double w[3];
        pnpr_cloud_world(c, i, w);
        n += hypot(w[0] - s->offset[0] - x, w[1] - s->offset[1] - y) < r && fabs(w[2] - s->offset[2]) < 0.1;
    }
    return n;
}

/* How many of the scanners do not see the ground point (x, y, 0). */
static int blocked(const pnpr_quality_scene *s, double x, double y)
{
    int n = 0;
    for (int k = 0; k < s->scanner_count; k++) {
        const double *o = s->scanner[k];
        double d[3] = {x - o[0], y - o[1], -o[2]}, l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        n += pnpr_quality_raycast(s, o, d, l - 0.05, NULL);
    }
    return n;
}

/* The ground is sampled up to its rectangle's border: along each side, every 1 m stretch has a
 * ground point within `reach` of the border (the data's outline is the true one, which the
 * figures count as an outline). Returns the worst stretch's distance. */
static double border_gap(const pnpr_cloud *c, const pnpr_quality_scene *s)
{
    enum { MAX_BINS = 128 };
    double gap[4][MAX_BINS], worst = 0;
    for (int k = 0; k < 4; k++)
        for (int i = 0; i < MAX_BINS; i++) gap[k][i] = INFINITY;
    const double *lo = s->ground_min, *hi = s->ground_max;
    for (size_t i = 0; i < c->count; i++) {
        if (c->label[i] != PNPR_QUALITY_GROUND) continue;
        double w[3];
        pnpr_cloud_world(c, i, w);
        double x = w[0] - s->offset[0], y = w[1] - s->offset[1];
        int bx = (int)floor(x - lo[0]), by = (int)floor(y - lo[1]);
        if (bx < 0 || by < 0 || bx >= MAX_BINS || by >= MAX_BINS) continue;
        double d[4] = {y - lo[1], hi[1] - y, x - lo[0], hi[0] - x};
        int b[4] = {bx, bx, by, by};
        for (int k = 0; k < 4; k++)
            if (d[k] < gap[k][b[k]]) gap[k][b[k]] = d[k];
    }
    int n[4] = {(int)(hi[0] - lo[0]), (int)(hi[0] - lo[0]), (int)(hi[1] - lo[1]), (int)(hi[1] - lo[1])};
    for (int k = 0; k < 4; k++)
        for (int i = 0; i < n[k] && i < MAX_BINS; i++)
            if (gap[k][i] > worst) worst = gap[k][i];
    return worst;
}

static void test_scan(void)
{
    pnpr_quality_scene s;
    pnpr_quality_scene_init(&s, PNPR_QUALITY_PRESET_SMALL);
    pnpr_cloud c = {0}, c2 = {0};
    pnpr_quality_scan_stats st;
    CHECK_STATUS(pnpr_quality_scan(&s, 1, &c, &st), PNPR_OK);
    CHECK_MSG(c.count > 120000 && c.count < 200000, "small scene: %zu points", c.count);
    CHECK(st.points == c.count && c.rgb && c.label && c.src_xyz);
    /* rays evenly spread over the elevation window: its solid angle / step^2 per scanner */
    double step = s.step_deg * PI / 180, window = 2 * PI * (sin(s.elevation_max_deg * PI / 180) - sin(s.elevation_min_deg * PI / 180));
    double rays = s.scanner_count * window / (step * step);
    CHECK_MSG(fabs((double)st.rays - rays) < 0.02 * rays, "%zu rays, %g expected", st.rays, rays);
    size_t sum = 0;
    for (int k = 0; k <= PNPR_QUALITY_UNSEEN; k++) sum += st.per_kind[k];
    CHECK(sum == c.count && st.per_kind[PNPR_QUALITY_WALL] > 1000 && st.per_kind[PNPR_QUALITY_ROOF] > 1000 &&
          st.per_kind[PNPR_QUALITY_CROWN] > 500 && st.per_kind[PNPR_QUALITY_SPHERE] > 100 && st.per_kind[PNPR_QUALITY_TRUNK] > 20);
    CHECK(c.has_viewpoint && c.up_hint == 3);
    for (int a = 0; a < 3; a++) CHECK_NEAR(c.viewpoint[a], s.offset[a] + s.scanner[0][a], 1e-9);
    /* deterministic */
    CHECK_STATUS(pnpr_quality_scan(&s, 1, &c2, NULL), PNPR_OK);
    CHECK(c2.count == c.count && !memcmp(c.src_xyz, c2.src_xyz, 3 * c.count * sizeof *c.src_xyz) &&
          !memcmp(c.rgb, c2.rgb, 3 * c.count));
    pnpr_cloud_free(&c2);
    /* range noise: ground heights within 5 sigma, RMS below sigma (the noise is along the ray);
     * float offsets agree with the exact world doubles */
    double rms = 0, worst = 0, drift = 0, green = 0;
    size_t ng = 0;
    for (size_t i = 0; i < c.count; i++) {
        for (int a = 0; a < 3; a++) {
            double e = fabs(c.origin[a] + c.xyz[3 * i + a] - c.src_xyz[3 * i + a]);
            if (e > drift) drift = e;
        }
        if (c.label[i] != PNPR_QUALITY_GROUND) continue;
        double z = c.src_xyz[3 * i + 2] - s.offset[2];
        rms += z * z;
        if (fabs(z) > worst) worst = fabs(z);
        green += c.rgb[3 * i + 1] > c.rgb[3 * i] && c.rgb[3 * i + 1] > c.rgb[3 * i + 2];
        ng++;
    }
    rms = sqrt(rms / (double)ng);
    CHECK_MSG(rms < s.range_sigma && rms > 0.2 * s.range_sigma && worst < 5 * s.range_sigma,
              "ground height noise: rms %g, worst %g (sigma %g)", rms, worst, s.range_sigma);
    CHECK_MSG(drift < 1e-3, "offsets vs world: %g", drift);
    CHECK_MSG(green == (double)ng, "ground points that are not green: %g of %zu", (double)ng - green, ng);
    /* density falls with range: the tripod's scan alone */
    pnpr_quality_scene tripod = s;
    tripod.scanner_count = 1;
    CHECK_STATUS(pnpr_quality_scan(&tripod, 1, &c2, NULL), PNPR_OK);
    double near = ring_density(&c2, &s, s.scanner[0][0], s.scanner[0][1], 2, 3);
    double far = ring_density(&c2, &s, s.scanner[0][0], s.scanner[0][1], 15, 18);
    CHECK_MSG(near > 20 * far && far > 0, "ground density near the tripod %g, at 15-18 m %g per m^2", near, far);
    pnpr_cloud_free(&c2);
    /* the ground reaches its border everywhere (the old two-scanner scan left 16-20 m unsampled) */
    double gap = border_gap(&c, &s);
    CHECK_MSG(gap < 0.5, "ground border: a 1 m stretch with no ground point within %g m", gap);
    /* occlusion shadows behind the house and the shed (east of them, hidden from every station),
     * ground seen in front of them and behind the block */
    CHECK(blocked(&s, 16.5, 13.5) == s.scanner_count && blocked(&s, 22.75, -7) == s.scanner_count);
    CHECK_MSG(points_near(&c, &s, 16.5, 13.5, 0.6) == 0, "points in the house's shadow: %zu", points_near(&c, &s, 16.5, 13.5, 0.6));
    CHECK_MSG(points_near(&c, &s, 22.75, -7, 0.6) == 0, "points in the shed's shadow: %zu", points_near(&c, &s, 22.75, -7, 0.6));
    CHECK(points_near(&c, &s, 4, 4, 0.6) > 5 && points_near(&c, &s, -14, 18.5, 0.6) > 5);
    pnpr_cloud_free(&c);
}

static void test_ball(void)
{
    pnpr_quality_scene s;
    pnpr_quality_scene_init(&s, PNPR_QUALITY_PRESET_BALL);
    CHECK(s.edge_count == 0 && !s.has_ground && s.sphere_count == 1 && s.building_count == 0);
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_quality_scan(&s, 0, &c, NULL), PNPR_OK);
    CHECK_MSG(c.count > 20000 && c.count < 60000, "ball: %zu points", c.count);
    const double *ctr = s.sphere[0].centre;
    double worst = 0, lowest = INFINITY;
    for (size_t i = 0; i < c.count; i++) {
        double d2 = 0;
        for (int a = 0; a < 3; a++) {
            double e = c.src_xyz[3 * i + a] - s.offset[a] - ctr[a];
            d2 += e * e;
        }
        double e = fabs(sqrt(d2) - s.sphere[0].radius);
        if (e > worst) worst = e;
        if (c.src_xyz[3 * i + 2] - s.offset[2] < lowest) lowest = c.src_xyz[3 * i + 2] - s.offset[2];
    }
    CHECK_MSG(worst < 6 * s.range_sigma, "ball: farthest point %g from the sphere", worst);
    CHECK_MSG(lowest < ctr[2] - 0.5 * s.sphere[0].radius, "ball: sampled down to z %g only", lowest);
    pnpr_cloud_free(&c);
    CHECK_STATUS(pnpr_quality_scan(NULL, 0, &c, NULL), PNPR_ERR_INVALID_ARGUMENT);
}

int main(void)
{
    test_raycast_flat();
    test_raycast_gabled_rotated();
    test_raycast_round();
    test_edges();
    test_scan();
    test_ball();
    return pnpr_test_finish("test_quality_scene");
}
