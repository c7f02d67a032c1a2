#version 330 core
in vec4 v_color;
in float v_sprite_px;
in float v_dot_radius_px;
out vec4 o_color;

void main()
{
    vec2 d = gl_PointCoord * 2.0 - 1.0;
    if (dot(d, d) > 1.0)
        discard;
    float a = v_color.a;
    if (v_dot_radius_px > 0.0) // antialiased dot: coverage from the distance to its edge
        a *= clamp(v_dot_radius_px + 0.5 - length(d) * 0.5 * v_sprite_px, 0.0, 1.0);
    o_color = vec4(v_color.rgb * a, a); // premultiplied
}
