#version 330 core
// The `lines` style: one screen-space quad per line segment (instanced, 4 vertices as a strip),
// u_width pixels wide plus one pixel of antialiasing fringe, extended by half the width at both
// ends (square caps, so that consecutive segments join without gaps). Ends behind the near plane
// are moved onto it in eye space first; depth is interpolated along the segment.
layout(location = 0) in vec3 a_p0;
layout(location = 1) in vec3 a_p1;
layout(location = 2) in float a_length; // the whole polyline's length (world units)

uniform mat4 u_view;     // includes the translation from the lines' origin
uniform mat4 u_proj;
uniform vec2 u_viewport; // frame size in pixels
uniform float u_width;   // stroke width in pixels
uniform float u_near;    // near plane distance (> 0)
uniform float u_pull;    // world units the ends move towards the eye along their view rays
uniform int u_ortho;     // orthographic: the view rays are parallel to -z
uniform float u_pixels_per_unit;
uniform float u_min_px;  // polylines shorter than this on screen (at this segment) are not drawn

out float v_across;      // signed distance from the centre line in pixels

void main()
{
    int corner = gl_VertexID & 3;
    float end = (corner & 1) != 0 ? 1.0 : 0.0;
    float side = (corner & 2) != 0 ? 1.0 : -1.0;
    vec4 e0 = u_view * vec4(a_p0, 1.0);
    vec4 e1 = u_view * vec4(a_p1, 1.0);
    // depth tolerance: along the view ray, so that the ends keep their screen positions
    if (u_ortho != 0) {
        e0.z += u_pull;
        e1.z += u_pull;
    } else {
        e0.xyz *= max(1.0 - u_pull / max(length(e0.xyz), 1e-30), 0.05);
        e1.xyz *= max(1.0 - u_pull / max(length(e1.xyz), 1e-30), 0.05);
    }
    // an illustrator does not draw a stroke of a few pixels: such polylines are scan noise
    float depth = u_ortho != 0 ? 1.0 : max(-0.5 * (e0.z + e1.z), 1e-6);
    if (a_length * u_pixels_per_unit / depth < u_min_px) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        v_across = 0.0;
        return;
    }
    float lim = -u_near * 1.001; // eye z of points in front of the near plane is below this
    if (e0.z > lim && e1.z > lim) { // wholly behind: a degenerate quad outside the clip volume
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        v_across = 0.0;
        return;
    }
    if (e0.z > lim) e0 = mix(e0, e1, (e0.z - lim) / (e0.z - e1.z));
    if (e1.z > lim) e1 = mix(e1, e0, (e1.z - lim) / (e1.z - e0.z));
    vec4 c0 = u_proj * e0, c1 = u_proj * e1;
    vec2 s0 = c0.xy / c0.w * 0.5 * u_viewport, s1 = c1.xy / c1.w * 0.5 * u_viewport;
    vec2 d = s1 - s0;
    float len = length(d);
    vec2 axis = len > 1e-4 ? d / len : vec2(1.0, 0.0);
    vec2 normal = vec2(-axis.y, axis.x);
    float half_w = 0.5 * u_width + 1.0;
    vec4 c = end > 0.5 ? c1 : c0;
    vec2 off_px = normal * (side * half_w) + axis * ((2.0 * end - 1.0) * 0.5 * u_width);
    gl_Position = c + vec4(off_px * 2.0 / u_viewport * c.w, 0.0, 0.0);
    v_across = side * half_w;
}
