/* pointnpr — the merge of a tiled run with a hook (io/tile_merge.c; internal to the library). */
#ifndef PNPR_TILE_MERGE_H
#define PNPR_TILE_MERGE_H

#include <pointnpr/tiles.h>

/* Called on every tile (number `tile`, file `path`) as read, before its halo is dropped: c (its points, core and halo), their
 * source indices idx and core flags; may change c's values and add properties (the same for every
 * tile). Not PNPR_OK stops the merge (err says why). */
typedef pnpr_status (*pnpr_tile_merge_hook)(void *user, size_t tile, const char *path, pnpr_cloud *c,
                                            const uint32_t *idx, const uint8_t *core, pnpr_error *err);

/* pnpr_tile_merge with a hook (NULL: none): the merge of segments (filters/segment_tiles.c) sets
 * the final labels and mean colours there. */
PNPR_NODISCARD pnpr_status pnpr_tile_merge_with(const char *const *paths, size_t count, uint64_t points, int seams,
                                                const char *out, const pnpr_progress *progress,
                                                pnpr_tile_merge_hook hook, void *user, pnpr_error *err);

#endif
