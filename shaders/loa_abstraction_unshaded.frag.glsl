#version 450 compatibility
// Normal pass without shading (paper 002 §3: "the scene is rendered normally without any
// shading"): texture x vertex colour, no lighting. Alpha: the material's opacity.
uniform sampler2D loa_baseTexture;
uniform bool loa_hasTexture = false; // set true on the StateSets that have a texture on unit 0

#pragma include "loa_abstraction_pass.glsl"

void main()
{
    if (!loa_materialCovers(loa_texCoord, loa_color))
        discard;
    vec4 base = loa_color;
    if (loa_hasTexture)
        base *= texture(loa_baseTexture, loa_texCoord);
    loa_fragColor = base;
}
