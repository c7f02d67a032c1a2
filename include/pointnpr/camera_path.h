/* pointnpr — camera_path.h: camera paths for animations (pure CPU, no GL; in the core library
 * `pointnpr` next to the camera, view/). A path is a list of keyframes, each a look-at camera
 * (camera.h's pnpr_camera) at a time in seconds; pnpr_camera_path_eval gives the camera at any
 * time:
 *   - eye and target each follow a cubic Hermite spline through the keys with Catmull-Rom
 *     tangents in time, m_i = (p_{i+1} - p_{i-1}) / (t_{i+1} - t_{i-1}) (one-sided at the ends
 *     of an open path, wrapped around on a loop): C1, and exactly the key at each key time;
 *   - the view direction is target - eye of the splined points; the up vector is each
 *     neighbouring key's up carried along by the smallest rotation from the key's view direction
 *     to the current one, the two blended (smoothstep) and re-orthogonalised against the view
 *     direction: no flip unless the view turns by 180 degrees between two keys;
 *   - the field of view is interpolated linearly.
 * Before the first key and after the last one the path holds still (the end keys' cameras).
 * The text format (pnpr_camera_path_read) and the presets are in docs/export.md. */
#ifndef POINTNPR_CAMERA_PATH_H
#define POINTNPR_CAMERA_PATH_H

#include "camera.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Most keys a path may have (a larger file is refused rather than slow). */
#define PNPR_CAMERA_PATH_KEYS_MAX 100000

typedef struct pnpr_camera_key {
    double time;                    /* seconds, strictly increasing along the path */
    double eye[3], target[3], up[3]; /* world coordinates; up need not be orthogonal */
    double fov_y_deg;               /* vertical field of view in (0, 179) */
} pnpr_camera_key;

typedef struct pnpr_camera_path {
    pnpr_camera_key *keys; /* owned (pnpr_camera_path_free) */
    size_t count;
    int loop;              /* closed path: the last key is the first one again (same eye,
                            * target, up), the tangents there wrap around (orbits) */
} pnpr_camera_path;

void pnpr_camera_path_free(pnpr_camera_path *path);

/* Checks a path: 1..PNPR_CAMERA_PATH_KEYS_MAX keys, finite values, strictly increasing times,
 * eye != target, an up not parallel to the view, fov in (0, 179), a loop's ends equal.
 * PNPR_ERR_INVALID_ARGUMENT (or PNPR_ERR_NUMERIC for non-finite values) naming the key. */
PNPR_NODISCARD pnpr_status pnpr_camera_path_check(const pnpr_camera_path *path, pnpr_error *err);

/* The camera at time t (clamped to the first and last key times). fov_y_deg and up as described
 * above; near/far 0 (automatic). The path must pass pnpr_camera_path_check. */
PNPR_NODISCARD pnpr_status pnpr_camera_path_eval(const pnpr_camera_path *path, double t, pnpr_camera *r_camera);

/* Time of the last key minus time of the first (0 for a single key). */
double pnpr_camera_path_duration(const pnpr_camera_path *path);

/* Reads a camera path file: keys of the camera-file format ("eye X Y Z", "target X Y Z",
 * "up X Y Z", "fov DEG"), each key opened by a "time T" line; "loop" on a line of its own closes
 * the path; '#' comments, blank lines. A key without up or fov takes the previous key's (the
 * first key: 0 0 1 and 45). A file without any "time" line is one camera at time 0 (so a camera
 * file is a path). Errors name FILE:LINE (err->line) and what was expected. */
PNPR_NODISCARD pnpr_status pnpr_camera_path_read(const char *filename, pnpr_camera_path *r_path, pnpr_error *err);

/* The same from memory: `size` bytes (a NUL byte ends a line's content; a line holds at most 1022
 * characters), `name` naming the text in messages. r_path is zeroed on failure. */
PNPR_NODISCARD pnpr_status pnpr_camera_path_parse(const char *text, size_t size, const char *name, pnpr_camera_path *r_path,
                                   pnpr_error *err);

/* Largest camera or camera path file read (pnpr_text_file_load). */
#define PNPR_CAMERA_FILE_MAX ((size_t)256 << 20)

/* A camera file (`pointnpr render|lines --camera FILE`, written by --save-camera) from memory:
 * the lines "eye X Y Z", "target X Y Z", "up X Y Z" (finite), "fov DEG" (0 < DEG < 179), '#'
 * comments, blank lines; eye and target required, the last line of a kind counts. r_camera
 * receives them (up 0 0 1 and fov 45 where not given; time 0); r_given (may be NULL) the
 * PNPR_CAMERA_GIVEN_* lines that were given, so that a host keeps its own up and fov otherwise.
 * The view is not checked (eye may equal target: pnpr_camera_path_check does that). Errors:
 * PNPR_ERR_FORMAT "NAME:LINE: expected 'eye|target|up X Y Z' or 'fov DEG' (0 < DEG < 179)"
 * (err->line set), or "NAME: a camera file needs both 'eye' and 'target'". */
enum { PNPR_CAMERA_GIVEN_UP = 1, PNPR_CAMERA_GIVEN_FOV = 2 };
PNPR_NODISCARD pnpr_status pnpr_camera_file_parse(const char *text, size_t size, const char *name, pnpr_camera_key *r_camera,
                                   unsigned *r_given, pnpr_error *err);

/* Writes the path in that format (through pnpr_output_*, output.h); reading it back gives the
 * same keys bit for bit (%.17g). */
PNPR_NODISCARD pnpr_status pnpr_camera_path_write(const char *filename, const pnpr_camera_path *path, pnpr_error *err);

/* Presets around a start camera (usually pnpr_camera_default's, which frames the content). */
typedef enum pnpr_camera_preset {
    PNPR_PRESET_ORBIT = 0, /* the eye circles `up` through the target at the start camera's
                            * distance and height: `degrees` over the duration, a
                            * loop for a full turn; keys every 2 degrees or less */
    PNPR_PRESET_FLYOVER,   /* a straight pass over the target: the eye moves along the start
                            * view's horizontal direction from the start eye to 2.2 radii on
                            * (radius = the start eye's horizontal distance / 2.2) at the start
                            * height, looking 1.2 radii ahead, down to the target's height */
    PNPR_PRESET_COUNT_
} pnpr_camera_preset;

typedef struct pnpr_camera_preset_options {
    /* zero = the default; defaults and ranges: pnpr_camera_preset_option_table (options.h) */
    double duration;  /* seconds */
    double degrees;   /* orbit: the angle turned (either sign) */
} pnpr_camera_preset_options;

/* The preset's path starting at `start` (its eye, target and fov) around the unit axis `up`
 * (NULL = start->up). PNPR_ERR_INVALID_ARGUMENT for an unknown preset, non-finite or negative
 * options, a start whose view runs along `up` (no horizontal direction). opts may be NULL. */
PNPR_NODISCARD pnpr_status pnpr_camera_path_preset(pnpr_camera_preset preset, const pnpr_camera *start, const double up[3],
                                    const pnpr_camera_preset_options *opts, pnpr_camera_path *r_path,
                                    pnpr_error *err);

/* The start camera of a preset for a cloud: pnpr_camera_default (with view_opts, fov, aspect),
 * its eye moved away from the target (along the same direction) until the content (the points
 * inside the robust bounds, up to 20000 of them evenly strided) fits the frame with the default
 * camera's 5% margin from each of 36 azimuths about the scene's up through the target, so that
 * an orbit keeps it in frame from every side. r_up receives the scene's up. */
PNPR_NODISCARD pnpr_status pnpr_camera_preset_start(const pnpr_cloud *cloud, const pnpr_view_options *view_opts,
                                     float fov_y_deg, float aspect, pnpr_camera *r_start, double r_up[3]);

#ifdef __cplusplus
}
#endif
#endif
