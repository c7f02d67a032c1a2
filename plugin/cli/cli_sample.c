/* render and animate on a cloud larger than memory: a uniform sample that fits (docs/tiles.md).
 *
 * A 4K frame has 8.3M pixels and the screen-space budget (--density) draws a few points per
 * pixel at most, so a 200M-point cloud is drawn from a small part of its points anyway. When the
 * whole cloud would not fit (the memory model, memory.h, for the cloud as read and the renderer),
 * a binary PLY is read through the reader's point filter keeping each point with the probability
 * that fits, decided by a hash of its index (the same points at every run and every size), and
 * the stored point spacing (the disk radii) grows by 1/sqrt of that share, as the spacing of a
 * uniformly thinned surface does. --sample asks for a share itself (a quick preview). */
#include "cli.h"

#include <pointnpr/memory.h>
#include <pointnpr/props.h>

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

typedef struct sample_keep {
    uint64_t seen;
    uint64_t below; /* keep when the index's hash < below (of 2^64) */
} sample_keep;

static uint64_t mix64(uint64_t x) /* splitmix64's finaliser */
{
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

static int keep_sample(void *user, uint64_t index, const double p[3])
{
    (void)p;
    sample_keep *s = user;
    s->seen = index + 1;
    return s->below == UINT64_MAX || mix64(index) < s->below;
}

/* The share of the file's points that fits, 1 when all do; 0 when it cannot tell (not a PLY). */
static double fitting_share(const char *in, const pnpr_memory_plan *mp, size_t limit, uint64_t *r_points)
{
    struct stat sb;
    if (pnpr_format_from_path(in) != PNPR_FORMAT_PLY || stat(in, &sb) != 0 || !S_ISREG(sb.st_mode)) return 0;
    pnpr_memory_plan one = *mp, none = *mp;
    one.points = 1000000;
    none.points = 0;
    pnpr_memory_estimate e1, e0;
    pnpr_memory_estimate_plan(&one, &e1);
    pnpr_memory_estimate_plan(&none, &e0);
    double per = (double)(e1.total - e0.total) / 1e6, avail = limit ? (double)limit : (double)pnpr_memory_available();
    avail -= (double)pnpr_memory_resident() + (double)e0.total;
    if ((double)sb.st_size * (1.0 + per / 12.0) < avail) return 1; /* 12 bytes a point at least: fits */
    sample_keep count = {0, 0};
    pnpr_read_options ro = {0};
    ro.keep = keep_sample;
    ro.keep_user = &count;
    pnpr_cloud none_read = {0};
    pnpr_error err = {0};
    if (pnpr_read_file(in, &ro, &none_read, &err) != PNPR_OK) return 0; /* the real read says why */
    pnpr_cloud_free(&none_read);
    *r_points = count.seen;
    double rec = count.seen ? (double)sb.st_size / (double)count.seen + 8.0 : 0, fit = avail / (rec + per);
    return fit >= (double)count.seen ? 1 : fit > 0 ? 0.9 * fit / (double)count.seen : 0;
}

int cli_read_fitting(const char *cmd, const char *in, const pnpr_read_options *opts, const pnpr_memory_plan *mp,
                     size_t limit, double share, int quiet, pnpr_cloud *cloud)
{
    pnpr_read_options ro = *opts;
    pnpr_error err = {0};
    uint64_t points = 0;
    const int asked = share > 0 && share < 1;
    if (!asked) share = fitting_share(in, mp, limit, &points);
    sample_keep keep = {0, UINT64_MAX};
    if (share > 0 && share < 1) {
        keep.below = (uint64_t)(share * 18446744073709551616.0);
        ro.keep = keep_sample;
        ro.keep_user = &keep;
    } else if (!cli_memory_check_file(cmd, in, limit)) {
        return 0;
    }
    pnpr_status st = pnpr_read_file(in, &ro, cloud, &err);
    if (st != PNPR_OK) { cli_report_error(cmd, st, &err); return 0; }
    if (!ro.keep) return 1;
    points = keep.seen;
    double kept = points ? (double)cloud->count / (double)points : 1;
    pnpr_property *sp = pnpr_cloud_find_property(cloud, PNPR_PROP_POINT_SPACING);
    if (sp && sp->type == PNPR_TYPE_FLOAT32 && kept > 0)
        for (size_t i = 0; i < cloud->count; i++) ((float *)sp->data)[i] /= (float)sqrt(kept);
    char a[32];
    if (!quiet && asked)
        fprintf(stderr, "%s: drawing a uniform sample of %zu of %llu points (%.1f%%, --sample)\n", in, cloud->count,
                (unsigned long long)points, 100.0 * kept);
    else if (!quiet)
        fprintf(stderr, "%s: %llu points do not fit in %s: drawing a uniform sample of %zu (%.1f%%; docs/tiles.md)\n", in,
                (unsigned long long)points, pnpr_memory_text(limit ? limit : pnpr_memory_available(), a, sizeof a),
                cloud->count, 100.0 * kept);
    return 1;
}
