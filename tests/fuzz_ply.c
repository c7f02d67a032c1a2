/* libFuzzer target for the PLY reader: any input must be read without crash, leak or UB; a cloud
 * that reads must write (ascii, binary LE, binary BE) and read back to the same content. The point
 * filter of tiles (read options' keep) runs on every input too: where the plain read succeeds it
 * fails with a message (UNSUPPORTED: ascii, list records) or keeps exactly the even vertices. */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int keep_even(void *user, uint64_t index, const double p[3])
{
    (void)p;
    *(uint64_t *)user = index + 1;
    return index % 2 == 0;
}

static void check_filter(const uint8_t *data, size_t size, const pnpr_cloud *all, int read_ok)
{
    uint64_t seen = 0;
    pnpr_read_options ro;
    memset(&ro, 0, sizeof ro);
    ro.keep = keep_even;
    ro.keep_user = &seen;
    pnpr_cloud even;
    pnpr_error err;
    memset(&even, 0, sizeof even);
    pnpr_status st = pnpr_read_ply_memory(data, size, &ro, &even, &err);
    if (st != PNPR_OK) {
        fuzz_check_failed(&even, &err);
        return;
    }
    if (!read_ok) { /* the filter skips the faces, whose errors the plain read found */
        pnpr_cloud_free(&even);
        return;
    }
    if (even.count != (all->count + 1) / 2 || seen != all->count || even.faces.count) abort();
    for (size_t i = 0; i < even.count; i++) {
        double a[3], b[3];
        pnpr_cloud_world(all, 2 * i, a);
        pnpr_cloud_world(&even, i, b);
        if (!fuzz_same_double(a[0], b[0]) || !fuzz_same_double(a[1], b[1]) || !fuzz_same_double(a[2], b[2])) abort();
    }
    pnpr_cloud_free(&even);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    pnpr_cloud cloud;
    pnpr_error err;
    memset(&cloud, 0, sizeof cloud);
    if (pnpr_read_ply_memory(data, size, NULL, &cloud, &err) != PNPR_OK) {
        fuzz_check_failed(&cloud, &err);
        check_filter(data, size, &cloud, 0);
        return 0;
    }
    check_filter(data, size, &cloud, 1);
    for (int enc = 0; enc < 3; enc++) {
        fuzz_sink sink = {0};
        pnpr_write_options wo;
        pnpr_cloud back;
        memset(&wo, 0, sizeof wo);
        memset(&back, 0, sizeof back);
        wo.encoding = (pnpr_ply_encoding)enc;
        if (pnpr_write_ply_stream(fuzz_write, &sink, &cloud, &wo, &err) != PNPR_OK) abort();
        if (pnpr_read_ply_memory(sink.data, sink.size, NULL, &back, &err) != PNPR_OK) abort();
        fuzz_check_same(&cloud, &back, FUZZ_SAME_FACES);
        pnpr_cloud_free(&back);
        free(sink.data);
    }
    pnpr_cloud_free(&cloud);
    return 0;
}
