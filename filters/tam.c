/* Tonal art maps (include/pointnpr/hierarchy.h): the stroke textures of the hierarchy style, one
 * image per tone (light to dark) and per scale, generated without GL. After Praun, Hoppe, Webb and
 * Finkelstein, "Real-Time Hatching" (SIGGRAPH 2001): the strokes of a tone are also in every darker
 * tone (nesting in tone) and the strokes of a coarse image are also in the finer images of its tone
 * (nesting in scale), each stroke the same width in pixels at every scale, so that the screen
 * density of a tone stays put as a texture is minified. Chi & Lee (sec. 4.2) assign a TAM to each
 * stroke node and pick its image by the light (tone, the row) and by the projected size (scale,
 * the column; the view-dependent traversal of 4.2.2 only needs the finest level); they leave the
 * TAMs to the user, so the three kinds here are ours:
 *   - hatch: Praun's nested pencil hatching,
 *   - dots: a halftone grid of discs (Chi & Lee's fig. 11 c),
 *   - paint: a brush dab with bristle streaks (their watercolour and painterly examples).
 *
 * Each texture is one splat: u (columns) runs along the stroke direction, v (rows) across. Choices
 * the papers leave open:
 *   - every kind is multiplied by a soft round footprint (1 up to 0.7 of the radius, a smoothstep
 *     to 0 at the radius, 0 beyond, radius measured at the pixel centres mapped onto -1..1) so
 *     that overlapping splats blend without square edges; "core" below means radius < 0.7;
 *   - one table of target core coverages per tone, shared by hatch and dots (tone_target);
 *   - hatch: Praun pick each next stroke as the best of random candidates; we take a fixed ordered
 *     list instead (jittered golden-ratio positions spread any prefix of it evenly across the
 *     splat, which is what the best-fit search buys) and add its strokes in order while that
 *     brings the core coverage closer to the target. Strokes are 1 pixel wide at every level
 *     (antialiased by a tent of one pixel, ends likewise), at most 5 degrees off their axis (8 drew zigzags),
 *     60-100% of the side long; ink composites "over" (1 - (1 - a)(1 - b)). Tones 0-2 hatch along
 *     u only; from tone 3 the strokes alternate between a second list across (along v) and the
 *     first, starting with the cross-hatch;
 *   - dots: 4 x 4 dots across at every level (the pattern scales with the texture); each disc is
 *     supersampled 4 x 4 per pixel. pi r^2 / c^2 (cell side c) ignores how the core cuts the grid,
 *     so the radius is bisected on the measured core coverage (the discs may overlap for the
 *     darkest tone: the union counts);
 *   - paint: 0.85 coverage at tone 0 with rows varying by +-0.03 (bristle streaks along u, a
 *     two-octave 1D value noise over v averaged over each row), the streaks widening linearly
 *     to 0.45 .. 1.0 at tone 5; the streaks are normalised to -1..1 at every level, so a distant
 *     dab keeps its grain. */
#include <pointnpr/hierarchy.h>

#include <math.h>
#include <stdint.h>
#include <string.h>
#include <strings.h>

enum {
    MAX_PIXELS = PNPR_TAM_SIZE * PNPR_TAM_SIZE,
    MAX_STROKES = 1024, /* per list: far more than the darkest tone needs at the finest level */
    CROSS_TONE = 3,     /* the first tone with cross-hatching */
    DOTS_ACROSS = 4,    /* dots across the side at every level */
    DOT_SUB = 4,        /* supersamples per pixel and axis */
    ROW_SUB = 8         /* noise samples averaged over one row (paint) */
};

#define CORE_RADIUS 0.7          /* the footprint is 1 inside, smoothstep to 0 at radius 1 */
#define STROKE_WIDTH 1.0         /* pixels, at every level */
#define STROKE_TILT_DEG 5.0      /* at most this far off the stroke's axis */
#define STROKE_MIN_LENGTH 0.6    /* of the side; the longest is the side */
#define STROKE_MARGIN 0.06       /* strokes' positions across: 0.06 .. 0.94 of the side */
#define GOLDEN 0.6180339887498949
#define TAM_PI 3.14159265358979323846

/* The target mean coverage of the footprint's core for tones 0..5 (hatch and dots): roughly even
 * steps in lightness, the lightest a sparse hatching, the darkest just below where 1-pixel strokes
 * and touching dots stop reading as strokes or dots. */
static const double tone_target[PNPR_TAM_TONES] = {0.08, 0.18, 0.30, 0.44, 0.60, 0.78};

static const char *const tam_names[PNPR_TAM_COUNT_] = {"paint", "hatch", "dots"};

/* Seeds of the fixed pseudo-random sequences (arbitrary constants). */
static const uint64_t SEED_HATCH = 0x5EED0001u, SEED_CROSS = 0x5EED0002u, SEED_NOISE = 0x5EED0003u;

/* A uniform number in [0, 1) from (seed, i) (splitmix64). */
static double unit_rand(uint64_t seed, uint64_t i)
{
    uint64_t z = seed * 0x9E3779B97F4A7C15ull + i * 0xBF58476D1CE4E5B9ull + 0x94D049BB133111EBull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (double)(z >> 11) / (double)(1ull << 53);
}

static double clamp01(double x) { return x < 0 ? 0 : x > 1 ? 1 : x; }

/* ---- the footprint ---------------------------------------------------------------------------- */

/* Distance of pixel (x, y)'s centre from the texture's centre, the square mapped onto -1..1. */
static double pixel_radius(int s, int x, int y)
{
    double a = (2.0 * x + 1.0) / s - 1.0, b = (2.0 * y + 1.0) / s - 1.0;
    return sqrt(a * a + b * b);
}

static double footprint(double r)
{
    if (r <= CORE_RADIUS) return 1;
    if (r >= 1) return 0;
    double t = (r - CORE_RADIUS) / (1 - CORE_RADIUS);
    return 1 - t * t * (3 - 2 * t);
}

/* The mean of cov over the core (the core of every side >= 2 holds pixels). */
static double core_mean(int s, const float *cov)
{
    double sum = 0;
    int n = 0;
    for (int y = 0; y < s; y++)
        for (int x = 0; x < s; x++)
            if (pixel_radius(s, x, y) < CORE_RADIUS) { sum += cov[y * s + x]; n++; }
    return n ? sum / n : 0;
}

/* cov times the footprint as bytes. */
static void store(int s, const float *cov, uint8_t *out)
{
    for (int y = 0; y < s; y++)
        for (int x = 0; x < s; x++)
            out[y * s + x] = (uint8_t)lrint(255.0 * clamp01(cov[y * s + x] * footprint(pixel_radius(s, x, y))));
}

/* ---- hatch ------------------------------------------------------------------------------------ */

typedef struct stroke {
    double x0, y0; /* start, pixels */
    double dx, dy; /* unit direction */
    double len;    /* pixels */
} stroke;

/* Candidate k of the list along u (cross 0) or along v (cross 1) at side s. */
static void stroke_make(int cross, int k, int s, stroke *r)
{
    uint64_t seed = cross ? SEED_CROSS : SEED_HATCH, i = 4 * (uint64_t)k;
    double g = (cross ? 0.25 : 0.5) + k * GOLDEN + 0.02 * (unit_rand(seed, i) - 0.5);
    double across = STROKE_MARGIN + (1 - 2 * STROKE_MARGIN) * (g - floor(g));
    double tilt = (2 * unit_rand(seed, i + 1) - 1) * STROKE_TILT_DEG * TAM_PI / 180;
    double length = STROKE_MIN_LENGTH + (1 - STROKE_MIN_LENGTH) * unit_rand(seed, i + 2);
    double start = (1 - length) * unit_rand(seed, i + 3);
    double a0 = start * s, b0 = (across - tan(tilt) * length / 2) * s; /* along, across */
    double da = cos(tilt), db = sin(tilt);
    r->x0 = cross ? b0 : a0;
    r->y0 = cross ? a0 : b0;
    r->dx = cross ? db : da;
    r->dy = cross ? da : db;
    r->len = length * s / cos(tilt);
}

/* Ink of the stroke at pixel centre (px, py): a tent of one pixel across and at the ends. */
static double stroke_ink(const stroke *st, double px, double py)
{
    double qx = px - st->x0, qy = py - st->y0;
    double t = qx * st->dx + qy * st->dy, d = fabs(qx * st->dy - qy * st->dx);
    return clamp01(STROKE_WIDTH / 2 + 0.5 - d) * clamp01(t + 0.5) * clamp01(st->len - t + 0.5);
}

/* next = cov with the stroke composited over it; returns next's core mean. */
static double stroke_apply(const stroke *st, int s, const float *cov, float *next)
{
    for (int y = 0; y < s; y++)
        for (int x = 0; x < s; x++) {
            double a = stroke_ink(st, x + 0.5, y + 0.5), c = cov[y * s + x];
            next[y * s + x] = (float)(1 - (1 - c) * (1 - a));
        }
    return core_mean(s, next);
}

typedef struct hatch_state {
    float cov[MAX_PIXELS], scratch[MAX_PIXELS];
    double mean;   /* core mean of cov */
    int next[2];   /* the next candidate of each list */
    int cross;     /* tones >= CROSS_TONE: the list whose turn it is */
} hatch_state;

/* Adds the next candidate of list `cross` unless that takes the core mean farther from target
 * than it is; 1 when added. */
static int hatch_step(int s, hatch_state *h, int cross, double target)
{
    stroke st;
    stroke_make(cross, h->next[cross], s, &st);
    double after = stroke_apply(&st, s, h->cov, h->scratch);
    if (after > target && after - target > target - h->mean) return 0;
    memcpy(h->cov, h->scratch, sizeof(float) * (size_t)s * (size_t)s);
    h->mean = after;
    h->next[cross]++;
    return 1;
}

static void hatch_tone(int s, int tone, hatch_state *h)
{
    double target = tone_target[tone];
    while (h->mean < target && h->next[0] < MAX_STROKES && h->next[1] < MAX_STROKES) {
        int cross = tone >= CROSS_TONE ? h->cross : 0;
        if (!hatch_step(s, h, cross, target)) break;
        if (tone >= CROSS_TONE) h->cross = !h->cross;
    }
}

/* malloc-free: the state (32 KiB) lives on the stack. */
static void hatch_level(int s, uint8_t *out)
{
    hatch_state h;
    memset(h.cov, 0, sizeof h.cov);
    h.mean = 0;
    h.next[0] = h.next[1] = 0;
    h.cross = 1;
    for (int tone = 0; tone < PNPR_TAM_TONES; tone++) {
        hatch_tone(s, tone, &h);
        store(s, h.cov, out + (size_t)tone * (size_t)s * (size_t)s);
    }
}

/* ---- dots ------------------------------------------------------------------------------------- */

/* Coverage of pixel (x, y) by the discs of radius r (pixels): the fraction of its supersamples
 * inside (a ramp one supersample wide), each sample tested against its own cell's dot, the
 * nearest one. */
static double dot_pixel(int s, int x, int y, double r)
{
    double c = (double)s / DOTS_ACROSS, h = 1.0 / DOT_SUB, sum = 0;
    for (int j = 0; j < DOT_SUB; j++)
        for (int i = 0; i < DOT_SUB; i++) {
            double px = x + (i + 0.5) * h, py = y + (j + 0.5) * h;
            double cx = (floor(px / c) + 0.5) * c, cy = (floor(py / c) + 0.5) * c;
            sum += clamp01((r - hypot(px - cx, py - cy)) / h + 0.5);
        }
    return sum / (DOT_SUB * DOT_SUB);
}

/* Fills cov with the discs of radius r; returns the core mean. */
static double dots_fill(int s, double r, float *cov)
{
    for (int y = 0; y < s; y++)
        for (int x = 0; x < s; x++)
            cov[y * s + x] = pixel_radius(s, x, y) < 1 ? (float)dot_pixel(s, x, y, r) : 0;
    return core_mean(s, cov);
}

/* The radius whose core coverage is target, by bisection (coverage grows with r; at r = the cell
 * side every cell is covered). */
static double dots_radius(int s, double target, float *cov)
{
    double lo = 0, hi = (double)s / DOTS_ACROSS;
    for (int it = 0; it < 30; it++) {
        double mid = 0.5 * (lo + hi);
        if (dots_fill(s, mid, cov) < target) lo = mid;
        else hi = mid;
    }
    return 0.5 * (lo + hi);
}

static void dots_level(int s, uint8_t *out)
{
    float cov[MAX_PIXELS];
    for (int tone = 0; tone < PNPR_TAM_TONES; tone++) {
        double r = dots_radius(s, tone_target[tone], cov);
        dots_fill(s, r, cov);
        store(s, cov, out + (size_t)tone * (size_t)s * (size_t)s);
    }
}

/* ---- paint ------------------------------------------------------------------------------------ */

/* 1D value noise in -1..1: random values at the integers, smoothstep between them. */
static double value_noise(uint64_t seed, double v)
{
    double f = floor(v), t = v - f;
    uint64_t i = (uint64_t)(int64_t)f;
    double a = 2 * unit_rand(seed, i) - 1, b = 2 * unit_rand(seed, i + 1) - 1;
    return a + (b - a) * t * t * (3 - 2 * t);
}

/* The bristle profile across the dab (v in 0..1): two octaves, about 9 and 23 bristles. */
static double bristles(double v)
{
    return 0.6 * value_noise(SEED_NOISE, 9 * v) + 0.4 * value_noise(SEED_NOISE + 1, 23 * v);
}

/* rows[j]: the bristle profile averaged over row j, scaled to -1..1 over the rows. */
static void paint_rows(int s, double *rows)
{
    double lo = INFINITY, hi = -INFINITY;
    for (int j = 0; j < s; j++) {
        double sum = 0;
        for (int k = 0; k < ROW_SUB; k++) sum += bristles((j + (k + 0.5) / ROW_SUB) / s);
        rows[j] = sum / ROW_SUB;
        lo = fmin(lo, rows[j]);
        hi = fmax(hi, rows[j]);
    }
    double span = hi - lo;
    for (int j = 0; j < s; j++) rows[j] = span > 1e-9 ? 2 * (rows[j] - lo) / span - 1 : 0;
}

static void paint_level(int s, uint8_t *out)
{
    double rows[PNPR_TAM_SIZE];
    float cov[MAX_PIXELS];
    paint_rows(s, rows);
    for (int tone = 0; tone < PNPR_TAM_TONES; tone++) {
        double f = (double)tone / (PNPR_TAM_TONES - 1);
        double centre = 0.85 - 0.125 * f, amp = 0.03 + 0.245 * f; /* 0.85 +- 0.03 .. 0.725 +- 0.275 */
        for (int y = 0; y < s; y++)
            for (int x = 0; x < s; x++) cov[y * s + x] = (float)clamp01(centre + amp * rows[y]);
        store(s, cov, out + (size_t)tone * (size_t)s * (size_t)s);
    }
}

/* ---- the API ---------------------------------------------------------------------------------- */

pnpr_status pnpr_tam_level(pnpr_tam_kind kind, int level, uint8_t *r_alpha)
{
    if (!r_alpha || level < 0 || level >= PNPR_TAM_LEVELS || (int)kind < 0 || (int)kind >= PNPR_TAM_COUNT_)
        return PNPR_ERR_INVALID_ARGUMENT;
    int s = PNPR_TAM_SIZE >> level;
    switch (kind) {
    case PNPR_TAM_HATCH: hatch_level(s, r_alpha); break;
    case PNPR_TAM_DOTS: dots_level(s, r_alpha); break;
    default: paint_level(s, r_alpha); break;
    }
    return PNPR_OK;
}

const char *pnpr_tam_name(pnpr_tam_kind kind)
{
    return (int)kind >= 0 && (int)kind < PNPR_TAM_COUNT_ ? tam_names[kind] : "";
}

int pnpr_tam_find(const char *name)
{
    if (!name) return -1;
    for (int i = 0; i < PNPR_TAM_COUNT_; i++)
        if (!strcasecmp(name, tam_names[i])) return i;
    return -1;
}

double pnpr_tam_tone_coverage(int tone)
{
    return tone >= 0 && tone < PNPR_TAM_TONES ? tone_target[tone] : 0.0;
}
