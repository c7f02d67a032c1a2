#version 330 core
// Stroke-based splatting: the order-independent strokes (brush.frag.glsl) onto the frame: the
// weighted mean colour, covering 1 - exp(-sum of -ln(1 - a)) = 1 - prod(1 - a), premultiplied,
// blended ONE, ONE_MINUS_SRC_ALPHA over what the frame holds.
uniform sampler2D u_accum;
uniform sampler2D u_optical;
out vec4 o_color;

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 acc = texelFetch(u_accum, p, 0);
    if (acc.a < 1e-6)
        discard;
    float cover = 1.0 - exp(-texelFetch(u_optical, p, 0).r);
    o_color = vec4(acc.rgb / acc.a * cover, cover);
}
