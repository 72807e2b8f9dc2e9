#version 430
// The structure tensor and edge tangent flow (osgLoA::StructureTensor; Kyprianidis & Doellner
// 2008 §3). LOA_TENSOR_STAGE 0: per-channel Sobel derivatives normalized by 1/8 (the derivative
// per texel), the tensor (E, F, G, 0) = sum over RGB of (fx.fx, fx.fy, fy.fy); stage 1: from a
// (smoothed) tensor, the flow (t.x, t.y, A, phi): t the unit minor eigenvector (edge tangent)
// with t.y > 0 (or t.y = 0, t.x > 0), A = (l1 - l2) / (l1 + l2), phi the angle of the major
// eigenvector; t = (0, 1), A = 0 where the tensor is isotropic. The CPU twins are
// StructureTensor::tensor and StructureTensor::flowOf.
vec4 loa_fetch0(ivec2 p);

vec4 loa_tensorFlow(vec3 efg)
{
    float E = efg.x, F = efg.y, G = efg.z;
    float root = sqrt((E - G) * (E - G) + 4.0 * F * F);
    float l1 = 0.5 * (E + G + root);
    float l2 = 0.5 * (E + G - root);
    if (!(root > 1e-9 * (l1 + l2)) || !(l1 + l2 > 0.0)) return vec4(0.0, 1.0, 0.0, 0.0);
    vec2 g = E >= G ? vec2(l1 - G, F) : vec2(F, l1 - E);
    g /= sqrt(dot(g, g));
    vec2 t = vec2(-g.y, g.x);
    if (t.y < 0.0 || (t.y == 0.0 && t.x < 0.0)) t = -t;
    return vec4(t, root / (l1 + l2), atan(-t.x, t.y));
}

vec4 loa_filterTexel(ivec2 p)
{
#if LOA_TENSOR_STAGE == 0
    vec3 n00 = loa_fetch0(p + ivec2(-1, -1)).rgb, n10 = loa_fetch0(p + ivec2(0, -1)).rgb,
         n20 = loa_fetch0(p + ivec2(1, -1)).rgb;
    vec3 n01 = loa_fetch0(p + ivec2(-1, 0)).rgb, n21 = loa_fetch0(p + ivec2(1, 0)).rgb;
    vec3 n02 = loa_fetch0(p + ivec2(-1, 1)).rgb, n12 = loa_fetch0(p + ivec2(0, 1)).rgb,
         n22 = loa_fetch0(p + ivec2(1, 1)).rgb;
    vec3 fx = ((n20 + n21 * 2.0 + n22) - (n00 + n01 * 2.0 + n02)) * 0.125;
    vec3 fy = ((n02 + n12 * 2.0 + n22) - (n00 + n10 * 2.0 + n20)) * 0.125;
    return vec4(dot(fx, fx), dot(fx, fy), dot(fy, fy), 0.0);
#else
    return loa_tensorFlow(loa_fetch0(p).rgb);
#endif
}
