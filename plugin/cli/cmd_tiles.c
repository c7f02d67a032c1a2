/* Tiled runs of `pointnpr features` (pointnpr/tiles.h, docs/tiles.md): one tile's job, the whole
 * run tile by tile in this process, the manifest of independent jobs for a scheduler, and
 * `pointnpr merge-tiles`. */
#include "cli.h"
#include "cli_opts.h"

#include <pointnpr/features.h>
#include <pointnpr/options.h>
#include <pointnpr/output.h>
#include <pointnpr/props.h>
#include <pointnpr/tiles.h>

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define STR_(x) #x
#define STR(x) STR_(x)

static const cli_opt tile_opts[] = {
    {"--tile-points", NULL, CLI_NUMBER, offsetof(cli_tile_args, tile_points), 1000, 4e9, 0, 0, NULL, NULL, "N",
     "run in tiles of at most N points each (docs/tiles.md)"},
    {"--tiles", NULL, CLI_FLAG, offsetof(cli_tile_args, tiled), 0, 0, 0, 0, NULL, NULL, NULL,
     "run in tiles as large as --memory-limit (or the memory available) allows"},
    {"--halo", NULL, CLI_NUMBER, offsetof(cli_tile_args, halo), 0, CLI_UNBOUNDED, 0, 0, NULL, NULL, "H",
     "a tile's halo in x and y, world units (default or 0: " STR(PNPR_TILE_HALO_SPACINGS) " point spacings)"},
    {"--manifest", NULL, CLI_TEXT, offsetof(cli_tile_args, manifest), 0, 0, 0, 0, NULL, NULL, "DIR",
     "write the tiles' jobs (DIR/jobs.txt) and their merge (DIR/merge.txt) instead of running them"},
    {"--tile-grid", NULL, CLI_LIST, offsetof(cli_tile_args, grid), 0, 0, 0, 9, NULL, NULL, "X,Y,CX,CY,NX,NY,OX,OY,OZ",
     "one tile's job (written by --manifest): the plan's grid and origin"},
    {"--tile", NULL, CLI_LIST, offsetof(cli_tile_args, cells), 0, 0, 0, 4, NULL, NULL, "X0,Y0,X1,Y1",
     "one tile's job: its cells"},
};

int cli_tile_option(cli_tile_args *t, const char *cmd, int argc, char **argv, int *i)
{
    return cli_opts_parse(tile_opts, CLI_COUNT(tile_opts), t, cmd, argc, argv, i);
}

void cli_tile_usage(FILE *f, int halo)
{
    cli_opts_usage(f, tile_opts, 2); /* --tile-points, --tiles */
    if (halo) cli_opts_usage(f, tile_opts + 2, 1);
    cli_opts_usage(f, tile_opts + 3, CLI_COUNT(tile_opts) - 3);
}

int cli_tile_wanted(const cli_tile_args *t)
{
    return t->tile_points > 0 || t->tiled || t->manifest || t->grid[4] > 0;
}

/* The job's grid and tile from --tile-grid and --tile; 0 after saying why. */
int cli_tile_job_args(const char *cmd, const cli_tile_args *a, pnpr_tile_grid *g, pnpr_tile *t)
{
    memset(g, 0, sizeof *g);
    memset(t, 0, sizeof *t);
    int whole = 1;
    for (int k = 0; k < 2; k++) {
        g->min[k] = a->grid[k];
        g->cell[k] = a->grid[2 + k];
        g->origin[k] = a->grid[6 + k];
        g->origin[2] = a->grid[8];
        for (int j = 0; j < 2; j++) /* whole numbers in 0..PNPR_TILE_GRID before any cast */
            whole &= a->cells[2 * j + k] == floor(a->cells[2 * j + k]) && a->cells[2 * j + k] >= 0 &&
                     a->cells[2 * j + k] <= PNPR_TILE_GRID;
        whole &= a->grid[4 + k] == floor(a->grid[4 + k]) && a->grid[4 + k] >= 1 && a->grid[4 + k] <= PNPR_TILE_GRID;
        g->cells[k] = whole ? (uint32_t)a->grid[4 + k] : 0;
        t->lo[k] = whole ? (uint32_t)a->cells[k] : 0;
        t->hi[k] = whole ? (uint32_t)a->cells[2 + k] : 0;
    }
    pnpr_error err = {0};
    if (whole && pnpr_tile_check(g, t, a->halo, &err) == PNPR_OK) return 1;
    fprintf(stderr, "pointnpr %s: --tile-grid and --tile do not describe a tile of a plan (%s); --manifest writes "
                    "them\n", cmd, whole ? err.message : "cell counts and cells are whole numbers within the grid");
    return 0;
}

/* What a tile's result keeps: its core; without a viewpoint also its halo, marked by
 * PNPR_PROP_TILE_CORE, over which the merge makes the tiles' orientations agree. */
static pnpr_status keep_for_merge(pnpr_cloud *c, const uint8_t *core, int halo)
{
    if (!halo) return pnpr_cloud_keep(c, core, NULL);
    pnpr_property *p = NULL;
    pnpr_status st = pnpr_cloud_add_property(c, PNPR_PROP_TILE_CORE, PNPR_TYPE_UINT8, &p);
    if (st == PNPR_OK && c->count) memcpy(p->data, core, c->count);
    return st;
}

/* One tile: read with its halo, features, certification, the core written. */
static int tile_job(const void *ctx, const char *out, const pnpr_tile_grid *g, const pnpr_tile *t, double halo,
                    size_t *r_uncertain)
{
    const cli_features_run *r = ctx;
    pnpr_cloud c = {0};
    uint8_t *core = NULL;
    pnpr_error err = {0};
    pnpr_read_options ro = {0};
    ro.progress = r->prog;
    pnpr_status st = pnpr_tile_read(r->in, g, t, halo, &ro, &c, &core, &err);
    if (st != PNPR_OK) { cli_report_error("features", st, &err); return 1; }
    size_t halo_points = 0, uncertain = 0;
    for (size_t i = 0; i < c.count; i++) halo_points += !core[i];
    pnpr_features_stats stats;
    st = pnpr_features_check_options(r->fo, &err);
    if (st == PNPR_OK) st = pnpr_compute_features(&c, r->fo, &stats);
    double box[4];
    pnpr_tile_box(g, t, halo, box);
    /* the whole cloud's k: a tile of fewer points (or fewer valid ones) computes with less */
    uint32_t k = r->fo->k ? r->fo->k : pnpr_features_defaults().k;
    if (st == PNPR_OK) st = pnpr_tile_certify(&c, core, box, k, r->fo->threads, NULL, &uncertain);
    st = st == PNPR_OK ? keep_for_merge(&c, core, !r->fo->has_viewpoint) : st;
    free(core);
    if (st == PNPR_OK) {
        char comment[256];
        snprintf(comment, sizeof comment, "pointnpr features k=%u threshold=%.4f tile %u,%u,%u,%u", stats.k_used,
                 stats.threshold_used, t->lo[0], t->lo[1], t->hi[0], t->hi[1]);
        pnpr_write_options wo = {0}; /* a tile is binary PLY, whatever OUT is: the merge places its records */
        wo.format = PNPR_FORMAT_PLY;
        wo.comment = comment;
        st = pnpr_write_file(out, &c, &wo, &err);
    } else if (!err.message[0]) {
        pnpr_error_set(&err, st, "%s: tile: %s", r->in, pnpr_status_string(st));
    }
    if (st == PNPR_OK && !r->quiet)
        fprintf(stderr, "tile %u,%u..%u,%u: %zu points and %zu in the halo, %zu not certain to equal a run in memory\n",
                t->lo[0], t->lo[1], t->hi[0], t->hi[1], c.count - (r->fo->has_viewpoint ? 0 : halo_points), halo_points,
                uncertain);
    pnpr_cloud_free(&c);
    if (st != PNPR_OK) { cli_report_error("features", st, &err); return 1; }
    *r_uncertain += uncertain;
    return 0;
}

/* A word for a POSIX shell: in single quotes, each ' as '\''; a relative path (abs) is written
 * from the current folder, so that the jobs run from anywhere. */
static void shell_word_at(FILE *f, const char *s, int abs)
{
    char cwd[PNPR_OUTPUT_PATH_MAX];
    if (abs && s[0] != '/' && getcwd(cwd, sizeof cwd)) { /* 'cwd'/'s' */
        shell_word_at(f, cwd, 0);
        fputc('/', f);
    }
    fputc('\'', f);
    for (; *s; s++) {
        if (*s == '\'') fputs("'\\''", f);
        else fputc(*s, f);
    }
    fputc('\'', f);
}

static void shell_word(FILE *f, const char *s)
{
    shell_word_at(f, s, 0);
}

/* The options of the command line that every job repeats: all but IN, the output and the planning
 * options (a value follows those named with one). */
static void job_options(FILE *f, int argc, char **argv, const char *in)
{
    static const char *const skip1[] = {"-o", "--output", "--tile-points", "--manifest", "--halo", "--memory-limit", NULL};
    for (int i = 1; i < argc; i++) {
        int skip = argv[i] == in || !strcmp(argv[i], "--tiles");
        for (int k = 0; skip1[k] && !skip; k++)
            if (!strcmp(argv[i], skip1[k])) skip = 2;
        if (skip == 2) i++;
        if (skip) continue;
        fputc(' ', f);
        shell_word(f, argv[i]);
    }
}

typedef struct manifest_ctx {
    const cli_tile_cmd *c;
    const pnpr_tile_plan *plan;
    const char *dir;
    int argc;
    char **argv;
    int merge;
} manifest_ctx;

static int write_manifest(FILE *f, const void *user)
{
    const manifest_ctx *m = user;
    const pnpr_tile_grid *g = &m->plan->grid;
    char path[PNPR_OUTPUT_PATH_MAX];
    if (m->merge) {
        fprintf(f, "pointnpr merge-tiles --points %llu%s%s -o ", (unsigned long long)m->plan->points,
                m->c->merge_flag ? " " : "", m->c->merge_flag ? m->c->merge_flag : "");
        shell_word_at(f, m->c->out, 1);
    }
    for (size_t t = 0; t < m->plan->count; t++) {
        const pnpr_tile *tl = &m->plan->tiles[t];
        snprintf(path, sizeof path, "%s/tile_%05zu.ply", m->dir, t);
        if (m->merge) {
            fputc(' ', f);
            shell_word_at(f, path, 1);
            continue;
        }
        fprintf(f, "pointnpr %s ", m->c->cmd);
        shell_word_at(f, m->c->in, 1);
        job_options(f, m->argc, m->argv, m->c->in);
        if (m->c->job_extra[0]) fprintf(f, " %s", m->c->job_extra);
        fprintf(f, " --tile-grid %.17g,%.17g,%.17g,%.17g,%u,%u,%.17g,%.17g,%.17g --tile %u,%u,%u,%u --halo %.17g -o ",
                g->min[0], g->min[1], g->cell[0], g->cell[1], g->cells[0], g->cells[1], g->origin[0], g->origin[1],
                g->origin[2], tl->lo[0], tl->lo[1], tl->hi[0], tl->hi[1], m->plan->halo);
        shell_word_at(f, path, 1);
        fputc('\n', f);
    }
    if (m->merge) fputc('\n', f);
    return ferror(f);
}

static int manifest(const cli_tile_cmd *c, const pnpr_tile_plan *plan, const char *dir, int argc, char **argv)
{
    char jobs[PNPR_OUTPUT_PATH_MAX], merge[PNPR_OUTPUT_PATH_MAX];
    if (strlen(dir) > PNPR_OUTPUT_PATH_MAX - 32) {
        fprintf(stderr, "pointnpr %s: --manifest %.40s...: the name is too long\n", c->cmd, dir);
        return 2;
    }
    if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
        fprintf(stderr, "pointnpr %s: %s: cannot make the folder: %s\n", c->cmd, dir, strerror(errno));
        return 1;
    }
    snprintf(jobs, sizeof jobs, "%s/jobs.txt", dir);
    snprintf(merge, sizeof merge, "%s/merge.txt", dir);
    manifest_ctx m = {c, plan, dir, argc, argv, 0};
    pnpr_error err = {0};
    pnpr_status st = pnpr_output_write(jobs, write_manifest, &m, &err);
    m.merge = 1;
    if (st == PNPR_OK) st = pnpr_output_write(merge, write_manifest, &m, &err);
    if (st != PNPR_OK) { cli_report_error(c->cmd, st, &err); return 1; }
    if (!c->quiet)
        fprintf(stderr, "wrote %s (%zu independent jobs: e.g. parallel < %s) and %s (run it when they are done)\n", jobs,
                plan->count, jobs, merge);
    return 0;
}

/* The run's work folder beside OUT: ".NAME.tiles.XXXXXX" (mkdtemp); 0 after saying why. */
static int work_folder(const char *cmd, const char *out, char *dir, size_t cap)
{
    const char *slash = strrchr(out, '/');
    int dlen = slash ? (int)(slash - out) + 1 : 0;
    int n = snprintf(dir, cap, "%.*s.%.100s.tiles.XXXXXX", dlen, out, slash ? slash + 1 : out);
    if (n > 0 && (size_t)n < cap && mkdtemp(dir)) return 1;
    fprintf(stderr, "pointnpr %s: cannot make a folder for the tiles beside %s: %s\n", cmd, out, strerror(errno));
    return 0;
}

/* Every tile in turn into the work folder, then the merge; the folder is removed either way. */
static int run_tiles(const cli_tile_cmd *c, const pnpr_tile_plan *plan)
{
    char dir[PNPR_OUTPUT_PATH_MAX - 32]; /* room for "/tile_NNNNN.ply" */
    if (!work_folder(c->cmd, c->out, dir, sizeof dir)) return 1;
    if (!c->quiet) fprintf(stderr, "the tiles go to %s until they are merged\n", dir);
    char (*paths)[PNPR_OUTPUT_PATH_MAX] = calloc(plan->count ? plan->count : 1, sizeof *paths);
    const char **list = calloc(plan->count ? plan->count : 1, sizeof *list);
    int rc = paths && list ? 0 : 1;
    if (rc) fprintf(stderr, "pointnpr %s: out of memory for %zu tiles\n", c->cmd, plan->count);
    size_t uncertain = 0, done = 0;
    for (; rc == 0 && done < plan->count; done++) {
        snprintf(paths[done], sizeof paths[done], "%s/tile_%05zu.ply", dir, done);
        list[done] = paths[done];
        if (!c->quiet) fprintf(stderr, "tile %zu of %zu (%llu points)\n", done + 1, plan->count,
                               (unsigned long long)plan->tiles[done].points);
        rc = c->job(c->ctx, paths[done], &plan->grid, &plan->tiles[done], plan->halo, &uncertain);
    }
    pnpr_error err = {0};
    pnpr_status st = rc ? PNPR_OK : c->merge(c->ctx, list, plan->count, plan->points, c->out, &c->prog, &err);
    if (st != PNPR_OK) { cli_report_error(c->cmd, st, &err); rc = 1; }
    for (size_t t = 0; t < done; t++) remove(paths[t]);
    rmdir(dir);
    free(paths);
    free(list);
    if (rc == 0 && !c->quiet) {
        fprintf(stderr, "wrote %s: %llu points from %zu tiles", c->out, (unsigned long long)plan->points, plan->count);
        if (c->certifies)
            fprintf(stderr, "; %zu not certain to equal a run in memory%s", uncertain,
                    uncertain ? " (a larger --halo makes them so; docs/tiles.md)" : "");
        fputc('\n', stderr);
    }
    return rc;
}

int cli_tile_plan(const cli_tile_cmd *c, const cli_tile_args *a, size_t memory_limit, uint32_t k, pnpr_tile_plan *r_plan)
{
    if (cli_output_is_stream(c->out)) {
        fprintf(stderr, "pointnpr %s: a tiled run places each point by its index: %s must be a file\n", c->cmd, c->out);
        return 2;
    }
    pnpr_tile_plan_options po = {0};
    po.tile_points = (uint64_t)a->tile_points;
    if (!po.tile_points && a->tiled) {
        size_t avail = memory_limit ? memory_limit : pnpr_memory_available(), held = pnpr_memory_resident();
        po.memory_limit = avail > held ? avail - held : 1;
    }
    po.features_k = k;
    po.job_bytes = c->job_bytes;
    po.halo = a->halo;
    po.progress = c->prog;
    pnpr_error err = {0};
    pnpr_status st = pnpr_tile_plan_make(c->in, &po, r_plan, &err);
    if (st != PNPR_OK) { cli_report_error(c->cmd, st, &err); return 1; }
    if (c->quiet) return 0;
    uint64_t most = 0;
    for (size_t t = 0; t < r_plan->count; t++) most = r_plan->tiles[t].points > most ? r_plan->tiles[t].points : most;
    if (most > r_plan->tile_points)
        fprintf(stderr, "pointnpr %s: warning: a tile holds %llu points, more than the %llu asked: one grid cell "
                        "(1/%d of the cloud's side) holds them all\n", c->cmd, (unsigned long long)most,
                (unsigned long long)r_plan->tile_points, PNPR_TILE_GRID);
    return 0;
}

int cli_tile_execute(const cli_tile_cmd *c, const cli_tile_args *a, const pnpr_tile_plan *plan, int argc, char **argv)
{
    if (!c->quiet)
        fprintf(stderr, "%s: %llu points in %zu tiles (a grid of %ux%u cells of %.6g), halo %.6g (point spacing %.4g)\n",
                c->in, (unsigned long long)plan->points, plan->count, plan->grid.cells[0], plan->grid.cells[1],
                plan->grid.cell[0], plan->halo, plan->spacing);
    return a->manifest ? manifest(c, plan, a->manifest, argc, argv) : run_tiles(c, plan);
}

static pnpr_status features_merge(const void *ctx, const char *const *paths, size_t n, uint64_t points, const char *out,
                                  const pnpr_progress *prog, pnpr_error *err)
{
    const cli_features_run *r = ctx;
    return pnpr_tile_merge(paths, n, points, !r->fo->has_viewpoint, out, prog, err);
}

int cli_features_tiles(const cli_features_run *r, const cli_tile_args *a, size_t memory_limit, int argc, char **argv)
{
    if (r->wo->format != PNPR_FORMAT_PLY || r->wo->encoding != PNPR_PLY_BINARY_LE) {
        fprintf(stderr, "pointnpr features: a tiled run writes binary PLY (records of one size): %s must end in .ply, "
                        "without --ascii\n", r->out);
        return 2;
    }
    if (a->grid[4] > 0) {
        pnpr_tile_grid g;
        pnpr_tile t;
        size_t uncertain = 0;
        return cli_tile_job_args("features", a, &g, &t) ? tile_job(r, r->out, &g, &t, a->halo, &uncertain) : 2;
    }
    /* per tile: its summary line, not every stage's */
    cli_features_run job = *r;
    job.prog.fn = NULL;
    pnpr_features_options fo = *r->fo;
    fo.progress.fn = NULL;
    job.fo = &fo;
    cli_tile_cmd c = {"features", r->in, r->out, r->quiet, r->prog, "", r->fo->has_viewpoint ? NULL : "--seams", 1, 0,
                      tile_job, features_merge, &job};
    pnpr_tile_plan plan;
    int rc = cli_tile_plan(&c, a, memory_limit, r->fo->k, &plan);
    if (rc) return rc;
    if (!r->quiet && !(r->fo->threshold > 0))
        fprintf(stderr, "pointnpr features: note: each tile picks its own automatic threshold; --threshold T makes "
                        "the tiles equal to a run in memory with that threshold\n");
    rc = cli_tile_execute(&c, a, &plan, argc, argv);
    pnpr_tile_plan_free(&plan);
    return rc;
}

typedef struct merge_args {
    double points;
    int seams, segments;
} merge_args;

/* pointnpr merge-tiles --points N [--seams] -o OUT.ply TILE.ply... */
int cli_merge_tiles(int argc, char **argv)
{
    cli_common c = {0};
    merge_args a = {-1, 0, 0};
    static const cli_opt opts[] = {
        {"--points", NULL, CLI_NUMBER, offsetof(merge_args, points), 0, 4294967294.0, 0, 0, NULL, NULL, "N",
         "the points of the tiled file"},
        {"--seams", NULL, CLI_FLAG, offsetof(merge_args, seams), 0, 0, 0, 0, NULL, NULL, NULL,
         "the jobs oriented normals without --viewpoint: make them agree across tiles"},
        {"--segments", NULL, CLI_FLAG, offsetof(merge_args, segments), 0, 0, 0, 0, NULL, NULL, NULL,
         "the tiles of `pointnpr segment --method components`: join their components"},
    };
    const char **tiles = calloc((size_t)argc, sizeof *tiles);
    size_t n = 0;
    for (int i = 1; tiles && i < argc; i++) {
        int oo = cli_opts_parse(opts, CLI_COUNT(opts), &a, "merge-tiles", argc, argv, &i);
        if (oo == 0) oo = cli_opts_parse(cli_common_opts, CLI_COUNT(cli_common_opts), &c, "merge-tiles", argc, argv, &i);
        if (oo < 0) { free(tiles); return 2; }
        if (c.help) {
            printf("usage: pointnpr merge-tiles --points N [--seams | --segments] -o OUT.ply TILE.ply...\n"
                   "  Writes the tiles of a tiled `pointnpr features` or `pointnpr segment` run (--manifest) as\n"
                   "  one cloud, each point at its index in the tiled file; every index must come exactly once.\n");
            cli_opts_usage(stdout, opts, CLI_COUNT(opts));
            free(tiles);
            return 0;
        }
        if (oo == 0) tiles[n++] = argv[i];
    }
    double points = a.points;
    if (!tiles || !c.out || points < 0 || n == 0 || points != floor(points)) {
        fprintf(stderr, "pointnpr merge-tiles: wants --points N, -o OUT.ply and the tiles (pointnpr merge-tiles --help)\n");
        free(tiles);
        return 2;
    }
    if (pnpr_format_from_path(c.out) != PNPR_FORMAT_PLY) {
        fprintf(stderr, "pointnpr merge-tiles: writes binary PLY: %s must end in .ply\n", c.out);
        free(tiles);
        return 2;
    }
    int rc = cli_check_output("merge-tiles", c.out, tiles, n, 1) ? 0 : 1;
    cli_progress_state ps = {{0}, 0, 0};
    pnpr_progress prog = {c.quiet ? NULL : cli_progress_stderr, &ps};
    pnpr_error err = {0};
    uint32_t S = 0;
    if (a.seams && a.segments) {
        fprintf(stderr, "pointnpr merge-tiles: --seams (features) or --segments (segment), not both\n");
        rc = 2;
    }
    pnpr_status st = rc ? PNPR_OK
                   : a.segments ? pnpr_tile_merge_segments(tiles, n, (uint64_t)points, c.out, &prog, &S, &err)
                                : pnpr_tile_merge(tiles, n, (uint64_t)points, a.seams, c.out, &prog, &err);
    if (st != PNPR_OK) { cli_report_error("merge-tiles", st, &err); rc = 1; }
    char segs[32] = "";
    if (a.segments) snprintf(segs, sizeof segs, ", %u segments", S);
    if (rc == 0 && !c.quiet) fprintf(stderr, "wrote %s (%.0f points from %zu tiles%s)\n", c.out, points, n, segs);
    free(tiles);
    return rc;
}
