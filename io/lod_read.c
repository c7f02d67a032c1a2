/* pointnpr — samples of a large PLY (include/pointnpr/lod.h): uniform (MeshLab's sample layer)
 * or by views (the MeshLab decoration's stream; render and animate use the same pieces in
 * plugin/cli/cli_sample.c, with the share sized to their memory limit).
 *
 * A file ordered for drawing is read in the ranges of each cell's runs that the share reaches;
 * another binary PLY is read whole through the point filter. A point is kept when its rank
 * (pnpr_lod_kept) is below its share, so both kinds of file keep the same rule. */
#include "../core/internal.h"
#include <pointnpr/lod.h>
#include <pointnpr/props.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define LOD_L PNPR_LOD_LEVELS

/* One pass of several: its reports mapped into [base, base + span] of the caller's progress, never
 * backwards (the reader reports its filter's pass and its decoding pass each from 0). */
typedef struct pass_progress {
    const pnpr_progress *outer;
    double base, span, last;
} pass_progress;

static int pass_report(void *user, const char *stage, double fraction)
{
    pass_progress *p = user;
    (void)stage;
    double f = p->base + p->span * (fraction >= 0 && fraction <= 1 ? fraction : 0);
    if (f > p->last) p->last = f;
    return pnpr_progress_report(p->outer, "sample", p->last);
}

static pnpr_progress pass_of(pass_progress *p, const pnpr_progress *outer, int pass, int passes)
{
    p->outer = outer;
    p->base = (double)pass / passes;
    p->span = 1.0 / passes;
    p->last = p->base;
    return (pnpr_progress){outer && outer->fn ? pass_report : NULL, p};
}

/* ---- the pieces of a read by views ---------------------------------------------------------- */

void pnpr_lod_add_cells(const pnpr_lod *l, pnpr_view_sample *v)
{
    for (uint32_t k = 0; k < l->cells; k++) {
        uint64_t n = pnpr_lod_cell_points(l, k);
        double c[3], rho;
        pnpr_lod_cell_ball(l, k, c, &rho);
        if (n) pnpr_view_sample_add_ball(v, c, rho, n);
    }
}

double pnpr_lod_plan_ranges(const pnpr_lod *l, const pnpr_view_sample *v, double uniform, uint64_t *r_ranges,
                            uint8_t *r_runs, size_t *r_count)
{
    *r_count = 0;
    double *share = malloc(((size_t)l->cells + 1) * sizeof *share);
    if (!share) return -1;
    for (uint32_t k = 0; k < l->cells; k++) {
        double c[3], rho;
        pnpr_lod_cell_ball(l, k, c, &rho);
        share[k] = v ? pnpr_view_sample_ball_share(v, c, rho) : uniform;
    }
    share[l->cells] = v ? 1 : uniform; /* the far outliers and non-finite points: each judged alone */
    *r_count = pnpr_lod_ranges(l, share, r_ranges, r_runs);
    free(share);
    double n = 0;
    for (size_t g = 0; g < *r_count; g++) n += (double)(r_ranges[2 * g + 1] - r_ranges[2 * g]);
    return n;
}

typedef struct refine_read {
    const pnpr_lod *l;
    const uint8_t *runs;
    size_t cursor;
    pnpr_view_sample *v;
} refine_read;

static int keep_refine(void *user, uint64_t i, const double p[3])
{
    refine_read *r = user;
    pnpr_lod_run_at(r->l, i, &r->cursor);
    pnpr_view_sample_add_n(r->v, p, (uint64_t)1 << (LOD_L - r->runs[r->cursor / LOD_L]));
    return 0;
}

/* A pass that keeps nothing (keep only looks: counts, histograms). */
static pnpr_status pass_only(const char *path, const pnpr_read_options *ro, pnpr_error *err)
{
    pnpr_cloud none = {0};
    pnpr_status st = pnpr_read_file(path, ro, &none, err);
    pnpr_cloud_free(&none);
    return st;
}

/* A pass's ranges (pnpr_lod_plan_ranges: by the views of v solved, or `uniform`) into ro, with
 * each cell's runs; *r_ranges and *r_runs are the caller's to free, also on failure. *r_points
 * (may be NULL): the points the ranges hold. */
static pnpr_status plan_pass(const pnpr_lod *l, const pnpr_view_sample *v, double uniform, const char *path,
                             pnpr_read_options *ro, uint64_t **r_ranges, uint8_t **r_runs, double *r_points,
                             pnpr_error *err)
{
    const size_t cells = (size_t)l->cells + 1;
    *r_ranges = malloc(2 * cells * sizeof **r_ranges);
    *r_runs = malloc(cells);
    double n = *r_ranges && *r_runs ? pnpr_lod_plan_ranges(l, v, uniform, *r_ranges, *r_runs, &ro->range_count) : -1;
    if (n < 0) return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s: out of memory for the ranges to read", path);
    ro->ranges = *r_ranges;
    if (r_points) *r_points = n;
    return PNPR_OK;
}

pnpr_status pnpr_lod_view_refine(const char *path, const pnpr_lod *l, pnpr_view_sample *v, double want,
                                 double frame_want, const pnpr_progress *progress, pnpr_error *err)
{
    uint64_t *ranges = NULL;
    uint8_t *runs = NULL;
    pnpr_read_options ro = {0};
    pnpr_status st = plan_pass(l, v, 1, path, &ro, &ranges, &runs, NULL, err);
    refine_read r = {l, runs, 0, v};
    ro.keep = keep_refine;
    ro.keep_user = &r;
    if (progress) ro.progress = *progress;
    if (st == PNPR_OK) {
        pnpr_view_sample_clear(v);
        st = pass_only(path, &ro, err);
    }
    if (st == PNPR_OK) pnpr_view_sample_solve(v, want, frame_want);
    free(ranges);
    free(runs);
    return st;
}

/* ---- the spacing of a sample ---------------------------------------------------------------- */

float pnpr_lod_grow_spacing(pnpr_cloud *cloud, const pnpr_view_sample *v, double uniform)
{
    pnpr_property *sp = pnpr_cloud_find_property(cloud, PNPR_PROP_POINT_SPACING);
    if (!sp || sp->type != PNPR_TYPE_FLOAT32) return 0;
    double sum = 0, weight = 0;
    for (size_t i = 0; i < cloud->count; i++) {
        double share = uniform;
        if (v) {
            double w[3];
            pnpr_cloud_world(cloud, i, w);
            share = pnpr_view_sample_share(v, w);
        }
        if (!(share > 0) || share > 1) share = 1;
        float *s = (float *)sp->data + i;
        if (isfinite(*s) && *s >= 0) {
            sum += *s / share;
            weight += 1 / share;
        }
        if (share < 1) *s /= (float)sqrt(share);
    }
    return weight > 0 ? (float)(sum / weight) : 0;
}

/* ---- a sample by views ---------------------------------------------------------------------- */

typedef struct view_read {
    const pnpr_lod *l; /* NULL: an ordinary file */
    size_t cursor;
    pnpr_view_sample *v;
    int solved;        /* 0: the histogram pass of an ordinary file (keeps nothing) */
    uint64_t seen;
} view_read;

static int keep_view(void *user, uint64_t i, const double p[3])
{
    view_read *r = user;
    r->seen = i + 1;
    if (!r->solved) {
        pnpr_view_sample_add(r->v, p);
        return 0;
    }
    return pnpr_lod_kept(r->l, i, &r->cursor, pnpr_view_sample_share(r->v, p));
}

pnpr_status pnpr_lod_read_view(const char *path, pnpr_view_sample *v, uint64_t points, const pnpr_read_options *opts,
                               pnpr_cloud *cloud, pnpr_lod_read_info *r_info, pnpr_error *err)
{
    pnpr_lod_read_info info = {0};
    if (r_info) *r_info = info;
    if (!path || !cloud || !v || v->views < 1 || (opts && (opts->keep || opts->ranges)))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "sample by view: no path, cloud or view, or a point "
                                                             "filter given");
    pnpr_lod l = {0};
    pnpr_error lerr = {0};
    info.ordered = pnpr_lod_open(path, &l, &lerr) == PNPR_OK;
    pnpr_read_options ro = opts ? *opts : (pnpr_read_options){0};
    const pnpr_progress outer = ro.progress;
    view_read r = {info.ordered ? &l : NULL, 0, v, 0, 0};
    ro.keep = keep_view;
    ro.keep_user = &r;
    uint64_t *ranges = NULL;
    uint8_t *runs = NULL;
    pass_progress pp;
    pnpr_view_sample_clear(v);
    pnpr_status st = PNPR_OK;
    if (info.ordered) { /* the cells as balls, then the runs that bound reaches: c as a pass over every point gives it */
        info.total = l.points;
        pnpr_lod_add_cells(&l, v);
        pnpr_view_sample_solve(v, (double)points, 0);
        pnpr_progress pr = pass_of(&pp, &outer, 0, 2);
        st = pnpr_lod_view_refine(path, &l, v, (double)points, 0, &pr, err);
        double n = 0;
        if (st == PNPR_OK) st = plan_pass(&l, v, 1, path, &ro, &ranges, &runs, &n, err);
        info.visited = (uint64_t)n;
    } else {
        ro.progress = pass_of(&pp, &outer, 0, 2);
        st = pass_only(path, &ro, err);
        info.total = info.visited = r.seen;
        pnpr_view_sample_solve(v, (double)points, 0);
    }
    /* an estimate when ordered (the runs read stand for the others): at most the points */
    info.in_view = v->least.visible < info.total ? v->least.visible : info.total;
    r.solved = 1;
    r.cursor = 0;
    pass_progress pp2;
    ro.progress = pass_of(&pp2, &outer, 1, 2);
    if (st == PNPR_OK) st = pnpr_read_file(path, &ro, cloud, err);
    if (st == PNPR_OK && r_info) *r_info = info;
    free(ranges);
    free(runs);
    pnpr_lod_free(&l);
    return st;
}

/* ---- a uniform sample -------------------------------------------------------------------- */

typedef struct sample_read {
    const pnpr_lod *l;    /* NULL: an ordinary file */
    size_t cursor;
    double share;         /* 0: the counting pass */
    uint64_t seen;
} sample_read;

static int keep_uniform(void *user, uint64_t v, const double p[3])
{
    (void)p;
    sample_read *s = user;
    s->seen = v + 1;
    return s->share > 0 && pnpr_lod_kept(s->l, v, &s->cursor, s->share);
}

pnpr_status pnpr_lod_read_sample(const char *path, uint64_t points, const pnpr_read_options *opts, pnpr_cloud *cloud,
                                 uint64_t *r_total, int *r_ordered, pnpr_error *err)
{
    if (r_total) *r_total = 0;
    if (r_ordered) *r_ordered = 0;
    if (!path || !cloud || (opts && opts->keep))
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "sample: no path or cloud, or a point filter given");
    pnpr_lod l = {0};
    pnpr_error lerr = {0};
    const int ordered = pnpr_lod_open(path, &l, &lerr) == PNPR_OK;
    sample_read s = {ordered ? &l : NULL, 0, 0, 0};
    pnpr_read_options ro = opts ? *opts : (pnpr_read_options){0};
    ro.keep = keep_uniform;
    ro.keep_user = &s;
    pnpr_status st = PNPR_OK;
    uint64_t total = l.points;
    if (!ordered) { /* a pass over the coordinates counts the points */
        pnpr_read_options count = ro;
        count.progress = (pnpr_progress){0};
        st = pass_only(path, &count, err);
        total = s.seen;
    }
    s.share = total > points ? (double)points / (double)total : 1;
    uint64_t *ranges = NULL;
    uint8_t *runs = NULL;
    if (st == PNPR_OK && ordered) st = plan_pass(&l, NULL, s.share, path, &ro, &ranges, &runs, NULL, err);
    if (st == PNPR_OK) st = pnpr_read_file(path, &ro, cloud, err);
    if (st == PNPR_OK && r_total) *r_total = total;
    if (st == PNPR_OK && r_ordered) *r_ordered = ordered;
    free(runs);
    free(ranges);
    pnpr_lod_free(&l);
    return st;
}
