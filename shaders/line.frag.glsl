#version 330 core
in float v_across;
out vec4 o_color;

uniform float u_width; // stroke width in pixels
uniform vec4 u_ink;    // rgba, straight alpha

void main()
{
    // coverage of a u_width wide line by this pixel, from the distance to the centre line
    float a = clamp(0.5 * u_width + 0.5 - abs(v_across), 0.0, 1.0) * u_ink.a;
    if (a <= 0.0)
        discard;
    o_color = vec4(u_ink.rgb * a, a); // premultiplied; blended with (1, 1 - src alpha)
}
