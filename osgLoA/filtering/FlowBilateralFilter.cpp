/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/DoGFilter>
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/FlowBilateralFilter>
#include <osgLoA/filtering/StructureTensor>

#include <algorithm>
#include <cmath>

namespace osgLoA
{

static FilterRegistry::Entry<FlowBilateralFilter>
    s_registeredFlowBilateralFilter("flow_bilateral",
                 "flow-based (orientation-aligned) bilateral filter in CIELab, Kyprianidis & Doellner 2008");

namespace
{
// D65 reference white of the sRGB/XYZ matrices below (Y = 1).
const float kXn = 0.95047f, kYn = 1.0f, kZn = 1.08883f;

float srgbToLinear(float c)
{
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}
float linearToSrgb(float l)
{
    return l <= 0.0031308f ? 12.92f * l : 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f;
}
float labF(float t)
{
    return t > 0.008856452f ? std::pow(t, 1.0f / 3.0f) : t * 7.787037f + 4.0f / 29.0f;
}
float labFInverse(float f)
{
    return f > 6.0f / 29.0f ? f * f * f : (f - 4.0f / 29.0f) / 7.787037f;
}
} // namespace

osg::Vec3f FlowBilateralFilter::rgbToLab(const osg::Vec3f& rgb)
{
    const float r = srgbToLinear(rgb[0]), g = srgbToLinear(rgb[1]), b = srgbToLinear(rgb[2]);
    const float X = 0.4124564f * r + 0.3575761f * g + 0.1804375f * b;
    const float Y = 0.2126729f * r + 0.7151522f * g + 0.0721750f * b;
    const float Z = 0.0193339f * r + 0.1191920f * g + 0.9503041f * b;
    const float fx = labF(X / kXn), fy = labF(Y / kYn), fz = labF(Z / kZn);
    return osg::Vec3f(116.0f * fy - 16.0f, 500.0f * (fx - fy), 200.0f * (fy - fz));
}

osg::Vec3f FlowBilateralFilter::labToRgb(const osg::Vec3f& lab)
{
    const float fy = (lab[0] + 16.0f) / 116.0f, fx = fy + lab[1] / 500.0f, fz = fy - lab[2] / 200.0f;
    const float X = kXn * labFInverse(fx), Y = kYn * labFInverse(fy), Z = kZn * labFInverse(fz);
    const float r = 3.2404542f * X - 1.5371385f * Y - 0.4985314f * Z;
    const float g = -0.9692660f * X + 1.8760108f * Y + 0.0415560f * Z;
    const float b = 0.0556434f * X - 0.2040259f * Y + 1.0572252f * Z;
    auto enc = [](float l) { return linearToSrgb(std::min(std::max(l, 0.0f), 1.0f)); };
    return osg::Vec3f(enc(r), enc(g), enc(b));
}

FilterImage FlowBilateralFilter::toLab(const FilterImage& rgb)
{
    FilterImage out(rgb.width(), rgb.height());
    for (int y = 0; y < rgb.height(); ++y)
        for (int x = 0; x < rgb.width(); ++x)
        {
            const osg::Vec4f c = rgb.get(x, y);
            out.set(x, y, osg::Vec4f(rgbToLab(osg::Vec3f(c[0], c[1], c[2])), c[3]));
        }
    return out;
}

FilterImage FlowBilateralFilter::bilateralPass(const FilterImage& lab, const FilterImage& tensor, int axis,
                                               const ImageBorder& border) const
{
    FilterImage out(lab.width(), lab.height());
    const int R = int(std::ceil(2.0f * _sigmaD));
    const float twoSigmaD2 = 2.0f * _sigmaD * _sigmaD, twoSigmaR2 = 2.0f * _sigmaR * _sigmaR;
    for (int y = 0; y < lab.height(); ++y)
        for (int x = 0; x < lab.width(); ++x)
        {
            const float* tp = tensor.texel(x, y);
            const osg::Vec2f t = StructureTensor::tangentOf(tp[0], tp[1], tp[2]);
            const osg::Vec2f d = axis == 0 ? osg::Vec2f(t[1], -t[0]) : t;
            const osg::Vec2f s = d / std::max(std::fabs(d[0]), std::fabs(d[1]));
            const float ds = s.length();
            const osg::Vec2f x0(float(x) + 0.5f, float(y) + 0.5f);
            const osg::Vec4f c = lab.get(x, y);
            const osg::Vec3f c0(c[0], c[1], c[2]);
            osg::Vec3f sum = c0;
            float norm = 1.0f;
            for (int j = 1; j <= R; ++j)
            {
                const float kd = std::exp(-(float(j) * ds) * (float(j) * ds) / twoSigmaD2);
                for (int side = 0; side < 2; ++side)
                {
                    const osg::Vec2f p = side == 0 ? x0 + s * float(j) : x0 - s * float(j);
                    const osg::Vec4f v = lab.sampleBilinear(p[0], p[1], border);
                    const osg::Vec3f c1(v[0], v[1], v[2]);
                    const float k = kd * std::exp(-(c1 - c0).length2() / twoSigmaR2);
                    sum += c1 * k;
                    norm += k;
                }
            }
            out.set(x, y, osg::Vec4f(sum / norm, c[3]));
        }
    return out;
}

FilterImage FlowBilateralFilter::apply(const FilterImage& input, const ImageBorder& border) const
{
    checkParameters();
    const bool edges = _edges == FDOG_EDGES;
    const int iterations = edges ? std::max(_ne, _na) : _na;
    const FilterImage tensor =
        iterations > 0 || edges ? StructureTensor::smoothedTensor(input, _rho, border) : FilterImage();
    FilterImage lab = toLab(input), colour = lab, edgeSource = lab;
    for (int i = 1; i <= iterations; ++i)
    {
        lab = bilateralPass(bilateralPass(lab, tensor, 0, border), tensor, 1, border);
        if (i == _na) colour = lab;
        if (i == _ne) edgeSource = lab;
    }
    FilterImage edgeImage;
    if (edges)
    {
        osg::ref_ptr<DoGFilter> dog = new DoGFilter;
        edgeImage = dog->flowDoG(edgeSource, tensor, border);
    }
    FilterImage out(input.width(), input.height());
    for (int y = 0; y < input.height(); ++y)
        for (int x = 0; x < input.width(); ++x)
        {
            const osg::Vec4f c = colour.get(x, y);
            osg::Vec3f rgb = labToRgb(osg::Vec3f(c[0], c[1], c[2]));
            if (edges) rgb *= edgeImage.get(x, y)[0];
            out.set(x, y, osg::Vec4f(rgb, c[3]));
        }
    return out;
}

std::vector<GpuFilterPass> FlowBilateralFilter::gpuPasses() const
{
    std::vector<GpuFilterPass> passes(1);
    passes[0].shader = "loa_filter_lab.comp.glsl";
    passes[0].defines = {{"LOA_LAB_STAGE", "0"}};
    passes[0].inputs = {-1};
    const bool edges = _edges == FDOG_EDGES;
    const int iterations = edges ? std::max(_ne, _na) : _na;
    if (iterations > 0 || edges)
    {
        const std::vector<GpuFilterPass> st = StructureTensor::tensorPasses(_rho, -1, 1);
        passes.insert(passes.end(), st.begin(), st.end());
    }
    const int tensor = int(passes.size()) - 1;
    const int R = int(std::ceil(2.0f * _sigmaD));
    int current = 0, colour = 0, edgeSource = 0;
    for (int i = 1; i <= iterations; ++i)
    {
        for (int axis = 0; axis < 2; ++axis)
        {
            GpuFilterPass p;
            p.shader = "loa_filter_flowbilateral.comp.glsl";
            p.defines = {{"LOA_AXIS", std::to_string(axis)}, {"LOA_STEPS", std::to_string(R)}};
            p.uniforms = {GpuUniform::scalar("loa_sigmaD", _sigmaD),
                          GpuUniform::scalar("loa_sigmaR", _sigmaR)};
            p.inputs = {current, tensor};
            p.radius = R + 1;
            passes.push_back(p);
            current = int(passes.size()) - 1;
        }
        if (i == _na) colour = current;
        if (i == _ne) edgeSource = current;
    }
    GpuFilterPass out;
    out.shader = "loa_filter_lab.comp.glsl";
    out.defines = {{"LOA_LAB_STAGE", "1"}};
    out.inputs = {colour};
    if (edges)
    {
        osg::ref_ptr<DoGFilter> dog = new DoGFilter;
        const std::vector<GpuFilterPass> fd = dog->flowDoGPasses(edgeSource, tensor, int(passes.size()));
        passes.insert(passes.end(), fd.begin(), fd.end());
        out.defines.push_back({"LOA_LAB_EDGES", "1"});
        out.inputs.push_back(int(passes.size()) - 1);
    }
    passes.push_back(out);
    return passes;
}

std::vector<FilterParameter> FlowBilateralFilter::parameters()
{
    std::vector<FilterParameter> ps(6);
    ps[0].name = "rho";
    ps[0].description = "structure tensor smoothing sigma_c, texels";
    ps[0].minimum = 0;
    ps[0].maximum = 16;
    ps[0].get = [this] { return double(_rho); };
    ps[0].set = [this](double v) { _rho = float(v); };
    ps[1].name = "ne";
    ps[1].description = "iterations before the edges are extracted (edges=fdog only)";
    ps[1].minimum = 0;
    ps[1].maximum = 16;
    ps[1].integer = true;
    ps[1].get = [this] { return double(_ne); };
    ps[1].set = [this](double v) { _ne = int(v); };
    ps[2].name = "na";
    ps[2].description = "iterations of the bilateral filter (each: along the gradient, then the tangent)";
    ps[2].minimum = 0;
    ps[2].maximum = 16;
    ps[2].integer = true;
    ps[2].get = [this] { return double(_na); };
    ps[2].set = [this](double v) { _na = int(v); };
    ps[3].name = "sigma_d";
    ps[3].description = "spatial standard deviation, texels (kernel cut at 2 sigma_d)";
    ps[3].minimum = 0.1;
    ps[3].maximum = 16;
    ps[3].get = [this] { return double(_sigmaD); };
    ps[3].set = [this](double v) { _sigmaD = float(v); };
    ps[4].name = "sigma_r";
    ps[4].description = "range standard deviation, CIELab Delta E";
    ps[4].minimum = 0.1;
    ps[4].maximum = 200;
    ps[4].get = [this] { return double(_sigmaR); };
    ps[4].set = [this](double v) { _sigmaR = float(v); };
    ps[5].name = "edges";
    ps[5].description = "none, or fdog: multiply by the FDoG edges of the image after ne iterations";
    ps[5].minimum = 0;
    ps[5].maximum = 1;
    ps[5].integer = true;
    ps[5].choices = {"none", "fdog"};
    ps[5].get = [this] { return double(_edges); };
    ps[5].set = [this](double v) { _edges = v > 0.5 ? FDOG_EDGES : NO_EDGES; };
    return ps;
}

} // namespace osgLoA
