#version 330 core
in vec2 v_uv;
in vec4 v_color;
in float v_fade;       // the queue's fade-in (stroke.vert)
in vec4 v_px;          // along, across (px from the centre); half length, half width (stroke.vert)
out vec4 o_color;

uniform sampler2DArray u_strokes; // alpha of the stroke textures in .r, one layer each
uniform float u_layer;
uniform vec4 u_ink;               // rgba; used unless u_ink_from_points
uniform int u_ink_from_points;

// The share of the pixel centred at x (px) that the interval [-h, h] covers.
float cover(float x, float h)
{
    return clamp(min(h, x + 0.5) - max(-h, x - 0.5), 0.0, 1.0);
}

void main()
{
    float a = texture(u_strokes, vec3(v_uv, u_layer)).r;
    a *= cover(v_px.x, v_px.z) * cover(v_px.y, v_px.w);
    vec4 c = u_ink_from_points != 0 ? vec4(v_color.rgb, u_ink.a) : u_ink;
    a *= c.a * v_fade;
    if (a <= 0.0)
        discard;
    o_color = vec4(c.rgb * a, a); // premultiplied; blended with (1, 1 - src alpha)
}
