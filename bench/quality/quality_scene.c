/* The analytic scene of `pointnpr bench quality`: presets, true crease edges, ray casting,
 * surface colours (docs/quality.md). Buildings are convex prisms (a box, or a box with a gabled
 * roof on top), so a ray meets one by clipping against its planes. */
#include "quality.h"

#include <math.h>
#include <string.h>

static const double QPI = 3.14159265358979323846;

static void set_rgb(uint8_t r[3], int a, int b, int c) { r[0] = (uint8_t)a; r[1] = (uint8_t)b; r[2] = (uint8_t)c; }

static void add_building(pnpr_quality_scene *s, double cx, double cy, double hx, double hy, double yaw,
                         double wall, double roof, const int wall_rgb[3], const int roof_rgb[3])
{
    if (s->building_count >= PNPR_QUALITY_MAX_BUILDINGS) return;
    pnpr_quality_building *b = &s->building[s->building_count++];
    b->centre[0] = cx; b->centre[1] = cy; b->half[0] = hx; b->half[1] = hy;
    b->yaw_deg = yaw; b->wall_height = wall; b->roof_height = roof;
    set_rgb(b->wall_rgb, wall_rgb[0], wall_rgb[1], wall_rgb[2]);
    set_rgb(b->roof_rgb, roof_rgb[0], roof_rgb[1], roof_rgb[2]);
}

static void add_tree(pnpr_quality_scene *s, double x, double y, double trunk_r, double trunk_h,
                     double crown_z, double crown_r)
{
    if (s->tree_count >= PNPR_QUALITY_MAX_TREES) return;
    pnpr_quality_tree *t = &s->tree[s->tree_count++];
    t->base[0] = x; t->base[1] = y; t->trunk_radius = trunk_r; t->trunk_height = trunk_h;
    t->crown_centre_z = crown_z; t->crown_radius = crown_r;
}

static void add_scanner(pnpr_quality_scene *s, double x, double y, double z)
{
    if (s->scanner_count >= PNPR_QUALITY_MAX_SCANNERS) return;
    double *p = s->scanner[s->scanner_count++];
    p[0] = x; p[1] = y; p[2] = z;
}

/* The sphere object shared by the house scene and the sphere-alone scene. */
static void add_ball(pnpr_quality_scene *s)
{
    pnpr_quality_sphere *b = &s->sphere[s->sphere_count++];
    b->centre[0] = -3; b->centre[1] = -7; b->centre[2] = 1.6;
    b->radius = 1.6;
    set_rgb(b->rgb, 70, 110, 190);
}

/* The house scene: a courtyard with three buildings, four trees and a ball, scanned as a survey
 * would: a tripod in front, a mast in the middle (18 m, sees every roof) and five masts (12 m)
 * along the courtyard's edges, placed so that the whole ground rectangle is sampled up to its
 * border (the data's outline is the true one, within a sample spacing) while the buildings still
 * cast occlusion shadows that no station sees into (east of the house and of the shed). */
static void house_scene(pnpr_quality_scene *s)
{
    static const int sandstone[3] = {205, 190, 165}, slate[3] = {95, 95, 102}, plaster[3] = {232, 224, 206},
                     tiles[3] = {165, 72, 52}, timber[3] = {176, 150, 112}, dark_tiles[3] = {84, 88, 96};
    s->has_ground = 1;
    s->ground_min[0] = -27; s->ground_min[1] = -21;
    s->ground_max[0] = 27; s->ground_max[1] = 23;
    add_building(s, -14, 12, 7, 4.5, 0, 7, 0, sandstone, slate);          /* flat-roofed block */
    add_building(s, 9.5, 11, 6.5, 3.8, 28, 4.2, 2.8, plaster, tiles);    /* rotated gabled house */
    add_building(s, 19, -6, 3.2, 2.3, -20, 2.6, 1.7, timber, dark_tiles); /* rotated gabled shed */
    add_tree(s, -23, -7, 0.22, 3.2, 4.6, 2.4);
    add_tree(s, 23, 15, 0.25, 3.5, 5.2, 2.8);
    add_tree(s, -3.5, 19, 0.2, 3.0, 4.2, 2.0);
    add_tree(s, 11, -14, 0.2, 2.8, 3.9, 1.9);
    add_ball(s);
    add_scanner(s, 1, -17, 1.8);   /* tripod */
    add_scanner(s, -2, 0, 18);     /* mast (a scanner on a lift) */
    add_scanner(s, -24, -18, 12);  /* masts (12 m) along the edges: south-west, south, north, */
    add_scanner(s, 10, -19, 12);   /* north-east and north-west; none east of the house and the */
    add_scanner(s, 7, 21, 12);     /* shed, so that their lee stays in shadow */
    add_scanner(s, -1, 22, 12);
    add_scanner(s, -25, 19, 12);
    s->elevation_min_deg = -87;
    s->elevation_max_deg = 60;
}

/* The ball alone, scanned from six positions around it and one above. */
static void sphere_scene(pnpr_quality_scene *s)
{
    add_ball(s);
    const double *c = s->sphere[0].centre;
    for (int k = 0; k < 6; k++) {
        double a = 2 * QPI * k / 6.0 + 0.3;
        add_scanner(s, c[0] + 12 * cos(a), c[1] + 12 * sin(a), k % 2 ? 1.8 : 7.5);
    }
    add_scanner(s, c[0] + 0.5, c[1] - 0.5, c[2] + 12);
    s->elevation_min_deg = -90;
    s->elevation_max_deg = 60;
}

/* The house scene's angular step (degrees) of a preset: small ~150k points, full ~1M, sparse a
 * quarter of small. */
static double house_step(pnpr_quality_preset preset)
{
    switch (preset) {
    case PNPR_QUALITY_PRESET_FULL: return 0.255;
    case PNPR_QUALITY_PRESET_SPARSE: return 1.3;
    default: return 0.65;
    }
}

void pnpr_quality_scene_init(pnpr_quality_scene *s, pnpr_quality_preset preset)
{
    memset(s, 0, sizeof *s);
    s->offset[0] = 512345.678; s->offset[1] = 5403210.5; s->offset[2] = 310.25;
    s->max_range = 90;
    s->range_sigma = 0.008;
    s->foliage_depth = 0.25;
    s->seed = 20240611;
    if (preset == PNPR_QUALITY_PRESET_BALL) {
        sphere_scene(s);
        s->step_deg = 0.2;
    } else {
        house_scene(s);
        s->step_deg = house_step(preset);
    }
    pnpr_quality_scene_edges(s);
}

/* ---- edges ---------------------------------------------------------------------------------- */

/* Building-local (x along the ridge, y across, z up) -> scene coordinates. */
static void to_scene(const pnpr_quality_building *b, double lx, double ly, double z, double r[3])
{
    double a = b->yaw_deg * QPI / 180, c = cos(a), s = sin(a);
    r[0] = b->centre[0] + c * lx - s * ly;
    r[1] = b->centre[1] + s * lx + c * ly;
    r[2] = z;
}

static void push_edge(pnpr_quality_scene *s, const pnpr_quality_building *b, const double p[3],
                      const double q[3], pnpr_quality_edge_kind kind, double angle)
{
    double limit = s->crease_angle_deg > 0 ? s->crease_angle_deg : 20;
    if (angle < limit || s->edge_count >= PNPR_QUALITY_MAX_EDGES) return;
    pnpr_quality_segment *e = &s->edge[s->edge_count++];
    to_scene(b, p[0], p[1], p[2], e->a);
    to_scene(b, q[0], q[1], q[2], e->b);
    e->kind = kind;
    e->angle_deg = angle;
}

static void building_edges(pnpr_quality_scene *s, const pnpr_quality_building *b)
{
    const double hx = b->half[0], hy = b->half[1], H = b->wall_height, R = b->roof_height;
    const double cx[4] = {-hx, hx, hx, -hx}, cy[4] = {-hy, -hy, hy, hy}; /* counter-clockwise */
    const double pitch = atan2(R, hy) * 180 / QPI;
    for (int k = 0; k < 4; k++) {
        int m = (k + 1) % 4;
        double p0[3] = {cx[k], cy[k], 0}, p1[3] = {cx[k], cy[k], H}, q0[3] = {cx[m], cy[m], 0}, q1[3] = {cx[m], cy[m], H};
        push_edge(s, b, p0, p1, PNPR_QUALITY_EDGE_CORNER, 90);
        push_edge(s, b, p0, q0, PNPR_QUALITY_EDGE_FOOT, 90);
        if (!(R > 0)) push_edge(s, b, p1, q1, PNPR_QUALITY_EDGE_EAVE, 90);
        else if (k == 0 || k == 2) push_edge(s, b, p1, q1, PNPR_QUALITY_EDGE_EAVE, 90 - pitch); /* long walls */
        else { /* gable ends: two rakes up to the ridge */
            double top[3] = {cx[k], 0, H + R};
            push_edge(s, b, p1, top, PNPR_QUALITY_EDGE_RAKE, 90);
            push_edge(s, b, q1, top, PNPR_QUALITY_EDGE_RAKE, 90);
        }
    }
    if (R > 0) {
        double r0[3] = {-hx, 0, H + R}, r1[3] = {hx, 0, H + R};
        push_edge(s, b, r0, r1, PNPR_QUALITY_EDGE_RIDGE, 2 * pitch);
    }
}

void pnpr_quality_scene_edges(pnpr_quality_scene *s)
{
    s->edge_count = 0;
    for (int i = 0; i < s->building_count; i++) building_edges(s, &s->building[i]);
}

/* ---- ray casting ---------------------------------------------------------------------------- */

enum { MAX_PLANES = 7 };

/* The planes n . x <= d of building b in its local frame; returns their number. Planes 0-3 are
 * walls, 4 the floor, 5.. the roof. */
static int building_planes(const pnpr_quality_building *b, double n[MAX_PLANES][3], double d[MAX_PLANES])
{
    const double hx = b->half[0], hy = b->half[1], H = b->wall_height, R = b->roof_height;
    static const double axes[5][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, -1}};
    const double off[5] = {hx, hx, hy, hy, 0};
    for (int i = 0; i < 5; i++) {
        memcpy(n[i], axes[i], sizeof axes[i]);
        d[i] = off[i];
    }
    if (!(R > 0)) {
        n[5][0] = 0; n[5][1] = 0; n[5][2] = 1; d[5] = H;
        return 6;
    }
    double k = hy > 0 ? R / hy : 0;
    for (int side = 0; side < 2; side++) {
        n[5 + side][0] = 0; n[5 + side][1] = side ? -k : k; n[5 + side][2] = 1;
        d[5 + side] = H + R;
    }
    return 7;
}

/* Slab clipping of a ray (building-local) against the convex solid: the hit is where the ray
 * enters the last of the planes it enters, when that is before it leaves the first it leaves and
 * in front of the origin (an origin inside the solid gives no hit). */
static int clip_convex(const double n[][3], const double *d, int np, const double o[3], const double v[3],
                       double t_max, double *r_t, int *r_plane)
{
    double t_in = -INFINITY, t_out = t_max;
    int enter = -1;
    for (int i = 0; i < np; i++) {
        double den = n[i][0] * v[0] + n[i][1] * v[1] + n[i][2] * v[2];
        double num = d[i] - (n[i][0] * o[0] + n[i][1] * o[1] + n[i][2] * o[2]);
        if (fabs(den) < 1e-15) {
            if (num < 0) return 0; /* parallel and outside */
            continue;
        }
        double t = num / den;
        if (den < 0 && t > t_in) { t_in = t; enter = i; }
        else if (den > 0 && t < t_out) t_out = t;
    }
    if (enter < 0 || t_in > t_out || !(t_in > 1e-9)) return 0;
    *r_t = t_in;
    *r_plane = enter;
    return 1;
}

static int hit_building(const pnpr_quality_building *b, const double o[3], const double v[3], double t_max,
                        pnpr_quality_hit *h)
{
    double a = b->yaw_deg * QPI / 180, c = cos(a), s = sin(a);
    double px = o[0] - b->centre[0], py = o[1] - b->centre[1];
    double lo[3] = {c * px + s * py, -s * px + c * py, o[2]}, lv[3] = {c * v[0] + s * v[1], -s * v[0] + c * v[1], v[2]};
    double n[MAX_PLANES][3], d[MAX_PLANES], t;
    int np = building_planes(b, n, d), plane;
    if (!clip_convex((const double(*)[3])n, d, np, lo, lv, t_max, &t, &plane)) return 0;
    double *pn = n[plane], len = sqrt(pn[0] * pn[0] + pn[1] * pn[1] + pn[2] * pn[2]);
    h->t = t;
    h->normal[0] = (c * pn[0] - s * pn[1]) / len;
    h->normal[1] = (s * pn[0] + c * pn[1]) / len;
    h->normal[2] = pn[2] / len;
    h->kind = plane >= 5 ? PNPR_QUALITY_ROOF : PNPR_QUALITY_WALL;
    return 1;
}

static int hit_sphere(const double c[3], double r, const double o[3], const double v[3], double t_max, double *r_t)
{
    double oc[3] = {o[0] - c[0], o[1] - c[1], o[2] - c[2]};
    double b = oc[0] * v[0] + oc[1] * v[1] + oc[2] * v[2];
    double cc = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - r * r;
    double disc = b * b - cc;
    if (cc < 0 || !(disc >= 0)) return 0; /* inside, or missed */
    double t = -b - sqrt(disc);
    if (!(t > 1e-9) || t > t_max) return 0;
    *r_t = t;
    return 1;
}

/* The entering side of a vertical cylinder (trunk), between z = 0 and its height. */
static int hit_trunk(const pnpr_quality_tree *tr, const double o[3], const double v[3], double t_max, double *r_t)
{
    double ox = o[0] - tr->base[0], oy = o[1] - tr->base[1];
    double a = v[0] * v[0] + v[1] * v[1], b = ox * v[0] + oy * v[1];
    double cc = ox * ox + oy * oy - tr->trunk_radius * tr->trunk_radius;
    if (a < 1e-18 || cc < 0) return 0;
    double disc = b * b - a * cc;
    if (!(disc >= 0)) return 0;
    double t = (-b - sqrt(disc)) / a, z = o[2] + t * v[2];
    if (!(t > 1e-9) || t > t_max || z < 0 || z > tr->trunk_height) return 0;
    *r_t = t;
    return 1;
}

static void keep(pnpr_quality_hit *best, int *found, double t, pnpr_quality_kind kind, int index,
                 const double o[3], const double v[3], const double centre[3], int vertical)
{
    if (*found && t >= best->t) return;
    *found = 1;
    best->t = t;
    best->kind = kind;
    best->index = index;
    double p[3] = {o[0] + t * v[0], o[1] + t * v[1], o[2] + t * v[2]};
    double n[3] = {p[0] - centre[0], p[1] - centre[1], vertical ? 0 : p[2] - centre[2]};
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int a = 0; a < 3; a++) best->normal[a] = l > 0 ? n[a] / l : (a == 2);
}

static void hit_objects(const pnpr_quality_scene *s, const double o[3], const double v[3], double t_max,
                        pnpr_quality_hit *best, int *found)
{
    double t;
    for (int i = 0; i < s->building_count; i++) {
        pnpr_quality_hit h;
        if (hit_building(&s->building[i], o, v, *found ? best->t : t_max, &h) && (!*found || h.t < best->t)) {
            *best = h;
            best->index = i;
            *found = 1;
        }
    }
    for (int i = 0; i < s->tree_count; i++) {
        const pnpr_quality_tree *tr = &s->tree[i];
        double c[3] = {tr->base[0], tr->base[1], tr->crown_centre_z}, axis[3] = {tr->base[0], tr->base[1], 0};
        if (hit_sphere(c, tr->crown_radius, o, v, t_max, &t)) keep(best, found, t, PNPR_QUALITY_CROWN, i, o, v, c, 0);
        if (hit_trunk(tr, o, v, t_max, &t)) keep(best, found, t, PNPR_QUALITY_TRUNK, i, o, v, axis, 1);
    }
    for (int i = 0; i < s->sphere_count; i++)
        if (hit_sphere(s->sphere[i].centre, s->sphere[i].radius, o, v, t_max, &t))
            keep(best, found, t, PNPR_QUALITY_SPHERE, i, o, v, s->sphere[i].centre, 0);
}

int pnpr_quality_raycast(const pnpr_quality_scene *s, const double origin[3], const double dir[3],
                         double t_max, pnpr_quality_hit *r_hit)
{
    double l = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    if (!(l > 0) || !isfinite(l)) return 0;
    for (int a = 0; a < 3; a++)
        if (!isfinite(origin[a])) return 0;
    if (!(t_max > 0) || !isfinite(t_max)) t_max = INFINITY;
    double v[3] = {dir[0] / l, dir[1] / l, dir[2] / l};
    pnpr_quality_hit best;
    memset(&best, 0, sizeof best);
    int found = 0;
    if (s->has_ground && fabs(v[2]) > 1e-15) {
        double t = -origin[2] / v[2], x = origin[0] + t * v[0], y = origin[1] + t * v[1];
        if (t > 1e-9 && t <= t_max && x >= s->ground_min[0] && x <= s->ground_max[0] && y >= s->ground_min[1] &&
            y <= s->ground_max[1]) {
            found = 1;
            best.t = t;
            best.kind = PNPR_QUALITY_GROUND;
            best.normal[2] = v[2] < 0 ? 1 : -1;
        }
    }
    hit_objects(s, origin, v, t_max, &best, &found);
    if (found && r_hit) *r_hit = best;
    return found;
}

/* ---- colours -------------------------------------------------------------------------------- */

static uint8_t mixc(int a, int b, double t)
{
    double v = a + (b - a) * (t < 0 ? 0 : (t > 1 ? 1 : t));
    return (uint8_t)(v + 0.5);
}

void pnpr_quality_colour(const pnpr_quality_scene *s, const pnpr_quality_hit *hit, const double p[3], uint8_t rgb[3])
{
    switch (hit->kind) {
    case PNPR_QUALITY_GROUND: { /* grass: low-frequency patches of lush and dry green */
        double v = 0.5 + 0.3 * sin(0.21 * p[0] + 0.7) * cos(0.17 * p[1] + 1.3) + 0.2 * sin(0.05 * p[0] + 0.09 * p[1] + 2);
        rgb[0] = mixc(62, 132, v); rgb[1] = mixc(104, 158, v); rgb[2] = mixc(38, 64, v);
        break;
    }
    case PNPR_QUALITY_WALL: memcpy(rgb, s->building[hit->index].wall_rgb, 3); break;
    case PNPR_QUALITY_ROOF: memcpy(rgb, s->building[hit->index].roof_rgb, 3); break;
    case PNPR_QUALITY_TRUNK: set_rgb(rgb, 96, 72, 48); break;
    case PNPR_QUALITY_CROWN: { /* foliage: darker underneath */
        const pnpr_quality_tree *t = &s->tree[hit->index];
        double v = 0.5 + 0.5 * (p[2] - t->crown_centre_z) / (t->crown_radius > 0 ? t->crown_radius : 1);
        rgb[0] = mixc(34, 78, v); rgb[1] = mixc(70, 128, v); rgb[2] = mixc(30, 52, v);
        break;
    }
    case PNPR_QUALITY_SPHERE: memcpy(rgb, s->sphere[hit->index].rgb, 3); break;
    default: set_rgb(rgb, 0, 0, 0); break;
    }
}
