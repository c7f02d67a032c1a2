/* The stage planner (include/pointnpr/plan.h), known answers: what each style needs on coloured,
 * colourless and labelled clouds, outlines on/off, what a cloud that carries features reuses,
 * requested extras, bad requests. */
#include "testutil.h"

#include <pointnpr/features.h>
#include <pointnpr/plan.h>

#include <string.h>

static pnpr_plan plan_for(uint32_t styles, int outline, const pnpr_cloud *c)
{
    pnpr_plan_request req = {0};
    req.styles = styles;
    req.outline = outline;
    pnpr_plan p;
    CHECK_STATUS(pnpr_plan_make(&req, c, &p), PNPR_OK);
    return p;
}

#define S(x) (1u << PNPR_STYLE_##x)

static void test_styles(void)
{
    pnpr_cloud coloured = {0}, grey = {0};
    CHECK_STATUS(pnpr_cloud_alloc(&coloured, 4), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(&coloured), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc(&grey, 4), PNPR_OK);
    pnpr_plan p = plan_for(S(CARTOON), 0, &coloured);
    CHECK(p.segments == PNPR_PLAN_SEGMENTS_JSEG && p.want == PNPR_WANT_NORMALS_ANY && !p.lines);
    p = plan_for(S(CARTOON), -1, &coloured);
    CHECK(p.segments == PNPR_PLAN_SEGMENTS_JSEG && p.want == 0);
    p = plan_for(S(CARTOON), 0, &grey);
    CHECK(p.segments == PNPR_PLAN_SEGMENTS_SHADE && p.want == PNPR_WANT_NORMALS_ANY);
    CHECK_STATUS(pnpr_cloud_alloc_labels(&coloured), PNPR_OK);
    p = plan_for(S(CARTOON), -1, &coloured);
    CHECK(p.segments == PNPR_PLAN_SEGMENTS_INPUT && p.want == 0);
    p = plan_for(S(SKETCHY), 0, &coloured); /* variant c (zero), no outline by default */
    CHECK(p.want == (PNPR_WANT_DITHER | PNPR_WANT_CLASSES | PNPR_WANT_DEGREE));
    CHECK(p.why[3] != NULL && p.why[4] == NULL && p.segments == PNPR_PLAN_SEGMENTS_NONE);
    p = plan_for(S(SKETCHY), 1, &coloured); /* outline asked for: normals */
    CHECK(p.want == (PNPR_WANT_DITHER | PNPR_WANT_CLASSES | PNPR_WANT_DEGREE | PNPR_WANT_NORMALS_ANY) && p.why[4] != NULL);
    p = plan_for(S(STIPPLE), 0, &coloured); /* stipple draws no outline by default */
    CHECK(p.want == (PNPR_WANT_DITHER | PNPR_WANT_CLASSES | PNPR_WANT_DEGREE));
    p = plan_for(S(LINES), 0, &coloured);
    CHECK(p.lines && p.want == (PNPR_WANT_CLASSES | PNPR_WANT_DEGREE | PNPR_WANT_NORMALS_ANY));
    p = plan_for(S(POINTS), 0, &coloured);
    CHECK(p.want == 0 && !p.lines && p.segments == PNPR_PLAN_SEGMENTS_NONE);
    p = plan_for(S(POINTS), 0, &grey); /* colourless: shaded from normals */
    CHECK(p.want == PNPR_WANT_NORMALS_ANY);
    p = plan_for(S(PAINTERLY), 0, &coloured);
    CHECK(p.want == (PNPR_WANT_DEGREE | PNPR_WANT_CLASSES));
    p = plan_for(S(LINES) | S(SKETCHY), 0, NULL); /* unknown content: planned as coloured */
    CHECK(p.want == (PNPR_WANT_DITHER | PNPR_WANT_CLASSES | PNPR_WANT_DEGREE | PNPR_WANT_NORMALS_ANY) && p.lines);
    p = plan_for(0, 0, &coloured); /* nothing drawn: nothing planned */
    CHECK(p.want == 0 && p.needed == 0);
    pnpr_cloud_free(&coloured);
    pnpr_cloud_free(&grey);
}

static void test_reuse(void)
{
    pnpr_cloud c = {0};
    CHECK_STATUS(pnpr_test_cube(&c, 1.0, 0.1, 0.0, NULL, 1), PNPR_OK);
    CHECK_STATUS(pnpr_cloud_alloc_rgb(&c), PNPR_OK);
    pnpr_features_options fo = {0};
    fo.want = PNPR_WANT_DITHER;
    CHECK_STATUS(pnpr_compute_features(&c, &fo, NULL), PNPR_OK);
    CHECK(c.normal == NULL); /* dithering needs no stored normals */
    CHECK(pnpr_plan_cloud_has(&c, PNPR_WANT_DITHER) && !pnpr_plan_cloud_has(&c, PNPR_WANT_NORMALS_ANY));
    pnpr_plan p = plan_for(S(SKETCHY), 1, &c); /* with an outline */
    CHECK(p.reused_features && !p.reused_normals && p.want == PNPR_WANT_NORMALS_ANY);
    /* normals without orientation: the features run stores them and orients nothing */
    fo.want = p.want;
    pnpr_features_stats st;
    CHECK_STATUS(pnpr_compute_features(&c, &fo, &st), PNPR_OK);
    CHECK(c.normal != NULL && st.runs[PNPR_STAGE_ORIENT] == 0 && st.runs[PNPR_STAGE_NORMALS] == 1);
    p = plan_for(S(SKETCHY), 1, &c);
    CHECK(p.want == 0 && p.reused_features && p.reused_normals);
    /* a command's own request: oriented normals, which cover any orientation */
    pnpr_plan_request req = {0};
    req.want = PNPR_WANT_NORMALS;
    req.styles = S(LINES);
    pnpr_cloud none = {0};
    CHECK_STATUS(pnpr_plan_make(&req, &none, &p), PNPR_OK);
    CHECK(p.want == (PNPR_WANT_NORMALS | PNPR_WANT_CLASSES | PNPR_WANT_DEGREE) && p.why[0] != NULL);
    pnpr_cloud_free(&c);
}

static void test_bad(void)
{
    pnpr_plan_request req = {0};
    pnpr_plan p;
    req.styles = 1u << PNPR_STYLE_COUNT_;
    CHECK_STATUS(pnpr_plan_make(&req, NULL, &p), PNPR_ERR_INVALID_ARGUMENT);
    req.styles = 0;
    req.sketch_variant = PNPR_SKETCH_COUNT_;
    CHECK_STATUS(pnpr_plan_make(&req, NULL, &p), PNPR_ERR_INVALID_ARGUMENT);
    req.sketch_variant = 0;
    req.outline = 2;
    CHECK_STATUS(pnpr_plan_make(&req, NULL, &p), PNPR_ERR_INVALID_ARGUMENT);
    req.outline = 0;
    req.want = 64;
    CHECK_STATUS(pnpr_plan_make(&req, NULL, &p), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_plan_make(NULL, NULL, &p), PNPR_ERR_INVALID_ARGUMENT);
}

static void test_style_names(void)
{
    pnpr_style s = PNPR_STYLE_POINTS;
    CHECK_STATUS(pnpr_style_from_name("Sketchy", &s), PNPR_OK);
    CHECK(s == PNPR_STYLE_SKETCHY);
    CHECK_STATUS(pnpr_style_from_name("CARTOON", &s), PNPR_OK);
    CHECK(s == PNPR_STYLE_CARTOON);
    CHECK_STATUS(pnpr_style_from_name("cartoons", &s), PNPR_ERR_NOT_FOUND);
    CHECK_STATUS(pnpr_style_from_name("", &s), PNPR_ERR_NOT_FOUND);
    for (int i = 0; i < PNPR_STYLE_COUNT_; i++) { /* every name reads back as its style */
        CHECK_STATUS(pnpr_style_from_name(pnpr_style_name((pnpr_style)i), &s), PNPR_OK);
        CHECK(s == (pnpr_style)i);
    }
}

int main(void)
{
    test_style_names();
    test_styles();
    test_reuse();
    test_bad();
    return pnpr_test_finish("test_plan");
}
