#version 430
// osgLoA::DeferredTexturing, texture prefetch (paper 000 §4.2): for each G-buffer fragment, mark
// the atlas tiles (8x8 texels, osgLoA::GpuFilterEngine::TILE) holding the texels that trilinear
// filtering reads: the 2x2 bilinear footprint (texel centres at i + 0.5, indices wrapped by the
// texture's modes) in level floor(lod) and, when the LoD has a fraction, level floor(lod) + 1, the
// LoD clamped to [0, levels - 1] (magnification reads level 0 only). With loa_markCoarser
// (progressive filtering) the footprints in all coarser levels are marked too: they are the
// fallback the shading stage uses while a finer level waits for the budget.
// The marks are one bit per tile (atomicOr), read back by the CPU.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(rgba32f, binding = 0) uniform readonly image2D loa_gTexCoord; // u, v, lod, TID

#pragma include "loa_deferred_atlas.glsl"
layout(std430, binding = 0) readonly buffer LoaDeferredPages { LoaPage loa_pages[]; };
layout(std430, binding = 1) readonly buffer LoaDeferredRegions { LoaAtlasRegion loa_atlasRegions[]; };
layout(std430, binding = 2) buffer LoaDeferredTileFlags { uint loa_tileFlags[]; };

uniform ivec2 loa_gbufferSize;
uniform int loa_textureCount;
uniform bool loa_markCoarser;


void loa_markTexel(LoaAtlasRegion r, int x, int y)
{
    uint tile = uint(r.tiles.x + (y >> 3) * r.tiles.y + (x >> 3));
    atomicOr(loa_tileFlags[tile >> 5], 1u << (tile & 31u));
}

void loa_markFootprint(int region, ivec2 wrap, vec2 uv)
{
    LoaAtlasRegion r = loa_atlasRegions[region];
    vec2 p = uv * vec2(r.rect.zw) - 0.5;
    ivec2 i = ivec2(floor(p));
    int x0 = loa_deferredWrap(i.x, r.rect.z, wrap.x), x1 = loa_deferredWrap(i.x + 1, r.rect.z, wrap.x);
    int y0 = loa_deferredWrap(i.y, r.rect.w, wrap.y), y1 = loa_deferredWrap(i.y + 1, r.rect.w, wrap.y);
    loa_markTexel(r, x0, y0);
    loa_markTexel(r, x1, y0);
    loa_markTexel(r, x0, y1);
    loa_markTexel(r, x1, y1);
}

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= loa_gbufferSize.x || p.y >= loa_gbufferSize.y) return;
    vec4 g = imageLoad(loa_gTexCoord, p);
    int tid = int(g.w);
    if (g.w < 0.0 || tid >= loa_textureCount) return;
    LoaPage page = loa_pages[tid];
    int levels = page.size.z;
    float lod = isnan(g.z) ? 0.0 : clamp(g.z, 0.0, float(levels - 1));
    int l0 = int(floor(lod));
    int first = page.addressing.z;
    ivec2 wrap = page.addressing.xy;
    loa_markFootprint(first + l0, wrap, g.xy);
    if (loa_markCoarser)
    {
        for (int l = l0 + 1; l < levels; ++l)
            loa_markFootprint(first + l, wrap, g.xy);
    }
    else if (lod > float(l0) && l0 + 1 < levels)
        loa_markFootprint(first + l0 + 1, wrap, g.xy);
}
