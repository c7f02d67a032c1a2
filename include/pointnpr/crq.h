/* pointnpr — crq.h: the continuous resolution queue (PointWorks section 4.4) of the renderer:
 * the order in which a frame draws each group's points (a prefix of it) and how a frame's point
 * budget is shared among the groups. Pure CPU, in the core library `pointnpr` (view/crq.c); the
 * renderer (render.h, which includes this header) builds its queue with it at upload. */
#ifndef POINTNPR_CRQ_H
#define POINTNPR_CRQ_H

#include "core.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The queue order: a permutation of 0..count-1 grouped by `group` (group g's points come before
 * group g+1's; groups are 0..group_count-1, points with group >= group_count go last, in
 * their own group) and randomly shuffled inside each group with a generator seeded by `seed`
 * (same inputs, same order, on every machine). group may be NULL (one group).
 * r_group_start (optional, group_count + 2 entries) receives where each group starts, the
 * "other" group last, then count. */
PNPR_NODISCARD pnpr_status pnpr_crq_order(size_t count, const uint8_t *group, uint32_t group_count,
                           uint64_t seed, uint32_t *r_order, size_t *r_group_start);

/* How many points of each group a frame draws: `total` points shared among the groups in
 * proportion to their sizes (floor, then the largest remainders, ties to the lower group), so
 * that the counts sum to min(total, sum of sizes) exactly. */
void pnpr_crq_split(const size_t *group_size, size_t group_count, size_t total, size_t *r_draw);

#ifdef __cplusplus
}
#endif
#endif
