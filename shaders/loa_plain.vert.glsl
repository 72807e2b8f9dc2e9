#version 450 compatibility
// Plain textured, lit rendering: the baseline every graphic style is measured against.
// Matrices come from OSG's uniforms (State::setUseModelViewAndProjectionUniforms).
uniform mat4 osg_ModelViewMatrix;
uniform mat4 osg_ModelViewProjectionMatrix;
uniform mat3 osg_NormalMatrix;

out vec3 loa_viewNormal;
out vec3 loa_viewPosition;
out vec2 loa_texCoord;
out vec4 loa_color;

void main()
{
    loa_viewPosition = (osg_ModelViewMatrix * gl_Vertex).xyz;
    loa_viewNormal = osg_NormalMatrix * gl_Normal;
    loa_texCoord = gl_MultiTexCoord0.xy;
    loa_color = gl_Color;
    gl_Position = osg_ModelViewProjectionMatrix * gl_Vertex;
}
