/* pointnpr CLI: one cmd_<name>.c per subcommand, each exporting `int cli_<name>(int argc, char **argv)`
 * where argv[0] is the subcommand name. Exit codes: 0 ok, 1 runtime error, 2 usage error. */
#ifndef PNPR_CLI_H
#define PNPR_CLI_H

#include <pointnpr/camera.h>
#include <pointnpr/io.h>
#include <pointnpr/memory.h>
#include <pointnpr/outliers.h>
#include <pointnpr/view.h>

#include <stdio.h>

int cli_info(int argc, char **argv);
int cli_convert(int argc, char **argv);
int cli_features(int argc, char **argv);
int cli_render(int argc, char **argv);
int cli_lines(int argc, char **argv);
int cli_segment(int argc, char **argv);
int cli_bench(int argc, char **argv);
int cli_bench_quality(int argc, char **argv); /* `bench quality`, argv[1] = "quality" */
int cli_explain(int argc, char **argv);
int cli_animate(int argc, char **argv);
int cli_options(int argc, char **argv);
int cli_merge_tiles(int argc, char **argv);

/* Progress on stderr; never cancels. user: a cli_progress_state (zeroed before first use).
 * On a terminal: one updating "\r<stage> 42%" line per stage; otherwise (logs, CI) one line
 * when a stage ends. */
typedef struct cli_progress_state {
    char stage[64];
    int last_pct;
    int tty;      /* 0 unknown, 1 yes, 2 no */
} cli_progress_state;
int cli_progress_stderr(void *user, const char *stage, double fraction);
/* Parsing helpers (cli_args.c): a finite number in [lo,hi]; n comma-separated finite numbers. */
int cli_parse_number(const char *s, double lo, double hi, double *r);
int cli_parse_list(const char *s, int n, double *r);

/* Options described by the library's tables (options.h: name, default, range, help), so that the
 * usage text and the parser show and accept exactly what the library does (cli_args.c). */
#include <pointnpr/options.h>
/* "  --k N                neighbourhood size (default 16, in 1..1024)" */
void cli_option_usage(FILE *f, const pnpr_option_desc *d, const char *metavar);
/* The usage line of the table entry called `name` (it must exist). */
void cli_table_usage(FILE *f, const pnpr_option_desc *table, size_t count, const char *name, const char *metavar);
/* Parses v as a value of d: a finite number in d's range (an integer for integer options).
 * Returns 1, or 0 after printing "pointnpr CMD: --NAME wants an integer in 1..1024, got 'v'". */
int cli_option_value(const pnpr_option_desc *d, const char *cmd, const char *v, double *r);
/* argv[*i] is --NAME of one of the table's entries in `names` (NULL-terminated list of the names
 * this command takes): parses its value into the struct at opts (advancing *i) and returns 1;
 * another argument (or no value follows): 0; a bad value: prints why and returns -1. */
int cli_table_option(const pnpr_option_desc *table, size_t count, const char *const *names, void *opts,
                     const char *cmd, int argc, char **argv, int *i);

/* The view options shared by render and lines: --eye X,Y,Z --target X,Y,Z --up X,Y,Z (look-at,
 * world coordinates), --fov DEG, --size WxH, or --camera FILE (the same look-at camera as text:
 * "eye X Y Z", "target X Y Z", "up X Y Z", "fov DEG" lines; cli_write_camera_file writes one).
 * --up also takes auto|x|y|z|-x|-y|-z (docs/view.md); without --eye/--target either form picks
 * the up of the default camera (pnpr_camera_default). */
typedef struct cli_view {
    int have_eye, have_target, have_up; /* have_up: the vector form (up) */
    double eye[3], target[3], up[3], fov;
    int width, height;
    int have_up_mode;                   /* the axis form (up_mode) */
    pnpr_up_mode up_mode;
} cli_view;
void cli_view_init(cli_view *v, int width, int height);
/* argv[*i] is a view option: parses it (advancing *i past its value) and returns 1; not a view
 * option (or no value follows): 0; a bad value: prints why and returns -1. */
int cli_view_option(cli_view *v, const char *cmd, int argc, char **argv, int *i);
/* --eye and --target given together; prints why and returns 0 if not. */
int cli_view_check(const cli_view *v, const char *cmd);
int cli_write_camera_file(const char *path, const double eye[3], const double target[3], const double up[3], double fov);
/* The look-at camera of the options (its up from --up: the vector, the axis, or the detected one
 * for auto; +z without --up), else the default camera of the cloud (pnpr_camera_default with the
 * --up choice); NULL when neither can be made. Cameras are the core library's (camera.h), with or
 * without the renderer. */
const pnpr_camera *cli_view_camera(const cli_view *v, const pnpr_cloud *cloud, pnpr_camera *r_cam);
/* The start camera of an animation preset (camera_path.h) and the axis it turns about: the look-at
 * camera of the options and its up when given, else pnpr_camera_preset_start of the cloud with
 * the --up choice. Returns 0 when neither can be made. */
int cli_view_preset_start(const cli_view *v, const pnpr_cloud *cloud, pnpr_camera *r_cam, double r_up[3]);

/* Checks, before any work, that OUT can be written and is none of the inputs
 * (pnpr_output_check); binary: refuses "-" when standard output is a terminal. Prints why and
 * returns 0 when not. */
int cli_check_output(const char *cmd, const char *out, const char *const *inputs, size_t input_count, int binary);
/* The point-cloud output of features/segment/convert: OUT must end in .ply or .pcd (or be "-" or
 * a special file: PLY) and pass cli_check_output against IN; sets wo->format. Returns 0 when
 * it may be written, else the exit code (2 a bad name, 1 cannot be written), after saying why. */
int cli_cloud_output(const char *cmd, const char *out, const char *in, pnpr_write_options *wo);
/* Whether OUT is "-" or an existing device, FIFO or socket (written through; any name goes). */
int cli_output_is_stream(const char *out);
/* Whether the name ends in `ext` (".png"; case-insensitive). */
int cli_has_ext(const char *path, const char *ext);

/* --memory-limit SIZE (render, animate, features): a limit on the whole process in bytes (K, M,
 * G, T suffixes: KiB..TiB); 0 = what the machine has (pnpr_memory_available). As
 * cli_outlier_option. */
int cli_memory_option(size_t *limit, const char *cmd, int argc, char **argv, int *i);
void cli_memory_usage(FILE *f);
/* Before reading IN: the file is read whole, so its size must fit. After: the estimate of `plan`
 * (memory.h). Both return 0 after printing why (with the figures), 1 when it fits. */
int cli_memory_check_file(const char *cmd, const char *in, size_t limit);
int cli_memory_check_plan(const char *cmd, const char *in, size_t limit, const pnpr_memory_plan *plan);
/* Reads IN for render and animate: a uniform sample of `share` of its points when 0 < share < 1
 * (binary PLY); else whole when it fits (cli_memory_check_file), else, for a PLY, a uniform sample
 * that fits `limit` (0: what is available) by the memory model of `mp` (its points are the
 * file's), saying so unless quiet (cli_sample.c). `views` (NULL: none), the cameras of the frames
 * to draw at mp's image size (pnpr_view_sample_init_frames): the sample follows their views instead (points near a camera kept, far ones thinned, unseen ones
 * left out), each frame's share of it at most frame_points (the frame's budget; 0: none) unless
 * `share` is asked.
 * *r_tone_radius: for a sample, the whole cloud's mean spacing as it estimates it (0: none; the
 * renderer's tone_radius). `plan` (may be NULL) fills the stages of mp that a sample will run
 * from the file's properties (a cloud read without points), with `plan_user`. Returns 0 after
 * printing why. */
typedef void (*cli_plan_fn)(const pnpr_cloud *header, void *user, pnpr_memory_plan *mp);
/* The frames a sample follows: their cameras when known before reading (a path file, a camera);
 * else, when from_preview is given and the file is sampled, the cameras from a uniform preview of
 * about 200 000 of its points (a preset's path comes from the cloud; the pass that counts the
 * points keeps them): from_preview returns how many into *r_cams (malloc'd; 0: none, a uniform
 * sample then). */
typedef struct cli_sample_views {
    const pnpr_camera *cams;
    size_t count;
    size_t (*from_preview)(pnpr_cloud *preview, void *user, pnpr_camera **r_cams);
    void *user;
} cli_sample_views;
int cli_read_fitting(const char *cmd, const char *in, const pnpr_read_options *opts, const pnpr_memory_plan *mp,
                     cli_plan_fn plan, void *plan_user, size_t limit, double share, const cli_sample_views *views,
                     double frame_points, int quiet, pnpr_cloud *cloud, float *r_tone_radius);

/* Far outliers (outliers.h), shared by features, segment, render and lines (cmd_info.c):
 * --drop-outliers removes them after reading, --outlier-factor F sets how far is far. */
typedef struct cli_outliers {
    int drop;
    double factor; /* 0 = PNPR_OUTLIER_FACTOR */
} cli_outliers;
/* argv[*i] is --drop-outliers or --outlier-factor F: parses it (advancing *i past its value)
 * and returns 1; not one of them (or no value follows): 0; a bad value: prints why, returns -1. */
int cli_outlier_option(cli_outliers *o, const char *cmd, int argc, char **argv, int *i);
/* The usage lines of the two options (defaults and range from outliers.h). */
void cli_outlier_usage(FILE *f);
/* After reading IN: counts its far outliers and removes them when asked; says so on stderr
 * (unless quiet) when there are any. r_info (may be NULL) describes the cloud as read. Returns 0,
 * or 1 after printing why it failed. */
int cli_outliers_apply(const cli_outliers *o, const char *cmd, const char *in, pnpr_cloud *cloud, int quiet,
                       pnpr_outlier_info *r_info);

/* Says which of IN and OUT is missing ("no output given (-o OUT.ply)", with out_hint as the
 * example name) and returns 0; 1 when both are there. */
int cli_need_in_out(const char *cmd, const char *in, const char *out, const char *out_hint);

/* --columns NAMES, shared by info, convert, features, segment, render and lines: the columns of
 * a text point cloud (XYZ, PTS, PWN, CSV, TXT; pnpr_read_options.columns, io/text_points.c),
 * e.g. x,y,z,r,g,b or x,y,z,intensity,_,nx,ny,nz. argv[*i] is --columns: sets *columns to its
 * value (advancing *i) and returns 1; another argument: 0; no value, or not a list of names
 * with x, y and z: prints why and returns -1. */
int cli_columns_option(const char **columns, const char *cmd, int argc, char **argv, int *i);
/* Its usage line. */
void cli_columns_usage(FILE *f);

/* Prints "pointnpr <cmd>: <message>" for a failed status (with pnpr_error detail when set). */
void cli_report_error(const char *cmd, pnpr_status st, const pnpr_error *err);
/* The same for work on the input IN: the message names IN (unless it does already). */
void cli_report_error_in(const char *cmd, const char *in, pnpr_status st, const pnpr_error *err);

/* Tiled runs of features (cmd_tiles.c, tiles.h): the options, parsed as cli_outlier_option. */
typedef struct cli_tile_args {
    double tile_points;  /* --tile-points N (0: not given) */
    int tiled;           /* --tiles: as large as the memory allows */
    double halo;         /* --halo H (0: the plan's automatic halo) */
    const char *manifest; /* --manifest DIR */
    double grid[9];      /* one tile's job: --tile-grid X,Y,CX,CY,NX,NY,OX,OY,OZ (NX 0: not given) */
    double cells[4];     /* --tile X0,Y0,X1,Y1 */
} cli_tile_args;
int cli_tile_option(cli_tile_args *t, const char *cmd, int argc, char **argv, int *i);
void cli_tile_usage(FILE *f, int halo); /* halo: with --halo (features; segment derives it) */
int cli_tile_wanted(const cli_tile_args *t); /* any of them given */
struct pnpr_features_options;
typedef struct cli_features_run {
    const char *in, *out;
    struct pnpr_features_options *fo;
    const pnpr_write_options *wo;
    pnpr_progress prog;
    int quiet;
} cli_features_run;
/* One tile's job (--tile-grid), or the plan and then every tile in turn and the merge, or the plan
 * and its manifest (--manifest; argv: the command's, repeated in every job). Returns the exit code. */
int cli_features_tiles(const cli_features_run *r, const cli_tile_args *a, size_t memory_limit, int argc, char **argv);

/* What a tiled run of a command needs besides the plan (cmd_tiles.c; features and segment). */
struct pnpr_tile_grid;
struct pnpr_tile;
struct pnpr_tile_plan;
typedef struct cli_tile_cmd {
    const char *cmd, *in, *out;
    int quiet;
    pnpr_progress prog;       /* the plan's and the merge's */
    const char *job_extra;    /* written into every job after the command's options ("" for none) */
    const char *merge_flag;   /* merge-tiles' option for this command, or NULL */
    int certifies;            /* the jobs count points not certain to equal a run in memory */
    size_t job_bytes;         /* --tiles: a job's bytes per point beyond the record (0: a feature job's) */
    /* one tile into out (its halo given); adds its uncertain points; returns an exit code */
    int (*job)(const void *ctx, const char *out, const struct pnpr_tile_grid *g, const struct pnpr_tile *t,
               double halo, size_t *r_uncertain);
    pnpr_status (*merge)(const void *ctx, const char *const *paths, size_t n, uint64_t points, const char *out,
                         const pnpr_progress *prog, pnpr_error *err);
    const void *ctx;
} cli_tile_cmd;
/* The grid and tile of one job from --tile-grid/--tile; 0 after saying why. */
int cli_tile_job_args(const char *cmd, const cli_tile_args *a, struct pnpr_tile_grid *g, struct pnpr_tile *t);
/* The plan (tiles sized for k neighbours under the memory limit when --tiles); an exit code. */
int cli_tile_plan(const cli_tile_cmd *c, const cli_tile_args *a, size_t memory_limit, uint32_t k,
                  struct pnpr_tile_plan *r_plan);
/* Every tile and the merge, or the manifest (--manifest); an exit code. */
int cli_tile_execute(const cli_tile_cmd *c, const cli_tile_args *a, const struct pnpr_tile_plan *plan, int argc,
                     char **argv);

#endif
