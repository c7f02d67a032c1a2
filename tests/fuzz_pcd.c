/* libFuzzer target for the PCD reader: any input must be read without crash, leak or UB; a failure
 * leaves a zeroed cloud and a message; a cloud that reads must write (binary PCD) and read back to
 * the same content (coordinates, colours, normals, labels, extra properties, viewpoint). */
#include <pointnpr/io.h>

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct fuzz_sink {
    unsigned char *data;
    size_t size, cap;
} fuzz_sink;

static int fuzz_write(void *user, const void *data, size_t size)
{
    fuzz_sink *m = user;
    if (size > SIZE_MAX - m->size) return 1;
    if (m->size + size > m->cap) {
        size_t cap = m->cap ? m->cap : 4096;
        while (cap < m->size + size) cap *= 2;
        unsigned char *g = realloc(m->data, cap);
        if (!g) return 1;
        m->data = g;
        m->cap = cap;
    }
    memcpy(m->data + m->size, data, size);
    m->size += size;
    return 0;
}

static int same_double(double a, double b)
{
    return (isnan(a) && isnan(b)) || a == b;
}

static void check_same(const pnpr_cloud *a, const pnpr_cloud *b)
{
    if (a->count != b->count || a->prop_count != b->prop_count || !a->rgb != !b->rgb || !a->normal != !b->normal ||
        !a->label != !b->label || a->has_viewpoint != b->has_viewpoint)
        abort();
    for (size_t i = 0; i < a->count; i++) {
        double wa[3], wb[3];
        pnpr_cloud_world(a, i, wa);
        pnpr_cloud_world(b, i, wb);
        for (int k = 0; k < 3; k++)
            if (!same_double(wa[k], wb[k])) abort();
    }
    if (a->rgb && memcmp(a->rgb, b->rgb, 3 * a->count) != 0) abort();
    if (a->label && memcmp(a->label, b->label, a->count * sizeof(uint32_t)) != 0) abort();
    if (a->normal)
        for (size_t i = 0; i < 3 * a->count; i++)
            if (!same_double(a->normal[i], b->normal[i])) abort();
    for (size_t k = 0; k < a->prop_count; k++) {
        if (strcmp(a->props[k].name, b->props[k].name) != 0 || a->props[k].type != b->props[k].type) abort();
        for (size_t i = 0; i < a->count; i++)
            if (!same_double(pnpr_type_get(a->props[k].type, a->props[k].data, i),
                             pnpr_type_get(b->props[k].type, b->props[k].data, i)))
                abort();
    }
    if (a->has_viewpoint && memcmp(a->viewpoint, b->viewpoint, sizeof a->viewpoint) != 0) abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    pnpr_cloud cloud;
    pnpr_error err;
    memset(&cloud, 0, sizeof cloud);
    if (pnpr_read_pcd_memory(data, size, NULL, &cloud, &err) != PNPR_OK) {
        pnpr_cloud zero;
        memset(&zero, 0, sizeof zero);
        if (memcmp(&cloud, &zero, sizeof zero) != 0 || err.message[0] == '\0') abort();
        return 0;
    }
    fuzz_sink sink = {0};
    pnpr_cloud back;
    memset(&back, 0, sizeof back);
    if (pnpr_write_pcd_stream(fuzz_write, &sink, &cloud, NULL, &err) != PNPR_OK) abort();
    if (pnpr_read_pcd_memory(sink.data, sink.size, NULL, &back, &err) != PNPR_OK) abort();
    check_same(&cloud, &back);
    pnpr_cloud_free(&back);
    free(sink.data);
    pnpr_cloud_free(&cloud);
    return 0;
}
