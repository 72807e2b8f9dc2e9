#version 430
// The isotropic difference of Gaussians (osgLoA::DoGFilter, flow = 0) on L*: LOA_AXIS 0 blurs
// input 0's L* (channel 0) horizontally with both kernels (loa_weightsE: sigma_e, loa_weightsR:
// k sigma_e, one-sided, zero-padded to LOA_RADIUS + 1) into (G_e, G_r, 0, alpha); LOA_AXIS 1
// blurs those vertically and writes the threshold T((G_e - tau G_r) scale) as grey, alpha kept.
// The CPU twin is DoGFilter::apply with flow = 0.
vec4 loa_fetch0(ivec2 p);

uniform float loa_weightsE[LOA_RADIUS + 1];
uniform float loa_weightsR[LOA_RADIUS + 1];
uniform float loa_tau;     // weight of the outer Gaussian
uniform float loa_scale;   // D -> u: 1 (edges) or 1 / (1 - tau) (xdog)
uniform float loa_epsilon; // threshold, L* units
uniform float loa_phi;     // steepness

// XDoG threshold (Winnemoeller et al. 2012): 1 if u >= epsilon, else 1 + tanh(phi (u - epsilon)).
// Twin of DoGFilter::threshold.
float loa_threshold(float u) { return u >= loa_epsilon ? 1.0 : 1.0 + tanh(max(loa_phi * (u - loa_epsilon), -20.0)); }

vec4 loa_filterTexel(ivec2 p)
{
    const ivec2 d = LOA_AXIS == 0 ? ivec2(1, 0) : ivec2(0, 1);
    vec4 c = loa_fetch0(p);
    // Axis 0 blurs channel 0 twice; axis 1 blurs channel 0 with kernel E and channel 1 with R.
    int second = LOA_AXIS == 0 ? 0 : 1;
    float se = c[0] * loa_weightsE[0], sr = c[second] * loa_weightsR[0];
    for (int k = 1; k <= LOA_RADIUS; ++k)
    {
        vec4 a = loa_fetch0(p + d * k), b = loa_fetch0(p - d * k);
        se += (a[0] + b[0]) * loa_weightsE[k];
        sr += (a[second] + b[second]) * loa_weightsR[k];
    }
#if LOA_AXIS == 0
    return vec4(se, sr, 0.0, c.a);
#else
    float v = loa_threshold((se - loa_tau * sr) * loa_scale);
    return vec4(v, v, v, c.a);
#endif
}
