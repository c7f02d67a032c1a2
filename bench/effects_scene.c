/* Test cloud of the effects benchmark (bench/effects.sh): 64 coloured boxes and thin walls
 * ("planes") on an 8 x 8 grid of ground tiles, 20 x 20 m, written as binary PLY through
 * pnpr_write_file. Cell i (box or wall i and the ground tile under it) gets label i mod S, so
 * the cloud has S segments (S = 64: one per object). Deterministic for a given seed.
 *   effects_scene OUT.ply [--points N] [--segments S] [--seed SEED]
 * Defaults: N = 1000000, S = 64, SEED = 1. */
#include <pointnpr/cloud.h>
#include <pointnpr/io.h>

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define GRID 8
#define CELLS (GRID * GRID)
#define CELL 2.5 /* metres */

typedef struct rng {
    uint64_t s;
} rng;

static uint64_t rng_next(rng *r) /* splitmix64 */
{
    uint64_t z = (r->s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static double rng_uniform(rng *r) { return (double)(rng_next(r) >> 11) * (1.0 / 9007199254740992.0); }

static double rng_normal(rng *r)
{
    double u = rng_uniform(r), v = rng_uniform(r);
    if (u < 1e-300) u = 1e-300;
    return sqrt(-2 * log(u)) * cos(6.283185307179586 * v);
}

typedef struct object {
    double lo[3], hi[3]; /* axis-aligned box; a wall is a box 0.08 m thin */
    double area[5];      /* faces x-, x+, y-, y+, top */
    double area_sum;
    uint8_t rgb[3];
} object;

/* A saturated colour of hue h in [0, 1). */
static void hue_rgb(double h, double v, uint8_t c[3])
{
    double r = fabs(h * 6 - 3) - 1, g = 2 - fabs(h * 6 - 2), b = 2 - fabs(h * 6 - 4);
    double ch[3] = {r, g, b};
    for (int k = 0; k < 3; k++) {
        double x = ch[k] < 0 ? 0 : ch[k] > 1 ? 1 : ch[k];
        c[k] = (uint8_t)lround(255 * v * (0.25 + 0.75 * x));
    }
}

static void make_objects(rng *r, object *o)
{
    for (int i = 0; i < CELLS; i++) {
        double cx = (i % GRID + 0.5) * CELL - GRID * CELL / 2, cy = (i / GRID + 0.5) * CELL - GRID * CELL / 2;
        double w, d, h = 0.5 + 2.5 * rng_uniform(r);
        if (i % 4 == 3) { /* a thin wall, along x or y */
            double len = 1.4 + 0.8 * rng_uniform(r);
            int along_x = (i / 4) % 2;
            w = along_x ? len : 0.08;
            d = along_x ? 0.08 : len;
        } else {
            w = 0.8 + 1.0 * rng_uniform(r);
            d = 0.8 + 1.0 * rng_uniform(r);
        }
        o[i].lo[0] = cx - w / 2; o[i].hi[0] = cx + w / 2;
        o[i].lo[1] = cy - d / 2; o[i].hi[1] = cy + d / 2;
        o[i].lo[2] = 0;          o[i].hi[2] = h;
        o[i].area[0] = o[i].area[1] = d * h;
        o[i].area[2] = o[i].area[3] = w * h;
        o[i].area[4] = w * d;
        o[i].area_sum = 0;
        for (int f = 0; f < 5; f++) o[i].area_sum += o[i].area[f];
        hue_rgb(fmod(i * 0.618033988749895, 1.0), 0.85, o[i].rgb);
    }
}

/* Point j: ground (35%) or the surface of a uniformly chosen object (faces by area). */
static void scene_point(rng *r, const object *o, float p[3], uint8_t c[3], uint32_t *cell)
{
    double q[3];
    if (rng_uniform(r) < 0.35) {
        q[0] = GRID * CELL * (rng_uniform(r) - 0.5);
        q[1] = GRID * CELL * (rng_uniform(r) - 0.5);
        q[2] = 0;
        int gx = (int)floor((q[0] + GRID * CELL / 2) / CELL), gy = (int)floor((q[1] + GRID * CELL / 2) / CELL);
        gx = gx < 0 ? 0 : gx >= GRID ? GRID - 1 : gx;
        gy = gy < 0 ? 0 : gy >= GRID ? GRID - 1 : gy;
        *cell = (uint32_t)(gy * GRID + gx);
        double fx = q[0] * 2, fy = q[1] * 2; /* 0.5 m checker */
        uint8_t v = (((long)floor(fx) + (long)floor(fy)) & 1) ? 150 : 110;
        c[0] = v; c[1] = v; c[2] = (uint8_t)(v - 10);
    } else {
        int i = (int)(rng_uniform(r) * CELLS);
        if (i >= CELLS) i = CELLS - 1;
        const object *b = &o[i];
        double t = rng_uniform(r) * b->area_sum;
        int f = 0;
        while (f < 4 && t >= b->area[f]) t -= b->area[f++];
        double a = rng_uniform(r), e = rng_uniform(r);
        int ax = f < 2 ? 0 : f < 4 ? 1 : 2; /* the face's normal axis */
        int s1 = (ax + 1) % 3, s2 = (ax + 2) % 3;
        q[ax] = (f == 0 || f == 2) ? b->lo[ax] : b->hi[ax];
        q[s1] = b->lo[s1] + a * (b->hi[s1] - b->lo[s1]);
        q[s2] = b->lo[s2] + e * (b->hi[s2] - b->lo[s2]);
        double shade = ax == 2 ? 1.0 : ax == 0 ? 0.8 : 0.65;
        for (int k = 0; k < 3; k++) c[k] = (uint8_t)lround(b->rgb[k] * shade);
        *cell = (uint32_t)i;
    }
    for (int k = 0; k < 3; k++) p[k] = (float)(q[k] + 0.002 * rng_normal(r)); /* 2 mm noise */
}

static int parse_u64(const char *s, unsigned long long lo, unsigned long long hi, unsigned long long *r)
{
    char *end = NULL;
    errno = 0;
    unsigned long long v = strtoull(s, &end, 10);
    if (errno || end == s || *end || s[0] == '-' || v < lo || v > hi) return 0;
    *r = v;
    return 1;
}

static int usage(void)
{
    fprintf(stderr, "usage: effects_scene OUT.ply [--points N] [--segments S] [--seed SEED]\n"
                    "  N: 1..100000000 points (default 1000000); S: 1..64 segments, label = cell mod S\n"
                    "  (default 64); SEED: any unsigned integer (default 1)\n");
    return 2;
}

int main(int argc, char **argv)
{
    unsigned long long n = 1000000, segments = CELLS, seed = 1;
    const char *out = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--points") && i + 1 < argc) {
            if (!parse_u64(argv[++i], 1, 100000000, &n)) return usage();
        } else if (!strcmp(argv[i], "--segments") && i + 1 < argc) {
            if (!parse_u64(argv[++i], 1, CELLS, &segments)) return usage();
        } else if (!strcmp(argv[i], "--seed") && i + 1 < argc) {
            if (!parse_u64(argv[++i], 0, UINT64_MAX, &seed)) return usage();
        } else if (argv[i][0] != '-' && !out) {
            out = argv[i];
        } else {
            return usage();
        }
    }
    if (!out) return usage();

    rng r = {seed};
    object objs[CELLS];
    make_objects(&r, objs);

    pnpr_cloud c = {0};
    pnpr_error err = {0};
    if (pnpr_cloud_alloc(&c, (size_t)n) != PNPR_OK || pnpr_cloud_alloc_rgb(&c) != PNPR_OK ||
        pnpr_cloud_alloc_labels(&c) != PNPR_OK) {
        fprintf(stderr, "effects_scene: out of memory for %llu points\n", n);
        pnpr_cloud_free(&c);
        return 1;
    }
    c.src_coord_type = PNPR_TYPE_FLOAT32;
    for (size_t j = 0; j < c.count; j++) {
        uint32_t cell = 0;
        scene_point(&r, objs, &c.xyz[3 * j], &c.rgb[3 * j], &cell);
        c.label[j] = cell % (uint32_t)segments;
    }
    pnpr_write_options wo = {0};
    wo.comment = "pointnpr bench/effects_scene: 64 boxes and walls on a ground, label = cell mod S";
    if (pnpr_write_file(out, &c, &wo, &err) != PNPR_OK) {
        fprintf(stderr, "effects_scene: %s\n", err.message);
        pnpr_cloud_free(&c);
        return 1;
    }
    fprintf(stderr, "effects_scene: %zu points, %llu segments -> %s\n", c.count, segments, out);
    pnpr_cloud_free(&c);
    return 0;
}
