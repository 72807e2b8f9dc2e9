#version 450 compatibility
// One direction of the separable Gaussian of the depth unsharp mask (Luft et al. 2006, paper 004
// §3.2.4): blurs (alpha * linear depth, alpha) so that the blurred depth is the alpha-weighted
// mean of the neighbourhood and pixels without a surface do not pull it (less ringing).
uniform sampler2D loa_blurInput;     // first pass: the G-buffer depth; second: the first pass
uniform sampler2D loa_blurCoverage;  // first pass: the G-buffer id target (alpha: drawn)
uniform bool loa_blurFirstPass;
uniform vec2 loa_blurDirection;      // (1, 0) or (0, 1)
uniform float loa_blurSigma;         // pixels
uniform vec2 loa_depthRange;         // near, far of the projection (for linear depth)
uniform bool loa_orthographic = false;

layout(location = 0) out vec4 loa_outBlur;

float loa_linearDepth(float d)
{
    float n = loa_depthRange.x, f = loa_depthRange.y;
    if (loa_orthographic)
        return n + d * (f - n);
    return n * f / (f - d * (f - n));
}

vec2 loa_sampleWeighted(ivec2 p)
{
    ivec2 size = textureSize(loa_blurInput, 0);
    p = clamp(p, ivec2(0), size - 1);
    if (!loa_blurFirstPass)
        return texelFetch(loa_blurInput, p, 0).rg;
    float a = texelFetch(loa_blurCoverage, p, 0).a;
    return vec2(a * loa_linearDepth(texelFetch(loa_blurInput, p, 0).r), a);
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    int radius = int(ceil(3.0 * loa_blurSigma));
    vec2 sum = vec2(0.0);
    float total = 0.0;
    for (int k = -radius; k <= radius; ++k)
    {
        float g = exp(-0.5 * float(k * k) / (loa_blurSigma * loa_blurSigma));
        sum += g * loa_sampleWeighted(p + k * ivec2(loa_blurDirection));
        total += g;
    }
    loa_outBlur = vec4(sum / total, 0.0, 1.0);
}
