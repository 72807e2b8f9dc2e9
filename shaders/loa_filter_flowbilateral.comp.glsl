#version 430
// One 1-D pass of the flow-based (orientation-aligned) bilateral filter (osgLoA::FlowBilateralFilter;
// Kyprianidis & Doellner 2008): input 0 a Lab image, input 1 the smoothed structure tensor.
// LOA_AXIS 0 filters along the gradient direction g = (t.y, -t.x), 1 along the edge tangent t,
// on the straight line x + j s, s = d / max(|d.x|, |d.y|), j = -LOA_STEPS..LOA_STEPS (bilinear
// samples), weights exp(-(j |s|)^2 / (2 sigma_d^2)) exp(-|c_j - c_0|^2 / (2 sigma_r^2)). Alpha
// kept. The CPU twin is FlowBilateralFilter::bilateralPass.
vec4 loa_fetch0(ivec2 p);
vec4 loa_fetch1(ivec2 p);
vec4 loa_sample0(vec2 p);

uniform float loa_sigmaD;
uniform float loa_sigmaR;

#pragma include "loa_structure_tensor.glsl"

vec4 loa_filterTexel(ivec2 p)
{
    vec2 t = loa_flowOfTensor(loa_fetch1(p).rgb).xy;
    vec2 d = LOA_AXIS == 0 ? vec2(t.y, -t.x) : t;
    vec2 s = d / max(abs(d.x), abs(d.y));
    float ds = length(s);
    vec2 x0 = vec2(p) + 0.5;
    vec4 c = loa_fetch0(p);
    vec3 sum = c.rgb;
    float norm = 1.0;
    float twoSigmaD2 = 2.0 * loa_sigmaD * loa_sigmaD, twoSigmaR2 = 2.0 * loa_sigmaR * loa_sigmaR;
    for (int j = 1; j <= LOA_STEPS; ++j)
    {
        float kd = exp(-(float(j) * ds) * (float(j) * ds) / twoSigmaD2);
        for (int side = 0; side < 2; ++side)
        {
            vec3 c1 = loa_sample0(side == 0 ? x0 + s * float(j) : x0 - s * float(j)).rgb;
            vec3 e = c1 - c.rgb;
            float k = kd * exp(-dot(e, e) / twoSigmaR2);
            sum += c1 * k;
            norm += k;
        }
    }
    return vec4(sum / norm, c.a);
}
