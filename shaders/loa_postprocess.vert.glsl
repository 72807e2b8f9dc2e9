#version 450 compatibility
// The full-screen pass of post-process filtering (osgLoA::PostProcessFiltering, paper 000 Eq. 1):
// a unit quad ([0,1]^2, texture coordinates equal to its positions) covering the viewport. The
// positions map straight to clip space, so the pass needs no matrices.
out vec2 loa_postprocess_texCoord;

void main()
{
    loa_postprocess_texCoord = gl_MultiTexCoord0.xy;
    gl_Position = vec4(gl_Vertex.xy * 2.0 - 1.0, 0.0, 1.0);
}
