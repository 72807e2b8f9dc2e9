#version 450 compatibility
// Weighted blended OIT (osgLoA::WeightedBlendedOIT; McGuire & Bavoil 2013): what a routed draw adds
// (blend ONE, ONE into both targets). Weight: the paper's equation 9 on the window depth z,
// w = max(1e-2, 3e3 (1 - z)^3); revealage as a sum of -ln(1 - a) (the product of (1 - a) is its
// exponential), with a at most 1 - 1/4096 so that an opaque fragment leaves a finite sum.
layout(location = 0) out vec4 loa_wboitAccumOut;  // (rgb a w, a w)
layout(location = 1) out vec4 loa_wboitRevealOut; // (-ln(1 - a), a w z)

void loa_abufferWrite(vec4 straightAlphaColor)
{
    vec4 c = clamp(straightAlphaColor, 0.0, 1.0);
    if (!(c.a >= 0.5 / 255.0))
        discard;
    float z = gl_FragCoord.z;
    float w = c.a * max(1e-2, 3e3 * (1.0 - z) * (1.0 - z) * (1.0 - z));
    loa_wboitAccumOut = vec4(c.rgb * w, w);
    loa_wboitRevealOut = vec4(-log(1.0 - min(c.a, 1.0 - 1.0 / 4096.0)), w * z, 0.0, 0.0);
}
