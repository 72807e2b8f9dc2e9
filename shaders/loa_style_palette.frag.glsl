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

const vec3 loa_palette_white = vec3(0.95047, 1.0, 1.08883); // D65

float loa_palette_toLinear(float c) { return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4); }
float loa_palette_toSrgb(float l) { return l <= 0.0031308 ? 12.92 * l : 1.055 * pow(l, 1.0 / 2.4) - 0.055; }
float loa_palette_f(float t) { return t > 0.008856452 ? pow(t, 1.0 / 3.0) : t * 7.787037 + 4.0 / 29.0; }
float loa_palette_fInverse(float f) { return f > 6.0 / 29.0 ? f * f * f : (f - 4.0 / 29.0) / 7.787037; }

vec3 loa_palette_rgbToLab(vec3 c)
{
    float r = loa_palette_toLinear(c.r), g = loa_palette_toLinear(c.g), b = loa_palette_toLinear(c.b);
    float X = 0.4124564 * r + 0.3575761 * g + 0.1804375 * b;
    float Y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
    float Z = 0.0193339 * r + 0.1191920 * g + 0.9503041 * b;
    float fx = loa_palette_f(X / loa_palette_white.x), fy = loa_palette_f(Y / loa_palette_white.y),
          fz = loa_palette_f(Z / loa_palette_white.z);
    return vec3(116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz));
}

vec3 loa_palette_labToRgb(vec3 lab)
{
    float fy = (lab.x + 16.0) / 116.0;
    float fx = fy + lab.y / 500.0, fz = fy - lab.z / 200.0;
    float X = loa_palette_white.x * loa_palette_fInverse(fx), Y = loa_palette_white.y * loa_palette_fInverse(fy),
          Z = loa_palette_white.z * loa_palette_fInverse(fz);
    vec3 l = vec3(3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z, -0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z,
                  0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z);
    l = clamp(l, 0.0, 1.0);
    return vec3(loa_palette_toSrgb(l.r), loa_palette_toSrgb(l.g), loa_palette_toSrgb(l.b));
}

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
    vec3 lab = loa_palette_rgbToLab(clamp(srgb, 0.0, 1.0));
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
    return loa_palette_labToRgb(bestLab);
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
