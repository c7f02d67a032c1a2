/* PNG output through libpng's simplified API; written to a temporary name, then renamed. */
#include <pointnpr/render.h>

#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

pnpr_status pnpr_write_png(const char *path, const uint8_t *rgba, int width, int height,
                           int alpha, pnpr_error *err)
{
    if (!path || !rgba || width <= 0 || height <= 0 || width > 65535 || height > 65535)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "PNG: bad arguments (%dx%d)", width, height);
    size_t n = (size_t)width * (size_t)height;
    const uint8_t *pixels = rgba;
    uint8_t *rgb = NULL;
    if (!alpha) {
        rgb = malloc(n * 3);
        if (!rgb) return PNPR_ERR_OUT_OF_MEMORY;
        for (size_t i = 0; i < n; i++) memcpy(rgb + 3 * i, rgba + 4 * i, 3);
        pixels = rgb;
    }
    size_t len = strlen(path);
    char *tmp = malloc(len + 16);
    if (!tmp) { free(rgb); return PNPR_ERR_OUT_OF_MEMORY; }
    snprintf(tmp, len + 16, "%s.tmp-png", path);
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    img.width = (png_uint_32)width;
    img.height = (png_uint_32)height;
    img.format = alpha ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB;
    int ok = png_image_write_to_file(&img, tmp, 0, pixels, 0, NULL);
    pnpr_status st = PNPR_OK;
    if (!ok) {
        st = pnpr_error_set(err, PNPR_ERR_IO, "%s: cannot write PNG (%s)", path, img.message);
        remove(tmp);
    } else if (rename(tmp, path) != 0) {
        st = pnpr_error_set(err, PNPR_ERR_IO, "%s: cannot write PNG (rename failed)", path);
        remove(tmp);
    }
    png_image_free(&img);
    free(tmp);
    free(rgb);
    return st;
}
