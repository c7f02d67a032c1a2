#include "testutil.h"

#include <dirent.h>
#include <string.h>

#include <math.h>
#include <stdlib.h>
#include <time.h>

int pnpr_test_failures = 0;

int pnpr_test_finish(const char *name)
{
    if (pnpr_test_failures) {
        fprintf(stderr, "%s: %d check(s) failed\n", name, pnpr_test_failures);
        return 1;
    }
    fprintf(stderr, "%s: all checks passed\n", name);
    return 0;
}

double pnpr_test_uniform(pnpr_test_rng *rng)
{
    /* splitmix64 */
    uint64_t z = (rng->state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

double pnpr_test_normal(pnpr_test_rng *rng)
{
    double u1 = pnpr_test_uniform(rng), u2 = pnpr_test_uniform(rng);
    if (u1 < 1e-300) u1 = 1e-300;
    return sqrt(-2.0 * log(u1)) * cos(6.283185307179586 * u2);
}

/* Stores world coordinates (already offset) into a fresh cloud with exact src_xyz. */
static pnpr_status finish_world(pnpr_cloud *cloud, double *world, size_t n)
{
    pnpr_status st = pnpr_cloud_alloc(cloud, n);
    if (st == PNPR_OK) st = pnpr_cloud_set_world(cloud, world);
    if (st == PNPR_OK) {
        cloud->src_xyz = world; /* ownership moves to the cloud */
        cloud->src_coord_type = PNPR_TYPE_FLOAT64;
        return PNPR_OK;
    }
    free(world);
    return st;
}

pnpr_status pnpr_test_sphere(pnpr_cloud *cloud, size_t n, double r, const double offset[3], uint64_t seed)
{
    static const double zero[3] = {0, 0, 0};
    if (!offset) offset = zero;
    double *w = malloc(3 * (n ? n : 1) * sizeof(double));
    if (!w) return PNPR_ERR_OUT_OF_MEMORY;
    pnpr_test_rng rng = {seed};
    for (size_t i = 0; i < n; i++) {
        double v[3], len;
        do {
            for (int a = 0; a < 3; a++) v[a] = pnpr_test_normal(&rng);
            len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        } while (len < 1e-9);
        for (int a = 0; a < 3; a++) w[3 * i + a] = offset[a] + r * v[a] / len;
    }
    return finish_world(cloud, w, n);
}

pnpr_status pnpr_test_cube(pnpr_cloud *cloud, double side, double h, double noise_sigma,
                           const double offset[3], uint64_t seed)
{
    static const double zero[3] = {0, 0, 0};
    if (!offset) offset = zero;
    if (!(side > 0) || !(h > 0)) return PNPR_ERR_INVALID_ARGUMENT;
    long m = (long)floor(side / h + 0.5); /* grid cells per edge */
    if (m < 1) m = 1;
    size_t cap = (size_t)(m + 1) * (size_t)(m + 1) * (size_t)(m + 1);
    double *w = malloc(3 * cap * sizeof(double));
    if (!w) return PNPR_ERR_OUT_OF_MEMORY;
    pnpr_test_rng rng = {seed};
    size_t n = 0;
    const double step = side / (double)m;
    for (long i = 0; i <= m; i++)
        for (long j = 0; j <= m; j++)
            for (long k = 0; k <= m; k++) {
                if (i != 0 && i != m && j != 0 && j != m && k != 0 && k != m) continue; /* interior */
                double p[3] = {i * step, j * step, k * step};
                for (int a = 0; a < 3; a++) {
                    double noise = noise_sigma > 0 ? noise_sigma * pnpr_test_normal(&rng) : 0.0;
                    w[3 * n + a] = offset[a] + p[a] + noise;
                }
                n++;
            }
    return finish_world(cloud, w, n);
}

pnpr_status pnpr_test_plane(pnpr_cloud *cloud, size_t nx, size_t ny, double h, const double offset[3])
{
    static const double zero[3] = {0, 0, 0};
    if (!offset) offset = zero;
    size_t n = nx * ny;
    double *w = malloc(3 * (n ? n : 1) * sizeof(double));
    if (!w) return PNPR_ERR_OUT_OF_MEMORY;
    for (size_t j = 0; j < ny; j++)
        for (size_t i = 0; i < nx; i++) {
            size_t q = j * nx + i;
            w[3 * q + 0] = offset[0] + (double)i * h;
            w[3 * q + 1] = offset[1] + (double)j * h;
            w[3 * q + 2] = offset[2];
        }
    return finish_world(cloud, w, n);
}

int pnpr_test_temporaries(const char *dir, const char *name)
{
    DIR *d = opendir(dir);
    if (!d) return -1;
    int n = 0;
    size_t nl = strlen(name);
    struct dirent *e;
    while ((e = readdir(d))) {
        size_t len = strlen(e->d_name);
        int named = nl == 0 || (!strncmp(e->d_name + 1, name, nl) && e->d_name[nl + 1] == '.');
        n += len > nl + 7 && e->d_name[0] == '.' && named && !strcmp(e->d_name + len - 5, ".part");
    }
    closedir(d);
    return n;
}

double pnpr_test_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}
