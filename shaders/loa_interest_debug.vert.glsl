#version 450 compatibility
// The interest debug view (paper 004 Figure 5): passes the scene position of each vertex.
uniform mat4 osg_ModelViewMatrix;
uniform mat4 osg_ModelViewProjectionMatrix;
uniform mat4 osg_ViewMatrixInverse;
uniform mat4 loa_worldToScene; // world -> LoA node coordinates (identity at the root)

out vec3 loa_scenePosition;

void main()
{
    vec4 world = osg_ViewMatrixInverse * (osg_ModelViewMatrix * gl_Vertex);
    loa_scenePosition = (loa_worldToScene * world).xyz;
    gl_Position = osg_ModelViewProjectionMatrix * gl_Vertex;
}
