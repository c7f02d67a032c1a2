/* SVG writer of vector drawings (include/pointnpr/drawing.h). Written here rather than through
 * cairo's SVG surface: cairo 1.16 (Debian 12) cannot name groups, so the layers an artist edits in
 * Inkscape would be lost, and it repeats a full style on every path (about 5x the bytes). The
 * PDF goes through cairo (drawing_pdf.c) from the same paths. */
#include <pointnpr/drawing.h>
#include <pointnpr/output.h>

#include <stdio.h>
#include <string.h>

static void colour_attr(FILE *f, const char *what, const uint8_t *c)
{
    fprintf(f, " %s=\"#%02x%02x%02x\"", what, c[0], c[1], c[2]);
    if (c[3] != 255) fprintf(f, " %s-opacity=\"%.3f\"", what, c[3] / 255.0);
}

/* Opens a group for a run of paths of one colour and kind, at the width of its first path (a
 * path of another width says its own: stroke widths vary more often than colours, e.g. the
 * visible sides of partly hidden strokes, and a group costs four times the attribute). */
static void open_run(FILE *f, const pnpr_drawing *d, size_t i)
{
    const uint8_t *c = d->rgba + 4 * i;
    fputs("<g", f);
    if (d->flags[i] & PNPR_PATH_DOT) {
        colour_attr(f, "fill", c);
    } else {
        fputs(" fill=\"none\"", f);
        colour_attr(f, "stroke", c);
        fprintf(f, " stroke-width=\"%.2f\"", d->stroke_width[i]);
    }
    fputs(">\n", f);
}

static int same_run(const pnpr_drawing *d, size_t a, size_t b)
{
    int dot = (d->flags[a] & PNPR_PATH_DOT) != 0;
    return !memcmp(d->rgba + 4 * a, d->rgba + 4 * b, 4) && (!dot || d->stroke_width[a] == d->stroke_width[b]) &&
           ((d->flags[a] ^ d->flags[b]) & PNPR_PATH_DOT) == 0;
}

/* The vertices of path i as "M x yL x y..." (+ "Z" when closed). */
static void write_d(FILE *f, const pnpr_drawing *d, size_t i)
{
    size_t a = d->offset[i], b = d->offset[i + 1];
    fprintf(f, "M%.2f %.2f", d->xy[2 * a], d->xy[2 * a + 1]);
    for (size_t v = a + 1; v < b; v++) fprintf(f, "L%.2f %.2f", d->xy[2 * v], d->xy[2 * v + 1]);
    if (d->flags[i] & PNPR_PATH_CLOSED) fputc('Z', f);
}

/* A filled area: one <path> with its subpaths (the paths after it flagged PNPR_PATH_SUBPATH),
 * even-odd rule. Returns the index after its last subpath. */
static size_t write_fill(FILE *f, const pnpr_drawing *d, size_t i)
{
    fputs("<path", f);
    colour_attr(f, "fill", d->rgba + 4 * i);
    fputs(" fill-rule=\"evenodd\" d=\"", f);
    write_d(f, d, i);
    size_t j = i + 1;
    for (; j < d->count && (d->flags[j] & PNPR_PATH_SUBPATH); j++) write_d(f, d, j);
    fputs("\"/>\n", f);
    return j;
}

/* Path i in the group opened at path g. */
static void write_path(FILE *f, const pnpr_drawing *d, size_t i, size_t g)
{
    size_t a = d->offset[i];
    if (d->flags[i] & PNPR_PATH_DOT) {
        fprintf(f, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\"/>\n", d->xy[2 * a], d->xy[2 * a + 1], 0.5 * d->stroke_width[i]);
        return;
    }
    fputs("<path", f);
    char w[32], wg[32];
    snprintf(w, sizeof w, "%.2f", d->stroke_width[i]);
    snprintf(wg, sizeof wg, "%.2f", d->stroke_width[g]);
    if (strcmp(w, wg)) fprintf(f, " stroke-width=\"%s\"", w);
    fputs(" d=\"", f);
    write_d(f, d, i);
    fputs("\"/>\n", f);
}

static int print_svg(FILE *f, const void *ctx)
{
    const pnpr_drawing *d = ctx;
    fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
               "<svg xmlns=\"http://www.w3.org/2000/svg\" "
               "xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\" version=\"1.1\" "
               "width=\"%dpx\" height=\"%dpx\" viewBox=\"0 0 %d %d\">\n",
            d->width, d->height, d->width, d->height);
    if (d->background[3]) {
        fprintf(f, "<rect x=\"0\" y=\"0\" width=\"%d\" height=\"%d\"", d->width, d->height);
        colour_attr(f, "fill", d->background);
        fputs("/>\n", f);
    }
    for (int L = 0; L < PNPR_LAYER_COUNT_; L++) {
        size_t prev = SIZE_MAX, group = 0;
        for (size_t i = 0; i < d->count; i++) {
            if (d->layer[i] != L || (d->flags[i] & PNPR_PATH_SUBPATH)) continue;
            if (prev == SIZE_MAX)
                fprintf(f, "<g id=\"%s\" inkscape:groupmode=\"layer\" inkscape:label=\"%s\" stroke-linecap=\"butt\" "
                           "stroke-linejoin=\"round\">\n",
                        pnpr_drawing_layer_name((pnpr_drawing_layer)L), pnpr_drawing_layer_name((pnpr_drawing_layer)L));
            if (d->flags[i] & PNPR_PATH_FILL) { /* filled areas carry their own colour */
                if (prev != SIZE_MAX && !(d->flags[prev] & PNPR_PATH_FILL)) fputs("</g>\n", f);
                write_fill(f, d, i);
                prev = i;
                continue;
            }
            if (prev == SIZE_MAX || (d->flags[prev] & PNPR_PATH_FILL) || !same_run(d, prev, i)) {
                if (prev != SIZE_MAX && !(d->flags[prev] & PNPR_PATH_FILL)) fputs("</g>\n", f);
                open_run(f, d, i);
                group = i;
            }
            write_path(f, d, i, group);
            prev = i;
        }
        if (prev != SIZE_MAX) fputs((d->flags[prev] & PNPR_PATH_FILL) ? "</g>\n" : "</g>\n</g>\n", f);
    }
    fputs("</svg>\n", f);
    return ferror(f) != 0;
}

pnpr_status pnpr_drawing_write_svg(const pnpr_drawing *d, const char *path, pnpr_error *err)
{
    if (!d || !path || d->width <= 0 || d->height <= 0)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "svg: no drawing or a drawing of size %dx%d",
                              d ? d->width : 0, d ? d->height : 0);
    return pnpr_output_write(path, print_svg, d, err);
}
