#version 450 compatibility
// Graphic style "streets" (paper 004 §3.2.3: streets in Brewer colours with their edges enhanced;
// osgLoA::StreetPresentation, docs/styles.md): the cartographic style, with streets drawn as on a
// road map. A street's class (major, minor, path, rail) comes from its sub-type where the model
// says (loa_streets_classOf[code]), else from its width (loa_streetWidth, measured by StreetPresentation::attach); it takes the
// class's fill colour, and its casing colour within loa_streets_casingPixels[class] pixels of the
// street's edge, box-filtered over the pixel. The edge distance comes from the model's street map
// (signed, world units, unit 10), so casings live in world space and no casing crosses a junction.
// CPU twins: StreetPresentation::classOf, casingCoverage.
#pragma include "loa_cartographic.glsl"

layout(binding = 10) uniform sampler2D loa_streetDistance;
uniform bool loa_hasStreetDistance = false;
uniform vec4 loa_streetDistanceTransform = vec4(1.0, 1.0, 0.0, 0.0); // texcoord = xy * s + o
uniform float loa_streetWidth = 0.0; // per street feature; 0: not measured
uniform float loa_streets_majorWidth = 7.5;
uniform float loa_streets_minorWidth = 3.5;
uniform vec3 loa_streets_fill[4];
uniform vec3 loa_streets_casing[4];
uniform float loa_streets_casingPixels[4];

uniform int loa_streets_classOf[64]; // class per FeatureSubType code (-1: by the width)

int loa_streets_class()
{
    int c = loa_featureSubType;
    int k = (c >= 0 && c < 64) ? loa_streets_classOf[c] : -1;
    if (k >= 0 && k < 4)
        return k;
    if (!(loa_streetWidth > 0.0))
        return -1;
    return loa_streetWidth >= loa_streets_majorWidth ? 0 : (loa_streetWidth >= loa_streets_minorWidth ? 1 : 2);
}

vec4 loa_styleColor(vec3 scenePosition, vec3 viewPosition, vec3 viewNormal, vec2 texCoord, vec4 color)
{
    int type = loa_cartographic_type();
    float light = loa_cartographic_light(viewPosition, viewNormal);
    vec3 base = loa_cartographic_color() * light;
    if (type != 2)
        return vec4(base, color.a);
    int k = loa_streets_class();
    if (k < 0)
        return vec4(base, color.a);
    vec3 fill = loa_streets_fill[k] * light;
    if (!loa_hasStreetDistance)
        return vec4(fill, color.a);
    vec2 tc = scenePosition.xy * loa_streetDistanceTransform.xy + loa_streetDistanceTransform.zw;
    float d = texture(loa_streetDistance, tc).r;
    // World units per pixel along the distance gradient (|grad d| = 1 in the world).
    float pixelSize = length(vec2(dFdx(d), dFdy(d)));
    float inside = all(greaterThanEqual(tc, vec2(0.0))) && all(lessThanEqual(tc, vec2(1.0))) ? 1.0 : 0.0;
    float w = loa_streets_casingPixels[k];
    float casing = (w > 0.0 && pixelSize > 0.0) ? inside * clamp(w + 0.5 - max(d, 0.0) / pixelSize, 0.0, 1.0) : 0.0;
    return vec4(mix(fill, loa_streets_casing[k] * light, casing), color.a);
}
