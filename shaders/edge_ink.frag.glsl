#version 330 core
// Outlines, step 3: ink on the near side of every silhouette and occluding contour of the
// hole-closed surface info (edge_fill.frag, edge_erode.frag).
//   Silhouettes (against no surface): a band u_width px wide whose outer edge is the inset (the
//   mask disks' overhang) inside the mask's boundary; u_erase: the overhang itself is painted in
//   the background (a separate draw, without blending).
//   Contours (against a farther surface): a pixel is inked when a pixel between the inset and
//   the inset + u_width + 1 px along one of 8 rays (the minimum filter moved the far side one
//   pixel away) lies farther than u_jump times the smaller depth extent of the two.
// Coverage falls off over the band's last pixel (antialiased). Beyond the frame border the border
// pixels repeat: the frame's edge is no outline.
uniform sampler2D u_filled;  // hole-closed info (this pixel)
uniform sampler2D u_eroded;  // minimum filter, distance to no surface, inset
uniform float u_width;       // outline width in pixels
uniform float u_jump;        // depth jump in depth extents
uniform vec4 u_ink;          // straight alpha
uniform int u_erase;         // 1: paint the overhang in u_background instead
uniform vec4 u_background;   // premultiplied
out vec4 o_color;

// the 8 march directions, the diagonals last (their steps are sqrt(2) px)
const ivec2 DIRS[8] = ivec2[8](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1),
                               ivec2(1, 1), ivec2(1, -1), ivec2(-1, 1), ivec2(-1, -1));

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(u_filled, 0);
    vec2 me = texelFetch(u_filled, p, 0).xy;
    if (me.y <= 0.0)
        discard;
    vec4 e = texelFetch(u_eroded, p, 0);
    bool speck = e.w < 0.0; // too small a blob for a silhouette of its own (edge_erode.frag)
    float inset = speck ? -1.0 - e.w : e.w;
    float beyond = e.z - inset; // distance past the inset to no surface
    if (u_erase != 0) {
        if (beyond > 0.5)
            discard;
        o_color = u_background;
        return;
    }
    float cover = beyond > 0.5 && !speck ? clamp(u_width + 0.5 - beyond, 0.0, 1.0) : 0.0;
    // the contours: along 8 rays (a disk of radius inset + u_width + 1 sampled by its 8 spokes);
    // the near surface's disks overhang the far one by the inset too: the band lies inside it
    int reach = int(ceil(inset + u_width + 1.5));
    for (int d = 0; d < 8 && cover < 1.0; d++) {
        ivec2 step = DIRS[d];
        float unit = d >= 4 ? 1.41421356 : 1.0;
        for (int s = 1; s <= reach; s++) {
            float past = float(s) * unit - inset;
            float c = past > 0.5 ? clamp(u_width + 1.5 - past, 0.0, 1.0) : 0.0;
            if (past > 0.5 && c <= cover)
                break;
            vec2 v = texelFetch(u_eroded, clamp(p + step * s, ivec2(0), size - 1), 0).xy;
            if (v.y > 0.0 && v.x > me.x + u_jump * min(me.y, v.y)) {
                // the far side must go on for two more pixels (depth noise makes specks)
                vec2 w = texelFetch(u_eroded, clamp(p + step * (s + 1), ivec2(0), size - 1), 0).xy;
                vec2 w2 = texelFetch(u_eroded, clamp(p + step * (s + 2), ivec2(0), size - 1), 0).xy;
                if (w.y > 0.0 && w.x > me.x + u_jump * min(me.y, w.y) && w2.y > 0.0 && w2.x > me.x + u_jump * min(me.y, w2.y))
                    cover = max(cover, c); // c = 0: this pixel is in the overhang along this ray
                break;
            }
        }
    }
    float a = cover * u_ink.a;
    if (a <= 0.0)
        discard;
    o_color = vec4(u_ink.rgb * a, a); // premultiplied; blended with (1, 1 - src alpha)
}
