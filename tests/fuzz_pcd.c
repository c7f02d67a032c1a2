/* libFuzzer target for the PCD reader: any input must be read without crash, leak or UB; a failure
 * leaves a zeroed cloud and a message; a cloud that reads must write (binary PCD) and read back to
 * the same content (coordinates, colours, normals, labels, extra properties, viewpoint). */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    pnpr_cloud cloud;
    pnpr_error err;
    memset(&cloud, 0, sizeof cloud);
    if (pnpr_read_pcd_memory(data, size, NULL, &cloud, &err) != PNPR_OK) {
        fuzz_check_failed(&cloud, &err);
        return 0;
    }
    fuzz_sink sink = {0};
    pnpr_cloud back;
    memset(&back, 0, sizeof back);
    if (pnpr_write_pcd_stream(fuzz_write, &sink, &cloud, NULL, &err) != PNPR_OK) abort();
    if (pnpr_read_pcd_memory(sink.data, sink.size, NULL, &back, &err) != PNPR_OK) abort();
    fuzz_check_same(&cloud, &back, FUZZ_SAME_VIEWPOINT);
    pnpr_cloud_free(&back);
    free(sink.data);
    pnpr_cloud_free(&cloud);
    return 0;
}
