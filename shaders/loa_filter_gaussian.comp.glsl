#version 430
// One separable pass of the Gaussian filter (osgLoA::GaussianFilter): LOA_AXIS 0 horizontal,
// 1 vertical; LOA_RADIUS taps each side with the normalized weights loa_weights[0..LOA_RADIUS]
// (centre first). Alpha passes through. The CPU twin is GaussianFilter::apply.
vec4 loa_fetch0(ivec2 p);

uniform float loa_weights[LOA_RADIUS + 1];

vec4 loa_filterTexel(ivec2 p)
{
    const ivec2 d = LOA_AXIS == 0 ? ivec2(1, 0) : ivec2(0, 1);
    vec4 c = loa_fetch0(p);
    vec3 s = c.rgb * loa_weights[0];
    for (int k = 1; k <= LOA_RADIUS; ++k)
        s += (loa_fetch0(p + d * k).rgb + loa_fetch0(p - d * k).rgb) * loa_weights[k];
    return vec4(s, c.a);
}
