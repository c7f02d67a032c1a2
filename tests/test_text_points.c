/* Text point clouds (io/text_points.c): XYZ, PTS, PWN, CSV/TXT with header rows or --columns,
 * every separator, comments, CR LF, exact doubles, colours as bytes or floats, count lines, and
 * errors with their line. Expected values are the ones the test texts spell out. */
#include "testutil.h"

#include <pointnpr/io.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SCRATCH(name) PNPR_TEST_SCRATCH "/text_" name

static pnpr_status read_mem(const char *text, pnpr_file_format fmt, const char *columns, pnpr_cloud *c,
                            pnpr_error *err)
{
    pnpr_read_options o = {0};
    o.format = fmt;
    o.columns = columns;
    pnpr_status st = pnpr_read_text_memory(text, strlen(text), &o, c, err);
    if (st != PNPR_OK) fprintf(stderr, "(expected or not) %s\n", err->message);
    return st;
}

static void check_point(const pnpr_cloud *c, size_t i, double x, double y, double z)
{
    CHECK_MSG(i < c->count, "point %zu of %zu", i, c->count);
    if (i >= c->count) return;
    double w[3];
    pnpr_cloud_world(c, i, w);
    CHECK_MSG(w[0] == x && w[1] == y && w[2] == z, "point %zu = %.17g %.17g %.17g, want %.17g %.17g %.17g", i, w[0],
              w[1], w[2], x, y, z);
}

static void test_xyz_and_pwn(void)
{
    pnpr_cloud c = {0};
    pnpr_error err;
    /* georeferenced: exact doubles, comments, blank lines, CR LF, tabs */
    CHECK_STATUS(read_mem("# scan\r\n5000000.123 5000000.456 100.789\r\n\r\n5000001.001\t5000000.002  100.5 # c\r\n",
                          PNPR_FORMAT_XYZ, NULL, &c, &err), PNPR_OK);
    CHECK(c.count == 2 && c.src_xyz != NULL && c.src_coord_type == PNPR_TYPE_FLOAT64);
    check_point(&c, 0, 5000000.123, 5000000.456, 100.789);
    check_point(&c, 1, 5000001.001, 5000000.002, 100.5);
    CHECK(c.normal == NULL && c.rgb == NULL && c.prop_count == 0);
    if (c.count == 2) CHECK(fabs(c.origin[0] + c.xyz[0] - 5000000.123) < 1e-3);
    /* six values: normals (CGAL's .xyz and .pwn) */
    CHECK_STATUS(read_mem("1 2 3 0 0 1\n4 5 6 0.6 0.8 0\n", PNPR_FORMAT_PWN, NULL, &c, &err), PNPR_OK);
    CHECK(c.count == 2 && c.normal != NULL && c.rgb == NULL);
    if (c.normal && c.count == 2) CHECK(c.normal[2] == 1.0f && c.normal[3] == 0.6f && c.normal[4] == 0.8f);
    /* six values that are all bytes, some above 1: colours (CloudCompare's x y z r g b) */
    CHECK_STATUS(read_mem("1 2 3 255 0 10\n4 5 6 0 1 0\n", PNPR_FORMAT_XYZ, NULL, &c, &err), PNPR_OK);
    CHECK(c.count == 2 && c.normal == NULL && c.rgb != NULL);
    if (c.rgb && c.count == 2) CHECK(c.rgb[0] == 255 && c.rgb[1] == 0 && c.rgb[2] == 10 && c.rgb[4] == 1);
    /* nine values (CGAL's triangles.xyz): normals, then extra properties */
    CHECK_STATUS(read_mem("1 2 3 0 0 1 7 8 9\n", PNPR_FORMAT_XYZ, NULL, &c, &err), PNPR_OK);
    CHECK(c.count == 1 && c.normal != NULL && c.prop_count == 3);
    if (c.prop_count == 3) {
        CHECK(strcmp(c.props[0].name, "scalar_7") == 0 && strcmp(c.props[2].name, "scalar_9") == 0);
        CHECK(c.props[1].type == PNPR_TYPE_FLOAT64 && ((double *)c.props[1].data)[0] == 8.0);
    }
    /* a normal beyond float range becomes infinite (no undefined conversion); .pwn is always normals */
    CHECK_STATUS(read_mem("1 2 3 1e300 0 0\n", PNPR_FORMAT_XYZ, NULL, &c, &err), PNPR_OK);
    CHECK(c.count == 1 && c.normal && isinf(c.normal[0]) && c.normal[0] > 0);
    CHECK_STATUS(read_mem("1 2 3 255 0 10\n", PNPR_FORMAT_PWN, NULL, &c, &err), PNPR_OK);
    CHECK(c.count == 1 && c.normal && !c.rgb && c.normal[0] == 255.0f);
    /* nan stays a (non-finite) point; an empty file is an empty cloud */
    CHECK_STATUS(read_mem("1 2 3\nnan 0 0\n", PNPR_FORMAT_XYZ, NULL, &c, &err), PNPR_OK);
    CHECK(c.count == 2 && c.src_xyz && isnan(c.src_xyz[3]));
    CHECK_STATUS(read_mem("# nothing\n", PNPR_FORMAT_XYZ, NULL, &c, &err), PNPR_OK);
    CHECK(c.count == 0);
    pnpr_cloud_free(&c);
}

static void test_pts(void)
{
    pnpr_cloud c = {0};
    pnpr_error err;
    CHECK_STATUS(read_mem("3\n1.5 2.5 3.5 -1200 10 20 30\n4 5 6 0 40 50 60\n7 8 9 2047 255 255 255\n",
                          PNPR_FORMAT_PTS, NULL, &c, &err), PNPR_OK);
    CHECK(c.count == 3 && c.rgb != NULL && c.prop_count == 1);
    check_point(&c, 0, 1.5, 2.5, 3.5);
    if (c.rgb && c.count == 3) CHECK(c.rgb[0] == 10 && c.rgb[5] == 60 && c.rgb[8] == 255);
    if (c.prop_count == 1) {
        CHECK(strcmp(c.props[0].name, "intensity") == 0);
        CHECK(((double *)c.props[0].data)[0] == -1200.0 && ((double *)c.props[0].data)[2] == 2047.0);
    }
    /* two scans, each with its count line; a count line that announces more is truncated */
    CHECK_STATUS(read_mem("1\n1 2 3\n2\n4 5 6\n7 8 9\n", PNPR_FORMAT_PTS, NULL, &c, &err), PNPR_OK);
    CHECK(c.count == 3);
    check_point(&c, 2, 7, 8, 9);
    CHECK_STATUS(read_mem("5\n1 2 3\n4 5 6\n", PNPR_FORMAT_PTS, NULL, &c, &err), PNPR_ERR_TRUNCATED);
    CHECK(strstr(err.message, "line 1: the count line announces 5 points, 2 follow") != NULL && err.line == 1);
    CHECK(c.count == 0 && c.xyz == NULL);
    pnpr_cloud_free(&c);
}

static void test_csv(void)
{
    pnpr_cloud c = {0};
    pnpr_error err;
    /* header row, commas, float colours, a label, an extra column, a skipped one */
    CHECK_STATUS(read_mem("X,Y,Z,Red,Green,Blue,label,gps_time,_\n1,2,3,1.0,0.5,0,7,1e9,x\n", PNPR_FORMAT_CSV, NULL,
                          &c, &err), PNPR_ERR_FORMAT); /* 'x' in a skipped column is still no number */
    CHECK(strstr(err.message, "line 2: point 0, column 9 (_): 'x' is not a number") != NULL);
    CHECK_STATUS(read_mem("X,Y,Z,Red,Green,Blue,label,gps_time,_\n1,2,3,1.0,0.5,0,7,1e9,0\n", PNPR_FORMAT_CSV, NULL,
                          &c, &err), PNPR_OK);
    CHECK(c.count == 1 && c.rgb && c.label && c.prop_count == 1);
    check_point(&c, 0, 1, 2, 3);
    if (c.rgb && c.label && c.count == 1) CHECK(c.rgb[0] == 255 && c.rgb[1] == 128 && c.rgb[2] == 0 && c.label[0] == 7);
    if (c.prop_count == 1) CHECK(strcmp(c.props[0].name, "gps_time") == 0 && ((double *)c.props[0].data)[0] == 1e9);
    /* CloudCompare's header, semicolons */
    CHECK_STATUS(read_mem("//X;Y;Z;Nx;Ny;Nz\n1;2;3;0;1;0\n", PNPR_FORMAT_CSV, NULL, &c, &err), PNPR_OK);
    CHECK(c.count == 1 && c.normal && c.normal[1] == 1.0f);
    /* --columns: names given, the file's own header row skipped */
    CHECK_STATUS(read_mem("a b c d\n10 1 2 3\n", PNPR_FORMAT_CSV, "intensity,x,y,z", &c, &err), PNPR_OK);
    check_point(&c, 0, 1, 2, 3);
    CHECK(c.prop_count == 1 && strcmp(c.props[0].name, "intensity") == 0);
    CHECK_STATUS(read_mem("1 2 3\n", PNPR_FORMAT_CSV, "x,y", &c, &err), PNPR_ERR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "no z column") != NULL);
    pnpr_cloud_free(&c);
}

static void test_errors(void)
{
    pnpr_cloud c = {0};
    pnpr_error err;
    CHECK_STATUS(read_mem("1 2 3\n4 5\n", PNPR_FORMAT_XYZ, NULL, &c, &err), PNPR_ERR_FORMAT);
    CHECK(strstr(err.message, "line 2: 2 values, the columns give 3") != NULL && err.line == 2);
    CHECK_STATUS(read_mem("1 2 3\n4 5 1,5.2\n", PNPR_FORMAT_XYZ, NULL, &c, &err), PNPR_ERR_FORMAT);
    CHECK_STATUS(read_mem("1 2 3\n4 5 0x10\n", PNPR_FORMAT_XYZ, NULL, &c, &err), PNPR_ERR_FORMAT);
    CHECK(strstr(err.message, "line 2: point 1, column 3 (z): '0x10' is not a number") != NULL);
    CHECK_STATUS(read_mem("1 2 3\n4 5 1e400\n", PNPR_FORMAT_XYZ, NULL, &c, &err), PNPR_ERR_FORMAT);
    CHECK_STATUS(read_mem("1 2 3\n\x01\x02\n", PNPR_FORMAT_XYZ, NULL, &c, &err), PNPR_ERR_FORMAT);
    CHECK(strstr(err.message, "line 2: byte 0x01 (offset 6) is not text") != NULL);
    CHECK_STATUS(read_mem("hello world\n", PNPR_FORMAT_XYZ, NULL, &c, &err), PNPR_ERR_FORMAT);
    CHECK(strstr(err.message, "line 1: the columns (header) have no x column") != NULL);
    CHECK_STATUS(read_mem("1 2 3 300 0 0\n", PNPR_FORMAT_PTS, NULL, &c, &err), PNPR_ERR_FORMAT);
    CHECK(strstr(err.message, "line 1: integer colour values are bytes 0..255") != NULL);
    CHECK(c.count == 0 && c.xyz == NULL);
    /* through pnpr_read_file: the extension picks the reader, the message names the file */
    FILE *f = fopen(SCRATCH("bad.xyz"), "wb");
    CHECK(f && fputs("1 2 3\n4 5 6 7\n", f) >= 0 && fclose(f) == 0);
    CHECK_STATUS(pnpr_read_file(SCRATCH("bad.xyz"), NULL, &c, &err), PNPR_ERR_FORMAT);
    CHECK(strncmp(err.message, SCRATCH("bad.xyz") ": line 2: 4 values", strlen(SCRATCH("bad.xyz") ": line 2: 4 values")) == 0);
    f = fopen(SCRATCH("ok.txt"), "wb");
    CHECK(f && fputs("x y z intensity\n1 2 3 4\n", f) >= 0 && fclose(f) == 0);
    CHECK_STATUS(pnpr_read_file(SCRATCH("ok.txt"), NULL, &c, &err), PNPR_OK);
    CHECK(c.count == 1 && c.prop_count == 1);
    CHECK(pnpr_format_from_path("a.XYZ") == PNPR_FORMAT_XYZ && pnpr_format_from_path("a.pts") == PNPR_FORMAT_PTS &&
          pnpr_format_from_path("a.pwn") == PNPR_FORMAT_PWN && pnpr_format_from_path("a.csv") == PNPR_FORMAT_CSV);
    pnpr_cloud_free(&c);
}

int main(void)
{
    test_xyz_and_pwn();
    test_pts();
    test_csv();
    test_errors();
    return pnpr_test_finish("test_text_points");
}
