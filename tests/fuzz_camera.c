/* libFuzzer target for the camera file and camera path parsers (view/camera_path_io.c:
 * `--camera FILE`, `--camera-path FILE`). Every input is parsed both ways. Each parse must finish
 * without crash, leak or undefined behaviour; a failure leaves a zeroed result and a message that
 * names the text ("NAME:LINE: ..." or "NAME: ..."); a camera file that parses has finite eye,
 * target and up and a fov in (0, 179); a path that parses passes pnpr_camera_path_check, has at
 * most one key per 12 bytes of text (a key needs "eye X Y Z" and "target X Y Z" lines: no count
 * is trusted), and printed back with %.17g it parses to the same keys bit for bit. */
#include <pointnpr/camera_path.h>

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int finite3(const double v[3])
{
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

static void fuzz_camera_file(const char *text, size_t size)
{
    pnpr_camera_key k;
    unsigned given = 99;
    pnpr_error err;
    memset(&err, 0, sizeof err);
    if (pnpr_camera_file_parse(text, size, "camera.txt", &k, &given, &err) != PNPR_OK) {
        if (strncmp(err.message, "camera.txt:", 11) != 0) abort();
        return;
    }
    if (!finite3(k.eye) || !finite3(k.target) || !finite3(k.up) || !(k.fov_y_deg > 0 && k.fov_y_deg < 179) ||
        given > (PNPR_CAMERA_GIVEN_UP | PNPR_CAMERA_GIVEN_FOV))
        abort();
}

/* The path printed back (keys only; "loop" first when closed); NULL when out of memory. */
static char *print_path(const pnpr_camera_path *p, size_t *r_size)
{
    size_t cap = 16 + 320 * p->count, n = 0;
    char *t = malloc(cap);
    if (!t) return NULL;
    n += (size_t)snprintf(t + n, cap - n, "%s", p->loop ? "loop\n" : "");
    for (size_t i = 0; i < p->count; i++) {
        const pnpr_camera_key *k = &p->keys[i];
        n += (size_t)snprintf(t + n, cap - n, "time %.17g\neye %.17g %.17g %.17g\ntarget %.17g %.17g %.17g\n"
                              "up %.17g %.17g %.17g\nfov %.17g\n", k->time, k->eye[0], k->eye[1], k->eye[2],
                              k->target[0], k->target[1], k->target[2], k->up[0], k->up[1], k->up[2], k->fov_y_deg);
    }
    *r_size = n;
    return t;
}

static void fuzz_camera_path(const char *text, size_t size)
{
    pnpr_camera_path path, back;
    pnpr_error err;
    memset(&err, 0, sizeof err);
    if (pnpr_camera_path_parse(text, size, "path.txt", &path, &err) != PNPR_OK) {
        if (path.keys || path.count || path.loop || strncmp(err.message, "path.txt:", 9) != 0) abort();
        return;
    }
    if (pnpr_camera_path_check(&path, &err) != PNPR_OK || path.count > size / 12) abort();
    size_t n = 0;
    char *t = print_path(&path, &n);
    if (t) {
        if (pnpr_camera_path_parse(t, n, "back", &back, &err) != PNPR_OK || back.count != path.count ||
            back.loop != path.loop || memcmp(back.keys, path.keys, path.count * sizeof *path.keys) != 0)
            abort();
        pnpr_camera_path_free(&back);
        free(t);
    }
    pnpr_camera_path_free(&path);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_camera_file((const char *)data, size);
    fuzz_camera_path((const char *)data, size);
    return 0;
}
