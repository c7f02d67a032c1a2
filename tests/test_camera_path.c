/* Camera paths (camera_path.h), pure CPU: the path passes through every key (exactly), the up of
 * an orbit never flips (also steep and backwards), a loop is C1 at its seam, a flyover moves
 * linearly, files round-trip bit for bit and bad files name FILE:LINE, the preset start frames
 * the content. */
#include "testutil.h"

#include <pointnpr/camera_path.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static double dist(const double a[3], const double b[3])
{
    double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return sqrt(dot(d, d));
}
static void view_dir(const pnpr_camera *c, double d[3])
{
    for (int k = 0; k < 3; k++) d[k] = c->target[k] - c->eye[k];
    double l = sqrt(dot(d, d));
    for (int k = 0; k < 3; k++) d[k] /= l;
}

/* Five keys at uneven times with tilted ups and changing fov. */
static void make_path(pnpr_camera_path *p)
{
    static const double t[5] = {0, 0.7, 1.1, 3.0, 3.25};
    p->count = 5;
    p->loop = 0;
    p->keys = calloc(5, sizeof *p->keys);
    for (int i = 0; i < 5; i++) {
        pnpr_camera_key *k = &p->keys[i];
        k->time = t[i];
        k->eye[0] = 4e5 + 3 * cos(i); k->eye[1] = -2e6 + 2 * sin(1.3 * i); k->eye[2] = 100 + 0.5 * i;
        k->target[0] = 4e5 + 0.1 * i; k->target[1] = -2e6; k->target[2] = 99;
        k->up[0] = 0.1 * i; k->up[1] = 0; k->up[2] = 1;
        k->fov_y_deg = 40 + 3 * i;
    }
}

static void test_through_keys(void)
{
    pnpr_camera_path p;
    make_path(&p);
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_camera_path_check(&p, &err), PNPR_OK);
    for (size_t i = 0; i < p.count; i++) {
        pnpr_camera c;
        CHECK_STATUS(pnpr_camera_path_eval(&p, p.keys[i].time, &c), PNPR_OK);
        CHECK_MSG(!memcmp(c.eye, p.keys[i].eye, sizeof c.eye) && !memcmp(c.target, p.keys[i].target, sizeof c.target),
                  "key %zu: eye/target not exactly the key's", i);
        CHECK_NEAR(c.fov_y_deg, p.keys[i].fov_y_deg, 1e-5);
        double d[3], u[3] = {p.keys[i].up[0], p.keys[i].up[1], p.keys[i].up[2]};
        view_dir(&c, d);
        double a = dot(u, d);
        for (int k = 0; k < 3; k++) u[k] -= a * d[k];
        CHECK_NEAR(dot(u, c.up) / sqrt(dot(u, u)), 1.0, 1e-12);
    }
    /* between the keys: continuous (no jump over a small step) and held outside */
    pnpr_camera a, b;
    for (double t = 0; t < 3.25; t += 1e-3) {
        CHECK_STATUS(pnpr_camera_path_eval(&p, t, &a), PNPR_OK);
        CHECK_STATUS(pnpr_camera_path_eval(&p, t + 1e-6, &b), PNPR_OK);
        CHECK_MSG(dist(a.eye, b.eye) < 1e-3 && dist(a.target, b.target) < 1e-3 && dot(a.up, b.up) > 0.999999, "jump at t %g", t);
    }
    CHECK_STATUS(pnpr_camera_path_eval(&p, -5, &a), PNPR_OK);
    CHECK(!memcmp(a.eye, p.keys[0].eye, sizeof a.eye));
    CHECK_STATUS(pnpr_camera_path_eval(&p, 99, &a), PNPR_OK);
    CHECK(!memcmp(a.eye, p.keys[4].eye, sizeof a.eye));
    CHECK_NEAR(pnpr_camera_path_duration(&p), 3.25, 0);
    pnpr_camera_path_free(&p);
}

/* An orbit preset from a start at `elev` degrees: the up never flips, stays in the vertical
 * plane of the view, and the eye stays on the circle. */
static void check_orbit(double elev, double degrees, int expect_loop)
{
    pnpr_camera start;
    memset(&start, 0, sizeof start);
    double r = 5, e = elev * 3.14159265358979323846 / 180;
    start.target[0] = 10; start.target[1] = 20; start.target[2] = 3;
    start.eye[0] = 10; start.eye[1] = 20 - r * cos(e); start.eye[2] = 3 + r * sin(e);
    start.up[2] = 1;
    start.fov_y_deg = 50;
    pnpr_camera_preset_options o = {8, degrees};
    pnpr_camera_path p;
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_camera_path_preset(PNPR_PRESET_ORBIT, &start, NULL, &o, &p, &err), PNPR_OK);
    CHECK(p.loop == expect_loop);
    double prev[3] = {0, 0, 0}, worst_flip = 1, worst_r = 0, z[3] = {0, 0, 1};
    for (int s = 0; s <= 8000; s++) {
        pnpr_camera c;
        CHECK_STATUS(pnpr_camera_path_eval(&p, 8.0 * s / 8000, &c), PNPR_OK);
        double d[3];
        view_dir(&c, d);
        CHECK_MSG(fabs(dot(d, c.up)) < 1e-9, "up not orthogonal to the view at step %d", s);
        CHECK_MSG(dot(c.up, z) > 0, "up points down at step %d (elevation %g)", s, elev);
        if (s > 0 && dot(c.up, prev) < worst_flip) worst_flip = dot(c.up, prev);
        memcpy(prev, c.up, sizeof prev);
        double v[3] = {c.eye[0] - 10, c.eye[1] - 20, c.eye[2] - 3};
        double dr = fabs(sqrt(dot(v, v)) - r) / r;
        if (dr > worst_r) worst_r = dr;
        CHECK_NEAR(c.fov_y_deg, 50, 1e-5);
    }
    CHECK_MSG(worst_flip > 0.9999, "the up turned by acos(%g) between two samples", worst_flip);
    CHECK_MSG(worst_r < 1e-4, "the orbit leaves its circle by %g of the radius", worst_r);
    if (expect_loop) { /* C1 at the seam: the velocity just before the end equals the one just after the start */
        pnpr_camera a, b, c0, c1;
        CHECK_STATUS(pnpr_camera_path_eval(&p, 8 - 2e-4, &a), PNPR_OK);
        CHECK_STATUS(pnpr_camera_path_eval(&p, 8 - 1e-4, &b), PNPR_OK);
        CHECK_STATUS(pnpr_camera_path_eval(&p, 0, &c0), PNPR_OK);
        CHECK_STATUS(pnpr_camera_path_eval(&p, 1e-4, &c1), PNPR_OK);
        for (int k = 0; k < 3; k++) CHECK_NEAR((b.eye[k] - a.eye[k]) / 1e-4, (c1.eye[k] - c0.eye[k]) / 1e-4, 1e-3);
    }
    pnpr_camera_path_free(&p);
}

static void test_orbits(void)
{
    check_orbit(35, 0, 1);    /* a full turn: a loop */
    check_orbit(85, 360, 1);  /* nearly from the top */
    check_orbit(-20, -270, 0); /* from below, backwards, three quarters */
    check_orbit(10, 45, 0);   /* a short arc: 24 keys */
}

static void test_flyover(void)
{
    pnpr_camera start;
    memset(&start, 0, sizeof start);
    start.eye[0] = 0; start.eye[1] = -4.4; start.eye[2] = 3;
    start.up[2] = 1;
    pnpr_camera_path p;
    pnpr_camera_preset_options o = {4, 0};
    CHECK_STATUS(pnpr_camera_path_preset(PNPR_PRESET_FLYOVER, &start, NULL, &o, &p, NULL), PNPR_OK);
    pnpr_camera c;
    CHECK_STATUS(pnpr_camera_path_eval(&p, 0, &c), PNPR_OK);
    CHECK(!memcmp(c.eye, start.eye, sizeof c.eye));
    CHECK_NEAR(c.target[1], -4.4 + 2.4, 1e-12); /* 1.2 radii ahead (radius 2) */
    CHECK_NEAR(c.target[2], 0, 1e-12);
    CHECK_NEAR(c.fov_y_deg, 45, 0);
    CHECK_STATUS(pnpr_camera_path_eval(&p, 1, &c), PNPR_OK); /* a quarter: linear */
    CHECK_NEAR(c.eye[1], -4.4 + 0.25 * 4.4, 1e-12);
    CHECK_NEAR(c.eye[2], 3, 1e-12);
    pnpr_camera_path_free(&p);
    start.target[2] = 0; start.eye[0] = start.eye[1] = 0; /* straight down the up axis */
    CHECK_STATUS(pnpr_camera_path_preset(PNPR_PRESET_FLYOVER, &start, NULL, &o, &p, NULL), PNPR_ERR_INVALID_ARGUMENT);
}

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb"); /* test input, not an output of the library */
    fputs(text, f);
    fclose(f);
}

static void expect_error(const char *text, long line, const char *words)
{
    const char *path = PNPR_TEST_SCRATCH "/bad.campath";
    write_text(path, text);
    pnpr_camera_path p;
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_camera_path_read(path, &p, &err), PNPR_ERR_FORMAT);
    char where[64];
    snprintf(where, sizeof where, "bad.campath:%ld: ", line);
    CHECK_MSG(strstr(err.message, where) && strstr(err.message, words), "message '%s', want '%s' and '%s'", err.message, where, words);
    CHECK(err.line == line);
    CHECK(p.keys == NULL && p.count == 0);
}

static void test_files(void)
{
    pnpr_camera_path p, q;
    make_path(&p);
    pnpr_error err = {0};
    const char *path = PNPR_TEST_SCRATCH "/roundtrip.campath";
    CHECK_STATUS(pnpr_camera_path_write(path, &p, &err), PNPR_OK);
    CHECK_STATUS(pnpr_camera_path_read(path, &q, &err), PNPR_OK);
    CHECK(q.count == p.count && q.loop == 0 && !memcmp(q.keys, p.keys, p.count * sizeof *p.keys));
    pnpr_camera_path_free(&q);
    pnpr_camera_path_free(&p);
    /* a camera file is a one-key path; up and fov carry over from key to key */
    write_text(PNPR_TEST_SCRATCH "/cam.txt", "# camera\neye 1 2 3\ntarget 0 0 0\nfov 30\n");
    CHECK_STATUS(pnpr_camera_path_read(PNPR_TEST_SCRATCH "/cam.txt", &q, &err), PNPR_OK);
    CHECK(q.count == 1 && q.keys[0].time == 0 && q.keys[0].fov_y_deg == 30 && q.keys[0].up[2] == 1);
    pnpr_camera_path_free(&q);
    write_text(PNPR_TEST_SCRATCH "/two.campath", "time 0\neye 1 0 0\ntarget 0 0 0\nup 0 1 0\nfov 20\n\ntime 2 # later\neye 0 0 1\ntarget 0 0 0\n");
    CHECK_STATUS(pnpr_camera_path_read(PNPR_TEST_SCRATCH "/two.campath", &q, &err), PNPR_OK);
    CHECK(q.count == 2 && q.keys[1].time == 2 && q.keys[1].up[1] == 1 && q.keys[1].fov_y_deg == 20);
    pnpr_camera_path_free(&q);
    expect_error("time 0\neye 1 0 0\ntarget 0 0 0\ntime 0\neye 2 0 0\ntarget 0 0 0\n", 4, "not after the previous key's time 0");
    expect_error("time 0\neye 1 0 0\ntime 1\n", 1, "needs both 'eye' and 'target'");
    expect_error("time 0\neye 1 0 0\ntarget 0 0 0\nzoom 3\n", 4, "expected 'time T'");
    expect_error("time 0\neye 1 0 0\ntarget 0 0 x\n", 3, "expected 'eye|target|up X Y Z'");
    expect_error("time 0\neye 1 0 0\ntarget 1 0 0\n", 1, "eye and target are the same point");
    expect_error("time 0\neye 0 0 5\ntarget 0 0 0\nup 0 0 1\n", 1, "parallel to the view");
    expect_error("eye 1 0 0\ntarget 0 0 0\ntime 1\n", 3, "'time' after camera lines without a time");
    expect_error("loop\ntime 0\neye 1 0 0\ntarget 0 0 0\ntime 1\neye 0 1 0\ntarget 0 0 0\ntime 2\neye 0 2 0\ntarget 0 0 0\n", 10,
                 "'loop' needs at least 3 keys");
    expect_error("# nothing\n", 1, "no camera");
    CHECK_STATUS(pnpr_camera_path_read(PNPR_TEST_SCRATCH "/missing.campath", &q, &err), PNPR_ERR_IO);
}

/* Camera files from memory: the values, which lines were given, NAME:LINE errors; the view is the
 * host's to check (eye == target parses). */
static void test_camera_file(void)
{
    static const char text[] = "# camera\neye 1 2 3\ntarget 4 5 6 # look\n\nfov 30\neye -1 -2 -3";
    pnpr_camera_key k;
    unsigned given = 0;
    pnpr_error err = {0};
    CHECK_STATUS(pnpr_camera_file_parse(text, sizeof text - 1, "c.txt", &k, &given, &err), PNPR_OK);
    CHECK(k.eye[0] == -1 && k.eye[1] == -2 && k.eye[2] == -3 && k.target[0] == 4 && k.target[1] == 5 && k.target[2] == 6);
    CHECK(k.fov_y_deg == 30 && given == PNPR_CAMERA_GIVEN_FOV && k.up[2] == 1);
    static const char same[] = "eye 1 1 1\ntarget 1 1 1\nup 0 1 0\n";
    CHECK_STATUS(pnpr_camera_file_parse(same, sizeof same - 1, "s.txt", &k, &given, &err), PNPR_OK);
    CHECK(given == PNPR_CAMERA_GIVEN_UP && k.up[1] == 1 && k.fov_y_deg == 45);
    static const struct { const char *text, *message; } bad[] = {
        {"eye 1 2 3\ntarget 0 0 0\ntime 1\n", "b.txt:3: expected 'eye|target|up X Y Z' or 'fov DEG' (0 < DEG < 179)"},
        {"eye 1 2\n", "b.txt:1: expected 'eye|target|up X Y Z' or 'fov DEG' (0 < DEG < 179)"},
        {"\nfov 179\n", "b.txt:2: expected 'eye|target|up X Y Z' or 'fov DEG' (0 < DEG < 179)"},
        {"loop\n", "b.txt:1: expected 'eye|target|up X Y Z' or 'fov DEG' (0 < DEG < 179)"},
        {"eye 1 2 3\n", "b.txt: a camera file needs both 'eye' and 'target'"},
        {"# empty\n", "b.txt: a camera file needs both 'eye' and 'target'"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        CHECK_STATUS(pnpr_camera_file_parse(bad[i].text, strlen(bad[i].text), "b.txt", &k, &given, &err), PNPR_ERR_FORMAT);
        CHECK_MSG(!strcmp(err.message, bad[i].message), "got '%s', want '%s'", err.message, bad[i].message);
    }
}

/* The preset start frames the content from every side: a long flat strip (8 x 1) is in frame
 * (without the 5% margin) from 72 azimuths about z, and the distance is tight (some point touches
 * the frame's edge with the margin at one of the 36 azimuths fitted). */
static void test_preset_start(void)
{
    pnpr_cloud c = {0};
    const double off[3] = {1000, 2000, 10};
    CHECK_STATUS(pnpr_test_plane(&c, 81, 11, 0.1, off), PNPR_OK);
    pnpr_camera start, def;
    double up[3];
    const float aspect = 4.0f / 3;
    CHECK_STATUS(pnpr_camera_default(&c, NULL, 45, aspect, &def, NULL), PNPR_OK);
    CHECK_STATUS(pnpr_camera_preset_start(&c, NULL, 45, aspect, &start, up), PNPR_OK);
    CHECK_NEAR(up[2], 1, 1e-9);
    CHECK(!memcmp(start.target, def.target, sizeof def.target));
    CHECK(dist(start.eye, start.target) >= dist(def.eye, def.target));
    pnpr_camera_preset_options o = {72, 360};
    pnpr_camera_path p;
    CHECK_STATUS(pnpr_camera_path_preset(PNPR_PRESET_ORBIT, &start, up, &o, &p, NULL), PNPR_OK);
    double ty = tan(22.5 * 3.14159265358979323846 / 180), tx = ty * aspect, worst = 0;
    for (int k = 0; k < 72; k++) {
        pnpr_camera cam;
        CHECK_STATUS(pnpr_camera_path_eval(&p, k, &cam), PNPR_OK);
        double f[3], s[3], u[3];
        view_dir(&cam, f);
        s[0] = f[1] * cam.up[2] - f[2] * cam.up[1]; s[1] = f[2] * cam.up[0] - f[0] * cam.up[2]; s[2] = f[0] * cam.up[1] - f[1] * cam.up[0];
        u[0] = s[1] * f[2] - s[2] * f[1]; u[1] = s[2] * f[0] - s[0] * f[2]; u[2] = s[0] * f[1] - s[1] * f[0];
        for (size_t i = 0; i < c.count; i++) {
            double q[3] = {c.origin[0] + c.xyz[3 * i] - cam.eye[0], c.origin[1] + c.xyz[3 * i + 1] - cam.eye[1],
                           c.origin[2] + c.xyz[3 * i + 2] - cam.eye[2]};
            double z = dot(q, f), fx = fabs(dot(q, s)) / (z * tx), fy = fabs(dot(q, u)) / (z * ty);
            if (fx > worst) worst = fx;
            if (fy > worst) worst = fy;
        }
    }
    CHECK_MSG(worst <= 1.0 && worst > 0.9, "the content reaches %g of the half frame (want in (0.9, 1])", worst);
    pnpr_camera_path_free(&p);
    pnpr_cloud_free(&c);
}

int main(void)
{
    test_through_keys();
    test_orbits();
    test_flyover();
    test_files();
    test_camera_file();
    test_preset_start();
    return pnpr_test_finish("test_camera_path");
}
