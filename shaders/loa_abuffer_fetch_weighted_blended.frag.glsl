#version 450 compatibility
#pragma import_defines(LOA_MAX_FRAGMENTS)
// Fetch of weighted blended OIT (osgLoA::WeightedBlendedOIT), linked with
// loa_abuffer_resolve.frag.glsl: the pixel's routed fragments as one, colour the weighted mean,
// alpha 1 - prod(1 - a), depth the weighted mean depth.
#ifndef LOA_MAX_FRAGMENTS
#define LOA_MAX_FRAGMENTS 64
#endif

uniform sampler2D loa_wboitAccum;
uniform sampler2D loa_wboitReveal;

bool loa_abufferInRegion(ivec2 pixel);

int loa_abufferFetch(ivec2 pixel, inout vec4 colors[LOA_MAX_FRAGMENTS], inout float depths[LOA_MAX_FRAGMENTS],
                     int count)
{
    if (count >= LOA_MAX_FRAGMENTS || !loa_abufferInRegion(pixel))
        return count;
    ivec2 size = textureSize(loa_wboitAccum, 0);
    if (pixel.x < 0 || pixel.y < 0 || pixel.x >= size.x || pixel.y >= size.y)
        return count;
    vec4 accum = texelFetch(loa_wboitAccum, pixel, 0);
    vec2 reveal = texelFetch(loa_wboitReveal, pixel, 0).rg;
    float alpha = 1.0 - exp(-reveal.r);
    if (!(accum.a > 0.0) || alpha < 0.5 / 255.0)
        return count;
    colors[count] = vec4(clamp(accum.rgb / accum.a, 0.0, 1.0), clamp(alpha, 0.0, 1.0));
    depths[count] = reveal.g / accum.a;
    return count + 1;
}
