#version 450 compatibility
// Graphic style "palette" (paper 003, texture level of abstraction; osgLoA::PaletteStyle,
// docs/styles.md): the base texel replaced by the nearest colour (CIELab) of row level - 1 of the
// texture's palette (osgLoA::TexturePalette, bound on unit 5 by osgLoA::PaletteMapping::attach),
// times the vertex colour, lit like "photorealistic" (ambient + (1 - ambient) diffuse). The number
// of colours `level` comes from loa_palette_strategy: 0 static (loa_palette_level, settable per
// object), 1 depth, 2 orientation (grazing: loa_palette_levelLow, frontal: loa_palette_levelHigh),
// 3 the interest the usage scenario gives this feature in the configuration being drawn: its
// metrics (view distance, view angle, region, focus, feature interest) per fragment or per
// object, loa_featureInterestOf of loa_transition.frag.glsl;
// always clamped to [1, loa_paletteLevels]. Without a palette or texture: photorealistic.
// The standalone palette program (osgLoA::PaletteMapping::createProgram) links this file with
// loa_palette.frag.glsl, whose main calls loa_palette_baseColor: the lookup is written once.
uniform sampler2D loa_baseTexture;
// The drawable has a texture on unit 0 (TransitionRenderer::bind). No initializer here: the
// standalone program's loa_palette.frag.glsl declares it with the default true, as loa_plain does.
uniform bool loa_hasTexture;
uniform vec3 loa_lightDirection = vec3(0.3, 0.5, 0.8); // towards the light, view space
uniform float loa_palette_ambient = 0.35;
uniform int loa_configuration;                // the configuration this draw belongs to (loa_pass.frag.glsl)
float loa_featureInterestOf(int j, vec3 p); // loa_transition.frag.glsl

// --- palette lookup. CPU twins: WeightedColor::toLab / fromLab, PaletteLookup.
layout(binding = 5) uniform sampler2D loa_paletteLookup; // K x K RGBA32F, (L*, a*, b*, 1) per colour
uniform bool loa_hasPalette = false; // PaletteMapping::attach sets it where a palette is bound
uniform int loa_paletteLevels = 1;   // K, the number of rows of loa_paletteLookup
uniform int loa_palette_strategy = 0; // 0 static, 1 depth, 2 orientation, 3 interest
uniform int loa_palette_level = 8;    // static: number of colours (per object on its StateSet)
uniform int loa_palette_levelNear = 32; // depth: colours at depth <= loa_palette_near
uniform int loa_palette_levelFar = 4;   // depth: colours at depth >= loa_palette_far
uniform float loa_palette_near = 50.0;  // view-space depth (-z), scene units
uniform float loa_palette_far = 400.0;
uniform int loa_palette_levelLow = 4;   // interest 0 / grazing view: colours
uniform int loa_palette_levelHigh = 32; // interest 1 / frontal view: colours

#pragma include "loa_cielab.glsl"

// The number of colours for this fragment by loa_palette_strategy, clamped to [1, K].
int loa_palette_levelOf(vec3 viewPosition, vec3 viewNormal, float interest)
{
    float level = float(loa_palette_level);
    if (loa_palette_strategy == 1)
        level = mix(float(loa_palette_levelNear), float(loa_palette_levelFar),
                    smoothstep(loa_palette_near, loa_palette_far, -viewPosition.z));
    else if (loa_palette_strategy == 2)
        level = mix(float(loa_palette_levelLow), float(loa_palette_levelHigh),
                    abs(dot(normalize(viewNormal), normalize(-viewPosition))));
    else if (loa_palette_strategy == 3)
        level = mix(float(loa_palette_levelLow), float(loa_palette_levelHigh), clamp(interest, 0.0, 1.0));
    return clamp(int(round(level)), 1, max(loa_paletteLevels, 1));
}

// The colour of row level - 1 nearest to srgb in CIELab (squared distance; ties: lower index),
// back in sRGB.
vec3 loa_palette_map(vec3 srgb, int level)
{
    vec3 lab = loa_cielab_fromSrgb(clamp(srgb, 0.0, 1.0));
    vec3 bestLab = texelFetch(loa_paletteLookup, ivec2(0, level - 1), 0).xyz;
    vec3 d = bestLab - lab;
    float best = dot(d, d);
    for (int i = 1; i < level; ++i)
    {
        vec3 c = texelFetch(loa_paletteLookup, ivec2(i, level - 1), 0).xyz;
        d = c - lab;
        float e = dot(d, d);
        if (e < best)
        {
            best = e;
            bestLab = c;
        }
    }
    return loa_cielab_toSrgbColor(bestLab);
}
// --- end of the palette lookup

// The unlit colour: the base texel mapped through the palette (when the drawable has a texture
// and a palette), times the vertex colour.
vec4 loa_palette_baseColor(vec2 texCoord, vec4 color, vec3 viewPosition, vec3 viewNormal, float interest)
{
    vec4 base = color;
    if (loa_hasTexture)
    {
        vec4 texel = texture(loa_baseTexture, texCoord);
        if (loa_hasPalette)
            texel.rgb = loa_palette_map(texel.rgb, loa_palette_levelOf(viewPosition, viewNormal, interest));
        base *= texel;
    }
    return base;
}

vec4 loa_styleColor(vec3 scenePosition, vec3 viewPosition, vec3 viewNormal, vec2 texCoord, vec4 color)
{
    vec4 base = loa_palette_baseColor(texCoord, color, viewPosition, viewNormal,
                                      loa_featureInterestOf(loa_configuration, scenePosition));
    float ambient = loa_palette_ambient;
    float diffuse = max(dot(viewNormal, normalize(loa_lightDirection)), 0.0);
    return vec4(base.rgb * (ambient + (1.0 - ambient) * diffuse), base.a);
}
