#version 330 core
// Stroke-based splatting while the camera moves (Lopes et al. section 3.3.3: "a two-pass weighted
// Gaussian blur ... when applied to a moving object, or during camera navigation"): one pass of a
// separable Gaussian of sigma u_sigma pixels along u_dir over the strokes' premultiplied colour
// (the alpha weights the colours), out to 3 sigma.
uniform sampler2D u_src;
uniform vec2 u_dir;
uniform float u_sigma;
out vec4 o_color;

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy), size = textureSize(u_src, 0);
    int r = int(ceil(3.0 * u_sigma));
    vec4 sum = vec4(0.0);
    float wsum = 0.0;
    for (int i = -r; i <= r; i++) {
        ivec2 q = clamp(p + ivec2(u_dir * float(i)), ivec2(0), size - 1);
        float w = exp(-0.5 * float(i * i) / (u_sigma * u_sigma));
        sum += w * texelFetch(u_src, q, 0);
        wsum += w;
    }
    o_color = sum / wsum;
}
