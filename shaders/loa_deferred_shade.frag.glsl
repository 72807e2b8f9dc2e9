#version 450 compatibility
#pragma import_defines(LOA_DEFERRED_FILTERED, LOA_DEFERRED_PROGRESSIVE)
// osgLoA::DeferredTexturing, shading stage (paper 000 §4.1, §4.2): deferred texture mapping from
// the G-buffer with the per-level filtered texture data.
//
// Per pixel: the page table row of the pixel's TID gives the texture's levels, wrap modes and
// the atlas region of level 0 (levels follow it). The texture is sampled by manual trilinear
// filtering, as GL_LINEAR_MIPMAP_LINEAR does: lambda clamped to [0, levels - 1], bilinear
// samples (texel centres at i + 0.5, the four indices wrapped by the texture's modes inside the
// region, texelFetch: no atlas bleeding) in levels floor(lambda) and floor(lambda) + 1, blended by
// the fraction (paper Eq. 2 applied to the filtered levels).
//
// Variants (osg::StateSet::setDefine, set by the node per frame):
//  - neither define: no filter; the source atlas is sampled (plain deferred texturing);
//  - LOA_DEFERRED_FILTERED: every tile the frame needs was filtered before this pass (unlimited
//    budget), so the filtered atlas is sampled without checks;
//  - LOA_DEFERRED_FILTERED and LOA_DEFERRED_PROGRESSIVE: progressive filtering. A level's
//    bilinear footprint may touch tiles not filtered yet (loa_tileFrame = 0). Then the finest
//    coarser level whose footprint is filtered is used (the node filters coarse levels first),
//    or the unfiltered source atlas while none is. A tile filtered in frame f fades in over
//    loa_fadeFrames frames: weight (frame - f + 1) / fadeFrames.
// (Variants rather than uniform branches: llvmpipe runs both sides of a branch.)
//
// Lighting as the graphic styles (GraphicStyle::lightFactor): base colour x texture x
// (ambient + (1 - ambient) max(n.l, 0)). Pixels without geometry are discarded; the depth
// written is the G-buffer's, converted to this camera's projection.
uniform sampler2D loa_gTexCoord;     // u, v, lambda, TID
uniform sampler2D loa_gNormal;       // view normal, feature id
uniform sampler2D loa_gBaseColor;    // vertex colour
uniform sampler2D loa_gDepth;        // G-buffer depth
uniform sampler2D loa_sourceAtlas;   // unfiltered mip levels
uniform sampler2D loa_filteredAtlas; // filtered mip levels (same layout)

#pragma include "loa_deferred_atlas.glsl"
layout(std430, binding = 4) readonly buffer LoaDeferredPages { LoaPage loa_pages[]; };
layout(std430, binding = 5) readonly buffer LoaDeferredRegions { LoaAtlasRegion loa_atlasRegions[]; };
layout(std430, binding = 6) readonly buffer LoaDeferredTileState { uint loa_tileFrame[]; };

uniform int loa_textureCount = 0;
uniform uint loa_frame = 1u;
uniform uint loa_fadeFrames = 0u;
uniform ivec2 loa_viewportOrigin = ivec2(0);
uniform mat4 loa_gbufferProjectionInverse;
uniform vec3 loa_lightDirection = vec3(0.3, 0.5, 0.8); // towards the light, view space
uniform float loa_ambient = 0.35;

layout(location = 0) out vec4 loa_fragColor;


/** The bilinear footprint of uv in a region: wrapped texel indices (x0, x1, y0, y1) inside the
 *  region and the weights of x1 and y1. */
struct LoaFootprint
{
    ivec4 index;
    vec2 weight;
};

LoaFootprint loa_footprint(LoaAtlasRegion r, ivec2 wrap, vec2 uv)
{
    vec2 p = uv * vec2(r.rect.zw) - 0.5;
    vec2 b = floor(p);
    ivec2 i = ivec2(b);
    LoaFootprint f;
    f.index = ivec4(loa_deferredWrap(i.x, r.rect.z, wrap.x), loa_deferredWrap(i.x + 1, r.rect.z, wrap.x),
                    loa_deferredWrap(i.y, r.rect.w, wrap.y), loa_deferredWrap(i.y + 1, r.rect.w, wrap.y));
    f.weight = p - b;
    return f;
}

vec4 loa_bilinear(sampler2D atlas, LoaAtlasRegion r, LoaFootprint f)
{
    ivec2 o = r.rect.xy;
    vec4 a = texelFetch(atlas, o + f.index.xz, 0), b = texelFetch(atlas, o + f.index.yz, 0);
    vec4 c = texelFetch(atlas, o + f.index.xw, 0), d = texelFetch(atlas, o + f.index.yw, 0);
    return mix(mix(a, b, f.weight.x), mix(c, d, f.weight.x), f.weight.y);
}

#if defined(LOA_DEFERRED_FILTERED) && defined(LOA_DEFERRED_PROGRESSIVE)
/** -1 when the tile of a texel is not filtered, else its fade-in weight in (0, 1]. */
float loa_tileWeight(LoaAtlasRegion r, int x, int y)
{
    uint filteredIn = loa_tileFrame[r.tiles.x + (y >> 3) * r.tiles.y + (x >> 3)];
    if (filteredIn == 0u) return -1.0;
    if (loa_fadeFrames <= 1u) return 1.0;
    return clamp(float(loa_frame - filteredIn + 1u) / float(loa_fadeFrames), 0.0, 1.0);
}

float loa_footprintWeight(LoaAtlasRegion r, LoaFootprint f)
{
    return min(min(loa_tileWeight(r, f.index.x, f.index.z), loa_tileWeight(r, f.index.y, f.index.z)),
               min(loa_tileWeight(r, f.index.x, f.index.w), loa_tileWeight(r, f.index.y, f.index.w)));
}

/** Bilinear sample of one level: filtered where its tiles are, else the progressive fallback. */
vec4 loa_sampleLevel(LoaPage page, int level, vec2 uv)
{
    int first = page.addressing.z, levels = page.size.z;
    ivec2 wrap = page.addressing.xy;
    // The finest level >= level that is filtered and fully faded in (usually `level` itself).
    int k = level;
    LoaAtlasRegion rk;
    LoaFootprint fk;
    for (; k < levels; ++k)
    {
        rk = loa_atlasRegions[first + k];
        fk = loa_footprint(rk, wrap, uv);
        if (loa_footprintWeight(rk, fk) >= 1.0) break;
    }
    vec4 v;
    if (k < levels)
        v = loa_bilinear(loa_filteredAtlas, rk, fk);
    else
    {
        LoaAtlasRegion r = loa_atlasRegions[first + level];
        v = loa_bilinear(loa_sourceAtlas, r, loa_footprint(r, wrap, uv));
    }
    // Finer levels still fading in, coarse to fine.
    for (int j = min(k, levels) - 1; j >= level; --j)
    {
        LoaAtlasRegion rj = loa_atlasRegions[first + j];
        LoaFootprint fj = loa_footprint(rj, wrap, uv);
        float w = loa_footprintWeight(rj, fj);
        if (w > 0.0) v = mix(v, loa_bilinear(loa_filteredAtlas, rj, fj), w);
    }
    return v;
}
#else
/** Bilinear sample of one level: the filtered atlas (every needed tile is filtered) or, without
 *  a filter, the source atlas. */
vec4 loa_sampleLevel(LoaPage page, int level, vec2 uv)
{
    LoaAtlasRegion r = loa_atlasRegions[page.addressing.z + level];
    LoaFootprint f = loa_footprint(r, page.addressing.xy, uv);
#ifdef LOA_DEFERRED_FILTERED
    return loa_bilinear(loa_filteredAtlas, r, f);
#else
    return loa_bilinear(loa_sourceAtlas, r, f);
#endif
}
#endif

vec4 loa_sampleTrilinear(int tid, vec2 uv, float lambda)
{
    LoaPage page = loa_pages[tid];
    int levels = page.size.z;
    float lod = isnan(lambda) ? 0.0 : clamp(lambda, 0.0, float(levels - 1));
    int l0 = int(floor(lod));
    float fraction = lod - float(l0);
    vec4 c0 = loa_sampleLevel(page, l0, uv);
    vec4 c1 = loa_sampleLevel(page, min(l0 + 1, levels - 1), uv);
    // Where lambda is an integer, level l0 + 1 is not needed (nor filtered): select, not mix, so
    // that whatever its texels hold cannot leak in.
    return fraction > 0.0 ? mix(c0, c1, fraction) : c0;
}

void main()
{
    ivec2 pixel = ivec2(gl_FragCoord.xy) - loa_viewportOrigin;
    float depth = texelFetch(loa_gDepth, pixel, 0).r;
    if (depth >= 1.0) discard;
    vec4 g = texelFetch(loa_gTexCoord, pixel, 0);
    vec4 base = texelFetch(loa_gBaseColor, pixel, 0);
    vec3 n = texelFetch(loa_gNormal, pixel, 0).xyz;
    int tid = int(g.w);
    if (g.w >= 0.0 && tid < loa_textureCount) base *= loa_sampleTrilinear(tid, g.xy, g.z);
    float diffuse = max(dot(normalize(n), normalize(loa_lightDirection)), 0.0);
    loa_fragColor = vec4(base.rgb * (loa_ambient + (1.0 - loa_ambient) * diffuse), base.a);

    vec2 size = vec2(textureSize(loa_gDepth, 0));
    vec4 ndc = vec4((vec2(pixel) + 0.5) / size * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    vec4 view = loa_gbufferProjectionInverse * ndc;
    vec4 clip = gl_ProjectionMatrix * vec4(view.xyz / view.w, 1.0);
    gl_FragDepth = clamp(clip.z / clip.w * 0.5 + 0.5, 0.0, 1.0);
}
