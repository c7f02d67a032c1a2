/* File-level I/O: picks the format (explicit option, extension, then magic bytes) and hands
 * over to the format readers/writers. PLY and PCD are written. */
#include <pointnpr/io.h>
#include <pointnpr/output.h>

#include "../core/internal.h"
#include "io_util.h"

#include <errno.h>
#include <stdarg.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

/* Format entry points that take a path (defined in io/ply.c and io/las.c; not public API). */
extern pnpr_status pnpr_read_ply_file(const char *path, const pnpr_read_options *opts, pnpr_cloud *cloud,
                                      pnpr_error *err);
extern pnpr_status pnpr_write_ply_file(const char *path, const pnpr_cloud *cloud,
                                       const pnpr_write_options *opts, pnpr_error *err);
extern pnpr_status pnpr_read_pcd_file(const char *path, const pnpr_read_options *opts, pnpr_cloud *cloud,
                                      pnpr_error *err);
extern pnpr_status pnpr_write_pcd_file(const char *path, const pnpr_cloud *cloud,
                                       const pnpr_write_options *opts, pnpr_error *err);
extern pnpr_status pnpr_read_off_file(const char *path, const pnpr_read_options *opts, pnpr_cloud *cloud,
                                      pnpr_error *err);
extern pnpr_status pnpr_read_text_file(const char *path, const pnpr_read_options *opts, pnpr_cloud *cloud,
                                       pnpr_error *err);
extern pnpr_status pnpr_read_las_file(const char *path, const pnpr_read_options *opts, pnpr_cloud *cloud,
                                      pnpr_error *err);

static char io_lower(char c)
{
    return c >= 'A' && c <= 'Z' ? (char)(c - 'A' + 'a') : c;
}

/* Case-insensitive comparison of the extension (without dot) with `ext` (lower case). */
static int io_ext_is(const char *dot_ext, const char *ext)
{
    while (*dot_ext && *ext && io_lower(*dot_ext) == *ext) { dot_ext++; ext++; }
    return *dot_ext == '\0' && *ext == '\0';
}

pnpr_file_format pnpr_format_from_path(const char *path)
{
    if (!path) return PNPR_FORMAT_AUTO;
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    const char *dot = strrchr(base, '.');
    if (!dot || dot == base) return PNPR_FORMAT_AUTO; /* no extension, or a hidden file like ".ply" */
    dot++;
    if (io_ext_is(dot, "ply")) return PNPR_FORMAT_PLY;
    if (io_ext_is(dot, "las")) return PNPR_FORMAT_LAS;
    if (io_ext_is(dot, "obj")) return PNPR_FORMAT_OBJ;
    if (io_ext_is(dot, "off")) return PNPR_FORMAT_OFF;
    if (io_ext_is(dot, "pcd")) return PNPR_FORMAT_PCD;
    if (io_ext_is(dot, "xyz")) return PNPR_FORMAT_XYZ;
    if (io_ext_is(dot, "pts")) return PNPR_FORMAT_PTS;
    if (io_ext_is(dot, "pwn")) return PNPR_FORMAT_PWN;
    if (io_ext_is(dot, "csv") || io_ext_is(dot, "txt")) return PNPR_FORMAT_CSV;
    return PNPR_FORMAT_AUTO;
}

/* PCD: PCL's comment line "# .PCD" or a first "VERSION " line. */
static int io_is_pcd(const unsigned char *b, size_t n)
{
    return (n >= 6 && memcmp(b, "# .PCD", 6) == 0) ||
           (n >= 8 && memcmp(b, "VERSION", 7) == 0 && (b[7] == ' ' || b[7] == '\t'));
}

/* Magic bytes: "ply\n" / "ply\r\n", "LASF", PCD (above), or an OFF keyword ([ST][C][N][4][n]OFF
 * followed by white space or the end). OBJ has no magic. */
static pnpr_file_format io_sniff(const unsigned char *b, size_t n)
{
    if (io_is_pcd(b, n))
        return PNPR_FORMAT_PCD;
    if ((n >= 4 && memcmp(b, "ply\n", 4) == 0) || (n >= 5 && memcmp(b, "ply\r\n", 5) == 0))
        return PNPR_FORMAT_PLY;
    if (n >= 4 && memcmp(b, "LASF", 4) == 0)
        return PNPR_FORMAT_LAS;
    size_t i = 0; /* OFF: after blank and '#' comment lines (as CGAL's files have them) */
    while (i < n) {
        if (b[i] == ' ' || b[i] == '\t' || b[i] == '\r' || b[i] == '\n') i++;
        else if (b[i] == '#') while (i < n && b[i] != '\n') i++;
        else break;
    }
    static const char prefix[] = "STCN4n";
    for (size_t k = 0; k < sizeof prefix - 1 && i < n; k++)
        if (b[i] == (unsigned char)prefix[k]) i++;
    if (n >= i + 3 && memcmp(b + i, "OFF", 3) == 0 &&
        (n == i + 3 || b[i + 3] == ' ' || b[i + 3] == '\t' || b[i + 3] == '\n' || b[i + 3] == '\r'))
        return PNPR_FORMAT_OFF;
    return PNPR_FORMAT_AUTO;
}

static const char *io_format_name(pnpr_file_format f)
{
    static const char *const names[PNPR_FORMAT_COUNT_] = {"", "PLY", "LAS", "OBJ", "OFF", "PCD", "XYZ", "PTS", "PWN",
                                                          "CSV"};
    return (int)f > 0 && f < PNPR_FORMAT_COUNT_ ? names[f] : "this format";
}

static pnpr_status io_check_input(const char *path, pnpr_error *err)
{
    struct stat sb;
    if (stat(path, &sb) != 0)
        return pnpr_error_set(err, PNPR_ERR_IO, "%s: %s", path, strerror(errno));
    if (S_ISDIR(sb.st_mode))
        return pnpr_error_set(err, PNPR_ERR_IO,
                              "%s: %s; a folder of tiles is read as one file once joined (pointnpr convert %s -o ALL.ply, "
                              "one tile at a time when they do not fit together: docs/tiles.md)", path, strerror(EISDIR),
                              path);
    return PNPR_OK;
}

static pnpr_status io_sniff_file(const char *path, pnpr_file_format *r_format, pnpr_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return pnpr_error_set(err, PNPR_ERR_IO, "%s: %s", path, strerror(errno));
    unsigned char head[4096]; /* room for the comment lines before an OFF keyword */
    size_t n = fread(head, 1, sizeof head, f);
    int failed = ferror(f);
    int saved = errno;
    fclose(f);
    if (failed)
        return pnpr_error_set(err, PNPR_ERR_IO, "%s: read error: %s", path, strerror(saved));
    *r_format = io_sniff(head, n);
    return PNPR_OK;
}

pnpr_status pnpr_read_file(const char *path, const pnpr_read_options *opts, pnpr_cloud *cloud,
                           pnpr_error *err)
{
    if (err) { err->message[0] = '\0'; err->offset = -1; err->line = 0; }
    if (!cloud)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "pnpr_read_file: cloud is NULL");
    pnpr_cloud_free(cloud);
    if (!path)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "pnpr_read_file: path is NULL");
    pnpr_read_options o;
    memset(&o, 0, sizeof o);
    if (opts) o = *opts;
    if ((int)o.format < 0 || o.format >= PNPR_FORMAT_COUNT_)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "%s: invalid read format %d", path, (int)o.format);
    pnpr_status st = io_check_input(path, err);
    if (st != PNPR_OK) return st;
    if (o.format == PNPR_FORMAT_AUTO) o.format = pnpr_format_from_path(path);
    if (o.format == PNPR_FORMAT_AUTO && (st = io_sniff_file(path, &o.format, err)) != PNPR_OK)
        return st;
    if (o.format != PNPR_FORMAT_PLY && (st = pnpr_io_no_filter(&o, err, path)) != PNPR_OK) return st;
    switch (o.format) {
    case PNPR_FORMAT_PLY: st = pnpr_read_ply_file(path, &o, cloud, err); break;
    case PNPR_FORMAT_LAS: st = pnpr_read_las_file(path, &o, cloud, err); break;
    case PNPR_FORMAT_PCD: st = pnpr_read_pcd_file(path, &o, cloud, err); break;
    case PNPR_FORMAT_OBJ: st = pnpr_read_mesh_file(path, &o, cloud, err); break;
    case PNPR_FORMAT_OFF: st = pnpr_read_off_file(path, &o, cloud, err); break;
    case PNPR_FORMAT_XYZ:
    case PNPR_FORMAT_PTS:
    case PNPR_FORMAT_PWN:
    case PNPR_FORMAT_CSV: st = pnpr_read_text_file(path, &o, cloud, err); break;
    default:
        st = pnpr_error_set(err, PNPR_ERR_UNSUPPORTED,
                            "%s: cannot tell the file format (expected .ply, .las, .obj, .off, .pcd, .xyz, .pts, .pwn, "
                            ".csv or .txt)", path);
        break;
    }
    if (st != PNPR_OK) pnpr_cloud_free(cloud);
    return st;
}

int pnpr_mem_sink_write(void *user, const void *data, size_t size)
{
    pnpr_mem_sink *m = user;
    if (size > m->cap - m->size) {
        size_t cap = m->cap ? m->cap : 65536;
        while (cap - m->size < size) {
            if (cap > SIZE_MAX / 2) return 1;
            cap *= 2;
        }
        unsigned char *g = realloc(m->data, cap);
        if (!g) return 1;
        m->data = g;
        m->cap = cap;
    }
    if (size) memcpy(m->data + m->size, data, size);
    m->size += size;
    return 0;
}

pnpr_status pnpr_write_file(const char *path, const pnpr_cloud *cloud, const pnpr_write_options *opts,
                            pnpr_error *err)
{
    if (err) { err->message[0] = '\0'; err->offset = -1; err->line = 0; }
    if (!path || !cloud)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "pnpr_write_file: NULL argument");
    pnpr_write_options o;
    memset(&o, 0, sizeof o);
    if (opts) o = *opts;
    if ((int)o.format < 0 || o.format >= PNPR_FORMAT_COUNT_)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "%s: invalid write format %d", path, (int)o.format);
    if (o.format == PNPR_FORMAT_AUTO) o.format = strcmp(path, "-") ? pnpr_format_from_path(path) : PNPR_FORMAT_PLY;
    switch (o.format) {
    case PNPR_FORMAT_PLY:
        return pnpr_write_ply_file(path, cloud, &o, err);
    case PNPR_FORMAT_PCD:
        return pnpr_write_pcd_file(path, cloud, &o, err);
    case PNPR_FORMAT_LAS:
    case PNPR_FORMAT_OBJ:
    case PNPR_FORMAT_OFF:
    case PNPR_FORMAT_XYZ:
    case PNPR_FORMAT_PTS:
    case PNPR_FORMAT_PWN:
    case PNPR_FORMAT_CSV:
        return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "%s: writing %s is not supported (PLY and PCD are written)",
                              path, io_format_name(o.format));
    default:
        return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED,
                              "%s: cannot tell the output format from the name (use a .ply or .pcd extension)", path);
    }
}

pnpr_status pnpr_io_fail(pnpr_error *err, pnpr_status st, long line, long long offset, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->message, sizeof err->message, fmt, ap);
        va_end(ap);
        err->line = line;
        err->offset = offset;
    }
    return st;
}

pnpr_status pnpr_io_write_path(const char *path, const pnpr_cloud *cloud, const pnpr_write_options *opts,
                               pnpr_error *err, const char *what, pnpr_io_stream_writer stream)
{
    if (!path || !path[0] || !cloud)
        return pnpr_io_fail(err, PNPR_ERR_INVALID_ARGUMENT, 0, -1, "%s: NULL/empty path or NULL cloud", what);
    pnpr_output *o = malloc(sizeof *o);
    if (!o) return pnpr_io_fail(err, PNPR_ERR_OUT_OF_MEMORY, 0, -1, "%s: out of memory", path);
    pnpr_status st = pnpr_output_open(o, path, err);
    if (st == PNPR_OK) {
        st = stream(pnpr_output_sink, o, cloud, opts, err);
        if (st != PNPR_OK && st != PNPR_ERR_IO) pnpr_error_prefix_path(err, path);
        st = pnpr_output_close(o, st, err);
    }
    free(o);
    return st;
}

size_t pnpr_ply_type_size(const char *t, size_t n)
{
    static const char *const names[][2] = {{"char", "int8"}, {"uchar", "uint8"}, {"short", "int16"}, {"ushort", "uint16"},
                                           {"int", "int32"}, {"uint", "uint32"}, {"float", "float32"}, {"double", "float64"}};
    static const size_t sizes[] = {1, 1, 2, 2, 4, 4, 4, 8};
    for (int k = 0; k < 8; k++)
        for (int a = 0; a < 2; a++)
            if (strlen(names[k][a]) == n && !strncmp(t, names[k][a], n)) return sizes[k];
    return 0;
}
