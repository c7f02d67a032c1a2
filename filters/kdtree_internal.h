/* kd-tree functions for the library's own filters (not installed; see include/pointnpr/knn.h). */
#ifndef PNPR_KDTREE_INTERNAL_H
#define PNPR_KDTREE_INTERNAL_H

#include <pointnpr/knn.h>

/* Up to this k the kNN keeps its candidates in a sorted list whose ties follow the input index,
 * the same in a tile as in the whole cloud (kdtree.c); beyond, a heap whose ties do not. */
#define PNPR_KNN_SORTED_MAX 256

/* Connected components of the tree's points at `distance` (two points are connected when their
 * distance is <= distance, tested exactly as pnpr_kdtree_radius does). r_labels (count entries:
 * the array the tree was built from) receives for every point the input index of one point of its
 * component, the same for the whole component; points left out of the tree (NaN/Inf) get their
 * own index. The cost does not grow with the distance: a subtree whose box lies within reach of a
 * point is joined at once (each subtree at most once), and a subtree already joined to the point's
 * component is skipped, so a distance beyond the cloud's diagonal costs O(n). Stage
 * "components" on progress (may be NULL). */
/* The first min(n, cap) of the n points that pnpr_kdtree_radius finds (the same points, in the
 * same order as it writes them), returning how many; unlike it, the search stops there, so a
 * radius that takes in the whole cloud costs O(cap + depth), not O(n). */
size_t pnpr_kdtree_radius_first(const pnpr_kdtree *tree, const float q[3], float radius, uint32_t *r_idx,
                                size_t cap);

/* Makes the tree report its own positions as ids from now on (tree position p is id p), and
 * writes to r_old (pnpr_kdtree_size entries) the id each position had: a caller that puts its
 * per-point arrays into tree order (new[p] = old[r_old[p]]) keeps using the tree, and its later
 * passes over the points walk them in space-filling order (neighbours close in memory). */
pnpr_status pnpr_kdtree_renumber(pnpr_kdtree *tree, uint32_t *r_old);

pnpr_status pnpr_kdtree_components(const pnpr_kdtree *tree, size_t count, float distance,
                                   const pnpr_progress *progress, uint32_t *r_labels);

#endif
