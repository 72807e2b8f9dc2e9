#version 430
// sRGB <-> CIELab (D65, L* in [0, 100]) for the flow-based filters (osgLoA::FlowBilateralFilter,
// osgLoA::DoGFilter). LOA_LAB_STAGE 0: input 0 (sRGB-encoded) to (L*, a*, b*, alpha); stage 1:
// input 0 (Lab) back to sRGB (clamped to [0, 1] in linear RGB), alpha kept; with LOA_LAB_EDGES 1
// the colour is multiplied by input 1's red channel (an edge image). The CPU twins are
// FlowBilateralFilter::rgbToLab and labToRgb.
vec4 loa_fetch0(ivec2 p);
vec4 loa_fetch1(ivec2 p);

#ifndef LOA_LAB_EDGES
#define LOA_LAB_EDGES 0
#endif

#pragma include "loa_cielab.glsl"

vec4 loa_filterTexel(ivec2 p)
{
    vec4 c = loa_fetch0(p);
#if LOA_LAB_STAGE == 0
    return vec4(loa_cielab_fromSrgb(c.rgb), c.a);
#else
    vec3 rgb = loa_cielab_toSrgbColor(c.rgb);
#if LOA_LAB_EDGES
    rgb *= loa_fetch1(p).r;
#endif
    return vec4(rgb, c.a);
#endif
}
