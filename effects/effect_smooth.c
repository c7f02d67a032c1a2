/* The smooth effect (effects.h): `iterations` passes of OpenCV's bilateral filter (Tomasi and
 * Manduchi 1998) on the RGB colours (0..1): window radius `radius` px, spatial sigma radius / 2,
 * colour sigma `sigma_color` (mean absolute channel difference). Alpha is kept. */
#include "effects_internal.h"

#include <stdlib.h>

pnpr_status pnpr_fx_smooth(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err)
{
    (void)seed;
    int w = src->width, h = src->height;
    size_t n = (size_t)w * (size_t)h * 3;
    float *buf = pnpr_fx_floats(n, err), *tmp = buf ? pnpr_fx_floats(n, err) : NULL;
    pnpr_status st = tmp ? PNPR_OK : PNPR_ERR_OUT_OF_MEMORY;
    if (st == PNPR_OK) {
        pnpr_fx_to_rgb(src, buf);
        st = pnpr_fx_bilateral_passes(buf, tmp, w, h, (int)(p[0] + 0.5f), p[1], (int)(p[2] + 0.5f), err);
    }
    if (st == PNPR_OK) pnpr_fx_from_rgb(buf, src, dst);
    free(buf);
    free(tmp);
    return st;
}
