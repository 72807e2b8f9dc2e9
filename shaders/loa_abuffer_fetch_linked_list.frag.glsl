#version 450 compatibility
#pragma import_defines(LOA_MAX_FRAGMENTS)
// Fetch of the per-pixel linked-list A-buffer (osgLoA::LinkedListABuffer), linked with
// loa_abuffer_resolve.frag.glsl: walks the pixel's list. When it holds more fragments than the
// arrays, the nearest are kept (each further fragment replaces the farthest kept one if it is
// nearer), so what is lost is what lies behind LOA_MAX_FRAGMENTS others.
#ifndef LOA_MAX_FRAGMENTS
#define LOA_MAX_FRAGMENTS 64
#endif

layout(binding = 7, r32ui) uniform readonly uimage2D loa_listHeads;
layout(std430, binding = 10) readonly buffer LoaListNodes { uint loa_listNodes[]; };
layout(std430, binding = 11) readonly buffer LoaListCounter { uint loa_listCount; uint loa_listCapacity; };

bool loa_abufferInRegion(ivec2 pixel);

int loa_abufferFetch(ivec2 pixel, inout vec4 colors[LOA_MAX_FRAGMENTS], inout float depths[LOA_MAX_FRAGMENTS],
                     int count)
{
    if (!loa_abufferInRegion(pixel))
        return count;
    ivec2 size = imageSize(loa_listHeads);
    if (pixel.x < 0 || pixel.y < 0 || pixel.x >= size.x || pixel.y >= size.y)
        return count;
    int start = count;
    uint stored = min(loa_listCount, loa_listCapacity);
    uint node = imageLoad(loa_listHeads, pixel).r;
    // Every node links to one stored before it, so a list has at most `stored` nodes.
    for (uint steps = 0u; node < stored && steps < stored; ++steps)
    {
        vec4 c = unpackUnorm4x8(loa_listNodes[3u * node]);
        float d = uintBitsToFloat(loa_listNodes[3u * node + 1u]);
        if (count < LOA_MAX_FRAGMENTS)
        {
            colors[count] = c;
            depths[count] = d;
            ++count;
        }
        else
        {
            int farthest = start;
            for (int i = start + 1; i < count; ++i)
                if (depths[i] > depths[farthest])
                    farthest = i;
            if (start < count && d < depths[farthest])
            {
                colors[farthest] = c;
                depths[farthest] = d;
            }
        }
        node = loa_listNodes[3u * node + 2u];
    }
    return count;
}
