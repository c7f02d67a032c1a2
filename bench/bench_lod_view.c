/* The read of a view's sample of a file ordered for drawing (pnpr_lod_read_view: the MeshLab
 * decoration's stream, docs/meshlab.md "A sample layer streamed by the view") against the
 * baseline, the uniform sample of the same count (pnpr_lod_read_sample), in the same run, taking
 * turns, median of 3. Views of the generated scene of bench_features (20 x 20 x 4 around the
 * origin) at 1280x720, 60 degrees: from a corner, from above, near the ground. Prints a markdown
 * table: wall time, the points read, the share of the file visited, the ratio to the baseline.
 *   bench_lod_view FILE_LOD.ply [POINTS]   (default 1000000) */
#include <pointnpr/lod.h>

#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

static double median3(double a, double b, double c)
{
    return a > b ? (b > c ? b : (a > c ? c : a)) : (a > c ? a : (b > c ? c : b));
}

/* One read: the view's (eye given) or the uniform one; its time, *r_kept and *r_visited. */
static double read_once(const char *path, const double *eye, const double *target, uint64_t points, size_t *r_kept,
                        double *r_visited)
{
    pnpr_cloud c = {0};
    pnpr_error err = {0};
    pnpr_lod_read_info info = {0};
    double t = now();
    pnpr_status st;
    if (eye) {
        pnpr_view_sample v;
        st = pnpr_view_sample_init(&v, eye, target, 60, 1280, 720);
        if (st == PNPR_OK) st = pnpr_lod_read_view(path, &v, points, NULL, &c, &info, &err);
    } else {
        st = pnpr_lod_read_sample(path, points, NULL, &c, &info.total, &info.ordered, &err);
        info.visited = 0;
    }
    t = now() - t;
    if (st != PNPR_OK || !info.ordered) {
        fprintf(stderr, "bench_lod_view: %s: %s\n", path, st != PNPR_OK ? err.message : "not ordered for drawing");
        exit(1);
    }
    *r_kept = c.count;
    *r_visited = info.total ? 100.0 * (double)info.visited / (double)info.total : 0;
    pnpr_cloud_free(&c);
    return t;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: bench_lod_view FILE_LOD.ply [POINTS]\n");
        return 2;
    }
    char *end = NULL;
    const long long asked = argc > 2 ? strtoll(argv[2], &end, 10) : 1000000;
    if (asked <= 0 || (end && *end)) {
        fprintf(stderr, "bench_lod_view: POINTS must be a positive whole number (got %s)\n", argv[2]);
        return 2;
    }
    const uint64_t points = (uint64_t)asked;
    pnpr_lod l = {0};
    pnpr_error err = {0};
    if (pnpr_lod_open(argv[1], &l, &err) != PNPR_OK) { /* before the table: a clean refusal */
        fprintf(stderr, "bench_lod_view: %s\n", err.message[0] ? err.message : "not a file ordered for drawing");
        return 1;
    }
    pnpr_lod_free(&l);
    static const struct { const char *name; double eye[3], target[3]; } views[] = {
        {"from a corner", {-9, -9, 1.5}, {0, 0, 0.5}},
        {"from above", {0, 0, 30}, {0, 0, 0}},
        {"near the ground", {0, 0, 2}, {3, 0, 0}},
    };
    printf("| view (1280x720, 60 degrees), %llu points asked | read, median of 3 | points | of the file visited | "
           "against the uniform sample |\n|---|---:|---:|---:|---:|\n", (unsigned long long)points);
    for (size_t k = 0; k < sizeof views / sizeof views[0]; k++) {
        double tv[3], tu[3], visited = 0, none;
        size_t kept = 0, ukept = 0;
        for (int r = 0; r < 3; r++) { /* taking turns */
            tu[r] = read_once(argv[1], NULL, NULL, points, &ukept, &none);
            tv[r] = read_once(argv[1], views[k].eye, views[k].target, points, &kept, &visited);
        }
        double v = median3(tv[0], tv[1], tv[2]), u = median3(tu[0], tu[1], tu[2]);
        printf("| %s | %.2f s | %zu | %.1f %% | %.2fx (uniform: %.2f s, %zu points) |\n", views[k].name, v, kept, visited,
               v / u, u, ukept);
    }
    return 0;
}
