/* OBJ/OFF input through the OpenMesh adapter: files written by the test, read back with exact
 * coordinates (5e6 + millimetres), faces as listed in the file, colours, normals, errors.
 * Skipped (and passing) only when the build has no OpenMesh. */
#include "testutil.h"

#include <pointnpr/io.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifndef PNPR_HAVE_OPENMESH
int main(void)
{
    pnpr_cloud c = {0};
    pnpr_error err;
    CHECK_STATUS(pnpr_read_mesh_file("x.obj", NULL, &c, &err), PNPR_ERR_UNSUPPORTED);
    CHECK(strstr(err.message, "OpenMesh") != NULL);
    printf("skipped: no OpenMesh\n");
    return pnpr_test_finish("test_mesh_io");
}
#else

#define SCRATCH(name) PNPR_TEST_SCRATCH "/mesh_" name

static int write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    if (!f) return 0;
    size_t n = strlen(text);
    int ok = fwrite(text, 1, n, f) == n;
    return fclose(f) == 0 && ok;
}

/* Reads `path` (written from `text`) with pnpr_read_file; returns the status. */
static pnpr_status read_text(const char *path, const char *text, pnpr_cloud *c, pnpr_error *err)
{
    CHECK_MSG(write_text(path, text), "cannot write %s", path);
    pnpr_status st = pnpr_read_file(path, NULL, c, err);
    if (st != PNPR_OK) fprintf(stderr, "(expected or not) %s: %s\n", path, err->message);
    return st;
}

static const double k_georef[4][3] = {
    {5000000.123, 5000000.456, 100.789},
    {5000001.001, 5000000.002, 100.5},
    {5000000.5, 5000001.25, 101.0},
    {5000001.0, 5000001.0, 101.5},
};
#define GEOREF_OBJ_V \
    "v 5000000.123 5000000.456 100.789\n" \
    "v 5000001.001 5000000.002 100.5\n"   \
    "v 5000000.5 5000001.25 101\n"        \
    "v 5000001 5000001 101.5\n"
#define GEOREF_OFF_V \
    "5000000.123 5000000.456 100.789\n" \
    "5000001.001 5000000.002 100.5\n"   \
    "5000000.5 5000001.25 101\n"        \
    "5000001 5000001 101.5\n"

static void check_georef(const char *what, const pnpr_cloud *c)
{
    CHECK_MSG(c->count == 4, "%s: count %zu", what, c->count);
    if (c->count != 4) return;
    CHECK_MSG(c->src_xyz != NULL && c->src_coord_type == PNPR_TYPE_FLOAT64, "%s: no exact coordinates", what);
    for (size_t i = 0; i < 4; i++)
        for (int a = 0; a < 3; a++) {
            double w[3];
            pnpr_cloud_world(c, i, w);
            CHECK_MSG(w[a] == k_georef[i][a], "%s: vertex %zu axis %d: %.17g != %.17g", what, i, a, w[a],
                      k_georef[i][a]);
            double via_float = c->origin[a] + (double)c->xyz[3 * i + a];
            CHECK_MSG(fabs(via_float - k_georef[i][a]) < 1e-4, "%s: float offset %zu.%d", what, i, a);
        }
}

/* Faces as flat lists: sizes[f] corners each, indices concatenated. */
static void check_faces(const char *what, const pnpr_cloud *c, size_t nf, const unsigned *sizes, const unsigned *idx)
{
    CHECK_MSG(c->faces.count == nf, "%s: %zu faces, want %zu", what, c->faces.count, nf);
    if (c->faces.count != nf || nf == 0) return;
    size_t k = 0;
    CHECK(c->faces.offset[0] == 0);
    for (size_t f = 0; f < nf; f++) {
        CHECK_MSG(c->faces.offset[f + 1] - c->faces.offset[f] == sizes[f], "%s: face %zu size", what, f);
        for (uint32_t j = c->faces.offset[f]; j < c->faces.offset[f + 1]; j++, k++)
            CHECK_MSG(c->faces.index[j] == idx[k], "%s: face %zu corner %u = %u, want %u", what, f,
                      j - c->faces.offset[f], c->faces.index[j], idx[k]);
    }
}

static void test_obj(void)
{
    pnpr_cloud c = {0};
    pnpr_error err;
    /* vertices and faces (a quad and a triangle sharing edges: non-manifold for OpenMesh's mesh,
     * but kept as the file lists them) */
    CHECK_STATUS(read_text(SCRATCH("georef.obj"),
                           "# georeferenced quad\n" GEOREF_OBJ_V "f 1 2 3 4\nf 1 2 3\n", &c, &err), PNPR_OK);
    check_georef("obj", &c);
    static const unsigned sizes[] = {4, 3}, idx[] = {0, 1, 2, 3, 0, 1, 2};
    check_faces("obj", &c, 2, sizes, idx);
    CHECK(c.rgb == NULL && c.normal == NULL && c.label == NULL && c.prop_count == 0);

    /* vertices only: a point cloud */
    CHECK_STATUS(read_text(SCRATCH("points.OBJ"),
                           "v 0.5 1.5 2.5\nv -1 -2 -3\n\nv 1e3 2e-3 0\n# end\n", &c, &err), PNPR_OK);
    CHECK(c.count == 3 && c.faces.count == 0);
    if (c.count == 3) {
        double w[3];
        pnpr_cloud_world(&c, 2, w);
        CHECK(w[0] == 1e3 && w[1] == 2e-3 && w[2] == 0.0);
        pnpr_cloud_world(&c, 1, w);
        CHECK(w[0] == -1.0 && w[1] == -2.0 && w[2] == -3.0);
    }

    /* vertex colours (floats after the coordinates) */
    CHECK_STATUS(read_text(SCRATCH("colours.obj"),
                           "v 1 2 3 1 0 0\nv 4 5 6 0 0 1\nv 7 8 9 0.2 0.4 0.6\n", &c, &err), PNPR_OK);
    CHECK(c.count == 3 && c.rgb != NULL);
    if (c.count == 3 && c.rgb) {
        static const uint8_t want[9] = {255, 0, 0, 0, 0, 255, 51, 102, 153};
        for (int k = 0; k < 9; k++) CHECK_MSG(c.rgb[k] == want[k], "obj colour %d = %u", k, c.rgb[k]);
    }

    /* normals through f v//vn (normalised) */
    CHECK_STATUS(read_text(SCRATCH("normals.obj"),
                           "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 2\nvn 0 0 1\nvn 3 0 0\nf 1//1 2//2 3//3\n", &c, &err),
                 PNPR_OK);
    CHECK(c.count == 3 && c.normal != NULL && c.faces.count == 1);
    if (c.count == 3 && c.normal) {
        CHECK(c.normal[2] == 1.0f && c.normal[5] == 1.0f && c.normal[6] == 1.0f);
        CHECK(c.normal[0] == 0.0f && c.normal[7] == 0.0f && c.normal[8] == 0.0f);
    }

    /* three triangles on one edge: OpenMesh's mesh would duplicate vertices, the cloud does not */
    CHECK_STATUS(read_text(SCRATCH("nonmanifold.obj"),
                           "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n", &c, &err),
                 PNPR_OK);
    CHECK(c.count == 5);
    static const unsigned nm_sizes[] = {3, 3, 3}, nm_idx[] = {0, 1, 2, 1, 0, 3, 0, 1, 4};
    check_faces("non-manifold obj", &c, 3, nm_sizes, nm_idx);
    pnpr_cloud_free(&c);
}

static void test_off(void)
{
    pnpr_cloud c = {0};
    pnpr_error err;
    CHECK_STATUS(read_text(SCRATCH("georef.off"), "OFF\n4 2 0\n" GEOREF_OFF_V "3 0 1 2\n4 3 2 1 0\n", &c, &err),
                 PNPR_OK);
    check_georef("off", &c);
    static const unsigned sizes[] = {3, 4}, idx[] = {0, 1, 2, 3, 2, 1, 0};
    check_faces("off", &c, 2, sizes, idx);
    CHECK(c.rgb == NULL && c.normal == NULL);

    /* blank lines are fine */
    CHECK_STATUS(read_text(SCRATCH("blank.off"), "OFF\n\n4 0 0\n" GEOREF_OFF_V "\n", &c, &err), PNPR_OK);
    check_georef("off with blank lines", &c);

    /* COFF with RGBA bytes */
    CHECK_STATUS(read_text(SCRATCH("colours.off"),
                           "COFF\n4 1 0\n"
                           "5000000.123 5000000.456 100.789 255 0 10 255\n"
                           "5000001.001 5000000.002 100.5 0 128 0 255\n"
                           "5000000.5 5000001.25 101 1 2 3 255\n"
                           "5000001 5000001 101.5 40 50 60 128\n"
                           "3 0 1 3\n",
                           &c, &err),
                 PNPR_OK);
    check_georef("coff", &c);
    CHECK(c.rgb != NULL);
    if (c.rgb && c.count == 4) {
        static const uint8_t want[12] = {255, 0, 10, 0, 128, 0, 1, 2, 3, 40, 50, 60};
        for (int k = 0; k < 12; k++) CHECK_MSG(c.rgb[k] == want[k], "coff colour %d = %u", k, c.rgb[k]);
    }
    static const unsigned c_sizes[] = {3}, c_idx[] = {0, 1, 3};
    check_faces("coff", &c, 1, c_sizes, c_idx);

    /* COFF with float colours */
    CHECK_STATUS(read_text(SCRATCH("fcolours.off"),
                           "COFF\n2 0 0\n1 2 3 1.0 0.0 0.2 1.0\n4 5 6 0.0 1.0 0.0 1.0\n", &c, &err), PNPR_OK);
    CHECK(c.count == 2 && c.rgb != NULL);
    if (c.rgb && c.count == 2) {
        static const uint8_t want[6] = {255, 0, 51, 0, 255, 0};
        for (int k = 0; k < 6; k++) CHECK_MSG(c.rgb[k] == want[k], "coff float colour %d = %u", k, c.rgb[k]);
    }

    /* NOFF normals */
    CHECK_STATUS(read_text(SCRATCH("normals.off"), "NOFF\n2 0 0\n1 2 3 0 0 1\n4 5 6 0 2 0\n", &c, &err), PNPR_OK);
    CHECK(c.count == 2 && c.normal != NULL && c.rgb == NULL);
    if (c.normal && c.count == 2) {
        CHECK(c.normal[0] == 0.0f && c.normal[1] == 0.0f && c.normal[2] == 1.0f);
        CHECK(c.normal[3] == 0.0f && c.normal[4] == 1.0f && c.normal[5] == 0.0f);
    }

    /* OFF recognised by its keyword when the extension says nothing (read through a stream) */
    CHECK_STATUS(read_text(SCRATCH("sniffed.dat"), "OFF\n4 1 0\n" GEOREF_OFF_V "3 0 1 2\n", &c, &err), PNPR_OK);
    check_georef("sniffed off", &c);
    CHECK(c.faces.count == 1);
    pnpr_cloud_free(&c);
}

static void expect_error(const char *path, const char *text, pnpr_status want, const char *needle)
{
    pnpr_cloud c = {0};
    pnpr_error err;
    CHECK(pnpr_cloud_alloc(&c, 7) == PNPR_OK); /* must be freed and left zeroed */
    pnpr_status st = text ? read_text(path, text, &c, &err) : pnpr_read_file(path, NULL, &c, &err);
    CHECK_MSG(st == want, "%s: got %s, want %s (%s)", path, pnpr_status_string(st), pnpr_status_string(want),
              err.message);
    CHECK_MSG(strstr(err.message, needle) != NULL, "%s: message \"%s\" lacks \"%s\"", path, err.message, needle);
    CHECK_MSG(strncmp(err.message, path, strlen(path)) == 0, "%s: message does not start with the path", path);
    CHECK(c.count == 0 && c.xyz == NULL && c.faces.count == 0);
    pnpr_cloud_free(&c);
}

static void test_errors(void)
{
    remove(SCRATCH("missing.obj"));
    expect_error(SCRATCH("missing.obj"), NULL, PNPR_ERR_IO, "No such file or directory");
    remove(SCRATCH("missing.off"));
    expect_error(SCRATCH("missing.off"), NULL, PNPR_ERR_IO, "No such file or directory");
    expect_error(SCRATCH("garbage.off"), "this is not an OFF file\n", PNPR_ERR_FORMAT, "OpenMesh could not read the file");
    expect_error(SCRATCH("truncated.off"), "OFF\n10 0 0\n1 2 3\n4 5 6\n", PNPR_ERR_TRUNCATED, "announces 10 vertices");
    expect_error(SCRATCH("comment.off"), "OFF\n3 0 0\n# a comment\n1 2 3\n4 5 6\n7 8 9\n", PNPR_ERR_FORMAT,
                 "OpenMesh read vertex");
    /* direct call with a format that is not OBJ/OFF */
    pnpr_cloud c = {0};
    pnpr_error err;
    pnpr_read_options opts = {0};
    opts.format = PNPR_FORMAT_LAS;
    CHECK_STATUS(pnpr_read_mesh_file(SCRATCH("georef.obj"), &opts, &c, &err), PNPR_ERR_UNSUPPORTED);
    CHECK_STATUS(pnpr_read_mesh_file(NULL, NULL, &c, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_read_mesh_file(SCRATCH("georef.obj"), NULL, NULL, &err), PNPR_ERR_INVALID_ARGUMENT);
}

typedef struct progress_log {
    int calls, cancel_at;
    double last;
} progress_log;

static int log_progress(void *user, const char *stage, double fraction)
{
    progress_log *l = user;
    CHECK(strcmp(stage, "read mesh") == 0);
    l->calls++;
    l->last = fraction;
    return l->cancel_at && l->calls >= l->cancel_at;
}

static void test_progress(void)
{
    pnpr_cloud c = {0};
    pnpr_error err;
    progress_log log = {0, 0, -1.0};
    pnpr_read_options opts = {0};
    opts.progress.fn = log_progress;
    opts.progress.user = &log;
    CHECK(write_text(SCRATCH("progress.obj"), GEOREF_OBJ_V));
    CHECK_STATUS(pnpr_read_file(SCRATCH("progress.obj"), &opts, &c, &err), PNPR_OK);
    CHECK(c.count == 4);
    CHECK(log.calls >= 2 && log.last == 1.0);
    for (int at = 1; at <= 3; at++) {
        progress_log cancel = {0, at, -1.0};
        opts.progress.user = &cancel;
        CHECK_STATUS(pnpr_read_file(SCRATCH("progress.obj"), &opts, &c, &err), PNPR_ERR_CANCELLED);
        CHECK(c.count == 0 && c.xyz == NULL);
    }
    pnpr_cloud_free(&c);
}

int main(void)
{
    test_obj();
    test_off();
    test_errors();
    test_progress();
    return pnpr_test_finish("test_mesh_io");
}
#endif
