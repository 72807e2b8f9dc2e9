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
uniform int loa_texEnvMode = 0; // 0 modulate, 1 replace, 2 decal, 3 add, 4 blend
uniform vec3 loa_lightDirection = vec3(0.3, 0.5, 0.8); // towards the light, view space
uniform float loa_photorealistic_ambient = 0.35;
uniform bool loa_photorealistic_materialDiffuse = false;
uniform bool loa_photorealistic_fixedFunction = true;

uniform bool loa_lighting = true;  // GL_LIGHTING of the model's state
uniform int loa_colorMaterial = 1; // 0 off, 1 ambient+diffuse, 2 ambient, 3 diffuse, 4 emission, 5 specular

// The fixed-function lighting of light 0 for the front material; `normal` is the vertex normal
// as given (not turned towards the viewer: one-sided lighting, OSG's default).
vec4 loa_photorealistic_lighting(vec3 viewPosition, vec3 normal, vec4 color)
{
    if (!loa_lighting)
        return color;
    vec4 ambient = loa_colorMaterial == 1 || loa_colorMaterial == 2 ? color : gl_FrontMaterial.ambient;
    vec4 diffuse = loa_colorMaterial == 1 || loa_colorMaterial == 3 ? color : gl_FrontMaterial.diffuse;
    vec4 emission = loa_colorMaterial == 4 ? color : gl_FrontMaterial.emission;
    vec4 specular = loa_colorMaterial == 5 ? color : gl_FrontMaterial.specular;
    vec4 position = gl_LightSource[0].position;
    vec3 toLight = position.w == 0.0 ? position.xyz : position.xyz / position.w - viewPosition;
    float attenuation = 1.0;
    if (position.w != 0.0)
    {
        float d = length(toLight);
        attenuation = 1.0 / max(gl_LightSource[0].constantAttenuation + gl_LightSource[0].linearAttenuation * d +
                                    gl_LightSource[0].quadraticAttenuation * d * d,
                                1.0e-6);
    }
    vec3 l = normalize(toLight);
    vec3 n = normalize(normal);
    float nDotL = max(dot(n, l), 0.0);
    vec3 c = emission.rgb + ambient.rgb * gl_LightModel.ambient.rgb +
             attenuation * (ambient.rgb * gl_LightSource[0].ambient.rgb +
                            nDotL * diffuse.rgb * gl_LightSource[0].diffuse.rgb);
    if (nDotL > 0.0)
    {
        float s = max(dot(n, normalize(l + vec3(0.0, 0.0, 1.0))), 0.0); // non-local viewer
        c += attenuation * (s > 0.0 ? pow(s, gl_FrontMaterial.shininess) : 0.0) * specular.rgb *
             gl_LightSource[0].specular.rgb;
    }
    return vec4(clamp(c, 0.0, 1.0), diffuse.a);
}

// The fixed-function texture environment of unit 0 (GL 1.5 table 3.22; BLEND uses the
// environment colour's default, black, so it is MODULATE's complement).
vec4 loa_photorealistic_texEnv(vec4 fragment, vec4 texel)
{
    if (loa_texEnvMode == 1)
        return texel;
    if (loa_texEnvMode == 2)
        return vec4(mix(fragment.rgb, texel.rgb, texel.a), fragment.a);
    if (loa_texEnvMode == 3)
        return vec4(min(fragment.rgb + texel.rgb, vec3(1.0)), fragment.a * texel.a);
    if (loa_texEnvMode == 4)
        return vec4(fragment.rgb * (1.0 - texel.rgb), fragment.a * texel.a);
    return fragment * texel;
}

vec4 loa_styleColor(vec3 scenePosition, vec3 viewPosition, vec3 viewNormal, vec2 texCoord, vec4 color)
{
    if (loa_photorealistic_fixedFunction)
    {
        // The normal as the model gives it: the pass turned it towards the viewer.
        vec3 modelNormal = gl_FrontFacing ? viewNormal : -viewNormal;
        vec4 lit = loa_photorealistic_lighting(viewPosition, modelNormal, color);
        return loa_hasTexture ? loa_photorealistic_texEnv(lit, texture(loa_baseTexture, texCoord)) : lit;
    }
    vec4 base = loa_photorealistic_materialDiffuse ? gl_FrontMaterial.diffuse : color;
    if (loa_hasTexture)
        base *= texture(loa_baseTexture, texCoord);
    float ambient = loa_photorealistic_ambient;
    float diffuse = max(dot(viewNormal, normalize(loa_lightDirection)), 0.0);
    return vec4(base.rgb * (ambient + (1.0 - ambient) * diffuse), base.a);
}
