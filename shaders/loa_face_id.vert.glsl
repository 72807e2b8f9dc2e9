#version 450 compatibility
// ID buffer for viewpoint entropy (osgLoA::ViewpointEntropy): each face's id arrives as an
// exact RGBA8 vertex colour (rgb = id, a = 255) and is passed on unchanged, flat, unlit.
uniform mat4 osg_ModelViewProjectionMatrix;

flat out vec4 loa_faceId;

void main()
{
    loa_faceId = gl_Color;
    gl_Position = osg_ModelViewProjectionMatrix * gl_Vertex;
}
