#version 450 compatibility
// A full-screen pass (osgLoA::StencilRoutedABuffer): vertices given in clip space.
void main()
{
    gl_Position = vec4(gl_Vertex.xy, 0.0, 1.0);
}
