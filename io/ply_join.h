/* pointnpr — clouds written one after another as one PLY file (io/ply_join.c; internal to the
 * library): the join of files, and the file ordered for drawing (io/ply_lod.c). */
#ifndef PNPR_PLY_JOIN_H
#define PNPR_PLY_JOIN_H

#include <pointnpr/io.h>
#include <pointnpr/output.h>

typedef struct pnpr_join_sink {
    pnpr_output *out;
    pnpr_mem_sink head;    /* this cloud's header while it is collected */
    int in_records;        /* the header is done: records pass through */
    char *first;           /* the first cloud's header, count "0", no padding (NUL-terminated) */
    int mismatch;          /* a later header differs from the first's */
    int too_long;
    int no_memory;         /* collecting or comparing a header ran out of memory */
    const char *extra_comment;  /* NULL, or lines ("comment ...\n") after the padding comment */
    const char *extra_elements; /* NULL, or element lines after the vertex element's */
} pnpr_join_sink;

/* One cloud's records into the output (its header, the first's, or compared with it; `path`
 * names it in messages). */
PNPR_NODISCARD pnpr_status pnpr_join_cloud(pnpr_join_sink *j, const pnpr_cloud *c, const pnpr_write_options *write,
                                           const char *path, pnpr_error *err);
/* Writes the output's header for `count` points (the same length for every count); 0 when every
 * byte was written. */
int pnpr_join_header(pnpr_join_sink *j, uint64_t count);

#endif
