#version 450 compatibility
// The vertex stage of every program that draws a feature in a graphic style (docs/rendering.md):
// model -> LoA-node ("scene") coordinates, landmark deformation (loa_landmark.vert.glsl), and
// back to view and clip space. The fixed-function matrices are used so that the same program runs
// in the stock osgviewer and in osgLoA's offscreen renderer.
#ifdef LOA_GEOMETRY_STAGE
// A style's geometry stage follows (loa_tree_sprites.geom.glsl): it reads these outputs under the
// names below and writes the fragment stage's inputs under their own.
#define loa_scenePosition loa_vsScenePosition
#define loa_viewPosition loa_vsViewPosition
#define loa_viewNormal loa_vsViewNormal
#define loa_texCoord loa_vsTexCoord
#define loa_texCoord1 loa_vsTexCoord1
#define loa_texCoord2 loa_vsTexCoord2
#define loa_color loa_vsColor
// Per-vertex data a geometry stage may read: texture units 5-7 (ObjectSpaceEdges: barycentric
// corner and crease mask, the neighbouring faces' normals).
out vec4 loa_vsEdgeData0;
out vec4 loa_vsEdgeData1;
out vec4 loa_vsEdgeData2;
#endif
uniform mat4 loa_viewToScene; // view -> LoA node local coordinates
uniform mat4 loa_sceneToView; // its inverse

vec3 loa_deformVertex(vec3 scenePosition);
vec3 loa_deformNormal(vec3 sceneNormal);

out vec3 loa_scenePosition; // before deformation: where the interest is measured
out vec3 loa_viewPosition;
out vec3 loa_viewNormal;
out vec2 loa_texCoord;
out vec2 loa_texCoord1; // texture units 1 and 2 (osgLoA::FixedFunctionUniforms::kUnits)
out vec2 loa_texCoord2;
out vec4 loa_color;
void main()
{
    vec4 view = gl_ModelViewMatrix * gl_Vertex;
    vec4 scene = loa_viewToScene * view;
    loa_scenePosition = scene.xyz / scene.w;
    vec4 deformed = loa_sceneToView * vec4(loa_deformVertex(loa_scenePosition), 1.0);
    loa_viewPosition = deformed.xyz / deformed.w;
    vec3 sceneNormal = mat3(loa_viewToScene) * (gl_NormalMatrix * gl_Normal);
    loa_viewNormal = mat3(loa_sceneToView) * loa_deformNormal(sceneNormal);
    // The texture matrix (osg::TexMat) and the projective divide, as fixed-function texturing.
    vec4 tc = gl_TextureMatrix[0] * gl_MultiTexCoord0;
    loa_texCoord = tc.xy / (tc.w != 0.0 ? tc.w : 1.0);
    vec4 tc1 = gl_TextureMatrix[1] * gl_MultiTexCoord1;
    loa_texCoord1 = tc1.xy / (tc1.w != 0.0 ? tc1.w : 1.0);
    vec4 tc2 = gl_TextureMatrix[2] * gl_MultiTexCoord2;
    loa_texCoord2 = tc2.xy / (tc2.w != 0.0 ? tc2.w : 1.0);
    loa_color = gl_Color;
#ifdef LOA_GEOMETRY_STAGE
    loa_vsEdgeData0 = gl_MultiTexCoord5;
    loa_vsEdgeData1 = gl_MultiTexCoord6;
    loa_vsEdgeData2 = gl_MultiTexCoord7;
#endif
    gl_Position = gl_ProjectionMatrix * deformed;
}
