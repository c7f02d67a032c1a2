#version 330 core
// Outlines, step 1 (docs/rendering.md, "Silhouettes and contours"): closes sampling holes in the
// visibility mask's per-pixel surface info (x = eye distance; y = the mask disk's depth extent:
// its radius over |cos| of the normal to the view ray, 0 = no surface; z = its radius).
// Along each of 8 directions a march looks for a surface nearer than the pixel by more than
// u_jump times the smaller depth extent of the two (an empty pixel: any surface), at most u_reach
// px (u_surface_reach from a pixel that shows a surface). The pixel is closed
//   - as a hole when all 8 directions meet one within u_hole of its projected disk radii;
//   - as a slit between scan lines (an empty pixel only) when at least 3 of the 4 opposite pairs
//     meet, on both sides, surfaces that face the eye (depth extent at most 2.5 radii) at about
//     the same depth (within u_jump extents, plus the same per disk radius of the gap): the rings
//     of a rotating scanner leave such slits; the sides of a gap between two objects are seen at
//     grazing angles and stay open.
// A closed pixel takes the mean info of the surfaces that close it; every other pixel keeps its
// own. Gaps open on one side (between two legs, a notch) are not closed: their outlines are real.
uniform sampler2D u_info;
uniform int u_reach;      // longest march in pixels
uniform float u_jump;     // depth jump in depth extents
uniform float u_hole;     // largest hole in projected disk radii
uniform float u_ppu;      // pixels per world unit at eye distance 1 (orthographic: at any distance)
uniform int u_ortho;
uniform int u_surface_reach; // longest march from a pixel that shows a surface (see-through holes)
uniform sampler2D u_cover;   // coarse coverage (edge_cover.frag): blocks of 2^u_skip_level px
uniform int u_skip_level;    // its 3x3 texels around a pixel span at least u_reach px: nothing
                             // covered there, nothing closes an empty pixel (0 = no shortcut)
out vec4 o_info;      // eye distance, depth extent, radius (holes: the mean of their closers), coverage

float radius_px(vec3 s)
{
    return s.z * u_ppu / (u_ortho != 0 ? 1.0 : max(s.x, 1e-6));
}

ivec2 direction(int d)
{
    // pairs of opposite directions: (0, 1), (2, 3), (4, 5), (6, 7)
    const ivec2 dirs[8] = ivec2[8](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1),
                                   ivec2(1, 1), ivec2(-1, -1), ivec2(1, -1), ivec2(-1, 1));
    return dirs[d];
}

// The first surface nearer than (z, extent) along direction d within reach: its info and distance
// (distance 0: none).
vec4 march(ivec2 p, ivec2 size, int d, int reach, float z, float extent)
{
    ivec2 step = direction(d);
    float unit = d >= 4 ? 1.41421356 : 1.0;
    for (int s = 1; s <= reach; s++) {
        ivec2 q = p + step * s;
        if (q.x < 0 || q.y < 0 || q.x >= size.x || q.y >= size.y)
            break;
        vec3 v = texelFetch(u_info, q, 0).xyz;
        if (v.y > 0.0 && v.x < z - u_jump * min(v.y, extent))
            return vec4(v, float(s) * unit);
    }
    return vec4(0.0);
}

bool slit_side(vec4 a, vec4 b)
{
    if (a.w <= 0.0 || b.w <= 0.0 || a.y > 2.5 * a.z || b.y > 2.5 * b.z)
        return false;
    float gap = (a.w + b.w) / max(min(radius_px(a.xyz), radius_px(b.xyz)), 0.5);
    return abs(a.x - b.x) <= u_jump * min(a.y, b.y) * (1.0 + gap);
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(u_info, 0);
    vec3 me = texelFetch(u_info, p, 0).xyz;
    bool empty = me.y <= 0.0;
    float z = empty ? 3.0e38 : me.x;
    float extent = empty ? 3.0e38 : me.y;
    if (empty && u_skip_level > 0) {
        ivec2 b = p >> u_skip_level, bs = textureSize(u_cover, 0);
        float cover = 0.0;
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++)
                cover += texelFetch(u_cover, clamp(b + ivec2(dx, dy), ivec2(0), bs - 1), 0).r;
        if (cover <= 0.0) {
            o_info = vec4(0.0);
            return;
        }
    }
    int reach = empty ? u_reach : min(u_reach, u_surface_reach);
    vec3 hole_sum = vec3(0.0), slit_sum = vec3(0.0);
    bool hole = true;
    int slit_pairs = 0, failed_pairs = 0;
    for (int pair = 0; pair < 4 && (hole || failed_pairs < 2); pair++) {
        vec4 a = march(p, size, 2 * pair, reach, z, extent);
        if (a.w <= 0.0) { // neither a hole nor this pair of a slit: the opposite side is not needed
            hole = false;
            failed_pairs++;
            if (!empty)
                break; // a surface pixel is only ever closed as a hole
            continue;
        }
        vec4 b = march(p, size, 2 * pair + 1, reach, z, extent);
        hole = hole && a.w > 0.0 && b.w > 0.0 && a.w <= u_hole * radius_px(a.xyz) && b.w <= u_hole * radius_px(b.xyz);
        hole_sum += a.xyz + b.xyz;
        if (empty && slit_side(a, b)) {
            slit_pairs++;
            slit_sum += 0.5 * (a.xyz + b.xyz);
        } else {
            failed_pairs++;
        }
        if (!hole && !empty)
            break;
    }
    if (hole && failed_pairs + slit_pairs == 4)
        o_info = vec4(hole_sum * 0.125, 1.0);
    else if (slit_pairs >= 3)
        o_info = vec4(slit_sum / float(slit_pairs), 1.0);
    else
        o_info = vec4(me, empty ? 0.0 : 1.0);
}
