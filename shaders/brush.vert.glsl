#version 330 core
// Stroke-based splatting (Lopes et al. section 3.3): one quad per point in the surface's tangent
// plane (instanced, 4 vertices as a strip), spanned by the Householder tangent and bitangent of the
// point's normal turned towards the camera (pnpr_householder_frame in filters/brush_stroke.c
// computes the same frame), turned by a
// bounded per-point angle, stretched along the tangent by the cluster's shape; a point without a
// normal faces the camera. Its texture variant and angle come from a hash of its position, so they
// do not change from frame to frame nor with the draw order.
layout(location = 0) in vec3 a_pos;
layout(location = 1) in float a_radius;  // the disk radius: the size of points without brush_size
layout(location = 2) in vec4 a_color;
layout(location = 4) in uint a_style;
layout(location = 5) in vec4 a_normal;   // unit normal; zero = unknown
layout(location = 6) in vec3 a_brush;    // size (r + eps; 0 = none), stretch, layers (1 or 2)
layout(location = 7) in uint a_queue;    // the per-cell queue key (pnpr_queue: the prelude)

uniform int u_style_filter;      // >= 0: draw only points whose a_style equals it (style maps)
uniform mat4 u_view;
uniform mat4 u_proj;
uniform float u_scale;           // brush scale x point scale (x the cell's disk growth: pnpr_queue)
uniform float u_jitter;          // radians: the per-point angle lies in [-u_jitter, u_jitter]
uniform int u_layer;             // 1: the second layer of small clusters' points

out vec2 v_uv;
out vec4 v_color;
flat out float v_variant;

uint mix_bits(uint h)
{
    h ^= h >> 16; h *= 0x7feb352du; h ^= h >> 15; h *= 0x846ca68bu; h ^= h >> 16;
    return h;
}

void main()
{
    bool hidden = a_style == PNPR_VSTYLE_HIDDEN || (u_style_filter >= 0 && int(a_style) != u_style_filter);
    float grow = 1.0;
    if (hidden || (u_layer == 1 && a_brush.z < 1.5) || pnpr_queue(a_pos, a_queue, grow) < 0.0) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // outside the clip volume: dropped
        v_uv = vec2(0.0);
        v_color = vec4(0.0);
        v_variant = 0.0;
        return;
    }
    vec3 t, b, n = a_normal.xyz;
    if (dot(n, n) > 0.25) {
        // a fitted normal has no sign, and the frame of -n is another frame: turn it towards the
        // camera, so that neighbours on a surface in view agree (it flips only where the surface
        // is seen edge-on, and the strokes there are edge-on too)
        vec3 cam = -(transpose(mat3(u_view)) * u_view[3].xyz);
        n = normalize(n);
        if (dot(n, cam - a_pos) < 0.0) n = -n;
        vec3 h = vec3(n.x + 1.0, n.y, n.z);
        float hh = dot(h, h);
        if (hh > 1e-12) {
            float f = 2.0 / hh;
            t = vec3(0.0, 1.0, 0.0) - f * h.y * h;
            b = vec3(0.0, 0.0, 1.0) - f * h.z * h;
        } else { // n = -e_x
            t = vec3(0.0, 0.0, 1.0);
            b = vec3(0.0, 1.0, 0.0);
        }
    } else { // the camera's right and up axes in world space
        t = vec3(u_view[0][0], u_view[1][0], u_view[2][0]);
        b = vec3(u_view[0][1], u_view[1][1], u_view[2][1]);
    }
    uint hsh = mix_bits(floatBitsToUint(a_pos.x) ^ mix_bits(floatBitsToUint(a_pos.y) ^ mix_bits(floatBitsToUint(a_pos.z))));
    if (u_layer == 1) hsh = mix_bits(hsh + 0x9e3779b9u);
    float ang = u_jitter * (float(hsh & 65535u) / 32767.5 - 1.0) + (u_layer == 1 ? 0.6 : 0.0);
    float c = cos(ang), s = sin(ang);
    vec3 tt = c * t + s * b, bb = -s * t + c * b;
    int corner = gl_VertexID & 3;
    vec2 q = vec2((corner & 1) != 0 ? 1.0 : -1.0, (corner & 2) != 0 ? 1.0 : -1.0);
    float size = pnpr_queue_size(a_brush.x > 0.0 ? a_brush.x : a_radius, grow) * u_scale;
    float stretch = max(a_brush.y, 1.0);
    vec3 p = a_pos + size * (q.x * stretch * tt + q.y * bb);
    vec4 clip = u_proj * (u_view * vec4(p, 1.0));
    // depth: the centre's, pulled towards the camera by the stroke's half-length, for the whole
    // quad: a stroke tilted against the view passes the visibility mask of its own surface (the
    // mask disks are camera-facing) and is hidden only by surfaces nearer than its extent
    vec4 eye = u_view * vec4(a_pos, 1.0);
    eye.z = min(eye.z + size * stretch, 0.5 * eye.z); // the camera looks down -z; stay in front of it
    vec4 pulled = u_proj * eye;
    // not in front of the near plane (the automatic one hugs the cloud): the pulled depth clamped
    // to it rather than the stroke clipped away
    gl_Position = vec4(clip.xy / max(clip.w, 1e-6) * pulled.w, max(pulled.z, -0.9999 * pulled.w), pulled.w);
    v_uv = q * 0.5 + 0.5;
    // the second layer: a slightly altered colour (the paper's "slightly altered color parameters")
    v_color = u_layer == 1 ? vec4(clamp(a_color.rgb * 1.12 + 0.02, 0.0, 1.0), a_color.a) : a_color;
    v_variant = float((hsh >> 16) % PNPR_BRUSH_VARIANTS);
}
