/* The toon effect (effects.h). STUB: being written. */
#include "effects_internal.h"

pnpr_status pnpr_fx_toon(const float *p, const pnpr_image *src, pnpr_image *dst, uint64_t seed, pnpr_error *err)
{
    (void)p; (void)src; (void)dst; (void)seed;
    return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "effects: toon is not written yet");
}
