/* Argument helpers shared by the subcommands: numbers, comma lists, the view options. */
#include "cli.h"

#include <pointnpr/camera.h>
#include <pointnpr/camera_path.h>

#include <pointnpr/memory.h>
#include <pointnpr/output.h>

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int cli_parse_number(const char *s, double lo, double hi, double *r)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (errno || end == s || *end || !isfinite(v) || v < lo || v > hi) return 0;
    *r = v;
    return 1;
}

void cli_option_usage(FILE *f, const pnpr_option_desc *d, const char *metavar)
{
    char left[64], def[64], range[64];
    snprintf(left, sizeof left, "--%s %s", d->name, metavar);
    pnpr_option_default_text(d, def, sizeof def);
    pnpr_option_range_text(d, range, sizeof range);
    int width = fprintf(f, "  %-20s %s", left, d->help);
    fprintf(f, width + (int)(strlen(def) + strlen(range)) > 88 ? "\n%23s(default %s, %s)\n" : "%s (default %s, %s)\n", "",
            def, range);
}

void cli_table_usage(FILE *f, const pnpr_option_desc *table, size_t count, const char *name, const char *metavar)
{
    const pnpr_option_desc *d = pnpr_option_find(table, count, name);
    if (d) cli_option_usage(f, d, metavar);
}

int cli_option_value(const pnpr_option_desc *d, const char *cmd, const char *v, double *r)
{
    if (cli_parse_number(v, -HUGE_VAL, HUGE_VAL, r) &&
        (pnpr_option_in_range(d, *r) || ((d->flags & PNPR_OPTION_NEGATIVE_OFF) && *r < 0 && isfinite(*r))))
        return 1; /* a negative value of a NEGATIVE_OFF option: off */
    char range[64];
    pnpr_option_range_text(d, range, sizeof range);
    const int integer = d->type == PNPR_OPTION_INT || d->type == PNPR_OPTION_UINT;
    fprintf(stderr, "pointnpr %s: --%s wants %s %s, got '%s'\n", cmd, d->name, integer ? "an integer" : "a number",
            range, v);
    return 0;
}

int cli_table_option(const pnpr_option_desc *table, size_t count, const char *const *names, void *opts,
                     const char *cmd, int argc, char **argv, int *i)
{
    const char *a = argv[*i];
    if (strncmp(a, "--", 2) != 0 || *i + 1 >= argc) return 0;
    const pnpr_option_desc *d = NULL;
    for (size_t n = 0; names[n] && !d; n++)
        if (!strcmp(a + 2, names[n])) d = pnpr_option_find(table, count, names[n]);
    if (!d) return 0;
    double x;
    if (!cli_option_value(d, cmd, argv[++*i], &x)) return -1;
    pnpr_option_set(d, opts, x);
    return 1;
}

int cli_parse_list(const char *s, int n, double *r)
{
    const char *p = s;
    for (int i = 0; i < n; i++) {
        char *end;
        errno = 0;
        r[i] = strtod(p, &end);
        if (errno || end == p || !isfinite(r[i])) return 0;
        if (i + 1 < n) { if (*end != ',') return 0; p = end + 1; }
        else if (*end) return 0;
    }
    return 1;
}

int cli_check_output(const char *cmd, const char *out, const char *const *inputs, size_t input_count, int binary)
{
    if (binary && !strcmp(out, "-") && isatty(STDOUT_FILENO)) {
        fprintf(stderr, "pointnpr %s: refusing to write binary data to a terminal (redirect standard output)\n", cmd);
        return 0;
    }
    pnpr_error err = {0};
    pnpr_status st = pnpr_output_check(out, inputs, input_count, &err);
    if (st != PNPR_OK) cli_report_error(cmd, st, &err);
    return st == PNPR_OK;
}

int cli_output_is_stream(const char *out)
{
    struct stat sb;
    return !strcmp(out, "-") || (stat(out, &sb) == 0 && !S_ISREG(sb.st_mode) && !S_ISDIR(sb.st_mode));
}

int cli_cloud_output(const char *cmd, const char *out, const char *in, pnpr_write_options *wo)
{
    pnpr_file_format f = pnpr_format_from_path(out);
    if (f == PNPR_FORMAT_AUTO && cli_output_is_stream(out)) f = PNPR_FORMAT_PLY;
    if (f != PNPR_FORMAT_PLY && f != PNPR_FORMAT_PCD) {
        fprintf(stderr, "pointnpr %s: %s: the output is a point cloud: its name must end in .ply or .pcd "
                        "(or be - or a device/FIFO for PLY)\n", cmd, out);
        return 2;
    }
    wo->format = f;
    return cli_check_output(cmd, out, &in, 1, wo->encoding != PNPR_PLY_ASCII || f == PNPR_FORMAT_PCD) ? 0 : 1;
}

int cli_has_ext(const char *path, const char *ext)
{
    size_t n = strlen(path), m = strlen(ext);
    if (n < m) return 0;
    for (size_t i = 0; i < m; i++)
        if (tolower((unsigned char)path[n - m + i]) != tolower((unsigned char)ext[i])) return 0;
    return 1;
}

void cli_view_init(cli_view *v, int width, int height)
{
    memset(v, 0, sizeof *v);
    v->up[2] = 1;
    v->fov = 45;
    v->width = width;
    v->height = height;
}

/* A camera file (pnpr_camera_file_parse, camera_path.h). Returns 1, or 0 after printing
 * FILE:LINE: what is wrong. */
static int read_camera_file(cli_view *v, const char *cmd, const char *path)
{
    char *text = NULL;
    size_t size = 0;
    pnpr_error err = {0};
    pnpr_camera_key k;
    unsigned given = 0;
    pnpr_status st = pnpr_text_file_load(path, PNPR_CAMERA_FILE_MAX, &text, &size, &err);
    if (st == PNPR_OK) st = pnpr_camera_file_parse(text, size, path, &k, &given, &err);
    free(text);
    if (st != PNPR_OK) { fprintf(stderr, "pointnpr %s: %s\n", cmd, err.message); return 0; }
    memcpy(v->eye, k.eye, sizeof v->eye);
    memcpy(v->target, k.target, sizeof v->target);
    if (given & PNPR_CAMERA_GIVEN_UP) { memcpy(v->up, k.up, sizeof v->up); v->have_up = 1; }
    if (given & PNPR_CAMERA_GIVEN_FOV) v->fov = k.fov_y_deg;
    v->have_eye = v->have_target = 1;
    return 1;
}

typedef struct camera_text {
    const double *eye, *target, *up;
    double fov;
} camera_text;

static int print_camera(FILE *f, const void *ctx)
{
    const camera_text *c = ctx;
    return fprintf(f, "# pointnpr camera (world coordinates; pointnpr render/lines --camera FILE)\n"
                      "eye %.17g %.17g %.17g\ntarget %.17g %.17g %.17g\nup %.17g %.17g %.17g\nfov %.9g\n",
                   c->eye[0], c->eye[1], c->eye[2], c->target[0], c->target[1], c->target[2], c->up[0], c->up[1],
                   c->up[2], c->fov) < 0;
}

int cli_write_camera_file(const char *path, const double eye[3], const double target[3], const double up[3], double fov)
{
    camera_text c = {eye, target, up, fov};
    pnpr_error err = {0};
    pnpr_status st = pnpr_output_write(path, print_camera, &c, &err);
    if (st != PNPR_OK) fprintf(stderr, "pointnpr: %s\n", err.message);
    return st == PNPR_OK;
}

/* --up auto|x|y|z|-x|-y|-z (up_mode) or X,Y,Z (a non-zero vector); 1 or -1 as cli_view_option. */
static int parse_up(cli_view *v, const char *cmd, const char *val)
{
    double u[3];
    if (pnpr_up_mode_parse(val, &v->up_mode)) {
        v->have_up_mode = 1;
        v->have_up = 0;
        return 1;
    }
    if (cli_parse_list(val, 3, u) && (u[0] != 0 || u[1] != 0 || u[2] != 0)) {
        memcpy(v->up, u, sizeof u);
        v->have_up = 1;
        v->have_up_mode = 0;
        return 1;
    }
    fprintf(stderr, "pointnpr %s: --up wants auto, x, y, z, -x, -y, -z or a non-zero vector X,Y,Z, got '%s'\n", cmd, val);
    return -1;
}

int cli_view_option(cli_view *v, const char *cmd, int argc, char **argv, int *i)
{
    const char *a = argv[*i], *val = *i + 1 < argc ? argv[*i + 1] : NULL;
    if (!strcmp(a, "--camera") && val) {
        (*i)++;
        return read_camera_file(v, cmd, val) ? 1 : -1;
    }
    double *vec = NULL;
    int *have = NULL;
    if (!strcmp(a, "--eye")) { vec = v->eye; have = &v->have_eye; }
    else if (!strcmp(a, "--target")) { vec = v->target; have = &v->have_target; }
    else if (strcmp(a, "--up") && strcmp(a, "--fov") && strcmp(a, "--size")) return 0;
    if (!val) return 0; /* "missing value" is reported by the caller's unknown-option path */
    (*i)++;
    if (!strcmp(a, "--up")) return parse_up(v, cmd, val);
    if (vec) {
        if (!cli_parse_list(val, 3, vec)) { fprintf(stderr, "pointnpr %s: %s wants X,Y,Z, got '%s'\n", cmd, a, val); return -1; }
        *have = 1;
        return 1;
    }
    if (!strcmp(a, "--fov")) {
        if (!cli_parse_number(val, 1e-3, 179, &v->fov)) { fprintf(stderr, "pointnpr %s: --fov wants degrees in (0,179], got '%s'\n", cmd, val); return -1; }
        return 1;
    }
    int w = 0, h = 0, n = 0;
    if (sscanf(val, "%dx%d%n", &w, &h, &n) != 2 || val[n] || w < 1 || h < 1 || w > 16384 || h > 16384) {
        fprintf(stderr, "pointnpr %s: --size wants WxH with 1..16384 each, got '%s'\n", cmd, val);
        return -1;
    }
    v->width = w;
    v->height = h;
    return 1;
}

/* |a x b| / (|a| |b|): the sine of the angle between a and b (0 when either is zero). */
static double sine_between(const double a[3], const double b[3])
{
    double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]), lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    return la > 0 && lb > 0 ? sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / la / lb : 0;
}

int cli_view_check(const cli_view *v, const char *cmd)
{
    if (v->have_eye != v->have_target) {
        fprintf(stderr, "pointnpr %s: --eye and --target go together\n", cmd);
        return 0;
    }
    if (!v->have_eye) return 1;
    double d[3] = {v->target[0] - v->eye[0], v->target[1] - v->eye[1], v->target[2] - v->eye[2]}, axis[3];
    if (d[0] == 0 && d[1] == 0 && d[2] == 0) {
        fprintf(stderr, "pointnpr %s: the eye and the target are the same point (%g,%g,%g); the camera needs a direction\n",
                cmd, v->eye[0], v->eye[1], v->eye[2]);
        return 0;
    }
    const double *up = v->have_up ? v->up : (v->have_up_mode && pnpr_up_mode_axis(v->up_mode, axis) ? axis : NULL);
    if (up && sine_between(d, up) < 1e-6) {
        fprintf(stderr, "pointnpr %s: --up (%g,%g,%g) is parallel to the view direction from the eye to the target; "
                        "give an up that is not\n", cmd, up[0], up[1], up[2]);
        return 0;
    }
    return 1;
}

static pnpr_view_options view_up_options(const cli_view *v)
{
    pnpr_view_options o = {0};
    if (v->have_up_mode) o.up_mode = v->up_mode;
    else if (v->have_up) {
        o.up_mode = PNPR_UP_VECTOR;
        memcpy(o.up, v->up, sizeof o.up);
    }
    return o;
}

const pnpr_camera *cli_view_camera(const cli_view *v, const pnpr_cloud *cloud, pnpr_camera *r_cam)
{
    memset(r_cam, 0, sizeof *r_cam);
    pnpr_view_options o = view_up_options(v);
    if (v->have_eye) {
        memcpy(r_cam->eye, v->eye, sizeof r_cam->eye);
        memcpy(r_cam->target, v->target, sizeof r_cam->target);
        memcpy(r_cam->up, v->up, sizeof r_cam->up); /* the vector form, else +z */
        pnpr_view_info info; /* an axis as given; auto: the detected up (+z without a point) */
        if (v->have_up_mode && !pnpr_up_mode_axis(v->up_mode, r_cam->up) && cloud &&
            pnpr_scene_frame(cloud, &o, &info) == PNPR_OK)
            memcpy(r_cam->up, info.up, sizeof r_cam->up);
        double d[3] = {v->target[0] - v->eye[0], v->target[1] - v->eye[1], v->target[2] - v->eye[2]};
        if (!v->have_up && sine_between(d, r_cam->up) < 1e-6) { /* e.g. straight down with the default +z */
            double y[3] = {0, 1, 0}, x[3] = {1, 0, 0};
            memcpy(r_cam->up, sine_between(d, y) > 0.5 ? y : x, sizeof r_cam->up);
        }
        r_cam->fov_y_deg = (float)v->fov;
        return r_cam;
    }
    if (cloud && cloud->count > 0 &&
        pnpr_camera_default(cloud, &o, (float)v->fov, (float)v->width / (float)v->height, r_cam, NULL) == PNPR_OK)
        return r_cam;
    return NULL;
}

int cli_view_preset_start(const cli_view *v, const pnpr_cloud *cloud, pnpr_camera *r_cam, double r_up[3])
{
    if (v->have_eye) {
        if (!cli_view_camera(v, cloud, r_cam)) return 0;
        memcpy(r_up, r_cam->up, sizeof r_cam->up);
        return 1;
    }
    pnpr_view_options o = view_up_options(v);
    return cloud && pnpr_camera_preset_start(cloud, &o, (float)v->fov, (float)v->width / (float)v->height, r_cam, r_up) == PNPR_OK;
}

int cli_columns_option(const char **columns, const char *cmd, int argc, char **argv, int *i)
{
    if (strcmp(argv[*i], "--columns") != 0) return 0;
    if (*i + 1 >= argc) {
        fprintf(stderr, "pointnpr %s: --columns wants a comma-separated list of names (x,y,z,...)\n", cmd);
        return -1;
    }
    const char *v = argv[++*i];
    /* the reader checks the names; an empty cloud read from no text says whether they are usable */
    pnpr_read_options ro = {0};
    ro.format = PNPR_FORMAT_CSV;
    ro.columns = v;
    pnpr_cloud c = {0};
    pnpr_error err = {0};
    if (pnpr_read_text_memory("", 0, &ro, &c, &err) != PNPR_OK) {
        fprintf(stderr, "pointnpr %s: --columns '%s': %s\n", cmd, v, err.message);
        return -1;
    }
    pnpr_cloud_free(&c);
    *columns = v;
    return 1;
}

void cli_columns_usage(FILE *f)
{
    fprintf(f, "  --columns NAMES      columns of a text point cloud (.xyz .pts .pwn .csv .txt), e.g.\n"
               "                       x,y,z,r,g,b; names: x y z nx ny nz r g b label intensity ... _ (skip);\n"
               "                       default: the file's header row, else the format's columns (docs/io.md)\n");
}

int cli_memory_option(size_t *limit, const char *cmd, int argc, char **argv, int *i)
{
    if (strcmp(argv[*i], "--memory-limit") || *i + 1 >= argc) return 0;
    const char *v = argv[++*i];
    if (pnpr_memory_parse(v, limit) == 0) return 1;
    fprintf(stderr, "pointnpr %s: --memory-limit wants a size such as 512M or 4G (K, M, G, T: KiB..TiB), got '%s'\n",
            cmd, v);
    return -1;
}

void cli_memory_usage(FILE *f)
{
    fprintf(f, "  --memory-limit SIZE  refuse before the work when the estimated peak of the process\n"
               "                       exceeds SIZE (512M, 4G; default: the memory the machine has\n"
               "                       available); a larger SIZE overrides the check\n");
}

int cli_memory_check_file(const char *cmd, const char *in, size_t limit)
{
    struct stat st;
    if (stat(in, &st) != 0 || !S_ISREG(st.st_mode)) return 1; /* a folder of tiles, a missing file: the reader says */
    char what[600];
    snprintf(what, sizeof what, "reading %s (read whole)", in);
    pnpr_error err = {0};
    if (pnpr_memory_check((size_t)st.st_size, limit, what, &err) == PNPR_OK) return 1;
    fprintf(stderr, "pointnpr %s: %s%s\n", cmd, err.message, limit ? "" : "; --memory-limit SIZE sets the limit yourself");
    return 0;
}

int cli_memory_check_plan(const char *cmd, const char *in, size_t limit, const pnpr_memory_plan *plan)
{
    pnpr_memory_estimate e;
    pnpr_memory_estimate_plan(plan, &e);
    char what[700], a[32], b[32], c[32];
    snprintf(what, sizeof what, "%s: %zu points (stages %s, kept %s%s%s)", in, plan->points,
             pnpr_memory_text(e.stages, a, sizeof a), pnpr_memory_text(e.kept, b, sizeof b),
             e.render ? ", renderer " : "", e.render ? pnpr_memory_text(e.render, c, sizeof c) : "");
    pnpr_error err = {0};
    if (pnpr_memory_check(e.total, limit, what, &err) == PNPR_OK) return 1;
    fprintf(stderr, "pointnpr %s: %s%s\n", cmd, err.message, limit ? "" : "; --memory-limit SIZE sets the limit yourself");
    return 0;
}
