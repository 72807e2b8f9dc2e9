#version 330 compatibility
// Jump flooding (osgLoA::DistanceField): one triangle covering the viewport, given in clip space.
void main()
{
    gl_Position = vec4(gl_Vertex.xy, 0.0, 1.0);
}
