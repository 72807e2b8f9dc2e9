#version 430
// The anisotropic Kuwahara filter (osgLoA::AnisotropicKuwaharaFilter: Kyprianidis, Kang &
// Döllner 2009 with the polynomial sector weights of Kyprianidis et al. 2010; multi-scale
// after Kyprianidis 2011). Compile-time constants: LOA_AKF_RADIUS (r), LOA_AKF_RMAX
// (floor(2 r), the loops' bound), LOA_AKF_Q, LOA_AKF_ALPHA, LOA_AKF_H (threshold, 8-bit units),
// LOA_AKF_ZETA, LOA_AKF_ETA (polynomial weights), LOA_AKF_BASE (1: the pass works on level 0,
// the full-size image, and reads with the contract's own wrapping), LOA_AKF_STAGE; the uniform loa_akfLevel is the pyramid level l (level
// l of size ceil(size / 2^l) lives in the top left corner of a full-size intermediate, and reads
// past its edge are wrapped at that size by this shader). Stages:
//   0 DOWN: pyramid level l from level l-1 (unit 0): the (1, 3, 3, 1) / 8 binomial, 4x4 taps;
//   1 SOBEL: the structure tensor (E, F, G, 0) of level l (unit 0), as StructureTensor::tensor;
//   2 BLURX, 3 BLURY: its Gaussian smoothing (LOA_RADIUS, loa_weights as GaussianFilter); BLURY
//     then propagates: the smoothed tensor normalized to trace 1 and, with LOA_AKF_COARSE,
//     merged with the coarser level's propagated tensor (unit 1) weighted by anisotropy;
//   4 PROPAGATE: the propagation of an unsmoothed tensor (unit 0; rho = 0);
//   5 FILTER: the filter of level l: image unit 0, tensor unit 1, with LOA_AKF_COARSE the
//     coarser level's result (unit 2) blended in by beta.
// No dynamically indexed arrays: the 8 sectors are two groups of vec4 (sectors 0, 2, 4, 6 and
// 1, 3, 5, 7), the offset -v reads its sectors swizzled (.zwxy). The CPU twins are
// AnisotropicKuwaharaFilter::apply, filterTexel and downsample.
vec4 loa_fetch0(ivec2 p);
vec4 loa_fetch1(ivec2 p);
vec4 loa_fetch2(ivec2 p);
ivec2 loa_size();
ivec2 loa_wrapMode; // set by the pass contract's main (shaders/loa_filter_common.comp.glsl)
uniform int loa_akfLevel;

#if LOA_AKF_STAGE == 2 || LOA_AKF_STAGE == 3
uniform float loa_weights[LOA_RADIUS + 1];
#endif

#ifndef LOA_AKF_COARSE
#define LOA_AKF_COARSE 0
#endif

ivec2 loa_akfLevelSize(int level)
{
    ivec2 s = loa_size();
    for (int i = 0; i < level; ++i)
        s = max((s + 1) / 2, ivec2(1));
    return s;
}

// loa_wrapIndex without integer division or branches (llvmpipe runs both sides of a branch and
// divides integers lane by lane): the floors of exact small quotients in float (|i|, n < 2^12:
// a quotient that is not an integer is at least 1/n away from one, far above float rounding).
int loa_akfWrapIndex(int i, int n, int mode)
{
    float fi = float(i), fn = float(n);
    int repeat = i - n * int(floor(fi / fn));
    int period = i - 2 * n * int(floor(fi / (2.0 * fn)));
    int mirror = period < n ? period : 2 * n - 1 - period;
    return mode == 0 ? repeat : (mode == 2 ? mirror : clamp(i, 0, n - 1));
}

ivec2 loa_akfWrap(ivec2 q, ivec2 size)
{
    return ivec2(loa_akfWrapIndex(q.x, size.x, loa_wrapMode.x), loa_akfWrapIndex(q.y, size.y, loa_wrapMode.y));
}

#if LOA_AKF_BASE
vec4 loa_akfFetch0(ivec2 q, ivec2 size) { return loa_fetch0(q); }
#else
vec4 loa_akfFetch0(ivec2 q, ivec2 size) { return loa_fetch0(loa_akfWrap(q, size)); }
#endif

// The filter's reads of the level image: at level 0 the contract's own (wrapped only in tiles
// near the region's edge: the engine's interior variant); at coarser levels wrapped at the
// level's size, except where the whole ellipse lies inside the level (llvmpipe skips the branch
// not taken by any invocation of a tile; wrapping every read costs about 3x).
ivec2 loa_akfSize;
vec4 loa_akfDirect(ivec2 q) { return loa_fetch0(q); }
vec4 loa_akfWrapped(ivec2 q) { return loa_fetch0(loa_akfWrap(q, loa_akfSize)); }

// Bilinear sample of unit 1 or 2 at continuous texel coordinates of a level (texel centres at
// i + 0.5), as FilterImage::sampleBilinear.
#define LOA_AKF_BILINEAR(FETCH)                                                                    \
    vec2 f = q - 0.5;                                                                              \
    vec2 b = floor(f);                                                                             \
    vec2 a = f - b;                                                                                \
    ivec2 i = ivec2(b);                                                                            \
    vec4 c00 = FETCH(loa_akfWrap(i, size)), c10 = FETCH(loa_akfWrap(i + ivec2(1, 0), size));       \
    vec4 c01 = FETCH(loa_akfWrap(i + ivec2(0, 1), size)), c11 = FETCH(loa_akfWrap(i + ivec2(1, 1), size)); \
    return (c00 * (1.0 - a.x) + c10 * a.x) * (1.0 - a.y) + (c01 * (1.0 - a.x) + c11 * a.x) * a.y;
vec4 loa_akfSample1(vec2 q, ivec2 size) { LOA_AKF_BILINEAR(loa_fetch1) }
vec4 loa_akfSample2(vec2 q, ivec2 size) { LOA_AKF_BILINEAR(loa_fetch2) }

#pragma include "loa_structure_tensor.glsl"

#define LOA_AKF_ROWS(FETCH)                                                                                   \
    for (int j = 0; j <= LOA_AKF_RMAX; ++j)                                                                   \
    {                                                                                                         \
        if (j > maxY) break;                                                                                  \
        float D = Pq - float(j * j) * det;                                                                    \
        if (D < 0.0) continue;                                                                                \
        float sq = sqrt(D);                                                                                   \
        int i0 = int(ceil((-Q * float(j) - sq) / Pq));                                                        \
        int i1 = min(LOA_AKF_RMAX, int(floor((-Q * float(j) + sq) / Pq)));                                    \
        i0 = max(i0, j == 0 ? 1 : -LOA_AKF_RMAX);                                                             \
        for (int i = i0; i <= i1; ++i)                                                                        \
        {                                                                                                     \
            vec2 v = vec2((c * float(i) + s * float(j)) * ia, (-s * float(i) + c * float(j)) * ib);           \
            float vxx = LOA_AKF_ZETA - LOA_AKF_ETA * v.x * v.x, vyy = LOA_AKF_ZETA - LOA_AKF_ETA * v.y * v.y; \
            vec4 za = max(vec4(0.0), vec4(v.y + vxx, -v.x + vyy, -v.y + vxx, v.x + vyy));                     \
            vec2 r = 0.70710678118654752 * vec2(v.x - v.y, v.x + v.y);                                        \
            vxx = LOA_AKF_ZETA - LOA_AKF_ETA * r.x * r.x;                                                     \
            vyy = LOA_AKF_ZETA - LOA_AKF_ETA * r.y * r.y;                                                     \
            vec4 zb = max(vec4(0.0), vec4(r.y + vxx, -r.x + vyy, -r.y + vxx, r.x + vyy));                     \
            vec4 wa = za * za, wb = zb * zb;                                                                  \
            float sum = wa.x + wa.y + wa.z + wa.w + wb.x + wb.y + wb.z + wb.w;                                \
            float g = exp(-3.125 * (v.x * v.x + v.y * v.y)) / max(sum, 1e-20);                                \
            wa *= g;                                                                                          \
            wb *= g;                                                                                          \
            vec4 wa2 = wa.zwxy, wb2 = wb.zwxy;                                                                \
            vec3 x0 = FETCH(p + ivec2(i, j)).rgb;                                                             \
            vec3 x1 = FETCH(p - ivec2(i, j)).rgb;                                                             \
            vec3 y0 = x0 * x0, y1 = x1 * x1;                                                                  \
            Wa += wa + wa2;                                                                                   \
            Wb += wb + wb2;                                                                                   \
            Ra += wa * x0.r + wa2 * x1.r;                                                                     \
            Ga += wa * x0.g + wa2 * x1.g;                                                                     \
            Ba += wa * x0.b + wa2 * x1.b;                                                                     \
            Rb += wb * x0.r + wb2 * x1.r;                                                                     \
            Gb += wb * x0.g + wb2 * x1.g;                                                                     \
            Bb += wb * x0.b + wb2 * x1.b;                                                                     \
            RRa += wa * y0.r + wa2 * y1.r;                                                                    \
            GGa += wa * y0.g + wa2 * y1.g;                                                                    \
            BBa += wa * y0.b + wa2 * y1.b;                                                                    \
            RRb += wb * y0.r + wb2 * y1.r;                                                                    \
            GGb += wb * y0.g + wb2 * y1.g;                                                                    \
            BBb += wb * y0.b + wb2 * y1.b;                                                                    \
        }                                                                                                     \
    }

#if LOA_AKF_STAGE == 5
// The filter of one level at texel p (AnisotropicKuwaharaFilter::filterTexel): RGB and the
// local deviation sbar.
vec4 loa_akfFilter(ivec2 p, ivec2 size, vec3 tensor)
{
    vec4 fl = loa_flowOfTensor(tensor);
    float c = fl.x, s = fl.y, A = fl.z;
    float a = LOA_AKF_RADIUS * clamp((LOA_AKF_ALPHA + A) / LOA_AKF_ALPHA, 0.1, 2.0);
    float b = LOA_AKF_RADIUS * clamp(LOA_AKF_ALPHA / (LOA_AKF_ALPHA + A), 0.1, 2.0);
    float ia = 1.0 / a, ib = 1.0 / b;
    float Pq = c * c * ia * ia + s * s * ib * ib;
    float Q = c * s * (ia * ia - ib * ib);
    float det = ia * ia * ib * ib;
    int maxY = min(LOA_AKF_RMAX, int(floor(sqrt(a * a * s * s + b * b * c * c))));

    vec3 x = loa_fetch0(p).rgb;
    vec4 Wa = vec4(0.125), Wb = vec4(0.125);
    vec4 Ra = vec4(x.r * 0.125), Ga = vec4(x.g * 0.125), Ba = vec4(x.b * 0.125);
    vec4 RRa = vec4(x.r * x.r * 0.125), GGa = vec4(x.g * x.g * 0.125), BBa = vec4(x.b * x.b * 0.125);
    vec4 Rb = Ra, Gb = Ga, Bb = Ba, RRb = RRa, GGb = GGa, BBb = BBa;

#if LOA_AKF_BASE
    LOA_AKF_ROWS(loa_akfDirect)
#else
    loa_akfSize = size;
    if (all(greaterThanEqual(p, ivec2(LOA_AKF_RMAX))) && all(lessThan(p + LOA_AKF_RMAX, size)))
    {
        LOA_AKF_ROWS(loa_akfDirect)
    }
    else
    {
        LOA_AKF_ROWS(loa_akfWrapped)
    }
#endif

    vec4 mRa = Ra / Wa, mGa = Ga / Wa, mBa = Ba / Wa;
    vec4 mRb = Rb / Wb, mGb = Gb / Wb, mBb = Bb / Wb;
    vec4 sa = sqrt(abs(RRa / Wa - mRa * mRa)) + sqrt(abs(GGa / Wa - mGa * mGa)) + sqrt(abs(BBa / Wa - mBa * mBa));
    vec4 sb = sqrt(abs(RRb / Wb - mRb * mRb)) + sqrt(abs(GGb / Wb - mGb * mGb)) + sqrt(abs(BBb / Wb - mBb * mBb));
    vec4 xa = max(255.0 * sa, vec4(LOA_AKF_H)), xb = max(255.0 * sb, vec4(LOA_AKF_H));
    vec4 xm = min(xa, xb);
    float scale = max(min(min(xm.x, xm.y), min(xm.z, xm.w)), 1.0);
    float base = pow(scale, -LOA_AKF_Q);
    vec4 ala = 1.0 / (base + pow(xa / scale, vec4(LOA_AKF_Q)));
    vec4 alb = 1.0 / (base + pow(xb / scale, vec4(LOA_AKF_Q)));
    float wsum = dot(ala, vec4(1.0)) + dot(alb, vec4(1.0));
    vec3 o = vec3(dot(ala, mRa) + dot(alb, mRb), dot(ala, mGa) + dot(alb, mGb), dot(ala, mBa) + dot(alb, mBb));
    return vec4(o / wsum, (dot(ala, sa) + dot(alb, sb)) / wsum);
}
#endif

#if LOA_AKF_STAGE == 3 || LOA_AKF_STAGE == 4
// The smoothed tensor J of level l normalized to trace 1 and, with LOA_AKF_COARSE, merged with
// the coarser level's propagated tensor (unit 1) weighted by their anisotropies.
vec4 loa_akfPropagate(ivec2 p, vec3 J)
{
    float tr = J.x + J.z;
    vec3 Jn = tr > 0.0 ? J / tr : vec3(0.5, 0.0, 0.5);
#if LOA_AKF_COARSE
    vec3 C = loa_akfSample1((vec2(p) + 0.5) * 0.5, loa_akfLevelSize(loa_akfLevel + 1)).rgb;
    float Al = loa_flowOfTensor(Jn).z, Ac = loa_flowOfTensor(C).z;
    if (Al + Ac > 1e-6) Jn = (Jn * Al + C * Ac) / (Al + Ac);
#endif
    return vec4(Jn, 0.0);
}
#endif

vec4 loa_filterTexel(ivec2 p)
{
    ivec2 size = loa_akfLevelSize(loa_akfLevel);
    if (p.x >= size.x || p.y >= size.y) return vec4(0.0);
#if LOA_AKF_STAGE == 0
    ivec2 fine = loa_akfLevelSize(loa_akfLevel - 1);
    // Weights (1, 3, 3, 1) / 8 without a local array (dynamically indexed arrays are slow on
    // llvmpipe).
    vec4 s = vec4(0.0);
    for (int b = 0; b < 4; ++b)
    {
        vec4 row = vec4(0.0);
        for (int a = 0; a < 4; ++a)
            row += loa_akfFetch0(2 * p + ivec2(a - 1, b - 1), fine) * (a == 0 || a == 3 ? 0.125 : 0.375);
        s += row * (b == 0 || b == 3 ? 0.125 : 0.375);
    }
    return s;
#elif LOA_AKF_STAGE == 1
    vec3 n00 = loa_akfFetch0(p + ivec2(-1, -1), size).rgb, n10 = loa_akfFetch0(p + ivec2(0, -1), size).rgb,
         n20 = loa_akfFetch0(p + ivec2(1, -1), size).rgb;
    vec3 n01 = loa_akfFetch0(p + ivec2(-1, 0), size).rgb, n21 = loa_akfFetch0(p + ivec2(1, 0), size).rgb;
    vec3 n02 = loa_akfFetch0(p + ivec2(-1, 1), size).rgb, n12 = loa_akfFetch0(p + ivec2(0, 1), size).rgb,
         n22 = loa_akfFetch0(p + ivec2(1, 1), size).rgb;
    vec3 fx = ((n20 + n21 * 2.0 + n22) - (n00 + n01 * 2.0 + n02)) * 0.125;
    vec3 fy = ((n02 + n12 * 2.0 + n22) - (n00 + n10 * 2.0 + n20)) * 0.125;
    return vec4(dot(fx, fx), dot(fx, fy), dot(fy, fy), 0.0);
#elif LOA_AKF_STAGE == 2 || LOA_AKF_STAGE == 3
    const ivec2 d = LOA_AKF_STAGE == 2 ? ivec2(1, 0) : ivec2(0, 1);
    vec4 c = loa_akfFetch0(p, size);
    vec3 s = c.rgb * loa_weights[0];
    for (int k = 1; k <= LOA_RADIUS; ++k)
        s += (loa_akfFetch0(p + d * k, size).rgb + loa_akfFetch0(p - d * k, size).rgb) * loa_weights[k];
#if LOA_AKF_STAGE == 2
    return vec4(s, c.a);
#else
    return loa_akfPropagate(p, s);
#endif
#elif LOA_AKF_STAGE == 4
    return loa_akfPropagate(p, loa_fetch0(p).rgb);
#else
    vec4 o = loa_akfFilter(p, size, loa_fetch1(p).rgb);
    vec3 rgb = o.rgb;
#if LOA_AKF_COARSE
    vec3 u = loa_akfSample2((vec2(p) + 0.5) * 0.5, loa_akfLevelSize(loa_akfLevel + 1)).rgb;
    vec3 dd = u - rgb;
    float sb = max(o.w, 1.0 / 255.0);
    float beta = exp(-dot(dd, dd) / (2.0 * sb * sb));
    rgb += dd * beta;
#endif
    return vec4(rgb, LOA_AKF_BASE == 1 ? loa_fetch0(p).a : 1.0);
#endif
}
