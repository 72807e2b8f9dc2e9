// The geometry stage's interface (a style's loa_*.geom.glsl): the vertex stage's outputs under
// their loa_vs* names (loa_style.vert.glsl with LOA_GEOMETRY_STAGE) in, the fragment stage's
// inputs out, and a copy of one corner's.
in vec3 loa_vsScenePosition[];
in vec3 loa_vsViewPosition[];
in vec3 loa_vsViewNormal[];
in vec2 loa_vsTexCoord[];
in vec2 loa_vsTexCoord1[];
in vec2 loa_vsTexCoord2[];
in vec4 loa_vsColor[];

out vec3 loa_scenePosition;
out vec3 loa_viewPosition;
out vec3 loa_viewNormal;
out vec2 loa_texCoord;
out vec2 loa_texCoord1;
out vec2 loa_texCoord2;
out vec4 loa_color;

// Corner i's attributes as the fragment stage's inputs (gl_Position aside).
void loa_copyCorner(int i)
{
    loa_scenePosition = loa_vsScenePosition[i];
    loa_viewPosition = loa_vsViewPosition[i];
    loa_viewNormal = loa_vsViewNormal[i];
    loa_texCoord = loa_vsTexCoord[i];
    loa_texCoord1 = loa_vsTexCoord1[i];
    loa_texCoord2 = loa_vsTexCoord2[i];
    loa_color = loa_vsColor[i];
}
