/* pointnpr — memory.h: what a command will hold, estimated before the work, and what the machine
 * has (GL-free, core library: core/memory.c).
 *
 * A 50M-point `render --style sketchy` needs about 17 GB: on a smaller machine it used to run for
 * minutes and then be killed. The commands now estimate the peak of what is left to do once the
 * cloud is read (feature stage, segments, the renderer's upload, the frame) from per-point figures
 * measured on real and generated clouds (docs/benchmarks.md, "Memory"), and refuse before the
 * work when it exceeds what is available or a limit the user gives, with the figures. The
 * estimate is a model, not a bound: it was within 20% of the measured peaks it was fitted to. */
#ifndef POINTNPR_MEMORY_H
#define POINTNPR_MEMORY_H

#include "cloud.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What is left to do on a cloud of `points` (zero = nothing). */
typedef struct pnpr_memory_plan {
    size_t points;
    uint32_t features_k;  /* the feature stage runs with this k (0: it does not run) */
    int normals_stored;   /* the cloud has no normals yet and the feature stage adds them */
    int segments;         /* the JSEG segmentation runs */
    uint32_t styles;      /* bits 1u << pnpr_style the renderer uploads for (0: no renderer) */
    int width, height;    /* the image in pixels, with a renderer */
    size_t drawn;         /* the most points a frame draws (the screen-space budget); 0 = all */
} pnpr_memory_plan;

/* The estimate, in bytes beyond what the process holds when it is made (the cloud as read); each
 * part saturates at SIZE_MAX instead of overflowing. */
typedef struct pnpr_memory_estimate {
    size_t stages;   /* the peak of the feature stage / segmentation while it runs */
    size_t kept;     /* what they add to the cloud (features, normals, labels), kept after */
    size_t render;   /* the renderer: GL context, upload, frame */
    size_t total;    /* kept + max(stages, render): the peak */
} pnpr_memory_estimate;

void pnpr_memory_estimate_plan(const pnpr_memory_plan *plan, pnpr_memory_estimate *r_estimate);

/* This process's resident memory now (Linux: /proc/self/statm), 0 when unknown. */
size_t pnpr_memory_resident(void);
/* Memory the process may still take: MemAvailable (/proc/meminfo), lowered to what the cgroup's
 * memory.max leaves (cgroup v2); SIZE_MAX when neither is known. */
size_t pnpr_memory_available(void);

/* Whether `need` more bytes fit: under `limit` - resident when limit > 0 (the user's limit on the
 * whole process), else under pnpr_memory_available(). PNPR_ERR_OUT_OF_MEMORY with a message
 * naming `what`, both figures (pnpr_memory_text) and where the second comes from, otherwise. */
PNPR_NODISCARD pnpr_status pnpr_memory_check(size_t need, size_t limit, const char *what, pnpr_error *err);

/* "1.5 GiB", "730 MiB", "12 KiB", "17 B" into buf (cap > 0, NUL-terminated); returns buf. */
const char *pnpr_memory_text(size_t bytes, char *buf, size_t cap);
/* Parses a size: a number with an optional binary suffix K, M, G, T (KiB..TiB; a trailing 'B' or
 * "iB" allowed), at least 1 byte, at most 2^62. 0 and sets *r on success, -1 otherwise. */
int pnpr_memory_parse(const char *text, size_t *r_bytes);

#ifdef __cplusplus
}
#endif
#endif
