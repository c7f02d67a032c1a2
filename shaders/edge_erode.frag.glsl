#version 330 core
// Outlines, step 2: the far side of a contour must be far over more than one pixel. Each surface
// pixel takes the nearest surface of its 3x3 neighbourhood (a minimum filter on eye distance; the
// depth extent comes with it); pixels without a surface stay without. A single pixel that a
// neighbouring disk's depth noise makes "far" is thereby not a contour (docs/rendering.md).
uniform sampler2D u_filled;
out vec2 o_info;

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(u_filled, 0);
    vec2 best = texelFetch(u_filled, p, 0).xy;
    if (best.y <= 0.0) {
        o_info = best;
        return;
    }
    for (int dy = -1; dy <= 1; dy++) {
        for (int dx = -1; dx <= 1; dx++) {
            vec2 v = texelFetch(u_filled, clamp(p + ivec2(dx, dy), ivec2(0), size - 1), 0).xy;
            if (v.y > 0.0 && v.x < best.x)
                best = v;
        }
    }
    o_info = best;
}
