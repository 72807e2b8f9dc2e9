#version 450 compatibility
// Per-pixel linked-list A-buffer (osgLoA::LinkedListABuffer; Yang et al. 2010): what a routed draw
// stores. The fragment takes the next node of the buffer (atomic counter), keeps its straight-alpha
// colour (RGBA8, as the stencil-routed A-buffer stores it) and window depth at the pixel centre, and
// becomes the head of its pixel's list. Fragments whose alpha rounds to 0 in RGBA8 are dropped, and
// so are those beyond the buffer's capacity (the CPU sees the count and grows the buffer).
layout(binding = 7, r32ui) uniform coherent uimage2D loa_listHeads;
layout(std430, binding = 10) buffer LoaListNodes { uint loa_listNodes[]; };
layout(std430, binding = 11) buffer LoaListCounter { uint loa_listCount; uint loa_listCapacity; };

void loa_abufferWrite(vec4 straightAlphaColor)
{
    vec4 c = clamp(straightAlphaColor, 0.0, 1.0);
    if (!(c.a >= 0.5 / 255.0))
        discard;
    uint node = atomicAdd(loa_listCount, 1u);
    if (node < loa_listCapacity)
    {
        uint previous = imageAtomicExchange(loa_listHeads, ivec2(gl_FragCoord.xy), node);
        loa_listNodes[3u * node] = packUnorm4x8(c);
        loa_listNodes[3u * node + 1u] = floatBitsToUint(gl_FragCoord.z);
        loa_listNodes[3u * node + 2u] = previous;
    }
    discard; // nothing to write to the framebuffer (it has no attachments)
}
