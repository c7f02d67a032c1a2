/* Profile lines (PointWorks section 5.2 and figure 6): directional points -> neighbourhood graph ->
 * shift -> merge -> minimum spanning forest -> spur pruning -> chains -> corners -> B-splines.
 * The formulas and default parameters (h = spacing):
 *  - spacing h: median distance from a directional point to its nearest distinct directional
 *    point (a sample of up to 20 000 points), unless given;
 *  - shift (noise reduction, figure 6c): each point moves half-way towards the mean of the
 *    directional points within 2h, but only across its feature direction d (the component of the
 *    move along d is removed, so lines do not shrink); 4 iterations collapse a feature band a few
 *    points wide onto its axis;
 *  - merge: points within merge_tol (h) of a not-yet-merged point form one node at their mean
 *    position, with their sign-aligned mean direction;
 *  - graph edges: each node to its 8 nearest nodes within connect_radius R (3h); an edge e between
 *    nodes a, b weighs |e| * (1 + beta * (1 - (|e^.d_a| + |e^.d_b|) / 2)), beta = 4: an edge along
 *    both directions costs its length, one across them up to 5x. Edges that run across both
 *    directions (|e^.d| < 0.5, i.e. > 60 degrees, at both ends) are not added: they would join
 *    parallel features;
 *  - minimum spanning forest: Kruskal, edges sorted by weight, union-find: O(E log E);
 *  - spurs: a leaf branch shorter than min_length (5h) that ends at a junction is removed;
 *  - chains: maximal paths between nodes whose degree is not 2; isolated chains (two leaf ends)
 *    shorter than min_length are dropped; an isolated chain whose ends are within R of each other
 *    and which is at least 3R long is closed (a ring the spanning tree had to cut);
 *  - corners: PointWorks classifies the points near a corner as non-directional, so lines stop
 *    short of corners. Two chain ends whose end tangents (over the last 3h) point at a common point
 *    (the rays pass within 2h of each other, each at most 10h ahead, at an angle over 30 degrees)
 *    vote for that point; votes within 2h of each other are one corner (their mean) and every
 *    end that voted for it is extended to it. Two ends facing each other across a gap (opposite
 *    tangents within 25 degrees, each end ahead of the other, at most 12h apart: a stretch of
 *    edge where noise hid the directional points) vote for the gap's midpoint the same way;
 *  - each chain is fitted and sampled by lines_spline.c. */
#include "lines_internal.h"

#include <pointnpr/features.h>
#include <pointnpr/knn.h>

#include "../core/internal.h"
#include "kdtree_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define RADIUS_CAP PNPR_LINES_NEIGHBOURS_MAX

int pnpr_lines_buf_push(pnpr_lines_buf *b, const double p[3])
{
    if (!b->ok) return 0;
    if (b->n == b->cap) {
        size_t cap = b->cap ? 2 * b->cap : 256;
        double *np = realloc(b->p, 3 * cap * sizeof *np);
        if (!np) { b->ok = 0; return 0; }
        b->p = np;
        b->cap = cap;
    }
    memcpy(b->p + 3 * b->n++, p, 3 * sizeof(double));
    return 1;
}

void pnpr_lines_free(pnpr_polylines *l)
{
    if (!l) return;
    free(l->offset);
    free(l->xyz);
    free(l->closed);
    memset(l, 0, sizeof *l);
}

static double dist3(const float *a, const float *b)
{
    double d[3] = {(double)a[0] - b[0], (double)a[1] - b[1], (double)a[2] - b[2]};
    return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

typedef struct edge { float w; uint32_t a, b; } edge;

static int cmp_edge(const void *x, const void *y)
{
    const edge *a = x, *b = y;
    if (a->w != b->w) return a->w < b->w ? -1 : 1;
    if (a->a != b->a) return a->a < b->a ? -1 : 1;
    return a->b < b->b ? -1 : (a->b > b->b);
}

static uint32_t find(uint32_t *parent, uint32_t x)
{
    while (parent[x] != x) { parent[x] = parent[parent[x]]; x = parent[x]; }
    return x;
}

typedef struct chain {
    size_t first, count; /* node ids in `chain_nodes` */
    int closed;
    int end_leaf[2];     /* the first/last node is a leaf of the forest */
    double ext[2][3];    /* corner extension of each end */
    int has_ext[2];
} chain;

/* End point and tangent (pointing outwards) of a chain end, over about 3h. */
static void end_tangent(const float *pos, const uint32_t *nodes, size_t count, int end, double h,
                        double r_e[3], double r_t[3])
{
    size_t i0 = end ? count - 1 : 0;
    const float *e = pos + 3 * (size_t)nodes[i0];
    const float *q = e;
    for (size_t s = 1; s < count; s++) {
        q = pos + 3 * (size_t)nodes[end ? count - 1 - s : s];
        if (dist3(e, q) >= 3 * h) break;
    }
    double t[3] = {(double)e[0] - q[0], (double)e[1] - q[1], (double)e[2] - q[2]};
    double l = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    for (int a = 0; a < 3; a++) { r_e[a] = e[a]; r_t[a] = l > 0 ? t[a] / l : 0; }
}

pnpr_status pnpr_lines_check_options(const pnpr_lines_options *o, pnpr_error *err)
{
    if (!o) return PNPR_OK;
    static const char *const names[6] = {"spacing", "connect_radius", "merge_tol", "direction_weight",
                                         "min_length", "sample_tol"};
    const float vals[6] = {o->spacing, o->connect_radius, o->merge_tol, o->direction_weight, o->min_length,
                           o->sample_tol};
    for (int i = 0; i < 6; i++)
        if (!isfinite(vals[i]) || vals[i] < 0)
            return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "lines: %s %g must be finite and >= 0", names[i],
                                  vals[i]);
    if (o->shift_iterations > PNPR_LINES_SHIFT_MAX)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "lines: shift_iterations %d is more than %d",
                              o->shift_iterations, PNPR_LINES_SHIFT_MAX);
    return PNPR_OK;
}

pnpr_status pnpr_profile_lines_points(const float *xyz_in, const float *dir_in, size_t m,
                                      const double origin[3], const pnpr_lines_options *opts,
                                      pnpr_polylines *r_lines, pnpr_lines_stats *r_stats)
{
    static const pnpr_lines_options defaults;
    pnpr_lines_stats local;
    if (!r_stats) r_stats = &local;
    memset(r_stats, 0, sizeof *r_stats);
    if (!r_lines) return PNPR_ERR_INVALID_ARGUMENT;
    memset(r_lines, 0, sizeof *r_lines);
    if (origin) memcpy(r_lines->origin, origin, sizeof r_lines->origin);
    if (!opts) opts = &defaults;
    if (m && (!xyz_in || !dir_in)) return PNPR_ERR_INVALID_ARGUMENT;
    if (m >= 0x7FFFFFFFu) return PNPR_ERR_UNSUPPORTED;
    if (pnpr_lines_check_options(opts, NULL) != PNPR_OK) return PNPR_ERR_INVALID_ARGUMENT;

    pnpr_status st = PNPR_OK;
    /* valid input points: finite position and a nonzero direction */
    float *pos = malloc((m ? m : 1) * 3 * sizeof *pos), *dir = malloc((m ? m : 1) * 3 * sizeof *dir);
    float *npos = NULL, *ndir = NULL;
    uint32_t *cluster = NULL, *parent = NULL, *adj_off = NULL, *adj = NULL, *chain_nodes = NULL;
    uint8_t *alive = NULL;
    edge *edges = NULL;
    chain *chains = NULL;
    pnpr_kdtree *tree = NULL;
    pnpr_lines_buf out = {NULL, 0, 0, 1};
    size_t n_edges = 0, n_forest = 0, n_chains = 0, n_nodes = 0;
    if (!pos || !dir) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
    size_t n = 0;
    for (size_t i = 0; i < m; i++) {
        const float *p = xyz_in + 3 * i, *d = dir_in + 3 * i;
        double l = sqrt((double)d[0] * d[0] + (double)d[1] * d[1] + (double)d[2] * d[2]);
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]) || !(l > 0) || !isfinite(l)) continue;
        memcpy(pos + 3 * n, p, 3 * sizeof(float));
        for (int a = 0; a < 3; a++) dir[3 * n + a] = (float)(d[a] / l);
        n++;
    }
    r_stats->directional_points = n;
    if (n < 2) goto done;
    double t0 = pnpr_now();

    if ((st = pnpr_kdtree_build(pos, n, 0, &tree)) != PNPR_OK) goto done;
    double h = opts->spacing > 0 ? opts->spacing : pnpr_kdtree_median_spacing(tree, 0);
    if (!(h > 0)) goto done; /* all points coincide: no line */
    r_stats->spacing_used = (float)h;
    const double R = opts->connect_radius > 0 ? opts->connect_radius : 3 * h;
    const double tol_merge = opts->merge_tol > 0 ? opts->merge_tol : h;
    const int shifts = opts->shift_iterations == 0 ? 4 : (opts->shift_iterations < 0 ? 0 : opts->shift_iterations);
    const double beta = opts->direction_weight > 0 ? opts->direction_weight : 4.0;
    const double min_len = opts->min_length > 0 ? opts->min_length : 5 * h;
    const double tol_sample = opts->sample_tol > 0 ? opts->sample_tol : 0.05 * h;
    uint32_t nb[RADIUS_CAP];

    /* 1. shift across the feature direction towards the neighbours' mean */
    npos = malloc(n * 3 * sizeof *npos);
    if (!npos) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
    for (int it = 0; it < shifts; it++) {
        for (size_t i = 0; i < n; i++) {
            const float *p = pos + 3 * i, *d = dir + 3 * i;
            size_t got = pnpr_kdtree_radius_first(tree, p, (float)(2 * h), nb, RADIUS_CAP);
            double mean[3] = {0, 0, 0};
            for (size_t r = 0; r < got; r++)
                for (int a = 0; a < 3; a++) mean[a] += pos[3 * (size_t)nb[r] + a];
            double mv[3];
            for (int a = 0; a < 3; a++) mv[a] = got ? mean[a] / (double)got - p[a] : 0.0;
            double along = mv[0] * d[0] + mv[1] * d[1] + mv[2] * d[2];
            for (int a = 0; a < 3; a++) npos[3 * i + a] = (float)(p[a] + 0.5 * (mv[a] - along * d[a]));
        }
        memcpy(pos, npos, n * 3 * sizeof *pos);
        pnpr_kdtree_free(tree);
        tree = NULL;
        if ((st = pnpr_kdtree_build(pos, n, 0, &tree)) != PNPR_OK) goto done;
        if (pnpr_progress_report(&opts->progress, "lines: shift", (it + 1.0) / (shifts + 1.0))) { st = PNPR_ERR_CANCELLED; goto done; }
    }

    /* 2. merge points closer than tol_merge */
    cluster = malloc(n * sizeof *cluster);
    ndir = malloc(n * 3 * sizeof *ndir);
    if (!cluster || !ndir) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
    for (size_t i = 0; i < n; i++) cluster[i] = PNPR_INDEX_NONE;
    for (size_t i = 0; i < n; i++) {
        if (cluster[i] != PNPR_INDEX_NONE) continue;
        size_t got = pnpr_kdtree_radius_first(tree, pos + 3 * i, (float)tol_merge, nb, RADIUS_CAP);
        const float *d0 = dir + 3 * i;
        double c[3] = {pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]}, dsum[3] = {d0[0], d0[1], d0[2]};
        size_t cnt = 1;
        cluster[i] = (uint32_t)n_nodes;
        for (size_t r = 0; r < got; r++) {
            uint32_t j = nb[r];
            if (cluster[j] != PNPR_INDEX_NONE) continue; /* merged already (or i itself) */
            cluster[j] = (uint32_t)n_nodes;
            const float *dj = dir + 3 * (size_t)j;
            double s = dj[0] * d0[0] + dj[1] * d0[1] + dj[2] * d0[2] < 0 ? -1.0 : 1.0;
            for (int a = 0; a < 3; a++) { c[a] += pos[3 * (size_t)j + a]; dsum[a] += s * dj[a]; }
            cnt++;
        }
        double dl = sqrt(dsum[0] * dsum[0] + dsum[1] * dsum[1] + dsum[2] * dsum[2]);
        for (int a = 0; a < 3; a++) {
            npos[3 * n_nodes + a] = (float)(c[a] / (double)cnt);
            ndir[3 * n_nodes + a] = dl > 0 ? (float)(dsum[a] / dl) : d0[a];
        }
        n_nodes++;
    }
    r_stats->merged_nodes = n_nodes;
    pnpr_kdtree_free(tree);
    tree = NULL;
    if ((st = pnpr_kdtree_build(npos, n_nodes, 0, &tree)) != PNPR_OK) goto done;

    /* 3. graph edges */
    size_t cap_edges = n_nodes * 8;
    edges = malloc((cap_edges ? cap_edges : 1) * sizeof *edges);
    if (!edges) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
    for (size_t a = 0; a < n_nodes; a++) {
        uint32_t idx[9];
        float d2[9];
        size_t got = pnpr_kdtree_knn(tree, npos + 3 * a, 9, idx, d2);
        const float *pa = npos + 3 * a, *da = ndir + 3 * a;
        for (size_t r = 0; r < got; r++) {
            uint32_t b = idx[r];
            if (b == a || d2[r] > R * R) continue;
            const float *pb = npos + 3 * (size_t)b, *db = ndir + 3 * (size_t)b;
            double e[3] = {(double)pb[0] - pa[0], (double)pb[1] - pa[1], (double)pb[2] - pa[2]};
            double len = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
            if (!(len > 0)) continue;
            double ca = fabs(e[0] * da[0] + e[1] * da[1] + e[2] * da[2]) / len;
            double cb = fabs(e[0] * db[0] + e[1] * db[1] + e[2] * db[2]) / len;
            if (ca < 0.5 && cb < 0.5) continue;
            edge ed = {(float)(len * (1 + beta * (1 - 0.5 * (ca + cb)))), (uint32_t)(a < b ? a : b), (uint32_t)(a < b ? b : a)};
            edges[n_edges++] = ed;
        }
    }
    r_stats->seconds_graph = pnpr_now() - t0;
    t0 = pnpr_now();

    /* 4. minimum spanning forest (Kruskal; duplicates of an edge are skipped by union-find) */
    qsort(edges, n_edges, sizeof *edges, cmp_edge);
    r_stats->graph_edges = n_edges;
    parent = malloc(n_nodes * sizeof *parent);
    if (!parent) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
    for (size_t i = 0; i < n_nodes; i++) parent[i] = (uint32_t)i;
    for (size_t e = 0; e < n_edges; e++) {
        uint32_t ra = find(parent, edges[e].a), rb = find(parent, edges[e].b);
        if (ra == rb) continue;
        parent[ra] = rb;
        edges[n_forest++] = edges[e];
    }
    r_stats->forest_edges = n_forest;
    r_stats->seconds_mst = pnpr_now() - t0;
    t0 = pnpr_now();
    if (pnpr_progress_report(&opts->progress, "lines: tree", 0.5)) { st = PNPR_ERR_CANCELLED; goto done; }

    /* adjacency (CSR over forest edges) and degrees */
    adj_off = calloc(n_nodes + 1, sizeof *adj_off);
    adj = malloc((2 * n_forest + 1) * sizeof *adj);
    alive = malloc(n_forest + 1);
    uint32_t *deg = parent; /* reuse: union-find is done */
    if (!adj_off || !adj || !alive) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
    memset(deg, 0, n_nodes * sizeof *deg);
    for (size_t e = 0; e < n_forest; e++) { deg[edges[e].a]++; deg[edges[e].b]++; alive[e] = 1; }
    for (size_t i = 0; i < n_nodes; i++) adj_off[i + 1] = adj_off[i] + deg[i];
    {
        uint32_t *fill = calloc(n_nodes, sizeof *fill);
        if (!fill) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
        for (size_t e = 0; e < n_forest; e++) {
            adj[adj_off[edges[e].a] + fill[edges[e].a]++] = (uint32_t)e;
            adj[adj_off[edges[e].b] + fill[edges[e].b]++] = (uint32_t)e;
        }
        free(fill);
    }
#define OTHER(e, v) (edges[e].a == (v) ? edges[e].b : edges[e].a)

    /* 5. prune spurs: leaf branches shorter than min_len that end at a junction */
    for (size_t leaf = 0; leaf < n_nodes; leaf++) {
        if (deg[leaf] != 1) continue;
        uint32_t v = (uint32_t)leaf, prev_e = PNPR_INDEX_NONE;
        double len = 0;
        size_t steps = 0;
        for (;;) {
            uint32_t next_e = PNPR_INDEX_NONE;
            for (uint32_t k = adj_off[v]; k < adj_off[v + 1]; k++)
                if (alive[adj[k]] && adj[k] != prev_e) { next_e = adj[k]; break; }
            if (next_e == PNPR_INDEX_NONE) break;
            uint32_t w = OTHER(next_e, v);
            len += dist3(npos + 3 * (size_t)v, npos + 3 * (size_t)w);
            prev_e = next_e;
            v = w;
            steps++;
            if (deg[v] != 2 || len >= min_len) break;
        }
        if (deg[v] >= 3 && len < min_len) { /* remove the branch leaf .. v */
            uint32_t u = (uint32_t)leaf, pe = PNPR_INDEX_NONE;
            for (size_t s = 0; s < steps; s++) {
                uint32_t ne = PNPR_INDEX_NONE;
                for (uint32_t k = adj_off[u]; k < adj_off[u + 1]; k++)
                    if (alive[adj[k]] && adj[k] != pe) { ne = adj[k]; break; }
                if (ne == PNPR_INDEX_NONE) break;
                uint32_t w = OTHER(ne, u);
                alive[ne] = 0;
                deg[u]--; deg[w]--;
                pe = ne;
                u = w;
            }
        }
    }

    /* 6. chains between nodes of degree != 2 */
    chain_nodes = malloc((2 * n_forest + n_nodes + 1) * sizeof *chain_nodes);
    chains = malloc((n_forest + 1) * sizeof *chains);
    uint8_t *used = calloc(n_forest + 1, 1);
    if (!chain_nodes || !chains || !used) { free(used); st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
    size_t cn = 0;
    for (size_t s = 0; s < n_nodes; s++) {
        if (deg[s] == 2 || deg[s] == 0) continue;
        for (uint32_t k = adj_off[s]; k < adj_off[s + 1]; k++) {
            uint32_t e = adj[k];
            if (!alive[e] || used[e]) continue;
            chain *c = &chains[n_chains];
            memset(c, 0, sizeof *c);
            c->first = cn;
            chain_nodes[cn++] = (uint32_t)s;
            uint32_t v = (uint32_t)s;
            for (;;) {
                used[e] = 1;
                v = OTHER(e, v);
                chain_nodes[cn++] = v;
                if (deg[v] != 2) break;
                uint32_t ne = PNPR_INDEX_NONE;
                for (uint32_t q = adj_off[v]; q < adj_off[v + 1]; q++)
                    if (alive[adj[q]] && !used[adj[q]]) { ne = adj[q]; break; }
                if (ne == PNPR_INDEX_NONE) break;
                e = ne;
            }
            c->count = cn - c->first;
            c->end_leaf[0] = deg[s] == 1;
            c->end_leaf[1] = deg[v] == 1;
            n_chains++;
        }
    }
    free(used);
#undef OTHER

    /* drop short isolated chains, close rings */
    for (size_t ci = 0; ci < n_chains; ci++) {
        chain *c = &chains[ci];
        const uint32_t *nodes = chain_nodes + c->first;
        double len = 0;
        for (size_t i = 1; i < c->count; i++) len += dist3(npos + 3 * (size_t)nodes[i - 1], npos + 3 * (size_t)nodes[i]);
        if (c->end_leaf[0] && c->end_leaf[1]) {
            if (len < min_len) { c->count = 0; continue; }
            if (len >= 3 * R && dist3(npos + 3 * (size_t)nodes[0], npos + 3 * (size_t)nodes[c->count - 1]) <= R)
                c->closed = 1;
        }
    }

    /* 7. corners: chain ends whose tangents meet */
    if (!opts->no_corners) {
        size_t ne = 0;
        for (size_t ci = 0; ci < n_chains; ci++)
            for (int end = 0; end < 2; end++) ne += chains[ci].count >= 2 && !chains[ci].closed && chains[ci].end_leaf[end];
        double *ep = malloc((ne + 1) * 6 * sizeof *ep);
        uint32_t *eref = malloc((ne + 1) * sizeof *eref);
        double *votes = malloc((ne * 8 + 1) * 4 * sizeof *votes); /* x y z, end pair packed */
        uint32_t *vpair = malloc((ne * 8 + 1) * 2 * sizeof *vpair);
        if (!ep || !eref || !votes || !vpair) { free(ep); free(eref); free(votes); free(vpair); st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
        size_t k = 0;
        for (size_t ci = 0; ci < n_chains; ci++)
            for (int end = 0; end < 2; end++) {
                chain *c = &chains[ci];
                if (c->count < 2 || c->closed || !c->end_leaf[end]) continue;
                end_tangent(npos, chain_nodes + c->first, c->count, end, h, ep + 6 * k, ep + 6 * k + 3);
                eref[k++] = (uint32_t)(2 * ci + (size_t)end);
            }
        size_t nv = 0;
        for (size_t i = 0; i < k; i++)
            for (size_t j = i + 1; j < k && nv < ne * 8; j++) {
                const double *e1 = ep + 6 * i, *t1 = e1 + 3, *e2 = ep + 6 * j, *t2 = e2 + 3;
                double w0[3] = {e1[0] - e2[0], e1[1] - e2[1], e1[2] - e2[2]};
                if (w0[0] * w0[0] + w0[1] * w0[1] + w0[2] * w0[2] > 144 * h * h) continue;
                double b = t1[0] * t2[0] + t1[1] * t2[1] + t1[2] * t2[2];
                if (b < -0.9) { /* facing each other across a gap? */
                    double wl = sqrt(w0[0] * w0[0] + w0[1] * w0[1] + w0[2] * w0[2]);
                    double a1 = -(t1[0] * w0[0] + t1[1] * w0[1] + t1[2] * w0[2]); /* e2 ahead of e1 */
                    double a2 = t2[0] * w0[0] + t2[1] * w0[1] + t2[2] * w0[2];    /* e1 ahead of e2 */
                    if (wl > 0 && a1 >= 0.9 * wl && a2 >= 0.9 * wl) {
                        for (int a = 0; a < 3; a++) votes[4 * nv + a] = 0.5 * (e1[a] + e2[a]);
                        votes[4 * nv + 3] = -1;
                        vpair[2 * nv] = (uint32_t)i;
                        vpair[2 * nv + 1] = (uint32_t)j;
                        nv++;
                    }
                    continue;
                }
                if (fabs(b) > 0.866) continue; /* nearly parallel: not a corner */
                double d = t1[0] * w0[0] + t1[1] * w0[1] + t1[2] * w0[2];
                double e = t2[0] * w0[0] + t2[1] * w0[1] + t2[2] * w0[2];
                double den = 1 - b * b;
                double s = (b * e - d) / den, u = (e - b * d) / den;
                if (s < -h || u < -h || s > 10 * h || u > 10 * h) continue;
                double c1[3], c2[3], gap = 0;
                for (int a = 0; a < 3; a++) {
                    c1[a] = e1[a] + s * t1[a];
                    c2[a] = e2[a] + u * t2[a];
                    gap += (c1[a] - c2[a]) * (c1[a] - c2[a]);
                }
                if (gap > 4 * h * h) continue;
                for (int a = 0; a < 3; a++) votes[4 * nv + a] = 0.5 * (c1[a] + c2[a]);
                votes[4 * nv + 3] = -1; /* corner id */
                vpair[2 * nv] = (uint32_t)i;
                vpair[2 * nv + 1] = (uint32_t)j;
                nv++;
            }
        /* cluster votes within 2h; each end joins the corner of its first vote */
        for (size_t v = 0; v < nv; v++) {
            if (votes[4 * v + 3] >= 0) continue;
            double c[3] = {0, 0, 0};
            size_t cnt = 0;
            for (size_t w = v; w < nv; w++) {
                if (votes[4 * w + 3] >= 0) continue;
                double dd = 0;
                for (int a = 0; a < 3; a++) dd += (votes[4 * w + a] - votes[4 * v + a]) * (votes[4 * w + a] - votes[4 * v + a]);
                if (dd > 4 * h * h) continue;
                votes[4 * w + 3] = (double)v;
                for (int a = 0; a < 3; a++) c[a] += votes[4 * w + a];
                cnt++;
            }
            for (int a = 0; a < 3; a++) c[a] /= (double)cnt;
            for (size_t w = v; w < nv; w++) {
                if (votes[4 * w + 3] != (double)v) continue;
                for (int pe = 0; pe < 2; pe++) {
                    uint32_t ref = eref[vpair[2 * w + pe]];
                    chain *ch = &chains[ref / 2];
                    if (ch->has_ext[ref % 2]) continue;
                    ch->has_ext[ref % 2] = 1;
                    memcpy(ch->ext[ref % 2], c, sizeof c);
                }
            }
            r_stats->corners++;
        }
        free(ep); free(eref); free(votes); free(vpair);
    }

    /* 8. B-spline per chain -> polylines */
    {
        size_t cap_l = n_chains + 1;
        r_lines->offset = malloc((cap_l + 1) * sizeof *r_lines->offset);
        r_lines->closed = malloc(cap_l);
        if (!r_lines->offset || !r_lines->closed) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
        r_lines->offset[0] = 0;
        pnpr_lines_buf q = {NULL, 0, 0, 1};
        for (size_t ci = 0; ci < n_chains; ci++) {
            chain *c = &chains[ci];
            if (c->count < 2) continue;
            q.n = 0;
            if (c->has_ext[0]) pnpr_lines_buf_push(&q, c->ext[0]);
            for (size_t i = 0; i < c->count; i++) {
                const float *p = npos + 3 * (size_t)chain_nodes[c->first + i];
                double dp[3] = {p[0], p[1], p[2]};
                pnpr_lines_buf_push(&q, dp);
            }
            if (c->has_ext[1]) pnpr_lines_buf_push(&q, c->ext[1]);
            size_t before = out.n;
            if (!q.ok || !pnpr_lines_fit_chain(q.p, q.n, c->closed, h, tol_sample, &out)) {
                free(q.p);
                st = PNPR_ERR_OUT_OF_MEMORY;
                goto done;
            }
            if (out.n - before < 2) { out.n = before; continue; }
            for (size_t i = before + 1; i < out.n; i++) {
                const double *a = out.p + 3 * (i - 1), *b = out.p + 3 * i;
                r_stats->total_length += sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
            }
            if (c->closed) {
                const double *a = out.p + 3 * (out.n - 1), *b = out.p + 3 * before;
                r_stats->total_length += sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
            }
            r_lines->closed[r_lines->count] = (uint8_t)c->closed;
            r_lines->offset[++r_lines->count] = out.n;
        }
        free(q.p);
        r_stats->chains = r_lines->count;
        r_lines->xyz = malloc((out.n ? out.n : 1) * 3 * sizeof *r_lines->xyz);
        if (!r_lines->xyz) { st = PNPR_ERR_OUT_OF_MEMORY; goto done; }
        for (size_t i = 0; i < 3 * out.n; i++) r_lines->xyz[i] = (float)out.p[i];
    }
    r_stats->seconds_fit = pnpr_now() - t0;
    pnpr_progress_report(&opts->progress, "lines: fit", 1.0);

done:
    if (st == PNPR_OK && !r_lines->offset) { /* no lines: a valid empty result */
        r_lines->offset = calloc(1, sizeof *r_lines->offset);
        r_lines->closed = malloc(1);
        r_lines->xyz = malloc(3 * sizeof *r_lines->xyz);
        if (!r_lines->offset || !r_lines->closed || !r_lines->xyz) st = PNPR_ERR_OUT_OF_MEMORY;
    }
    if (st != PNPR_OK) {
        double o[3];
        memcpy(o, r_lines->origin, sizeof o);
        pnpr_lines_free(r_lines);
        memcpy(r_lines->origin, o, sizeof o);
    }
    pnpr_kdtree_free(tree);
    free(pos); free(dir); free(npos); free(ndir); free(cluster); free(parent);
    free(adj_off); free(adj); free(alive); free(edges); free(chains); free(chain_nodes); free(out.p);
    return st;
}

pnpr_status pnpr_profile_lines(const pnpr_cloud *cloud, const pnpr_lines_options *opts,
                               pnpr_polylines *r_lines, pnpr_lines_stats *r_stats)
{
    if (!cloud || !r_lines || (cloud->count && !cloud->xyz)) return PNPR_ERR_INVALID_ARGUMENT;
    const pnpr_property *cls = pnpr_cloud_find_property(cloud, "feature_class");
    const pnpr_property *dx = pnpr_cloud_find_property(cloud, "feature_dir_x");
    const pnpr_property *dy = pnpr_cloud_find_property(cloud, "feature_dir_y");
    const pnpr_property *dz = pnpr_cloud_find_property(cloud, "feature_dir_z");
    if (!cls || !dx || !dy || !dz) {
        memset(r_lines, 0, sizeof *r_lines);
        return PNPR_ERR_NOT_FOUND;
    }
    size_t m = 0;
    for (size_t i = 0; i < cloud->count; i++) m += pnpr_type_get(cls->type, cls->data, i) == PNPR_CLASS_DIRECTIONAL;
    float *p = malloc((m ? m : 1) * 3 * sizeof *p), *d = malloc((m ? m : 1) * 3 * sizeof *d);
    if (!p || !d) { free(p); free(d); memset(r_lines, 0, sizeof *r_lines); return PNPR_ERR_OUT_OF_MEMORY; }
    size_t j = 0;
    for (size_t i = 0; i < cloud->count; i++) {
        if (pnpr_type_get(cls->type, cls->data, i) != PNPR_CLASS_DIRECTIONAL) continue;
        memcpy(p + 3 * j, cloud->xyz + 3 * i, 3 * sizeof(float));
        d[3 * j] = (float)pnpr_type_get(dx->type, dx->data, i);
        d[3 * j + 1] = (float)pnpr_type_get(dy->type, dy->data, i);
        d[3 * j + 2] = (float)pnpr_type_get(dz->type, dz->data, i);
        j++;
    }
    pnpr_status st = pnpr_profile_lines_points(p, d, m, cloud->origin, opts, r_lines, r_stats);
    free(p);
    free(d);
    return st;
}
