/* LAS 1.0-1.4 reader (uncompressed point data), plain C11, no library.
 *
 * What is read
 *  - Public header block: signature "LASF", version, header size, offset to point data, point
 *    data format (low 6 bits; bit 7 or 6 set means LAZ compression, which is refused), point
 *    record length (records may be longer than the format's base size: the extra bytes are
 *    skipped), legacy 32-bit point count and, for 1.4 headers, the 64-bit count (used when the
 *    legacy count is 0; when both are set they must agree), scale and offset per axis.
 *    Variable length records (VLRs/EVLRs) are skipped: the point data offset says where the
 *    points are.
 *  - Point formats 0-3 (legacy) and 6-8 (LAS 1.4). Formats 4, 5, 9, 10 (waveform packets) and
 *    unknown ids are refused with PNPR_ERR_UNSUPPORTED.
 *
 * What is kept
 *  - World coordinates X*scale + offset, computed in double. They go to cloud->src_xyz exactly
 *    (src_coord_type = FLOAT64) and, through pnpr_cloud_set_world, to the float offsets from an
 *    origin at the bounding-box centre.
 *  - RGB (formats 2, 3, 7, 8). LAS stores 16-bit channels, but many writers put 8-bit values in
 *    them unscaled. Rule, decided over all points and all three channels of the file:
 *      1. maximum <= 255: the values are 8-bit already and are kept as they are;
 *      2. otherwise, if every value is a multiple of 256 (low byte 0 everywhere): 8-bit colours
 *         stored as the LAS specification asks (c * 256), restored exactly as v >> 8;
 *      3. otherwise: genuine 16-bit, reduced with (v*255 + 32767) / 65535 (rounded to nearest).
 *    Rule 2 matters: rule 3 would map c * 256 to c - 1 for every c >= 129 (255 -> 254).
 *    A genuinely 16-bit file whose colours are all very dark (<= 255 of 65535) is read as
 *    8-bit by rule 1: that is the price of the rule, and it matches what viewers commonly do.
 *  - Extra properties "intensity" (ushort) and "classification" (uchar). For formats 0-5 in
 *    LAS >= 1.1 the classification byte also carries the synthetic/key-point/withheld flags in
 *    its top 3 bits; only the class (low 5 bits) is kept. LAS 1.0 and formats 6-10 store the
 *    class in a full byte, kept as is.
 *  - Everything else (return numbers, flags, scan angle, user data, point source id, GPS time,
 *    NIR, extra bytes) is dropped.
 *
 * Errors are precise (PNPR_ERR_FORMAT / TRUNCATED / UNSUPPORTED with the byte offset in
 * pnpr_error.offset where it helps); the size of the point data is checked against the bytes
 * present before anything is allocated (pnpr_read_las_file maps the file, io/file_bytes.h, so
 * before any point is read), and every size computation is overflow-checked. */
#include "../core/internal.h"
#include "file_bytes.h"
#include "io_util.h"
#include <pointnpr/io.h>

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Exported for io/io.c (not in the public header): reads a .las file through
 * pnpr_read_las_memory on its mapped bytes (io/file_bytes.h); error messages are prefixed with the
 * path. */
pnpr_status pnpr_read_las_file(const char *path, const pnpr_read_options *opts, pnpr_cloud *cloud,
                               pnpr_error *err);

#define LAS_HEADER_MIN_12 227u /* LAS 1.0-1.2 */
#define LAS_HEADER_MIN_13 235u /* + start of waveform data */
#define LAS_HEADER_MIN_14 375u /* + EVLRs, 64-bit point counts */
#define LAS_PROGRESS_STEP 65536u

/* Little-endian readers: assemble from bytes, so alignment and host byte order do not matter. */
static uint16_t rd_u16(const unsigned char *p)
{
    return (uint16_t)(p[0] | (p[1] << 8));
}

static uint32_t rd_u32(const unsigned char *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

static int32_t rd_i32(const unsigned char *p)
{
    uint32_t u = rd_u32(p);
    int32_t v;
    memcpy(&v, &u, sizeof v); /* two's complement reinterpretation without UB */
    return v;
}

static uint64_t rd_u64(const unsigned char *p)
{
    return (uint64_t)rd_u32(p) | ((uint64_t)rd_u32(p + 4) << 32);
}

static double rd_f64(const unsigned char *p)
{
    uint64_t u = rd_u64(p);
    double v;
    memcpy(&v, &u, sizeof v);
    return v;
}

/* Base record size of a point format, or 0 for formats this reader does not handle. */
static unsigned las_format_size(unsigned id)
{
    static const unsigned sizes[] = {20, 28, 26, 34, 0, 0, 30, 36, 38};
    return id < sizeof sizes / sizeof sizes[0] ? sizes[id] : 0;
}

/* Where the fields of one point record are (byte offsets; rgb < 0 = none). */
typedef struct las_layout {
    unsigned classification;
    int legacy; /* formats 0-5: classification byte holds flags in its top bits */
    int rgb;
} las_layout;

static las_layout las_layout_for(unsigned id)
{
    las_layout l;
    l.legacy = id < 6;
    l.classification = l.legacy ? 15u : 16u;
    switch (id) {
    case 2: l.rgb = 20; break;
    case 3: l.rgb = 28; break;
    case 7: case 8: l.rgb = 30; break;
    default: l.rgb = -1; break;
    }
    return l;
}

typedef struct las_header {
    unsigned major, minor;
    unsigned header_size;
    uint32_t data_offset;
    unsigned format;
    unsigned record_length;
    uint64_t count;
    double scale[3], offset[3];
} las_header;

static pnpr_status las_parse_header(const unsigned char *d, size_t size, las_header *h, pnpr_error *err)
{
    if (size < 4 || memcmp(d, "LASF", 4) != 0) {
        char sig[4 * 4 + 1];
        size_t n = size < 4 ? size : 4, k = 0;
        for (size_t i = 0; i < n; i++) {
            unsigned char c = d[i];
            if (c >= 0x20 && c < 0x7f && c != '"' && c != '\\') sig[k++] = (char)c;
            else k += (size_t)snprintf(sig + k, sizeof sig - k, "\\x%02x", c);
        }
        sig[k] = '\0';
        return pnpr_io_fail(err, PNPR_ERR_FORMAT, 0, 0, "not a LAS file: signature is \"%s\", expected \"LASF\"", sig);
    }
    if (size < LAS_HEADER_MIN_12)
        return pnpr_io_fail(err, PNPR_ERR_TRUNCATED, 0, (long long)size,
                        "LAS header needs %u bytes, file has %zu", LAS_HEADER_MIN_12, size);
    h->major = d[24];
    h->minor = d[25];
    if (h->major != 1 || h->minor > 4)
        return pnpr_io_fail(err, PNPR_ERR_UNSUPPORTED, 0, 24, "LAS version %u.%u is not supported (1.0-1.4 are)",
                        h->major, h->minor);
    h->header_size = rd_u16(d + 94);
    unsigned need = h->minor >= 4 ? LAS_HEADER_MIN_14 : h->minor == 3 ? LAS_HEADER_MIN_13 : LAS_HEADER_MIN_12;
    if (h->header_size < need)
        return pnpr_io_fail(err, PNPR_ERR_FORMAT, 0, 94, "LAS %u.%u header size %u is too small (at least %u bytes)",
                        h->major, h->minor, h->header_size, need);
    if (size < h->header_size)
        return pnpr_io_fail(err, PNPR_ERR_TRUNCATED, 0, (long long)size,
                        "LAS header needs %u bytes, file has %zu", h->header_size, size);
    h->data_offset = rd_u32(d + 96);
    if (h->data_offset < h->header_size)
        return pnpr_io_fail(err, PNPR_ERR_FORMAT, 0, 96, "point data offset %lu lies inside the %u-byte header",
                        (unsigned long)h->data_offset, h->header_size);
    if (h->data_offset > size)
        return pnpr_io_fail(err, PNPR_ERR_TRUNCATED, 0, 96,
                        "point data offset %lu is beyond the end of the file (%zu bytes)",
                        (unsigned long)h->data_offset, size);
    unsigned fmt_byte = d[104];
    if (fmt_byte & 0xC0u)
        return pnpr_io_fail(err, PNPR_ERR_UNSUPPORTED, 0, 104,
                        "LAZ compressed LAS is not supported (point data format byte %u)", fmt_byte);
    h->format = fmt_byte & 0x3Fu;
    unsigned base = las_format_size(h->format);
    if (base == 0) {
        if (h->format == 4 || h->format == 5 || h->format == 9 || h->format == 10)
            return pnpr_io_fail(err, PNPR_ERR_UNSUPPORTED, 0, 104,
                            "LAS point data format %u (with waveform packets) is not supported", h->format);
        return pnpr_io_fail(err, PNPR_ERR_UNSUPPORTED, 0, 104,
                        "unknown LAS point data format %u (formats 0-3 and 6-8 are supported)", h->format);
    }
    h->record_length = rd_u16(d + 105);
    if (h->record_length < base)
        return pnpr_io_fail(err, PNPR_ERR_FORMAT, 0, 105,
                        "point record length %u is smaller than the %u bytes of point data format %u",
                        h->record_length, base, h->format);
    uint32_t legacy = rd_u32(d + 107);
    h->count = legacy;
    if (h->minor >= 4) {
        uint64_t count64 = rd_u64(d + 247);
        if (legacy == 0)
            h->count = count64;
        else if (count64 != 0 && count64 != legacy)
            return pnpr_io_fail(err, PNPR_ERR_FORMAT, 0, 247,
                            "legacy point count %lu disagrees with the 64-bit point count %llu",
                            (unsigned long)legacy, (unsigned long long)count64);
    }
    static const char axis[3] = {'x', 'y', 'z'};
    for (int a = 0; a < 3; a++) {
        h->scale[a] = rd_f64(d + 131 + 8 * a);
        h->offset[a] = rd_f64(d + 155 + 8 * a);
        if (!isfinite(h->scale[a]) || h->scale[a] == 0.0)
            return pnpr_io_fail(err, PNPR_ERR_FORMAT, 0, 131 + 8 * a, "%c scale factor %g is not a finite non-zero number",
                            axis[a], h->scale[a]);
        if (!isfinite(h->offset[a]))
            return pnpr_io_fail(err, PNPR_ERR_FORMAT, 0, 155 + 8 * a, "%c offset %g is not finite", axis[a], h->offset[a]);
    }
    /* The points must all be present: offset + count * record_length <= size (no overflow). */
    uint64_t avail = (uint64_t)(size - h->data_offset);
    if (h->count > avail / h->record_length) {
        uint64_t first_missing = avail / h->record_length;
        if (h->count > (UINT64_MAX - h->data_offset) / h->record_length)
            return pnpr_io_fail(err, PNPR_ERR_TRUNCATED, 0, (long long)(h->data_offset + first_missing * h->record_length),
                            "header announces %llu points of %u bytes, more than any file can hold; "
                            "file has %zu bytes, point %llu is the first missing",
                            (unsigned long long)h->count, h->record_length, size,
                            (unsigned long long)first_missing);
        uint64_t needed = h->data_offset + h->count * h->record_length;
        return pnpr_io_fail(err, PNPR_ERR_TRUNCATED, 0, (long long)(h->data_offset + first_missing * h->record_length),
                        "truncated point data: needs %llu bytes, has %zu; point %llu of %llu is the first missing",
                        (unsigned long long)needed, size, (unsigned long long)first_missing,
                        (unsigned long long)h->count);
    }
    if (h->count > SIZE_MAX / (3 * sizeof(double)))
        return pnpr_io_fail(err, PNPR_ERR_OUT_OF_MEMORY, 0, 107, "%llu points do not fit in memory",
                        (unsigned long long)h->count);
    return PNPR_OK;
}

/* 16-bit to 8-bit channel, rounded to nearest. */
static uint8_t las_rgb8(uint16_t v)
{
    return (uint8_t)(((uint32_t)v * 255u + 32767u) / 65535u);
}

static pnpr_status las_read_points(const unsigned char *d, const las_header *h, const pnpr_read_options *opts,
                                   pnpr_cloud *cloud, pnpr_error *err)
{
    const size_t n = (size_t)h->count;
    const las_layout lay = las_layout_for(h->format);
    const pnpr_progress *progress = opts ? &opts->progress : NULL;
    pnpr_status st = pnpr_cloud_alloc(cloud, n);
    if (st == PNPR_OK) st = pnpr_cloud_alloc_src_xyz(cloud);
    if (st == PNPR_OK && lay.rgb >= 0) st = pnpr_cloud_alloc_rgb(cloud);
    pnpr_property *intensity = NULL, *klass = NULL;
    if (st == PNPR_OK) st = pnpr_cloud_add_property(cloud, PNPR_PROP_INTENSITY, PNPR_TYPE_UINT16, &intensity);
    if (st == PNPR_OK) st = pnpr_cloud_add_property(cloud, PNPR_PROP_CLASSIFICATION, PNPR_TYPE_UINT8, &klass);
    if (st != PNPR_OK)
        return pnpr_io_fail(err, st, 0, -1, "cannot allocate %zu points", n);
    /* add_property may have moved the array: look both up again */
    intensity = pnpr_cloud_find_property(cloud, PNPR_PROP_INTENSITY);
    klass = pnpr_cloud_find_property(cloud, PNPR_PROP_CLASSIFICATION);
    uint16_t *inten = intensity->data;
    uint8_t *cls = klass->data;
    const uint8_t class_mask = (lay.legacy && h->minor >= 1) ? 0x1Fu : 0xFFu;
    uint16_t rgb_max = 0;
    unsigned rgb_low_bits = 0; /* OR of all low bytes: 0 when every value is a multiple of 256 */

    if (pnpr_progress_report(progress, "read las", 0.0))
        return pnpr_io_fail(err, PNPR_ERR_CANCELLED, 0, -1, "cancelled");
    const unsigned char *rec = d + h->data_offset;
    for (size_t i = 0; i < n; i++, rec += h->record_length) {
        if (i && i % LAS_PROGRESS_STEP == 0 && pnpr_progress_report(progress, "read las", (double)i / (double)n))
            return pnpr_io_fail(err, PNPR_ERR_CANCELLED, 0, -1, "cancelled");
        for (int a = 0; a < 3; a++) {
            /* two statements: C allows fusing into an fma only within one expression (clang's
             * default; GCC in ISO mode never fuses), so the result is the rounded X*scale, then
             * the rounded sum, on every platform — the value tests and other tools compute */
            double scaled = (double)rd_i32(rec + 4 * a) * h->scale[a];
            cloud->src_xyz[3 * i + a] = scaled + h->offset[a];
        }
        inten[i] = rd_u16(rec + 12);
        cls[i] = (uint8_t)(rec[lay.classification] & class_mask);
        if (lay.rgb >= 0) {
            for (int c = 0; c < 3; c++) {
                uint16_t v = rd_u16(rec + lay.rgb + 2 * c);
                if (v > rgb_max) rgb_max = v;
                rgb_low_bits |= v & 0xFFu;
            }
        }
    }
    if (lay.rgb >= 0) {
        const int mode = rgb_max <= 255 ? 1 : rgb_low_bits == 0 ? 2 : 3; /* rules 1-3 above */
        rec = d + h->data_offset;
        for (size_t i = 0; i < n; i++, rec += h->record_length)
            for (int c = 0; c < 3; c++) {
                uint16_t v = rd_u16(rec + lay.rgb + 2 * c);
                cloud->rgb[3 * i + c] = mode == 1 ? (uint8_t)v : mode == 2 ? (uint8_t)(v >> 8) : las_rgb8(v);
            }
    }
    cloud->src_coord_type = PNPR_TYPE_FLOAT64;
    cloud->up_hint = 3; /* LAS (ASPRS): projected coordinates, z is elevation */
    if ((st = pnpr_cloud_set_world(cloud, cloud->src_xyz)) != PNPR_OK)
        return pnpr_io_fail(err, st, 0, -1, "cannot set world coordinates");
    if (pnpr_progress_report(progress, "read las", 1.0))
        return pnpr_io_fail(err, PNPR_ERR_CANCELLED, 0, -1, "cancelled");
    return PNPR_OK;
}

pnpr_status pnpr_read_las_memory(const void *data, size_t size, const pnpr_read_options *opts,
                                 pnpr_cloud *cloud, pnpr_error *err)
{
    if (err) { err->message[0] = '\0'; err->offset = -1; err->line = 0; }
    if (!cloud || (!data && size))
        return pnpr_io_fail(err, PNPR_ERR_INVALID_ARGUMENT, 0, -1, "pnpr_read_las_memory: NULL argument");
    pnpr_cloud_free(cloud);
    if (pnpr_io_no_filter(opts, err, "read las") != PNPR_OK) return PNPR_ERR_UNSUPPORTED;
    if (!data) data = "";
    las_header h;
    memset(&h, 0, sizeof h);
    pnpr_status st = las_parse_header(data, size, &h, err);
    if (st == PNPR_OK) st = las_read_points(data, &h, opts, cloud, err);
    if (st != PNPR_OK) pnpr_cloud_free(cloud);
    return st;
}

pnpr_status pnpr_read_las_file(const char *path, const pnpr_read_options *opts, pnpr_cloud *cloud,
                               pnpr_error *err)
{
    if (!path || !cloud)
        return pnpr_io_fail(err, PNPR_ERR_INVALID_ARGUMENT, 0, -1, "pnpr_read_las_file: NULL argument");
    return pnpr_file_bytes_read(path, pnpr_read_las_memory, opts, cloud, err);
}
