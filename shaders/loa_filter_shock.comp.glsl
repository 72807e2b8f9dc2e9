#version 430
// Coherence-enhancing shock filtering (osgLoA::ShockFilter; Kyprianidis & Kang 2011).
// LOA_SHOCK_STAGE 0: flow-guided smoothing of the image (unit 0) along the tangent field of the
//   tensor (E, F, G) (unit 1): second-order Runge-Kutta streamlines, step 1 texel, Gaussian
//   weights exp(-u^2 / (2 sigma^2)) for arc length u < 2 sigma, sigma = LOA_SHOCK_SIGMA (times
//   (1 + A)^2 / 4 with LOA_SHOCK_ADAPTIVE), stopping where the tangent turns by more than
//   acos(LOA_SHOCK_COSMAX) in a step; at most LOA_SHOCK_STEPS steps each way.
// LOA_SHOCK_STAGE 1: the shock filter of the image (unit 0) with the tensor (unit 1) and the
//   luminance source (unit 2): the sign of a 1D Laplacian of Gaussian (LOA_SHOCK_SIGMAG, half
//   width 5 sigma, LOA_SHOCK_LOGSTEPS steps at most) of the luminance along the gradient
//   direction, 0 below LOA_SHOCK_TAU; then the brightest (sign > 0) or darkest (sign < 0) of the
//   texel and the nearest texels along the gradient within LOA_SHOCK_RADIUS (LOA_SHOCK_RSTEPS
//   steps at most), half a texel to either side of the line.
// LOA_SHOCK_STAGE 2: a copy (no iterations and no final smoothing).
// Alpha passes through. The CPU twins are ShockFilter::flowSmooth and ShockFilter::shock.
vec4 loa_fetch0(ivec2 p);
vec4 loa_fetch1(ivec2 p);
vec4 loa_sample0(vec2 p);
vec4 loa_sample1(vec2 p);
vec4 loa_sample2(vec2 p);

#pragma include "loa_structure_tensor.glsl"

float loa_luma(vec3 c) { return 0.299 * c.r + 0.587 * c.g + 0.114 * c.b; }

#if LOA_SHOCK_STAGE == 0
vec2 loa_shockTangent(vec2 q) { return loa_flowOfTensor(loa_sample1(q).rgb).xy; }

vec4 loa_filterTexel(ivec2 p)
{
    vec2 p0 = vec2(p) + 0.5;
    vec4 f0 = loa_flowOfTensor(loa_fetch1(p).rgb);
#if LOA_SHOCK_ADAPTIVE
    float s = LOA_SHOCK_SIGMA * 0.25 * (1.0 + f0.z) * (1.0 + f0.z);
#else
    float s = LOA_SHOCK_SIGMA;
#endif
    float len = 2.0 * s, twoS2 = 2.0 * s * s;
    vec4 centre = loa_fetch0(p);
    vec3 c = centre.rgb;
    float w = 1.0;
    for (int side = 0; side < 2; ++side)
    {
        vec2 v = f0.xy * (side == 0 ? -1.0 : 1.0);
        vec2 q = p0 + v;
        float u = 1.0;
        for (int k = 0; k < LOA_SHOCK_STEPS; ++k)
        {
            if (!(u < len)) break;
            float kk = exp(-u * u / twoS2);
            c += loa_sample0(q).rgb * kk;
            w += kk;
            vec2 t = loa_shockTangent(q);
            if (dot(v, t) < 0.0) t = -t;
            t = loa_shockTangent(q + t * 0.5);
            float vt = dot(v, t);
            if (abs(vt) <= LOA_SHOCK_COSMAX) break;
            if (vt < 0.0) t = -t;
            v = t;
            q += t;
            u += 1.0;
        }
    }
    return vec4(c / w, centre.a);
}
#elif LOA_SHOCK_STAGE == 1
vec4 loa_filterTexel(ivec2 p)
{
    const float s2 = LOA_SHOCK_SIGMAG * LOA_SHOCK_SIGMAG, twoS2 = 2.0 * s2, halfWidth = 5.0 * LOA_SHOCK_SIGMAG;
    vec4 f = loa_flowOfTensor(loa_fetch1(p).rgb);
    vec2 n = vec2(f.y, -f.x);
    float nx = abs(n.x), ny = abs(n.y);
    vec2 p0 = vec2(p) + 0.5;
    float ds = 1.0 / max(nx, ny);
    float sum = -s2 * loa_luma(loa_sample2(p0).rgb);
    for (int k = 1; k <= LOA_SHOCK_LOGSTEPS; ++k)
    {
        float d = float(k) * ds;
        if (d > halfWidth) break;
        float kk = (d * d - s2) * exp(-d * d / twoS2);
        vec2 o = n * d;
        sum += kk * (loa_luma(loa_sample2(p0 - o).rgb) + loa_luma(loa_sample2(p0 + o).rgb));
    }
    sum = -sum / (2.5066282746310002 * s2 * LOA_SHOCK_SIGMAG);
    if (abs(sum) < LOA_SHOCK_TAU) sum = 0.0;

    vec4 c0 = loa_fetch0(p);
    vec4 hi = c0, lo = c0;
    float hiL = loa_luma(c0.rgb), loL = hiL;
    vec2 dp = nx > ny ? vec2(0.0, 0.5) : vec2(0.5, 0.0);
    for (int k = 1; k <= LOA_SHOCK_RSTEPS; ++k)
    {
        float d = float(k) * ds;
        if (d > LOA_SHOCK_RADIUS) break;
        vec2 o = n * d;
        for (int m = 0; m < 4; ++m)
        {
            vec2 q = p0 + (m < 2 ? o : -o) + ((m & 1) == 0 ? dp : -dp);
            vec4 c = loa_fetch0(ivec2(floor(q)));
            float l = loa_luma(c.rgb);
            if (l > hiL)
            {
                hiL = l;
                hi = c;
            }
            if (l < loL)
            {
                loL = l;
                lo = c;
            }
        }
    }
    vec4 r = sum > 0.0 ? hi : (sum < 0.0 ? lo : c0);
    return vec4(r.rgb, c0.a);
}
#else
vec4 loa_filterTexel(ivec2 p) { return loa_fetch0(p); }
#endif
