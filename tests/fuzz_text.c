/* libFuzzer target for the text point-cloud reader (io/text_points.c): every input is read as
 * XYZ, as PTS, and as CSV with --columns "x,y,z,r,g,b,label". Each read must finish without crash,
 * leak or undefined behaviour; a failure leaves a zeroed cloud and a message that names a line
 * (or no line for an option error); a cloud that reads has at most one point per 6 bytes of text
 * (+1 for a last line without its newline: no count is trusted), keeps exact doubles
 * (FLOAT64), and writes to binary PLY and reads back to the same content. */
#include "fuzz_common.h"

#include <stdio.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void read_as(const uint8_t *data, size_t size, pnpr_file_format fmt, const char *columns)
{
    pnpr_read_options ro;
    memset(&ro, 0, sizeof ro);
    ro.format = fmt;
    ro.columns = columns;
    pnpr_cloud cloud;
    pnpr_error err;
    memset(&cloud, 0, sizeof cloud);
    if (pnpr_read_text_memory(data, size, &ro, &cloud, &err) != PNPR_OK) {
        fuzz_check_failed(&cloud, &err);
        if (strncmp(err.message, "line ", 5) != 0) abort();
        return;
    }
    if (cloud.count > (size + 1) / 6 || cloud.src_coord_type != PNPR_TYPE_FLOAT64 || (cloud.count && !cloud.src_xyz))
        abort();
    fuzz_sink sink = {0};
    pnpr_write_options wo;
    pnpr_cloud back;
    memset(&wo, 0, sizeof wo);
    memset(&back, 0, sizeof back);
    if (pnpr_write_ply_stream(fuzz_write, &sink, &cloud, &wo, &err) != PNPR_OK) abort();
    if (pnpr_read_ply_memory(sink.data, sink.size, NULL, &back, &err) != PNPR_OK) abort();
    fuzz_check_same(&cloud, &back, 0);
    pnpr_cloud_free(&back);
    free(sink.data);
    pnpr_cloud_free(&cloud);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    read_as(data, size, PNPR_FORMAT_XYZ, NULL);
    read_as(data, size, PNPR_FORMAT_PTS, NULL);
    read_as(data, size, PNPR_FORMAT_CSV, "x,y,z,r,g,b,label");
    return 0;
}
