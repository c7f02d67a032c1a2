/* Terrestrial-LiDAR sampling of the analytic scene: from every scanner position, rays over a
 * regular angular grid (constant elevation step; the azimuth step widens as 1/cos(elevation), so
 * that the rays are spread evenly over the sphere as in a scan thinned to an even angular
 * spacing; a small seeded jitter for the beam's wobble); the first hit is a point, moved along
 * the ray by Gaussian range noise (and, in foliage, by an exponential penetration depth). Density
 * therefore falls with the square of the range and with the incidence angle, and every object
 * casts an occlusion shadow. */
#include "quality.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double QPI = 3.14159265358979323846;

/* Deterministic uniform [0,1) and normal numbers (splitmix64), caller-owned state. */
static double uni(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return (double)((z ^ (z >> 31)) >> 11) * (1.0 / 9007199254740992.0);
}

static double gauss(uint64_t *s)
{
    double u = uni(s), v = uni(s);
    return sqrt(-2 * log(u > 1e-300 ? u : 1e-300)) * cos(2 * QPI * v);
}

/* Growable point buffer (world doubles, colours, kinds). */
typedef struct buffer {
    double *world;
    uint8_t *rgb, *kind;
    size_t count, cap;
} buffer;

static int buffer_push(buffer *b, const double w[3], const uint8_t rgb[3], uint8_t kind)
{
    if (b->count == b->cap) {
        size_t cap = b->cap ? 2 * b->cap : 65536;
        double *w2 = realloc(b->world, cap * 3 * sizeof *w2);
        if (!w2) return 0;
        b->world = w2;
        uint8_t *c2 = realloc(b->rgb, cap * 3);
        if (!c2) return 0;
        b->rgb = c2;
        uint8_t *k2 = realloc(b->kind, cap);
        if (!k2) return 0;
        b->kind = k2;
        b->cap = cap;
    }
    memcpy(b->world + 3 * b->count, w, 3 * sizeof *w);
    memcpy(b->rgb + 3 * b->count, rgb, 3);
    b->kind[b->count++] = kind;
    return 1;
}

static void buffer_free(buffer *b)
{
    free(b->world);
    free(b->rgb);
    free(b->kind);
    memset(b, 0, sizeof *b);
}

static uint8_t clamp8(double v) { return (uint8_t)(v < 0 ? 0 : (v > 255 ? 255 : v + 0.5)); }

/* One ray: its point (if any) into the buffer. Returns 0 when out of memory. */
static int scan_ray(const pnpr_quality_scene *s, const double *o, const double v[3], uint64_t *rng, buffer *b,
                    pnpr_quality_scan_stats *st)
{
    pnpr_quality_hit h;
    st->rays++;
    if (!pnpr_quality_raycast(s, o, v, s->max_range, &h)) return 1;
    double t = h.t + s->range_sigma * gauss(rng);
    if (h.kind == PNPR_QUALITY_CROWN) t -= s->foliage_depth * log(1 - uni(rng) * 0.999);
    double p[3] = {o[0] + h.t * v[0], o[1] + h.t * v[1], o[2] + h.t * v[2]}, w[3];
    uint8_t rgb[3];
    pnpr_quality_colour(s, &h, p, rgb);
    double grain = h.kind == PNPR_QUALITY_CROWN ? 18 : 6; /* leaves vary more than walls */
    for (int a = 0; a < 3; a++) {
        w[a] = s->offset[a] + o[a] + t * v[a];
        rgb[a] = clamp8(rgb[a] + grain * (2 * uni(rng) - 1));
    }
    st->points++;
    st->per_kind[h.kind]++;
    return buffer_push(b, w, rgb, (uint8_t)h.kind);
}

/* The azimuth step of the elevation row `el_deg`: `step` divided by cos(elevation), so that the
 * rays are evenly spread over the sphere (a scanner's constant azimuth step crowds them towards
 * the poles; surveys thin that out), at most 360 degrees (one ray at the pole). */
static double azimuth_step(double el_deg, double step)
{
    double c = cos(el_deg * QPI / 180);
    return c * 360 > step ? step / c : 360;
}

static int scan_from(const pnpr_quality_scene *s, int k, buffer *b, pnpr_quality_scan_stats *st)
{
    uint64_t rng = s->seed * 0x2545F4914F6CDD1Dull + (uint64_t)k * 0x9E3779B97F4A7C15ull;
    const double step = s->step_deg > 0 ? s->step_deg : 0.2, jitter = 0.1 * step;
    const long n_el = (long)floor((s->elevation_max_deg - s->elevation_min_deg) / step) + 1;
    for (long e = 0; e < n_el; e++) {
        double row = s->elevation_min_deg + e * step, az_step = azimuth_step(row, step);
        long n_az = (long)floor(360.0 / az_step + 0.5);
        for (long a = 0; a < n_az; a++) {
            double el = (row + jitter * (2 * uni(&rng) - 1)) * QPI / 180;
            double az = (a * az_step + jitter * (2 * uni(&rng) - 1)) * QPI / 180;
            double v[3] = {cos(el) * cos(az), cos(el) * sin(az), sin(el)};
            if (!scan_ray(s, s->scanner[k], v, &rng, b, st)) return 0;
        }
    }
    return 1;
}

pnpr_status pnpr_quality_scan(const pnpr_quality_scene *s, int want_labels, pnpr_cloud *r_cloud,
                              pnpr_quality_scan_stats *r_stats)
{
    if (!s || !r_cloud) return PNPR_ERR_INVALID_ARGUMENT;
    pnpr_cloud_free(r_cloud);
    pnpr_quality_scan_stats st;
    memset(&st, 0, sizeof st);
    buffer b;
    memset(&b, 0, sizeof b);
    for (int k = 0; k < s->scanner_count; k++)
        if (!scan_from(s, k, &b, &st)) { buffer_free(&b); return PNPR_ERR_OUT_OF_MEMORY; }
    pnpr_status status = pnpr_cloud_alloc(r_cloud, b.count);
    if (status == PNPR_OK) status = pnpr_cloud_set_world(r_cloud, b.world);
    if (status == PNPR_OK) status = pnpr_cloud_alloc_rgb(r_cloud);
    if (status == PNPR_OK && want_labels) status = pnpr_cloud_alloc_labels(r_cloud);
    if (status != PNPR_OK) { buffer_free(&b); pnpr_cloud_free(r_cloud); return status; }
    if (b.count) memcpy(r_cloud->rgb, b.rgb, 3 * b.count);
    for (size_t i = 0; want_labels && i < b.count; i++) r_cloud->label[i] = b.kind[i];
    r_cloud->src_xyz = b.world; /* ownership moves to the cloud: exact world doubles */
    r_cloud->src_coord_type = PNPR_TYPE_FLOAT64;
    b.world = NULL;
    buffer_free(&b);
    if (s->scanner_count > 0) {
        r_cloud->has_viewpoint = 1;
        for (int a = 0; a < 3; a++) r_cloud->viewpoint[a] = s->offset[a] + s->scanner[0][a];
    }
    r_cloud->up_hint = 3;
    if (r_stats) *r_stats = st;
    return PNPR_OK;
}
