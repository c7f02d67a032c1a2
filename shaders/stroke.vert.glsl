#version 330 core
// Pass 2 of the sketchy style: one textured quad per point (instanced, 4 vertices as a strip).
// u_mode 0: directional stroke along the point's feature direction projected to the screen;
// u_mode 1: hatch along a direction fixed on the surface: the fixed world direction (1,1,1)/sqrt 3
// projected onto the point's tangent plane (the same for either orientation of the normal, so
// neighbours agree), projected to the screen like mode 0; the hatches then move rigidly with the
// surface as the camera moves instead of keeping a screen angle while the surface slides under
// them (HATCH_DIR in render/renderer_internal.h). Without a normal: the constant screen direction
// of 45 degrees.
layout(location = 0) in vec3 a_pos;
layout(location = 1) in float a_radius;
layout(location = 2) in vec4 a_color;
layout(location = 3) in vec3 a_dir;
layout(location = 4) in uint a_style; // the point's style under a style map
layout(location = 5) in vec4 a_normal; // unit normal (either orientation); zero = unknown
layout(location = 7) in uint a_queue;  // the per-cell queue key (pnpr_queue: the prelude)

uniform int u_style_filter;      // >= 0: draw only points whose a_style equals it (style maps)
uniform mat4 u_view;
uniform mat4 u_proj;
uniform vec2 u_viewport;          // frame size in pixels
uniform float u_pixels_per_unit;  // proj[1][1] * viewport height / 2
uniform float u_length;           // stroke length in disk radii
uniform float u_width;            // stroke width in pixels
uniform float u_half_max;         // the longest half length in pixels (pnpr_draw_options.stroke_max / 2)
uniform float u_radius_scale;
uniform int u_mode;
uniform int u_thin;               // 1: tone hatches, thinned so that ink coverage follows the tone
uniform float u_tone_radius;      // > 0: tone hatches are this radius (the cloud's mean) long, not
                                  // their point's: as long everywhere, denser samples keep fewer
uniform int u_fade_in;            // 1: the last points of the cell's queue prefix fade in

out vec2 v_uv;
out vec4 v_color;
out float v_fade;
out vec4 v_px;                    // the fragment along and across the stroke in px; its half extents

void main()
{
    float grow = 1.0; // strokes keep their size: the disk growth is the mask's
    bool hidden = a_style == PNPR_VSTYLE_HIDDEN || (u_style_filter >= 0 && int(a_style) != u_style_filter);
    float fade = hidden ? -1.0 : pnpr_queue(a_pos, a_queue, grow);
    if (fade < 0.0) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // outside the clip volume: dropped
        v_color = vec4(0.0);
        v_uv = vec2(0.0);
        v_px = vec4(0.0);
        v_fade = 0.0;
        return;
    }
    int corner = gl_VertexID & 3;
    vec2 q = vec2((corner & 1) != 0 ? 1.0 : -1.0, (corner & 2) != 0 ? 1.0 : -1.0);
    vec4 clip = u_proj * (u_view * vec4(a_pos, 1.0));
    float w = max(clip.w, 1e-6);
    vec2 axis = vec2(0.70710678, 0.70710678);
    vec3 dir = a_dir;
    if (u_mode == 1) {
        vec3 n = a_normal.xyz;
        dir = vec3(0.0);
        if (dot(n, n) > 0.25) {
            n = normalize(n);
            vec3 t = PNPR_HATCH_DIR - n * dot(n, PNPR_HATCH_DIR);
            // the normal within about 18 degrees of (1,1,1): a second world direction, orthogonal
            if (dot(t, t) < 0.1)
                t = PNPR_HATCH_DIR2 - n * dot(n, PNPR_HATCH_DIR2);
            dir = normalize(t);
        }
    }
    if (dot(dir, dir) > 0.0) {
        vec4 clip2 = u_proj * (u_view * vec4(a_pos + dir * a_radius, 1.0));
        if (clip2.w > 1e-6) {
            vec2 s = (clip2.xy / clip2.w - clip.xy / w) * u_viewport;
            float len = length(s);
            if (len > 1e-4)
                axis = s / len;
        }
    }
    float r = a_radius * u_radius_scale;
    float r_len = u_thin != 0 && u_tone_radius > 0.0 ? u_tone_radius * u_radius_scale : r;
    float half_len = max(min(0.5 * u_length * r_len * u_pixels_per_unit / w, u_half_max), 1.5);
    float half_wid = 0.5 * u_width;
    if (u_thin != 0) {
        // a dithering point stands for the area of one sample (about r^2, r the distance to the
        // 4th neighbour); a hatch inks about half of its 2 half_len x 2 half_wid quad (the
        // texture's soft profile): keep the fraction sample / ink of them (a per-point hash,
        // stable from frame to frame), so that the inked area follows the tone
        float r_px = r * u_pixels_per_unit / w;
        float keep = r_px * r_px / (2.0 * half_len * half_wid);
        uint h = uint(gl_InstanceID) * 2654435761u;
        h ^= h >> 15; h *= 2246822519u; h ^= h >> 13;
        if (float(h & 65535u) / 65536.0 >= keep) {
            gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
            v_color = vec4(0.0);
            v_uv = vec2(0.0);
            v_px = vec4(0.0);
            v_fade = 0.0;
            return;
        }
    }
    // the quad half a pixel larger all round: stroke.frag weighs each fragment by the share of its
    // pixel the stroke covers (area coverage, as a vector renderer draws it)
    vec2 side = vec2(-axis.y, axis.x);
    vec2 ext = vec2(half_len + 0.5, half_wid + 0.5); // pixels whose centre is further are not covered
    vec2 off_px = axis * (q.x * ext.x) + side * (q.y * ext.y);
    gl_Position = clip + vec4(off_px * 2.0 / u_viewport * clip.w, 0.0, 0.0);
    v_uv = q * ext / vec2(half_len, half_wid) * 0.5 + 0.5;
    v_px = vec4(q * ext, half_len, half_wid);
    v_color = a_color;
    v_fade = u_fade_in != 0 ? fade : 1.0;
}
