/* libFuzzer target for a file ordered for drawing (pointnpr/lod.h): any input must be parsed
 * without crash, leak or UB; a refusal says why. What parses keeps its promises: a grid of 1 to
 * PNPR_VIEW_CELLS_MAX cells, runs ascending to the vertex count, each vertex found in its run;
 * and a read of its ranges visits exactly their points, or fails with a message (the PLY reader
 * may refuse what the index does not describe, such as vertices without x). */
#include "fuzz_common.h"

#include <pointnpr/lod.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

typedef struct visit {
    uint64_t visited;
} visit;

static int keep_half(void *user, uint64_t index, const double p[3])
{
    (void)p;
    ((visit *)user)->visited++;
    return index % 2 == 0;
}

static void check_ranges(const uint8_t *data, size_t size, const pnpr_lod *l)
{
    const size_t cells = (size_t)l->cells + 1;
    double *share = malloc(cells * sizeof *share);
    uint64_t *ranges = malloc(2 * cells * sizeof *ranges);
    uint8_t *runs = malloc(cells);
    if (!share || !ranges || !runs) abort();
    for (size_t k = 0; k < cells; k++) share[k] = k % 3 == 0 ? 0 : k % 3 == 1 ? 0.01 : 1;
    size_t m = pnpr_lod_ranges(l, share, ranges, runs);
    uint64_t in_ranges = 0;
    for (size_t g = 0; g < m; g++) {
        if (ranges[2 * g] >= ranges[2 * g + 1] || ranges[2 * g + 1] > l->points || (g && ranges[2 * g] <= ranges[2 * g - 1]))
            abort();
        in_ranges += ranges[2 * g + 1] - ranges[2 * g];
    }
    visit v = {0};
    pnpr_read_options ro;
    memset(&ro, 0, sizeof ro);
    ro.keep = keep_half;
    ro.keep_user = &v;
    ro.ranges = ranges;
    ro.range_count = m;
    pnpr_cloud c;
    pnpr_error err;
    memset(&c, 0, sizeof c);
    if (pnpr_read_ply_memory(data, size, &ro, &c, &err) == PNPR_OK) {
        if (v.visited != in_ranges) abort();
        pnpr_cloud_free(&c);
    } else {
        fuzz_check_failed(&c, &err);
    }
    free(share);
    free(ranges);
    free(runs);
}

/* The view's pieces on whatever grid parsed (huge sides, far origins): the cells as balls, a
 * solve, the ranges a share reaches, valid and within the points. */
static void check_view(const pnpr_lod *l)
{
    double eye[3], target[3];
    for (int a = 0; a < 3; a++) {
        target[a] = l->origin[a] + 0.5 * l->side * (double)l->n[a];
        eye[a] = target[a] - (a == 2 ? -3.0 : 2.0) * l->side * (double)l->n[a] - 1.0;
    }
    pnpr_view_sample v;
    if (pnpr_view_sample_init(&v, eye, target, 50, 640, 480) != PNPR_OK) return; /* not finite: no view */
    pnpr_lod_add_cells(l, &v);
    pnpr_view_sample_solve(&v, (double)l->points / 3.0, 0);
    const size_t cells = (size_t)l->cells + 1;
    uint64_t *ranges = malloc(2 * cells * sizeof *ranges);
    uint8_t *runs = malloc(cells);
    if (!ranges || !runs) abort();
    size_t m = 0;
    double n = pnpr_lod_plan_ranges(l, &v, 1, ranges, runs, &m);
    double sum = 0;
    for (size_t g = 0; g < m; g++) {
        if (ranges[2 * g] >= ranges[2 * g + 1] || ranges[2 * g + 1] > l->points) abort();
        sum += (double)(ranges[2 * g + 1] - ranges[2 * g]);
    }
    if (n != sum || n > (double)l->points) abort();
    free(ranges);
    free(runs);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    pnpr_lod l;
    pnpr_error err;
    memset(&err, 0, sizeof err);
    if (pnpr_lod_parse(data, size, &l, &err) != PNPR_OK) {
        if (err.message[0] == '\0' || l.start) abort();
        return 0;
    }
    const size_t runs = ((size_t)l.cells + 1) * PNPR_LOD_LEVELS;
    if (!l.cells || l.cells > 32768 || l.cells != l.n[0] * l.n[1] * l.n[2] || l.start[0] != 0 ||
        l.start[runs] != l.points || !(l.side > 0))
        abort();
    for (size_t r = 0; r < runs; r++)
        if (l.start[r] > l.start[r + 1]) abort();
    size_t cursor = 0;
    for (uint64_t v = 0; v < l.points && v < 100000; v++) {
        int j = pnpr_lod_run_at(&l, v, &cursor);
        if (j != (int)(cursor % PNPR_LOD_LEVELS) || l.start[cursor] > v || l.start[cursor + 1] <= v) abort();
    }
    check_ranges(data, size, &l);
    check_view(&l);
    pnpr_lod_free(&l);
    return 0;
}
