#version 450 compatibility
#pragma import_defines(LOA_MAX_FRAGMENTS)
// A-buffer resolve (paper 004 §3.2.4, Algorithm 2), as functions, for every order-independent
// transparency method (osgLoA::OrderIndependentTransparency): the method's fetch shader
// (loa_abuffer_fetch_*.frag.glsl) defines loa_abufferFetch, which gathers a pixel's fragments;
// sorting, merging and blending are here. The CPU reference osgLoA::ReferenceCompositor does the
// very same operations (docs/abuffer.md).
//
// LOA_MAX_FRAGMENTS: the arrays' size; a StateSet define (StencilRoutedABuffer sets N x max passes,
// at most 64) overrides the default. Keep it small: llvmpipe's cost grows with it (docs/abuffer.md).
#ifndef LOA_MAX_FRAGMENTS
#define LOA_MAX_FRAGMENTS 64
#endif

// The routed region (osgLoA::OrderIndependentTransparency::addRegionState): a mask of tiles where
// routed draws can have put fragments; the fetch of every method returns nothing elsewhere, and
// the storage there is not cleared (stale).
uniform sampler2D loa_abufferRegionMask;
uniform ivec3 loa_abufferRegion; // origin x, y of the tiles and their size in pixels; size 0: no mask

bool loa_abufferInRegion(ivec2 pixel)
{
    if (loa_abufferRegion.z <= 0)
        return true;
    ivec2 t = pixel - loa_abufferRegion.xy;
    if (t.x < 0 || t.y < 0)
        return false;
    t /= loa_abufferRegion.z;
    ivec2 size = textureSize(loa_abufferRegionMask, 0);
    if (t.x >= size.x || t.y >= size.y)
        return false;
    return texelFetch(loa_abufferRegionMask, t, 0).r > 0.5;
}

// Stable insertion sort of the first count entries by depth, nearest first.
void loa_sortByDepth(int count, inout vec4 colors[LOA_MAX_FRAGMENTS], inout float depths[LOA_MAX_FRAGMENTS])
{
    for (int i = 1; i < count; ++i)
    {
        vec4 c = colors[i];
        float d = depths[i];
        int j = i - 1;
        while (j >= 0 && depths[j] > d)
        {
            colors[j + 1] = colors[j];
            depths[j + 1] = depths[j];
            --j;
        }
        colors[j + 1] = c;
        depths[j + 1] = d;
    }
}

// Merges fragments of one surface in sorted entries (from the nearest unmerged fragment s, each
// following j with depths[j] - depths[s] <= mergeEpsilon joins it: colour = alpha-weighted mean,
// alpha = min(1, sum)); mergeEpsilon < 0 merges nothing. Returns the number of surfaces, which
// replace the first entries.
int loa_mergeSurfaces(int count, inout vec4 colors[LOA_MAX_FRAGMENTS], inout float depths[LOA_MAX_FRAGMENTS],
                      float mergeEpsilon)
{
    if (mergeEpsilon < 0.0)
        return count;
    int m = 0;
    int i = 0;
    while (i < count)
    {
        float d0 = depths[i];
        vec3 sumC = vec3(0.0);
        float sumA = 0.0;
        int j = i;
        while (j < count && depths[j] - d0 <= mergeEpsilon)
        {
            sumC += colors[j].rgb * colors[j].a;
            sumA += colors[j].a;
            ++j;
        }
        colors[m] = vec4(sumC / sumA, min(1.0, sumA));
        depths[m] = d0;
        ++m;
        i = j;
    }
    return m;
}

// Sorts, merges and blends back to front (color = mix(color, c.rgb, c.a) from transparent
// black): the premultiplied rgba of the layers, to be drawn with ONE, ONE_MINUS_SRC_ALPHA.
// Entries with alpha <= 0 must not be passed (loa_abufferWrite discards them).
vec4 loa_compositeLayers(int count, inout vec4 colors[LOA_MAX_FRAGMENTS], inout float depths[LOA_MAX_FRAGMENTS],
                         float mergeEpsilon)
{
    loa_sortByDepth(count, colors, depths);
    int n = loa_mergeSurfaces(count, colors, depths, mergeEpsilon);
    vec4 p = vec4(0.0);
    for (int k = n - 1; k >= 0; --k)
    {
        vec4 c = colors[k];
        p = vec4(mix(p.rgb, c.rgb, c.a), mix(p.a, 1.0, c.a));
    }
    return p;
}
