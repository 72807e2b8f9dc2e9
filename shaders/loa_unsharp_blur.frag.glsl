#version 450 compatibility
// The blurred depth of the depth unsharp mask (Luft et al. 2006, paper 004 §3.2.4), at a reduced
// resolution (osgLoA::DepthUnsharpMask). Works on (alpha * linear depth, alpha) so that the blur
// is the alpha-weighted mean of the neighbourhood and pixels without a surface do not pull it
// (less ringing).
//   pass 0: the mean of each f x f block of the G-buffer's depth, weighted by its coverage
//   pass 1, 2: one direction of the separable Gaussian, sigma / f texels
uniform sampler2D loa_blurInput;     // pass 0: the G-buffer depth; else the previous pass
uniform sampler2D loa_blurCoverage;  // pass 0: the G-buffer id target (alpha: drawn)
uniform int loa_blurPass;
uniform int loa_blurFactor;          // f: full-resolution pixels per reduced texel
uniform vec2 loa_blurDirection;      // (1, 0) or (0, 1)
uniform float loa_blurSigma;         // full-resolution pixels
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

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    if (loa_blurPass == 0)
    {
        ivec2 size = textureSize(loa_blurInput, 0);
        ivec2 first = p * loa_blurFactor;
        vec2 sum = vec2(0.0);
        for (int y = 0; y < loa_blurFactor; ++y)
            for (int x = 0; x < loa_blurFactor; ++x)
            {
                ivec2 q = min(first + ivec2(x, y), size - 1);
                float a = texelFetch(loa_blurCoverage, q, 0).a;
                if (a > 0.0)
                    sum += vec2(a * loa_linearDepth(texelFetch(loa_blurInput, q, 0).r), a);
            }
        loa_outBlur = vec4(sum / float(loa_blurFactor * loa_blurFactor), 0.0, 1.0);
        return;
    }
    ivec2 size = textureSize(loa_blurInput, 0);
    float sigma = loa_blurSigma / float(loa_blurFactor);
    int radius = int(ceil(3.0 * sigma));
    vec2 sum = vec2(0.0);
    float total = 0.0;
    for (int k = -radius; k <= radius; ++k)
    {
        float g = exp(-0.5 * float(k * k) / (sigma * sigma));
        ivec2 q = clamp(p + k * ivec2(loa_blurDirection), ivec2(0), size - 1);
        sum += g * texelFetch(loa_blurInput, q, 0).rg;
        total += g;
    }
    loa_outBlur = vec4(sum / total, 0.0, 1.0);
}
