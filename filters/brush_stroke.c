/* Stroke-based splatting's strokes (Lopes et al. section 3.3; include/pointnpr/brush.h): the
 * Householder tangent frame (3.3.1) and the Gaussian-sum brush textures (3.3.2, eq. 1).
 *
 * Choices the paper leaves open (docs/brush.md): the grid is 3 columns along the stroke (u) of 3
 * rows (9 Gaussians) or 2 rows (6), centred, `dev` apart; eq. (1) divides both factors by sigma_x,
 * a misprint we read as sigma_y for the second; |x|^lambda keeps odd and fractional exponents
 * defined; each Gaussian's amplitude and centre deviate by up to `jitter` (A: that fraction, P0:
 * that fraction of dev, or of sigma when dev is small) and the columns' theta walks by at most
 * theta_dev from 0; the outer 8% of the square fade to 0 so that no stroke ends in a hard edge. */
#include <pointnpr/brush.h>

#include "../core/internal.h"

#include <math.h>
#include <stdint.h>
#include <strings.h>

void pnpr_householder_frame(const float n[3], float r_t[3], float r_b[3])
{
    double x = n[0], y = n[1], z = n[2], len = sqrt(x * x + y * y + z * z);
    if (!(len > 0) || !isfinite(len)) {
        r_t[0] = 0; r_t[1] = 1; r_t[2] = 0;
        r_b[0] = 0; r_b[1] = 0; r_b[2] = 1;
        return;
    }
    double h[3] = {x + len, y, z}; /* max(n_x - |n|, n_x + |n|) = n_x + |n| */
    double hh = h[0] * h[0] + h[1] * h[1] + h[2] * h[2];
    if (!(hh > 1e-12 * len * len)) { /* n = -e_x: h vanishes */
        r_t[0] = 0; r_t[1] = 0; r_t[2] = 1;
        r_b[0] = 0; r_b[1] = 1; r_b[2] = 0;
        return;
    }
    double f = 2.0 / hh;
    for (int a = 0; a < 3; a++) {
        r_t[a] = (float)((a == 1) - f * h[a] * h[1]);
        r_b[a] = (float)((a == 2) - f * h[a] * h[2]);
    }
}

/* The paper's figure 4 c, d, b (theta_dev and jitter are ours: the paper bounds them but gives no
 * values). bristle first, the default: an illustrator's review of the pictures (docs/brush.md)
 * found it the one whose strokes read as paint on stone and foliage alike. */
static const pnpr_brush_preset presets[] = {
    {"bristle", "nine spread Gaussians, separate filaments (paper fig. 4 c)", {1, 0.38f, 2.7f, 0.142f, 0.071f, 9, 10, 0.15f}},
    {"flat", "six Gaussians, a broad flat brush (paper fig. 4 d)", {2.27f, 0.3f, 2.4f, 0.099f, 0.1259f, 6, 10, 0.15f}},
    {"round", "nine close Gaussians, one dense round dab (paper fig. 4 b)", {8, 0.03f, 3, 0.114f, 0.0989f, 9, 10, 0.15f}},
};

_Static_assert(sizeof presets / sizeof presets[0] == PNPR_BRUSH_PRESET_COUNT, "PNPR_BRUSH_PRESET_COUNT");

const pnpr_brush_preset *pnpr_brush_presets(size_t *r_count)
{
    if (r_count) *r_count = sizeof presets / sizeof presets[0];
    return presets;
}

const char *pnpr_brush_preset_list(char *buf, size_t cap, const char *sep)
{
    const char *names[PNPR_BRUSH_PRESET_COUNT];
    for (size_t i = 0; i < PNPR_BRUSH_PRESET_COUNT; i++) names[i] = presets[i].name;
    return pnpr_join_names(buf, cap, sep, names, PNPR_BRUSH_PRESET_COUNT, 0);
}

pnpr_status pnpr_brush_preset_find(const char *name, uint32_t *r_index)
{
    if (!name || !r_index) return PNPR_ERR_INVALID_ARGUMENT;
    for (uint32_t i = 0; i < sizeof presets / sizeof presets[0]; i++)
        if (!strcasecmp(name, presets[i].name)) { *r_index = i; return PNPR_OK; }
    return PNPR_ERR_NOT_FOUND;
}

/* A uniform number in [-1, 1) from (seed, i) (splitmix64). */
static double rand_signed(uint64_t seed, uint64_t i)
{
    uint64_t z = seed * 0x9E3779B97F4A7C15ull + i * 0xBF58476D1CE4E5B9ull + 0x94D049BB133111EBull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (double)(z >> 11) / (double)(1ull << 52) - 1.0;
}

static int shape_ok(const pnpr_brush_shape *s)
{
    return isfinite(s->amplitude) && s->amplitude > 0 && isfinite(s->dev) && s->dev >= 0 && s->dev <= 1 &&
           s->lambda >= 0.5f && s->lambda <= 8 && s->sigma_x > 0 && s->sigma_x <= 1 && s->sigma_y > 0 &&
           s->sigma_y <= 1 && (s->gaussians == 6 || s->gaussians == 9) && isfinite(s->theta_dev) &&
           s->theta_dev >= 0 && s->theta_dev <= 90 && isfinite(s->jitter) && s->jitter >= 0 && s->jitter <= 0.5f;
}

/* One Gaussian of eq. (1) at offset (dx, dy) from its centre, rotated by (c, s) = cos, sin theta. */
static double gaussian(const pnpr_brush_shape *g, double a, double dx, double dy, double c, double s)
{
    double xr = (c * dx - s * dy) / g->sigma_x, yr = (s * dx + c * dy) / g->sigma_y;
    return a * exp(-0.5 * pow(fabs(xr), g->lambda)) * exp(-0.5 * pow(fabs(yr), g->lambda));
}

static double edge_fade(double t)
{
    double e = fmin(t, 1.0 - t) / 0.08;
    if (e >= 1) return 1;
    return e <= 0 ? 0 : e * e * (3 - 2 * e);
}

pnpr_status pnpr_brush_texture(const pnpr_brush_shape *s, uint32_t variant, int w, int h, uint8_t *r_alpha)
{
    if (!s || !r_alpha || w < 1 || h < 1 || w > 1024 || h > 1024 || !shape_ok(s)) return PNPR_ERR_INVALID_ARGUMENT;
    enum { COLS = 3 };
    int rows = s->gaussians == 9 ? 3 : 2;
    double cx[9], cy[9], amp[9], cth[COLS], sth[COLS], theta = 0;
    double step = fmax(s->dev, 0.5 * fmin(s->sigma_x, s->sigma_y)); /* how far a centre may wander */
    const double deg = 3.14159265358979 / 180.0;
    for (int c = 0; c < COLS; c++) {
        theta += s->theta_dev * deg * rand_signed(variant, 100u + (unsigned)c);
        cth[c] = cos(theta);
        sth[c] = sin(theta);
    }
    for (int r = 0, g = 0; r < rows; r++)
        for (int c = 0; c < COLS; c++, g++) {
            cx[g] = 0.5 + (c - 1) * s->dev + s->jitter * step * rand_signed(variant, 3u * (unsigned)g);
            cy[g] = 0.5 + (r - 0.5 * (rows - 1)) * s->dev + s->jitter * step * rand_signed(variant, 3u * (unsigned)g + 1);
            amp[g] = s->amplitude * (1.0 + s->jitter * rand_signed(variant, 3u * (unsigned)g + 2));
        }
    for (int y = 0; y < h; y++) {
        double v = (y + 0.5) / h;
        for (int x = 0; x < w; x++) {
            double u = (x + 0.5) / w, z = 0;
            for (int g = 0; g < rows * COLS; g++)
                z += gaussian(s, amp[g], u - cx[g], v - cy[g], cth[g % COLS], sth[g % COLS]);
            z = fmin(z, 1.0) * edge_fade(u) * edge_fade(v);
            r_alpha[(size_t)y * (size_t)w + (size_t)x] = (uint8_t)lrint(z * 255.0);
        }
    }
    return PNPR_OK;
}
