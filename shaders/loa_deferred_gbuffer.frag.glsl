#version 450 compatibility
// osgLoA::DeferredTexturing, geometry stage (paper 000 §4.1, Fig. 6/11): instead of sampling the
// texture, store what deferred texturing needs to sample (and filter) it later:
//   target 0 (RGBA32F): u, v, mip LoD lambda (unclamped), TID (-1: untextured)
//   target 1 (RGBA32F): view normal (towards the viewer), feature id
//   target 2 (RGBA8):   base colour (vertex colour)
// lambda is the OpenGL 4.5 spec's level of detail (§8.14.1, eq. 8.7): the scale factor
// rho = max(|d(s,t)/dx|, |d(s,t)/dy|) with (s,t) in level-0 texels, lambda = log2(rho); the
// shading stage clamps it to the texture's levels as GL_LINEAR_MIPMAP_LINEAR does.
// loa_deferredTid and loa_deferredTextureSize are set by the node on every StateSet that has a
// texture on unit 0; the pass camera's defaults mark everything else untextured.
uniform int loa_deferredTid = -1;
uniform vec2 loa_deferredTextureSize = vec2(1.0);
uniform uint loa_featureId = 0u;

in vec2 loa_texCoord;
in vec3 loa_viewNormal;
in vec4 loa_color;

layout(location = 0) out vec4 loa_gTexCoord;
layout(location = 1) out vec4 loa_gNormal;
layout(location = 2) out vec4 loa_gBaseColor;

void main()
{
    vec2 texel = loa_texCoord * loa_deferredTextureSize;
    vec2 dx = dFdx(texel), dy = dFdy(texel);
    float rho = max(length(dx), length(dy));
    float lod = log2(max(rho, 1.0e-30));
    loa_gTexCoord = vec4(loa_texCoord, lod, float(loa_deferredTid));
    vec3 n = normalize(loa_viewNormal);
    if (!gl_FrontFacing)
        n = -n;
    loa_gNormal = vec4(n, float(loa_featureId));
    loa_gBaseColor = loa_color;
}
