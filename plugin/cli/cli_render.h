/* The render options and steps shared by `render` and `animate` (cli_render_opts.c). The options,
 * cli_render_load and cli_render_end are there in every build; cli_render_start and
 * cli_render_frame only with the renderer (PNPR_HAVE_RENDER). */
#ifndef PNPR_CLI_RENDER_H
#define PNPR_CLI_RENDER_H

#include "cli.h"

#include <pointnpr/brush.h>
#include <pointnpr/render.h>

typedef struct cli_render_opts {
    pnpr_draw_options dopt;
    pnpr_upload_options uopt;
    pnpr_tone_options tone;
    pnpr_brush_options bopt;      /* the brush stage's options (the plan runs it for the brush style) */
    pnpr_sphere_tree_options topt; /* the hierarchy's tree (the plan builds it for the hierarchy style) */
    const char *importance_path;  /* --importance FILE.png */
    uint8_t *importance;          /* read by cli_render_opts_finish (dopt.hierarchy points at it) */
    double bg[3];                 /* 0..255; bg[0] < 0: not given (the look's paper, else white) */
    int look;                     /* --look: pnpr_looks index + 1 (0: none) */
    int style_given;              /* --style was given (it and --look exclude each other) */
    int alpha, quiet, max_tile;
    int budget_all;               /* --budget all: every point (no --density either) */
    size_t memory_limit;          /* --memory-limit (0: what the machine has) */
    double sample;                /* --sample S: the share of the points read (0: all, or what fits) */
    cli_outliers outliers;
    const char *columns;          /* --columns (text point clouds) */
    cli_view view;
    const char *style_map_path;
    pnpr_style_map smap;          /* read by cli_render_opts_finish */
    const char *effects_path;     /* --effects FILE */
    pnpr_effect_pipeline fx;      /* read by cli_render_opts_finish (count 0: none) */
    pnpr_layering layering;       /* --layering, over the file's */
    int have_layering;
    pnpr_effects_options fx_opts; /* --effects-scale, --effects-serial (seed and progress set per frame) */
    int have_fx_opts;
    int uses[PNPR_STYLE_COUNT_];  /* the styles a frame may draw */
} cli_render_opts;

void cli_render_opts_init(cli_render_opts *o, int width, int height);
/* argv[*i] is one of the shared options (style, draw, tone, outline, background, --alpha,
 * --max-tile, --quiet, the view and outlier options): parses it (advancing *i past its value)
 * and returns 1; not one of them (or no value follows): 0; a bad value: prints why, returns -1. */
int cli_render_option(cli_render_opts *o, const char *cmd, int argc, char **argv, int *i);
/* The usage lines of the shared options (the command's default size). */
void cli_render_usage(FILE *f, int width, int height);
/* After parsing: the view check, the background, the style map. Returns 0 after printing why
 * (a usage error). */
int cli_render_opts_finish(cli_render_opts *o, const char *cmd);
void cli_render_opts_free(cli_render_opts *o);

typedef struct cli_render_session {
    pnpr_cloud cloud;
    pnpr_gl_context *ctx;
    pnpr_renderer *ren;
    cli_progress_state ps;
    pnpr_progress prog;
    uint8_t *pixels;              /* view.width x view.height RGBA */
    pnpr_sphere_tree tree;        /* the hierarchy style's tree (when the plan builds it) */
    float tone_radius;            /* a sample's estimate of the whole cloud's mean spacing (0: none) */
} cli_render_session;

/* Reads IN and applies the outlier options; a sample of a cloud that does not fit follows the views
 * of the frames to draw (NULL: a uniform sample; cli_read_fitting). Returns 1, or 0 after printing why. */
int cli_render_load(cli_render_session *s, const cli_render_opts *o, const char *cmd, const char *in,
                    const cli_sample_views *views);
/* The key light's "above" is tone_up (the camera's up); then the stage plan, the GL context, the
 * renderer with the cloud (and the profile lines), the pixel buffer. Returns 1, or 0 after
 * printing why. */
int cli_render_start(cli_render_session *s, cli_render_opts *o, const char *cmd, const char *in, const double tone_up[3]);
/* One image through `camera` (NULL = fit) into s->pixels; tiles report progress unless quiet or
 * !tile_progress. Returns 1, or 0 after printing why. */
int cli_render_frame(cli_render_session *s, const cli_render_opts *o, const char *cmd, const char *in,
                     const pnpr_camera *camera, int tile_progress, pnpr_render_stats *r_stats);
void cli_render_end(cli_render_session *s);

#endif
