#version 450 compatibility
// The object passes of image-space / hybrid abstraction (osgLoA::AbstractionNode, papers 001, 002):
// unshaded normal pass, object-ID pass and object-space shading pass share this vertex stage.
// The Gouraud shade (002 §3.1) is computed per vertex here: ambient + (1 - ambient) max(n.l, 0),
// the normal turned towards the eye (two-sided), one directional light in view space.
uniform mat4 osg_ModelViewMatrix;
uniform mat4 osg_ModelViewProjectionMatrix;
uniform mat3 osg_NormalMatrix;
uniform vec3 loa_lightDirection = vec3(0.3, 0.5, 0.8); // towards the light, view space
uniform float loa_abstraction_ambient = 0.35;

out vec2 loa_texCoord;
out vec4 loa_color;
out float loa_gouraud;
out vec3 loa_objectPosition; // model coordinates: the pencil texture's frame, fixed to the polygon
out vec3 loa_objectNormal;
out vec4 loa_viewSurface; // view-space normal (turned towards the eye) and view distance along -z

void main()
{
    vec3 viewPosition = (osg_ModelViewMatrix * gl_Vertex).xyz;
    vec3 n = osg_NormalMatrix * gl_Normal;
    float len = length(n);
    n = len > 0.0 ? n / len : vec3(0.0, 0.0, 1.0);
    if (dot(n, -viewPosition) < 0.0)
        n = -n;
    float diffuse = max(dot(n, normalize(loa_lightDirection)), 0.0);
    loa_gouraud = loa_abstraction_ambient + (1.0 - loa_abstraction_ambient) * diffuse;
    loa_texCoord = gl_MultiTexCoord0.xy;
    loa_color = gl_Color;
    loa_objectPosition = gl_Vertex.xyz / (gl_Vertex.w != 0.0 ? gl_Vertex.w : 1.0);
    loa_objectNormal = gl_Normal;
    loa_viewSurface = vec4(n, -viewPosition.z);
    gl_Position = osg_ModelViewProjectionMatrix * gl_Vertex;
}
