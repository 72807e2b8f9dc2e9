#version 430
// One separable box-mean pass of the guided filter (osgLoA::GuidedFilter): the mean over
// 2 LOA_RADIUS + 1 texels along LOA_AXIS (0 x, 1 y) of a value of input 0: LOA_SOURCE 1 the
// guide's moments (r, g, b, r r), 2 (r g, r b, g g, g b), 3 (b b, 0, 0, 0), 0 the input itself.
// The CPU twin is the boxMean of GuidedFilter.cpp.
vec4 loa_fetch0(ivec2 p);

vec4 loa_guidedValue(ivec2 p)
{
    vec4 c = loa_fetch0(p);
#if LOA_SOURCE == 1
    return vec4(c.rgb, c.r * c.r);
#elif LOA_SOURCE == 2
    return vec4(c.r * c.g, c.r * c.b, c.g * c.g, c.g * c.b);
#elif LOA_SOURCE == 3
    return vec4(c.b * c.b, 0.0, 0.0, 0.0);
#else
    return c;
#endif
}

vec4 loa_filterTexel(ivec2 p)
{
    const ivec2 d = LOA_AXIS == 0 ? ivec2(1, 0) : ivec2(0, 1);
    vec4 s = vec4(0.0);
    for (int k = -LOA_RADIUS; k <= LOA_RADIUS; ++k)
        s += loa_guidedValue(p + d * k);
    return s / float(2 * LOA_RADIUS + 1);
}
