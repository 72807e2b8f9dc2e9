#version 450 compatibility
#pragma import_defines(LOA_MAX_FRAGMENTS)
// Stencil-routed A-buffer resolve (paper 004 §3.2.4, Algorithm 2), as functions; the CPU
// reference osgLoA::ReferenceCompositor does the very same operations (docs/abuffer.md).
//
// Uniforms (osgLoA::StencilRoutedABuffer::addResolveState sets them):
//   loa_abufferColor   sampler2DMSArray: RGBA8 straight-alpha colour, one layer per routing pass
//   loa_abufferDepth   sampler2DMSArray: window depth of the same samples (depth-stencil texture)
//   loa_abufferSamples int: samples routed per layer (N)
//   loa_abufferLayers  int: layers (routing passes) written this frame
// LOA_MAX_FRAGMENTS: the arrays' size; a StateSet define (StencilRoutedABuffer sets N x max passes,
// at most 64) overrides the default. Keep it small: llvmpipe's cost grows with it (docs/abuffer.md).
#ifndef LOA_MAX_FRAGMENTS
#define LOA_MAX_FRAGMENTS 64
#endif

uniform sampler2DMSArray loa_abufferColor;
uniform sampler2DMSArray loa_abufferDepth;
uniform int loa_abufferSamples;
uniform int loa_abufferLayers;

// Appends the pixel's routed fragments after the first `count` entries; returns the new count.
// Empty samples (depth 1, never routed: Algorithm 2 lines 4-7) are skipped. Routing fills the
// samples of a layer and the layers in arrival order, so a layer without any fragment ends the
// list. At most LOA_MAX_FRAGMENTS entries in all.
int loa_abufferFetch(ivec2 pixel, inout vec4 colors[LOA_MAX_FRAGMENTS], inout float depths[LOA_MAX_FRAGMENTS],
                     int count)
{
    for (int layer = 0; layer < loa_abufferLayers; ++layer)
    {
        bool any = false;
        for (int s = 0; s < loa_abufferSamples; ++s)
        {
            float d = texelFetch(loa_abufferDepth, ivec3(pixel, layer), s).r;
            if (d >= 1.0)
                continue;
            if (count >= LOA_MAX_FRAGMENTS)
                return count;
            colors[count] = texelFetch(loa_abufferColor, ivec3(pixel, layer), s);
            depths[count] = d;
            ++count;
            any = true;
        }
        if (!any)
            break;
    }
    return count;
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
