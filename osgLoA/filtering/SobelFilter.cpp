/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/SobelFilter>

#include <cmath>

namespace osgLoA
{

static FilterRegistry::Entry<SobelFilter>
    s_registeredSobelFilter("sobel",
                 "Sobel gradient magnitude of luminance (threshold=0), or black edges where M >= threshold");

osg::Vec2f SobelFilter::gradient(const FilterImage& image, int x, int y, const ImageBorder& border)
{
    float v[3][3]; // v[j][i] = Y(x + i - 1, y + j - 1)
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i)
            v[j][i] = luminance(image.fetch(x + i - 1, y + j - 1, border));
    const float gx = (v[0][2] + 2.0f * v[1][2] + v[2][2]) - (v[0][0] + 2.0f * v[1][0] + v[2][0]);
    const float gy = (v[2][0] + 2.0f * v[2][1] + v[2][2]) - (v[0][0] + 2.0f * v[0][1] + v[0][2]);
    return osg::Vec2f(gx, gy);
}

float SobelFilter::magnitude(const FilterImage& image, int x, int y, const ImageBorder& border)
{
    const osg::Vec2f g = gradient(image, x, y, border);
    return std::sqrt(g[0] * g[0] + g[1] * g[1]) * 0.25f;
}

FilterImage SobelFilter::apply(const FilterImage& input, const ImageBorder& border) const
{
    checkParameters();
    FilterImage out(input.width(), input.height());
    for (int y = 0; y < input.height(); ++y)
        for (int x = 0; x < input.width(); ++x)
        {
            const float m = magnitude(input, x, y, border);
            const float v = _threshold > 0.0f ? (m >= _threshold ? 0.0f : 1.0f) : m;
            out.set(x, y, osg::Vec4f(v, v, v, input.get(x, y)[3]));
        }
    return out;
}

std::vector<GpuFilterPass> SobelFilter::gpuPasses() const
{
    GpuFilterPass p;
    p.shader = "loa_filter_sobel.comp.glsl";
    p.uniforms = {GpuUniform::scalar("loa_threshold", _threshold)};
    p.inputs = {-1};
    p.radius = 1;
    return {p};
}

std::vector<FilterParameter> SobelFilter::parameters()
{
    FilterParameter t;
    t.name = "threshold";
    t.description = "edge threshold on M = |Sobel gradient of luminance| / 4 (0: output M itself)";
    t.minimum = minimumThreshold();
    t.maximum = maximumThreshold();
    t.get = [this] { return double(_threshold); };
    t.set = [this](double v) { _threshold = float(v); };
    return {t};
}

} // namespace osgLoA
