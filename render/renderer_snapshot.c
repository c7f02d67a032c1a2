/* Reading frames back: pnpr_renderer_read_frame, and pnpr_renderer_snapshot, which renders
 * images larger than GL's limit (or than max_tile_size) in tiles with guard bands and assembles
 * them. */
#include "renderer_internal.h"
#include "gl_state.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

/* GL's rows go bottom-up: flip in place; then optionally un-premultiply. */
static void finish_pixels(uint8_t *rgba, int w, int h, int unpremultiply)
{
    size_t row = (size_t)w * 4;
    for (int y = 0; y < h / 2; y++) {
        uint8_t *p = rgba + (size_t)y * row, *q = rgba + (size_t)(h - 1 - y) * row;
        for (size_t i = 0; i < row; i++) { uint8_t t = p[i]; p[i] = q[i]; q[i] = t; }
    }
    if (unpremultiply) {
        for (size_t i = 0; i < (size_t)w * (size_t)h; i++) {
            uint8_t *p = rgba + 4 * i;
            if (p[3] == 0 || p[3] == 255) continue;
            for (int c = 0; c < 3; c++) {
                unsigned v = (p[c] * 255u + p[3] / 2u) / p[3];
                p[c] = (uint8_t)(v > 255 ? 255 : v);
            }
        }
    }
}

pnpr_status pnpr_renderer_read_raw(pnpr_renderer *r, unsigned format, unsigned type, void *buf)
{
    if (!r || !buf) return PNPR_ERR_INVALID_ARGUMENT;
    if (!r->fbo || r->fb_w <= 0) return PNPR_ERR_EMPTY;
    pnpr_gl_state saved;
    pnpr_gl_state_save(&saved);
    pnpr_gl_state_neutral();
    glBindFramebuffer(GL_READ_FRAMEBUFFER, r->fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, r->fb_w, r->fb_h, (GLenum)format, (GLenum)type, buf);
    pnpr_gl_state_restore(&saved);
    return PNPR_OK;
}

pnpr_status pnpr_renderer_read_frame(pnpr_renderer *r, uint8_t *rgba, int unpremultiply)
{
    pnpr_status st = pnpr_renderer_read_raw(r, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    if (st == PNPR_OK) finish_pixels(rgba, r->fb_w, r->fb_h, unpremultiply);
    return st;
}

pnpr_status pnpr_renderer_read_depth(pnpr_renderer *r, float *r_depth)
{
    pnpr_status st = pnpr_renderer_read_raw(r, GL_DEPTH_COMPONENT, GL_FLOAT, r_depth);
    if (st != PNPR_OK) return st;
    int w = r->fb_w, h = r->fb_h;
    for (int y = 0; y < h / 2; y++) /* bottom row first -> top row first */
        for (int x = 0; x < w; x++) {
            float *a = r_depth + (size_t)y * (size_t)w + (size_t)x, *b = r_depth + (size_t)(h - 1 - y) * (size_t)w + (size_t)x;
            float t = *a;
            *a = *b;
            *b = t;
        }
    return PNPR_OK;
}

pnpr_status pnpr_image_bytes(int width, int height, size_t limit, size_t *r_bytes, pnpr_error *err)
{
    if (r_bytes) *r_bytes = 0;
    if (width <= 0 || height <= 0)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "image size %dx%d must be positive", width, height);
    if (limit == 0) limit = PNPR_IMAGE_BYTES_DEFAULT_LIMIT;
    if ((size_t)width > SIZE_MAX / 4 / (size_t)height || (size_t)width * (size_t)height * 4 > limit)
        return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY,
                              "image %dx%d needs %.3g GiB of RGBA memory, more than the limit of %.3g GiB",
                              width, height, (double)width * (double)height * 4.0 / 1073741824.0,
                              (double)limit / 1073741824.0);
    if (r_bytes) *r_bytes = (size_t)width * (size_t)height * 4;
    return PNPR_OK;
}

/* The guard band of the tiles of a width x height image under `plan`: GL drops a point sprite
 * whose centre leaves the viewport, so every tile is rendered with a margin of the largest
 * sprite's half size (estimated from the largest disk at the box's nearest depth, clamped to GL's
 * point size range and to a quarter tile), plus the reach of dots, lines and outlines. */
int pnpr_renderer_tile_margin(const pnpr_renderer *r, const pnpr_draw_options *o, const frame_plan *plan, int tmax)
{
    double dmin = INFINITY;
    for (int k = 0; k < 8; k++) {
        double p[3] = {(k & 1) ? r->bmax[0] : r->bmin[0], (k & 2) ? r->bmax[1] : r->bmin[1],
                       (k & 4) ? r->bmax[2] : r->bmin[2]};
        double d = -((double)plan->fc.view[2] * p[0] + (double)plan->fc.view[6] * p[1] +
                     (double)plan->fc.view[10] * p[2] + (double)plan->fc.view[14]);
        if (d < dmin) dmin = d;
    }
    if (!(dmin > plan->fc.near_plane)) dmin = plan->fc.near_plane;
    if (plan->fc.ortho) dmin = 1; /* orthographic: clip w = 1, sprite sizes do not depend on depth */
    /* o: checked and filled (pnpr_renderer_check_options); the mask scale: cartoon's default, the larger */
    float ps = o->point_scale, ms = pnpr_draw_mask_scale(o, PNPR_STYLE_CARTOON);
    double grow = ps * plan->lod_max * (ms > PNPR_PAINT_MAX_BRUSH ? ms : PNPR_PAINT_MAX_BRUSH);
    double sprite = r->count ? 2.0 * r->max_radius * grow * plan->fc.pixels_per_unit / dmin : 0;
    if (!(sprite <= r->max_point_size)) sprite = r->max_point_size;
    double extra = (double)o->dot_size + (double)o->line_width +
                   PNPR_EDGE_MAX_REACH + PNPR_EDGE_MAX_INSET + 3 + (o->outline_width > 0 ? o->outline_width : 4);
    double stroke = pnpr_stroke_half_max(o); /* a stroke reaches this far from its point */
    if (stroke > extra && stroke < 1e4) extra = stroke;
    int margin = (int)ceil(0.5 * sprite + extra) + 1;
    if (margin > tmax / 4) margin = tmax / 4;
    return margin;
}

/* The inner iw x ih pixels of the tile just drawn (after its margin) into the image at (x0, y0). */
static void read_tile(pnpr_renderer *r, int margin, int iw, int ih, int width, int x0, int y0, uint8_t *rgba)
{
    pnpr_gl_state saved;
    pnpr_gl_state_save(&saved);
    pnpr_gl_state_neutral();
    glBindFramebuffer(GL_READ_FRAMEBUFFER, r->fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ROW_LENGTH, width);
    glReadPixels(margin, margin, iw, ih, GL_RGBA, GL_UNSIGNED_BYTE, rgba + ((size_t)y0 * (size_t)width + (size_t)x0) * 4);
    pnpr_gl_state_restore(&saved);
}

pnpr_status pnpr_renderer_snapshot(pnpr_renderer *r, const pnpr_camera *camera, const pnpr_draw_options *opts,
                                   int width, int height, const pnpr_snapshot_options *sopts,
                                   uint8_t *r_rgba, pnpr_render_stats *r_stats, pnpr_error *err)
{
    if (!r || !r_rgba) return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "snapshot: NULL renderer or pixels");
    if (r_stats) memset(r_stats, 0, sizeof *r_stats);
    pnpr_snapshot_options so;
    memset(&so, 0, sizeof so);
    if (sopts) so = *sopts;
    if (width <= 0 || height <= 0)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "snapshot: image size %dx%d must be positive", width, height);
    if (so.max_tile_size < 0)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "snapshot: max_tile_size %d is negative", so.max_tile_size);
    int tmax = (int)r->max_size;
    if (so.max_tile_size > 0 && so.max_tile_size < tmax) tmax = so.max_tile_size;
    pnpr_target tgt = {0, 0, 0, width, height, 1, 0};
    if (width <= tmax && height <= tmax) { /* one frame: exactly pnpr_renderer_draw */
        pnpr_status st = pnpr_renderer_draw_frame(r, camera, opts, &tgt, NULL, r_stats, NULL, err);
        if (st != PNPR_OK) return st;
        pnpr_progress_report(&so.progress, "tile 1/1", 1.0);
        return pnpr_renderer_read_frame(r, r_rgba, so.unpremultiply);
    }
    if (tmax < 16)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "snapshot: tiles of at most %d px are too small", tmax);
    pnpr_draw_options o;
    pnpr_status st = pnpr_renderer_check_options(r, opts, &o, err);
    if (st != PNPR_OK) return st;
    frame_plan plan;
    st = pnpr_renderer_plan_frame(r, camera, &o, width, height, &plan, err);
    if (st != PNPR_OK) return st;
    int margin = pnpr_renderer_tile_margin(r, &o, &plan, tmax);
    int inner = tmax - 2 * margin;
    int nx = (width + inner - 1) / inner, ny = (height + inner - 1) / inner;
    if ((double)nx * ny > PNPR_SNAPSHOT_TILES_MAX)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT,
                              "snapshot: %dx%d in tiles of %d px takes %.0f tiles, more than %d (raise max_tile_size)",
                              width, height, tmax, (double)nx * ny, PNPR_SNAPSHOT_TILES_MAX);
    int ntiles = nx * ny, done = 0;
    tgt.width = tgt.height = tmax;
    for (int ty = 0; ty < ny; ty++)
        for (int tx = 0; tx < nx; tx++) {
            int x0 = tx * inner, y0 = ty * inner;
            int iw = width - x0 < inner ? width - x0 : inner, ih = height - y0 < inner ? height - y0 : inner;
            tile_rect t = {width, height, x0 - margin, y0 - margin, tmax, tmax};
            pnpr_render_stats ts;
            st = pnpr_renderer_draw_frame(r, camera, &o, &tgt, &t, &ts, NULL, err);
            if (st != PNPR_OK) return st;
            if (r_stats && done == 0) *r_stats = ts;
            read_tile(r, margin, iw, ih, width, x0, y0, r_rgba);
            done++;
            char stage[48];
            snprintf(stage, sizeof stage, "tile %d/%d", done, ntiles);
            if (pnpr_progress_report(&so.progress, stage, (double)done / ntiles))
                return pnpr_error_set(err, PNPR_ERR_CANCELLED, "snapshot: cancelled after %s", stage);
        }
    finish_pixels(r_rgba, width, height, so.unpremultiply);
    return PNPR_OK;
}
