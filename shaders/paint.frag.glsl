#version 330 core
in vec4 v_color;
in vec2 v_rot;
out vec4 o_color;

uniform sampler2D u_brush; // the brush dab's alpha in .r (generated at renderer creation)

void main()
{
    vec2 d = gl_PointCoord * 2.0 - 1.0;
    if (dot(d, d) > 1.0)
        discard;
    vec2 q = vec2(v_rot.x * d.x + v_rot.y * d.y, -v_rot.y * d.x + v_rot.x * d.y);
    float a = texture(u_brush, q * 0.5 + 0.5).r;
    if (a <= 0.004)
        discard;
    o_color = vec4(v_color.rgb * a, a); // premultiplied
}
