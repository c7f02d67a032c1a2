#version 330 core
// Stroke-based splatting's fragments: the brush texture's alpha (a Gaussian sum, brush.h) in the
// point's colour. u_oit 1: weighted blended order-independent transparency (McGuire & Bavoil
// 2013) into two float attachments, added up (blend ONE, ONE): 0 <- (c a w, a w), 1 <- -ln(1 - a),
// whose sum gives the revealage prod(1 - a) = exp(-sum) without per-buffer blend functions (GL 3.3).
// The weight w = a^u_weight lets the denser parts of a stroke win over the faint rims of its
// neighbours. u_oit 0: premultiplied colour for ordinary "over" blending (draw order matters).
in vec2 v_uv;
in vec4 v_color;
flat in float v_variant;

uniform sampler2DArray u_brush;
uniform int u_oit;
uniform float u_weight;

layout(location = 0) out vec4 o_accum;
layout(location = 1) out vec4 o_optical;

void main()
{
    // a fractional layer (the hierarchy's tones) blends the two layers around it
    float l0 = floor(v_variant), f = v_variant - l0;
    float t = texture(u_brush, vec3(v_uv, l0)).r;
    if (f > 0.0) t = mix(t, texture(u_brush, vec3(v_uv, l0 + 1.0)).r, f);
    float a = t * v_color.a;
    if (a < 0.5 / 255.0)
        discard;
    if (u_oit == 1) {
        float w = max(pow(a, u_weight), 1e-3);
        o_accum = vec4(v_color.rgb * a * w, a * w);
        o_optical = vec4(-log(1.0 - min(a, 0.996)), 0.0, 0.0, 0.0);
    } else {
        o_accum = vec4(v_color.rgb * a, a);
        o_optical = vec4(0.0);
    }
}
