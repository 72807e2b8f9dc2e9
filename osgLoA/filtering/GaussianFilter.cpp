/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/GaussianFilter>

#include <cmath>

namespace osgLoA
{

static FilterRegistry::Entry<GaussianFilter> s_registeredGaussianFilter("gaussian", "Gaussian smoothing (sigma texels)");

int GaussianFilter::radiusFor(float sigma)
{
    return sigma <= 0.0f ? 0 : int(std::ceil(3.0f * sigma));
}

std::vector<float> GaussianFilter::weightsFor(float sigma)
{
    const int r = radiusFor(sigma);
    std::vector<float> w(std::size_t(r) + 1, 1.0f);
    if (r == 0) return w;
    double sum = 0;
    std::vector<double> d(w.size());
    for (int k = 0; k <= r; ++k)
    {
        d[std::size_t(k)] = std::exp(-0.5 * double(k) * k / (double(sigma) * sigma));
        sum += k == 0 ? d[0] : 2 * d[std::size_t(k)];
    }
    for (int k = 0; k <= r; ++k)
        w[std::size_t(k)] = float(d[std::size_t(k)] / sum);
    return w;
}

FilterImage GaussianFilter::blurAxis(const FilterImage& in, const std::vector<float>& w, int axis,
                                     const ImageBorder& border)
{
    FilterImage out(in.width(), in.height());
    const int r = int(w.size()) - 1;
    const int dx = axis == 0 ? 1 : 0, dy = axis == 0 ? 0 : 1;
    for (int y = 0; y < in.height(); ++y)
        for (int x = 0; x < in.width(); ++x)
        {
            const osg::Vec4f c = in.get(x, y);
            osg::Vec3f s = osg::Vec3f(c[0], c[1], c[2]) * w[0];
            for (int k = 1; k <= r; ++k)
            {
                const osg::Vec4f a = in.fetch(x + dx * k, y + dy * k, border);
                const osg::Vec4f b = in.fetch(x - dx * k, y - dy * k, border);
                s += osg::Vec3f(a[0] + b[0], a[1] + b[1], a[2] + b[2]) * w[std::size_t(k)];
            }
            out.set(x, y, osg::Vec4f(s, c[3]));
        }
    return out;
}

FilterImage GaussianFilter::apply(const FilterImage& input, const ImageBorder& border) const
{
    const std::vector<float> w = weightsFor(_sigma);
    return blurAxis(blurAxis(input, w, 0, border), w, 1, border);
}

std::vector<GpuFilterPass> GaussianFilter::gpuPasses() const
{
    const std::vector<float> w = weightsFor(_sigma);
    const int r = int(w.size()) - 1;
    std::vector<GpuFilterPass> passes(2);
    for (int axis = 0; axis < 2; ++axis)
    {
        GpuFilterPass& p = passes[std::size_t(axis)];
        p.shader = "loa_filter_gaussian.comp.glsl";
        p.defines = {{"LOA_AXIS", std::to_string(axis)}, {"LOA_RADIUS", std::to_string(r)}};
        p.uniforms = {GpuUniform::array("loa_weights", w)};
        p.inputs = {axis == 0 ? -1 : 0};
        p.radius = r;
    }
    return passes;
}

std::vector<FilterParameter> GaussianFilter::parameters()
{
    FilterParameter s;
    s.name = "sigma";
    s.description = "standard deviation, texels";
    s.minimum = 0;
    s.maximum = 32;
    s.get = [this] { return double(_sigma); };
    s.set = [this](double v) { _sigma = float(v); };
    return {s};
}

} // namespace osgLoA
