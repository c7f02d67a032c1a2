#version 330 core
// Round splats as GL points: pass 1 (visibility mask), the `points` style, the faint points under
// `lines`. Point size is perspective-correct: the disk's world diameter projected at the point's
// depth.
layout(location = 0) in vec3 a_pos;
layout(location = 1) in float a_radius;
layout(location = 2) in vec4 a_color;
layout(location = 4) in uint a_style; // the point's style under a style map
layout(location = 5) in vec4 a_normal; // unit normal (either orientation); zero = unknown
layout(location = 7) in uint a_queue;  // the per-cell queue key (pnpr_queue: the prelude)

uniform int u_style_filter;      // >= 0: draw only points whose a_style equals it (style maps)
uniform mat4 u_view;
uniform mat4 u_proj;
uniform float u_pixels_per_unit; // proj[1][1] * viewport height / 2: pixels per world unit at w = 1
uniform float u_radius_scale;    // multiplies a_radius
uniform float u_depth_push;      // eye-space push away from the viewer, in radii (mask pass)
uniform float u_max_size;        // implementation's largest point size
uniform float u_fade;            // 0..1: the colour is mix(a_color, u_fade_color, u_fade)
uniform vec4 u_fade_color;
uniform float u_fixed_size;      // > 0: a dot of this diameter in pixels (stipple), antialiased
uniform float u_levels;          // >= 2: colour quantised to this many levels per channel (cartoon)
uniform int u_ortho;             // orthographic projection: view rays along -z
uniform int u_thin;              // 1: tone dots, thinned so that ink coverage follows the tone
uniform int u_fade_in;           // 1: the last points of the cell's queue prefix fade in (stipple dots)

out vec4 v_color;
out float v_sprite_px;           // the sprite's size in pixels
out float v_dot_radius_px;       // > 0: antialiased dot of this radius; 0: hard disk
out vec3 v_info;                 // the mask's surface info: eye distance, the disk's depth extent
                                 // (radius / |cos| of the angle between normal and view ray), radius

void main()
{
    float grow = 1.0;
    bool hidden = a_style == PNPR_VSTYLE_HIDDEN || (u_style_filter >= 0 && int(a_style) != u_style_filter);
    float fade = hidden ? -1.0 : pnpr_queue(a_pos, a_queue, grow);
    if (fade < 0.0) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // outside the clip volume: dropped
        gl_PointSize = 1.0;
        v_color = vec4(0.0);
        v_sprite_px = 1.0;
        v_dot_radius_px = 0.0;
        v_info = vec3(0.0);
        return;
    }
    float r = pnpr_queue_size(a_radius, grow) * u_radius_scale;
    vec4 eye = u_view * vec4(a_pos, 1.0);
    vec4 clip = u_proj * eye;
    float size = 2.0 * r * u_pixels_per_unit / max(clip.w, 1e-6);
    gl_PointSize = clamp(size, 1.0, u_max_size);
    v_dot_radius_px = 0.0;
    if (u_fixed_size > 0.0) {
        gl_PointSize = clamp(u_fixed_size + 1.0, 1.0, u_max_size); // + a fringe pixel
        v_dot_radius_px = 0.5 * u_fixed_size;
        // a dithering point stands for one sample's area (about r^2 with r the distance to the
        // 4th neighbour): keep the fraction sample / dot of them (stable per-point hash)
        float r_px = a_radius * u_pixels_per_unit / max(clip.w, 1e-6);
        uint h = uint(gl_VertexID) * 2654435761u;
        h ^= h >> 15; h *= 2246822519u; h ^= h >> 13;
        if (u_thin != 0 && float(h & 65535u) / 65536.0 >= r_px * r_px / (0.785 * u_fixed_size * u_fixed_size)) {
            gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
            v_color = vec4(0.0);
            v_info = vec3(0.0);
            return;
        }
    }
    v_sprite_px = gl_PointSize;
    // the depth extent of the disk: its radius over the cosine between normal and view ray
    // (at least 0.1); without a normal, 2.5 radii (a typical oblique view)
    float cosv = 0.4;
    vec3 ne = mat3(u_view) * a_normal.xyz;
    if (dot(ne, ne) > 0.25)
        cosv = max(abs(dot(normalize(ne), u_ortho != 0 ? vec3(0.0, 0.0, -1.0) : normalize(eye.xyz))), 0.1);
    // at least the pixel's footprint: where the disks are about a pixel or smaller, depth steps
    // between neighbouring pixels come from the surface's slant over a pixel (up to about one
    // footprint at 45 degrees, more with noisy normals) and the points' range noise, not one disk
    float footprint = (u_ortho != 0 ? 1.0 : max(clip.w, 1e-6)) / max(u_pixels_per_unit, 1e-30);
    v_info = vec3(-eye.z, max(max(r / cosv, footprint), 1e-30), r);
    eye.z -= u_depth_push * r; // the camera looks down -z
    vec4 pushed = u_proj * eye;
    // keep the disk's screen position, take the pushed depth
    gl_Position = vec4(clip.xy / clip.w * pushed.w, pushed.z, pushed.w);
    v_color = mix(a_color, u_fade_color, u_fade);
    if (u_fade_in != 0)
        v_color.a *= fade;
    if (u_levels >= 2.0)
        v_color.rgb = floor(v_color.rgb * (u_levels - 1.0) + 0.5) / (u_levels - 1.0);
}
