/* Reading a PNG in tests, composited on white (libpng's simplified API). Header-only: the core
 * tests have libpng only when it was found (PNPR_TEST_HAVE_PNG). */
#ifndef PNPR_TEST_PNG_READ_H
#define PNPR_TEST_PNG_READ_H

#include <png.h>
#include <string.h>

/* Reads `path` as `format` (PNG_FORMAT_GRAY, PNG_FORMAT_RGB, ...) into `out` when it is w x h;
 * 0 on failure or another size. */
static inline int pnpr_test_read_png(const char *path, int w, int h, png_uint_32 format, unsigned char *out)
{
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&img, path)) return 0;
    img.format = format;
    if (img.width != (png_uint_32)w || img.height != (png_uint_32)h) { png_image_free(&img); return 0; }
    png_color white = {255, 255, 255};
    return png_image_finish_read(&img, &white, out, 0, NULL);
}

#endif
