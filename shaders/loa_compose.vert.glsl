#version 450 compatibility
// A full-screen triangle for image-space passes: the vertices are given in clip space.
out vec2 loa_screenCoord;

void main()
{
    loa_screenCoord = gl_Vertex.xy * 0.5 + 0.5;
    gl_Position = vec4(gl_Vertex.xy, 0.0, 1.0);
}
