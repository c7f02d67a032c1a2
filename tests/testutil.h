/* Small test harness shared by tests/test_*.c: checks that count failures, shape generators with
 * known answers, and a deterministic RNG (no global state: callers own the pnpr_test_rng). */
#ifndef PNPR_TESTUTIL_H
#define PNPR_TESTUTIL_H

#include <pointnpr/cloud.h>
#include <stdio.h>
#include <stdint.h>

extern int pnpr_test_failures; /* per test executable (each test is its own process) */

#define CHECK(cond) \
    do { if (!(cond)) { fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); pnpr_test_failures++; } } while (0)
#define CHECK_MSG(cond, ...) \
    do { if (!(cond)) { fprintf(stderr, "%s:%d: CHECK failed: %s: ", __FILE__, __LINE__, #cond); fprintf(stderr, __VA_ARGS__); fputc('\n', stderr); pnpr_test_failures++; } } while (0)
#define CHECK_STATUS(expr, expected) \
    do { pnpr_status s_ = (expr); if (s_ != (expected)) { fprintf(stderr, "%s:%d: %s returned %d (%s), expected %d (%s)\n", __FILE__, __LINE__, #expr, (int)s_, pnpr_status_string(s_), (int)(expected), pnpr_status_string(expected)); pnpr_test_failures++; } } while (0)
#define CHECK_NEAR(a, b, tol) \
    do { double a_ = (a), b_ = (b); if (!(a_ - b_ <= (tol) && b_ - a_ <= (tol))) { fprintf(stderr, "%s:%d: CHECK_NEAR failed: %s = %.9g, %s = %.9g, tol %g\n", __FILE__, __LINE__, #a, a_, #b, b_, (double)(tol)); pnpr_test_failures++; } } while (0)

/* Prints "name: N passed, M failed" style summary and returns the process exit code. */
int pnpr_test_finish(const char *name);

typedef struct pnpr_test_rng { uint64_t state; } pnpr_test_rng;
double pnpr_test_uniform(pnpr_test_rng *rng);            /* [0,1) */
double pnpr_test_normal(pnpr_test_rng *rng);             /* N(0,1) */

/* Shape generators: fill a cloud (freed first) with world coordinates offset by `offset`
 * (added in double, so large offsets are exact in src_xyz). Return PNPR_OK or an error. */
/* n points uniformly on the unit sphere (radius r) centred at offset. */
pnpr_status pnpr_test_sphere(pnpr_cloud *cloud, size_t n, double r, const double offset[3], uint64_t seed);
/* Axis-aligned cube [0,side]^3 sampled on a regular grid of spacing h on each face (no duplicates
 * on shared edges), plus optional Gaussian noise of sigma (world units) along all axes. */
pnpr_status pnpr_test_cube(pnpr_cloud *cloud, double side, double h, double noise_sigma,
                           const double offset[3], uint64_t seed);
/* Plane z=0, grid of nx*ny points spacing h. */
pnpr_status pnpr_test_plane(pnpr_cloud *cloud, size_t nx, size_t ny, double h, const double offset[3]);

/* Seconds of the monotonic clock (the benchmarks' timer). */
double pnpr_test_seconds(void);

/* Number of temporaries of the output `name` (".<name>.<hex>.part", pointnpr/output.h; "" = of
 * any output) in the folder `dir`; -1 if the folder cannot be read. */
int pnpr_test_temporaries(const char *dir, const char *name);

#endif
