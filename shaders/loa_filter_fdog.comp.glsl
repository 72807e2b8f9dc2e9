#version 430
// The flow-based difference of Gaussians (osgLoA::DoGFilter, flow = 1; Kang et al. 2007,
// Kyprianidis & Doellner 2008), input 1 the smoothed structure tensor.
// LOA_FDOG_STAGE 0: input 0 holds L* in channel 0; the 1-D DoG across the edge along the
//   gradient direction g = (t.y, -t.x): samples x + j s, s = g / max(|g.x|, |g.y|),
//   j = -LOA_STEPS..LOA_STEPS, bilinear; Gaussians of sigma_e and sigma_r = k sigma_e normalized
//   separately; writes (u = (G_e - tau G_r) scale, 0, 0, alpha).
// LOA_FDOG_STAGE 1: input 0 holds u; line integral convolution along the flow curve (Euler steps
//   of one texel, x += t(x), t from the bilinearly sampled tensor aligned with the previous step,
//   LOA_STEPS steps each way, weights exp(-i^2 / (2 sigma_m^2))), then the threshold; grey.
// The CPU twin is DoGFilter::flowDoG.
vec4 loa_fetch0(ivec2 p);
vec4 loa_fetch1(ivec2 p);
vec4 loa_sample0(vec2 p);
vec4 loa_sample1(vec2 p);

uniform float loa_sigmaE;
uniform float loa_sigmaR;
uniform float loa_sigmaM;
uniform float loa_tau;     // weight of the outer Gaussian
uniform float loa_scale;   // D -> u: 1 (edges) or 1 / (1 - tau) (xdog)
uniform float loa_epsilon; // threshold, L* units
uniform float loa_phi;     // steepness

// XDoG threshold (Winnemoeller et al. 2012): 1 if u >= epsilon, else 1 + tanh(phi (u - epsilon)).
// Twin of DoGFilter::threshold.
float loa_threshold(float u) { return u >= loa_epsilon ? 1.0 : 1.0 + tanh(max(loa_phi * (u - loa_epsilon), -20.0)); }

#pragma include "loa_structure_tensor.glsl"

vec4 loa_filterTexel(ivec2 p)
{
    vec2 x0 = vec2(p) + 0.5;
    vec4 c = loa_fetch0(p);
    vec2 t = loa_flowOfTensor(loa_fetch1(p).rgb).xy;
#if LOA_FDOG_STAGE == 0
    vec2 g = vec2(t.y, -t.x);
    vec2 s = g / max(abs(g.x), abs(g.y));
    float ds = length(s);
    float se = c.r, we = 1.0, sk = c.r, wk = 1.0;
    for (int j = 1; j <= LOA_STEPS; ++j)
    {
        float la = loa_sample0(x0 + s * float(j)).r;
        float lb = loa_sample0(x0 - s * float(j)).r;
        float d2 = (float(j) * ds) * (float(j) * ds);
        float ke = exp(-d2 / (2.0 * loa_sigmaE * loa_sigmaE));
        float kk = exp(-d2 / (2.0 * loa_sigmaR * loa_sigmaR));
        se += ke * (la + lb);
        we += 2.0 * ke;
        sk += kk * (la + lb);
        wk += 2.0 * kk;
    }
    return vec4((se / we - loa_tau * sk / wk) * loa_scale, 0.0, 0.0, c.a);
#else
    float sum = c.r, wsum = 1.0;
    for (int side = 0; side < 2; ++side)
    {
        vec2 x = x0;
        vec2 v = side == 0 ? t : -t;
        for (int i = 1; i <= LOA_STEPS; ++i)
        {
            x += v;
            float k = exp(-float(i * i) / (2.0 * loa_sigmaM * loa_sigmaM));
            sum += k * loa_sample0(x).r;
            wsum += k;
            vec2 tn = loa_flowOfTensor(loa_sample1(x).rgb).xy;
            if (dot(tn, v) < 0.0) tn = -tn;
            v = tn;
        }
    }
    float v = loa_threshold(sum / wsum);
    return vec4(v, v, v, c.a);
#endif
}
