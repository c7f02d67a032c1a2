/* Shared by the sphere hierarchy's sources (filters/sphere_leaves.c, sphere_tree.c,
 * sphere_traverse.c); not installed. */
#ifndef PNPR_SPHERE_INTERNAL_H
#define PNPR_SPHERE_INTERNAL_H

#include <pointnpr/hierarchy.h>
#include <pointnpr/knn.h>

/* The colour of colourless clouds' nodes (0..255 grey). */
#define PNPR_SPHERE_GREY 200.0f

/* A node under construction, in full precision: the build aggregates these; the finished tree
 * holds them packed (pnpr_sphere_node, 64 bytes: the renderer holds the tree beside its vertex
 * buffers, docs/hierarchy.md "Memory"). Fields as pnpr_sphere_node's; leaf_end and level as
 * pnpr_sphere_leaf_end and pnpr_sphere_tree.merge_level give them. */
typedef struct sphere_work {
    float centre[3], radius, extent;
    float normal[3], cone, colour[3], curvature, dir[3];
    float dissimilarity, level;
    uint32_t parent, child[2], leaf_begin, leaf_end, region;
    uint8_t kind;
} sphere_work;

/* A tree under construction: nodes 0 .. leaves-1 are the leaves (seed order), inner nodes follow. */
typedef struct sphere_build {
    sphere_work *nodes;
    size_t leaves, count, cap;
    uint32_t *point_leaf; /* point -> leaf (seed order) */
    float spacing;
} sphere_build;

pnpr_status pnpr_sphere_pick_leaves(const float *xyz, size_t count, float spacing, uint32_t *r_seed,
                                    size_t *r_leaves);
pnpr_status pnpr_sphere_assign(const pnpr_cloud *c, const pnpr_kdtree *leaf_tree, sphere_build *b, int threads,
                               const pnpr_progress *progress);
pnpr_status pnpr_sphere_leaf_shape(sphere_build *b, const uint32_t *knn, size_t k, float fraction, int threads,
                                   const pnpr_progress *progress);
/* v projected into the plane normal to n, unit length (0 when degenerate). */
void pnpr_sphere_tangent(const float n[3], const double v[3], float r_dir[3]);
/* CIE76 delta E between two 0..255 RGB colours. */
double pnpr_sphere_colour_distance(const float a[3], const float b[3]);
/* The Perlin noise at node n's centre, -1..1 (the stroke jitter of sec. 4.3): features of about
 * ten leaves across, so the jitter drifts over a region instead of flickering from stroke to
 * stroke (Perlin's noise is band-limited to its lattice). Computed when drawn, not stored. */
float pnpr_sphere_noise(const pnpr_sphere_tree *t, const pnpr_sphere_node *n);
/* 3D gradient noise (Perlin 1985, improved gradients), about -1..1, deterministic. */
float pnpr_perlin3(double x, double y, double z);

#endif
