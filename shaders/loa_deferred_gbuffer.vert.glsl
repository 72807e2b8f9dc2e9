#version 450 compatibility
// osgLoA::DeferredTexturing, geometry stage (paper 000 §4.1): the vertex stage of the override
// program that writes the G-buffer. Fixed-function matrices, so that it runs in the stock
// osgviewer and in osgLoA's offscreen renderer alike.
out vec2 loa_texCoord;   // texture unit 0 (the diffuse channel)
out vec3 loa_viewNormal;
out vec4 loa_color;      // vertex colour: the base colour

void main()
{
    loa_texCoord = gl_MultiTexCoord0.xy;
    loa_viewNormal = gl_NormalMatrix * gl_Normal;
    loa_color = gl_Color;
    gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex;
}
