/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/CannyFilter>
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/GaussianFilter>
#include <osgLoA/filtering/SobelFilter>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <vector>

namespace osgLoA
{

static FilterRegistry::Entry<CannyFilter>
    s_registeredCannyFilter("canny",
                 "Canny edges: Gaussian (sigma), Sobel, non-maximum suppression, hysteresis (low, high)");

namespace
{
constexpr float kWeak = 0.5f;
constexpr float kStrong = 1.0f;

osg::Vec4f grey(float v, float alpha)
{
    return osg::Vec4f(v, v, v, alpha);
}

bool outside(int i, int n, WrapMode mode)
{
    return mode != WrapMode::Repeat && (i < 0 || i >= n);
}
} // namespace

int CannyFilter::squaredThreshold(float t)
{
    const double s = 1020.0 * double(t);
    return int(std::ceil(s * s));
}

void CannyFilter::checkParameters() const
{
    ImageFilter::checkParameters();
    if (_low > _high)
        throw std::invalid_argument("canny: parameter low = " + std::to_string(_low) +
                                    " is above parameter high = " + std::to_string(_high) +
                                    " (low must be <= high)");
}

FilterImage CannyFilter::quantizedLuminance(const FilterImage& input, const ImageBorder& border) const
{
    FilterImage y(input.width(), input.height());
    for (int j = 0; j < input.height(); ++j)
        for (int i = 0; i < input.width(); ++i)
        {
            const osg::Vec4f c = input.get(i, j);
            y.set(i, j, grey(SobelFilter::luminance(c), c[3]));
        }
    const std::vector<float> w = GaussianFilter::weightsFor(std::max(0.0f, _sigma));
    FilterImage s = GaussianFilter::blurAxis(GaussianFilter::blurAxis(y, w, 0, border), w, 1, border);
    for (int j = 0; j < s.height(); ++j)
        for (int i = 0; i < s.width(); ++i)
        {
            const float* p = s.texel(i, j);
            const float scaled = p[0] * 255.0f + 0.5f; // the GLSL twin is `precise`: no fused multiply-add
            const float l = std::min(255.0f, std::max(0.0f, std::floor(scaled)));
            s.set(i, j, grey(l, p[3]));
        }
    return s;
}

FilterImage CannyFilter::edgeClasses(const FilterImage& input, const ImageBorder& border) const
{
    const int w = input.width(), h = input.height();
    FilterImage out(w, h);
    if (input.empty()) return out;
    const FilterImage lum = quantizedLuminance(input, border);
    // Integer Sobel gradients of L (exact in float) and their squared magnitudes.
    std::vector<int> gx(out.texelCount()), gy(out.texelCount()), m2(out.texelCount());
    auto L = [&](int x, int y) { return int(lum.fetch(x, y, border)[0]); };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const std::size_t k = std::size_t(y) * std::size_t(w) + std::size_t(x);
            gx[k] = (L(x + 1, y - 1) + 2 * L(x + 1, y) + L(x + 1, y + 1)) -
                    (L(x - 1, y - 1) + 2 * L(x - 1, y) + L(x - 1, y + 1));
            gy[k] = (L(x - 1, y + 1) + 2 * L(x, y + 1) + L(x + 1, y + 1)) -
                    (L(x - 1, y - 1) + 2 * L(x, y - 1) + L(x + 1, y - 1));
            m2[k] = gx[k] * gx[k] + gy[k] * gy[k];
        }
    // m2 of a neighbour: 0 outside the image except along an axis that repeats.
    auto M = [&](int x, int y)
    {
        if (outside(x, w, border.s) || outside(y, h, border.t)) return 0;
        return m2[std::size_t(wrapIndex(y, h, border.t)) * std::size_t(w) +
                  std::size_t(wrapIndex(x, w, border.s))];
    };
    const int lowSq = squaredThreshold(_low), highSq = squaredThreshold(_high);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const std::size_t k = std::size_t(y) * std::size_t(w) + std::size_t(x);
            const int m = m2[k];
            float c = 0.0f;
            if (m >= lowSq)
            {
                const int a = std::abs(gx[k]), b = std::abs(gy[k]);
                int dx = 1, dy = 1;
                bool diagonal = false;
                if (32768 * b < 13573 * a)
                    dy = 0; // gradient near 0 degrees: left and right neighbours
                else if (32768 * b > 79109 * a)
                    dx = 0; // near 90 degrees: above and below
                else
                {
                    diagonal = true;
                    dx = (gx[k] < 0) != (gy[k] < 0) ? -1 : 1;
                }
                const int before = M(x - dx, y - dy), after = M(x + dx, y + dy);
                if (m > before && (diagonal ? m > after : m >= after)) c = m >= highSq ? kStrong : kWeak;
            }
            out.set(x, y, grey(c, input.get(x, y)[3]));
        }
    return out;
}

FilterImage CannyFilter::hysteresis(const FilterImage& classes, const ImageBorder& border, int iterations)
{
    FilterImage out = classes;
    const int w = classes.width(), h = classes.height();
    // Breadth-first from every strong texel through weak ones; a texel first reached at depth d
    // is what d Jacobi steps of 8-neighbour propagation (the GPU passes) make strong.
    std::vector<std::pair<int, int>> frontier, next;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (classes.get(x, y)[0] == kStrong) frontier.push_back({x, y});
    for (int depth = 0; !frontier.empty() && (iterations < 0 || depth < iterations); ++depth)
    {
        next.clear();
        for (const auto& [x, y] : frontier)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                {
                    const int nx = wrapIndex(x + dx, w, border.s), ny = wrapIndex(y + dy, h, border.t);
                    float* p = out.texel(nx, ny);
                    if (p[0] != kWeak) continue;
                    p[0] = p[1] = p[2] = kStrong;
                    next.push_back({nx, ny});
                }
        frontier.swap(next);
    }
    return out;
}

FilterImage CannyFilter::applyBoundedHysteresis(const FilterImage& input, const ImageBorder& border,
                                                int iterations) const
{
    checkParameters();
    const FilterImage classes = hysteresis(edgeClasses(input, border), border, iterations);
    FilterImage out(input.width(), input.height());
    for (int y = 0; y < input.height(); ++y)
        for (int x = 0; x < input.width(); ++x)
            out.set(x, y, grey(classes.get(x, y)[0] == kStrong ? 0.0f : 1.0f, input.get(x, y)[3]));
    return out;
}

FilterImage CannyFilter::apply(const FilterImage& input, const ImageBorder& border) const
{
    return applyBoundedHysteresis(input, border, -1);
}

std::vector<GpuFilterPass> CannyFilter::gpuPasses() const
{
    const std::vector<float> w = GaussianFilter::weightsFor(std::clamp(_sigma, 0.0f, maximumSigma()));
    const int r = int(w.size()) - 1;
    const int n = std::clamp(_hysteresisIterations, 0, maximumHysteresisIterations());
    auto pass = [&](int stage, std::vector<int> inputs, int radius)
    {
        GpuFilterPass p;
        p.shader = "loa_filter_canny.comp.glsl";
        p.defines = {{"LOA_CANNY_STAGE", std::to_string(stage)}};
        p.inputs = std::move(inputs);
        p.radius = radius;
        return p;
    };
    std::vector<GpuFilterPass> passes;
    for (int axis = 0; axis < 2; ++axis)
    {
        // Stage 0: Y blurred along x; stage 1: along y, then rounded to 8 bits.
        GpuFilterPass p = pass(axis, {axis == 0 ? -1 : 0}, r);
        p.defines.push_back({"LOA_RADIUS", std::to_string(r)});
        p.uniforms = {GpuUniform::array("loa_weights", w)};
        passes.push_back(p);
    }
    passes.push_back(pass(2, {1}, 1)); // gradient (gx, gy, m2)
    GpuFilterPass classify = pass(3, {2}, 1);
    classify.uniforms = {GpuUniform::integer("loa_lowSq", squaredThreshold(_low)),
                         GpuUniform::integer("loa_highSq", squaredThreshold(_high))};
    passes.push_back(classify);
    for (int i = 0; i < n; ++i)
        passes.push_back(pass(4, {int(passes.size()) - 1}, 1)); // one hysteresis step
    passes.push_back(pass(5, {int(passes.size()) - 1, -1}, 0)); // edge image, input's alpha
    return passes;
}

std::vector<FilterParameter> CannyFilter::parameters()
{
    FilterParameter s;
    s.name = "sigma";
    s.description = "standard deviation of the Gaussian smoothing of luminance, texels (0: none)";
    s.minimum = 0;
    s.maximum = maximumSigma();
    s.get = [this] { return double(_sigma); };
    s.set = [this](double v) { _sigma = float(v); };
    FilterParameter lo;
    lo.name = "low";
    lo.description = "weak-edge threshold on M = |Sobel gradient| / 4 (a unit step gives 1), <= high";
    lo.minimum = 0;
    lo.maximum = maximumThreshold();
    lo.get = [this] { return double(_low); };
    lo.set = [this](double v) { _low = float(v); };
    FilterParameter hi;
    hi.name = "high";
    hi.description = "strong-edge threshold on M, >= low";
    hi.minimum = 0;
    hi.maximum = maximumThreshold();
    hi.get = [this] { return double(_high); };
    hi.set = [this](double v) { _high = float(v); };
    FilterParameter it;
    it.name = "hysteresis_iterations";
    it.description = "GPU hysteresis propagation passes: weak chains longer than this are cut on the GPU";
    it.minimum = 0;
    it.maximum = maximumHysteresisIterations();
    it.integer = true;
    it.get = [this] { return double(_hysteresisIterations); };
    it.set = [this](double v) { _hysteresisIterations = int(v); };
    return {s, lo, hi, it};
}

} // namespace osgLoA
