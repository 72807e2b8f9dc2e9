#version 430
// The pass contract of osgLoA's GPU image filters (osgLoA::GpuFilterEngine, docs/filtering.md).
//
// A filter pass is this shader object linked with the pass's own shader object
// (shaders/loa_filter_NAME.comp.glsl), both compiled with the pass's #defines. The engine
// binds:
//   - image units 0..3: the pass's inputs (rgba32f atlases: the filter's input or earlier
//     passes' outputs), unit 4: the output atlas;
//   - SSBO 0: the region table: one entry per image in the atlas (a texture's mip level, or a
//     rendered frame): its rectangle in the atlas (x, y, width, height) and wrap modes
//     (0 repeat, 1 clamp, 2 mirror, as osgLoA::WrapMode); all atlases of a run share the layout;
//   - SSBO 1: the work list: (region, tile x, tile y, -) per work group (8x8 texel tiles), or
//     (region, first line / 64, -, -) per work group of 64 lines for LOA_LINES passes;
//   - LOA_INTERIOR = 1 for the variant that runs tiles whose reads stay inside the region
//     (within the pass's radius + 1), so loa_fetchN need not wrap.
// TEXELS passes define vec4 loa_filterTexel(ivec2 p) for texel p of the current region (0-based,
// inside the region); the engine stores the result. LINES passes (LOA_LINES = 1 rows, 2 columns)
// define void loa_filterLine(int line) and store with loa_store. Inputs are read with
// loa_fetchN(ivec2) (integer texel, wrapped by the region's modes) and loa_sampleN(vec2)
// (bilinear at continuous texel coordinates, texel centres at i + 0.5, wrapped: what
// osgLoA::FilterImage::sampleBilinear computes on the CPU).

#ifndef LOA_LINES
#define LOA_LINES 0
#endif

#if LOA_LINES == 0
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
#else
layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;
#endif

struct LoaRegion
{
    ivec4 rect; // x, y, width, height in the atlas
    ivec4 wrap; // wrap s, wrap t, -, -
};
layout(std430, binding = 0) readonly buffer LoaRegions { LoaRegion loa_regions[]; };
layout(std430, binding = 1) readonly buffer LoaWork { uvec4 loa_work[]; };
uniform uint loa_workCount;

layout(rgba32f, binding = 0) uniform readonly image2D loa_in0;
layout(rgba32f, binding = 1) uniform readonly image2D loa_in1;
layout(rgba32f, binding = 2) uniform readonly image2D loa_in2;
layout(rgba32f, binding = 3) uniform readonly image2D loa_in3;
layout(rgba32f, binding = 4) uniform image2D loa_out;

ivec4 loa_rect;
ivec2 loa_wrapMode;

int loa_wrapIndex(int i, int n, int mode)
{
    if (i >= 0 && i < n) return i;
    // GLSL leaves % undefined for negative operands: fold negative i explicitly.
    if (mode == 0) return i >= 0 ? i % n : (n - 1) - ((-i - 1) % n);
    if (mode == 2)
    {
        int period = 2 * n;
        int r = i >= 0 ? i % period : (period - 1) - ((-i - 1) % period);
        return r < n ? r : period - 1 - r;
    }
    return i < 0 ? 0 : n - 1;
}

ivec2 loa_size() { return loa_rect.zw; }
#if defined(LOA_INTERIOR) && LOA_INTERIOR == 1
// The engine dispatches tiles whose reads all lie inside their region (the tile dilated by the
// pass's radius + 1) with this variant: no wrap arithmetic (llvmpipe runs a Gaussian pass about
// 3x faster without it; docs/filtering.md).
ivec2 loa_wrapped(ivec2 p) { return loa_rect.xy + p; }
#else
ivec2 loa_wrapped(ivec2 p)
{
    return loa_rect.xy + ivec2(loa_wrapIndex(p.x, loa_rect.z, loa_wrapMode.x),
                               loa_wrapIndex(p.y, loa_rect.w, loa_wrapMode.y));
}
#endif

vec4 loa_fetch0(ivec2 p) { return imageLoad(loa_in0, loa_wrapped(p)); }
vec4 loa_fetch1(ivec2 p) { return imageLoad(loa_in1, loa_wrapped(p)); }
vec4 loa_fetch2(ivec2 p) { return imageLoad(loa_in2, loa_wrapped(p)); }
vec4 loa_fetch3(ivec2 p) { return imageLoad(loa_in3, loa_wrapped(p)); }
vec4 loa_load(ivec2 p) { return imageLoad(loa_out, loa_wrapped(p)); }
void loa_store(ivec2 p, vec4 v) { imageStore(loa_out, loa_rect.xy + p, v); }

#define LOA_BILINEAR(FETCH)                                                                        \
    vec2 f = p - 0.5;                                                                              \
    vec2 b = floor(f);                                                                             \
    vec2 a = f - b;                                                                                \
    ivec2 i = ivec2(b);                                                                            \
    return mix(mix(FETCH(i), FETCH(i + ivec2(1, 0)), a.x), mix(FETCH(i + ivec2(0, 1)), FETCH(i + ivec2(1, 1)), a.x), \
               a.y);
vec4 loa_sample0(vec2 p) { LOA_BILINEAR(loa_fetch0) }
vec4 loa_sample1(vec2 p) { LOA_BILINEAR(loa_fetch1) }
vec4 loa_sample2(vec2 p) { LOA_BILINEAR(loa_fetch2) }
vec4 loa_sample3(vec2 p) { LOA_BILINEAR(loa_fetch3) }

#if LOA_LINES == 0
vec4 loa_filterTexel(ivec2 p);
#else
void loa_filterLine(int line);
#endif

void main()
{
    uint item = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    if (item >= loa_workCount) return;
    uvec4 w = loa_work[item];
    LoaRegion r = loa_regions[w.x];
    loa_rect = r.rect;
    loa_wrapMode = r.wrap.xy;
#if LOA_LINES == 0
    ivec2 p = ivec2(w.yz) * 8 + ivec2(gl_LocalInvocationID.xy);
    if (p.x >= loa_rect.z || p.y >= loa_rect.w) return;
    imageStore(loa_out, loa_rect.xy + p, loa_filterTexel(p));
#else
    int line = int(w.y) * 64 + int(gl_LocalInvocationID.x);
    if (line >= (LOA_LINES == 1 ? loa_rect.w : loa_rect.z)) return;
    loa_filterLine(line);
#endif
}
