#version 430
// The structure tensor and edge tangent flow (osgLoA::StructureTensor; Kyprianidis & Doellner
// 2008 §3). LOA_TENSOR_STAGE 0: per-channel Sobel derivatives normalized by 1/8 (the derivative
// per texel), the tensor (E, F, G, 0) = sum over RGB of (fx.fx, fx.fy, fy.fy); stage 1: from a
// (smoothed) tensor, the flow (t.x, t.y, A, phi): t the unit minor eigenvector (edge tangent)
// with t.y > 0 (or t.y = 0, t.x > 0), A = (l1 - l2) / (l1 + l2), phi the angle of the major
// eigenvector; t = (0, 1), A = 0 where the tensor is isotropic. The CPU twins are
// StructureTensor::tensor and StructureTensor::flowOf.
vec4 loa_fetch0(ivec2 p);

#pragma include "loa_structure_tensor.glsl"

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
    return loa_flowOfTensor(loa_fetch0(p).rgb);
#endif
}
