#version 450 compatibility
#pragma import_defines(LOA_MAX_FRAGMENTS)
// StencilRoutedABuffer::createResolveNode: composites the A-buffer of this pixel (Algorithm 2)
// and outputs it premultiplied; the node blends it with ONE, ONE_MINUS_SRC_ALPHA over what the
// camera drew before. Linked with loa_abuffer_resolve.frag.glsl.
#ifndef LOA_MAX_FRAGMENTS
#define LOA_MAX_FRAGMENTS 64
#endif

int loa_abufferFetch(ivec2 pixel, inout vec4 colors[LOA_MAX_FRAGMENTS], inout float depths[LOA_MAX_FRAGMENTS],
                     int count);
vec4 loa_compositeLayers(int count, inout vec4 colors[LOA_MAX_FRAGMENTS], inout float depths[LOA_MAX_FRAGMENTS],
                         float mergeEpsilon);

uniform float loa_abufferMergeEpsilon;

layout(location = 0) out vec4 loa_fragColor;

void main()
{
    vec4 colors[LOA_MAX_FRAGMENTS];
    float depths[LOA_MAX_FRAGMENTS];
    int count = loa_abufferFetch(ivec2(gl_FragCoord.xy), colors, depths, 0);
    if (count == 0)
        discard;
    loa_fragColor = loa_compositeLayers(count, colors, depths, loa_abufferMergeEpsilon);
}
