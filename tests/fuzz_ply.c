/* libFuzzer target for the PLY reader: any input must be read without crash, leak or UB; a cloud
 * that reads must write (ascii, binary LE, binary BE) and read back to the same content. */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    pnpr_cloud cloud;
    pnpr_error err;
    memset(&cloud, 0, sizeof cloud);
    if (pnpr_read_ply_memory(data, size, NULL, &cloud, &err) != PNPR_OK) {
        fuzz_check_failed(&cloud, &err);
        return 0;
    }
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
