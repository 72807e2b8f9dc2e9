/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/DomainTransformFilter>
#include <osgLoA/filtering/FilterRegistry>

#include <cmath>

namespace osgLoA
{

static FilterRegistry::Entry<DomainTransformFilter> s_registeredDomainTransformFilter(
    "domain_transform",
    "domain transform recursive filter (Gastal and Oliveira 2011; sigma_s, sigma_r, iterations)");

double DomainTransformFilter::iterationSigma(double sigmaS, int i, int iterations)
{
    return sigmaS * std::sqrt(3.0) * std::pow(2.0, iterations - i) /
           std::sqrt(std::pow(4.0, iterations) - 1.0);
}

namespace
{
/** One line of the image: n texels at `first`, `stride` floats apart (RGBA). */
struct Line
{
    float* first;
    std::ptrdiff_t stride;
    float* at(int i) const { return first + i * stride; }
};

/** The recursion of one line in place: forward then backward. weight[i] = a^d_i for i in [0, P] is the weight
 *  between positions i-1 and i of the line extended by the wrap mode, periodic with P = n (repeat, clamp) or
 *  2n (mirror); values at position i are those of wrapIndex(i, n, mode). */
void filterLine(const Line& line, int n, WrapMode mode, const std::vector<double>& weight,
                std::vector<double>& scratch)
{
    // Clamp uses only weight[1 .. n-1].
    const int period = mode == WrapMode::Mirror ? 2 * n : n;
    auto value = [&](int i, int c) { return double(line.at(wrapIndex(i, n, mode))[c]); };
    auto w = [&](int i) { return weight[std::size_t(((i % period) + period) % period)]; };
    double prev[3];
    // Forward.
    if (mode == WrapMode::Clamp || n == 1)
        for (int c = 0; c < 3; ++c)
            prev[c] = value(0, c);
    else
    {
        double acc[3] = {0, 0, 0}, beta = 1;
        for (int i = -period; i < 0; ++i)
        {
            const double wi = w(i);
            for (int c = 0; c < 3; ++c)
                acc[c] = (1 - wi) * value(i, c) + wi * acc[c];
            beta *= wi;
        }
        for (int c = 0; c < 3; ++c)
            prev[c] = acc[c] / (1 - beta);
    }
    scratch.resize(std::size_t(3 * n));
    for (int i = 0; i < n; ++i)
    {
        const double wi = w(i);
        for (int c = 0; c < 3; ++c)
            prev[c] = scratch[std::size_t(3 * i + c)] = (1 - wi) * double(line.at(i)[c]) + wi * prev[c];
    }
    // Backward, on the forward result J (scratch) extended the same way.
    auto j = [&](int i, int c) { return scratch[std::size_t(3 * wrapIndex(i, n, mode) + c)]; };
    double next[3];
    if (mode == WrapMode::Clamp || n == 1)
        for (int c = 0; c < 3; ++c)
            next[c] = j(n - 1, c);
    else
    {
        double acc[3] = {0, 0, 0}, beta = 1;
        for (int i = n + period - 1; i >= n; --i)
        {
            const double wi = w(i + 1);
            for (int c = 0; c < 3; ++c)
                acc[c] = (1 - wi) * j(i, c) + wi * acc[c];
            beta *= wi;
        }
        for (int c = 0; c < 3; ++c)
            next[c] = acc[c] / (1 - beta);
    }
    for (int i = n - 1; i >= 0; --i)
    {
        const double wi = w(i + 1);
        for (int c = 0; c < 3; ++c)
        {
            next[c] = (1 - wi) * scratch[std::size_t(3 * i + c)] + wi * next[c];
            line.at(i)[c] = float(next[c]);
        }
    }
}

/** d between positions i-1 and i of the input line, i in [0, period), wrapped. */
void lineDerivative(const float* first, std::ptrdiff_t stride, int n, WrapMode mode, double ratio,
                    std::vector<double>& d)
{
    const int period = mode == WrapMode::Mirror ? 2 * n : n;
    d.resize(std::size_t(period) + 1);
    for (int i = 0; i <= period; ++i)
    {
        const float* a = first + wrapIndex(i - 1, n, mode) * stride;
        const float* b = first + wrapIndex(i, n, mode) * stride;
        d[std::size_t(i)] = 1.0 + ratio * (std::fabs(double(b[0]) - a[0]) + std::fabs(double(b[1]) - a[1]) +
                                           std::fabs(double(b[2]) - a[2]));
    }
}
} // namespace

FilterImage DomainTransformFilter::apply(const FilterImage& input, const ImageBorder& border) const
{
    checkParameters();
    if (input.empty()) return input;
    const int w = input.width(), h = input.height();
    const double ratio = double(_sigmaS) / double(_sigmaR);
    FilterImage out = input;
    // The derivatives of every row and column of the input.
    std::vector<std::vector<double>> rowD(static_cast<std::size_t>(h)), colD(static_cast<std::size_t>(w));
    for (int y = 0; y < h; ++y)
        lineDerivative(input.texel(0, y), 4, w, border.s, ratio, rowD[std::size_t(y)]);
    for (int x = 0; x < w; ++x)
        lineDerivative(input.texel(x, 0), std::ptrdiff_t(4) * w, h, border.t, ratio, colD[std::size_t(x)]);

    std::vector<double> weight, scratch;
    for (int i = 1; i <= _iterations; ++i)
    {
        const double lnA = -std::sqrt(2.0) / iterationSigma(_sigmaS, i, _iterations);
        for (int y = 0; y < h; ++y)
        {
            const std::vector<double>& d = rowD[std::size_t(y)];
            weight.resize(d.size());
            for (std::size_t k = 0; k < d.size(); ++k)
                weight[k] = std::exp(lnA * d[k]);
            filterLine(Line{out.texel(0, y), 4}, w, border.s, weight, scratch);
        }
        for (int x = 0; x < w; ++x)
        {
            const std::vector<double>& d = colD[std::size_t(x)];
            weight.resize(d.size());
            for (std::size_t k = 0; k < d.size(); ++k)
                weight[k] = std::exp(lnA * d[k]);
            filterLine(Line{out.texel(x, 0), std::ptrdiff_t(4) * w}, h, border.t, weight, scratch);
        }
    }
    return out;
}

std::vector<GpuFilterPass> DomainTransformFilter::gpuPasses() const
{
    checkParameters();
    std::vector<GpuFilterPass> passes;
    const float ratio = float(double(_sigmaS) / double(_sigmaR));
    for (int i = 1; i <= _iterations; ++i)
    {
        const float lnA = float(-std::sqrt(2.0) / iterationSigma(_sigmaS, i, _iterations));
        for (int axis = 0; axis < 2; ++axis)
        {
            GpuFilterPass p;
            p.shader = "loa_filter_domain_transform.comp.glsl";
            p.uniforms = {GpuUniform::scalar("loa_lnA", lnA), GpuUniform::scalar("loa_ratio", ratio)};
            const int previous = int(passes.size()) - 1;
            p.inputs = {previous, -1};
            p.radius = -1;
            p.dispatch = axis == 0 ? GpuFilterPass::ROWS : GpuFilterPass::COLUMNS;
            passes.push_back(p);
        }
    }
    return passes;
}

std::vector<FilterParameter> DomainTransformFilter::parameters()
{
    FilterParameter ss;
    ss.name = "sigma_s";
    ss.description = "spatial standard deviation, texels";
    ss.minimum = 0.01;
    ss.maximum = 1000;
    ss.get = [this] { return double(_sigmaS); };
    ss.set = [this](double v) { _sigmaS = float(v); };

    FilterParameter sr;
    sr.name = "sigma_r";
    sr.description = "range standard deviation, RGB units in [0, 1]";
    sr.minimum = 0.001;
    sr.maximum = 10;
    sr.get = [this] { return double(_sigmaR); };
    sr.set = [this](double v) { _sigmaR = float(v); };

    FilterParameter it;
    it.name = "iterations";
    it.description = "number of iterations N (each a horizontal and a vertical pass)";
    it.minimum = 1;
    it.maximum = 10;
    it.integer = true;
    it.get = [this] { return double(_iterations); };
    it.set = [this](double v) { _iterations = int(v); };
    return {ss, sr, it};
}

} // namespace osgLoA
