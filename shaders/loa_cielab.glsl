// sRGB <-> CIELAB (D65 white, L* in [0, 100]), included (#pragma include "loa_cielab.glsl") by the
// Lab filter stage (loa_filter_lab.comp.glsl) and the palette style (loa_style_palette.frag.glsl).
// CPU twins: FlowBilateralFilter::rgbToLab / labToRgb, WeightedColor::toLab / fromLab.
const vec3 loa_cielab_white = vec3(0.95047, 1.0, 1.08883);

float loa_cielab_toLinear(float c) { return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4); }
float loa_cielab_toSrgb(float l) { return l <= 0.0031308 ? 12.92 * l : 1.055 * pow(l, 1.0 / 2.4) - 0.055; }
float loa_cielab_f(float t) { return t > 0.008856452 ? pow(t, 1.0 / 3.0) : t * 7.787037 + 4.0 / 29.0; }
float loa_cielab_fInverse(float f) { return f > 6.0 / 29.0 ? f * f * f : (f - 4.0 / 29.0) / 7.787037; }

// sRGB-encoded colour to (L*, a*, b*).
vec3 loa_cielab_fromSrgb(vec3 c)
{
    float r = loa_cielab_toLinear(c.r), g = loa_cielab_toLinear(c.g), b = loa_cielab_toLinear(c.b);
    float X = 0.4124564 * r + 0.3575761 * g + 0.1804375 * b;
    float Y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
    float Z = 0.0193339 * r + 0.1191920 * g + 0.9503041 * b;
    float fx = loa_cielab_f(X / loa_cielab_white.x), fy = loa_cielab_f(Y / loa_cielab_white.y),
          fz = loa_cielab_f(Z / loa_cielab_white.z);
    return vec3(116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz));
}

// (L*, a*, b*) to an sRGB-encoded colour, clamped to [0, 1] in linear RGB.
vec3 loa_cielab_toSrgbColor(vec3 lab)
{
    float fy = (lab.x + 16.0) / 116.0;
    float fx = fy + lab.y / 500.0, fz = fy - lab.z / 200.0;
    float X = loa_cielab_white.x * loa_cielab_fInverse(fx), Y = loa_cielab_white.y * loa_cielab_fInverse(fy),
          Z = loa_cielab_white.z * loa_cielab_fInverse(fz);
    vec3 l = vec3(3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z, -0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z,
                  0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z);
    l = clamp(l, 0.0, 1.0);
    return vec3(loa_cielab_toSrgb(l.r), loa_cielab_toSrgb(l.g), loa_cielab_toSrgb(l.b));
}
