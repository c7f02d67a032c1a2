/* Camera path files (camera_path.h, docs/export.md): the camera-file lines (eye, target, up, fov)
 * per key, each key opened by "time T", "loop" to close the path; and camera files, the same
 * lines for one camera without "time" and "loop". Both parsed from memory (fuzzed:
 * tests/fuzz_camera.c). Errors name FILE:LINE. */
#include "camera_path_internal.h"

#include "../core/internal.h"

#include <pointnpr/output.h>

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct path_reader {
    const char *file;
    pnpr_camera_path *path;
    size_t cap;
    int implicit;              /* camera lines came before any "time": one key at time 0 */
    int single;                /* a camera file: no "time" or "loop", one message for bad lines */
    int have_eye, have_target;  /* of the key being read */
    unsigned given;             /* PNPR_CAMERA_GIVEN_* lines of a camera file */
    long key_line;             /* where the key being read starts */
} path_reader;

static pnpr_status fail(pnpr_error *err, const path_reader *r, long line, const char *what)
{
    pnpr_status st = pnpr_error_set(err, PNPR_ERR_FORMAT, "%s:%ld: %s", r->file, line, what);
    if (err) err->line = line;
    return st;
}

static pnpr_status camera_file_incomplete(const path_reader *r, pnpr_error *err)
{
    return pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: a camera file needs both 'eye' and 'target'", r->file);
}

/* The key being read is complete and valid on its own. */
static pnpr_status finish_key(path_reader *r, pnpr_error *err)
{
    if (r->path->count == 0) return PNPR_OK;
    const pnpr_camera_key *k = &r->path->keys[r->path->count - 1];
    char why[200], msg[300];
    if (r->single) /* the CLI's --camera checks the view itself (cli_view_check) */
        return r->have_eye && r->have_target ? PNPR_OK : camera_file_incomplete(r, err);
    if (!r->have_eye || !r->have_target) {
        snprintf(msg, sizeof msg, "the key at time %g needs both 'eye' and 'target'", k->time);
        return fail(err, r, r->key_line, msg);
    }
    if (pnpr_camera_key_problem(k, why, sizeof why)) {
        snprintf(msg, sizeof msg, "the key at time %g: %s", k->time, why);
        return fail(err, r, r->key_line, msg);
    }
    return PNPR_OK;
}

/* Opens a new key at time t (the previous key's up and fov, else 0 0 1 and 45). */
static pnpr_status new_key(path_reader *r, double t, long line, pnpr_error *err)
{
    pnpr_camera_path *p = r->path;
    if (p->count == PNPR_CAMERA_PATH_KEYS_MAX) return fail(err, r, line, "too many keys (at most 100000)");
    if (p->count == r->cap) {
        size_t cap = r->cap ? 2 * r->cap : 16;
        pnpr_camera_key *k2 = realloc(p->keys, cap * sizeof *k2);
        if (!k2) return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s: out of memory", r->file);
        p->keys = k2;
        r->cap = cap;
    }
    pnpr_camera_key *k = &p->keys[p->count];
    memset(k, 0, sizeof *k);
    k->up[2] = 1;
    k->fov_y_deg = 45;
    if (p->count > 0) {
        memcpy(k->up, p->keys[p->count - 1].up, sizeof k->up);
        k->fov_y_deg = p->keys[p->count - 1].fov_y_deg;
    }
    k->time = t;
    p->count++;
    r->have_eye = r->have_target = 0;
    r->key_line = line;
    return PNPR_OK;
}

static pnpr_status time_line(path_reader *r, const char *line, long ln, pnpr_error *err)
{
    double t;
    char extra[2], msg[200];
    if (r->implicit) return fail(err, r, ln, "'time' after camera lines without a time: give every key a 'time' line first");
    if (sscanf(line, " %*s %lf %1s", &t, extra) != 1 || !isfinite(t)) return fail(err, r, ln, "expected 'time SECONDS'");
    pnpr_status st = finish_key(r, err);
    if (st != PNPR_OK) return st;
    if (r->path->count > 0 && !(t > r->path->keys[r->path->count - 1].time)) {
        snprintf(msg, sizeof msg, "time %g is not after the previous key's time %g", t, r->path->keys[r->path->count - 1].time);
        return fail(err, r, ln, msg);
    }
    return new_key(r, t, ln, err);
}

#define CAMERA_FILE_EXPECTED "expected 'eye|target|up X Y Z' or 'fov DEG' (0 < DEG < 179)"

static pnpr_status camera_line(path_reader *r, const char *key, const char *line, long ln, pnpr_error *err)
{
    double x[3];
    char extra[2];
    pnpr_status st;
    if (r->path->count == 0 && (st = new_key(r, 0, ln, err)) != PNPR_OK) return st;
    if (r->path->count == 1 && r->key_line == ln) r->implicit = 1;
    pnpr_camera_key *k = &r->path->keys[r->path->count - 1];
    if (!strcmp(key, "fov")) {
        if (sscanf(line, " %*s %lf %1s", &x[0], extra) != 1 || !(x[0] > 0 && x[0] < 179))
            return fail(err, r, ln, r->single ? CAMERA_FILE_EXPECTED : "expected 'fov DEG' (0 < DEG < 179)");
        k->fov_y_deg = x[0];
        r->given |= PNPR_CAMERA_GIVEN_FOV;
        return PNPR_OK;
    }
    if (sscanf(line, " %*s %lf %lf %lf %1s", &x[0], &x[1], &x[2], extra) != 3 || !isfinite(x[0]) || !isfinite(x[1]) || !isfinite(x[2]))
        return fail(err, r, ln, r->single ? CAMERA_FILE_EXPECTED : "expected 'eye|target|up X Y Z' (finite numbers)");
    double *dst = !strcmp(key, "eye") ? k->eye : (!strcmp(key, "target") ? k->target : k->up);
    memcpy(dst, x, sizeof x);
    if (!strcmp(key, "eye")) r->have_eye = 1;
    if (!strcmp(key, "target")) r->have_target = 1;
    if (!strcmp(key, "up")) r->given |= PNPR_CAMERA_GIVEN_UP;
    return PNPR_OK;
}

static pnpr_status read_line(path_reader *r, char *line, long ln, pnpr_error *err)
{
    char key[32], extra[2];
    char *hash = strchr(line, '#');
    if (hash) *hash = 0;
    if (sscanf(line, " %31s", key) != 1) return PNPR_OK; /* blank */
    if (!strcmp(key, "eye") || !strcmp(key, "target") || !strcmp(key, "up") || !strcmp(key, "fov"))
        return camera_line(r, key, line, ln, err);
    if (r->single) return fail(err, r, ln, CAMERA_FILE_EXPECTED);
    if (!strcmp(key, "time")) return time_line(r, line, ln, err);
    if (!strcmp(key, "loop")) {
        if (sscanf(line, " %*s %1s", extra) == 1) return fail(err, r, ln, "expected 'loop' alone on its line");
        r->path->loop = 1;
        return PNPR_OK;
    }
    return fail(err, r, ln, "expected 'time T', 'eye|target|up X Y Z', 'fov DEG' or 'loop'");
}

static pnpr_status read_lines(path_reader *r, const char *text, size_t size, long *r_ln, pnpr_error *err)
{
    char line[1024];
    size_t pos = 0;
    long ln = 0;
    pnpr_status st = PNPR_OK;
    for (int got; st == PNPR_OK && (got = pnpr_text_line(text, size, &pos, line, sizeof line)) != 0;) {
        ln++;
        st = got < 0 ? fail(err, r, ln, "line longer than 1022 characters") : read_line(r, line, ln, err);
    }
    *r_ln = ln;
    return st;
}

pnpr_status pnpr_camera_path_parse(const char *text, size_t size, const char *name, pnpr_camera_path *r_path,
                                   pnpr_error *err)
{
    if ((!text && size) || !name || !r_path) return PNPR_ERR_INVALID_ARGUMENT;
    memset(r_path, 0, sizeof *r_path);
    path_reader r = {.file = name, .path = r_path};
    long ln = 0;
    pnpr_status st = read_lines(&r, text, size, &ln, err);
    if (st == PNPR_OK) st = finish_key(&r, err);
    if (st == PNPR_OK && r_path->count == 0) st = fail(err, &r, ln, "no camera: expected 'time T' with 'eye' and 'target' lines");
    if (st == PNPR_OK && r_path->loop && !pnpr_camera_path_loop_closed(r_path))
        st = fail(err, &r, ln, "'loop' needs at least 3 keys, the last repeating the first key's eye, target and up");
    if (st != PNPR_OK) pnpr_camera_path_free(r_path);
    return st;
}

pnpr_status pnpr_camera_path_read(const char *filename, pnpr_camera_path *r_path, pnpr_error *err)
{
    if (!filename || !r_path) return PNPR_ERR_INVALID_ARGUMENT;
    memset(r_path, 0, sizeof *r_path);
    char *text = NULL;
    size_t size = 0;
    pnpr_status st = pnpr_text_file_load(filename, PNPR_CAMERA_FILE_MAX, &text, &size, err);
    if (st == PNPR_OK) st = pnpr_camera_path_parse(text, size, filename, r_path, err);
    free(text);
    return st;
}

pnpr_status pnpr_camera_file_parse(const char *text, size_t size, const char *name, pnpr_camera_key *r_camera,
                                   unsigned *r_given, pnpr_error *err)
{
    if ((!text && size) || !name || !r_camera) return PNPR_ERR_INVALID_ARGUMENT;
    pnpr_camera_path path = {0};
    path_reader r = {.file = name, .path = &path, .single = 1};
    long ln = 0;
    pnpr_status st = read_lines(&r, text, size, &ln, err);
    if (st == PNPR_OK) st = path.count ? finish_key(&r, err) : camera_file_incomplete(&r, err);
    if (st == PNPR_OK) *r_camera = path.keys[0];
    if (st == PNPR_OK && r_given) *r_given = r.given;
    pnpr_camera_path_free(&path);
    return st;
}

static int print_path(FILE *f, const void *ctx)
{
    const pnpr_camera_path *p = ctx;
    int bad = fprintf(f, "# pointnpr camera path (world coordinates; docs/export.md)\n") < 0;
    if (p->loop) bad |= fprintf(f, "loop\n") < 0;
    for (size_t i = 0; i < p->count && !bad; i++) {
        const pnpr_camera_key *k = &p->keys[i];
        bad |= fprintf(f, "time %.17g\neye %.17g %.17g %.17g\ntarget %.17g %.17g %.17g\nup %.17g %.17g %.17g\nfov %.17g\n",
                       k->time, k->eye[0], k->eye[1], k->eye[2], k->target[0], k->target[1], k->target[2], k->up[0],
                       k->up[1], k->up[2], k->fov_y_deg) < 0;
    }
    return bad;
}

pnpr_status pnpr_camera_path_write(const char *filename, const pnpr_camera_path *path, pnpr_error *err)
{
    pnpr_status st = pnpr_camera_path_check(path, err);
    if (st != PNPR_OK) return st;
    return pnpr_output_write(filename, print_path, path, err);
}
