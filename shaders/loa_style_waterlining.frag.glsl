#version 450 compatibility
// Graphic style "waterlining" (paper 004 §3.2.3, Figure 8A; osgLoA::Waterlining, docs/styles.md):
// the cartographic style, with lines parallel to the shore inside water features at non-linear
// intervals. The shore distance comes from the model's shoreline map (world units, bound on unit 8
// by Waterlining::attach), sampled at the fragment's scene position, so the lines live in world
// space. Line k (1..count) lies at d_k = spacing k^exponent, the shoreline (k = 0) at 0; each is
// width pixels wide, box-filtered over the pixel, of strength 1 - fade (k - 1) / (count - 1).
// CPU twin: Waterlining::lineCoverage.
#pragma include "loa_cartographic.glsl"

layout(binding = 8) uniform sampler2D loa_waterDistance;
uniform bool loa_hasWaterDistance = false;
uniform vec4 loa_waterDistanceTransform = vec4(1.0, 1.0, 0.0, 0.0); // texcoord = xy * s + o
uniform vec3 loa_waterlining_lineColor = vec3(31.0, 120.0, 180.0) / 255.0; // Paired dark blue
uniform float loa_waterlining_spacing = 1.0;
uniform float loa_waterlining_exponent = 1.5;
uniform int loa_waterlining_count = 5;
uniform float loa_waterlining_width = 1.5;
uniform float loa_waterlining_fade = 0.6;
uniform bool loa_waterlining_shoreline = true;

// Coverage of the lines at shore distance d for a pixel of pixelSize world units.
float loa_waterlining_coverage(float d, float pixelSize)
{
    if (d < 0.0 || !(pixelSize > 0.0) || loa_waterlining_spacing <= 0.0)
        return 0.0;
    float e = max(loa_waterlining_exponent, 1.0e-3);
    int count = max(loa_waterlining_count, 0);
    // The nearest line index in k-space, and its neighbours (the spacing is not linear in k).
    int k0 = int(round(pow(d / loa_waterlining_spacing, 1.0 / e)));
    float best = 0.0;
    for (int k = k0 - 1; k <= k0 + 1; ++k)
    {
        if (k < (loa_waterlining_shoreline ? 0 : 1) || k > count)
            continue;
        float dk = loa_waterlining_spacing * pow(float(k), e);
        float strength = k == 0 ? 1.0 : 1.0 - loa_waterlining_fade * float(k - 1) / float(max(count - 1, 1));
        float c = clamp(0.5 * loa_waterlining_width + 0.5 - abs(d - dk) / pixelSize, 0.0, 1.0);
        best = max(best, clamp(strength, 0.0, 1.0) * c);
    }
    return best;
}

vec4 loa_styleColor(vec3 scenePosition, vec3 viewPosition, vec3 viewNormal, vec2 texCoord, vec4 color)
{
    int type = loa_cartographic_type();
    vec3 base = loa_cartographic_color() * loa_cartographic_light(viewPosition, viewNormal);
    if (type != 3 || !loa_hasWaterDistance)
        return vec4(base, color.a);
    vec2 tc = scenePosition.xy * loa_waterDistanceTransform.xy + loa_waterDistanceTransform.zw;
    float d = texture(loa_waterDistance, tc).r;
    // World units per pixel along the distance gradient (|grad d| = 1 in the world).
    float pixelSize = length(vec2(dFdx(d), dFdy(d)));
    float inside = all(greaterThanEqual(tc, vec2(0.0))) && all(lessThanEqual(tc, vec2(1.0))) ? 1.0 : 0.0;
    float line = inside * loa_waterlining_coverage(d, pixelSize);
    return vec4(mix(base, loa_waterlining_lineColor, line), color.a);
}
