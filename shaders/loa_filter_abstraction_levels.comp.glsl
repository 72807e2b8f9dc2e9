#version 430
// Abstraction levels (osgLoA::AbstractionLevelsFilter, paper 001 §4.1): input 0 is the frame with
// the focus weight phi in alpha, inputs 1..LOA_LEVELS the frame after 1..LOA_LEVELS Kuwahara
// iterations. The level lambda = mix(far, focus, phi); the colour is the linear interpolation of
// the two neighbouring levels (tent weights max(0, 1 - |lambda - i|)). Alpha (phi) passes through.
#ifndef LOA_LEVELS
#define LOA_LEVELS 3
#endif
uniform float loa_levelsFar;
uniform float loa_levelsFocus;

vec4 loa_fetch0(ivec2 p);
vec4 loa_fetch1(ivec2 p);
vec4 loa_fetch2(ivec2 p);
vec4 loa_fetch3(ivec2 p);

vec4 loa_filterTexel(ivec2 p)
{
    vec4 f = loa_fetch0(p);
    float phi = clamp(f.a, 0.0, 1.0);
    float lambda = mix(loa_levelsFar, loa_levelsFocus, phi);
    vec3 c = max(0.0, 1.0 - abs(lambda)) * f.rgb;
    c += max(0.0, 1.0 - abs(lambda - 1.0)) * loa_fetch1(p).rgb;
#if LOA_LEVELS >= 2
    c += max(0.0, 1.0 - abs(lambda - 2.0)) * loa_fetch2(p).rgb;
#endif
#if LOA_LEVELS >= 3
    c += max(0.0, 1.0 - abs(lambda - 3.0)) * loa_fetch3(p).rgb;
#endif
    return vec4(c, f.a);
}
