#version 430
// The bilateral filter (osgLoA::BilateralFilter, Tomasi and Manduchi 1998) over the disk of
// LOA_RADIUS texels: weights exp(loa_spatialCoefficient |offset|^2 + loa_rangeCoefficient D^2),
// D the Euclidean colour distance, or with LOA_L1 1 the sum of absolute differences. Filters the
// RGB of input 0 as it is (stored RGB, or Lab between the loa_filter_lab.comp.glsl passes);
// alpha passes through. The CPU twin is BilateralFilter::apply.
vec4 loa_fetch0(ivec2 p);

uniform float loa_spatialCoefficient; // -1 / (2 sigma_d^2)
uniform float loa_rangeCoefficient;   // -1 / (2 sigma_r^2)

vec4 loa_filterTexel(ivec2 p)
{
    vec4 c0 = loa_fetch0(p);
    vec3 sum = vec3(0.0);
    float norm = 0.0;
    for (int j = -LOA_RADIUS; j <= LOA_RADIUS; ++j)
        for (int i = -LOA_RADIUS; i <= LOA_RADIUS; ++i)
        {
            int r2 = i * i + j * j;
            if (r2 > LOA_RADIUS * LOA_RADIUS) continue;
            vec3 c = loa_fetch0(p + ivec2(i, j)).rgb;
            vec3 d = c - c0.rgb;
#if LOA_L1
            float l = abs(d.r) + abs(d.g) + abs(d.b);
            float d2 = l * l;
#else
            float d2 = dot(d, d);
#endif
            float w = exp(loa_spatialCoefficient * float(r2) + loa_rangeCoefficient * d2);
            sum += w * c;
            norm += w;
        }
    return vec4(sum / norm, c0.a);
}
