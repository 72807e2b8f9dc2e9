#version 430
// Soft lightness quantization (osgLoA::ColorQuantizationFilter, Winnemoeller et al. 2006) of a
// Lab image (input 0, from loa_filter_lab.comp.glsl stage 0): L* becomes
// q_nearest + dq/2 tanh(loa_phiQ (L* - q_nearest)), dq = 100 / loa_levels, q_nearest the nearest
// bin boundary; a*, b* and alpha pass through. The CPU twin is
// ColorQuantizationFilter::quantizeLightness.
vec4 loa_fetch0(ivec2 p);

uniform int loa_levels;
uniform float loa_phiQ;

vec4 loa_filterTexel(ivec2 p)
{
    vec4 lab = loa_fetch0(p);
    float dq = 100.0 / float(loa_levels);
    float nearest = dq * floor(lab.x / dq + 0.5);
    // tanh overflows (e^2x / e^2x) for large arguments in some drivers; |x| = 15 is already 1.
    float q = nearest + 0.5 * dq * tanh(clamp(loa_phiQ * (lab.x - nearest), -15.0, 15.0));
    return vec4(q, lab.yzw);
}
