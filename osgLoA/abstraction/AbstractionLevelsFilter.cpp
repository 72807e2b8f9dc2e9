/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/abstraction/AbstractionLevelsFilter>
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/KuwaharaFilter>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace osgLoA
{

static FilterRegistry::Entry<AbstractionLevelsFilter>
    s_registeredAbstractionLevelsFilter("abstraction_levels",
                 "iterated Kuwahara levels chosen per pixel by the focus weight in alpha "
                 "(paper 001 abstraction levels)");

float AbstractionLevelsFilter::level(float phi) const
{
    const float p = std::isfinite(phi) ? std::clamp(phi, 0.0f, 1.0f) : 0.0f;
    return float(_iterations) + (float(_iterationsFocus) - float(_iterations)) * p;
}

float AbstractionLevelsFilter::levelWeight(float lambda, int i)
{
    return std::max(0.0f, 1.0f - std::fabs(lambda - float(i)));
}

void AbstractionLevelsFilter::checkParameters() const
{
    ImageFilter::checkParameters();
    if (_iterationsFocus > _iterations)
        throw std::invalid_argument(
            "abstraction_levels: parameter iterations_focus = " + std::to_string(_iterationsFocus) +
            " exceeds iterations = " + std::to_string(_iterations));
}

FilterImage AbstractionLevelsFilter::apply(const FilterImage& input, const ImageBorder& border) const
{
    checkParameters();
    osg::ref_ptr<KuwaharaFilter> k = new KuwaharaFilter;
    k->setRadius(_radius);
    std::vector<FilterImage> levels{input};
    for (int i = 1; i <= _iterations; ++i)
        levels.push_back(k->apply(levels.back(), border));
    if (_iterationsFocus == _iterations) return levels.back();
    FilterImage out(input.width(), input.height());
    for (int y = 0; y < input.height(); ++y)
        for (int x = 0; x < input.width(); ++x)
        {
            const float phi = input.get(x, y)[3];
            const float lambda = level(phi);
            osg::Vec4f c(0, 0, 0, phi);
            for (int i = 0; i <= _iterations; ++i)
            {
                const float w = levelWeight(lambda, i);
                const osg::Vec4f l = levels[std::size_t(i)].get(x, y);
                c[0] += w * l[0];
                c[1] += w * l[1];
                c[2] += w * l[2];
            }
            out.set(x, y, c);
        }
    return out;
}

std::vector<GpuFilterPass> AbstractionLevelsFilter::gpuPasses() const
{
    osg::ref_ptr<KuwaharaFilter> k = new KuwaharaFilter;
    k->setRadius(_radius);
    const std::vector<GpuFilterPass> one = k->gpuPasses();
    std::vector<GpuFilterPass> passes;
    std::vector<int> levelOutput; // pass index of each iteration's output
    const int n = std::clamp(_iterations, 1, 3);
    for (int i = 0; i < n; ++i)
    {
        const int offset = int(passes.size());
        const int previous = i == 0 ? -1 : levelOutput.back();
        for (GpuFilterPass p : one)
        {
            for (int& in : p.inputs)
                in = in < 0 ? previous : in + offset;
            passes.push_back(p);
        }
        levelOutput.push_back(int(passes.size()) - 1);
    }
    if (_iterationsFocus == _iterations) return passes;
    GpuFilterPass blend;
    blend.shader = "loa_filter_abstraction_levels.comp.glsl";
    blend.defines = {{"LOA_LEVELS", std::to_string(n)}};
    blend.uniforms = {GpuUniform::scalar("loa_levelsFar", float(_iterations)),
                      GpuUniform::scalar("loa_levelsFocus", float(_iterationsFocus))};
    blend.inputs = {-1};
    for (int o : levelOutput)
        blend.inputs.push_back(o);
    blend.radius = 0;
    passes.push_back(blend);
    return passes;
}

std::vector<FilterParameter> AbstractionLevelsFilter::parameters()
{
    FilterParameter r;
    r.name = "radius";
    r.description = "Kuwahara sector size r, texels (2: 3x3 sampled regions, 4: 5x5)";
    r.minimum = KuwaharaFilter::minimumRadius();
    r.maximum = KuwaharaFilter::maximumRadius();
    r.integer = true;
    r.get = [this] { return double(_radius); };
    r.set = [this](double v) { _radius = int(v); };
    FilterParameter it;
    it.name = "iterations";
    it.description = "Kuwahara iterations at the strongest level (focus weight 0)";
    it.minimum = 1;
    it.maximum = 3;
    it.integer = true;
    it.get = [this] { return double(_iterations); };
    it.set = [this](double v) { _iterations = int(v); };
    FilterParameter f;
    f.name = "iterations_focus";
    f.description = "Kuwahara iterations at the focus (focus weight 1), at most iterations";
    f.minimum = 0;
    f.maximum = 3;
    f.integer = true;
    f.get = [this] { return double(_iterationsFocus); };
    f.set = [this](double v) { _iterationsFocus = int(v); };
    return {r, it, f};
}

} // namespace osgLoA
