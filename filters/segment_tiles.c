/* Connected components of a cloud larger than memory (pointnpr/tiles.h, docs/tiles.md): the
 * automatic distance of the whole file, and the merge of the tiles' components.
 *
 * Components split into tiles exactly: two points closer than the distance d are both read by
 * the tile whose core holds either of them when its halo is at least d (pnpr_tile_components_halo),
 * so every edge of the whole cloud is an edge of some tile, and no tile has an edge the whole cloud
 * lacks (the same floats: the plan's origin). A tile's components joined over the points that
 * several tiles read (union-find over the tiles' own labels) are the whole cloud's.
 *
 * The automatic distance is a median over a stride sample of the file (pnpr_segment_median_spacing).
 * Each sample point's term needs only the points near it: a pass reads the sample and the points
 * within a reach r of a sample point, and a term is certain when it is at most r. The terms left
 * uncertain are larger than r, so the median is known once fewer than half of them are uncertain;
 * otherwise the reach grows fourfold for those. */
#include <pointnpr/knn.h>
#include <pointnpr/props.h>
#include <pointnpr/segment.h>
#include <pointnpr/tiles.h>

#include "../core/internal.h"
#include "../core/vec3.h"
#include "../io/tile_merge.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define NONE 0xFFFFFFFFu
#define REACH_ROUNDS 24                 /* fourfold each: from the spacing past any cloud's size */
#define REACH_POINTS_MAX (64u << 20)    /* the points a round may read: beyond, give the distance */
#define REACH_BYTES 48                  /* a point read in a round, beyond its record: the sample
                                         * mark, the kd-tree and the float offsets */

/* The grid's longer side (world units). */
static double grid_side(const pnpr_tile_grid *grid)
{
    return fmax(grid->cell[0] * grid->cells[0], grid->cell[1] * grid->cells[1]);
}

double pnpr_tile_components_halo(const pnpr_tile_grid *grid, float distance)
{
    /* the floats are offsets from the origin: a margin for their rounding */
    return 1.01 * (double)distance + 1e-6 * grid_side(grid);
}

/* ---- the automatic distance ------------------------------------------------------------------ */

typedef struct reach_cell {
    int64_t key[3];
    uint32_t first; /* the first sample in the cell (next[] links the others), NONE: empty slot */
} reach_cell;

typedef struct reach_pass {
    uint64_t step;          /* every step-th point is a sample */
    size_t ns;              /* samples */
    double *pos;            /* their coordinates as stored (pass 1) */
    uint8_t *open;          /* term not yet certain */
    double reach, margin;
    reach_cell *cells;      /* a hash of the open samples' cells (side reach), 2^bits slots */
    uint32_t *next;
    unsigned bits;
    uint32_t *kept_sample;  /* per point read: its sample, or NONE */
    size_t kept, cap;
    size_t collected;       /* samples the first pass met */
    size_t max_kept;        /* the points a round may read */
    int failed;
} reach_pass;

static int sample_of(const reach_pass *r, uint64_t index)
{
    return index % r->step == 0 && index / r->step < r->ns;
}

static int collect_sample(void *user, uint64_t index, const double p[3])
{
    reach_pass *r = user;
    if (sample_of(r, index)) {
        memcpy(r->pos + 3 * (index / r->step), p, 3 * sizeof(double));
        r->collected++;
    }
    return 0;
}

static int cell_key(const reach_pass *r, const double p[3], int64_t k[3])
{
    for (int a = 0; a < 3; a++) {
        double c = floor(p[a] / (r->reach + r->margin)); /* a box of that half-side spans 3 cells */
        if (!(fabs(c) < 4e18)) return 0;
        k[a] = (int64_t)c;
    }
    return 1;
}

static size_t cell_slot(const reach_pass *r, const int64_t k[3])
{
    uint64_t h = (uint64_t)k[0] * 0x9E3779B97F4A7C15ull ^ (uint64_t)k[1] * 0xC2B2AE3D27D4EB4Full ^
                 (uint64_t)k[2] * 0x165667B19E3779F9ull;
    size_t mask = ((size_t)1 << r->bits) - 1, s = (size_t)(h >> 20) & mask;
    while (r->cells[s].first != NONE && memcmp(r->cells[s].key, k, sizeof r->cells[s].key)) s = (s + 1) & mask;
    return s;
}

/* The open samples' cells; 0 when out of memory. */
static int build_cells(reach_pass *r)
{
    free(r->cells);
    for (r->bits = 4; ((size_t)1 << r->bits) < 2 * r->ns + 2; r->bits++) {}
    r->cells = malloc(((size_t)1 << r->bits) * sizeof *r->cells);
    if (!r->cells) return 0;
    for (size_t s = 0; s < ((size_t)1 << r->bits); s++) r->cells[s].first = NONE;
    for (size_t i = 0; i < r->ns; i++) {
        int64_t k[3];
        if (!r->open[i] || !cell_key(r, r->pos + 3 * i, k)) continue;
        size_t s = cell_slot(r, k);
        memcpy(r->cells[s].key, k, sizeof k);
        r->next[i] = r->cells[s].first;
        r->cells[s].first = (uint32_t)i;
    }
    return 1;
}

/* Whether p lies within the reach of an open sample (a box of half-side reach + margin). */
static int near_open_sample(const reach_pass *r, const double p[3])
{
    int64_t k[3];
    if (!cell_key(r, p, k)) return 0;
    const double h = r->reach + r->margin;
    for (int dz = -1; dz <= 1; dz++)
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                int64_t q[3] = {k[0] + dx, k[1] + dy, k[2] + dz};
                for (uint32_t s = r->cells[cell_slot(r, q)].first; s != NONE; s = r->next[s]) {
                    const double *c = r->pos + 3 * (size_t)s;
                    if (fabs(p[0] - c[0]) <= h && fabs(p[1] - c[1]) <= h && fabs(p[2] - c[2]) <= h) return 1;
                }
            }
    return 0;
}

static int keep_near(void *user, uint64_t index, const double p[3])
{
    reach_pass *r = user;
    int sample = sample_of(r, index) && r->open[index / r->step];
    if (!sample && !near_open_sample(r, p)) return 0;
    if (r->kept == r->cap) {
        size_t cap = r->cap ? 2 * r->cap : 4096;
        if (cap > r->max_kept) cap = r->max_kept;
        uint32_t *k = cap > r->cap ? realloc(r->kept_sample, cap * sizeof *k) : NULL;
        if (!k) { r->failed = 1; return 0; }
        r->kept_sample = k;
        r->cap = cap;
    }
    r->kept_sample[r->kept++] = sample ? (uint32_t)(index / r->step) : NONE;
    return 1;
}

/* One round: reads the open samples and the points within their reach, and settles the terms
 * that reach certifies (term[] and open[]); *r_none counts the samples that have no term. */
static pnpr_status reach_round(reach_pass *r, const char *path, const pnpr_tile_plan *plan, float *term,
                               size_t *r_none, pnpr_error *err)
{
    if (!build_cells(r)) return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s: components: out of memory", path);
    r->kept = 0;
    pnpr_read_options ro = {0};
    ro.format = PNPR_FORMAT_PLY;
    ro.keep = keep_near;
    ro.keep_user = r;
    ro.origin = plan->grid.origin;
    pnpr_cloud c = {0};
    pnpr_status st = pnpr_read_file(path, &ro, &c, err);
    if (st == PNPR_OK && (r->failed || c.count != r->kept))
        st = pnpr_error_set(err, r->failed ? PNPR_ERR_OUT_OF_MEMORY : PNPR_ERR_IO,
                            "%s: components: %s", path,
                            r->failed ? "the automatic distance needs more points near its sample than the memory "
                                        "limit lets it read: give --radius"
                                      : "the file changed");
    pnpr_kdtree *tree = NULL;
    if (st == PNPR_OK) st = pnpr_kdtree_build(c.xyz, c.count, 0, &tree);
    for (size_t i = 0; st == PNPR_OK && i < c.count; i++) {
        uint32_t s = r->kept_sample[i];
        if (s == NONE) continue;
        const float *p = c.xyz + 3 * i;
        float eighth, nn = pnpr_finite3f(p) ? pnpr_segment_nn_distinct(tree, p, &eighth) : 0;
        /* every point within reach was read: a term (or the 8 coincident points) within it is the
         * whole file's; so is any when the whole file was read */
        if (!pnpr_finite3f(p) || c.count == plan->points || (nn > 0 ? nn : eighth) <= r->reach) {
            r->open[s] = 0;
            term[s] = nn;
            *r_none += !(nn > 0);
        }
    }
    if (st != PNPR_OK && !err->message[0]) pnpr_error_set(err, st, "%s: components: %s", path, pnpr_status_string(st));
    pnpr_kdtree_free(tree);
    pnpr_cloud_free(&c);
    return st;
}

/* The margin of a reach: float offsets round by up to 2^-23 of their size, so a box of half-side
 * reach + margin in doubles holds every point within reach in floats. */
static double reach_margin(double reach, double offset)
{
    return 0.01 * reach + 1e-6 * (offset + reach);
}

pnpr_status pnpr_tile_components_distance(const char *path, const pnpr_tile_plan *plan,
                                          const pnpr_components_options *opts, size_t memory_limit, float *r_distance,
                                          pnpr_error *err)
{
    pnpr_error local = {0};
    if (!err) err = &local;
    err->message[0] = '\0';
    if (!path || !plan || !r_distance) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "components: NULL argument");
    *r_distance = 0;
    if (opts && opts->distance > 0) {
        *r_distance = pnpr_components_distance(opts, 0);
        return PNPR_OK;
    }
    reach_pass r;
    memset(&r, 0, sizeof r);
    r.max_kept = memory_limit ? memory_limit / (plan->record_bytes + REACH_BYTES) : REACH_POINTS_MAX;
    if (r.max_kept > REACH_POINTS_MAX) r.max_kept = REACH_POINTS_MAX;
    r.step = plan->points / PNPR_SEGMENT_SPACING_SAMPLE + 1;
    r.ns = plan->points ? (size_t)((plan->points - 1) / r.step + 1) : 0;
    r.pos = malloc((3 * r.ns + 1) * sizeof *r.pos);
    r.open = malloc(r.ns + 1);
    r.next = malloc((r.ns + 1) * sizeof *r.next);
    float *term = malloc((r.ns + 1) * sizeof *term), *done = malloc((r.ns + 1) * sizeof *done);
    pnpr_status st = r.pos && r.open && r.next && term && done ? PNPR_OK : PNPR_ERR_OUT_OF_MEMORY;
    if (st != PNPR_OK) pnpr_error_set(err, st, "%s: components: out of memory", path);
    if (st == PNPR_OK) {
        for (size_t i = 0; i < 3 * r.ns; i++) r.pos[i] = NAN; /* a sample the pass does not reach */
        memset(r.open, 1, r.ns + 1);
        pnpr_read_options ro = {0};
        ro.format = PNPR_FORMAT_PLY;
        ro.keep = collect_sample;
        ro.keep_user = &r;
        pnpr_cloud none = {0};
        st = pnpr_read_file(path, &ro, &none, err);
        pnpr_cloud_free(&none);
        if (st == PNPR_OK && r.collected != r.ns)
            st = pnpr_error_set(err, PNPR_ERR_IO, "%s: components: the file changed since it was planned", path);
    }
    double offset = 0; /* the largest float offset of a sample */
    for (size_t i = 0; st == PNPR_OK && i < 3 * r.ns; i++)
        if (isfinite(r.pos[i])) offset = fmax(offset, fabs(r.pos[i] - plan->grid.origin[i % 3]));
    double side = grid_side(&plan->grid);
    r.reach = plan->spacing > 0 ? plan->spacing : side > 0 ? side / 1e6 : 1;
    r.margin = reach_margin(r.reach, offset);
    size_t none = 0, open = r.ns;
    float median = 0;
    for (int round = 0; st == PNPR_OK && open; round++) {
        if (round == REACH_ROUNDS) {
            st = pnpr_error_set(err, PNPR_ERR_NUMERIC, "%s: components: no automatic distance found: give --radius", path);
            break;
        }
        st = reach_round(&r, path, plan, term, &none, err);
        open = 0;
        size_t m = 0, terms = r.ns - none;
        for (size_t i = 0; i < r.ns; i++) {
            open += r.open[i];
            if (!r.open[i] && term[i] > 0) done[m++] = term[i]; /* certain: at most reach; the open ones beyond */
        }
        if (st == PNPR_OK && (terms == 0 || terms / 2 < m)) {
            median = terms ? pnpr_select_float(done, m, terms / 2) : 0;
            break;
        }
        r.reach *= 4; /* the median is among the open terms: reach further for them */
        r.margin = reach_margin(r.reach, offset);
    }
    if (st == PNPR_OK) *r_distance = pnpr_components_distance(opts, median);
    free(r.pos); free(r.open); free(r.next); free(r.cells); free(r.kept_sample); free(term); free(done);
    return st;
}

/* ---- a tile's job ------------------------------------------------------------------------------ */

pnpr_status pnpr_tile_components_job(pnpr_cloud *tile, const uint8_t *core, float distance, int threads,
                                     uint32_t *r_components)
{
    if (!tile || (tile->count && !core) || !(distance > 0)) return PNPR_ERR_INVALID_ARGUMENT;
    pnpr_status st = pnpr_cloud_add_property(tile, PNPR_PROP_TILE_CORE, PNPR_TYPE_UINT8, NULL);
    if (st == PNPR_OK) st = pnpr_cloud_add_property(tile, PNPR_PROP_TILE_COMPONENT, PNPR_TYPE_UINT32, NULL);
    if (st != PNPR_OK) return st;
    /* found after both are added: adding one moves the others */
    pnpr_property *tc = pnpr_cloud_find_property(tile, PNPR_PROP_TILE_CORE);
    pnpr_property *tl = pnpr_cloud_find_property(tile, PNPR_PROP_TILE_COMPONENT);
    if (tile->count) memcpy(tc->data, core, tile->count);
    pnpr_components_options o = {0};
    o.distance = distance;
    o.min_size = 1;
    o.threads = threads;
    pnpr_segment_info info;
    st = pnpr_segment_components(tile->xyz, tile->count, &o, tl->data, &info);
    if (st == PNPR_OK && r_components) *r_components = info.segment_count;
    return st;
}

/* ---- the merge ------------------------------------------------------------------------------- */

#define INVALID 0xFFFFFFFEu /* owner of a point with a non-finite coordinate */

typedef struct seg_merge {
    uint64_t points;
    uint32_t *owner;   /* per source index: the node of its core tile's component, INVALID, NONE */
    uint32_t *parent;  /* per node (a tile's own component): union-find */
    uint32_t *first;   /* per node: its least source index among core points (NONE: none) */
    double *sum;       /* per node: red, green, blue and count of its core points */
    size_t nodes, cap;
    size_t *base;      /* per tile: its first node */
    uint32_t *tile_nodes; /* per tile: its nodes (its own components) */
    uint32_t *label;   /* per node, once numbered: the final label of its root */
    uint32_t valid;    /* the components; the points with a non-finite coordinate get label `valid` */
    double invalid[4];
    float *mean;       /* 3 per label */
} seg_merge;

static uint32_t uf_find(uint32_t *parent, uint32_t x)
{
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
}

/* A tile's nodes: one per local label (labels of points with finite coordinates). */
static pnpr_status add_nodes(seg_merge *m, size_t tile, const pnpr_cloud *c, const uint32_t *local)
{
    uint64_t n = 0;
    for (size_t i = 0; i < c->count; i++)
        if (pnpr_finite3f(c->xyz + 3 * i) && local[i] >= n) n = (uint64_t)local[i] + 1;
    if (n > c->count) return PNPR_ERR_FORMAT; /* a tile's own labels are fewer than its points */
    if (m->nodes + n > NONE - 2) return PNPR_ERR_UNSUPPORTED;
    if (m->nodes + n > m->cap) {
        size_t cap = m->cap ? m->cap : 4096;
        while (cap < m->nodes + n) cap *= 2;
        uint32_t *p = realloc(m->parent, cap * sizeof *p);
        if (p) m->parent = p;
        uint32_t *f = p ? realloc(m->first, cap * sizeof *f) : NULL;
        if (f) m->first = f;
        double *s = f ? realloc(m->sum, 4 * cap * sizeof *s) : NULL;
        if (!s) return PNPR_ERR_OUT_OF_MEMORY;
        m->sum = s;
        m->cap = cap;
    }
    for (size_t k = m->nodes; k < m->nodes + n; k++) {
        m->parent[k] = (uint32_t)k;
        m->first[k] = NONE;
        memset(m->sum + 4 * k, 0, 4 * sizeof *m->sum);
    }
    m->base[tile] = m->nodes;
    m->tile_nodes[tile] = (uint32_t)n;
    m->nodes += n;
    return PNPR_OK;
}

/* Reads a tile's result: its source indices, core flags and own labels (c owns them). */
static pnpr_status read_tile(const char *path, pnpr_cloud *c, const uint32_t **r_idx, const uint8_t **r_core,
                             const uint32_t **r_local, pnpr_error *err)
{
    pnpr_status st = pnpr_read_file(path, NULL, c, err);
    if (st != PNPR_OK) return st;
    const pnpr_property *si = pnpr_cloud_find_property(c, PNPR_PROP_SOURCE_INDEX);
    const pnpr_property *tc = pnpr_cloud_find_property(c, PNPR_PROP_TILE_CORE);
    const pnpr_property *tl = pnpr_cloud_find_property(c, PNPR_PROP_TILE_COMPONENT);
    if (!si || si->type != PNPR_TYPE_UINT32 || !tc || tc->type != PNPR_TYPE_UINT8 || !tl || tl->type != PNPR_TYPE_UINT32)
        return pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: not a tile of `pointnpr segment` (it needs %s, %s and %s)", path,
                              PNPR_PROP_SOURCE_INDEX, PNPR_PROP_TILE_CORE, PNPR_PROP_TILE_COMPONENT);
    *r_idx = si->data;
    *r_core = tc->data;
    *r_local = tl->data;
    return PNPR_OK;
}

/* A finite point's node, or NONE when its label lies beyond the tile's components (a tile file
 * changed since pass 1). */
static uint32_t node_of(const seg_merge *m, size_t tile, uint32_t local)
{
    return local < m->tile_nodes[tile] ? (uint32_t)m->base[tile] + local : NONE;
}

/* Pass 1 (halo 0): every core point's owner, each node's first index and colour sums. Pass 2
 * (halo 1): the halo points join their nodes to their owners'. */
static pnpr_status seg_pass(seg_merge *m, const char *path, size_t tile, int halo, pnpr_error *err)
{
    pnpr_cloud c = {0};
    const uint32_t *idx = NULL, *local = NULL;
    const uint8_t *core = NULL;
    pnpr_status st = read_tile(path, &c, &idx, &core, &local, err);
    if (st == PNPR_OK && !halo && (st = add_nodes(m, tile, &c, local)) != PNPR_OK)
        pnpr_error_set(err, st, "%s: merge: %s", path,
                       st == PNPR_ERR_FORMAT        ? "labels beyond its points: not a tile of `pointnpr segment`"
                       : st == PNPR_ERR_UNSUPPORTED ? "too many components"
                                                    : "out of memory");
    for (size_t i = 0; st == PNPR_OK && i < c.count; i++) {
        uint32_t s = idx[i];
        if (s >= m->points) {
            st = pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: point %zu: source index %u beyond the file's %llu points", path,
                                i, s, (unsigned long long)m->points);
            break;
        }
        int valid = pnpr_finite3f(c.xyz + 3 * i);
        uint32_t node = valid ? node_of(m, tile, local[i]) : INVALID;
        if (node == NONE) {
            st = pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: point %zu: a component beyond the tile's (it changed?)", path, i);
            break;
        }
        if (halo && !core[i] && (m->owner[s] == NONE || (m->owner[s] == INVALID) != !valid)) {
            st = pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: halo point %zu (source index %u) %s", path, i, s,
                                m->owner[s] == NONE ? "is in no tile's core (a tile missing?)" : "differs from its core tile's");
            break;
        }
        if (halo && !core[i] && valid) {
            uint32_t a = uf_find(m->parent, node), b = uf_find(m->parent, m->owner[s]);
            if (a < b) m->parent[b] = a; else m->parent[a] = b;
        }
        if (halo || !core[i]) continue;
        if (m->owner[s] != NONE) {
            st = pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: core point %zu: source index %u comes twice (tiles overlap)",
                                path, i, s);
            break;
        }
        m->owner[s] = node;
        double *sum = valid ? m->sum + 4 * (size_t)node : m->invalid;
        if (c.rgb) for (int k = 0; k < 3; k++) sum[k] += c.rgb[3 * i + k];
        sum[3] += 1;
        if (valid && s < m->first[node]) m->first[node] = s;
    }
    pnpr_cloud_free(&c);
    return st;
}

/* The components (roots) numbered by their first point in file order, as pnpr_segment_finish
 * numbers them in memory; their mean colours as pnpr_segment_mean_colors gives them. */
static pnpr_status seg_number(seg_merge *m)
{
    for (size_t k = 0; k < m->nodes; k++) {
        uint32_t r = uf_find(m->parent, (uint32_t)k);
        if (r == k) continue;
        if (m->first[k] < m->first[r]) m->first[r] = m->first[k];
        for (int j = 0; j < 4; j++) m->sum[4 * (size_t)r + j] += m->sum[4 * k + j];
    }
    size_t roots = 0;
    for (size_t k = 0; k < m->nodes; k++) roots += m->parent[k] == k && m->first[k] != NONE;
    uint64_t *key = malloc((roots + 1) * sizeof *key);
    m->label = calloc(m->nodes + 1, sizeof *m->label);
    m->mean = malloc(3 * (roots + 1) * sizeof *m->mean);
    if (!key || !m->label || !m->mean) { free(key); return PNPR_ERR_OUT_OF_MEMORY; }
    size_t n = 0;
    for (size_t k = 0; k < m->nodes; k++)
        if (m->parent[k] == k && m->first[k] != NONE) key[n++] = (uint64_t)m->first[k] << 32 | k;
    qsort(key, n, sizeof *key, pnpr_cmp_u64);
    for (size_t l = 0; l < n; l++) {
        uint32_t r = (uint32_t)(key[l] & 0xFFFFFFFFu);
        m->label[r] = (uint32_t)l;
        const double *s = m->sum + 4 * (size_t)r;
        for (int c = 0; c < 3; c++) m->mean[3 * l + c] = (float)(s[c] / s[3]);
    }
    m->valid = (uint32_t)n;
    for (int c = 0; c < 3; c++) m->mean[3 * n + c] = m->invalid[3] > 0 ? (float)(m->invalid[c] / m->invalid[3]) : 0.0f;
    for (size_t k = 0; k < m->nodes; k++) m->label[k] = m->label[uf_find(m->parent, (uint32_t)k)];
    free(key);
    return PNPR_OK;
}

/* The merge's hook: a tile's final labels, and their colours when it has colours. */
static pnpr_status seg_relabel(void *user, size_t tile, const char *path, pnpr_cloud *c, const uint32_t *idx,
                               const uint8_t *core, pnpr_error *err)
{
    (void)idx; (void)core;
    seg_merge *m = user;
    pnpr_property *tl = pnpr_cloud_find_property(c, PNPR_PROP_TILE_COMPONENT);
    if (!tl || tl->type != PNPR_TYPE_UINT32)
        return pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: merge: the tile changed since it was first read", path);
    pnpr_status st = pnpr_cloud_alloc_labels(c);
    const uint32_t *local = tl->data;
    for (size_t i = 0; st == PNPR_OK && i < c->count; i++) {
        uint32_t node = pnpr_finite3f(c->xyz + 3 * i) ? node_of(m, tile, local[i]) : INVALID;
        if (node == NONE)
            return pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: merge: point %zu: a component beyond the tile's (it changed?)",
                                  path, i);
        c->label[i] = node == INVALID ? m->valid : m->label[node];
    }
    if (st == PNPR_OK) st = pnpr_cloud_remove_property(c, PNPR_PROP_TILE_COMPONENT);
    return st == PNPR_OK && c->rgb ? pnpr_segment_add_colors(c, m->mean, m->valid + (m->invalid[3] > 0)) : st;
}

pnpr_status pnpr_tile_merge_segments(const char *const *paths, size_t count, uint64_t points, const char *out,
                                     const pnpr_progress *progress, uint32_t *r_segment_count, pnpr_error *err)
{
    pnpr_error local = {0};
    if (!err) err = &local;
    if (r_segment_count) *r_segment_count = 0;
    if ((!paths && count) || !out) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "merge: NULL argument");
    if (points >= UINT32_MAX) return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED, "%s: merge: tiles take fewer than 2^32 points", out);
    seg_merge m;
    memset(&m, 0, sizeof m);
    m.points = points;
    m.owner = malloc((points + 1) * sizeof *m.owner);
    m.base = calloc(count + 1, sizeof *m.base);
    m.tile_nodes = calloc(count + 1, sizeof *m.tile_nodes);
    pnpr_status st = m.owner && m.base && m.tile_nodes ? PNPR_OK : pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s: merge: out of memory", out);
    for (uint64_t i = 0; st == PNPR_OK && i < points; i++) m.owner[i] = NONE;
    for (int halo = 0; halo < 2; halo++)
        for (size_t t = 0; st == PNPR_OK && t < count; t++) {
            st = seg_pass(&m, paths[t], t, halo, err);
            if (st == PNPR_OK && pnpr_progress_report(progress, "components", (double)(halo * count + t + 1) / (2.0 * count)))
                st = pnpr_error_set(err, PNPR_ERR_CANCELLED, "%s: merge cancelled", out);
        }
    for (uint64_t i = 0; st == PNPR_OK && i < points; i++)
        if (m.owner[i] == NONE)
            st = pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: merge: point %llu of %llu is in no tile (a tile missing?)", out,
                                (unsigned long long)i, (unsigned long long)points);
    free(m.owner);
    if (st == PNPR_OK && (st = seg_number(&m)) != PNPR_OK) pnpr_error_set(err, st, "%s: merge: out of memory", out);
    if (st == PNPR_OK) st = pnpr_tile_merge_with(paths, count, points, 0, out, progress, seg_relabel, &m, err);
    if (st == PNPR_OK && r_segment_count) *r_segment_count = m.valid + (m.invalid[3] > 0);
    free(m.parent); free(m.first); free(m.sum); free(m.base); free(m.tile_nodes); free(m.label); free(m.mean);
    return st;
}
