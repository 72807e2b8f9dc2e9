/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/BilateralFilter>
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/FlowBilateralFilter>

#include <cmath>

namespace osgLoA
{

static FilterRegistry::Entry<BilateralFilter> s_registeredBilateralFilter(
    "bilateral",
    "bilateral filter (Tomasi and Manduchi 1998; sigma_d, sigma_r, radius, color_space, range_norm)");

int BilateralFilter::effectiveRadius() const
{
    if (_radius > 0) return _radius;
    return std::max(1, int(std::ceil(2.0f * _sigmaD)));
}

FilterImage BilateralFilter::apply(const FilterImage& input, const ImageBorder& border) const
{
    checkParameters();
    const int w = input.width(), h = input.height();
    if (input.empty()) return input;
    const int r = effectiveRadius();

    // The window: the disk i^2 + j^2 <= r^2, with its spatial weights.
    struct Tap
    {
        int dx, dy;
        float weight;
    };
    std::vector<Tap> taps;
    const double spatial = -0.5 / (double(_sigmaD) * _sigmaD);
    for (int j = -r; j <= r; ++j)
        for (int i = -r; i <= r; ++i)
            if (i * i + j * j <= r * r) taps.push_back({i, j, float(std::exp(spatial * (i * i + j * j)))});
    const float range = float(-0.5 / (double(_sigmaR) * _sigmaR));

    // The values filtered: RGB, or CIELab.
    std::vector<float> src(std::size_t(w) * h * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const float* p = input.texel(x, y);
            osg::Vec3f c(p[0], p[1], p[2]);
            if (_colorSpace == LAB) c = FlowBilateralFilter::rgbToLab(c);
            float* q = &src[(std::size_t(y) * w + x) * 3];
            q[0] = c[0], q[1] = c[1], q[2] = c[2];
        }

    FilterImage out(w, h);
    const bool l1 = _rangeNorm == L1;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const float* c0 = &src[(std::size_t(y) * w + x) * 3];
            const bool inside = x - r >= 0 && x + r < w && y - r >= 0 && y + r < h;
            double s0 = 0, s1 = 0, s2 = 0, ws = 0;
            for (const Tap& t : taps)
            {
                const int sx = inside ? x + t.dx : wrapIndex(x + t.dx, w, border.s);
                const int sy = inside ? y + t.dy : wrapIndex(y + t.dy, h, border.t);
                const float* c = &src[(std::size_t(sy) * w + sx) * 3];
                const float d0 = c[0] - c0[0], d1 = c[1] - c0[1], d2 = c[2] - c0[2];
                float d2sum;
                if (l1)
                {
                    const float d = std::fabs(d0) + std::fabs(d1) + std::fabs(d2);
                    d2sum = d * d;
                }
                else
                    d2sum = d0 * d0 + d1 * d1 + d2 * d2;
                const double wt = double(t.weight) * std::exp(range * d2sum);
                s0 += wt * c[0];
                s1 += wt * c[1];
                s2 += wt * c[2];
                ws += wt;
            }
            osg::Vec3f v(float(s0 / ws), float(s1 / ws), float(s2 / ws));
            if (_colorSpace == LAB) v = FlowBilateralFilter::labToRgb(v);
            out.set(x, y, osg::Vec4f(v, input.texel(x, y)[3]));
        }
    return out;
}

std::vector<GpuFilterPass> BilateralFilter::gpuPasses() const
{
    checkParameters();
    const int r = effectiveRadius();
    const bool lab = _colorSpace == LAB;
    std::vector<GpuFilterPass> passes;
    if (lab)
    {
        GpuFilterPass convert;
        convert.shader = "loa_filter_lab.comp.glsl";
        convert.defines = {{"LOA_LAB_STAGE", "0"}};
        convert.inputs = {-1};
        passes.push_back(convert);
    }
    GpuFilterPass p;
    p.shader = "loa_filter_bilateral.comp.glsl";
    p.defines = {{"LOA_RADIUS", std::to_string(r)}, {"LOA_L1", _rangeNorm == L1 ? "1" : "0"}};
    p.uniforms = {GpuUniform::scalar("loa_spatialCoefficient", float(-0.5 / (double(_sigmaD) * _sigmaD))),
                  GpuUniform::scalar("loa_rangeCoefficient", float(-0.5 / (double(_sigmaR) * _sigmaR)))};
    p.inputs = {lab ? 0 : -1};
    p.radius = r;
    passes.push_back(p);
    if (lab)
    {
        GpuFilterPass back;
        back.shader = "loa_filter_lab.comp.glsl";
        back.defines = {{"LOA_LAB_STAGE", "1"}};
        back.inputs = {1};
        passes.push_back(back);
    }
    return passes;
}

std::vector<FilterParameter> BilateralFilter::parameters()
{
    FilterParameter sd;
    sd.name = "sigma_d";
    sd.description = "spatial standard deviation, texels";
    sd.minimum = 0.1;
    sd.maximum = 32;
    sd.get = [this] { return double(_sigmaD); };
    sd.set = [this](double v) { _sigmaD = float(v); };

    FilterParameter sr;
    sr.name = "sigma_r";
    sr.description = "range standard deviation: RGB units in [0, 1] (color_space=rgb) or Lab units (lab)";
    sr.minimum = 0.001;
    sr.maximum = 100;
    sr.get = [this] { return double(_sigmaR); };
    sr.set = [this](double v) { _sigmaR = float(v); };

    FilterParameter radius;
    radius.name = "radius";
    radius.description = "window radius, texels (disk); 0 = ceil(2 sigma_d)";
    radius.minimum = 0;
    radius.maximum = 64;
    radius.integer = true;
    radius.get = [this] { return double(_radius); };
    radius.set = [this](double v) { _radius = int(v); };

    FilterParameter cs;
    cs.name = "color_space";
    cs.description = "space of the range distance: stored RGB, or CIELab (D65)";
    cs.minimum = 0;
    cs.maximum = 1;
    cs.integer = true;
    cs.choices = {"rgb", "lab"};
    cs.get = [this] { return double(_colorSpace); };
    cs.set = [this](double v) { _colorSpace = ColorSpace(int(v)); };

    FilterParameter norm;
    norm.name = "range_norm";
    norm.description =
        "colour distance: Euclidean (l2) or sum of absolute differences (l1, as cv::bilateralFilter)";
    norm.minimum = 0;
    norm.maximum = 1;
    norm.integer = true;
    norm.choices = {"l2", "l1"};
    norm.get = [this] { return double(_rangeNorm); };
    norm.set = [this](double v) { _rangeNorm = RangeNorm(int(v)); };
    return {sd, sr, radius, cs, norm};
}

} // namespace osgLoA
