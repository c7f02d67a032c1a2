/* An input file as one read-only byte range, for the readers that parse a buffer (io/ply.c,
 * io/pcd.c, io/las.c); not installed.
 *
 * A regular file is mapped (mmap, read-only): its pages come from the page cache when the parser
 * touches them, and nothing is copied to the heap. Each reader parses its header first and checks
 * the counts it announces against the size before it allocates or touches the body, so a file
 * whose header lies (a 2 GB sparse file "with" 10^9 points) costs the header's pages and fails
 * at once instead of being read whole. Pipes, character devices and files that cannot be mapped
 * are read into memory (there is no size to check a header against before reading them).
 *
 * Caveat, as for every mapping reader (PCL's PCD reader maps too): if another process truncates
 * the file while it is being parsed, touching the pages that vanished raises SIGBUS. */
#ifndef PNPR_FILE_BYTES_H
#define PNPR_FILE_BYTES_H

#include <pointnpr/io.h>

#include <stddef.h>

typedef struct pnpr_file_bytes {
    const unsigned char *data; /* size bytes; never NULL once opened */
    size_t size;
    void *map;                 /* the mapping (unmapped by close), or NULL */
    unsigned char *copy;       /* the heap copy (freed by close), or NULL */
} pnpr_file_bytes;

/* Opens path and makes its bytes available; errors name the path (PNPR_ERR_IO with the system's
 * reason, PNPR_ERR_OUT_OF_MEMORY). On error *fb is zeroed and nothing needs closing. */
pnpr_status pnpr_file_bytes_open(const char *path, pnpr_file_bytes *fb, pnpr_error *err);

/* A mapped file: hands back the pages of bytes [from, upto) (whole pages inside the range), so
 * that a reader going through a file larger than memory (a tile's filter pass, tiles.h) holds
 * only the part it is in; pages touched again come back from the file. No-op for a heap copy or
 * NULL. */
void pnpr_file_bytes_drop(const pnpr_file_bytes *fb, size_t from, size_t upto);

/* Releases what open took; safe on a zeroed struct. */
void pnpr_file_bytes_close(pnpr_file_bytes *fb);

/* A reader of a whole file's bytes (pnpr_read_ply_memory, ...). */
typedef pnpr_status (*pnpr_memory_reader)(const void *data, size_t size, const pnpr_read_options *opts,
                                          pnpr_cloud *cloud, pnpr_error *err);

/* The file entry point of a buffer reader: opens path (above), runs read on its bytes, closes;
 * the reader's errors are prefixed with the path. cloud is freed first. */
pnpr_status pnpr_file_bytes_read(const char *path, pnpr_memory_reader read, const pnpr_read_options *opts,
                                 pnpr_cloud *cloud, pnpr_error *err);

#endif
