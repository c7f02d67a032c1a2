/* libFuzzer target for the OBJ/OFF reader (OpenMesh behind the validating pre-pass of
 * io/mesh_check.c). Every input is read three times: named .obj, named .off, and without an
 * extension (sniffed by its magic bytes, OFF files then go through the reader's temporary link).
 * Each read must finish without crash, leak, undefined behaviour, hang or unbounded memory (the
 * CTest run enforces 1 s and 100 MB per input of at most 1 KB, tests/corpus/fuzz_mesh.options).
 * A failure leaves a zeroed cloud and a message that starts with the file name, and comes from
 * the pre-pass, never from the adapter's checks behind OpenMesh ("FILE: OpenMesh could not read",
 * "FILE: OpenMesh read ..."): what the pre-pass lets through, OpenMesh must read as it says. An
 * OBJ/OFF cloud that reads has at most one vertex per 6 bytes of file (counts are never
 * trusted), and faces of at least 3 corners that all name its vertices.
 *
 * OpenMesh reads from a path, so the input is written to files in a private temporary folder,
 * made on the first call and removed at exit: the only state this target keeps. */
#include <pointnpr/io.h>

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

typedef struct fuzz_files {
    char dir[192], obj[224], off[224], bare[224];
} fuzz_files;

static void fuzz_cleanup(void);

/* The folder and the three names, made once per process. */
static const fuzz_files *fuzz_paths(void)
{
    static fuzz_files files;
    static int ready;
    if (!ready) {
        const char *tmp = getenv("TMPDIR");
        snprintf(files.dir, sizeof files.dir, "%s/pnpr-fuzz-mesh-XXXXXX", tmp && *tmp ? tmp : "/tmp");
        if (!mkdtemp(files.dir)) abort();
        snprintf(files.obj, sizeof files.obj, "%s/input.obj", files.dir);
        snprintf(files.off, sizeof files.off, "%s/input.off", files.dir);
        snprintf(files.bare, sizeof files.bare, "%s/input", files.dir);
        ready = 1;
        atexit(fuzz_cleanup);
    }
    return &files;
}

static void fuzz_cleanup(void)
{
    const fuzz_files *f = fuzz_paths();
    remove(f->obj);
    remove(f->off);
    remove(f->bare);
    rmdir(f->dir);
}

static void write_input(const char *path, const uint8_t *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f || (size && fwrite(data, 1, size, f) != size) || fclose(f) != 0) abort();
}

/* Faces of >= 3 corners naming vertices of the cloud, offsets increasing from 0. */
static void check_faces(const pnpr_cloud *c)
{
    if (!c->faces.count) return;
    if (!c->faces.offset || !c->faces.index || c->faces.offset[0] != 0) abort();
    for (size_t f = 0; f < c->faces.count; f++) {
        uint32_t b = c->faces.offset[f], e = c->faces.offset[f + 1];
        if (e < b || e - b < 3) abort();
        for (uint32_t j = b; j < e; j++)
            if (c->faces.index[j] >= c->count) abort();
    }
}

/* mesh: the name says OBJ or OFF (other sniffed formats have other invariants). */
static void read_input(const char *path, int mesh, size_t size)
{
    pnpr_cloud c;
    pnpr_error err;
    memset(&c, 0, sizeof c);
    if (pnpr_read_file(path, NULL, &c, &err) != PNPR_OK) {
        pnpr_cloud zero;
        memset(&zero, 0, sizeof zero);
        if (memcmp(&c, &zero, sizeof zero) != 0 || strncmp(err.message, path, strlen(path)) != 0) abort();
        /* the pre-pass must catch what OpenMesh cannot read or reads differently */
        if (mesh && strncmp(err.message + strlen(path), ": OpenMesh ", 11) == 0) abort();
        return;
    }
    if (mesh) {
        if (c.count > size / 6) abort();
        check_faces(&c);
    }
    pnpr_cloud_free(&c);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const fuzz_files *f = fuzz_paths();
    write_input(f->obj, data, size);
    read_input(f->obj, 1, size);
    write_input(f->off, data, size);
    read_input(f->off, 1, size);
    write_input(f->bare, data, size);
    read_input(f->bare, 0, size);
    return 0;
}
