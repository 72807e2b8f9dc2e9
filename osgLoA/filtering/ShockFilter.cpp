/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/GaussianFilter>
#include <osgLoA/filtering/ShockFilter>
#include <osgLoA/filtering/StructureTensor>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace osgLoA
{

static FilterRegistry::Entry<ShockFilter>
    s_registeredShockFilter("shock",
                 "coherence-enhancing shock filtering (Kyprianidis & Kang 2011): flow-guided smoothing "
                 "and directional shock filter, iterated");

namespace
{
const double kPi = 3.14159265358979323846;

/** The parameters as the filter uses them (clamped to their ranges). */
struct ShockParams
{
    int iterations;
    float sigmaD, sigmaS, maxAngle, sigmaI, sigmaG, tauS, radius, sigmaA;
    bool adaptive;
};

float luma(const osg::Vec4f& c)
{
    return 0.299f * c[0] + 0.587f * c[1] + 0.114f * c[2];
}

int licSteps(float sigma)
{
    return int(std::ceil(2.0f * sigma));
}

float cosOfDegrees(float degrees)
{
    return float(std::cos(double(degrees) * kPi / 180.0));
}

std::string glslFloat(float v)
{
    char b[48];
    std::snprintf(b, sizeof b, "%.9g", double(v));
    std::string s = b;
    if (s.find_first_of(".eE") == std::string::npos) s += ".0";
    return s;
}

osg::Vec2f tangentAt(const FilterImage& tensor, const osg::Vec2f& p, const ImageBorder& border)
{
    const osg::Vec4f t = tensor.sampleBilinear(p.x(), p.y(), border);
    const osg::Vec4f f = StructureTensor::flowOf(t[0], t[1], t[2]);
    return osg::Vec2f(f[0], f[1]);
}
} // namespace

FilterImage ShockFilter::flowSmooth(const FilterImage& image, const FilterImage& tensor, float sigma,
                                    float maxAngle, bool adaptive, const ImageBorder& border)
{
    if (sigma <= 0.0f || image.empty()) return image;
    const float cosMax = cosOfDegrees(maxAngle);
    const int steps = licSteps(sigma);
    FilterImage out(image.width(), image.height());
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x)
        {
            const osg::Vec2f p0(float(x) + 0.5f, float(y) + 0.5f);
            const float* t0 = tensor.texel(x, y);
            const osg::Vec4f f0 = StructureTensor::flowOf(t0[0], t0[1], t0[2]);
            const float s = adaptive ? sigma * 0.25f * (1.0f + f0[2]) * (1.0f + f0[2]) : sigma;
            const float length = 2.0f * s, twoS2 = 2.0f * s * s;
            const osg::Vec4f centre = image.get(x, y);
            osg::Vec3f c(centre[0], centre[1], centre[2]);
            float w = 1.0f;
            for (int side = 0; side < 2; ++side)
            {
                osg::Vec2f v = osg::Vec2f(f0[0], f0[1]) * (side == 0 ? -1.0f : 1.0f);
                osg::Vec2f p = p0 + v;
                float u = 1.0f;
                for (int k = 0; k < steps; ++k)
                {
                    if (!(u < length)) break;
                    const float kk = std::exp(-u * u / twoS2);
                    const osg::Vec4f sample = image.sampleBilinear(p.x(), p.y(), border);
                    c += osg::Vec3f(sample[0], sample[1], sample[2]) * kk;
                    w += kk;
                    osg::Vec2f t = tangentAt(tensor, p, border);
                    if (v * t < 0.0f) t = -t;
                    t = tangentAt(tensor, p + t * 0.5f, border);
                    const float vt = v * t;
                    if (std::fabs(vt) <= cosMax) break;
                    if (vt < 0.0f) t = -t;
                    v = t;
                    p += t;
                    u += 1.0f;
                }
            }
            out.set(x, y, osg::Vec4f(c / w, centre[3]));
        }
    return out;
}

FilterImage ShockFilter::shock(const FilterImage& image, const FilterImage& lumaSource,
                               const FilterImage& tensor, float sigmaG, float tauS, float radius,
                               const ImageBorder& border)
{
    FilterImage out(image.width(), image.height());
    const float s2 = sigmaG * sigmaG, twoS2 = 2.0f * s2, halfWidth = 5.0f * sigmaG;
    const int logSteps = int(std::floor(halfWidth)), rSteps = int(std::floor(radius));
    const float norm = float(std::sqrt(2.0 * kPi)) * s2 * sigmaG;
    auto L = [&](const osg::Vec2f& q) { return luma(lumaSource.sampleBilinear(q.x(), q.y(), border)); };
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x)
        {
            const float* tt = tensor.texel(x, y);
            const osg::Vec4f f = StructureTensor::flowOf(tt[0], tt[1], tt[2]);
            const osg::Vec2f n(f[1], -f[0]);
            const float nx = std::fabs(n.x()), ny = std::fabs(n.y());
            const osg::Vec2f p0(float(x) + 0.5f, float(y) + 0.5f);

            const float ds = 1.0f / std::max(nx, ny);
            float sum = -s2 * luma(lumaSource.get(x, y));
            for (int k = 1; k <= logSteps; ++k)
            {
                const float d = float(k) * ds;
                if (d > halfWidth) break;
                const float kk = (d * d - s2) * std::exp(-d * d / twoS2);
                const osg::Vec2f o = n * d;
                sum += kk * (L(p0 - o) + L(p0 + o));
            }
            sum = -sum / norm;
            if (std::fabs(sum) < tauS) sum = 0.0f;

            const osg::Vec4f c0 = image.get(x, y);
            osg::Vec4f hi = c0, lo = c0;
            float hiL = luma(c0), loL = hiL;
            const osg::Vec2f dp = nx > ny ? osg::Vec2f(0.0f, 0.5f) : osg::Vec2f(0.5f, 0.0f);
            for (int k = 1; k <= rSteps; ++k)
            {
                const float d = float(k) * ds;
                if (d > radius) break;
                const osg::Vec2f o = n * d;
                const osg::Vec2f qs[4] = {p0 + o + dp, p0 + o - dp, p0 - o + dp, p0 - o - dp};
                for (const osg::Vec2f& q : qs)
                {
                    const osg::Vec4f c = image.fetch(int(std::floor(q.x())), int(std::floor(q.y())), border);
                    const float l = luma(c);
                    if (l > hiL)
                    {
                        hiL = l;
                        hi = c;
                    }
                    if (l < loL)
                    {
                        loL = l;
                        lo = c;
                    }
                }
            }
            const osg::Vec4f r = sum > 0.0f ? hi : (sum < 0.0f ? lo : c0);
            out.set(x, y, osg::Vec4f(r[0], r[1], r[2], c0[3]));
        }
    return out;
}

namespace
{
ShockParams paramsOf(int iterations, float sigmaD, float sigmaS, float maxAngle, float sigmaI, float sigmaG,
                     float tauS, float radius, float sigmaA, bool adaptive)
{
    ShockParams p;
    p.iterations = std::clamp(iterations, 0, 10);
    p.sigmaD = std::clamp(sigmaD, 0.0f, 8.0f);
    p.sigmaS = std::clamp(sigmaS, 0.0f, 16.0f);
    p.maxAngle = std::clamp(maxAngle, 0.0f, 90.0f);
    p.sigmaI = std::clamp(sigmaI, 0.0f, 8.0f);
    p.sigmaG = std::clamp(sigmaG, 0.25f, 8.0f);
    p.tauS = std::clamp(tauS, 0.0f, 1.0f);
    p.radius = std::clamp(radius, 0.0f, 8.0f);
    p.sigmaA = std::clamp(sigmaA, 0.0f, 8.0f);
    p.adaptive = adaptive;
    return p;
}
} // namespace

FilterImage ShockFilter::apply(const FilterImage& input, const ImageBorder& border) const
{
    if (input.empty()) return FilterImage(input.width(), input.height());
    const ShockParams P = paramsOf(_iterations, _sigmaD, _sigmaS, _maxAngle, _sigmaI, _sigmaG, _tauS, _radius,
                                   _sigmaA, _adaptive);
    FilterImage img = input, tensor;
    for (int it = 0; it < P.iterations; ++it)
    {
        if (P.sigmaS > 0.0f)
            img = flowSmooth(img, StructureTensor::smoothedTensor(img, P.sigmaD, border), P.sigmaS,
                             P.maxAngle, P.adaptive, border);
        tensor = StructureTensor::smoothedTensor(img, P.sigmaD, border);
        FilterImage lumaSource = img;
        if (P.sigmaI > 0.0f)
        {
            const std::vector<float> w = GaussianFilter::weightsFor(P.sigmaI);
            lumaSource = GaussianFilter::blurAxis(GaussianFilter::blurAxis(img, w, 0, border), w, 1, border);
        }
        img = shock(img, lumaSource, tensor, P.sigmaG, P.tauS, P.radius, border);
    }
    if (P.sigmaA > 0.0f)
    {
        if (P.iterations == 0) tensor = StructureTensor::smoothedTensor(img, P.sigmaD, border);
        img = flowSmooth(img, tensor, P.sigmaA, 90.0f, false, border);
    }
    return img;
}

std::vector<GpuFilterPass> ShockFilter::gpuPasses() const
{
    const ShockParams P = paramsOf(_iterations, _sigmaD, _sigmaS, _maxAngle, _sigmaI, _sigmaG, _tauS, _radius,
                                   _sigmaA, _adaptive);
    std::vector<GpuFilterPass> passes;
    auto append = [&](const std::vector<GpuFilterPass>& more)
    {
        passes.insert(passes.end(), more.begin(), more.end());
        return int(passes.size()) - 1;
    };
    auto lic = [&](int image, int tensor, float sigma, float maxAngle, bool adaptive)
    {
        GpuFilterPass p;
        p.shader = "loa_filter_shock.comp.glsl";
        p.defines = {{"LOA_SHOCK_STAGE", "0"},
                     {"LOA_SHOCK_SIGMA", glslFloat(sigma)},
                     {"LOA_SHOCK_STEPS", std::to_string(licSteps(sigma))},
                     {"LOA_SHOCK_COSMAX", glslFloat(cosOfDegrees(maxAngle))},
                     {"LOA_SHOCK_ADAPTIVE", adaptive ? "1" : "0"}};
        p.inputs = {image, tensor};
        p.radius = licSteps(sigma) + 2; // bilinear samples and the Runge-Kutta midpoint
        return append({p});
    };
    int image = -1, tensor = -1;
    for (int it = 0; it < P.iterations; ++it)
    {
        if (P.sigmaS > 0.0f)
        {
            const int t1 = append(StructureTensor::tensorPasses(P.sigmaD, image, int(passes.size())));
            image = lic(image, t1, P.sigmaS, P.maxAngle, P.adaptive);
        }
        tensor = append(StructureTensor::tensorPasses(P.sigmaD, image, int(passes.size())));
        int lumaSource = image;
        if (P.sigmaI > 0.0f)
        {
            const std::vector<float> w = GaussianFilter::weightsFor(P.sigmaI);
            const int r = int(w.size()) - 1;
            for (int axis = 0; axis < 2; ++axis)
            {
                GpuFilterPass g;
                g.shader = "loa_filter_gaussian.comp.glsl";
                g.defines = {{"LOA_AXIS", std::to_string(axis)}, {"LOA_RADIUS", std::to_string(r)}};
                g.uniforms = {GpuUniform::array("loa_weights", w)};
                g.inputs = {lumaSource};
                g.radius = r;
                lumaSource = append({g});
            }
        }
        GpuFilterPass s;
        s.shader = "loa_filter_shock.comp.glsl";
        s.defines = {{"LOA_SHOCK_STAGE", "1"},
                     {"LOA_SHOCK_SIGMAG", glslFloat(P.sigmaG)},
                     {"LOA_SHOCK_LOGSTEPS", std::to_string(int(std::floor(5.0f * P.sigmaG)))},
                     {"LOA_SHOCK_TAU", glslFloat(P.tauS)},
                     {"LOA_SHOCK_RADIUS", glslFloat(P.radius)},
                     {"LOA_SHOCK_RSTEPS", std::to_string(int(std::floor(P.radius)))}};
        s.inputs = {image, tensor, lumaSource};
        s.radius = int(std::ceil(std::max(5.0f * P.sigmaG, P.radius))) + 2;
        image = append({s});
    }
    if (P.sigmaA > 0.0f)
    {
        if (P.iterations == 0) tensor = append(StructureTensor::tensorPasses(P.sigmaD, -1, 0));
        image = lic(image, tensor, P.sigmaA, 90.0f, false);
    }
    if (image == -1)
    {
        GpuFilterPass copy;
        copy.shader = "loa_filter_shock.comp.glsl";
        copy.defines = {{"LOA_SHOCK_STAGE", "2"}};
        copy.inputs = {-1};
        passes.push_back(copy);
    }
    return passes;
}

std::vector<FilterParameter> ShockFilter::parameters()
{
    auto make = [](const char* name, const char* description, double lo, double hi, float* value)
    {
        FilterParameter p;
        p.name = name;
        p.description = description;
        p.minimum = lo;
        p.maximum = hi;
        p.get = [value] { return double(*value); };
        p.set = [value](double v) { *value = float(v); };
        return p;
    };
    FilterParameter n;
    n.name = "iterations";
    n.description = "iterations of flow-guided smoothing and shock filtering";
    n.minimum = 0;
    n.maximum = 10;
    n.integer = true;
    n.get = [this] { return double(_iterations); };
    n.set = [this](double v) { _iterations = int(v); };
    FilterParameter adaptive;
    adaptive.name = "adaptive";
    adaptive.description = "flow-guided smoothing length adapted to the anisotropy";
    adaptive.minimum = 0;
    adaptive.maximum = 1;
    adaptive.integer = true;
    adaptive.choices = {"off", "on"};
    adaptive.get = [this] { return _adaptive ? 1.0 : 0.0; };
    adaptive.set = [this](double v) { _adaptive = v > 0.5; };
    return {n,
            make("sigma_d", "structure tensor smoothing, texels", 0, 8, &_sigmaD),
            make("sigma_s", "flow-guided smoothing sigma, texels", 0, 16, &_sigmaS),
            make("max_angle", "largest streamline turn per step, degrees", 0, 90, &_maxAngle),
            adaptive,
            make("sigma_i", "luminance pre-smoothing for the shock sign, texels", 0, 8, &_sigmaI),
            make("sigma_g", "directional Laplacian of Gaussian sigma, texels", 0.25, 8, &_sigmaG),
            make("tau_s", "shock sign threshold", 0, 1, &_tauS),
            make("radius", "dilation/erosion radius along the gradient, texels", 0, 8, &_radius),
            make("sigma_a", "final flow-guided smoothing sigma, texels", 0, 8, &_sigmaA)};
}

} // namespace osgLoA
