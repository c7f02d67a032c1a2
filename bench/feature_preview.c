/* Documentation pictures of the feature analysis, without GL: an orthographic point splat of a
 * PLY written by `pointnpr features`, coloured by feature_class (red directional, blue
 * non-directional, grey dithering points, light grey the rest) or by the scan's own colours.
 *   feature_preview IN.ply OUT.png [--view front|side|top] [--rgb] [--size N]
 * The renderer (render/) is the real way to draw clouds; this tool only makes the figures of
 * docs/features.md reproducible. */
#include <pointnpr/features.h>
#include <pointnpr/io.h>

#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int write_png(const char *path, const unsigned char *rgb, int w, int h)
{
    FILE *f = fopen(path, "wb");
    if (!f) return 0;
    png_structp ps = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop pi = ps ? png_create_info_struct(ps) : NULL;
    if (!ps || !pi || setjmp(png_jmpbuf(ps))) {
        png_destroy_write_struct(&ps, &pi);
        fclose(f);
        return 0;
    }
    png_init_io(ps, f);
    png_set_IHDR(ps, pi, (png_uint_32)w, (png_uint_32)h, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(ps, pi);
    for (int y = 0; y < h; y++) png_write_row(ps, (png_const_bytep)(rgb + 3 * (size_t)y * (size_t)w));
    png_write_end(ps, NULL);
    png_destroy_write_struct(&ps, &pi);
    return fclose(f) == 0;
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: feature_preview IN.ply OUT.png [--view front|side|top] [--rgb] [--size N]\n");
        return 2;
    }
    int size = 900, use_rgb = 0;
    int ax0 = 0, ax1 = 2, depth = 1, depth_sign = -1; /* front: x right, z up, looking along +y */
    for (int i = 3; i < argc; i++) {
        if (!strcmp(argv[i], "--rgb")) use_rgb = 1;
        else if (!strcmp(argv[i], "--size") && i + 1 < argc) size = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--view") && i + 1 < argc) {
            const char *v = argv[++i];
            if (!strcmp(v, "side")) { ax0 = 1; ax1 = 2; depth = 0; depth_sign = 1; }
            else if (!strcmp(v, "top")) { ax0 = 0; ax1 = 1; depth = 2; depth_sign = 1; }
        }
    }
    if (size < 16 || size > 8192) { fprintf(stderr, "feature_preview: --size wants 16..8192\n"); return 2; }
    pnpr_cloud c = {0};
    pnpr_error err = {0};
    if (pnpr_read_file(argv[1], NULL, &c, &err) != PNPR_OK) { fprintf(stderr, "%s\n", err.message); return 1; }
    pnpr_property *cp = pnpr_cloud_find_property(&c, "feature_class");
    const uint8_t *cls = cp && cp->type == PNPR_TYPE_UINT8 ? cp->data : NULL;
    float lo[3], hi[3];
    if (pnpr_cloud_bounds(&c, lo, hi) == 0) { fprintf(stderr, "feature_preview: no valid points\n"); return 1; }
    float ext = fmaxf(hi[ax0] - lo[ax0], hi[ax1] - lo[ax1]);
    if (!(ext > 0)) ext = 1;
    size_t npx = (size_t)size * (size_t)size;
    float *zb = malloc(npx * sizeof *zb);
    unsigned char *img = malloc(3 * npx);
    if (!zb || !img) return 1;
    for (size_t i = 0; i < npx; i++) { zb[i] = -INFINITY; img[3 * i] = img[3 * i + 1] = img[3 * i + 2] = 255; }
    for (size_t i = 0; i < c.count; i++) {
        const float *p = c.xyz + 3 * i;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) continue;
        int x = (int)((p[ax0] - lo[ax0]) / ext * (float)(size - 2));
        int y = size - 2 - (int)((p[ax1] - lo[ax1]) / ext * (float)(size - 2));
        float z = depth_sign * p[depth];
        unsigned char col[3] = {225, 225, 225};
        if (use_rgb && c.rgb) memcpy(col, c.rgb + 3 * i, 3);
        else if (cls && cls[i] == PNPR_CLASS_DIRECTIONAL) { col[0] = 220; col[1] = 20; col[2] = 20; }
        else if (cls && cls[i] == PNPR_CLASS_NONDIRECTIONAL) { col[0] = 30; col[1] = 60; col[2] = 220; }
        else if (cls && cls[i] == PNPR_CLASS_DITHER) { col[0] = col[1] = col[2] = 110; }
        for (int dy = 0; dy < 2; dy++)
            for (int dx = 0; dx < 2; dx++) {
                int xx = x + dx, yy = y + dy;
                if (xx < 0 || yy < 0 || xx >= size || yy >= size) continue;
                size_t q = (size_t)yy * (size_t)size + (size_t)xx;
                if (z < zb[q]) continue;
                zb[q] = z;
                memcpy(img + 3 * q, col, 3);
            }
    }
    int ok = write_png(argv[2], img, size, size);
    free(zb); free(img);
    pnpr_cloud_free(&c);
    if (!ok) { fprintf(stderr, "feature_preview: cannot write %s\n", argv[2]); return 1; }
    return 0;
}
