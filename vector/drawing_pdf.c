/* PDF writer of vector drawings through cairo (include/pointnpr/drawing.h): one page of
 * width x height CSS pixels (0.75 pt each), the drawing's paths in order, each with its width and
 * colour; disks for dots. The bytes go through pnpr_output (temporary + rename). */
#include <pointnpr/drawing.h>
#include <pointnpr/output.h>

#ifdef PNPR_HAVE_CAIRO
#include <cairo-pdf.h>
#include <cairo.h>

#include <math.h>

static cairo_status_t pdf_sink(void *closure, const unsigned char *data, unsigned int length)
{
    return pnpr_output_sink(closure, data, length) ? CAIRO_STATUS_WRITE_ERROR : CAIRO_STATUS_SUCCESS;
}

static void set_colour(cairo_t *cr, const uint8_t *c)
{
    cairo_set_source_rgba(cr, c[0] / 255.0, c[1] / 255.0, c[2] / 255.0, c[3] / 255.0);
}

static void add_subpath(cairo_t *cr, const pnpr_drawing *d, size_t i)
{
    size_t a = d->offset[i], b = d->offset[i + 1];
    cairo_move_to(cr, d->xy[2 * a], d->xy[2 * a + 1]);
    for (size_t v = a + 1; v < b; v++) cairo_line_to(cr, d->xy[2 * v], d->xy[2 * v + 1]);
    if (d->flags[i] & PNPR_PATH_CLOSED) cairo_close_path(cr);
}

/* Draws path i (a filled area with the subpaths after it); returns the index after it. */
static size_t draw_path(cairo_t *cr, const pnpr_drawing *d, size_t i)
{
    size_t a = d->offset[i];
    set_colour(cr, d->rgba + 4 * i);
    if (d->flags[i] & PNPR_PATH_FILL) {
        cairo_new_path(cr);
        size_t j = i;
        do add_subpath(cr, d, j++); while (j < d->count && (d->flags[j] & PNPR_PATH_SUBPATH));
        cairo_set_fill_rule(cr, CAIRO_FILL_RULE_EVEN_ODD);
        cairo_fill(cr);
        return j;
    }
    if (d->flags[i] & PNPR_PATH_DOT) {
        cairo_new_path(cr);
        cairo_arc(cr, d->xy[2 * a], d->xy[2 * a + 1], 0.5 * d->stroke_width[i], 0, 6.283185307179586);
        cairo_fill(cr);
        return i + 1;
    }
    cairo_set_line_width(cr, d->stroke_width[i]);
    cairo_new_path(cr);
    add_subpath(cr, d, i);
    cairo_stroke(cr);
    return i + 1;
}

static pnpr_status draw_pdf(const pnpr_drawing *d, pnpr_output *out)
{
    cairo_surface_t *s = cairo_pdf_surface_create_for_stream(pdf_sink, out, 0.75 * d->width, 0.75 * d->height);
    cairo_t *cr = cairo_create(s);
    cairo_scale(cr, 0.75, 0.75);
    if (d->background[3]) {
        set_colour(cr, d->background);
        cairo_paint(cr);
    }
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    for (int L = 0; L < PNPR_LAYER_COUNT_; L++)
        for (size_t i = 0; i < d->count;)
            i = d->layer[i] == L && !(d->flags[i] & PNPR_PATH_SUBPATH) ? draw_path(cr, d, i) : i + 1;
    cairo_status_t cs = cairo_status(cr);
    cairo_destroy(cr);
    cairo_surface_finish(s);
    if (cs == CAIRO_STATUS_SUCCESS) cs = cairo_surface_status(s);
    cairo_surface_destroy(s);
    if (cs == CAIRO_STATUS_SUCCESS) return PNPR_OK;
    return cs == CAIRO_STATUS_WRITE_ERROR ? PNPR_ERR_IO : cs == CAIRO_STATUS_NO_MEMORY ? PNPR_ERR_OUT_OF_MEMORY
                                                                                        : PNPR_ERR_UNSUPPORTED;
}

pnpr_status pnpr_drawing_write_pdf(const pnpr_drawing *d, const char *path, pnpr_error *err)
{
    if (!d || !path || d->width <= 0 || d->height <= 0)
        return pnpr_error_set(err, PNPR_ERR_INVALID_ARGUMENT, "pdf: no drawing or a drawing of size %dx%d",
                              d ? d->width : 0, d ? d->height : 0);
    pnpr_output out;
    pnpr_status st = pnpr_output_open(&out, path, err);
    if (st != PNPR_OK) return st;
    st = draw_pdf(d, &out);
    if (st != PNPR_OK && st != PNPR_ERR_IO) pnpr_error_set(err, st, "%s: cairo could not write the PDF", path);
    return pnpr_output_close(&out, st, err);
}

#else

pnpr_status pnpr_drawing_write_pdf(const pnpr_drawing *d, const char *path, pnpr_error *err)
{
    (void)d;
    return pnpr_error_set(err, PNPR_ERR_UNSUPPORTED,
                          "%s: PDF output needs cairo; this build has none (packaging/install-deps.sh installs libcairo2-dev)",
                          path ? path : "pdf");
}

#endif
