#version 330 core
// Outlines, step 2, on the hole-closed info (edge_fill.frag):
//   x, y: the far side of a contour must be far over more than one pixel: each surface pixel
//         takes the nearest surface of its 3x3 neighbourhood (a minimum filter on eye distance,
//         the depth extent comes with it); pixels without a surface stay without;
//   z:    the distance to the nearest pixel without a surface along the 8 directions (at most
//         u_limit px; the frame border is no such pixel);
//   w:    the inset (negative, -1 - inset: a speck, thick() below): the mask disks reach about
//         u_inset of their projected radius beyond the
//         outermost points; the silhouette is drawn that far inside the mask's boundary and the
//         overhang is erased (edge_ink.frag), at most u_inset_max px. The radius is the mean of
//         the 3x3 neighbourhood's disks (one disk's radius varies from point to point: a ragged
//         band).
uniform sampler2D u_filled;
uniform float u_ppu;      // pixels per world unit at eye distance 1
uniform int u_ortho;
uniform float u_inset;
uniform float u_inset_max;
uniform float u_limit;
uniform float u_width;   // the outline width (px)
uniform sampler2D u_cover; // coarse coverage of u_filled (edge_cover.frag), blocks of 2^u_skip_level px
uniform int u_skip_level;  // its 3x3 texels around a pixel span at least u_limit px: all covered,
                           // no empty pixel is that near (0 = no shortcut)
out vec4 o_info;

// the 8 march directions, the diagonals last (their steps are sqrt(2) px)
const ivec2 DIRS[8] = ivec2[8](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1),
                               ivec2(1, 1), ivec2(1, -1), ivec2(-1, 1), ivec2(-1, -1));

// Near a silhouette: is the surface here more than a speck? Some run of surface pixels from p
// (along one of 8 directions) must be longer than the ink band on both sides of a blob (inset and
// width twice, plus 2 px, at most 48 px); a lone disk or a few sparse disks fail it and get no
// silhouette of their own (an isolated point would otherwise be drawn as a ring).
bool thick(ivec2 p, ivec2 size, float dist, float inset)
{
    if (dist >= u_limit)
        return true; // no empty pixel near: not a silhouette pixel
    float need = min(2.0 * (inset + u_width) + 2.0, 48.0);
    for (int d = 0; d < 8; d++) {
        ivec2 step = DIRS[d];
        float unit = d >= 4 ? 1.41421356 : 1.0;
        int s = 1;
        for (; float(s) * unit < need; s++) {
            ivec2 q = clamp(p + step * s, ivec2(0), size - 1);
            if (texelFetch(u_filled, q, 0).y <= 0.0)
                break;
        }
        if (float(s) * unit >= need)
            return true;
    }
    return false;
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(u_filled, 0);
    vec4 me = texelFetch(u_filled, p, 0);
    if (me.y <= 0.0) {
        o_info = vec4(0.0);
        return;
    }
    vec2 best = me.xy;
    float rsum = 0.0, rn = 0.0;
    for (int dy = -1; dy <= 1; dy++) {
        for (int dx = -1; dx <= 1; dx++) {
            vec3 v = texelFetch(u_filled, clamp(p + ivec2(dx, dy), ivec2(0), size - 1), 0).xyz;
            if (v.y <= 0.0)
                continue;
            if (v.x < best.x)
                best = v.xy;
            rsum += v.z;
            rn += 1.0;
        }
    }
    float dist = u_limit;
    int steps = int(u_limit);
    if (u_skip_level > 0) {
        ivec2 b = p >> u_skip_level, bs = textureSize(u_cover, 0);
        float cover = 0.0;
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++)
                cover += texelFetch(u_cover, clamp(b + ivec2(dx, dy), ivec2(0), bs - 1), 0).g;
        if (cover >= 8.5)
            steps = 0;
    }
    for (int d = 0; d < 8; d++) {
        ivec2 step = DIRS[d];
        float unit = d >= 4 ? 1.41421356 : 1.0;
        for (int s = 1; s <= steps && float(s) * unit < dist; s++) {
            ivec2 q = p + step * s;
            if (q.x < 0 || q.y < 0 || q.x >= size.x || q.y >= size.y)
                break;
            if (texelFetch(u_filled, q, 0).y <= 0.0) {
                dist = float(s) * unit;
                break;
            }
        }
    }
    float r_px = rsum / rn * u_ppu / (u_ortho != 0 ? 1.0 : max(me.x, 1e-6));
    float inset = clamp(u_inset * r_px - 0.5, 0.0, u_inset_max);
    o_info = vec4(best, dist, thick(p, size, dist, inset) ? inset : -1.0 - inset);
}
