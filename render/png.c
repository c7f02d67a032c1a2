/* PNG output through libpng's simplified API, written as every output is (pointnpr/output.h). */
#include <pointnpr/render.h>
#include <pointnpr/output.h>

#include <errno.h>
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
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    img.width = (png_uint_32)width;
    img.height = (png_uint_32)height;
    img.format = alpha ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB;
    pnpr_status st = PNPR_OK;
    pnpr_output *o = malloc(sizeof *o);
    if (!o) st = pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    else if ((st = pnpr_output_open(o, path, err)) == PNPR_OK) {
        if (err) err->message[0] = '\0';
        int ok = png_image_write_to_stdio(&img, o->f, 0, pixels, 0, NULL);
        if (!ok && ferror(o->f) && !o->write_errno) o->write_errno = errno ? errno : EIO;
        if (!ok && !ferror(o->f)) /* libpng refused the image itself */
            st = pnpr_error_set(err, PNPR_ERR_IO, "%s: cannot write PNG (%s)", path, img.message);
        else if (!ok)
            st = PNPR_ERR_IO;
        st = pnpr_output_close(o, st, err);
    }
    free(o);
    png_image_free(&img);
    free(rgb);
    return st;
}

pnpr_status pnpr_read_png_grey(const char *path, uint8_t **r_grey, int *r_width, int *r_height, pnpr_error *err)
{
    if (!path || !r_grey || !r_width || !r_height)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "PNG: bad arguments");
    *r_grey = NULL;
    *r_width = *r_height = 0;
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&img, path))
        return pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: cannot read PNG (%s)", path, img.message);
    if (img.width == 0 || img.height == 0 || img.width > 16384 || img.height > 16384) {
        png_image_free(&img);
        return pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: PNG of %ux%u pixels (at most 16384 x 16384)", path,
                              (unsigned)img.width, (unsigned)img.height);
    }
    img.format = PNG_FORMAT_GRAY;
    uint8_t *g = malloc(PNG_IMAGE_SIZE(img));
    if (!g) { png_image_free(&img); return pnpr_error_set(err, PNPR_ERR_OUT_OF_MEMORY, "%s: out of memory", path); }
    if (!png_image_finish_read(&img, NULL, g, 0, NULL)) {
        free(g);
        pnpr_status st = pnpr_error_set(err, PNPR_ERR_FORMAT, "%s: cannot read PNG (%s)", path, img.message);
        png_image_free(&img);
        return st;
    }
    *r_grey = g;
    *r_width = (int)img.width;
    *r_height = (int)img.height;
    png_image_free(&img);
    return PNPR_OK;
}
