#version 330 core
// Outlines, the shortcuts' coarse coverage: one texel per u_block x u_block block of u_src, red =
// some pixel of the block shows a surface (w > 0), green = every pixel does. (The passes read the
// 3x3 texels around a pixel's block: nothing there, no hole march; everything, no distance march.)
// Written by hand rather than with glGenerateMipmap: Mesa's llvmpipe builds float mipmaps slowly
// (150 ms for a 1024x768 frame), this pass reads each pixel once.
uniform sampler2D u_src;
uniform int u_block;
out vec2 o_cover;

void main()
{
    ivec2 size = textureSize(u_src, 0);
    ivec2 base = ivec2(gl_FragCoord.xy) * u_block;
    float any_px = 0.0, all_px = 1.0;
    for (int y = 0; y < u_block; y++) {
        for (int x = 0; x < u_block; x++) {
            ivec2 q = base + ivec2(x, y);
            if (q.x >= size.x || q.y >= size.y)
                continue;
            float w = texelFetch(u_src, q, 0).w > 0.0 ? 1.0 : 0.0;
            any_px = max(any_px, w);
            all_px = min(all_px, w);
        }
    }
    o_cover = vec2(any_px, all_px);
}
