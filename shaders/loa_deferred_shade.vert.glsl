#version 450 compatibility
// osgLoA::DeferredTexturing, shading stage: a full-screen triangle, vertices given in clip space.
void main()
{
    gl_Position = vec4(gl_Vertex.xy, 0.0, 1.0);
}
