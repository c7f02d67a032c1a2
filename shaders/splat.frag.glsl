#version 330 core
in vec4 v_color;
in float v_sprite_px;
in float v_dot_radius_px;
in vec3 v_info;
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_info; // the visibility mask's surface info (outlines), when bound

void main()
{
    vec2 d = gl_PointCoord * 2.0 - 1.0;
    if (dot(d, d) > 1.0)
        discard;
    float a = v_color.a;
    if (v_dot_radius_px > 0.0) // antialiased dot: coverage from the distance to its edge
        a *= clamp(v_dot_radius_px + 0.5 - length(d) * 0.5 * v_sprite_px, 0.0, 1.0);
    o_color = vec4(v_color.rgb * a, a); // premultiplied
    o_info = vec4(v_info, 1.0); // w: coverage (its mipmaps: the covered fraction of a block)
}
