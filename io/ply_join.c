/* Joining files into one PLY with one input in memory at a time (include/pointnpr/io.h,
 * pnpr_join_ply; docs/tiles.md "A folder of tiles").
 *
 * Each input is read and written through pnpr_write_ply_stream into a filter:
 *  - the first input's header goes to the output with a count of 0 and a padding comment line
 *    ("comment" and spaces) before its first element, so that the real count, known at the end,
 *    fits in the same bytes: the header is written again over itself then;
 *  - every later input's header must equal the first's but for the count (the same properties,
 *    types and encoding); only its records go on;
 *  - faces cannot follow vertices of later inputs: an input with faces is refused;
 *  - an input without points is skipped (a text file without points has no columns to compare).
 * The records are what writing the joined cloud in memory gives (pointnpr convert without
 * --stream): the writer puts a record's bytes from that point alone, and double coordinates are
 * the exact world values. The header differs by the padding line.
 *
 * Choice: a padding comment rather than a zero-padded count ("element vertex 000042"): a reader
 * that parses the count with base 0 (C's strtol convention) would read zero-padded digits as
 * octal; every PLY reader skips comments. */
#include "ply_join.h"

#include "../core/internal.h"
#include <pointnpr/io.h>
#include <pointnpr/output.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define JOIN_HEADER_MAX ((size_t)1 << 20) /* a header longer than this is not pointnpr's */
#define JOIN_COUNT_DIGITS 20              /* room for any uint64 count */



/* h (len bytes, ending in "end_header\n") with its vertex count replaced by "0": a new string,
 * NULL when it has no "element vertex N" line or memory runs out. */
static char *zero_count(const unsigned char *h, size_t len)
{
    char *s = malloc(len + 1);
    if (!s) return NULL;
    memcpy(s, h, len);
    s[len] = '\0';
    char *e = strstr(s, "\nelement vertex ");
    if (!e) { free(s); return NULL; }
    char *d = e + strlen("\nelement vertex "), *end = d;
    while (*end >= '0' && *end <= '9') end++;
    if (end == d || *end != '\n') { free(s); return NULL; }
    d[0] = '0';
    memmove(d + 1, end, strlen(end) + 1);
    return s;
}

/* The output's header for `count` points: the first header with the count and the padding
 * comment before its first element line. Its length never depends on count. Returns 0 when
 * every byte was written. */
int pnpr_join_header(pnpr_join_sink *j, uint64_t count)
{
    char digits[32];
    int nd = snprintf(digits, sizeof digits, "%llu", (unsigned long long)count);
    const char *elem = strstr(j->first, "\nelement ") + 1, *vc = strstr(j->first, "\nelement vertex 0\n") + 1;
    char pad[JOIN_COUNT_DIGITS + 48];
    int np = snprintf(pad, sizeof pad, "comment joined: room for the count%*s\n", JOIN_COUNT_DIGITS - nd, "");
    const char *vend = vc + strlen("element vertex 0"), *end = j->first + strlen(j->first) - strlen("end_header\n");
    const char *comment = j->extra_comment ? j->extra_comment : "", *elems = j->extra_elements ? j->extra_elements : "";
    int bad = pnpr_output_sink(j->out, j->first, (size_t)(elem - j->first)) ||
              pnpr_output_sink(j->out, pad, (size_t)np) || pnpr_output_sink(j->out, comment, strlen(comment)) ||
              pnpr_output_sink(j->out, elem, (size_t)(vc - elem)) ||
              pnpr_output_sink(j->out, "element vertex ", 15) || pnpr_output_sink(j->out, digits, (size_t)nd) ||
              pnpr_output_sink(j->out, vend, (size_t)(end - vend)) || pnpr_output_sink(j->out, elems, strlen(elems)) ||
              pnpr_output_sink(j->out, end, strlen(end));
    return bad;
}

/* The header once complete: the first's is kept and written, a later one compared. */
static int header_done(pnpr_join_sink *j)
{
    char *z = zero_count(j->head.data, j->head.size);
    j->head.size = 0;
    if (!z) { j->no_memory = 1; return 1; } /* the writer always writes "element vertex N" */
    if (!j->first) {
        j->first = z;
        return pnpr_join_header(j, 0);
    }
    j->mismatch = strcmp(z, j->first) != 0;
    free(z);
    return j->mismatch;
}

static int join_write(void *user, const void *data, size_t size)
{
    pnpr_join_sink *j = user;
    const unsigned char *p = data;
    while (size && !j->in_records) {
        /* the writer gives the header in pieces: collect up to its end */
        if (pnpr_mem_sink_write(&j->head, p, 1)) { j->no_memory = 1; return 1; }
        p++;
        size--;
        size_t n = j->head.size;
        if (n > JOIN_HEADER_MAX) { j->too_long = 1; return 1; }
        /* a line of its own: "property float end_header" ends in the same 11 bytes */
        if (n >= 12 && !memcmp(j->head.data + n - 12, "\nend_header\n", 12)) {
            if (header_done(j)) return 1;
            j->in_records = 1;
        }
    }
    return size ? pnpr_output_sink(j->out, p, size) : 0;
}

/* One input read and passed on; *r_points grows by its count. An empty input is skipped (a text
 * file without points has no columns to compare), unless it is the last and none had points:
 * then its header is the output's. */
static pnpr_status join_one(pnpr_join_sink *j, const char *path, const pnpr_join_options *o, int last, uint64_t *r_points,
                            pnpr_error *err)
{
    pnpr_cloud c = {0};
    pnpr_status st = pnpr_read_file(path, &o->read, &c, err);
    if (st != PNPR_OK) return st;
    if (c.count == 0 && (j->first || !last)) {
        pnpr_cloud_free(&c);
        return PNPR_OK;
    }
    if (c.faces.count) {
        pnpr_cloud_free(&c);
        return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "%s: has faces; a mesh is joined in memory (pointnpr convert without --stream)",
                              path);
    }
    st = pnpr_join_cloud(j, &c, &o->write, path, err);
    *r_points += c.count;
    pnpr_cloud_free(&c);
    return st;
}

pnpr_status pnpr_join_cloud(pnpr_join_sink *j, const pnpr_cloud *c, const pnpr_write_options *write, const char *path,
                            pnpr_error *err)
{
    pnpr_write_options wo = *write;
    wo.format = PNPR_FORMAT_PLY;
    wo.progress = (pnpr_progress){0};
    j->in_records = 0;
    pnpr_status st = pnpr_write_ply_stream(join_write, j, c, &wo, err);
    if (j->no_memory) return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s: out of memory for its PLY header", path);
    if (j->mismatch)
        return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED,
                              "%s: its points have other properties or types than the first input's (pointnpr info shows "
                              "them); join such files in memory (pointnpr convert without --stream) or convert them apart",
                              path);
    if (j->too_long) return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "%s: a PLY header longer than 1 MiB", path);
    if (st != PNPR_OK && err && !strstr(err->message, path)) { /* the writer's message names no input */
        char m[sizeof err->message];
        snprintf(m, sizeof m, "%s", err->message);
        pnpr_error_set(err, st, "%s: %s", path, m);
    }
    return st;
}

static pnpr_status check_join(const char *const *inputs, size_t count, const char *path, const pnpr_join_options *o,
                              pnpr_error *err)
{
    if (!path || (count && !inputs))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "join: no inputs or no output");
    for (size_t i = 0; i < count; i++)
        if (!inputs[i]) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "join: input %zu is NULL", i + 1);
    if (o->read.keep || o->read.origin)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "join: a point filter or origin is not the join's");
    if (o->write.format != PNPR_FORMAT_AUTO && o->write.format != PNPR_FORMAT_PLY)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "%s: a join writes PLY", path);
    return PNPR_OK;
}

pnpr_status pnpr_join_ply(const char *const *inputs, size_t count, const char *path, const pnpr_join_options *opts,
                          uint64_t *r_points, pnpr_error *err)
{
    pnpr_join_options o = opts ? *opts : (pnpr_join_options){0};
    if (r_points) *r_points = 0;
    pnpr_status st = check_join(inputs, count, path, &o, err);
    if (st != PNPR_OK) return st;
    if (!count) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "%s: no inputs to join", path);
    /* the output is none of the inputs (also through links): the rename at the end would replace it */
    if ((st = pnpr_output_check(path, inputs, count, err)) != PNPR_OK) return st;
    pnpr_output out;
    if ((st = pnpr_output_open(&out, path, err)) != PNPR_OK) return st;
    if (out.mode != PNPR_OUTPUT_REPLACE) {
        pnpr_status discarded = pnpr_output_close(&out, PNPR_ERR_UNSUPPORTED, NULL);
        return pnpr_error_set(err, discarded,
                              "%s: a join writes its vertex count last, into a regular file (not a device, pipe or "
                              "standard output)", path);
    }
    pnpr_join_sink j = {&out, {0}, 0, NULL, 0, 0, 0, NULL, NULL};
    uint64_t points = 0;
    for (size_t i = 0; st == PNPR_OK && i < count; i++) {
        if (pnpr_progress_report(&o.progress, "join", (double)i / (double)count))
            st = pnpr_error_set(err, PNPR_ERR_CANCELLED, "%s: cancelled; nothing written", path);
        else st = join_one(&j, inputs[i], &o, i + 1 == count, &points, err);
        if (st == PNPR_OK && points > UINT32_MAX)
            st = pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "%s: %llu points after %s, more than one cloud holds (%u: 32-bit "
                                "indices)", path, (unsigned long long)points, inputs[i], UINT32_MAX);
    }
    if (st == PNPR_OK && (fflush(out.f) != 0 || fseek(out.f, 0, SEEK_SET) != 0 || pnpr_join_header(&j, points)))
        st = PNPR_ERR_IO;
    if (st == PNPR_OK) pnpr_progress_report(&o.progress, "join", 1.0);
    free(j.head.data);
    free(j.first);
    pnpr_status cs = pnpr_output_close(&out, st, err);
    if (r_points && cs == PNPR_OK) *r_points = points;
    return cs;
}
