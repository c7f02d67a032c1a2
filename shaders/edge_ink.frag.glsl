#version 330 core
// Outlines, step 3: ink on the near side of every silhouette and occluding contour of the
// hole-closed surface info. A surface pixel is inked when a pixel within u_width px shows no
// surface or, after the minimum filter (edge_erode.frag), one farther than u_jump times the
// smaller depth extent of the two (edge_fill.frag); the ink's coverage falls off
// over the last pixel (antialiased band u_width px wide). Beyond the frame border the border
// pixels repeat: the frame's edge is no outline.
uniform sampler2D u_filled;  // hole-closed info (this pixel)
uniform sampler2D u_eroded;  // its minimum filter (the neighbours)
uniform float u_width;    // outline width in pixels
uniform float u_jump;     // depth jump in depth extents
uniform vec4 u_ink;       // straight alpha
out vec4 o_color;

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(u_filled, 0);
    vec2 me = texelFetch(u_filled, p, 0).xy;
    if (me.y <= 0.0)
        discard;
    int reach = int(ceil(u_width + 1.5));
    float cover = 0.0;
    for (int dy = -reach; dy <= reach; dy++) {
        for (int dx = -reach; dx <= reach; dx++) {
            float d = length(vec2(dx, dy));
            // the minimum filter moved a far surface one pixel away: one pixel more reach
            float c = clamp(u_width + 1.5 - d, 0.0, 1.0);
            if (c <= cover)
                continue;
            ivec2 q = clamp(p + ivec2(dx, dy), ivec2(0), size - 1);
            vec2 v = texelFetch(u_eroded, q, 0).xy;
            if (v.y <= 0.0)
                cover = max(cover, clamp(u_width + 0.5 - d, 0.0, 1.0));
            else if (v.x > me.x + u_jump * min(me.y, v.y))
                cover = c;
        }
    }
    float a = cover * u_ink.a;
    if (a <= 0.0)
        discard;
    o_color = vec4(u_ink.rgb * a, a); // premultiplied; blended with (1, 1 - src alpha)
}
