/* Shared by the libFuzzer targets (tests/fuzz_*.c): an in-memory write sink, and the checks every
 * reader must pass: a failure leaves a zeroed cloud and a message; a cloud written and read back
 * holds the same content. Any broken promise aborts (libFuzzer reports it). */
#ifndef PNPR_FUZZ_COMMON_H
#define PNPR_FUZZ_COMMON_H

#include <pointnpr/io.h>

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef pnpr_mem_sink fuzz_sink;      /* the library's memory sink */
#define fuzz_write pnpr_mem_sink_write

static inline int fuzz_same_double(double a, double b)
{
    return (isnan(a) && isnan(b)) || a == b;
}

/* A failed read: the cloud must be all zero and the error must say something. */
static inline void fuzz_check_failed(const pnpr_cloud *cloud, const pnpr_error *err)
{
    pnpr_cloud zero;
    memset(&zero, 0, sizeof zero);
    if (memcmp(cloud, &zero, sizeof zero) != 0 || err->message[0] == '\0') abort();
}

/* Faces and the viewpoint are compared when the format keeps them (PLY faces, PCD viewpoint). */
enum { FUZZ_SAME_FACES = 1, FUZZ_SAME_VIEWPOINT = 2 };

static inline void fuzz_check_same(const pnpr_cloud *a, const pnpr_cloud *b, int what)
{
    if (a->count != b->count || a->prop_count != b->prop_count || !a->rgb != !b->rgb || !a->normal != !b->normal ||
        !a->label != !b->label)
        abort();
    for (size_t i = 0; i < a->count; i++) {
        double wa[3], wb[3];
        pnpr_cloud_world(a, i, wa);
        pnpr_cloud_world(b, i, wb);
        for (int k = 0; k < 3; k++)
            if (!fuzz_same_double(wa[k], wb[k])) abort();
    }
    if (a->rgb && memcmp(a->rgb, b->rgb, 3 * a->count) != 0) abort();
    if (a->label && memcmp(a->label, b->label, a->count * sizeof(uint32_t)) != 0) abort();
    if (a->normal)
        for (size_t i = 0; i < 3 * a->count; i++)
            if (!fuzz_same_double(a->normal[i], b->normal[i])) abort();
    for (size_t k = 0; k < a->prop_count; k++) {
        if (strcmp(a->props[k].name, b->props[k].name) != 0 || a->props[k].type != b->props[k].type) abort();
        for (size_t i = 0; i < a->count; i++)
            if (!fuzz_same_double(pnpr_type_get(a->props[k].type, a->props[k].data, i),
                                  pnpr_type_get(b->props[k].type, b->props[k].data, i)))
                abort();
    }
    if ((what & FUZZ_SAME_FACES) && a->faces.count != b->faces.count) abort();
    if ((what & FUZZ_SAME_FACES) && a->faces.count) {
        if (memcmp(a->faces.offset, b->faces.offset, (a->faces.count + 1) * sizeof(uint32_t)) != 0) abort();
        if (memcmp(a->faces.index, b->faces.index, a->faces.offset[a->faces.count] * sizeof(uint32_t)) != 0)
            abort();
    }
    if ((what & FUZZ_SAME_VIEWPOINT) && (a->has_viewpoint != b->has_viewpoint ||
                                         (a->has_viewpoint && memcmp(a->viewpoint, b->viewpoint, sizeof a->viewpoint) != 0)))
        abort();
}

#endif
