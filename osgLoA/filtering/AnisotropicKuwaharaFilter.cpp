/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/AnisotropicKuwaharaFilter>
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/GaussianFilter>
#include <osgLoA/filtering/StructureTensor>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace osgLoA
{

static FilterRegistry::Entry<AnisotropicKuwaharaFilter>
    s_registeredAnisotropicKuwaharaFilter("akf",
                 "anisotropic Kuwahara filter (Kyprianidis et al. 2009, polynomial weights; levels > 1: "
                 "multi-scale after Kyprianidis 2011)");

namespace
{
const float kPi = 3.14159265358979323846f;

/** The parameters as the filter uses them (clamped to their ranges). */
struct AkfParams
{
    float r, q, alpha, rho, h;
    int levels;
    int rmax; ///< the largest semi-axis, floor(2 r): the loops' constant bound
    float zeta, eta;
};

AkfParams paramsOf(float radius, float q, float alpha, float rho, int levels, float h)
{
    AkfParams p;
    p.r = std::clamp(radius, 1.0f, 12.0f);
    p.q = std::clamp(q, 1.0f, 16.0f);
    p.alpha = std::clamp(alpha, 0.05f, 10.0f);
    p.rho = std::clamp(rho, 0.0f, 8.0f);
    p.levels = std::clamp(levels, 1, 6);
    p.h = std::clamp(h, 0.0f, 64.0f);
    p.rmax = int(std::floor(2.0f * p.r));
    p.zeta = 1.0f / 3.0f;
    const float s = std::sin(3.0f * kPi / 16.0f);
    p.eta = (p.zeta + std::cos(3.0f * kPi / 16.0f)) / (s * s);
    return p;
}

/** The shader stages of shaders/loa_filter_akf.comp.glsl (LOA_AKF_STAGE). */
enum AkfStage
{
    STAGE_DOWN = 0,
    STAGE_SOBEL = 1,
    STAGE_BLURX = 2,
    STAGE_BLURY = 3,
    STAGE_PROPAGATE = 4,
    STAGE_FILTER = 5
};

/** A float as a GLSL literal that reads back as the same float. */
std::string glslFloat(float v)
{
    char b[48];
    std::snprintf(b, sizeof b, "%.9g", double(v));
    std::string s = b;
    if (s.find_first_of(".eE") == std::string::npos) s += ".0";
    return s;
}

/** Polynomial sector weights of one offset v (unit disc), sectors 0, 2, 4, 6 in wa and
 *  1, 3, 5, 7 in wb, each multiplied by g = exp(-3.125 |v|^2) / (sum of the 8). */
void sectorWeights(float vx, float vy, float zeta, float eta, float wa[4], float wb[4])
{
    float vxx = zeta - eta * vx * vx, vyy = zeta - eta * vy * vy;
    float z;
    z = std::max(0.0f, vy + vxx);
    wa[0] = z * z;
    z = std::max(0.0f, -vx + vyy);
    wa[1] = z * z;
    z = std::max(0.0f, -vy + vxx);
    wa[2] = z * z;
    z = std::max(0.0f, vx + vyy);
    wa[3] = z * z;
    const float rx = 0.70710678118654752f * (vx - vy), ry = 0.70710678118654752f * (vx + vy);
    vxx = zeta - eta * rx * rx;
    vyy = zeta - eta * ry * ry;
    z = std::max(0.0f, ry + vxx);
    wb[0] = z * z;
    z = std::max(0.0f, -rx + vyy);
    wb[1] = z * z;
    z = std::max(0.0f, -ry + vxx);
    wb[2] = z * z;
    z = std::max(0.0f, rx + vyy);
    wb[3] = z * z;
    const float sum = wa[0] + wa[1] + wa[2] + wa[3] + wb[0] + wb[1] + wb[2] + wb[3];
    const float g = std::exp(-3.125f * (vx * vx + vy * vy)) / std::max(sum, 1e-20f);
    for (int k = 0; k < 4; ++k)
    {
        wa[k] *= g;
        wb[k] *= g;
    }
}

/** The sector accumulators, laid out as the shader's vec4s: [sector group a = 0,2,4,6 |
 *  b = 1,3,5,7][slot 0..3]. */
struct Sectors
{
    float W[2][4] = {};
    float S[2][3][4] = {};  ///< sum of w c, per channel
    float SS[2][3][4] = {}; ///< sum of w c^2, per channel

    /** Adds the sample pair c0 at +v and c1 at -v with weights wa, wb (sector k at -v is
     *  sector k+4 at +v: slot s of a group takes slot (s + 2) mod 4 of the opposite sample). */
    void addPair(const float wa[4], const float wb[4], const osg::Vec4f& c0, const osg::Vec4f& c1)
    {
        const float* w[2] = {wa, wb};
        for (int g = 0; g < 2; ++g)
            for (int s = 0; s < 4; ++s)
            {
                const float w0 = w[g][s], w1 = w[g][(s + 2) & 3];
                W[g][s] += w0 + w1;
                for (int c = 0; c < 3; ++c)
                {
                    S[g][c][s] += w0 * c0[c] + w1 * c1[c];
                    SS[g][c][s] += w0 * (c0[c] * c0[c]) + w1 * (c1[c] * c1[c]);
                }
            }
    }
};
} // namespace

FilterImage AnisotropicKuwaharaFilter::downsample(const FilterImage& image, const ImageBorder& border)
{
    const int w = std::max(1, (image.width() + 1) / 2), h = std::max(1, (image.height() + 1) / 2);
    FilterImage out(w, h);
    const float k[4] = {0.125f, 0.375f, 0.375f, 0.125f};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            osg::Vec4f s(0, 0, 0, 0);
            for (int b = 0; b < 4; ++b)
            {
                osg::Vec4f row(0, 0, 0, 0);
                for (int a = 0; a < 4; ++a)
                    row += image.fetch(2 * x + a - 1, 2 * y + b - 1, border) * k[a];
                s += row * k[b];
            }
            out.set(x, y, s);
        }
    return out;
}

osg::Vec4f AnisotropicKuwaharaFilter::filterTexel(const FilterImage& image, int x, int y,
                                                  const osg::Vec3f& tensor, const ImageBorder& border) const
{
    const AkfParams P = paramsOf(_radius, _sharpness, _alpha, _rho, _levels, _threshold);
    const osg::Vec4f flow = StructureTensor::flowOf(tensor[0], tensor[1], tensor[2]);
    const float c = flow[0], s = flow[1], A = flow[2];
    const float a = P.r * std::clamp((P.alpha + A) / P.alpha, 0.1f, 2.0f);
    const float b = P.r * std::clamp(P.alpha / (P.alpha + A), 0.1f, 2.0f);
    const float ia = 1.0f / a, ib = 1.0f / b;
    // |v|^2 = Pq i^2 + 2 Q i j + R j^2 with det(Pq, Q; Q, R) = 1 / (a b)^2.
    const float Pq = c * c * ia * ia + s * s * ib * ib;
    const float Q = c * s * (ia * ia - ib * ib);
    const float det = ia * ia * ib * ib;
    const int maxY = std::min(P.rmax, int(std::floor(std::sqrt(a * a * s * s + b * b * c * c))));

    Sectors acc;
    {
        const osg::Vec4f c0 = image.fetch(x, y, border);
        const float wa[4] = {0.0625f, 0.0625f, 0.0625f, 0.0625f}; // 1/8 per sector, halved:
        acc.addPair(wa, wa, c0, c0);                              // the pair adds c0 twice
    }
    for (int j = 0; j <= maxY; ++j)
    {
        const float D = Pq - float(j * j) * det;
        if (D < 0.0f) continue;
        const float sq = std::sqrt(D);
        int i0 = int(std::ceil((-Q * float(j) - sq) / Pq));
        const int i1 = std::min(P.rmax, int(std::floor((-Q * float(j) + sq) / Pq)));
        i0 = std::max(i0, j == 0 ? 1 : -P.rmax);
        for (int i = i0; i <= i1; ++i)
        {
            const float vx = (c * float(i) + s * float(j)) * ia;
            const float vy = (-s * float(i) + c * float(j)) * ib;
            float wa[4], wb[4];
            sectorWeights(vx, vy, P.zeta, P.eta, wa, wb);
            acc.addPair(wa, wb, image.fetch(x + i, y + j, border), image.fetch(x - i, y - j, border));
        }
    }

    // Sector means, deviations and weights.
    float mean[2][3][4], sigma[2][4], xk[2][4];
    float xmin = 1e30f;
    for (int g = 0; g < 2; ++g)
        for (int k = 0; k < 4; ++k)
        {
            sigma[g][k] = 0.0f;
            for (int ch = 0; ch < 3; ++ch)
            {
                const float m = acc.S[g][ch][k] / acc.W[g][k];
                mean[g][ch][k] = m;
                sigma[g][k] += std::sqrt(std::fabs(acc.SS[g][ch][k] / acc.W[g][k] - m * m));
            }
            xk[g][k] = std::max(255.0f * sigma[g][k], P.h);
            xmin = std::min(xmin, xk[g][k]);
        }
    const float scale = std::max(xmin, 1.0f);
    const float base = std::pow(scale, -P.q);
    osg::Vec3f o(0, 0, 0);
    float wsum = 0.0f, sbar = 0.0f;
    for (int g = 0; g < 2; ++g)
        for (int k = 0; k < 4; ++k)
        {
            const float al = 1.0f / (base + std::pow(xk[g][k] / scale, P.q));
            o += osg::Vec3f(mean[g][0][k], mean[g][1][k], mean[g][2][k]) * al;
            wsum += al;
            sbar += al * sigma[g][k];
        }
    o /= wsum;
    return osg::Vec4f(o, sbar / wsum);
}

namespace
{
/** The tensor normalized to trace 1 (isotropic where the trace is 0). */
osg::Vec3f normalizedTensor(const float* t)
{
    const float tr = t[0] + t[2];
    if (!(tr > 0.0f)) return osg::Vec3f(0.5f, 0.0f, 0.5f);
    return osg::Vec3f(t[0], t[1], t[2]) / tr;
}

float anisotropyOf(const osg::Vec3f& J)
{
    return StructureTensor::flowOf(J[0], J[1], J[2])[2];
}
} // namespace

FilterImage AnisotropicKuwaharaFilter::apply(const FilterImage& input, const ImageBorder& border) const
{
    FilterImage out(input.width(), input.height());
    if (input.empty()) return out;
    const AkfParams P = paramsOf(_radius, _sharpness, _alpha, _rho, _levels, _threshold);
    if (P.levels == 1)
    {
        const FilterImage tensor = StructureTensor::smoothedTensor(input, P.rho, border);
        for (int y = 0; y < input.height(); ++y)
            for (int x = 0; x < input.width(); ++x)
            {
                const float* t = tensor.texel(x, y);
                const osg::Vec4f o = filterTexel(input, x, y, osg::Vec3f(t[0], t[1], t[2]), border);
                out.set(x, y, osg::Vec4f(o[0], o[1], o[2], input.get(x, y)[3]));
            }
        return out;
    }

    std::vector<FilterImage> pyramid{input};
    for (int l = 1; l < P.levels; ++l)
        pyramid.push_back(downsample(pyramid.back(), border));
    FilterImage coarseTensor, coarseResult;
    for (int l = P.levels - 1; l >= 0; --l)
    {
        const FilterImage& I = pyramid[std::size_t(l)];
        const FilterImage J = StructureTensor::smoothedTensor(I, P.rho, border);
        FilterImage prop(I.width(), I.height()), result(I.width(), I.height());
        for (int y = 0; y < I.height(); ++y)
            for (int x = 0; x < I.width(); ++x)
            {
                osg::Vec3f Jn = normalizedTensor(J.texel(x, y));
                if (l < P.levels - 1)
                {
                    const osg::Vec4f cs = coarseTensor.sampleBilinear((float(x) + 0.5f) * 0.5f,
                                                                      (float(y) + 0.5f) * 0.5f, border);
                    const osg::Vec3f C(cs[0], cs[1], cs[2]);
                    const float Al = anisotropyOf(Jn), Ac = anisotropyOf(C);
                    if (Al + Ac > 1e-6f) Jn = (Jn * Al + C * Ac) / (Al + Ac);
                }
                prop.set(x, y, osg::Vec4f(Jn, 0.0f));
                const osg::Vec4f o = filterTexel(I, x, y, Jn, border);
                osg::Vec3f rgb(o[0], o[1], o[2]);
                if (l < P.levels - 1)
                {
                    const osg::Vec4f u = coarseResult.sampleBilinear((float(x) + 0.5f) * 0.5f,
                                                                     (float(y) + 0.5f) * 0.5f, border);
                    const osg::Vec3f d = osg::Vec3f(u[0], u[1], u[2]) - rgb;
                    const float sb = std::max(o[3], 1.0f / 255.0f);
                    const float beta = std::exp(-(d * d) / (2.0f * sb * sb));
                    rgb += d * beta;
                }
                result.set(x, y, osg::Vec4f(rgb, l == 0 ? I.get(x, y)[3] : 1.0f));
            }
        coarseTensor = prop;
        coarseResult = result;
    }
    return coarseResult;
}

int AnisotropicKuwaharaFilter::dependencyRadius() const
{
    const AkfParams P = paramsOf(_radius, _sharpness, _alpha, _rho, _levels, _threshold);
    if (P.levels > 1) return -1;
    return ImageFilter::dependencyRadius();
}

std::vector<GpuFilterPass> AnisotropicKuwaharaFilter::gpuPasses() const
{
    const AkfParams P = paramsOf(_radius, _sharpness, _alpha, _rho, _levels, _threshold);
    const std::vector<std::pair<std::string, std::string>> common = {
        {"LOA_AKF_RADIUS", glslFloat(P.r)}, {"LOA_AKF_RMAX", std::to_string(P.rmax)},
        {"LOA_AKF_Q", glslFloat(P.q)},      {"LOA_AKF_ALPHA", glslFloat(P.alpha)},
        {"LOA_AKF_H", glslFloat(P.h)},      {"LOA_AKF_ZETA", glslFloat(P.zeta)},
        {"LOA_AKF_ETA", glslFloat(P.eta)}};
    // The level is a uniform, so that the levels share programs (llvmpipe compiles each
    // program in about half a second).
    auto pass = [&](AkfStage stage, int level, std::vector<int> inputs, int radius)
    {
        GpuFilterPass p;
        p.shader = "loa_filter_akf.comp.glsl";
        p.defines = common;
        p.defines.push_back({"LOA_AKF_STAGE", std::to_string(int(stage))});
        p.defines.push_back({"LOA_AKF_BASE", level == 0 && stage != STAGE_DOWN ? "1" : "0"});
        p.uniforms = {GpuUniform::integer("loa_akfLevel", level)};
        p.inputs = std::move(inputs);
        p.radius = radius;
        return p;
    };
    std::vector<GpuFilterPass> passes;
    if (P.levels == 1)
    {
        passes = StructureTensor::tensorPasses(P.rho, -1, 0);
        const int tensor = int(passes.size()) - 1;
        passes.push_back(pass(STAGE_FILTER, 0, {-1, tensor}, P.rmax));
        return passes;
    }

    // Pyramid: image[l] = the pass holding level l (-1: the input).
    std::vector<int> image{-1};
    for (int l = 1; l < P.levels; ++l)
    {
        passes.push_back(pass(STAGE_DOWN, l, {image.back()}, 2));
        image.push_back(int(passes.size()) - 1);
    }
    // Per level: Sobel, Gaussian x, then Gaussian y with the propagation merged in (one pass
    // less per level; every pass costs llvmpipe its tiles' dispatch even where it has nothing
    // to do), and the filter. rho = 0: Sobel, then the propagation on its own.
    const std::vector<float> gw = GaussianFilter::weightsFor(P.rho);
    const int gr = int(gw.size()) - 1;
    int prop = -1, result = -1;
    for (int l = P.levels - 1; l >= 0; --l)
    {
        passes.push_back(pass(STAGE_SOBEL, l, {image[std::size_t(l)]}, 1));
        int tensor = int(passes.size()) - 1;
        std::vector<int> in;
        if (gr > 0)
        {
            GpuFilterPass bx = pass(STAGE_BLURX, l, {tensor}, gr);
            bx.defines.push_back({"LOA_RADIUS", std::to_string(gr)});
            bx.uniforms.push_back(GpuUniform::array("loa_weights", gw));
            passes.push_back(bx);
            in.push_back(int(passes.size()) - 1);
        }
        else
            in.push_back(tensor);
        if (prop >= 0) in.push_back(prop);
        GpuFilterPass pp = pass(gr > 0 ? STAGE_BLURY : STAGE_PROPAGATE, l, in, std::max(gr, 1));
        if (gr > 0)
        {
            pp.defines.push_back({"LOA_RADIUS", std::to_string(gr)});
            pp.uniforms.push_back(GpuUniform::array("loa_weights", gw));
        }
        pp.defines.push_back({"LOA_AKF_COARSE", prop >= 0 ? "1" : "0"});
        passes.push_back(pp);
        prop = int(passes.size()) - 1;
        std::vector<int> fin{image[std::size_t(l)], prop};
        if (result >= 0) fin.push_back(result);
        GpuFilterPass f = pass(STAGE_FILTER, l, fin, P.rmax);
        f.defines.push_back({"LOA_AKF_COARSE", result >= 0 ? "1" : "0"});
        passes.push_back(f);
        result = int(passes.size()) - 1;
    }
    return passes;
}

std::vector<FilterParameter> AnisotropicKuwaharaFilter::parameters()
{
    auto make = [](const char* name, const char* description, double lo, double hi, bool integer)
    {
        FilterParameter p;
        p.name = name;
        p.description = description;
        p.minimum = lo;
        p.maximum = hi;
        p.integer = integer;
        return p;
    };
    FilterParameter r = make("radius", "filter radius r, texels (ellipse semi-axes r/2 .. 2r)", 1, 12, false);
    r.get = [this] { return double(_radius); };
    r.set = [this](double v) { _radius = float(v); };
    FilterParameter q = make("q", "sharpness of the sector weighting", 1, 16, false);
    q.get = [this] { return double(_sharpness); };
    q.set = [this](double v) { _sharpness = float(v); };
    FilterParameter al = make("alpha", "eccentricity parameter (small: elongated ellipses)", 0.05, 10, false);
    al.get = [this] { return double(_alpha); };
    al.set = [this](double v) { _alpha = float(v); };
    FilterParameter rho = make("rho", "structure tensor smoothing sigma, texels", 0, 8, false);
    rho.get = [this] { return double(_rho); };
    rho.set = [this](double v) { _rho = float(v); };
    FilterParameter n = make("levels", "pyramid levels N (1: single scale)", 1, 6, true);
    n.get = [this] { return double(_levels); };
    n.set = [this](double v) { _levels = int(v); };
    FilterParameter h =
        make("threshold", "sector deviation threshold h, 8-bit units (0: none)", 0, 64, false);
    h.get = [this] { return double(_threshold); };
    h.set = [this](double v) { _threshold = float(v); };
    return {r, q, al, rho, n, h};
}

} // namespace osgLoA
