/* render and animate on a cloud larger than memory: a sample that fits (docs/tiles.md).
 *
 * A 4K frame has 8.3M pixels and the screen-space budget (--density) draws a few points per
 * pixel at most, so a 200M-point cloud is drawn from a small part of its points anyway. When the
 * whole cloud would not fit (the memory model, memory.h, for the cloud as read and the renderer),
 * a binary PLY is read through the reader's point filter keeping each point with the probability
 * that fits, decided by a hash of its index (the same points at every run and every size), and
 * the stored point spacing (the disk radii) grows by 1/sqrt of that share, as the spacing of a
 * uniformly thinned surface does. --sample asks for a share itself (a quick preview). With
 * cameras given (render --eye/--target, --camera or --camera-path; animate: its path's frames, up
 * to 64 views standing for them all; a preset's path made from a preview of the cloud), the share
 * follows their views instead: points near a camera kept, far ones thinned, unseen ones left out
 * (below). */
#include "cli.h"

#include <pointnpr/crq.h>
#include <pointnpr/lod.h>
#include <pointnpr/memory.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* A file ordered for drawing (pointnpr/lod.h): the ranges a pass reads and each point's rank
 * (pnpr_lod_rank), instead of every point and the hash of its index. */
typedef struct lod_read {
    int on;
    pnpr_lod lod;
    uint64_t *ranges;       /* 2 (cells + 1) values */
    uint8_t *runs;          /* each cell's runs the ranges hold */
    size_t count;           /* the ranges of the next pass */
    size_t cursor;          /* the run of the last point ranked (pnpr_lod_run_at) */
} lod_read;

/* Whether the point of index i is in the sample of `share` (its rank below it). */
static int point_kept(lod_read *lr, uint64_t i, double share)
{
    return pnpr_lod_kept(lr && lr->on ? &lr->lod : NULL, i, lr ? &lr->cursor : NULL, share);
}

typedef struct sample_keep {
    uint64_t seen;
    double share;  /* keep when the point's rank < share (1: all) */
    lod_read *lr;  /* NULL: an ordinary file */
} sample_keep;

static int keep_sample(void *user, uint64_t index, const double p[3])
{
    (void)p;
    sample_keep *s = user;
    s->seen = index + 1;
    return point_kept(s->lr, index, s->share);
}

/* The share of what fits that a sample takes: the cloud as read is estimated from the file's
 * record size, and the process's resident memory after reading is a little more (a sample that
 * fitted 150 MiB by 0.9 was refused by 1 MiB after reading). */
#define SAMPLE_MARGIN 0.85
/* What reading a sample holds beyond its points (the reader's buffers, the heap): a 400k-point
 * file of 12-byte records sampled under 110M to 135M grew the process by 4 to 5 MiB more than its
 * points, and was refused after reading by 1 to 2 MiB. */
#define SAMPLE_RESERVE (8.0 * 1048576.0)

/* The most points of `rec` bytes each (the cloud as read) that fit in `room` with the estimate of
 * `mp` for them (memory.h: the same figures as the check after reading); at most `points`. */
static double fitting_count(const pnpr_memory_plan *mp, double rec, double room, uint64_t points)
{
    uint64_t lo = 0, hi = points;
    while (lo < hi) {
        uint64_t mid = lo + (hi - lo + 1) / 2;
        pnpr_memory_plan p = *mp;
        p.points = (size_t)mid;
        pnpr_memory_estimate e;
        pnpr_memory_estimate_plan(&p, &e);
        if ((double)e.total + rec * (double)mid <= room) lo = mid;
        else hi = mid - 1;
    }
    return (double)lo;
}

/* The share of the file's points that fits, 1 when all do (decided from its size alone, without a
 * pass unless need_pass); 0 when it cannot tell (not a PLY); -1 when not even one point does. The pass over the coordinates calls
 * `keep` with `user` (it counts, makes the views' histograms, or keeps a preview); *r_points: the
 * points seen (*seen after the pass); r_kept (NULL: freed): the points `keep` kept. A file ordered
 * for drawing (lr on) is read in lr's ranges only (none: the pass reads its header alone), and
 * its index counts its points. */
static double fitting_share(const char *in, const pnpr_memory_plan *mp, cli_plan_fn plan, void *plan_user,
                            size_t limit, int (*keep)(void *, uint64_t, const double *), void *user,
                            const uint64_t *seen, int need_pass, uint64_t *r_points, pnpr_cloud *r_kept, lod_read *lr)
{
    struct stat sb;
    if (pnpr_format_from_path(in) != PNPR_FORMAT_PLY || stat(in, &sb) != 0 || !S_ISREG(sb.st_mode)) return 0;
    double room = (limit ? (double)limit : (double)pnpr_memory_available()) - (double)pnpr_memory_resident();
    uint64_t most = (uint64_t)sb.st_size / 12; /* 12 bytes a point at least: at most this many */
    if (!need_pass && fitting_count(mp, 12.0 + 8.0, room - (double)sb.st_size, most) >= (double)most) return 1;
    pnpr_read_options ro = {0};
    ro.keep = keep;
    ro.keep_user = user;
    if (lr && lr->on) {
        ro.ranges = lr->ranges;
        ro.range_count = lr->count;
        lr->cursor = 0;
    }
    pnpr_cloud none_read = {0};
    pnpr_error err = {0};
    if (pnpr_read_file(in, &ro, &none_read, &err) != PNPR_OK) return 0; /* the real read says why */
    pnpr_memory_plan m = *mp; /* with the stages the file's properties leave to run */
    if (plan) plan(&none_read, plan_user, &m);
    if (r_kept) *r_kept = none_read;
    else pnpr_cloud_free(&none_read);
    *r_points = lr && lr->on ? lr->lod.points : *seen;
    if (!*r_points) return 1;
    /* the cloud as read, a point: its record and 8 bytes, x 1.5 for the reader's arrays, which grow
     * by doubling while a filtered stream's count is unknown (measured: 104 bytes a point for the
     * farm's 64-byte records; at x 1 a sample sized to fit 200M was refused by 1 MiB) */
    const double n = (double)*r_points;
    double rec = 1.5 * (double)sb.st_size / n + 8.0;
    double fit = fitting_count(&m, rec, room - SAMPLE_RESERVE, *r_points);
    return fit >= n ? 1 : fit > 0 ? SAMPLE_MARGIN * fit / n : -1;
}

/* ---- the views' sample: cameras given (crq.h) ---------------------------------------------- */

typedef struct view_keep {
    uint64_t seen;
    int solved;           /* 0: the histogram pass (keeps nothing) */
    pnpr_view_sample v;
    lod_read *lr;         /* NULL: an ordinary file */
} view_keep;

static int keep_view(void *user, uint64_t index, const double p[3])
{
    view_keep *k = user;
    k->seen = index + 1;
    if (!k->solved) {
        pnpr_view_sample_add(&k->v, p);
        return 0;
    }
    return point_kept(k->lr, index, pnpr_view_sample_share(&k->v, p));
}

/* ---- a file ordered for drawing (lod.h) ----------------------------------------------------- */

static void lod_end(lod_read *lr)
{
    pnpr_lod_free(&lr->lod);
    free(lr->ranges);
    free(lr->runs);
    memset(lr, 0, sizeof *lr);
}

/* lr on when `in` is a file ordered for drawing (a warning when it says it is one but its index
 * lies: it is read as an ordinary PLY then). Its first pass reads no range. */
static void lod_begin(lod_read *lr, const char *in, int quiet)
{
    pnpr_error err = {0};
    memset(lr, 0, sizeof *lr);
    pnpr_status st = pnpr_lod_open(in, &lr->lod, &err);
    const size_t cells = (size_t)lr->lod.cells + 1;
    if (st == PNPR_OK && (!(lr->ranges = malloc(2 * cells * sizeof *lr->ranges)) || !(lr->runs = malloc(cells))))
        st = PNPR_ERR_OUT_OF_MEMORY;
    if (st == PNPR_OK) lr->on = 1;
    else if (st != PNPR_ERR_UNSUPPORTED && !quiet) {
        size_t n = strlen(in); /* the message names the file: once is enough */
        const char *why = !strncmp(err.message, in, n) && !strncmp(err.message + n, ": ", 2) ? err.message + n + 2 : err.message;
        fprintf(stderr, "%s: warning: its order for drawing cannot be used (%s); reading it as an ordinary PLY\n", in,
                why[0] ? why : pnpr_status_string(st));
    }
    if (!lr->on) lod_end(lr);
}

/* The ranges of the next pass (pnpr_lod_plan_ranges): by the views of v solved, or `uniform`
 * (v NULL). Returns the points the ranges hold, or -1 when memory runs out. */
static double lod_plan(lod_read *lr, const pnpr_view_sample *v, double uniform)
{
    return pnpr_lod_plan_ranges(&lr->lod, v, uniform, lr->ranges, lr->runs, &lr->count);
}

/* The views of the cameras (the frames to draw) into k, each view's own histogram when there are
 * several (the frame's cap); 0 when there are none, or one is not a look-at view (the frame would
 * not draw either). */
static int init_views(view_keep *k, const pnpr_camera *cams, size_t count, int width, int height)
{
    if (!cams || count == 0) return 0;
    double *eyes = malloc(7 * count * sizeof *eyes), *targets = eyes + 3 * count, *fovs = eyes + 6 * count;
    if (!eyes) return 0;
    for (size_t i = 0; i < count; i++) {
        memcpy(eyes + 3 * i, cams[i].eye, sizeof cams[i].eye);
        memcpy(targets + 3 * i, cams[i].target, sizeof cams[i].target);
        fovs[i] = cams[i].fov_y_deg > 0 ? cams[i].fov_y_deg : 45;
    }
    int ok = pnpr_view_sample_init_frames(&k->v, eyes, targets, fovs, count, width, height) == PNPR_OK;
    free(eyes);
    if (ok && k->v.views > 1 && !(k->v.each = calloc((size_t)k->v.views, sizeof *k->v.each))) return 0;
    return ok;
}

/* The frames' views from a uniform preview of the file (a preset's path comes from the cloud):
 * the pass that counts the points keeps about PREVIEW_POINTS of them (fewer for wider records).
 * When the file is to be sampled (`asked`, or it does not fit), the views of the frames of
 * views->from_preview go into vk, and a second pass makes their histograms: returns 1 then, with
 * *r_fit and *r_points; else 0 with the uniform share that fits in *r_fit. */
#define PREVIEW_POINTS 200000.0
static int preview_views(const char *in, const pnpr_memory_plan *mp, cli_plan_fn plan, void *plan_user, size_t limit,
                         int asked, const cli_sample_views *views, view_keep *vk, double *r_fit, uint64_t *r_points)
{
    struct stat sb;
    double most = vk->lr->on ? (double)vk->lr->lod.points : stat(in, &sb) == 0 ? (double)sb.st_size / 12.0 : 0;
    sample_keep count = {0, most > PREVIEW_POINTS ? PREVIEW_POINTS / most : 1, vk->lr};
    if (vk->lr->on && lod_plan(vk->lr, NULL, count.share) < 0) {
        *r_fit = 0; /* the read says what does not fit */
        return 0;
    }
    pnpr_cloud preview = {0};
    *r_fit = fitting_share(in, mp, plan, plan_user, limit, keep_sample, &count, &count.seen, asked, r_points, &preview,
                           vk->lr);
    pnpr_camera *cams = NULL;
    size_t n = (asked || (*r_fit > 0 && *r_fit < 1)) && preview.count ? views->from_preview(&preview, views->user, &cams) : 0;
    pnpr_cloud_free(&preview);
    int ok = n && init_views(vk, cams, n, mp->width, mp->height);
    free(cams);
    vk->lr->count = 0;
    if (ok && vk->lr->on) pnpr_lod_add_cells(&vk->lr->lod, &vk->v);
    if (ok) *r_fit = fitting_share(in, mp, plan, plan_user, limit, keep_view, vk, &vk->seen, 1, r_points, NULL, vk->lr);
    return ok;
}

/* A file ordered for drawing: the cells' bound (pnpr_lod_add_cells) counts too many points in
 * view, and a sample solved on it has too few: c solved again from the runs it reaches
 * (pnpr_lod_view_refine). */
static int lod_refine(const char *cmd, const char *in, lod_read *lr, view_keep *vk, double want, double frame_want)
{
    pnpr_error err = {0};
    pnpr_status st = pnpr_lod_view_refine(in, &lr->lod, &vk->v, want, frame_want, NULL, &err);
    if (st != PNPR_OK) { cli_report_error(cmd, st, &err); return 0; }
    return 1;
}

/* The read of `share` of the file (all of it when 1): by the views of vk (NULL: uniform), in the
 * ranges of a file ordered for drawing (lr on); the spacing grown and the sample reported. */
static int read_sample(const char *cmd, const char *in, pnpr_read_options *ro, size_t limit, double share,
                       view_keep *vk, lod_read *lr, int quiet, int asked, pnpr_cloud *cloud, float *r_tone_radius)
{
    pnpr_error err = {0};
    sample_keep keep = {0, 1, lr};
    double visited = -1;
    if (share > 0 && share < 1) {
        keep.share = share;
        ro->keep = vk ? keep_view : keep_sample;
        ro->keep_user = vk ? (void *)vk : (void *)&keep;
        if (lr->on && (visited = lod_plan(lr, vk ? &vk->v : NULL, share)) < 0) {
            fprintf(stderr, "pointnpr %s: %s: out of memory for the ranges to read\n", cmd, in);
            return 0;
        }
        ro->ranges = lr->on ? lr->ranges : NULL;
        ro->range_count = lr->on ? lr->count : 0;
        lr->cursor = 0;
    } else if (!cli_memory_check_file(cmd, in, limit)) {
        return 0;
    }
    pnpr_status st = pnpr_read_file(in, ro, cloud, &err);
    if (st != PNPR_OK) { cli_report_error(cmd, st, &err); return 0; }
    if (!ro->keep) return 1;
    uint64_t points = lr->on ? lr->lod.points : vk ? vk->seen : keep.seen;
    double kept = points ? (double)cloud->count / (double)points : 1;
    *r_tone_radius = pnpr_lod_grow_spacing(cloud, vk ? &vk->v : NULL, kept);
    char a[32], how[96] = "";
    const char *what = !vk                ? "a uniform sample"
                       : vk->v.views > 1 ? "a sample by the frames' views (points near a camera kept, far and unseen ones thinned)"
                                         : "a sample by the view (points near the camera kept, far and unseen ones thinned)";
    if (visited >= 0)
        snprintf(how, sizeof how, "; ordered for drawing: %.1f%% of its points read", 100.0 * visited / (double)(points ? points : 1));
    if (!quiet && asked)
        fprintf(stderr, "%s: drawing %s of %zu of %llu points (%.1f%%, --sample%s)\n", in, what, cloud->count,
                (unsigned long long)points, 100.0 * kept, how);
    else if (!quiet)
        fprintf(stderr, "%s: %llu points do not fit in %s: drawing %s of %zu (%.1f%%%s; docs/tiles.md)\n", in,
                (unsigned long long)points, pnpr_memory_text(limit ? limit : pnpr_memory_available(), a, sizeof a), what,
                cloud->count, 100.0 * kept, how);
    return 1;
}

/* The share that fits, by the views when there are (*r_by_view: vk's views, their histograms
 * made) or uniform (*r_share; the asked one stays), and the points (*r_points): returns what
 * fits (< 0: not even a sample; the uniform share, or the views' fit). */
static double plan_sample(const char *in, const pnpr_memory_plan *mp, cli_plan_fn plan, void *plan_user, size_t limit,
                          const cli_sample_views *views, int asked, lod_read *lr, view_keep *vk, int *r_by_view,
                          double *r_share, uint64_t *r_points)
{
    const int ply = pnpr_format_from_path(in) == PNPR_FORMAT_PLY;
    double fit = 0;
    vk->lr = lr;
    *r_by_view = ply && views && init_views(vk, views->cams, views->count, mp->width, mp->height);
    if (*r_by_view) {
        if (lr->on) pnpr_lod_add_cells(&lr->lod, &vk->v);
        fit = fitting_share(in, mp, plan, plan_user, limit, keep_view, vk, &vk->seen, asked, r_points, NULL, lr);
        if (asked && !*r_points) *r_by_view = 0; /* no pass (not a regular file): the uniform share asked */
        return fit;
    }
    if (ply && views && views->from_preview && !views->count) {
        *r_by_view = preview_views(in, mp, plan, plan_user, limit, asked, views, vk, &fit, r_points);
        if (!asked && !*r_by_view) *r_share = fit;
        return fit;
    }
    if (!asked) {
        sample_keep count = {0, 0, lr};
        *r_share = fitting_share(in, mp, plan, plan_user, limit, keep_sample, &count, &count.seen, 0, r_points, NULL, lr);
    }
    return *r_share;
}

int cli_read_fitting(const char *cmd, const char *in, const pnpr_read_options *opts, const pnpr_memory_plan *mp,
                     cli_plan_fn plan, void *plan_user, size_t limit, double share, const cli_sample_views *views,
                     double frame_points, int quiet, pnpr_cloud *cloud, float *r_tone_radius)
{
    *r_tone_radius = 0;
    pnpr_read_options ro = *opts;
    uint64_t points = 0;
    const int asked = share > 0 && share < 1, ply = pnpr_format_from_path(in) == PNPR_FORMAT_PLY;
    lod_read lr = {0};
    if (ply) lod_begin(&lr, in, quiet);
    view_keep vk = {0};
    int by_view = 0;
    const double asked_share = share;
    double fit = plan_sample(in, mp, plan, plan_user, limit, views, asked, &lr, &vk, &by_view, &share, &points);
    if (!asked && fit < 0 && lr.on) { /* the order's index took the room: the ordinary read may fit */
        lod_end(&lr);
        free(vk.v.each);
        memset(&vk, 0, sizeof vk);
        share = asked_share;
        fit = plan_sample(in, mp, plan, plan_user, limit, views, asked, &lr, &vk, &by_view, &share, &points);
    }
    int ok = 1;
    if (!asked && fit < 0) { /* refused before reading the file */
        char a[32];
        fprintf(stderr, "pointnpr %s: %s: not even a sample of its %llu points fits in %s: drawing needs more "
                        "(--memory-limit; docs/tiles.md)\n", cmd, in, (unsigned long long)points,
                pnpr_memory_text(limit ? limit : pnpr_memory_available(), a, sizeof a));
        ok = 0;
    } else if (by_view) {
        if (!asked) share = fit;
        /* each frame's share at most what it draws (the screen-space budget thins by depth too, but
         * a larger sample costs reading and upload) */
        pnpr_view_sample_solve(&vk.v, share * (double)points, asked ? 0 : frame_points);
        vk.solved = 1;
        if (lr.on && share < 1) ok = lod_refine(cmd, in, &lr, &vk, share * (double)points, asked ? 0 : frame_points);
        if (points && !vk.v.least.visible)
            fprintf(stderr, "%s: warning: none of its %llu points is in view of the camera%s (they lie behind "
                            "the eye or outside the field of view)\n", in, (unsigned long long)points,
                    vk.v.views > 1 ? "s of the frames" : "");
    }
    free(vk.v.each); /* read by the solve only */
    vk.v.each = NULL;
    if (ok) ok = read_sample(cmd, in, &ro, limit, share, by_view ? &vk : NULL, &lr, quiet, asked, cloud, r_tone_radius);
    lod_end(&lr);
    return ok;
}
