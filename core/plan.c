/* The stage planner (include/pointnpr/plan.h). */
#include <pointnpr/brush.h>
#include <pointnpr/features.h>
#include <pointnpr/plan.h>

#include <string.h>

static void need(pnpr_plan *p, uint32_t bit, const char *why)
{
    int b = 0;
    while ((1u << b) != bit) b++;
    if (!(p->needed & bit)) p->why[b] = why;
    p->needed |= bit;
}

int pnpr_plan_cloud_has(const pnpr_cloud *c, uint32_t want)
{
    if (!c) return 0;
    if ((want & (PNPR_WANT_NORMALS | PNPR_WANT_NORMALS_ANY)) && !c->normal) return 0;
    if ((want & PNPR_WANT_DEGREE) && !pnpr_cloud_find_property(c, PNPR_PROP_FEATURE_DEGREE)) return 0;
    if (want & (PNPR_WANT_CLASSES | PNPR_WANT_DITHER)) {
        static const char *const names[] = {PNPR_PROP_FEATURE_CLASS, PNPR_PROP_FEATURE_DIR_X, PNPR_PROP_FEATURE_DIR_Y, PNPR_PROP_FEATURE_DIR_Z};
        for (int i = 0; i < 4; i++)
            if (!pnpr_cloud_find_property(c, names[i])) return 0;
    }
    return 1;
}

/* What each style needs (PointWorks section 5; docs/rendering.md). */
static void style_needs(pnpr_plan *p, pnpr_style s, pnpr_sketch_variant v, int colours, int labels)
{
    switch (s) {
    case PNPR_STYLE_SKETCHY:
        need(p, PNPR_WANT_CLASSES, "sketchy draws directional points as strokes along their direction");
        if (v == PNPR_SKETCH_ALL) need(p, PNPR_WANT_DITHER, "sketchy variant c draws dithering points as hatches");
        break;
    case PNPR_STYLE_STIPPLE:
        need(p, PNPR_WANT_DITHER, "stipple draws dithering and feature points as dots");
        break;
    case PNPR_STYLE_PAINTERLY:
        need(p, PNPR_WANT_DEGREE, "painterly sorts points into feature-degree bins");
        need(p, PNPR_WANT_CLASSES, "painterly puts directional strokes on top");
        break;
    case PNPR_STYLE_BRUSH:
        p->brush = 1;
        p->brush_why = "brush sizes its splats from kNN distances and fits normals per colour cluster";
        break;
    case PNPR_STYLE_HIERARCHY:
        p->hierarchy = 1;
        p->hierarchy_why = labels ? "hierarchy builds its sphere tree over the input's segment labels (regions) and their merges"
                                  : colours ? "hierarchy builds its sphere tree: leaf spheres, JSEG regions, their merges"
                                            : "hierarchy builds its sphere tree: leaf spheres, geometric regions (no colours), their merges";
        break;
    case PNPR_STYLE_LINES:
        p->lines = 1;
        p->lines_why = "the lines style draws them";
        break;
    case PNPR_STYLE_CARTOON:
        if (labels) {
            p->segments = PNPR_PLAN_SEGMENTS_INPUT;
            p->segments_why = "the input carries segment labels: cartoon fills each with its mean colour";
        } else if (colours) {
            p->segments = PNPR_PLAN_SEGMENTS_JSEG;
            p->segments_why = "cartoon fills each colour segment with its mean colour";
        } else {
            p->segments = PNPR_PLAN_SEGMENTS_SHADE;
            p->segments_why = "no colours: cartoon draws bands of the key light's tone";
            need(p, PNPR_WANT_NORMALS_ANY, "cartoon shades a colourless cloud from its normals");
        }
        break;
    default:
        break;
    }
}

pnpr_status pnpr_plan_make(const pnpr_plan_request *req, const pnpr_cloud *cloud, pnpr_plan *r_plan)
{
    if (!req || !r_plan) return PNPR_ERR_INVALID_ARGUMENT;
    memset(r_plan, 0, sizeof *r_plan);
    if ((req->styles >> PNPR_STYLE_COUNT_) != 0 || (unsigned)req->sketch_variant >= PNPR_SKETCH_COUNT_ ||
        req->outline < -1 || req->outline > 1 || (req->want & ~(uint32_t)(PNPR_WANT_ALL | PNPR_WANT_NORMALS_ANY)))
        return PNPR_ERR_INVALID_ARGUMENT;
    pnpr_plan *p = r_plan;
    int colours = !cloud || cloud->rgb, labels = cloud && cloud->label;
    int outlines = 0;
    for (int s = 0; s < PNPR_STYLE_COUNT_; s++) {
        if (!(req->styles & (1u << s))) continue;
        style_needs(p, (pnpr_style)s, req->sketch_variant, colours, labels);
        outlines |= req->outline > 0 || (req->outline == 0 && pnpr_style_outline_default((pnpr_style)s, NULL));
        if (!colours && (s == PNPR_STYLE_POINTS || s == PNPR_STYLE_PAINTERLY))
            need(p, PNPR_WANT_NORMALS_ANY, "no colours: the points are shaded by a key light on their normals");
    }
    if (outlines) need(p, PNPR_WANT_NORMALS_ANY, "outlines weigh depth jumps by the surface's slant (normals)");
    if (req->lines && !p->lines) { p->lines = 1; p->lines_why = "requested"; }
    if (p->lines) need(p, PNPR_WANT_CLASSES, "profile lines connect directional points along their directions");
    for (int b = 0; b < 5; b++)
        if (req->want & (1u << b)) need(p, 1u << b, "requested");
    /* wants imply their prerequisites */
    if (p->needed & PNPR_WANT_DITHER) need(p, PNPR_WANT_CLASSES, "dithering runs over the non-feature points");
    if (p->needed & PNPR_WANT_CLASSES) need(p, PNPR_WANT_DEGREE, "feature points are those above the degree threshold");
    /* what the cloud carries is reused */
    const uint32_t normal_bits = PNPR_WANT_NORMALS | PNPR_WANT_NORMALS_ANY;
    uint32_t features = p->needed & ~normal_bits;
    p->reused_features = features && pnpr_plan_cloud_has(cloud, features);
    p->reused_normals = cloud && cloud->normal;
    if (p->brush && pnpr_brush_cloud_ready(cloud)) { p->brush = 0; p->brush_why = NULL; }
    p->want = p->needed;
    if (p->reused_features) p->want &= normal_bits;
    if (p->reused_normals) p->want &= ~normal_bits;
    /* any orientation is enough when oriented normals come anyway */
    if (p->want & PNPR_WANT_NORMALS) p->want &= ~(uint32_t)PNPR_WANT_NORMALS_ANY;
    return PNPR_OK;
}
