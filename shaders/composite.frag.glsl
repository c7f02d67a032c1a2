#version 330 core
// Copies the renderer's frame texel for texel into the target viewport (premultiplied alpha).
uniform sampler2D u_frame;
uniform ivec2 u_origin; // the target viewport's lower-left corner in window pixels
out vec4 o_color;

void main()
{
    o_color = texelFetch(u_frame, ivec2(gl_FragCoord.xy) - u_origin, 0);
}
