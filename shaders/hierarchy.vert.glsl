#version 330 core
// Chi & Lee's painterly hierarchy: one quad per stroke that the CPU traversal chose
// (pnpr_sphere_tree_traverse, filters/sphere_traverse.c), centred at a_pos and spanned by +-a_u
// (along the stroke) and +-a_v (across), instanced as a 4-vertex strip; a_tone picks the tonal art
// map's layer. The fragments are brush.frag.glsl's (order-independent blending).
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_u;
layout(location = 2) in vec3 a_v;
layout(location = 3) in vec4 a_color;
layout(location = 4) in float a_tone;

uniform mat4 u_view;
uniform mat4 u_proj;

out vec2 v_uv;
out vec4 v_color;
flat out float v_variant;

void main()
{
    int corner = gl_VertexID & 3;
    vec2 q = vec2((corner & 1) != 0 ? 1.0 : -1.0, (corner & 2) != 0 ? 1.0 : -1.0);
    vec4 clip = u_proj * (u_view * vec4(a_pos + q.x * a_u + q.y * a_v, 1.0));
    // depth: the centre's, pulled towards the camera by the stroke's extent (as brush.vert.glsl):
    // a stroke tilted against the view passes the visibility mask of its own surface
    vec4 eye = u_view * vec4(a_pos, 1.0);
    eye.z = min(eye.z + max(length(a_u), length(a_v)), 0.5 * eye.z);
    vec4 pulled = u_proj * eye;
    // not in front of the near plane (the automatic one hugs the cloud): the pulled depth clamped
    // to it rather than the stroke clipped away
    gl_Position = vec4(clip.xy / max(clip.w, 1e-6) * pulled.w, max(pulled.z, -0.9999 * pulled.w), pulled.w);
    v_uv = q * 0.5 + 0.5;
    v_color = a_color;
    v_variant = a_tone;
}
