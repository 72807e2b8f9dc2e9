#version 430
// The guided filter's linear coefficients of output channel LOA_CHANNEL (osgLoA::GuidedFilter,
// He et al. 2013 Eq. 14-15 with the colour guide): from the window means of inputs 0..2 (mean r,
// g, b, rr | rg, rb, gg, gb | bb), Sigma = E[I I^T] - mu mu^T, a = (Sigma + loa_eps U)^-1
// Sigma e_c, b = mu_c - a . mu. Writes (a, b).
vec4 loa_fetch0(ivec2 p);
vec4 loa_fetch1(ivec2 p);
vec4 loa_fetch2(ivec2 p);

uniform float loa_eps;

vec4 loa_filterTexel(ivec2 p)
{
    vec4 m0 = loa_fetch0(p), m1 = loa_fetch1(p), m2 = loa_fetch2(p);
    vec3 mu = m0.rgb;
    float rr = m0.a - mu.r * mu.r, rg = m1.x - mu.r * mu.g, rb = m1.y - mu.r * mu.b;
    float gg = m1.z - mu.g * mu.g, gb = m1.w - mu.g * mu.b, bb = m2.x - mu.b * mu.b;
    mat3 sigma = mat3(rr, rg, rb, rg, gg, gb, rb, gb, bb);
    vec3 a = inverse(sigma + mat3(loa_eps)) * sigma[LOA_CHANNEL];
    return vec4(a, mu[LOA_CHANNEL] - dot(a, mu));
}
