#version 430
// The classic Kuwahara filter (osgLoA::KuwaharaFilter), three passes with LOA_RADIUS = r:
//   LOA_KUWAHARA_STAGE 0: L(x, y) = sum over i in [0, r] of s(x - i, y),
//   LOA_KUWAHARA_STAGE 1: R(x, y) = sum over i in [0, r] of s(x + i, y),
//     with s = (R, G, B, R^2 + G^2 + B^2) of the input texel (wrapped);
//   LOA_KUWAHARA_STAGE 2: the four sectors of (r+1)^2 texels as column sums of L (left
//     sectors Q0 above, Q2 below) and R (right sectors Q1, Q3) over [y - r, y] and [y, y + r];
//     variance = mean of s.w - |mean of rgb|^2; the mean of the sector with the smallest
//     variance (first of Q0, Q1, Q2, Q3 on ties); alpha from the input (unit 2).
// Rows are wrapped when stage 2 reads L and R, columns when stages 0 and 1 read the input, so
// every sector texel is read with its own wrapped coordinates as on the CPU.
// The CPU twin is KuwaharaFilter::apply.
vec4 loa_fetch0(ivec2 p);
vec4 loa_fetch1(ivec2 p);
vec4 loa_fetch2(ivec2 p);

#if LOA_KUWAHARA_STAGE < 2
vec4 loa_filterTexel(ivec2 p)
{
    const int dir = LOA_KUWAHARA_STAGE == 0 ? -1 : 1;
    vec4 s = vec4(0.0);
    for (int i = 0; i <= LOA_RADIUS; ++i)
    {
        vec3 c = loa_fetch0(p + ivec2(dir * i, 0)).rgb;
        s += vec4(c, dot(c, c));
    }
    return s;
}
#else
vec4 loa_filterTexel(ivec2 p)
{
    vec4 q0 = vec4(0.0), q1 = vec4(0.0), q2 = vec4(0.0), q3 = vec4(0.0);
    for (int j = 1; j <= LOA_RADIUS; ++j)
    {
        q0 += loa_fetch0(p - ivec2(0, j));
        q1 += loa_fetch1(p - ivec2(0, j));
        q2 += loa_fetch0(p + ivec2(0, j));
        q3 += loa_fetch1(p + ivec2(0, j));
    }
    vec4 l = loa_fetch0(p), r = loa_fetch1(p);
    q0 += l;
    q2 += l;
    q1 += r;
    q3 += r;
    const float n = 1.0 / float((LOA_RADIUS + 1) * (LOA_RADIUS + 1));
    q0 *= n;
    q1 *= n;
    q2 *= n;
    q3 *= n;
    float v0 = q0.w - dot(q0.rgb, q0.rgb);
    float v1 = q1.w - dot(q1.rgb, q1.rgb);
    float v2 = q2.w - dot(q2.rgb, q2.rgb);
    float v3 = q3.w - dot(q3.rgb, q3.rgb);
    vec3 m = q0.rgb;
    float best = v0;
    if (v1 < best)
    {
        best = v1;
        m = q1.rgb;
    }
    if (v2 < best)
    {
        best = v2;
        m = q2.rgb;
    }
    if (v3 < best) m = q3.rgb;
    return vec4(m, loa_fetch2(p).a);
}
#endif
