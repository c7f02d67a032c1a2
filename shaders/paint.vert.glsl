#version 330 core
// Painterly brush dabs (section 5.3): one point sprite per point, its size the brush size of the
// pass (u_radius_scale), its colour the point's blended colour of that pass (a_color comes from
// the pass's colour level), rotated by a per-point hash so that the dabs do not line up.
layout(location = 0) in vec3 a_pos;
layout(location = 1) in float a_radius;
layout(location = 2) in vec4 a_color;
layout(location = 4) in uint a_style;
layout(location = 7) in uint a_queue;  // the per-cell queue key (pnpr_queue: the prelude; u_queue_scale: the pass's share)

uniform mat4 u_view;
uniform mat4 u_proj;
uniform float u_pixels_per_unit;
uniform float u_radius_scale;
uniform float u_max_size;
uniform int u_style_filter;      // >= 0: draw only points whose a_style equals it

out vec4 v_color;
out vec2 v_rot;                  // cos, sin of the dab's angle

void main()
{
    float grow = 1.0;
    bool hidden = a_style == PNPR_VSTYLE_HIDDEN || (u_style_filter >= 0 && int(a_style) != u_style_filter);
    if (hidden || pnpr_queue(a_pos, a_queue, grow) < 0.0) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // outside the clip volume: dropped
        gl_PointSize = 1.0;
        v_color = vec4(0.0);
        v_rot = vec2(1.0, 0.0);
        return;
    }
    vec4 clip = u_proj * (u_view * vec4(a_pos, 1.0));
    float r = pnpr_queue_size(a_radius, grow) * u_radius_scale;
    gl_PointSize = clamp(2.0 * r * u_pixels_per_unit / max(clip.w, 1e-6), 1.0, u_max_size);
    gl_Position = clip;
    uint h = uint(gl_VertexID) * 2654435761u;
    h ^= h >> 15; h *= 2246822519u; h ^= h >> 13;
    float ang = float(h & 65535u) * (3.14159265 / 65536.0);
    v_rot = vec2(cos(ang), sin(ang));
    v_color = a_color;
}
