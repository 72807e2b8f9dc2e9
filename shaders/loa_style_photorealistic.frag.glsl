#version 450 compatibility
// Graphic style "photorealistic" (osgLoA::GraphicStyle, docs/styles.md): the model as OSG's
// fixed-function pipeline draws it (paper 004's photorealistic style is the model itself).
//
// loa_photorealistic_fixedFunction (default true): the fixed function's lighting equation (light
// 0, the material or the colour-tracking material, the light model's ambient; evaluated per
// fragment with the interpolated normal, where the fixed function lights per vertex: the two
// agree on flat faces and differ slightly inside curved ones) combined with the texture of unit 0 by the model's texture
// environment (loa_texEnvMode), with the texture matrix applied; the model's state reaches the
// shader through osgLoA::FixedFunctionUniforms. A plain render and a scenario that draws every
// feature photorealistically then give the same image (tests/PhotorealisticIdentityGLTest).
// false: the project's simple lighting (texture x base colour x (ambient + (1 - ambient)
// diffuse) from loa_lightDirection in view space), as loa_plain.frag.glsl; the base colour is the
// vertex colour, or gl_FrontMaterial.diffuse with loa_photorealistic_materialDiffuse.
uniform sampler2D loa_baseTexture;
uniform bool loa_hasTexture; // unit 0 has a texture (osgLoA::FixedFunctionUniforms)
uniform vec3 loa_lightDirection = vec3(0.3, 0.5, 0.8); // towards the light, view space
uniform float loa_photorealistic_ambient = 0.35;
uniform bool loa_photorealistic_materialDiffuse = false;
uniform bool loa_photorealistic_fixedFunction = true;

// The fixed-function lighting of light 0 and texture environment of unit 0
// (loa_fixed_function.frag.glsl, linked into every style's program).
vec4 loa_fixedFunctionLighting(vec3 viewPosition, vec3 normal, vec4 color);
vec4 loa_fixedFunctionTexEnv(vec4 fragment, vec4 texel);
vec4 loa_fixedFunctionTexEnvMode(int mode, vec4 fragment, vec4 texel);

// Texture units 1 and 2 (a lightmap, a detail texture), applied after unit 0 as the fixed
// function's texture stages are (osgLoA::FixedFunctionUniforms::kUnits).
uniform sampler2D loa_texture1;
uniform sampler2D loa_texture2;
uniform bool loa_hasTexture1 = false;
uniform bool loa_hasTexture2 = false;
uniform int loa_texEnvMode1 = 0;
uniform int loa_texEnvMode2 = 0;
in vec2 loa_texCoord1;
in vec2 loa_texCoord2;

vec4 loa_styleColor(vec3 scenePosition, vec3 viewPosition, vec3 viewNormal, vec2 texCoord, vec4 color)
{
    if (loa_photorealistic_fixedFunction)
    {
        // The normal as the model gives it: the pass turned it towards the viewer.
        vec3 modelNormal = gl_FrontFacing ? viewNormal : -viewNormal;
        vec4 c = loa_fixedFunctionLighting(viewPosition, modelNormal, color);
        if (loa_hasTexture)
            c = loa_fixedFunctionTexEnv(c, texture(loa_baseTexture, texCoord));
        if (loa_hasTexture1)
            c = loa_fixedFunctionTexEnvMode(loa_texEnvMode1, c, texture(loa_texture1, loa_texCoord1));
        if (loa_hasTexture2)
            c = loa_fixedFunctionTexEnvMode(loa_texEnvMode2, c, texture(loa_texture2, loa_texCoord2));
        return c;
    }
    vec4 base = loa_photorealistic_materialDiffuse ? gl_FrontMaterial.diffuse : color;
    if (loa_hasTexture)
        base *= texture(loa_baseTexture, texCoord);
    float ambient = loa_photorealistic_ambient;
    float diffuse = max(dot(viewNormal, normalize(loa_lightDirection)), 0.0);
    return vec4(base.rgb * (ambient + (1.0 - ambient) * diffuse), base.a);
}
