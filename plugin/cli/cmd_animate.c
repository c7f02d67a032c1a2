/* pointnpr animate IN -o OUT.mp4|DIR/: frames of a camera path (a path file, --orbit, --flyover;
 * include/pointnpr/camera_path.h) rendered as `render` would render each of them, written as
 * DIR/frame-%05d.png (resumable: complete frames are kept), then a video through ffmpeg.
 * pointnpr animate IN --save-path FILE without -o writes the camera path only: camera paths are
 * the core library's, so that works in a build without the renderer too (PNPR_HAVE_RENDER). */
#include "cli.h"
#include "cli_render.h"
#include "cli_opts.h"

#include <stdio.h>

#include <pointnpr/camera_path.h>
#include <pointnpr/output.h>

#include <errno.h>
#include <math.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

extern char **environ;

/* Names inside the frames folder (whose name is at most PNPR_OUTPUT_PATH_MAX - 32). */
#define FILE_MAX (PNPR_OUTPUT_PATH_MAX + 64)
/* At most this many frames (the five digits of frame-%05d.png). */
#define FRAMES_MAX 100000

typedef struct anim_args {
    const char *in, *out, *path_file, *save_path, *frames_dir;
    int preset;            /* -1: none, else pnpr_camera_preset */
    pnpr_camera_preset_options po; /* --duration, --degrees (the library's table) */
    double fps;
    int have_duration, keep_frames, video;
    char dir[PNPR_OUTPUT_PATH_MAX];
    pnpr_camera_path path; /* the path file's (read before any work) or the preset's */
    int path_made;         /* 1: the path is made (a preset's from a preview of a cloud that is
                            * sampled), -1: making it failed (said why) */
} anim_args;

#define ANIM_FPS 25 /* --fps: the default */
#define ANIM_STR(x) #x
#define ANIM_XSTR(x) ANIM_STR(x)

/* --orbit / --flyover: one preset (the member: the anim_args). */
static int parse_preset(anim_args *r, int preset)
{
    if (r->preset >= 0 && r->preset != preset) {
        fprintf(stderr, "pointnpr animate: --orbit and --flyover are two camera paths; give one\n");
        return 0;
    }
    r->preset = preset;
    return 1;
}
static int parse_orbit(void *r, const char *cmd, const char *v) { (void)cmd; (void)v; return parse_preset(r, PNPR_PRESET_ORBIT); }
static int parse_flyover(void *r, const char *cmd, const char *v) { (void)cmd; (void)v; return parse_preset(r, PNPR_PRESET_FLYOVER); }

#define A_OPT(name, kind, member, lo, hi, metavar, help)                                                            \
    {name, NULL, kind, offsetof(anim_args, member), lo, hi, 0, 0, NULL, NULL, metavar, help}
static const cli_opt anim_opts[] = {
    A_OPT("--camera-path", CLI_TEXT, path_file, 0, 0, "FILE",
          "keyframes: 'time T' lines, each followed by a camera file's lines (eye, target, up, fov); 'loop' "
          "closes the path (docs/export.md)"),
    {"--orbit", NULL, CLI_FLAG_CUSTOM, 0, 0, 0, 0, 0, NULL, parse_orbit, NULL,
     "circle the content about the up axis, from the default view (or the --eye/--target/--camera view), "
     "the content in frame from every side"},
    {"--flyover", NULL, CLI_FLAG_CUSTOM, 0, 0, 0, 0, 0, NULL, parse_flyover, NULL,
     "a straight pass over the content, looking ahead and down"},
    A_OPT("--fps", CLI_NUMBER, fps, 0.01, 1000, "N", "frames per second (default " ANIM_XSTR(ANIM_FPS) ")"),
    A_OPT("--save-path", CLI_TEXT, save_path, 0, 0, "FILE",
          "write the camera path used (e.g. a preset) to FILE; `pointnpr render --camera-path FILE --camera-at T` "
          "renders the frame at T alone"),
    A_OPT("--frames-dir", CLI_TEXT, frames_dir, 0, 0, "DIR",
          "where the frames go for a video (default OUT without .mp4 + .frames)"),
    A_OPT("--keep-frames", CLI_FLAG, keep_frames, 0, 0, NULL, "keep the frames after the video is made (default: removed)"),
    {"--output", "-o", CLI_TEXT, offsetof(anim_args, out), 0, 0, 0, 0, NULL, NULL, "OUT", "the video or the frames' folder"},
};

static void usage(FILE *f)
{
    fprintf(f,
            "usage: pointnpr animate IN -o OUT.mp4|DIR/ (--camera-path FILE | --orbit | --flyover) [options]\n"
            "       pointnpr animate IN --save-path FILE (--camera-path FILE | --orbit | --flyover) [options]\n"
            "  Renders the frames of a camera path as `pointnpr render` renders one picture, into\n"
            "  DIR/frame-00000.png ... (for OUT.mp4: OUT.frames/), then OUT.mp4 with ffmpeg. Frames that\n"
            "  are already complete are kept, so an interrupted run resumes (docs/export.md). Without\n"
            "  -o, only the camera path is written (--save-path; also in a build without the renderer).\n"
            "options:\n");
    size_t pn;
    const pnpr_option_desc *pt = pnpr_camera_preset_option_table(&pn);
    cli_opts_usage(f, anim_opts, 2); /* --camera-path, --orbit */
    cli_table_usage(f, pt, pn, "degrees", "DEG");
    cli_opts_usage(f, anim_opts + 2, 1); /* --flyover */
    cli_table_usage(f, pt, pn, "duration", "S");
    cli_opts_usage(f, anim_opts + 3, CLI_COUNT(anim_opts) - 3);
    fprintf(f,
            "  Frame k shows the path at (first key's time) + k / fps; an open path ends with its last\n"
            "  key, a loop stops one frame before it (the first frame again).\n");
    cli_render_usage(f, 1280, 720);
}

/* Parses argv; returns -1 to go on, else the exit code (help, usage error). */
static int parse_args(int argc, char **argv, anim_args *r, cli_render_opts *o)
{
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        size_t pn;
        const pnpr_option_desc *pt = pnpr_camera_preset_option_table(&pn);
        static const char *const preset_names[] = {"duration", "degrees", NULL};
        int got = cli_table_option(pt, pn, preset_names, &r->po, "animate", argc, argv, &i);
        if (got == 0) got = cli_opts_parse(anim_opts, CLI_COUNT(anim_opts), r, "animate", argc, argv, &i);
        if (got == 0) got = cli_render_option(o, "animate", argc, argv, &i);
        if (got < 0) return 2;
        if (got > 0) continue;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) { usage(stdout); return 0; }
        if (cli_operand("animate", a, &r->in, usage)) return 2;
    }
    r->have_duration = r->po.duration != 0;
    if (!r->in || (!r->out && !r->save_path)) { usage(stderr); return 2; }
    return -1;
}

static int is_dir(const char *p)
{
    struct stat sb;
    return stat(p, &sb) == 0 && S_ISDIR(sb.st_mode);
}

/* The camera source, the path file, the output kind and the frames folder; -1 = fine, else the
 * exit code. */
static int check_args(anim_args *r, cli_render_opts *o)
{
    if ((r->preset >= 0) == (r->path_file != NULL)) {
        fprintf(stderr, "pointnpr animate: give one camera path: --camera-path FILE, --orbit or --flyover\n");
        return 2;
    }
    if (r->path_file && (r->have_duration || o->view.have_eye)) {
        fprintf(stderr, "pointnpr animate: --camera-path FILE has its own times and cameras (no --duration, --eye, --camera)\n");
        return 2;
    }
    if (r->po.degrees != 0 && r->preset != PNPR_PRESET_ORBIT) { fprintf(stderr, "pointnpr animate: --degrees is for --orbit\n"); return 2; }
    if (!cli_render_opts_finish(o, "animate")) return 2;
    pnpr_error err = {0};
    pnpr_status st = r->path_file ? pnpr_camera_path_read(r->path_file, &r->path, &err) : PNPR_OK;
    if (st != PNPR_OK) { cli_report_error("animate", st, &err); return 2; }
    if (r->save_path && !cli_check_output("animate", r->save_path, &r->in, 1, 0)) return 1; /* e.g. the input */
    if (!r->out) return -1; /* the camera path only */
    size_t n = strlen(r->out);
    r->video = cli_has_ext(r->out, ".mp4");
    if (!r->video && !(n > 0 && r->out[n - 1] == '/') && !is_dir(r->out)) {
        fprintf(stderr, "pointnpr animate: the output is a video OUT.mp4 or a folder DIR/ for the frames, got '%s'\n", r->out);
        return 2;
    }
    if (r->video && !cli_check_output("animate", r->out, &r->in, 1, 0)) return 1;
    int len = r->video && !r->frames_dir ? snprintf(r->dir, sizeof r->dir, "%.*s.frames", (int)(n - 4), r->out)
                                         : snprintf(r->dir, sizeof r->dir, "%s", r->frames_dir ? r->frames_dir : r->out);
    if (len < 0 || (size_t)len >= sizeof r->dir - 32) { fprintf(stderr, "pointnpr animate: the frames folder name is too long\n"); return 2; }
    while (len > 1 && r->dir[len - 1] == '/') r->dir[--len] = 0; /* "DIR/" names the folder DIR */
    return -1;
}

/* A preset's path into r->path (a path file is read already); written to --save-path when asked.
 * Returns 1, or 0 after printing why. */
static int make_path(anim_args *r, const cli_render_opts *o, const pnpr_cloud *cloud)
{
    pnpr_error err = {0};
    pnpr_status st = PNPR_OK;
    if (r->path_made) return r->path_made > 0; /* made (or failed, said why) from a preview */
    if (!r->path_file) {
        pnpr_camera start;
        double up[3];
        if (!cli_view_preset_start(&o->view, cloud, &start, up)) {
            fprintf(stderr, "pointnpr animate: %s: no camera to start the preset from (no finite point?)\n", r->in);
            return 0;
        }
        st = pnpr_camera_path_preset((pnpr_camera_preset)r->preset, &start, up, &r->po, &r->path, &err);
    }
    if (st == PNPR_OK && r->save_path) st = pnpr_camera_path_write(r->save_path, &r->path, &err);
    if (st != PNPR_OK) cli_report_error("animate", st, &err);
    r->path_made = st == PNPR_OK;
    return st == PNPR_OK;
}

/* Frames of the path: an open path ends with its last key, a loop one frame before it. */
static long frame_count(const pnpr_camera_path *path, double fps)
{
    double n = floor(pnpr_camera_path_duration(path) * fps + 0.5);
    if (n > FRAMES_MAX) return FRAMES_MAX + 1;
    return path->loop ? (n < 1 ? 1 : (long)n) : (long)n + 1;
}

#ifdef PNPR_HAVE_RENDER
/* A PNG that was written to its end (IEND last) at the expected size. */
static int frame_complete(const char *file, int w, int h)
{
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    static const unsigned char iend[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
    unsigned char head[24], tail[12];
    FILE *f = fopen(file, "rb");
    if (!f) return 0;
    int ok = fread(head, 1, 24, f) == 24 && fseek(f, -12, SEEK_END) == 0 && fread(tail, 1, 12, f) == 12;
    fclose(f);
    unsigned long fw = ok ? (unsigned long)head[16] << 24 | (unsigned long)head[17] << 16 | head[18] << 8 | head[19] : 0;
    unsigned long fh = ok ? (unsigned long)head[20] << 24 | (unsigned long)head[21] << 16 | head[22] << 8 | head[23] : 0;
    return ok && !memcmp(head, sig, 8) && !memcmp(head + 12, "IHDR", 4) && fw == (unsigned long)w && fh == (unsigned long)h &&
           !memcmp(tail, iend, 12);
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct anim_progress {
    double start, last_print;
    long rendered, kept;
    int tty;
} anim_progress;

/* "frame k/n (p%), s/frame, ETA": on a terminal one updating line, else a line at the first and
 * the last frame and at most every 2 seconds. */
static void report(anim_progress *p, long k, long n)
{
    double t = now_s(), per = p->rendered > 0 ? (t - p->start) / (double)p->rendered : 0, eta = per * (double)(n - 1 - k);
    if (!p->tty && p->rendered > 1 && k + 1 < n && t - p->last_print < 2) return;
    p->last_print = t;
    fprintf(stderr, "%sanimate: frame %ld/%ld (%.0f%%), %.2f s/frame, ETA %ldm%02lds%s", p->tty ? "\r" : "", k + 1, n,
            100.0 * (double)(k + 1) / (double)n, per, (long)eta / 60, (long)eta % 60, p->tty && k + 1 < n ? "" : "\n");
    fflush(stderr);
}

static void frame_name(char *buf, size_t size, const char *dir, long k)
{
    snprintf(buf, size, "%s/frame-%05ld.png", dir, k);
}

/* Renders the frames that are not complete yet. Returns 1, or 0 after printing why. */
static int render_frames(cli_render_session *s, const cli_render_opts *o, const anim_args *r, long n, anim_progress *p)
{
    char file[FILE_MAX];
    for (long k = 0; k < n; k++) {
        frame_name(file, sizeof file, r->dir, k);
        if (frame_complete(file, o->view.width, o->view.height)) { p->kept++; continue; }
        pnpr_camera cam;
        if (pnpr_camera_path_eval(&r->path, r->path.keys[0].time + (double)k / r->fps, &cam) != PNPR_OK) return 0;
        if (p->rendered == 0) p->start = now_s();
        if (!cli_render_frame(s, o, "animate", r->in, &cam, 0, NULL)) return 0;
        pnpr_error err = {0};
        pnpr_status st = pnpr_write_png(file, s->pixels, o->view.width, o->view.height, o->alpha, &err);
        if (st != PNPR_OK) { cli_report_error("animate", st, &err); return 0; }
        p->rendered++;
        if (!o->quiet) report(p, k, n);
    }
    return 1;
}

/* The frames folder exists (created when missing). */
static int make_dir(const char *dir)
{
    if (mkdir(dir, 0777) == 0 || (errno == EEXIST && is_dir(dir))) return 1;
    fprintf(stderr, "pointnpr animate: cannot make the frames folder %s: %s\n", dir, errno == EEXIST ? "not a folder" : strerror(errno));
    return 0;
}

static uint64_t fnv(uint64_t h, const void *data, size_t size)
{
    const unsigned char *b = data;
    for (size_t i = 0; i < size; i++) h = (h ^ b[i]) * 1099511628211ull;
    return h;
}

/* A digest of what the frames depend on: the options (not -o, --frames-dir, --save-path,
 * --quiet, --keep-frames) and the path's keys. */
static unsigned long long settings_digest(int argc, char **argv, const pnpr_camera_path *path)
{
    uint64_t h = 14695981039346656037ull;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-o") || !strcmp(a, "--output") || !strcmp(a, "--frames-dir") || !strcmp(a, "--save-path")) { i++; continue; }
        if (!strcmp(a, "--quiet") || !strcmp(a, "--keep-frames")) continue;
        h = fnv(h, a, strlen(a) + 1);
    }
    h = fnv(h, &path->loop, sizeof path->loop);
    return fnv(h, path->keys, path->count * sizeof *path->keys);
}

static int print_manifest(FILE *f, const void *ctx)
{
    return fprintf(f, "# pointnpr animate: the frames in this folder were made with these settings\nsettings %016llx\n",
                   *(const unsigned long long *)ctx) < 0;
}

/* DIR/animate.txt: written on the first run; a later run with other settings refuses to mix its
 * frames in. Returns 1, or 0 after printing why. */
static int check_manifest(const char *dir, unsigned long long digest)
{
    char file[FILE_MAX], line[128];
    snprintf(file, sizeof file, "%s/animate.txt", dir);
    FILE *f = fopen(file, "r");
    unsigned long long old = 0;
    int have = 0;
    while (f && !have && fgets(line, sizeof line, f)) have = sscanf(line, "settings %llx", &old) == 1;
    if (f) fclose(f);
    if (have && old != digest) {
        fprintf(stderr, "pointnpr animate: %s holds frames of another animation (other options or path, see %s); "
                        "remove them or give another --frames-dir\n", dir, file);
        return 0;
    }
    if (have) return 1;
    pnpr_error err = {0};
    pnpr_status st = pnpr_output_write(file, print_manifest, &digest, &err);
    if (st != PNPR_OK) cli_report_error("animate", st, &err);
    return st == PNPR_OK;
}

/* From the loaded cloud to the frames on disk. Returns 1, or 0 after printing why. */
static int animate(cli_render_session *s, cli_render_opts *o, anim_args *r, int argc, char **argv, long *r_n)
{
    anim_progress p = {0, 0, 0, 0, isatty(fileno(stderr))};
    if (!make_path(r, o, &s->cloud)) return 0;
    long n = frame_count(&r->path, r->fps);
    if (n > FRAMES_MAX) {
        fprintf(stderr, "pointnpr animate: more than %d frames (duration x fps)\n", FRAMES_MAX);
        return 0;
    }
    *r_n = n;
    /* the key light's "above": the path's first up, as `render --camera-path` takes it */
    if (!make_dir(r->dir) || !check_manifest(r->dir, settings_digest(argc, argv, &r->path)) ||
        !cli_render_start(s, o, "animate", r->in, r->path.keys[0].up) || !render_frames(s, o, r, n, &p))
        return 0;
    if (!o->quiet)
        fprintf(stderr, "animate: %ld frames in %s (%ld rendered, %ld complete ones kept)\n", n, r->dir, p.rendered, p.kept);
    return 1;
}

/* ffmpeg on PATH into buf; 0 when there is none. */
static int find_ffmpeg(char *buf, size_t size)
{
    const char *path = getenv("PATH");
    while (path && *path) {
        const char *end = strchr(path, ':');
        size_t len = end ? (size_t)(end - path) : strlen(path);
        struct stat sb;
        if (len > 0 && snprintf(buf, size, "%.*s/ffmpeg", (int)len, path) < (int)size && stat(buf, &sb) == 0 &&
            S_ISREG(sb.st_mode) && access(buf, X_OK) == 0)
            return 1;
        path = end ? end + 1 : NULL;
    }
    return 0;
}

/* ffmpeg -i DIR/frame-%05d.png ... tmp; returns 1 when it exited 0. */
static int run_ffmpeg(const char *ffmpeg, const anim_args *r, long n, const char *tmp)
{
    char pattern[2 * PNPR_OUTPUT_PATH_MAX], fps[32], frames[32];
    size_t j = 0;
    for (const char *c = r->dir; *c && j + 2 < sizeof pattern - 20; c++) { /* '%' is ffmpeg's: doubled */
        if (*c == '%') pattern[j++] = '%';
        pattern[j++] = *c;
    }
    snprintf(pattern + j, sizeof pattern - j, "/frame-%%05d.png");
    snprintf(fps, sizeof fps, "%.17g", r->fps);
    snprintf(frames, sizeof frames, "%ld", n);
    char *args[] = {"ffmpeg", "-nostdin", "-hide_banner", "-loglevel", "error", "-y", "-framerate", fps, "-start_number", "0",
                    "-i", pattern, "-frames:v", frames, "-c:v", "libx264", "-pix_fmt", "yuv420p",
                    "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-movflags", "+faststart", (char *)tmp, NULL};
    pid_t pid;
    int status = 0, e = posix_spawn(&pid, ffmpeg, NULL, NULL, args, environ);
    if (e != 0) { fprintf(stderr, "pointnpr animate: cannot run %s: %s\n", ffmpeg, strerror(e)); return 0; }
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return 1;
    fprintf(stderr, "pointnpr animate: %s failed (%s %d) making the video from %s\n", ffmpeg,
            WIFEXITED(status) ? "exit status" : "signal", WIFEXITED(status) ? WEXITSTATUS(status) : WTERMSIG(status), pattern);
    return 0;
}

/* Copies the finished video into OUT through pnpr_output (temporary + rename). */
static int copy_to_output(const char *tmp, const char *out)
{
    FILE *src = fopen(tmp, "rb");
    if (!src) { fprintf(stderr, "pointnpr animate: %s: %s\n", tmp, strerror(errno)); return 0; }
    pnpr_output o;
    pnpr_error err = {0};
    pnpr_status st = pnpr_output_open(&o, out, &err);
    char buf[1 << 16];
    size_t got;
    while (st == PNPR_OK && (got = fread(buf, 1, sizeof buf, src)) > 0)
        if (fwrite(buf, 1, got, o.f) != got) st = PNPR_ERR_IO;
    if (st == PNPR_OK && ferror(src)) st = pnpr_error_set(&err, PNPR_ERR_IO, "%s: %s", tmp, strerror(errno));
    fclose(src);
    if (o.f) st = pnpr_output_close(&o, st, &err);
    if (st != PNPR_OK) cli_report_error("animate", st, &err);
    return st == PNPR_OK;
}

static void remove_frames(const char *dir, long n)
{
    char file[FILE_MAX];
    for (long k = 0; k < n; k++) {
        frame_name(file, sizeof file, dir, k);
        unlink(file);
    }
    snprintf(file, sizeof file, "%s/animate.txt", dir);
    unlink(file);
    rmdir(dir); /* only when nothing else is in it */
}

/* The video from the frames; the frames stay when it cannot be made. Returns 1, or 0. */
static int make_video(const anim_args *r, long n, int quiet)
{
    char ffmpeg[PNPR_OUTPUT_PATH_MAX], tmp[FILE_MAX];
    if (!find_ffmpeg(ffmpeg, sizeof ffmpeg)) {
        fprintf(stderr, "pointnpr animate: cannot make %s: ffmpeg is not on PATH (Debian: apt-get install ffmpeg); "
                        "the %ld frames are kept in %s\n", r->out, n, r->dir);
        return 0;
    }
    snprintf(tmp, sizeof tmp, "%s/.animate-video.mp4", r->dir);
    int ok = run_ffmpeg(ffmpeg, r, n, tmp) && copy_to_output(tmp, r->out);
    unlink(tmp);
    if (!ok) { fprintf(stderr, "pointnpr animate: the frames are kept in %s\n", r->dir); return 0; }
    if (!quiet) fprintf(stderr, "animate: %ld frames at %g fps -> %s\n", n, r->fps, r->out);
    if (!r->keep_frames) remove_frames(r->dir, n);
    return 1;
}

#endif

/* The cameras a sample of a cloud larger than memory follows (cli_read_fitting): every frame of the
 * path (a path file's, or a preset's once made), into *r_cams (malloc'd). Returns how many (0:
 * none, or a frame not evaluated: animate() says why). */
static size_t sample_cameras(const anim_args *r, pnpr_camera **r_cams)
{
    *r_cams = NULL;
    if (!r->path_file && !r->path_made) return 0;
    long n = frame_count(&r->path, r->fps);
    if (n < 1 || n > FRAMES_MAX || !(*r_cams = malloc((size_t)n * sizeof **r_cams))) return 0;
    for (long k = 0; k < n; k++)
        if (pnpr_camera_path_eval(&r->path, r->path.keys[0].time + (double)k / r->fps, &(*r_cams)[k]) != PNPR_OK) {
            free(*r_cams);
            *r_cams = NULL;
            return 0;
        }
    return (size_t)n;
}

typedef struct preview_user {
    anim_args *r;
    const cli_render_opts *o;
} preview_user;

/* cli_sample_views.from_preview for a preset: its path from a uniform preview of a cloud that is
 * sampled (its start camera needs the cloud), then its frames' cameras. */
static size_t preset_cameras(pnpr_cloud *preview, void *user, pnpr_camera **r_cams)
{
    preview_user *u = user;
    *r_cams = NULL;
    /* the outlier options, as the cloud read gets them (a preset fitted to far points would fly
     * round them) */
    if (cli_outliers_apply(&u->o->outliers, "animate", u->r->in, preview, 1, NULL) != 0 || !make_path(u->r, u->o, preview)) {
        u->r->path_made = -1; /* said why: animate() does not make it again */
        return 0;
    }
    return sample_cameras(u->r, r_cams);
}

/* Without -o: the cloud (for a preset's start camera) and the path, written to --save-path.
 * Returns the exit code. */
static int save_path_only(cli_render_opts *o, anim_args *r)
{
    cli_render_session s;
    memset(&s, 0, sizeof s);
    preview_user pu = {r, o}; /* a cloud that is sampled: the path from the preview, as with -o */
    const cli_sample_views views = {NULL, 0, preset_cameras, &pu};
    int ok = (r->path_file || cli_render_load(&s, o, "animate", r->in, &views)) && make_path(r, o, &s.cloud);
    cli_render_end(&s);
    if (ok && !o->quiet) fprintf(stderr, "wrote %s\n", r->save_path);
    return ok ? 0 : 1;
}

int cli_animate(int argc, char **argv)
{
    anim_args r;
    memset(&r, 0, sizeof r);
    r.preset = -1;
    r.fps = ANIM_FPS;
    cli_render_opts o;
    cli_render_opts_init(&o, 1280, 720);
    int rc = parse_args(argc, argv, &r, &o);
    if (rc < 0) rc = check_args(&r, &o);
    if (rc < 0 && !r.out) rc = save_path_only(&o, &r);
#ifndef PNPR_HAVE_RENDER
    if (rc < 0) {
        fprintf(stderr, "pointnpr animate: this build has no renderer (libepoxy and libpng were not found): "
                        "it can write the camera path only (--save-path FILE without -o)\n");
        rc = 1;
    }
    pnpr_camera_path_free(&r.path);
    cli_render_opts_free(&o);
    return rc;
#else
    if (rc >= 0) { pnpr_camera_path_free(&r.path); cli_render_opts_free(&o); return rc; }
    char ffmpeg[PNPR_OUTPUT_PATH_MAX];
    if (r.video && !find_ffmpeg(ffmpeg, sizeof ffmpeg))
        fprintf(stderr, "pointnpr animate: warning: ffmpeg is not on PATH: the frames go to %s, but %s cannot be made "
                        "(Debian: apt-get install ffmpeg)\n", r.dir, r.out);
    cli_render_session s;
    long n = 0;
    pnpr_camera *cams = NULL;
    size_t cam_count = sample_cameras(&r, &cams);
    preview_user pu = {&r, &o};
    const cli_sample_views views = {cams, cam_count, r.path_file ? NULL : preset_cameras, &pu};
    rc = cli_render_load(&s, &o, "animate", r.in, &views) && animate(&s, &o, &r, argc, argv, &n) ? 0 : 1;
    free(cams);
    cli_render_end(&s);
    if (rc == 0 && r.video && !make_video(&r, n, o.quiet)) rc = 1;
    pnpr_camera_path_free(&r.path);
    cli_render_opts_free(&o);
    return rc;
#endif
}
