#version 330 core
// Outlines, step 1 (docs/rendering.md, "Silhouettes and contours"): closes sampling holes in the
// visibility mask's per-pixel surface info (x = eye distance; y = the mask disk's depth extent:
// its radius over |cos| of the normal to the view ray, 0 = no surface; z = its radius). A pixel
// is a hole when, in all 8 directions, the march meets a surface nearer than itself by more than
// u_jump times the smaller depth extent of the two (an empty pixel: any surface) within u_hole
// of that surface's projected disk radii (at most u_reach px). A hole takes the
// mean info of the 8 surfaces that close it; every other pixel keeps its own. Narrow gaps open on
// one side (between two legs, a notch) are not closed: their outlines are real.
uniform sampler2D u_info;
uniform int u_reach;      // longest march in pixels
uniform float u_jump;     // depth jump in depth extents
uniform float u_hole;     // largest hole in projected disk radii
uniform float u_ppu;      // pixels per world unit at eye distance 1 (orthographic: at any distance)
uniform int u_ortho;
uniform int u_surface_reach; // longest march from a pixel that shows a surface (see-through holes)
uniform int u_skip_level;    // a mipmap level of u_info whose 3x3 texels around a pixel span at
                             // least u_reach px (w = covered fraction): nothing covered there,
                             // nothing closes an empty pixel (0 = no shortcut)
out vec4 o_info;      // eye distance, depth extent, radius (holes: the mean of their closers), coverage

float radius_px(vec3 s)
{
    return s.z * u_ppu / (u_ortho != 0 ? 1.0 : max(s.x, 1e-6));
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(u_info, 0);
    vec3 me = texelFetch(u_info, p, 0).xyz;
    float z = me.y > 0.0 ? me.x : 3.0e38;
    float extent = me.y > 0.0 ? me.y : 3.0e38;
    vec3 sum = vec3(0.0);
    if (me.y <= 0.0 && u_skip_level > 0) {
        ivec2 b = p >> u_skip_level, bs = textureSize(u_info, u_skip_level);
        float cover = 0.0;
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++)
                cover += texelFetch(u_info, clamp(b + ivec2(dx, dy), ivec2(0), bs - 1), u_skip_level).w;
        if (cover <= 0.0) {
            o_info = vec4(0.0);
            return;
        }
    }
    int reach = me.y > 0.0 ? min(u_reach, u_surface_reach) : u_reach;
    for (int d = 0; d < 8; d++) {
        ivec2 step = ivec2(d == 0 || d == 4 || d == 5 ? 1 : d == 1 || d == 6 || d == 7 ? -1 : 0,
                           d == 2 || d == 4 || d == 6 ? 1 : d == 3 || d == 5 || d == 7 ? -1 : 0);
        float unit = d >= 4 ? 1.41421356 : 1.0;
        bool closed = false;
        for (int s = 1; s <= reach; s++) {
            ivec2 q = p + step * s;
            if (q.x < 0 || q.y < 0 || q.x >= size.x || q.y >= size.y)
                break;
            vec3 v = texelFetch(u_info, q, 0).xyz;
            if (v.y > 0.0 && v.x < z - u_jump * min(v.y, extent)) {
                closed = float(s) * unit <= u_hole * radius_px(v);
                sum += v;
                break;
            }
        }
        if (!closed) {
            o_info = vec4(me, me.y > 0.0 ? 1.0 : 0.0);
            return;
        }
    }
    o_info = vec4(sum * 0.125, 1.0);
}
