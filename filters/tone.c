/* Tone: per point darkness from colour and a key light (include/pointnpr/tone.h). */
#include <pointnpr/options.h>
#include <pointnpr/tone.h>

#include <math.h>
#include <string.h>

static double norm3(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0 && isfinite(l)) for (int a = 0; a < 3; a++) v[a] /= l;
    else l = 0;
    return l;
}

void pnpr_tone_light(const pnpr_tone_options *opts, double r_light[3])
{
    double up[3] = {0, 0, 1};
    if (opts) {
        double l[3] = {opts->light[0], opts->light[1], opts->light[2]};
        if (norm3(l) > 0) { memcpy(r_light, l, sizeof l); return; }
        double u[3] = {opts->up[0], opts->up[1], opts->up[2]};
        if (norm3(u) > 0) memcpy(up, u, sizeof u);
    }
    /* from above, 35 degrees off the up axis: towards a horizontal direction h that is the
     * world's -y (or -x when up is near y) mixed with its left-hand side, as illustrators light
     * from the upper left-front */
    double ref[3] = {0, -1, 0};
    if (fabs(up[1]) > 0.9) { ref[0] = -1; ref[1] = 0; }
    double d = ref[0] * up[0] + ref[1] * up[1] + ref[2] * up[2];
    double h[3] = {ref[0] - d * up[0], ref[1] - d * up[1], ref[2] - d * up[2]};
    norm3(h);
    double left[3] = {up[1] * h[2] - up[2] * h[1], up[2] * h[0] - up[0] * h[2], up[0] * h[1] - up[1] * h[0]};
    double s = sin(35.0 * 3.14159265358979 / 180.0), c = cos(35.0 * 3.14159265358979 / 180.0);
    for (int a = 0; a < 3; a++) r_light[a] = c * up[a] + s * (0.8 * h[a] + 0.6 * left[a]);
    norm3(r_light);
}

static int valid_options(const pnpr_tone_options *o)
{
    if ((unsigned)o->source >= PNPR_TONE_SOURCE_COUNT_) return 0;
    for (int a = 0; a < 3; a++)
        if (!isfinite(o->up[a]) || !isfinite(o->light[a])) return 0;
    size_t n;
    const pnpr_option_desc *table = pnpr_tone_option_table(&n);
    return pnpr_option_check(table, n, o, NULL) == PNPR_OK; /* the ranges: options.h */
}

static float lit_shade(const float *n, const double l[3], double ambient)
{
    double len = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
    if (!(len > 1e-12) || !isfinite(len)) return (float)(ambient + 0.5 * (1 - ambient));
    double c = fabs((n[0] * l[0] + n[1] * l[1] + n[2] * l[2]) / len);
    return (float)(ambient + (1 - ambient) * (c < 1 ? c : 1));
}

pnpr_status pnpr_tone(const uint8_t *rgb, const float *normals, size_t count,
                      const pnpr_tone_options *opts, float *r_tone)
{
    pnpr_tone_options o;
    memset(&o, 0, sizeof o);
    if (opts) o = *opts;
    if (!valid_options(&o) || (count && !r_tone)) return PNPR_ERR_INVALID_ARGUMENT;
    pnpr_tone_source src = o.source;
    if (src == PNPR_TONE_AUTO) src = rgb && normals ? PNPR_TONE_BOTH : normals ? PNPR_TONE_LIGHT : PNPR_TONE_COLOR;
    if (src == PNPR_TONE_BOTH && !(rgb && normals)) src = rgb ? PNPR_TONE_COLOR : PNPR_TONE_LIGHT;
    if (src == PNPR_TONE_COLOR && !rgb) src = normals ? PNPR_TONE_LIGHT : PNPR_TONE_SOURCE_COUNT_;
    if (src == PNPR_TONE_LIGHT && !normals) src = rgb ? PNPR_TONE_COLOR : PNPR_TONE_SOURCE_COUNT_;
    size_t nt;
    const pnpr_option_desc *table = pnpr_tone_option_table(&nt);
    pnpr_option_fill_defaults(table, nt, &o); /* the zeros: the table's defaults */
    double ambient = o.ambient, cw = o.colour_weight, contrast = o.contrast, gamma = o.gamma;
    double l[3];
    pnpr_tone_light(&o, l);
    for (size_t i = 0; i < count; i++) {
        double dark = 0.5, shade = 1;
        if (src == PNPR_TONE_LIGHT || src == PNPR_TONE_BOTH) shade = lit_shade(normals + 3 * i, l, ambient);
        if (src == PNPR_TONE_COLOR || src == PNPR_TONE_BOTH) {
            const uint8_t *c = rgb + 3 * i;
            dark = 1.0 - (0.299 * c[0] + 0.587 * c[1] + 0.114 * c[2]) / 255.0;
        }
        if (src == PNPR_TONE_LIGHT) dark = 1 - shade;
        else if (src == PNPR_TONE_BOTH) dark = 1 - shade * (1 - cw * dark);
        double t = (dark - 0.5) * contrast + 0.5;
        t = t > 0 ? (t < 1 ? t : 1) : 0;
        r_tone[i] = (float)pow(t, gamma);
    }
    return PNPR_OK;
}
