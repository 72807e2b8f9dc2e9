/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/ColorQuantizationFilter>
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/FlowBilateralFilter>

#include <cmath>

namespace osgLoA
{

static FilterRegistry::Entry<ColorQuantizationFilter>
    s_registeredColorQuantizationFilter("quantize",
                 "soft luminance quantization in CIELab (Winnemoeller et al. 2006; levels, phi_q)");

float ColorQuantizationFilter::quantizeLightness(float lightness, int levels, float phiQ)
{
    const float dq = 100.0f / float(levels);
    const float nearest = dq * std::round(lightness / dq);
    return nearest + 0.5f * dq * std::tanh(phiQ * (lightness - nearest));
}

FilterImage ColorQuantizationFilter::apply(const FilterImage& input, const ImageBorder&) const
{
    checkParameters();
    FilterImage out(input.width(), input.height());
    for (int y = 0; y < input.height(); ++y)
        for (int x = 0; x < input.width(); ++x)
        {
            const float* p = input.texel(x, y);
            osg::Vec3f lab = FlowBilateralFilter::rgbToLab(osg::Vec3f(p[0], p[1], p[2]));
            lab[0] = quantizeLightness(lab[0], _levels, _phiQ);
            out.set(x, y, osg::Vec4f(FlowBilateralFilter::labToRgb(lab), p[3]));
        }
    return out;
}

std::vector<GpuFilterPass> ColorQuantizationFilter::gpuPasses() const
{
    checkParameters();
    std::vector<GpuFilterPass> passes(3);
    passes[0].shader = "loa_filter_lab.comp.glsl";
    passes[0].defines = {{"LOA_LAB_STAGE", "0"}};
    passes[0].inputs = {-1};
    passes[1].shader = "loa_filter_quantize.comp.glsl";
    passes[1].uniforms = {GpuUniform::integer("loa_levels", _levels), GpuUniform::scalar("loa_phiQ", _phiQ)};
    passes[1].inputs = {0};
    passes[2].shader = "loa_filter_lab.comp.glsl";
    passes[2].defines = {{"LOA_LAB_STAGE", "1"}};
    passes[2].inputs = {1};
    return passes;
}

std::vector<FilterParameter> ColorQuantizationFilter::parameters()
{
    FilterParameter levels;
    levels.name = "levels";
    levels.description = "number of lightness bins over L* in [0, 100]";
    levels.minimum = 2;
    levels.maximum = 64;
    levels.integer = true;
    levels.get = [this] { return double(_levels); };
    levels.set = [this](double v) { _levels = int(v); };

    FilterParameter phi;
    phi.name = "phi_q";
    phi.description = "sharpness of the bin transitions, per L* unit (Winnemoeller: 3 to 14)";
    phi.minimum = 0;
    phi.maximum = 100;
    phi.get = [this] { return double(_phiQ); };
    phi.set = [this](double v) { _phiQ = float(v); };
    return {levels, phi};
}

} // namespace osgLoA
