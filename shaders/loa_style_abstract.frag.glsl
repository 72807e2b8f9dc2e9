#version 450 compatibility
// Graphic style "abstract" (paper 004 §3.1, Figures 3D and 4; osgLoA::GraphicStyle,
// docs/styles.md). Textured surfaces show the texture abstraction of
// osgLoA::TextureAbstraction: per mip level (paper 000 Eq. 2) a bilateral + quantized colour
// texture (unit 3, loa_filteredTexture) and a DoG outline texture (unit 4, loa_abstractOutline),
// prepared once per model by osgLoA::StylePreparation. As the paper has it, colour and outline
// are blended here, at rendering time, each with its own weight: loa_abstract_colorBlend (0 the
// texture as it is, 1 the abstracted colour) and loa_abstract_outlineBlend (0 no outlines, 1 the
// DoG lines at full strength). Lighting and texture environment are the model's, as the
// photorealistic style has them (loa_fixed_function.frag.glsl), so an abstract feature keeps its
// brightness and a blend with photorealistic changes the texture, not the light; with
// loa_abstract_modelLighting false, soft lighting (ambient loa_abstract_ambient) instead.
// Untextured surfaces (their lit colour) are colour-quantized per fragment in Oklab
// (lightness to loa_abstract_levels levels, chroma to a multiple of loa_abstract_chromaStep,
// inside the sRGB gamut; CPU twin osgLoA::ColorQuantization): a flat colour has no texels to
// speckle. A texture the preparation could not filter (reported by name when it skipped it)
// falls back to the texture sampled 2 mip levels coarser (blurred), not quantized: per-texel
// quantization of a raw texture makes speckle, not abstraction.
uniform sampler2D loa_baseTexture;
uniform bool loa_hasTexture; // the drawable has a texture on unit 0 (TransitionRenderer::bind)
layout(binding = 3) uniform sampler2D loa_filteredTexture; // FilterConfiguration's diffuse channel
uniform bool loa_hasFilteredTexture = false; // a filtered texture is bound (FilterConfiguration)
layout(binding = 4) uniform sampler2D loa_abstractOutline; // TextureAbstraction's outline channel
uniform bool loa_hasAbstractOutline = false;
uniform float loa_abstract_colorBlend = 1.0;
uniform float loa_abstract_outlineBlend = 1.0;
uniform vec3 loa_lightDirection = vec3(0.3, 0.5, 0.8); // towards the light, view space
uniform int loa_abstract_levels = 5;
uniform float loa_abstract_chromaStep = 0.05;
uniform float loa_abstract_ambient = 0.6;
uniform bool loa_abstract_modelLighting = true; // the model's fixed-function lighting; false: soft

vec3 loa_abstract_toLinear(vec3 c)
{
    c = clamp(c, 0.0, 1.0);
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045)));
}

vec3 loa_abstract_toSrgb(vec3 c)
{
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

vec3 loa_abstract_linearToOklab(vec3 c)
{
    float l = 0.4122214708 * c.r + 0.5363325363 * c.g + 0.0514459929 * c.b;
    float m = 0.2119034982 * c.r + 0.6806995451 * c.g + 0.1073969566 * c.b;
    float s = 0.0883024619 * c.r + 0.2817188376 * c.g + 0.6299787005 * c.b;
    vec3 lms = pow(max(vec3(l, m, s), vec3(0.0)), vec3(1.0 / 3.0));
    return vec3(0.2104542553 * lms.x + 0.7936177850 * lms.y - 0.0040720468 * lms.z,
                1.9779984951 * lms.x - 2.4285922050 * lms.y + 0.4505937099 * lms.z,
                0.0259040371 * lms.x + 0.7827717662 * lms.y - 0.8086757660 * lms.z);
}

vec3 loa_abstract_oklabToLinear(vec3 lab)
{
    float l = lab.x + 0.3963377774 * lab.y + 0.2158037573 * lab.z;
    float m = lab.x - 0.1055613458 * lab.y - 0.0638541728 * lab.z;
    float s = lab.x - 0.0894841775 * lab.y - 1.2914855480 * lab.z;
    l = l * l * l;
    m = m * m * m;
    s = s * s * s;
    return vec3(4.0767416621 * l - 3.3077115913 * m + 0.2309699292 * s,
                -1.2684380046 * l + 2.6097574011 * m - 0.3413193965 * s,
                -0.0041960863 * l - 0.7034186147 * m + 1.7076147010 * s);
}

bool loa_abstract_inGamut(vec3 c)
{
    return all(greaterThanEqual(c, vec3(-1.0e-6))) && all(lessThanEqual(c, vec3(1.0 + 1.0e-6)));
}

vec3 loa_abstract_quantize(vec3 srgb)
{
    float n = float(max(loa_abstract_levels, 2) - 1);
    float step = loa_abstract_chromaStep;
    vec3 lab = loa_abstract_linearToOklab(loa_abstract_toLinear(srgb));
    float lightness = floor(clamp(lab.x, 0.0, 1.0) * n + 0.5) / n;
    float chroma = length(lab.yz);
    vec3 linear = loa_abstract_oklabToLinear(vec3(lightness, 0.0, 0.0)); // grey
    if (chroma > 0.0 && step <= 0.0)
    {
        linear = loa_abstract_oklabToLinear(vec3(lightness, lab.yz)); // chroma kept, clamped below
    }
    else if (chroma > 0.0)
    {
        int k = min(64, int(floor(chroma / step + 0.01)));
        for (; k > 0; --k)
        {
            vec3 c = loa_abstract_oklabToLinear(vec3(lightness, lab.yz * (float(k) * step / chroma)));
            if (loa_abstract_inGamut(c))
            {
                linear = c;
                break;
            }
        }
    }
    return loa_abstract_toSrgb(linear);
}

vec4 loa_fixedFunctionLighting(vec3 viewPosition, vec3 normal, vec4 color); // loa_fixed_function.frag.glsl
vec4 loa_fixedFunctionTexEnv(vec4 fragment, vec4 texel);

vec4 loa_styleColor(vec3 scenePosition, vec3 viewPosition, vec3 viewNormal, vec2 texCoord, vec4 color)
{
    // The surface as the model lights it (as the photorealistic style does), or soft lighting.
    vec4 lit;
    if (loa_abstract_modelLighting)
        lit = loa_fixedFunctionLighting(viewPosition, gl_FrontFacing ? viewNormal : -viewNormal, color);
    else
    {
        float ambient = loa_abstract_ambient;
        float diffuse = max(dot(viewNormal, normalize(loa_lightDirection)), 0.0);
        lit = vec4(color.rgb * (ambient + (1.0 - ambient) * diffuse), color.a);
    }
    if (loa_hasTexture && loa_hasFilteredTexture)
    {
        vec4 texel = mix(texture(loa_baseTexture, texCoord), texture(loa_filteredTexture, texCoord),
                         clamp(loa_abstract_colorBlend, 0.0, 1.0));
        if (loa_hasAbstractOutline)
            texel.rgb *= mix(1.0, texture(loa_abstractOutline, texCoord).r, clamp(loa_abstract_outlineBlend, 0.0, 1.0));
        return loa_fixedFunctionTexEnv(lit, texel);
    }
    if (loa_hasTexture)
        return loa_fixedFunctionTexEnv(lit, texture(loa_baseTexture, texCoord, 2.0));
    return vec4(loa_abstract_quantize(lit.rgb), lit.a);
}
