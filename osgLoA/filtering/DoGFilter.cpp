/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/DoGFilter>
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/FlowBilateralFilter>
#include <osgLoA/filtering/GaussianFilter>
#include <osgLoA/filtering/StructureTensor>

#include <algorithm>
#include <cmath>

namespace osgLoA
{

static FilterRegistry::Entry<DoGFilter> s_registeredDoGFilter(
    "dog", "difference of Gaussians on L*: isotropic (flow=0) or flow-based FDoG (flow=1), XDoG threshold");

namespace
{
int radius3(float sigma)
{
    return sigma <= 0.0f ? 0 : int(std::ceil(3.0f * sigma));
}

/** GaussianFilter's one-sided weights for sigma, padded with zeros to r + 1 entries. */
std::vector<float> paddedWeights(float sigma, int r)
{
    std::vector<float> w = GaussianFilter::weightsFor(sigma);
    w.resize(std::size_t(r) + 1, 0.0f);
    return w;
}

/** The 1-D two-kernel blur of the isotropic DoG: channel `src` (and `src2`, or src again) along
 *  axis; output (kernel e of src, kernel r of src2, 0, alpha). */
FilterImage blurPair(const FilterImage& in, int src, int src2, const std::vector<float>& we,
                     const std::vector<float>& wr, int axis, const ImageBorder& border)
{
    FilterImage out(in.width(), in.height());
    const int r = int(we.size()) - 1;
    const int dx = axis == 0 ? 1 : 0, dy = axis == 0 ? 0 : 1;
    for (int y = 0; y < in.height(); ++y)
        for (int x = 0; x < in.width(); ++x)
        {
            const osg::Vec4f c = in.get(x, y);
            float se = c[src] * we[0], sr = c[src2] * wr[0];
            for (int k = 1; k <= r; ++k)
            {
                const osg::Vec4f a = in.fetch(x + dx * k, y + dy * k, border);
                const osg::Vec4f b = in.fetch(x - dx * k, y - dy * k, border);
                se += (a[src] + b[src]) * we[std::size_t(k)];
                sr += (a[src2] + b[src2]) * wr[std::size_t(k)];
            }
            out.set(x, y, osg::Vec4f(se, sr, 0.0f, c[3]));
        }
    return out;
}

osg::Vec4f grey(float v, float alpha)
{
    return osg::Vec4f(v, v, v, alpha);
}
} // namespace

float DoGFilter::responseScale() const
{
    return _mode == XDOG ? 1.0f / (1.0f - _tau) : 1.0f;
}

float DoGFilter::threshold(float u) const
{
    if (u >= _epsilon) return 1.0f;
    return 1.0f + std::tanh(std::max(_phi * (u - _epsilon), -20.0f));
}

FilterImage DoGFilter::flowDoG(const FilterImage& luminance, const FilterImage& tensor,
                               const ImageBorder& border) const
{
    const int w = luminance.width(), h = luminance.height();
    // Stage 1: the 1-D DoG across the edge (along g), scaled to u.
    const float sr = _k * _sigmaE;
    const int K = radius3(sr);
    const float scale = responseScale();
    FilterImage u(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const float* tp = tensor.texel(x, y);
            const osg::Vec2f t = StructureTensor::tangentOf(tp[0], tp[1], tp[2]);
            const osg::Vec2f g(t[1], -t[0]);
            const osg::Vec2f s = g / std::max(std::fabs(g[0]), std::fabs(g[1]));
            const float ds = s.length();
            const osg::Vec2f x0(float(x) + 0.5f, float(y) + 0.5f);
            const osg::Vec4f c = luminance.get(x, y);
            float se = c[0], we = 1.0f, sk = c[0], wk = 1.0f;
            for (int j = 1; j <= K; ++j)
            {
                const osg::Vec2f a = x0 + s * float(j), b = x0 - s * float(j);
                const float la = luminance.sampleBilinear(a[0], a[1], border)[0];
                const float lb = luminance.sampleBilinear(b[0], b[1], border)[0];
                const float d2 = (float(j) * ds) * (float(j) * ds);
                const float ke = std::exp(-d2 / (2.0f * _sigmaE * _sigmaE));
                const float kk = std::exp(-d2 / (2.0f * sr * sr));
                se += ke * (la + lb);
                we += 2.0f * ke;
                sk += kk * (la + lb);
                wk += 2.0f * kk;
            }
            u.set(x, y, osg::Vec4f((se / we - _tau * sk / wk) * scale, 0.0f, 0.0f, c[3]));
        }
    // Stage 2: line integral convolution along the flow, then the threshold.
    const int M = radius3(_sigmaM);
    FilterImage out(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const float* tp = tensor.texel(x, y);
            const osg::Vec2f t0 = StructureTensor::tangentOf(tp[0], tp[1], tp[2]);
            const osg::Vec2f x0(float(x) + 0.5f, float(y) + 0.5f);
            float sum = u.get(x, y)[0], wsum = 1.0f;
            for (int side = 0; side < 2; ++side)
            {
                osg::Vec2f p = x0, v = side == 0 ? t0 : -t0;
                for (int i = 1; i <= M; ++i)
                {
                    p += v;
                    const float k = std::exp(-float(i * i) / (2.0f * _sigmaM * _sigmaM));
                    sum += k * u.sampleBilinear(p[0], p[1], border)[0];
                    wsum += k;
                    const osg::Vec4f e = tensor.sampleBilinear(p[0], p[1], border);
                    osg::Vec2f tn = StructureTensor::tangentOf(e[0], e[1], e[2]);
                    if (tn * v < 0.0f) tn = -tn;
                    v = tn;
                }
            }
            out.set(x, y, grey(threshold(sum / wsum), u.get(x, y)[3]));
        }
    return out;
}

FilterImage DoGFilter::apply(const FilterImage& input, const ImageBorder& border) const
{
    checkParameters();
    const FilterImage lab = FlowBilateralFilter::toLab(input);
    if (_flow) return flowDoG(lab, StructureTensor::smoothedTensor(input, _rho, border), border);
    const int r = radius3(_k * _sigmaE);
    const std::vector<float> we = paddedWeights(_sigmaE, r), wr = paddedWeights(_k * _sigmaE, r);
    const FilterImage hz = blurPair(lab, 0, 0, we, wr, 0, border);
    const FilterImage vt = blurPair(hz, 0, 1, we, wr, 1, border);
    FilterImage out(input.width(), input.height());
    const float scale = responseScale();
    for (int y = 0; y < input.height(); ++y)
        for (int x = 0; x < input.width(); ++x)
        {
            const float* p = vt.texel(x, y);
            out.set(x, y, grey(threshold((p[0] - _tau * p[1]) * scale), p[3]));
        }
    return out;
}

namespace
{
std::vector<GpuUniform> thresholdUniforms(float tau, float scale, float epsilon, float phi)
{
    return {GpuUniform::scalar("loa_tau", tau), GpuUniform::scalar("loa_scale", scale),
            GpuUniform::scalar("loa_epsilon", epsilon), GpuUniform::scalar("loa_phi", phi)};
}

GpuFilterPass labPass()
{
    GpuFilterPass p;
    p.shader = "loa_filter_lab.comp.glsl";
    p.defines = {{"LOA_LAB_STAGE", "0"}};
    p.inputs = {-1};
    return p;
}
} // namespace

std::vector<GpuFilterPass> DoGFilter::flowDoGPasses(int luminance, int tensor, int firstIndex) const
{
    const float sr = _k * _sigmaE;
    const int K = radius3(sr), M = radius3(_sigmaM);
    GpuFilterPass across;
    across.shader = "loa_filter_fdog.comp.glsl";
    across.defines = {{"LOA_FDOG_STAGE", "0"}, {"LOA_STEPS", std::to_string(K)}};
    across.uniforms = thresholdUniforms(_tau, responseScale(), _epsilon, _phi);
    across.uniforms.push_back(GpuUniform::scalar("loa_sigmaE", _sigmaE));
    across.uniforms.push_back(GpuUniform::scalar("loa_sigmaR", sr));
    across.inputs = {luminance, tensor};
    across.radius = K + 1;
    GpuFilterPass along;
    along.shader = "loa_filter_fdog.comp.glsl";
    along.defines = {{"LOA_FDOG_STAGE", "1"}, {"LOA_STEPS", std::to_string(M)}};
    along.uniforms = thresholdUniforms(_tau, responseScale(), _epsilon, _phi);
    along.uniforms.push_back(GpuUniform::scalar("loa_sigmaM", _sigmaM));
    along.inputs = {firstIndex, tensor};
    along.radius = M + 1;
    return {across, along};
}

std::vector<GpuFilterPass> DoGFilter::gpuPasses() const
{
    std::vector<GpuFilterPass> passes{labPass()};
    if (_flow)
    {
        const std::vector<GpuFilterPass> st = StructureTensor::tensorPasses(_rho, -1, 1);
        passes.insert(passes.end(), st.begin(), st.end());
        const std::vector<GpuFilterPass> fd = flowDoGPasses(0, int(passes.size()) - 1, int(passes.size()));
        passes.insert(passes.end(), fd.begin(), fd.end());
        return passes;
    }
    const int r = radius3(_k * _sigmaE);
    for (int axis = 0; axis < 2; ++axis)
    {
        GpuFilterPass p;
        p.shader = "loa_filter_dog.comp.glsl";
        p.defines = {{"LOA_AXIS", std::to_string(axis)}, {"LOA_RADIUS", std::to_string(r)}};
        p.uniforms = thresholdUniforms(_tau, responseScale(), _epsilon, _phi);
        p.uniforms.push_back(GpuUniform::array("loa_weightsE", paddedWeights(_sigmaE, r)));
        p.uniforms.push_back(GpuUniform::array("loa_weightsR", paddedWeights(_k * _sigmaE, r)));
        p.inputs = {axis};
        p.radius = r;
        passes.push_back(p);
    }
    return passes;
}

std::vector<FilterParameter> DoGFilter::parameters()
{
    auto number = [](const char* name, const char* description, double lo, double hi, float& v)
    {
        FilterParameter p;
        p.name = name;
        p.description = description;
        p.minimum = lo;
        p.maximum = hi;
        p.get = [&v] { return double(v); };
        p.set = [&v](double x) { v = float(x); };
        return p;
    };
    std::vector<FilterParameter> ps;
    ps.push_back(number("sigma_e", "standard deviation of the inner Gaussian, texels", 0.1, 16, _sigmaE));
    ps.push_back(number("k", "ratio of the outer to the inner standard deviation", 1, 8, _k));
    ps.push_back(
        number("tau", "weight of the outer Gaussian (p = tau / (1 - tau) in XDoG terms)", 0, 0.999, _tau));
    ps.push_back(number("epsilon", "threshold, L* units", -100, 100, _epsilon));
    ps.push_back(number("phi", "steepness of the soft threshold, 1/L*", 0, 1000, _phi));
    ps.push_back(
        number("sigma_m", "flow-curve smoothing standard deviation (flow=1), texels", 0, 16, _sigmaM));
    ps.push_back(number("rho", "structure tensor smoothing sigma_c (flow=1), texels", 0, 16, _rho));
    FilterParameter flow;
    flow.name = "flow";
    flow.description = "0 isotropic DoG, 1 flow-based DoG (FDoG)";
    flow.minimum = 0;
    flow.maximum = 1;
    flow.integer = true;
    flow.get = [this] { return _flow ? 1.0 : 0.0; };
    flow.set = [this](double v) { _flow = v > 0.5; };
    ps.push_back(flow);
    FilterParameter mode;
    mode.name = "mode";
    mode.description = "edges: black lines on white; xdog: continuous tone (u = D / (1 - tau))";
    mode.minimum = 0;
    mode.maximum = 1;
    mode.integer = true;
    mode.choices = {"edges", "xdog"};
    mode.get = [this] { return double(_mode); };
    mode.set = [this](double v) { _mode = v > 0.5 ? XDOG : EDGES; };
    ps.push_back(mode);
    return ps;
}

} // namespace osgLoA
