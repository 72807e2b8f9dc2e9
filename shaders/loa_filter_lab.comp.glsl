#version 430
// sRGB <-> CIELab (D65, L* in [0, 100]) for the flow-based filters (osgLoA::FlowBilateralFilter,
// osgLoA::DoGFilter). LOA_LAB_STAGE 0: input 0 (sRGB-encoded) to (L*, a*, b*, alpha); stage 1:
// input 0 (Lab) back to sRGB (clamped to [0, 1] in linear RGB), alpha kept; with LOA_LAB_EDGES 1
// the colour is multiplied by input 1's red channel (an edge image). The CPU twins are
// FlowBilateralFilter::rgbToLab and labToRgb.
vec4 loa_fetch0(ivec2 p);
vec4 loa_fetch1(ivec2 p);

#ifndef LOA_LAB_EDGES
#define LOA_LAB_EDGES 0
#endif

const vec3 loa_white = vec3(0.95047, 1.0, 1.08883);

float loa_srgbToLinear(float c) { return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4); }
float loa_linearToSrgb(float l) { return l <= 0.0031308 ? 12.92 * l : 1.055 * pow(l, 1.0 / 2.4) - 0.055; }
float loa_labF(float t) { return t > 0.008856452 ? pow(t, 1.0 / 3.0) : t * 7.787037 + 4.0 / 29.0; }
float loa_labFInverse(float f) { return f > 6.0 / 29.0 ? f * f * f : (f - 4.0 / 29.0) / 7.787037; }

vec3 loa_rgbToLab(vec3 c)
{
    float r = loa_srgbToLinear(c.r), g = loa_srgbToLinear(c.g), b = loa_srgbToLinear(c.b);
    float X = 0.4124564 * r + 0.3575761 * g + 0.1804375 * b;
    float Y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
    float Z = 0.0193339 * r + 0.1191920 * g + 0.9503041 * b;
    float fx = loa_labF(X / loa_white.x), fy = loa_labF(Y / loa_white.y), fz = loa_labF(Z / loa_white.z);
    return vec3(116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz));
}

vec3 loa_labToRgb(vec3 lab)
{
    float fy = (lab.x + 16.0) / 116.0;
    float fx = fy + lab.y / 500.0, fz = fy - lab.z / 200.0;
    float X = loa_white.x * loa_labFInverse(fx), Y = loa_white.y * loa_labFInverse(fy),
          Z = loa_white.z * loa_labFInverse(fz);
    vec3 l = vec3(3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z, -0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z,
                  0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z);
    l = clamp(l, 0.0, 1.0);
    return vec3(loa_linearToSrgb(l.r), loa_linearToSrgb(l.g), loa_linearToSrgb(l.b));
}

vec4 loa_filterTexel(ivec2 p)
{
    vec4 c = loa_fetch0(p);
#if LOA_LAB_STAGE == 0
    return vec4(loa_rgbToLab(c.rgb), c.a);
#else
    vec3 rgb = loa_labToRgb(c.rgb);
#if LOA_LAB_EDGES
    rgb *= loa_fetch1(p).r;
#endif
    return vec4(rgb, c.a);
#endif
}
