// ColorQuantization: the abstract style's quantization in Oklab, on the CPU.
#include <osgLoA/styles/ColorQuantization>

#include <algorithm>
#include <cmath>

namespace osgLoA
{

namespace
{
// Below -kGamutEps or above 1 + kGamutEps (float rounding only) in linear sRGB counts as outside the gamut.
constexpr float kGamutEps = 1.0e-6f;
// A chroma within this fraction of a step below a multiple counts as that multiple, so that a
// quantized colour (with rounding noise of the colour conversions) maps to itself.
constexpr float kChromaSlack = 0.01f;
constexpr int kMaxChromaSteps = 64;

osg::Vec3f toLinear(const osg::Vec3f& srgb)
{
    return osg::Vec3f(ColorQuantization::srgbToLinear(srgb.x()), ColorQuantization::srgbToLinear(srgb.y()),
                      ColorQuantization::srgbToLinear(srgb.z()));
}

osg::Vec3f linearToOklab(const osg::Vec3f& c)
{
    const float l = 0.4122214708f * c.x() + 0.5363325363f * c.y() + 0.0514459929f * c.z();
    const float m = 0.2119034982f * c.x() + 0.6806995451f * c.y() + 0.1073969566f * c.z();
    const float s = 0.0883024619f * c.x() + 0.2817188376f * c.y() + 0.6299787005f * c.z();
    const float l_ = std::cbrt(l), m_ = std::cbrt(m), s_ = std::cbrt(s);
    return osg::Vec3f(0.2104542553f * l_ + 0.7936177850f * m_ - 0.0040720468f * s_,
                      1.9779984951f * l_ - 2.4285922050f * m_ + 0.4505937099f * s_,
                      0.0259040371f * l_ + 0.7827717662f * m_ - 0.8086757660f * s_);
}

osg::Vec3f oklabToLinear(const osg::Vec3f& lab)
{
    const float l_ = lab.x() + 0.3963377774f * lab.y() + 0.2158037573f * lab.z();
    const float m_ = lab.x() - 0.1055613458f * lab.y() - 0.0638541728f * lab.z();
    const float s_ = lab.x() - 0.0894841775f * lab.y() - 1.2914855480f * lab.z();
    const float l = l_ * l_ * l_, m = m_ * m_ * m_, s = s_ * s_ * s_;
    return osg::Vec3f(4.0767416621f * l - 3.3077115913f * m + 0.2309699292f * s,
                      -1.2684380046f * l + 2.6097574011f * m - 0.3413193965f * s,
                      -0.0041960863f * l - 0.7034186147f * m + 1.7076147010f * s);
}

bool inGamut(const osg::Vec3f& linear)
{
    for (int i = 0; i < 3; ++i)
        if (linear[i] < -kGamutEps || linear[i] > 1.0f + kGamutEps) return false;
    return true;
}

float clamp01(float v)
{
    return std::min(1.0f, std::max(0.0f, v));
}
} // namespace

float ColorQuantization::srgbToLinear(float c)
{
    c = clamp01(c);
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

float ColorQuantization::linearToSrgb(float c)
{
    c = clamp01(c);
    return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

osg::Vec3f ColorQuantization::srgbToOklab(const osg::Vec3f& srgb)
{
    return linearToOklab(toLinear(srgb));
}

osg::Vec3f ColorQuantization::oklabToSrgb(const osg::Vec3f& lab)
{
    const osg::Vec3f c = oklabToLinear(lab);
    return osg::Vec3f(linearToSrgb(c.x()), linearToSrgb(c.y()), linearToSrgb(c.z()));
}

int ColorQuantization::lightnessLevel(const osg::Vec3f& srgb, int levels)
{
    const int n = std::max(levels, 2) - 1;
    return static_cast<int>(std::floor(clamp01(srgbToOklab(srgb).x()) * n + 0.5f));
}

osg::Vec3f ColorQuantization::quantize(const osg::Vec3f& srgb, int levels, float chromaStep)
{
    const int n = std::max(levels, 2) - 1;
    const osg::Vec3f lab = srgbToOklab(srgb);
    const float lightness = std::floor(clamp01(lab.x()) * n + 0.5f) / n;
    const float chroma = std::sqrt(lab.y() * lab.y() + lab.z() * lab.z());
    osg::Vec3f linear = oklabToLinear(osg::Vec3f(lightness, 0.0f, 0.0f)); // grey
    if (chroma > 0.0f && chromaStep <= 0.0f)
    {
        linear = oklabToLinear(osg::Vec3f(lightness, lab.y(), lab.z())); // chroma kept, clamped below
    }
    else if (chroma > 0.0f)
    {
        // The multiple of chromaStep below the chroma; then down by whole steps until the
        // colour is inside the gamut (k = 0, grey, always is).
        int k = std::min(kMaxChromaSteps, static_cast<int>(std::floor(chroma / chromaStep + kChromaSlack)));
        for (; k > 0; --k)
        {
            const float f = k * chromaStep / chroma;
            const osg::Vec3f c = oklabToLinear(osg::Vec3f(lightness, lab.y() * f, lab.z() * f));
            if (inGamut(c))
            {
                linear = c;
                break;
            }
        }
    }
    return osg::Vec3f(linearToSrgb(linear.x()), linearToSrgb(linear.y()), linearToSrgb(linear.z()));
}

osg::Vec4f ColorQuantization::quantize(const osg::Vec4f& srgba, int levels, float chromaStep)
{
    const osg::Vec3f q = quantize(osg::Vec3f(srgba.x(), srgba.y(), srgba.z()), levels, chromaStep);
    return osg::Vec4f(q, srgba.w());
}

} // namespace osgLoA
