#version 430
// Sobel edges (osgLoA::SobelFilter), one pass of radius 1: Y = 0.299 R + 0.587 G + 0.114 B of
// the 3x3 neighbourhood (wrapped by the region's modes), gx = [-1 0 1; -2 0 2; -1 0 1] * Y,
// gy its transpose (y = row), M = sqrt(gx^2 + gy^2) / 4. loa_threshold t = 0 writes M in RGB;
// t > 0 writes 0 where M >= t and 1 elsewhere. Alpha passes through. The CPU twin is
// SobelFilter::apply.
vec4 loa_fetch0(ivec2 p);

uniform float loa_threshold;

float loa_sobelY(ivec2 p)
{
    vec3 c = loa_fetch0(p).rgb;
    return 0.299 * c.r + 0.587 * c.g + 0.114 * c.b;
}

vec4 loa_filterTexel(ivec2 p)
{
    float a = loa_sobelY(p + ivec2(-1, -1)), b = loa_sobelY(p + ivec2(0, -1));
    float c = loa_sobelY(p + ivec2(1, -1)), d = loa_sobelY(p + ivec2(-1, 0));
    float f = loa_sobelY(p + ivec2(1, 0)), g = loa_sobelY(p + ivec2(-1, 1));
    float h = loa_sobelY(p + ivec2(0, 1)), i = loa_sobelY(p + ivec2(1, 1));
    float gx = (c + 2.0 * f + i) - (a + 2.0 * d + g);
    float gy = (g + 2.0 * h + i) - (a + 2.0 * b + c);
    float m = sqrt(gx * gx + gy * gy) * 0.25;
    float v = loa_threshold > 0.0 ? (m >= loa_threshold ? 0.0 : 1.0) : m;
    return vec4(v, v, v, loa_fetch0(p).a);
}
