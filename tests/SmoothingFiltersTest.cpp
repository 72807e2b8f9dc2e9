// The edge-preserving smoothing filters of paper 000 (osgLoA issue 6): bilateral, guided, domain transform
// (RF), L0 gradient minimization and soft colour quantization. CPU references only: hand-computed values on
// tiny images, invariants (constant images, alpha), the wrap modes as FilterImage::fetch defines them,
// parameter validation, the filters' documented failure regimes, and write-read-write round trips in .osgt
// and .osgb. GPU: SmoothingFiltersGLTest; OpenCV: SmoothingFiltersOpenCVTest.
#include "support/TestSupport.h"

#include <osgLoA/filtering/BilateralFilter>
#include <osgLoA/filtering/ColorQuantizationFilter>
#include <osgLoA/filtering/DomainTransformFilter>
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/FlowBilateralFilter>
#include <osgLoA/filtering/GuidedFilter>
#include <osgLoA/filtering/L0Smoothing>

#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <random>
#include <set>
#include <sstream>

using namespace osgLoA;

namespace
{
const double kPi = 3.14159265358979323846;
const WrapMode kModes[3] = {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror};

/** Random 8-bit colours (alpha random too, to see it pass through). */
FilterImage noise(int w, int h, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> d(0, 255);
    FilterImage img(w, h);
    for (float& v : img.data())
        v = float(d(rng)) / 255.0f;
    return img;
}

/** A smooth colour image with a few edges (for filters whose behaviour on noise is degenerate). */
FilterImage pattern(int w, int h, unsigned seed)
{
    FilterImage img = noise(w, h, seed);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            float* p = img.texel(x, y);
            const float base = (x * 3 + y * 2) % 17 < 8 ? 0.2f : 0.8f;
            for (int c = 0; c < 3; ++c)
                p[c] = std::round((base + 0.1f * (p[c] - 0.5f) + 0.05f * c) * 255.0f) / 255.0f;
        }
    return img;
}

FilterImage grey(const std::vector<float>& values, int w, int h)
{
    FilterImage img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const float v = values[std::size_t(y * w + x)];
            img.set(x, y, osg::Vec4f(v, v, v, 1.0f));
        }
    return img;
}

FilterImage crop(const FilterImage& img, int x0, int y0, int w, int h)
{
    FilterImage out(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            out.set(x, y, img.get(x0 + x, y0 + y));
    return out;
}

/** The image extended to (w + 2 pad) x (h + 2 pad) by a wrap mode (pad = w, h: the 3x3 tiling for repeat). */
FilterImage extend(const FilterImage& img, int padX, int padY, WrapMode mode)
{
    FilterImage out(img.width() + 2 * padX, img.height() + 2 * padY);
    for (int y = 0; y < out.height(); ++y)
        for (int x = 0; x < out.width(); ++x)
            out.set(x, y, img.fetch(x - padX, y - padY, ImageBorder(mode, mode)));
    return out;
}

/** The image and its reflections, 2w x 2h (the period of the mirrored extension). */
FilterImage mirrorTile(const FilterImage& img)
{
    FilterImage out(2 * img.width(), 2 * img.height());
    for (int y = 0; y < out.height(); ++y)
        for (int x = 0; x < out.width(); ++x)
            out.set(x, y, img.fetch(x, y, ImageBorder(WrapMode::Mirror, WrapMode::Mirror)));
    return out;
}

float maxDiff(const FilterImage& a, const FilterImage& b, bool alpha = false)
{
    EXPECT_EQ(a.width(), b.width());
    EXPECT_EQ(a.height(), b.height());
    return FilterImage::maxAbsDifference(a, b, alpha);
}

std::string fileBytes(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::vector<osg::ref_ptr<ImageFilter>> allFilters()
{
    return {new BilateralFilter, new GuidedFilter, new DomainTransformFilter, new L0Smoothing,
            new ColorQuantizationFilter};
}

/** Filters with small parameters, for tiny images. */
osg::ref_ptr<ImageFilter> small(const std::string& spec)
{
    return FilterRegistry::create(spec);
}

template <class T> osg::ref_ptr<T> make()
{
    return new T;
}

double seconds(const std::function<void()>& f)
{
    const auto t0 = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
} // namespace

// ---------------------------------------------------------------------------------------------
// Registry, parameters, validation

TEST(SmoothingFiltersTest, RegistryCreatesEveryFilterAndTheCanonicalStringRoundTrips)
{
    const std::vector<std::string> names = FilterRegistry::names();
    for (const char* n : {"bilateral", "guided", "domain_transform", "l0", "quantize"})
    {
        EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n;
        EXPECT_FALSE(FilterRegistry::description(n).empty()) << n;
        osg::ref_ptr<ImageFilter> f = FilterRegistry::create(n);
        ASSERT_TRUE(f.valid()) << n;
        EXPECT_EQ(f->filterName(), n);
        // The canonical form names every parameter and creates an equal filter.
        const std::string canonical = f->getParameterString();
        EXPECT_EQ(FilterRegistry::create(canonical)->getParameterString(), canonical);
    }
    EXPECT_EQ(FilterRegistry::create("bilateral")->getParameterString(),
              "bilateral:sigma_d=3,sigma_r=0.1,radius=0,color_space=rgb,range_norm=l2");
    EXPECT_EQ(FilterRegistry::create("guided")->getParameterString(), "guided:radius=4,eps=0.01");
    EXPECT_EQ(FilterRegistry::create("domain_transform")->getParameterString(),
              "domain_transform:sigma_s=30,sigma_r=0.25,iterations=3");
    EXPECT_EQ(FilterRegistry::create("l0")->getParameterString(),
              "l0:lambda=0.02,kappa=2,beta_max=100000");
    EXPECT_EQ(FilterRegistry::create("quantize")->getParameterString(), "quantize:levels=8,phi_q=3");

    osg::ref_ptr<ImageFilter> b =
        FilterRegistry::create("bilateral:sigma_d=2,color_space=lab,range_norm=l1,radius=5");
    const BilateralFilter* bf = dynamic_cast<const BilateralFilter*>(b.get());
    ASSERT_TRUE(bf);
    EXPECT_FLOAT_EQ(bf->getSigmaD(), 2.0f);
    EXPECT_EQ(bf->getColorSpace(), BilateralFilter::LAB);
    EXPECT_EQ(bf->getRangeNorm(), BilateralFilter::L1);
    EXPECT_EQ(bf->getRadius(), 5);
    EXPECT_EQ(bf->effectiveRadius(), 5);
    EXPECT_EQ(make<BilateralFilter>()->effectiveRadius(), 6); // ceil(2 * 3)

    // Interactivity and GPU passes.
    EXPECT_FALSE(make<L0Smoothing>()->isInteractive());
    EXPECT_FALSE(make<L0Smoothing>()->hasGpuImplementation());
    EXPECT_EQ(make<L0Smoothing>()->dependencyRadius(), -1);
    EXPECT_EQ(make<DomainTransformFilter>()->dependencyRadius(), -1);
    EXPECT_EQ(make<DomainTransformFilter>()->gpuPasses().size(), 6u);
    EXPECT_EQ(make<BilateralFilter>()->dependencyRadius(), 6);
    EXPECT_EQ(make<GuidedFilter>()->gpuPasses().size(), 16u);
    EXPECT_EQ(make<GuidedFilter>()->dependencyRadius(),
              16); // four box passes of radius 4
    EXPECT_EQ(make<ColorQuantizationFilter>()->dependencyRadius(), 0);
    for (const char* n : {"bilateral", "guided", "domain_transform", "quantize"})
        EXPECT_TRUE(FilterRegistry::create(n)->isInteractive()) << n;
}

TEST(SmoothingFiltersTest, BadParametersAreRefusedWithTheirRange)
{
    auto message = [](const std::function<void()>& f)
    {
        try
        {
            f();
        }
        catch (const std::invalid_argument& e)
        {
            return std::string(e.what());
        }
        return std::string("no exception");
    };
    EXPECT_EQ(message([] { FilterRegistry::create("bilateral:sigma_r=0"); }),
              "bilateral: parameter sigma_r = 0 is not a number in [0.001, 100]");
    EXPECT_EQ(message([] { FilterRegistry::create("bilateral:color_space=hsv"); }),
              "bilateral: parameter color_space = 'hsv' is not one of rgb lab");
    EXPECT_NE(
        message([] { FilterRegistry::create("guided:radius=2.5"); }).find("is not an integer in [0, 32]"),
        std::string::npos);
    EXPECT_EQ(message([] { FilterRegistry::create("guided:eps=2"); }),
              "guided: parameter eps = 2 is not a number in [1e-06, 1]");
    EXPECT_EQ(message([] { FilterRegistry::create("domain_transform:iterations=0"); }),
              "domain_transform: parameter iterations = 0 is not an integer in [1, 10]");
    EXPECT_EQ(message([] { FilterRegistry::create("l0:kappa=1"); }),
              "l0: parameter kappa = 1 is not a number in [1.1, 100]");
    EXPECT_EQ(message([] { FilterRegistry::create("quantize:levels=1"); }),
              "quantize: parameter levels = 1 is not an integer in [2, 64]");
    EXPECT_NE(message([] { FilterRegistry::create("l0:sigma=1"); }).find("unknown parameter 'sigma'"),
              std::string::npos);

    // Values set directly (or read from a file) are checked when the filter runs.
    const FilterImage img(4, 4, osg::Vec4f(0.5f, 0.5f, 0.5f, 1));
    const ImageBorder border;
    osg::ref_ptr<BilateralFilter> b = new BilateralFilter;
    b->setSigmaR(-1);
    EXPECT_NE(message([&] { b->apply(img, border); }).find("sigma_r"), std::string::npos);
    EXPECT_NE(message([&] { b->gpuPasses(); }).find("sigma_r"), std::string::npos);
    osg::ref_ptr<GuidedFilter> g = new GuidedFilter;
    g->setEps(0);
    EXPECT_NE(message([&] { g->apply(img, border); }).find("eps"), std::string::npos);
    osg::ref_ptr<DomainTransformFilter> d = new DomainTransformFilter;
    d->setSigmaS(std::nanf(""));
    EXPECT_NE(message([&] { d->apply(img, border); }).find("sigma_s"), std::string::npos);
    osg::ref_ptr<L0Smoothing> l = new L0Smoothing;
    l->setKappa(1.0f);
    EXPECT_NE(message([&] { l->apply(img, border); }).find("kappa"), std::string::npos);
    osg::ref_ptr<ColorQuantizationFilter> q = new ColorQuantizationFilter;
    q->setLevels(0);
    EXPECT_NE(message([&] { q->apply(img, border); }).find("levels"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// Invariants

TEST(SmoothingFiltersTest, ConstantImagesStayConstantAndAlphaPassesThrough)
{
    const osg::Vec4f colour(0.2f, 0.6f, 0.9f, 1.0f);
    for (osg::ref_ptr<ImageFilter> f : allFilters())
        for (WrapMode mode : kModes)
        {
            if (f->filterName() == "quantize") continue; // quantization changes a constant: below
            FilterImage img(9, 7, colour);
            const FilterImage out = f->apply(img, ImageBorder(mode, mode));
            EXPECT_LT(maxDiff(out, img, true), 2e-6f) << f->filterName() << " " << ImageBorder::name(mode);
        }
    // Quantization maps a constant to a constant.
    const FilterImage q = make<ColorQuantizationFilter>()->apply(FilterImage(5, 5, colour), ImageBorder());
    EXPECT_LT(maxDiff(q, FilterImage(5, 5, q.get(0, 0)), true), 1e-7f);

    // Alpha passes through unchanged.
    const FilterImage n = noise(10, 8, 3);
    for (osg::ref_ptr<ImageFilter> f : allFilters())
    {
        const FilterImage out = f->apply(n, ImageBorder());
        for (int y = 0; y < n.height(); ++y)
            for (int x = 0; x < n.width(); ++x)
                ASSERT_EQ(out.texel(x, y)[3], n.texel(x, y)[3]) << f->filterName();
    }
}

// ---------------------------------------------------------------------------------------------
// Wrap modes: a filter reads past the border as FilterImage::fetch does.

TEST(SmoothingFiltersTest, LocalFiltersReadPastTheBorderAsTheWrapModesSay)
{
    const FilterImage img = pattern(13, 11, 7);
    const std::vector<std::string> specs = {"bilateral:sigma_d=1.5,sigma_r=0.2",
                                            "bilateral:sigma_d=1,sigma_r=5,color_space=lab,radius=4",
                                            "guided:radius=2,eps=0.004", "quantize:levels=5,phi_q=0.5"};
    for (const std::string& spec : specs)
    {
        osg::ref_ptr<ImageFilter> f = small(spec);
        // Repeat: the centre of the filtered 3x3 tiling (any border mode there).
        const FilterImage repeat = f->apply(img, ImageBorder(WrapMode::Repeat, WrapMode::Repeat));
        const FilterImage tiled = f->apply(extend(img, 13, 11, WrapMode::Repeat), ImageBorder());
        EXPECT_LT(maxDiff(repeat, crop(tiled, 13, 11, 13, 11)), 2e-6f) << spec;
        // Mirror: the first quadrant of the mirrored 2x2 tiling filtered with repeat.
        const FilterImage mirror = f->apply(img, ImageBorder(WrapMode::Mirror, WrapMode::Mirror));
        const FilterImage mirrored =
            f->apply(mirrorTile(img), ImageBorder(WrapMode::Repeat, WrapMode::Repeat));
        EXPECT_LT(maxDiff(mirror, crop(mirrored, 0, 0, 13, 11)), 2e-6f) << spec;
        // Clamp: the centre of the image padded by repeating the edge texels. (The guided filter's second box
        // pass reads the per-window coefficients clamped too, as the GPU passes read an earlier pass's
        // output, which differs from the coefficients of windows centred outside the image;
        // GuidedFilterMatchesTheOneDimensionalFormulaOnGrey checks its clamp. Repeat and mirror are the same
        // either way: the windows are symmetric.)
        const FilterImage clamp = f->apply(img, ImageBorder(WrapMode::Clamp, WrapMode::Clamp));
        if (spec.rfind("guided", 0) != 0)
        {
            const FilterImage padded = f->apply(extend(img, 12, 12, WrapMode::Clamp), ImageBorder());
            EXPECT_LT(maxDiff(clamp, crop(padded, 12, 12, 13, 11)), 2e-6f) << spec;
        }
        // The axes follow their own modes: repeat in s, mirror in t.
        const FilterImage mixed = f->apply(img, ImageBorder(WrapMode::Repeat, WrapMode::Mirror));
        FilterImage mixedExtension(3 * 13, 2 * 11);
        for (int y = 0; y < mixedExtension.height(); ++y)
            for (int x = 0; x < mixedExtension.width(); ++x)
                mixedExtension.set(x, y,
                                   img.fetch(x - 13, y, ImageBorder(WrapMode::Repeat, WrapMode::Mirror)));
        const FilterImage mixedOut =
            f->apply(mixedExtension, ImageBorder(WrapMode::Repeat, WrapMode::Repeat));
        EXPECT_LT(maxDiff(mixed, crop(mixedOut, 13, 0, 13, 11)), 2e-6f) << spec;
        // And the modes do differ at the border.
        if (spec.rfind("quantize", 0) != 0)
        {
            EXPECT_GT(maxDiff(repeat, clamp), 1e-3f) << spec;
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Bilateral

TEST(SmoothingFiltersTest, BilateralMatchesHandComputedWeights)
{
    // A grey 3x3 image: 1 in the centre, 0 elsewhere; radius 1 (the disk: centre and 4 neighbours), sigma_d =
    // sigma_r = 1, clamp.
    osg::ref_ptr<BilateralFilter> f = new BilateralFilter;
    f->setSigmaD(1);
    f->setSigmaR(1);
    f->setRadius(1);
    const FilterImage img = grey({0, 0, 0, 0, 1, 0, 0, 0, 0}, 3, 3);
    const FilterImage out = f->apply(img, ImageBorder());
    const double es = std::exp(-0.5); // spatial weight of a neighbour
    // l2: the distance^2 between grey 0 and grey 1 is 3 (three channels).
    const double er = std::exp(-1.5);
    EXPECT_NEAR(out.get(1, 1)[0], 1.0 / (1.0 + 4 * es * er), 1e-6);
    // Edge texel (1, 0): itself, (0,0), (2,0), (1,-1) -> (1,0) by clamp, all 0; (1,1) = 1.
    EXPECT_NEAR(out.get(1, 0)[0], es * er / (1.0 + 3 * es + es * er), 1e-6);
    EXPECT_NEAR(out.get(0, 0)[0], 0.0,
                1e-7); // the diagonal centre is outside the disk
    // l1: the distance is 3, squared 9.
    f->setRangeNorm(BilateralFilter::L1);
    const FilterImage outL1 = f->apply(img, ImageBorder());
    EXPECT_NEAR(outL1.get(1, 1)[0], 1.0 / (1.0 + 4 * es * std::exp(-4.5)), 1e-6);
    // On grey images, l1 distances are sqrt(3) times the l2 ones: l1 with sigma_r sqrt(3) is l2.
    const FilterImage g =
        grey({0.1f, 0.5f, 0.3f, 0.9f, 0.2f, 0.7f, 0.4f, 0.8f, 0.6f, 0.0f, 1.0f, 0.35f}, 4, 3);
    f->setSigmaR(0.2f * std::sqrt(3.0f));
    const FilterImage viaL1 = f->apply(g, ImageBorder());
    f->setRangeNorm(BilateralFilter::L2);
    f->setSigmaR(0.2f);
    EXPECT_LT(maxDiff(viaL1, f->apply(g, ImageBorder())), 1e-6f);
}

TEST(SmoothingFiltersTest, BilateralInLabMeasuresRangeInLabUnits)
{
    // Two colours 30 Lab units apart stay apart with sigma_r = 5 (weight e^-18); 1 Lab unit apart they are
    // averaged almost like a Gaussian.
    osg::Vec3f a = FlowBilateralFilter::labToRgb(osg::Vec3f(50, 10, 10));
    osg::Vec3f b = FlowBilateralFilter::labToRgb(osg::Vec3f(50, 10, 40));
    osg::Vec3f c = FlowBilateralFilter::labToRgb(osg::Vec3f(51, 10, 10));
    auto step = [](const osg::Vec3f& left, const osg::Vec3f& right)
    {
        FilterImage img(8, 4);
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 8; ++x)
                img.set(x, y, osg::Vec4f(x < 4 ? left : right, 1));
        return img;
    };
    osg::ref_ptr<ImageFilter> f = small("bilateral:sigma_d=2,sigma_r=5,color_space=lab");
    const FilterImage far = step(a, b);
    EXPECT_LT(maxDiff(f->apply(far, ImageBorder()), far), 1e-5f);
    const FilterImage nearStep = step(a, c);
    const FilterImage out = f->apply(nearStep, ImageBorder());
    const float lLeft =
        FlowBilateralFilter::rgbToLab(osg::Vec3f(out.get(3, 1)[0], out.get(3, 1)[1], out.get(3, 1)[2]))[0];
    EXPECT_GT(lLeft, 50.3f); // pulled towards 51 across the edge
    EXPECT_LT(lLeft, 50.7f);
}

TEST(SmoothingFiltersTest, BilateralFailureRegimesBlurHighContrastStepsAndSteepenSoftEdges)
{
    // (1) With sigma_r far above the contrast the range weight is ~1: the filter degenerates to a Gaussian
    // over the disk and a high-contrast step is blurred (the paper: "the bilateral filter may fail when used
    // in high-contrast images", choosing sigma_r is a trade-off).
    std::vector<float> v(16 * 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 16; ++x)
            v[std::size_t(y * 16 + x)] = x < 8 ? 0.0f : 1.0f;
    const FilterImage step = grey(v, 16, 3);
    const FilterImage sharp = small("bilateral:sigma_d=2,sigma_r=0.1")->apply(step, ImageBorder());
    EXPECT_LT(maxDiff(sharp, step),
              1e-6f); // e^(-3/0.02): the step is kept exactly
    const FilterImage blurred = small("bilateral:sigma_d=2,sigma_r=100")->apply(step, ImageBorder());
    // The 1-D profile of the disk-weighted Gaussian at x = 7 (clamp in y, h = 3).
    double num = 0, den = 0;
    for (int j = -4; j <= 4; ++j)
        for (int i = -4; i <= 4; ++i)
            if (i * i + j * j <= 16)
            {
                const double w = std::exp(-(i * i + j * j) / 8.0);
                num += w * (7 + i >= 8 ? 1.0 : 0.0);
                den += w;
            }
    EXPECT_NEAR(blurred.get(7, 1)[0], num / den,
                2e-4); // range weights e^(-3/20000)
    EXPECT_GT(blurred.get(7, 1)[0], 0.25f);

    // (2) Gradient reversal (He et al. 2013 §3.4; Durand and Dorsey 2002): on a soft edge (a 4-texel ramp)
    // the texels on the ramp have few similar neighbours and are pulled towards the flat on their own side,
    // so the filtered edge is STEEPER than the input; boosting the detail layer I - B (here E = B + 5 (I -
    // B)) then reverses the gradient beside the edge. The guided filter (q = mean(a) I + mean(b), a <= 1 per
    // window) barely steepens the same edge and reverses nothing.
    std::vector<float> ramp(32 * 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 32; ++x)
            ramp[std::size_t(y * 32 + x)] = std::min(1.0f, std::max(0.0f, (x - 14) / 4.0f));
    const FilterImage soft = grey(ramp, 32, 3);
    auto maxGradient = [](const FilterImage& img)
    {
        float g = 0;
        for (int x = 1; x < img.width(); ++x)
            g = std::max(g, std::fabs(img.get(x, 1)[0] - img.get(x - 1, 1)[0]));
        return g;
    };
    auto reversals = [&](const FilterImage& base)
    {
        int count = 0;
        for (int x = 1; x < soft.width(); ++x)
        {
            auto boosted = [&](int i)
            { return base.get(i, 1)[0] + 5 * (soft.get(i, 1)[0] - base.get(i, 1)[0]); };
            if ((boosted(x) - boosted(x - 1)) * (soft.get(x, 1)[0] - soft.get(x - 1, 1)[0]) < -1e-6f) ++count;
        }
        return count;
    };
    const FilterImage bilateral = small("bilateral:sigma_d=3,sigma_r=0.3")->apply(soft, ImageBorder());
    EXPECT_NEAR(maxGradient(soft), 0.25f, 1e-6f);
    EXPECT_GT(maxGradient(bilateral), 0.3f) << "the bilateral filter steepens the soft edge";
    EXPECT_GE(reversals(bilateral), 2);
    const FilterImage guided = small("guided:radius=3,eps=0.01")->apply(soft, ImageBorder());
    EXPECT_LT(maxGradient(guided), 0.26f);
    EXPECT_EQ(reversals(guided), 0);
}

// ---------------------------------------------------------------------------------------------
// Guided filter

TEST(SmoothingFiltersTest, GuidedFilterMatchesTheOneDimensionalFormulaOnGrey)
{
    // On a grey image (r = g = b = v) the colour guide's covariance is var * ones(3x3), and (var ones + eps
    // U)^-1 var ones = var / (3 var + eps) ones: the filter is the grey guided filter q = mean(alpha) v +
    // mean(beta), alpha = var / (var + eps / 3), beta = (1 - alpha) mu. With h = 1 and clamp the 3x3 box
    // means are 1-D means over 3 texels.
    const std::vector<float> row = {0.1f, 0.1f, 0.8f, 0.9f, 0.3f, 0.3f, 0.35f};
    const int n = int(row.size());
    const double eps = 0.02, r = 1;
    auto at = [&](const std::vector<double>& a, int i)
    { return a[std::size_t(std::min(n - 1, std::max(0, i)))]; };
    std::vector<double> v(row.begin(), row.end()), alpha(static_cast<std::size_t>(n)),
        beta(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k)
    {
        double mu = 0, m2 = 0;
        for (int i = -1; i <= 1; ++i)
            mu += at(v, k + i) / 3, m2 += at(v, k + i) * at(v, k + i) / 3;
        const double var = m2 - mu * mu;
        alpha[std::size_t(k)] = var / (var + eps / 3);
        beta[std::size_t(k)] = (1 - alpha[std::size_t(k)]) * mu;
    }
    osg::ref_ptr<GuidedFilter> f = new GuidedFilter;
    f->setRadius(int(r));
    f->setEps(float(eps));
    const FilterImage out = f->apply(grey(row, n, 1), ImageBorder());
    for (int k = 0; k < n; ++k)
    {
        const double a = (at(alpha, k - 1) + at(alpha, k) + at(alpha, k + 1)) / 3;
        const double b = (at(beta, k - 1) + at(beta, k) + at(beta, k + 1)) / 3;
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(out.get(k, 0)[c], a * v[std::size_t(k)] + b, 1e-6) << k;
    }
    // Radius 0 is the identity (zero variance, a = 0, b = I).
    f->setRadius(0);
    const FilterImage img = noise(6, 5, 2);
    EXPECT_LT(maxDiff(f->apply(img, ImageBorder()), img), 1e-6f);
}

TEST(SmoothingFiltersTest, GuidedFilterHalosAtStrongEdgesAreConfinedToTwoRadiiAndGrowWithEps)
{
    // A high-contrast step: windows straddling it have variance ~0.25 and a = var / (var + eps) < 1, so both
    // sides leak towards each other ("halos near edges", He et al. 2013 §3.5 and §4: the local linear model
    // cannot fit a window crossing an edge exactly). The leak reaches exactly 2r texels from the edge (a
    // texel's output averages the coefficients of the windows covering it) and grows with eps.
    std::vector<float> v(40 * 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 40; ++x)
            v[std::size_t(y * 40 + x)] = x < 20 ? 0.1f : 0.9f;
    const FilterImage step = grey(v, 40, 3);
    auto leak = [&](float eps, int x)
    {
        osg::ref_ptr<GuidedFilter> f = new GuidedFilter;
        f->setRadius(3);
        f->setEps(eps);
        return std::fabs(f->apply(step, ImageBorder()).get(x, 1)[0] - step.get(x, 1)[0]);
    };
    EXPECT_GT(leak(0.01f, 19), 1e-3f);
    EXPECT_GT(leak(0.01f, 20 + 5),
              1e-6f); // 6 = 2r texels from the last dark texel
    EXPECT_LT(leak(0.01f, 20 + 6), 1e-6f);
    EXPECT_LT(leak(0.01f, 19 - 6), 1e-6f);
    EXPECT_GT(leak(0.1f, 19), 3 * leak(0.01f, 19));
    EXPECT_GT(leak(0.1f, 19), 0.03f);
}

// ---------------------------------------------------------------------------------------------
// Domain transform

namespace
{
/** An independent RF: each recursion runs over its input extended `pad` texels each side by the wrap mode,
 *  starting from the extended line's first sample. */
FilterImage bruteForceRF(const FilterImage& input, float sigmaS, float sigmaR, int iterations, WrapMode mode,
                         int pad)
{
    FilterImage out = input;
    const double ratio = double(sigmaS) / sigmaR;
    for (int it = 1; it <= iterations; ++it)
    {
        const double a =
            std::exp(-std::sqrt(2.0) / DomainTransformFilter::iterationSigma(sigmaS, it, iterations));
        for (int axis = 0; axis < 2; ++axis)
        {
            const int n = axis == 0 ? input.width() : input.height();
            const int lines = axis == 0 ? input.height() : input.width();
            for (int l = 0; l < lines; ++l)
            {
                auto pos = [&](int i) {
                    return axis == 0 ? std::make_pair(wrapIndex(i, n, mode), l)
                                     : std::make_pair(l, wrapIndex(i, n, mode));
                };
                auto weight = [&](int i) { // between i-1 and i
                    const auto p0 = pos(i - 1), p1 = pos(i);
                    double d = 0;
                    for (int c = 0; c < 3; ++c)
                        d += std::fabs(double(input.get(p1.first, p1.second)[c]) -
                                       input.get(p0.first, p0.second)[c]);
                    return std::pow(a, 1.0 + ratio * d);
                };
                std::vector<osg::Vec3d> f(static_cast<std::size_t>(n)), j(static_cast<std::size_t>(n));
                for (int i = 0; i < n; ++i)
                {
                    const auto p = pos(i);
                    const osg::Vec4f v = out.get(p.first, p.second);
                    f[std::size_t(i)] = osg::Vec3d(v[0], v[1], v[2]);
                }
                auto fAt = [&](int i) { return f[std::size_t(wrapIndex(i, n, mode))]; };
                osg::Vec3d acc = fAt(-pad);
                for (int i = -pad + 1; i < n; ++i)
                {
                    const double w = weight(i);
                    acc = fAt(i) * (1 - w) + acc * w;
                    if (i >= 0) j[std::size_t(i)] = acc;
                }
                auto jAt = [&](int i) { return j[std::size_t(wrapIndex(i, n, mode))]; };
                acc = jAt(n - 1 + pad);
                for (int i = n - 2 + pad; i >= 0; --i)
                {
                    const double w = weight(i + 1);
                    acc = jAt(i) * (1 - w) + acc * w;
                    if (i < n)
                    {
                        const auto p = pos(i);
                        float* t = out.texel(p.first, p.second);
                        t[0] = float(acc[0]), t[1] = float(acc[1]), t[2] = float(acc[2]);
                    }
                }
            }
        }
    }
    return out;
}
} // namespace

TEST(SmoothingFiltersTest, DomainTransformMatchesHandComputedRecursion)
{
    // [0, 1] grey, 2x1, one iteration, clamp: sigma_H = sigma_s, a = e^(-sqrt2 / sigma_s), d = 1 + sigma_s /
    // sigma_r * 3, w = a^d. Forward J = [0, 1 - w], backward K = [w (1 - w), 1 - w]; the vertical pass of a
    // 1-texel column changes nothing.
    osg::ref_ptr<DomainTransformFilter> f = new DomainTransformFilter;
    f->setSigmaS(2);
    f->setSigmaR(1);
    f->setIterations(1);
    const double w = std::exp(-std::sqrt(2.0) / 2.0 * (1.0 + 2.0 * 3.0));
    const FilterImage out = f->apply(grey({0, 1}, 2, 1), ImageBorder());
    EXPECT_NEAR(out.get(0, 0)[0], w * (1 - w), 1e-7);
    EXPECT_NEAR(out.get(1, 0)[0], 1 - w, 1e-7);
    // Eq. 14: the iterations' variances add up to sigma_s^2, each half the previous sigma.
    double sum = 0;
    for (int i = 1; i <= 3; ++i)
        sum += std::pow(DomainTransformFilter::iterationSigma(30, i, 3), 2);
    EXPECT_NEAR(sum, 900.0, 1e-9);
    EXPECT_NEAR(DomainTransformFilter::iterationSigma(30, 1, 3),
                2 * DomainTransformFilter::iterationSigma(30, 2, 3), 1e-12);
}

TEST(SmoothingFiltersTest, DomainTransformBordersAreTheRecursionOverTheWrappedLine)
{
    const FilterImage img = pattern(14, 9, 11);
    for (WrapMode mode : kModes)
    {
        osg::ref_ptr<DomainTransformFilter> f = new DomainTransformFilter;
        f->setSigmaS(3);
        f->setSigmaR(0.5f);
        const FilterImage out = f->apply(img, ImageBorder(mode, mode));
        // a <= e^(-sqrt2 / 2.62) = 0.58 per texel: 150 texels of warm-up leave < 1e-30.
        const FilterImage brute = bruteForceRF(img, 3, 0.5f, 3, mode, 150);
        EXPECT_LT(maxDiff(out, brute), 2e-6f) << ImageBorder::name(mode);
    }
    // Repeat is the RF of the infinitely tiled image: the 3x3 tiling gives the same centre, and so, up to the
    // decay of e^(-sqrt2/sigma_H) over one image width, does clamp on the tiling.
    osg::ref_ptr<ImageFilter> f = small("domain_transform:sigma_s=3,sigma_r=0.5");
    const FilterImage repeat = f->apply(img, ImageBorder(WrapMode::Repeat, WrapMode::Repeat));
    const FilterImage tiled = extend(img, 14, 9, WrapMode::Repeat);
    EXPECT_LT(
        maxDiff(repeat, crop(f->apply(tiled, ImageBorder(WrapMode::Repeat, WrapMode::Repeat)), 14, 9, 14, 9)),
        2e-6f);
    EXPECT_LT(maxDiff(repeat, crop(f->apply(tiled, ImageBorder()), 14, 9, 14, 9)), 1e-3f);
    EXPECT_GT(maxDiff(repeat, f->apply(img, ImageBorder())), 1e-3f);
}

TEST(SmoothingFiltersTest, DomainTransformSmoothsWithSigmaSAndStopsAtEdges)
{
    // On a flat line (d = 1) the N iterations are a symmetric low-pass of variance ~sigma_s^2: each RF pass
    // has variance 2a / (1 - a)^2 = sigma_H^2 (1 + O(1/sigma_H^2)). (A weak impulse, so that d stays ~1
    // around it; the RF is a convex combination per output texel but does not conserve mass where d varies.)
    const int n = 161;
    const float amplitude = 1e-4f;
    std::vector<float> impulse(std::size_t(n), 0.0f);
    impulse[80] = amplitude;
    osg::ref_ptr<DomainTransformFilter> f = new DomainTransformFilter;
    f->setSigmaS(8);
    f->setSigmaR(1); // d = 1 + 8 * 3e-4 next to the impulse
    const FilterImage out = f->apply(grey(impulse, n, 1), ImageBorder());
    double mass = 0, mean = 0, var = 0;
    for (int x = 0; x < n; ++x)
        mass += out.get(x, 0)[0] / amplitude, mean += x * out.get(x, 0)[0] / amplitude;
    mean /= mass;
    for (int x = 0; x < n; ++x)
        var += (x - mean) * (x - mean) * out.get(x, 0)[0] / amplitude / mass;
    EXPECT_NEAR(mass, 1.0, 2e-3);
    EXPECT_NEAR(mean, 80.0, 1e-3);
    EXPECT_NEAR(std::sqrt(var), 8.0, 0.4);
    // A step of contrast 1 with sigma_r = 0.05: d = 1 + 160 * 3 at the edge, nothing crosses.
    std::vector<float> v(24, 0.2f);
    for (int x = 12; x < 24; ++x)
        v[std::size_t(x)] = 0.8f;
    const FilterImage step = grey(v, 24, 1);
    EXPECT_LT(maxDiff(small("domain_transform:sigma_s=8,sigma_r=0.05")->apply(step, ImageBorder()), step),
              1e-6f);
}

// ---------------------------------------------------------------------------------------------
// L0 smoothing

TEST(SmoothingFiltersTest, L0DftMatchesTheDefinitionForAnyLength)
{
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int n : {1, 2, 3, 4, 5, 7, 8, 12, 17, 64, 96, 100, 127})
    {
        std::vector<std::complex<double>> x(static_cast<std::size_t>(n));
        for (auto& c : x)
            c = {u(rng), u(rng)};
        std::vector<std::complex<double>> X = x;
        L0Smoothing::dft(X, false);
        double err = 0;
        for (int k = 0; k < n; ++k)
        {
            std::complex<double> s = 0;
            for (int j = 0; j < n; ++j)
                s += x[std::size_t(j)] * std::polar(1.0, -2 * kPi * double((long long)j * k % n) / n);
            err = std::max(err, std::abs(s - X[std::size_t(k)]));
        }
        EXPECT_LT(err, 1e-10 * n) << n;
        L0Smoothing::dft(X, true);
        double back = 0;
        for (int k = 0; k < n; ++k)
            back = std::max(back, std::abs(X[std::size_t(k)] - x[std::size_t(k)]));
        EXPECT_LT(back, 1e-12 * n) << n;
    }
}

TEST(SmoothingFiltersTest, L0FlattensEverythingForLargeLambdaAndKeepsCleanSteps)
{
    // Weak noise (+-0.05): sum_c (h^2 + v^2) <= 6 * 0.1^2 = 0.06 is below lambda / beta = 0.5 at the first
    // iteration, every gradient is removed, and as beta grows the smoothed gradients shrink faster
    // (~1/beta^2) than the threshold (1/beta): S converges to the constant that minimizes sum (S - I)^2, the
    // mean (within 1 / (1 + beta_max D_min)).
    FilterImage n = noise(8, 6, 4);
    for (float& v : n.data())
        v = std::round((0.45f + 0.1f * v) * 255.0f) / 255.0f;
    osg::ref_ptr<L0Smoothing> f = new L0Smoothing;
    f->setLambda(0.1f);
    const FilterImage out = f->apply(n, ImageBorder(WrapMode::Repeat, WrapMode::Repeat));
    for (int c = 0; c < 3; ++c)
    {
        double mean = 0;
        for (std::size_t k = 0; k < n.texelCount(); ++k)
            mean += n.data()[k * 4 + c] / double(n.texelCount());
        for (std::size_t k = 0; k < n.texelCount(); ++k)
            EXPECT_NEAR(out.data()[k * 4 + c], mean, 1e-4) << c;
    }
    // A clean step with small lambda is kept: 2 gradients cost 2 lambda, far less than flattening it would
    // cost in data.
    std::vector<float> v(16 * 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 16; ++x)
            v[std::size_t(y * 16 + x)] = x < 8 ? 0.25f : 0.75f;
    const FilterImage step = grey(v, 16, 4);
    EXPECT_LT(maxDiff(small("l0:lambda=0.01")->apply(step, ImageBorder()), step), 1e-4f);
}

TEST(SmoothingFiltersTest, L0StaircasesARampIntoFlatSteps)
{
    // L0 counts every nonzero gradient, so smooth shading is what it handles worst (Xu et al. 2011 §6; the
    // "staircasing" of L0 and TV methods): a ramp's ends are clipped into flat plateaus, a ramp near the
    // threshold becomes a few flat steps with sharp jumps, and a gentler one disappears (flattened to its
    // mean). The solver's smoothing keeps linear functions, so a steep ramp keeps a linear middle. 64 x 16
    // grey ramps, clamp.
    auto ramp = [](float lo, float hi)
    {
        std::vector<float> v(64 * 16);
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 64; ++x)
                v[std::size_t(y * 64 + x)] =
                    std::round((lo + (hi - lo) * float(x) / 63.0f) * 255.0f) / 255.0f;
        return grey(v, 64, 16);
    };
    auto profile = [](const FilterImage& out, int& jumps, int& flats)
    {
        jumps = flats = 0;
        for (int x = 1; x < out.width(); ++x)
        {
            const float d = out.get(x, 8)[0] - out.get(x - 1, 8)[0];
            EXPECT_GT(d, -1e-4f) << "monotone at " << x;
            if (std::fabs(d) > 1e-3f) ++jumps;
            if (std::fabs(d) < 2e-4f) ++flats;
        }
    };
    int jumps = 0, flats = 0;
    // 0.3 .. 0.7 with lambda = 0.035: a staircase of flat steps.
    const FilterImage steps = small("l0:lambda=0.035")->apply(ramp(0.3f, 0.7f), ImageBorder());
    profile(steps, jumps, flats);
    EXPECT_GE(jumps, 1);
    EXPECT_LE(jumps, 10);
    EXPECT_GE(flats, 48) << "of 63 gradients, most are exactly flat";
    EXPECT_NEAR(steps.get(0, 8)[0], steps.get(15, 8)[0], 1e-3f);
    EXPECT_NEAR(steps.get(48, 8)[0], steps.get(63, 8)[0], 1e-3f);
    EXPECT_LT(steps.get(63, 8)[0] - steps.get(0, 8)[0], 0.2f) << "contrast 0.4 is reduced";
    // lambda = 0.05: the ramp is flattened to its mean.
    const FilterImage flat = small("l0:lambda=0.05")->apply(ramp(0.3f, 0.7f), ImageBorder());
    EXPECT_LT(flat.get(63, 8)[0] - flat.get(0, 8)[0], 0.02f);
    EXPECT_NEAR(flat.get(32, 8)[0], 0.5f, 0.01f);
    // 0 .. 1 with lambda = 0.02: plateaus at the ends, a linear middle.
    const FilterImage clipped = small("l0:lambda=0.02")->apply(ramp(0.0f, 1.0f), ImageBorder());
    EXPECT_GT(clipped.get(0, 8)[0], 0.05f);
    EXPECT_NEAR(clipped.get(0, 8)[0], clipped.get(4, 8)[0], 2e-4f);
    EXPECT_NEAR(clipped.get(32, 8)[0] - clipped.get(31, 8)[0], 1.0f / 63.0f, 2e-3f);
}

TEST(SmoothingFiltersTest, L0BordersArePeriodicForRepeatAndMirroredOtherwise)
{
    const FilterImage img = pattern(12, 10, 9);
    osg::ref_ptr<ImageFilter> f = small("l0:lambda=0.005");
    const ImageBorder repeat(WrapMode::Repeat, WrapMode::Repeat);
    // Repeat: the periodic problem, so the 3x3 tiling (also periodic) has the same solution.
    const FilterImage r = f->apply(img, repeat);
    EXPECT_LT(maxDiff(r, crop(f->apply(extend(img, 12, 10, WrapMode::Repeat), repeat), 12, 10, 12, 10)),
              1e-5f);
    // Mirror and clamp: the periodic problem on the mirrored 2x2 tiling (no gradient across the border); both
    // modes give the same result.
    const FilterImage m = f->apply(img, ImageBorder(WrapMode::Mirror, WrapMode::Mirror));
    EXPECT_LT(maxDiff(m, crop(f->apply(mirrorTile(img), repeat), 0, 0, 12, 10)), 1e-5f);
    EXPECT_LT(maxDiff(m, f->apply(img, ImageBorder(WrapMode::Clamp, WrapMode::Clamp))), 1e-7f);
    EXPECT_GT(maxDiff(m, r), 1e-3f);
}

TEST(SmoothingFiltersTest, L0IsFastEnoughForPrefiltering)
{
    // 128 x 128 (a power of two) and 96 x 80 (Bluestein), timed.
    const FilterImage a = pattern(128, 128, 1), b = pattern(96, 80, 2);
    osg::ref_ptr<ImageFilter> f = small("l0");
    const double tRepeat = seconds([&] { f->apply(a, ImageBorder(WrapMode::Repeat, WrapMode::Repeat)); });
    const double tMirror = seconds([&] { f->apply(a, ImageBorder(WrapMode::Mirror, WrapMode::Mirror)); });
    const double tOdd = seconds([&] { f->apply(b, ImageBorder(WrapMode::Repeat, WrapMode::Repeat)); });
    std::printf("l0 (22 iterations): 128x128 repeat %.3f s, mirror %.3f s; 96x80 repeat %.3f s\n", tRepeat,
                tMirror, tOdd);
    EXPECT_LT(tRepeat, 1.0);
}

// ---------------------------------------------------------------------------------------------
// Colour quantization

TEST(SmoothingFiltersTest, QuantizationFollowsWinnemoellersFormulaAndKeepsChroma)
{
    // Mid grey: L* = 53.389; 10 levels: dq = 10, nearest boundary 50, Q = 50 + 5 tanh(3 * 3.389).
    const float L = FlowBilateralFilter::rgbToLab(osg::Vec3f(0.5f, 0.5f, 0.5f))[0];
    EXPECT_NEAR(ColorQuantizationFilter::quantizeLightness(L, 10, 3.0f),
                50.0 + 5.0 * std::tanh(3.0 * (L - 50.0)), 1e-5);
    EXPECT_NEAR(ColorQuantizationFilter::quantizeLightness(L, 10, 3.0f), 55.0f, 1e-4f);
    EXPECT_NEAR(ColorQuantizationFilter::quantizeLightness(L, 10, 0.1f), 50.0 + 5.0 * std::tanh(0.3389),
                1e-4);
    EXPECT_FLOAT_EQ(ColorQuantizationFilter::quantizeLightness(0.0f, 8, 3.0f), 0.0f);
    EXPECT_NEAR(ColorQuantizationFilter::quantizeLightness(100.0f, 8, 3.0f), 100.0f, 1e-4f);
    // phi_q = 0 is a hard staircase on the bin boundaries.
    EXPECT_FLOAT_EQ(ColorQuantizationFilter::quantizeLightness(53.0f, 4, 0.0f), 50.0f);

    osg::ref_ptr<ColorQuantizationFilter> f = new ColorQuantizationFilter;
    f->setLevels(10);
    // Moderate colours, so that moving L* by up to dq / 2 stays inside the sRGB gamut (labToRgb clamps to
    // it).
    FilterImage n = noise(32, 32, 8);
    for (float& v : n.data())
        v = 0.3f + 0.4f * v;
    const FilterImage out = f->apply(n, ImageBorder());
    std::set<int> plateaus;
    for (std::size_t k = 0; k < n.texelCount(); ++k)
    {
        const float* p = &n.data()[k * 4];
        const float* q = &out.data()[k * 4];
        const osg::Vec3f in = FlowBilateralFilter::rgbToLab(osg::Vec3f(p[0], p[1], p[2]));
        const osg::Vec3f o = FlowBilateralFilter::rgbToLab(osg::Vec3f(q[0], q[1], q[2]));
        ASSERT_NEAR(o[0], ColorQuantizationFilter::quantizeLightness(in[0], 10, 3.0f), 2e-3f);
        ASSERT_NEAR(o[1], in[1], 2e-3f); // chroma kept
        ASSERT_NEAR(o[2], in[2], 2e-3f);
        if (std::fabs(in[0] - 10 * std::round(in[0] / 10)) > 1.5f)
            plateaus.insert(int(std::lround(o[0] * 10)));
    }
    // Away from the boundaries the lightness takes only the bin centres 5, 15, ..., 95.
    for (int p : plateaus)
        EXPECT_EQ((p - 50) % 100, 0) << p / 10.0;
}

// ---------------------------------------------------------------------------------------------
// Serialization

TEST(SmoothingFiltersTest, EveryFilterRoundTripsThroughOsgtAndOsgb)
{
    const std::string dir = loatest::freshDirectory("SmoothingFiltersRoundTrip");
    const std::vector<std::string> specs = {
        "bilateral:sigma_d=2.5,sigma_r=4.25,radius=7,color_space=lab,range_norm=l1",
        "guided:radius=6,eps=0.04", "domain_transform:sigma_s=12.5,sigma_r=0.125,iterations=4",
        "l0:lambda=0.005,kappa=1.5,beta_max=50000", "quantize:levels=12,phi_q=7.5"};
    for (const std::string& spec : specs)
    {
        osg::ref_ptr<ImageFilter> f = FilterRegistry::create(spec);
        for (const char* ext : {"osgt", "osgb"})
        {
            const std::string first = dir + "/" + f->filterName() + "-first." + ext;
            const std::string second = dir + "/" + f->filterName() + "-second." + ext;
            ASSERT_TRUE(osgDB::writeObjectFile(*f, first)) << first;
            osg::ref_ptr<ImageFilter> back =
                dynamic_cast<ImageFilter*>(osgDB::readRefObjectFile(first).get());
            ASSERT_TRUE(back.valid()) << first;
            EXPECT_EQ(back->className(), std::string(f->className()));
            EXPECT_EQ(back->getParameterString(), f->getParameterString()) << ext;
            ASSERT_TRUE(osgDB::writeObjectFile(*back, second));
            EXPECT_EQ(fileBytes(first), fileBytes(second)) << spec << " " << ext;
        }
        // Defaults round-trip too (nothing written for them in .osgt but the class).
        osg::ref_ptr<ImageFilter> plain = FilterRegistry::create(f->filterName());
        const std::string path = dir + "/" + f->filterName() + "-default.osgt";
        ASSERT_TRUE(osgDB::writeObjectFile(*plain, path));
        osg::ref_ptr<ImageFilter> back = dynamic_cast<ImageFilter*>(osgDB::readRefObjectFile(path).get());
        ASSERT_TRUE(back.valid());
        EXPECT_EQ(back->getParameterString(), plain->getParameterString());
    }
    // The text form names the parameters and the enums by name.
    const std::string text = fileBytes(dir + "/bilateral-first.osgt");
    EXPECT_NE(text.find("osgLoA::BilateralFilter"), std::string::npos);
    EXPECT_NE(text.find("ColorSpace LAB"), std::string::npos);
    EXPECT_NE(text.find("RangeNorm L1"), std::string::npos);
    EXPECT_NE(text.find("SigmaR 4.25"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// Timings of the CPU references (printed; the GL test prints the GPU's).

TEST(SmoothingFiltersTest, CpuTimingsAt256)
{
    const FilterImage img = pattern(256, 256, 5);
    const ImageBorder border(WrapMode::Repeat, WrapMode::Repeat);
    for (const char* spec :
         {"bilateral", "bilateral:color_space=lab,sigma_r=5", "guided", "domain_transform", "quantize", "l0"})
    {
        osg::ref_ptr<ImageFilter> f = small(spec);
        const double t = seconds([&] { f->apply(img, border); });
        std::printf("CPU 256x256 %-40s %.3f s\n", f->getParameterString().c_str(), t);
    }
}
