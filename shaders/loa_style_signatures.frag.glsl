#version 450 compatibility
// Graphic style "signatures" (paper 004 §3.2.3, Figure 8B, after Glanville 2004; osgLoA::
// GreenSpaceSignatures, docs/styles.md): the cartographic style, with map symbols of the kind of
// vegetation bombed over green spaces:
//  - a world-space grid of cells of size 2^l holds one symbol per cell, anchored at a point
//    jittered inside the cell by an integer hash of the cell;
//  - a symbol is a sprite of loa_signatures_symbolPixels standing upright on screen on the
//    projection of its anchor: it faces the viewer and keeps its size at any distance;
//  - the levels l = ceil(log2(C sigma)) and l + 1 are used (C = loa_signatures_cellPixels, sigma
//    the ground footprint of a pixel), each with a fraction of its symbols present that depends on
//    its cells' size on screen, so zooming adds or removes single symbols;
//  - the cells within ceil((symbolPixels + 1.5) / S) of the fragment's cell (S a cell's size on
//    screen) hold every symbol that can reach it, so none is cut at a cell border; the one
//    anchored lowest on screen is drawn in front.
// Vegetation standing on green ground (the ground map: GreenSpaceSignatures::attach) gives way to
// the symbols: drawn in this style alone it is left out; blended with other styles it shows the
// ground the view ray meets behind it.
// The symbol comes from the feature's sub-type: loa_signatures_symbols[loa_featureSubType].
// CPU twins: GreenSpaceSignatures::hash, anchor, cellSymbol, level, visibleFraction, presence,
// symbolDistance, sample.
#pragma include "loa_cartographic.glsl"

uniform mat4 loa_viewToScene; // view -> LoA node local coordinates (loa_style.vert.glsl)
uniform mat4 loa_sceneToView;
uniform int loa_signatures_symbols[64]; // symbol per sub-type code (GreenSpaceSignatures::Symbol)
uniform float loa_signatures_cellPixels = 10.0;
uniform float loa_signatures_symbolPixels = 11.0;
uniform float loa_signatures_jitter = 0.6;
uniform float loa_signatures_minUp = 0.7;
uniform vec3 loa_signatures_ink = vec3(0.0, 68.0, 27.0) / 255.0;
uniform vec3 loa_signatures_fill[7];
uniform float loa_signatures_vegetationHeight = 0.25;
// The ground map (GreenSpaceSignatures::attach): lowest green surface per texel, GL_NEAREST.
layout(binding = 9) uniform sampler2D loa_greenGround;
uniform vec4 loa_greenGroundTransform = vec4(1.0, 1.0, 0.0, 0.0); // texcoord = xy * s + o
uniform bool loa_hasGreenGround = false;
uniform float loa_greenGroundTexel = 0.0; // the map's texel size, world units

const int LOA_SIG_NONE = 0, LOA_SIG_DECIDUOUS = 1, LOA_SIG_CONIFEROUS = 2, LOA_SIG_MIXED = 3,
          LOA_SIG_GRASS = 4, LOA_SIG_SCRUB = 5, LOA_SIG_ORCHARD = 6;

uint loa_signatures_pcg(uint x)
{
    x = x * 747796405u + 2891336453u;
    uint w = ((x >> ((x >> 28u) + 4u)) ^ x) * 277803737u;
    return (w >> 22u) ^ w;
}

uint loa_signatures_hash(ivec2 c, int level, uint salt)
{
    uint l = loa_signatures_pcg(uint(level + 64) * 83492791u ^ salt);
    uint y = loa_signatures_pcg(uint(c.y) * 19349663u ^ l);
    return loa_signatures_pcg(uint(c.x) * 73856093u ^ y);
}

float loa_signatures_unit(uint h)
{
    return float(h >> 8u) / 16777216.0;
}

float loa_signatures_segment(vec2 q, vec2 a, vec2 b)
{
    vec2 pa = q - a, ba = b - a;
    float h = clamp(dot(pa, ba) / dot(ba, ba), 0.0, 1.0);
    return length(pa - ba * h);
}

float loa_signatures_triangle(vec2 q, vec2 a, vec2 b, vec2 c)
{
    float d = min(loa_signatures_segment(q, a, b), min(loa_signatures_segment(q, b, c), loa_signatures_segment(q, c, a)));
    vec2 ab = b - a, bc = c - b, ca = a - c;
    bool inside = ab.x * (q.y - a.y) - ab.y * (q.x - a.x) >= 0.0 && bc.x * (q.y - b.y) - bc.y * (q.x - b.x) >= 0.0 &&
                  ca.x * (q.y - c.y) - ca.y * (q.x - c.x) >= 0.0;
    return inside ? -d : d;
}

// The ground map's height at a world x/y; -1e30 where there is no green ground (or no map).
float loa_signatures_ground(vec2 xy)
{
    if (!loa_hasGreenGround)
        return -1.0e30;
    return textureLod(loa_greenGround, xy * loa_greenGroundTransform.xy + loa_greenGroundTransform.zw, 0.0).r;
}

// Signed distance in symbol heights; inkOnly for trunks and strokes.
float loa_signatures_distance(int symbol, vec2 q, out bool inkOnly)
{
    const float inf = 1.0e30;
    float fill = inf, ink = inf;
    if (symbol == LOA_SIG_DECIDUOUS || symbol == LOA_SIG_ORCHARD)
    {
        fill = length(q - vec2(0.0, 0.64)) - 0.34;
        ink = loa_signatures_segment(q, vec2(0.0, 0.02), vec2(0.0, 0.34)) - 0.06;
    }
    else if (symbol == LOA_SIG_CONIFEROUS)
    {
        fill = loa_signatures_triangle(q, vec2(-0.3, 0.22), vec2(0.3, 0.22), vec2(0.0, 0.98));
        ink = loa_signatures_segment(q, vec2(0.0, 0.02), vec2(0.0, 0.24)) - 0.06;
    }
    else if (symbol == LOA_SIG_GRASS)
    {
        ink = min(loa_signatures_segment(q, vec2(0.0, 0.04), vec2(-0.28, 0.5)),
                  min(loa_signatures_segment(q, vec2(0.0, 0.04), vec2(0.0, 0.62)),
                      loa_signatures_segment(q, vec2(0.0, 0.04), vec2(0.28, 0.5)))) - 0.05;
    }
    else if (symbol == LOA_SIG_SCRUB)
    {
        fill = min(min(length(q - vec2(-0.2, 0.24)) - 0.2, length(q - vec2(0.2, 0.24)) - 0.2),
                   length(q - vec2(0.0, 0.42)) - 0.22);
    }
    inkOnly = ink < fill;
    return min(fill, ink);
}

vec4 loa_styleColor(vec3 scenePosition, vec3 viewPosition, vec3 viewNormal, vec2 texCoord, vec4 color)
{
    int type = loa_cartographic_type();
    int code = loa_featureSubType;
    int featureSymbol = (type == 4 && code >= 0 && code < 64) ? loa_signatures_symbols[code] : LOA_SIG_NONE;
    // The surface's own flat-shading factor, in uniform control flow (it takes derivatives).
    float surfaceLight = loa_cartographic_light(viewPosition, viewNormal);
    // Vegetation (more than vegetationHeight + one ground-map texel above the map: the map holds
    // the ground at texel centres, and sloped ground rises by up to about a texel between them)
    // shows the ground the view ray meets behind it: p is the fragment's own position or that
    // ground point.
    vec3 p = scenePosition;
    float ground = loa_signatures_ground(scenePosition.xy);
    bool aboveGround = featureSymbol != LOA_SIG_NONE && ground > -1.0e29 &&
                       scenePosition.z > ground + loa_signatures_vegetationHeight + loa_greenGroundTexel;
    bool vegetation = aboveGround;
    if (vegetation)
    {
        bool ortho = gl_ProjectionMatrix[3][3] == 1.0;
        vec3 eye = (loa_viewToScene * vec4(0.0, 0.0, 0.0, 1.0)).xyz;
        vec3 dir = ortho ? mat3(loa_viewToScene) * vec3(0.0, 0.0, -1.0) : scenePosition - eye;
        if (dir.z < -1.0e-6)
            p = scenePosition + dir * ((ground - scenePosition.z) / dir.z);
        else
            vegetation = false;
    }
    // Derivatives are taken at the top level, before any discard.
    vec2 jx = dFdx(p.xy), jy = dFdy(p.xy);
    vec4 clipF = gl_ProjectionMatrix * (loa_sceneToView * vec4(p, 1.0));
    vec2 ndcF = clipF.xy / clipF.w;
    vec2 pixelsPerNdc = 1.0 / vec2(dFdx(ndcF.x), dFdy(ndcF.y));
#if defined(LOA_PASS_GBUFFER_COLOR)
    // Drawn in this style alone: the vegetation is left out, and the feature's own ground behind
    // it (depth, normal and edges included) shows. Blended with other styles (fused, A-buffer,
    // ping-pong) the fragment stays, showing that ground in this style's share.
    if (aboveGround)
        discard;
#endif
    vec3 n = vegetation ? vec3(0.0, 0.0, 1.0) : normalize(mat3(loa_viewToScene) * viewNormal);
    if (n.z < 0.0)
        n = -n;
    float light = vegetation ? loa_cartographic_ambient + (1.0 - loa_cartographic_ambient) *
                                                             max(dot(normalize(mat3(loa_sceneToView) * n),
                                                                     normalize(loa_lightDirection)),
                                                                 0.0)
                             : surfaceLight;
    // No symbols where there is no green ground (a green feature without ground geometry, or a
    // model not prepared): the feature is drawn as cartographic draws it.
    if (!(ground > -1.0e29))
        featureSymbol = LOA_SIG_NONE;
    vec3 base = loa_cartographic_color() * light;
    if (featureSymbol <= LOA_SIG_NONE || featureSymbol > LOA_SIG_ORCHARD || n.z < loa_signatures_minUp)
        return vec4(base, color.a);
    float a = dot(jx, jx), b = dot(jx, jy), d = dot(jy, jy);
    float sigma = sqrt(0.5 * (a + d) + sqrt(0.25 * (a - d) * (a - d) + b * b));
    if (!(sigma > 0.0) || any(isinf(pixelsPerNdc)) || any(isnan(pixelsPerNdc)))
        return vec4(base, color.a);
    float cellPixels = loa_signatures_cellPixels;
    float size = max(1.0, min(loa_signatures_symbolPixels, 2.0 * cellPixels - 1.5));
    float jitter = featureSymbol == LOA_SIG_ORCHARD ? 0.0 : clamp(loa_signatures_jitter, 0.0, 1.0);
    int l0 = int(clamp(ceil(log2(max(cellPixels * sigma, 1.0e-30))), -40.0, 40.0));
    float bestY = 1.0e30, bestAlpha = 0.0, bestInk = 0.0;
    int bestSymbol = LOA_SIG_NONE;
    for (int l = l0; l <= l0 + 1; ++l)
    {
        float s = exp2(float(l));
        float S = s / sigma;
        float f = (S <= cellPixels || S >= 4.0 * cellPixels) ? 0.0
                  : (S <= 2.0 * cellPixels ? (S - cellPixels) / cellPixels : (4.0 * cellPixels - S) / (2.0 * cellPixels));
        if (f <= 0.0)
            continue;
        ivec2 cell0 = ivec2(floor(p.xy / s));
        // Cells within reach: a symbol reaches size + 1.5 pixels from its anchor.
        int r = int(ceil((size + 1.5) / S));
        for (int j = -r; j <= r; ++j)
            for (int i = -r; i <= r; ++i)
            {
                ivec2 c = cell0 + ivec2(i, j);
                float pres = clamp((1.1 * f - loa_signatures_unit(loa_signatures_hash(c, l, 3u))) / 0.1, 0.0, 1.0);
                if (pres <= 0.0)
                    continue;
                int sym = featureSymbol;
                if (sym == LOA_SIG_MIXED)
                    sym = loa_signatures_unit(loa_signatures_hash(c, l, 4u)) < 0.5 ? LOA_SIG_DECIDUOUS : LOA_SIG_CONIFEROUS;
                else if (sym == LOA_SIG_ORCHARD)
                    sym = LOA_SIG_DECIDUOUS;
                vec2 u = vec2(loa_signatures_unit(loa_signatures_hash(c, l, 1u)),
                              loa_signatures_unit(loa_signatures_hash(c, l, 2u)));
                vec2 anchor = (vec2(c) + 0.5 + jitter * (u - 0.5)) * s;
                float z = loa_signatures_ground(anchor);
                vec4 clipA = gl_ProjectionMatrix * (loa_sceneToView * vec4(anchor, z > -1.0e29 ? z : p.z, 1.0));
                if (clipA.w <= 0.0)
                    continue;
                vec2 anchorPixel = gl_FragCoord.xy + (clipA.xy / clipA.w - ndcF) * pixelsPerNdc;
                bool inkOnly;
                float dist = loa_signatures_distance(sym, (gl_FragCoord.xy - anchorPixel) / size, inkOnly) * size;
                float alpha = clamp(0.5 - dist, 0.0, 1.0) * pres;
                if (alpha <= 0.0 || !(anchorPixel.y < bestY))
                    continue;
                bestY = anchorPixel.y;
                bestAlpha = alpha;
                bestInk = inkOnly ? 1.0 : clamp(dist + 1.5, 0.0, 1.0);
                bestSymbol = sym;
            }
    }
    if (bestSymbol == LOA_SIG_NONE)
        return vec4(base, color.a);
    vec3 symbolColor = mix(loa_signatures_fill[bestSymbol], loa_signatures_ink, bestInk);
    return vec4(mix(base, symbolColor, bestAlpha), color.a);
}
