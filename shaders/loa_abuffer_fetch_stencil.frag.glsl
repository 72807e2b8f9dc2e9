#version 450 compatibility
#pragma import_defines(LOA_MAX_FRAGMENTS)
// Fetch of the stencil-routed A-buffer (osgLoA::StencilRoutedABuffer; Myers & Bavoil 2007), linked
// with loa_abuffer_resolve.frag.glsl. Uniforms (StencilRoutedABuffer::addResolveState):
//   loa_abufferColor   sampler2DMSArray: RGBA8 straight-alpha colour, one layer per routing pass
//   loa_abufferDepth   sampler2DMSArray: window depth of the same samples (depth-stencil texture)
//   loa_abufferSamples int: samples routed per layer (N)
//   loa_abufferLayers  int: layers (routing passes) written this frame
#ifndef LOA_MAX_FRAGMENTS
#define LOA_MAX_FRAGMENTS 64
#endif

bool loa_abufferInRegion(ivec2 pixel);

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
    if (!loa_abufferInRegion(pixel))
        return count;
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
