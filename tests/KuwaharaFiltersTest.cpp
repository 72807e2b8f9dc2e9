// The Kuwahara-family and shock filters' CPU references (KuwaharaFilter "kuwahara",
// AnisotropicKuwaharaFilter "akf", ShockFilter "shock"): hand-computed values on tiny images, an
// independent naive Kuwahara, edges kept sharp, constants kept constant, wrap modes (filtering
// with a wrap mode equals the centre of filtering the correspondingly padded image), parameter
// validation, registry specifications, serializer round trips, and the known failure regimes
// (classic Kuwahara blocks on a noisy gradient; AKF isotropic where A = 0).
#include <osgLoA/filtering/AnisotropicKuwaharaFilter>
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/GaussianFilter>
#include <osgLoA/filtering/KuwaharaFilter>
#include <osgLoA/filtering/ShockFilter>
#include <osgLoA/filtering/StructureTensor>

#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <cmath>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

using namespace osgLoA;

namespace
{
FilterImage grey(int w, int h, const std::vector<float>& v)
{
    FilterImage img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const float g = v[std::size_t(y * w + x)];
            img.set(x, y, osg::Vec4f(g, g, g, 1.0f));
        }
    return img;
}

/** Deterministic colour noise of standard deviation sigma added to every RGB channel. */
void addNoise(FilterImage& img, float sigma, unsigned seed)
{
    std::mt19937 rng(seed);
    std::normal_distribution<float> n(0.0f, sigma);
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x)
            for (int c = 0; c < 3; ++c)
                img.texel(x, y)[c] += n(rng);
}

/** A random colour image with random alpha. */
FilterImage randomImage(int w, int h, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    FilterImage img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            img.set(x, y, osg::Vec4f(u(rng), u(rng), u(rng), u(rng)));
    return img;
}

/** The naive Kuwahara filter: sector sums by direct loops; returns the chosen sector index in
 *  `choice` when given. Independent of KuwaharaFilter's summed-area tables. */
FilterImage naiveKuwahara(const FilterImage& in, int r, const ImageBorder& border,
                          std::vector<int>* choice = nullptr)
{
    FilterImage out(in.width(), in.height());
    if (choice) choice->assign(in.texelCount(), 0);
    const int dx[4] = {-r, 0, -r, 0}, dy[4] = {-r, -r, 0, 0};
    for (int y = 0; y < in.height(); ++y)
        for (int x = 0; x < in.width(); ++x)
        {
            double best = 1e300;
            osg::Vec3d bestMean;
            int bestK = 0;
            for (int k = 0; k < 4; ++k)
            {
                osg::Vec3d s(0, 0, 0);
                double ss = 0;
                for (int j = 0; j <= r; ++j)
                    for (int i = 0; i <= r; ++i)
                    {
                        const osg::Vec4f c = in.fetch(x + dx[k] + i, y + dy[k] + j, border);
                        s += osg::Vec3d(c[0], c[1], c[2]);
                        ss += double(c[0]) * c[0] + double(c[1]) * c[1] + double(c[2]) * c[2];
                    }
                const double n = double(r + 1) * (r + 1);
                const osg::Vec3d m = s / n;
                const double var = ss / n - m * m;
                if (var < best)
                {
                    best = var;
                    bestMean = m;
                    bestK = k;
                }
            }
            out.set(x, y,
                    osg::Vec4f(float(bestMean[0]), float(bestMean[1]), float(bestMean[2]), in.get(x, y)[3]));
            if (choice) (*choice)[std::size_t(y) * std::size_t(in.width()) + std::size_t(x)] = bestK;
        }
    return out;
}

/** The image padded by `pad` texels on every side, the padding read with the border's modes. */
FilterImage padded(const FilterImage& in, int pad, const ImageBorder& border)
{
    FilterImage out(in.width() + 2 * pad, in.height() + 2 * pad);
    for (int y = 0; y < out.height(); ++y)
        for (int x = 0; x < out.width(); ++x)
            out.set(x, y, in.fetch(x - pad, y - pad, border));
    return out;
}

FilterImage crop(const FilterImage& in, int x0, int y0, int w, int h)
{
    FilterImage out(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            out.set(x, y, in.get(x0 + x, y0 + y));
    return out;
}

/** Filtering with `border` equals the centre of filtering the image padded by `pad` (with those
 *  modes) with any border: the wrap modes are honoured exactly. */
float wrapError(const ImageFilter& f, const FilterImage& img, const ImageBorder& border, int pad)
{
    const FilterImage direct = f.apply(img, border);
    const FilterImage big = f.apply(padded(img, pad, border), ImageBorder(WrapMode::Clamp, WrapMode::Clamp));
    return FilterImage::maxAbsDifference(direct, crop(big, pad, pad, img.width(), img.height()), true);
}

std::string fileBytes(const std::string& path)
{
    std::ifstream f(path, std::ios::binary);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

/** Writes, reads back and writes again; the two files must be identical. */
template <class T> osg::ref_ptr<T> roundTrip(const T& object, const std::string& dir, const std::string& ext)
{
    const std::string first = dir + "/" + object.filterName() + "-first." + ext;
    const std::string second = dir + "/" + object.filterName() + "-second." + ext;
    EXPECT_TRUE(osgDB::writeObjectFile(object, first)) << first;
    osg::ref_ptr<T> back = dynamic_cast<T*>(osgDB::readRefObjectFile(first).get());
    EXPECT_TRUE(back.valid()) << first << " did not read back";
    if (!back) return back;
    EXPECT_TRUE(osgDB::writeObjectFile(*back, second)) << second;
    EXPECT_FALSE(fileBytes(first).empty());
    EXPECT_EQ(fileBytes(first), fileBytes(second)) << object.filterName() << "." << ext;
    return back;
}

/** Mean over rows of column x's red channel, and its standard deviation over rows. */
void columnStats(const FilterImage& img, int x, int y0, int y1, double& mean, double& sd)
{
    double s = 0, ss = 0;
    const int n = y1 - y0;
    for (int y = y0; y < y1; ++y)
    {
        s += img.get(x, y)[0];
        ss += double(img.get(x, y)[0]) * img.get(x, y)[0];
    }
    mean = s / n;
    sd = std::sqrt(std::max(0.0, ss / n - mean * mean));
}

/** Standard deviation of the red channel minus `reference` over the interior (margin m). */
double residualSd(const FilterImage& img, const FilterImage& reference, int m)
{
    double s = 0, ss = 0;
    int n = 0;
    for (int y = m; y < img.height() - m; ++y)
        for (int x = m; x < img.width() - m; ++x)
        {
            const double d = double(img.get(x, y)[0]) - reference.get(x, y)[0];
            s += d;
            ss += d * d;
            ++n;
        }
    const double mean = s / n;
    return std::sqrt(std::max(0.0, ss / n - mean * mean));
}

/** Mean absolute second difference (x and y) of the red channel over the interior: zero on a
 *  linear ramp, large where the output has steps (blocks). */
double roughness(const FilterImage& img, int m)
{
    double s = 0;
    int n = 0;
    for (int y = m; y < img.height() - m; ++y)
        for (int x = m; x < img.width() - m; ++x)
        {
            const double c = img.get(x, y)[0];
            s += std::fabs(img.get(x - 1, y)[0] - 2 * c + img.get(x + 1, y)[0]) +
                 std::fabs(img.get(x, y - 1)[0] - 2 * c + img.get(x, y + 1)[0]);
            ++n;
        }
    return s / n;
}

const ImageBorder kClamp(WrapMode::Clamp, WrapMode::Clamp);
} // namespace

// ---------------------------------------------------------------------------------------------
// Classic Kuwahara

TEST(KuwaharaFilterTest, HandComputedSectorsOnA3x3Image)
{
    // Grey values (dyadic, so every sum is exact):
    //   0    1    1        r = 1: sectors of 2x2 texels around the centre (1, 1):
    //   1/2  1/2  1        Q0 = {0, 1, 1/2, 1/2}   mean 1/2, variance 1/8 per channel
    //   1/2  1/2  0        Q1 = {1, 1, 1/2, 1}     mean 7/8, variance 3/64
    //                      Q2 = {1/2, 1/2, 1/2, 1/2} mean 1/2, variance 0  <- chosen
    //                      Q3 = {1/2, 1, 1/2, 0}   mean 1/2, variance 1/8
    const FilterImage img = grey(3, 3, {0, 1, 1, 0.5f, 0.5f, 1, 0.5f, 0.5f, 0});
    osg::ref_ptr<KuwaharaFilter> f = new KuwaharaFilter;
    f->setRadius(1);
    for (WrapMode m : {WrapMode::Clamp, WrapMode::Repeat, WrapMode::Mirror})
        EXPECT_EQ(f->apply(img, ImageBorder(m, m)).get(1, 1)[0], 0.5f) << ImageBorder::name(m);
    // Corner (0, 0). Clamp and mirror (r = 1 reads index -1 as 0): Q0 = {0, 0, 0, 0}, variance
    // 0, the first sector: 0. Repeat: Q0 = {0, 1/2, 1, 0} (variance 11/64), Q1 = {1/2, 1/2, 0, 1}
    // (1/8), Q2 = {1, 0, 1, 1/2} (11/64), Q3 = {0, 1, 1/2, 1/2} (1/8): Q1 and Q3 tie, the
    // first (Q1, mean 1/2) wins.
    EXPECT_EQ(f->apply(img, kClamp).get(0, 0)[0], 0.0f);
    EXPECT_EQ(f->apply(img, ImageBorder(WrapMode::Mirror, WrapMode::Mirror)).get(0, 0)[0], 0.0f);
    EXPECT_EQ(f->apply(img, ImageBorder(WrapMode::Repeat, WrapMode::Repeat)).get(0, 0)[0], 0.5f);
    // Texel (2, 0), clamp: Q0 reads columns 1..2 of rows -1..0 (row -1 clamps to 0):
    // {1, 1, 1, 1}, variance 0, the first sector: 1.
    EXPECT_EQ(f->apply(img, kClamp).get(2, 0)[0], 1.0f);
}

TEST(KuwaharaFilterTest, MatchesANaiveImplementationForEveryWrapMode)
{
    const FilterImage img = randomImage(17, 13, 7);
    osg::ref_ptr<KuwaharaFilter> f = new KuwaharaFilter;
    for (int r : {1, 2, 3, 5})
        for (WrapMode s : {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror})
            for (WrapMode t : {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror})
            {
                f->setRadius(r);
                const ImageBorder border(s, t);
                // Summed-area tables vs direct sums, both in double: only rounding differs.
                EXPECT_LT(
                    FilterImage::maxAbsDifference(f->apply(img, border), naiveKuwahara(img, r, border), true),
                    1e-6f)
                    << "r=" << r << " " << ImageBorder::name(s) << "/" << ImageBorder::name(t);
            }
}

TEST(KuwaharaFilterTest, EveryOutputIsOneSectorMeanAndStepEdgesStaySharp)
{
    // A vertical and a horizontal step edge: every texel has a sector entirely on its side of
    // the edge (variance 0), so the output equals the input exactly.
    std::vector<float> v(12 * 10), h(12 * 10);
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 12; ++x)
        {
            v[std::size_t(y * 12 + x)] = x < 5 ? 0.25f : 0.75f;
            h[std::size_t(y * 12 + x)] = y < 4 ? 0.125f : 0.875f;
        }
    osg::ref_ptr<KuwaharaFilter> f = new KuwaharaFilter;
    f->setRadius(3);
    for (const std::vector<float>* values : {&v, &h})
    {
        const FilterImage img = grey(12, 10, *values);
        EXPECT_EQ(FilterImage::maxAbsDifference(f->apply(img, kClamp), img, true), 0.0f);
    }
    // A random image: each output texel is the mean of one of its four sectors (the naive
    // implementation's choice), to float rounding.
    const FilterImage rnd = randomImage(15, 11, 3);
    std::vector<int> choice;
    const FilterImage naive = naiveKuwahara(rnd, 2, kClamp, &choice);
    f->setRadius(2);
    EXPECT_LT(FilterImage::maxAbsDifference(f->apply(rnd, kClamp), naive), 1e-6f);
    std::vector<int> used(4, 0);
    for (int k : choice)
        ++used[std::size_t(k)];
    for (int k = 0; k < 4; ++k)
        EXPECT_GT(used[std::size_t(k)], 0) << "sector " << k << " never chosen on a random image";
}

TEST(KuwaharaFilterTest, ConstantStaysConstantAndAlphaPassesThrough)
{
    FilterImage img(9, 7, osg::Vec4f(0.3f, 0.6f, 0.9f, 0.5f));
    img.set(4, 3, osg::Vec4f(0.3f, 0.6f, 0.9f, 0.25f)); // alpha differs: not filtered
    osg::ref_ptr<KuwaharaFilter> f = new KuwaharaFilter;
    const FilterImage out = f->apply(img, ImageBorder(WrapMode::Repeat, WrapMode::Mirror));
    for (int y = 0; y < 7; ++y)
        for (int x = 0; x < 9; ++x)
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(out.get(x, y)[c], img.get(x, y)[c], 1e-6f);
    EXPECT_EQ(out.get(4, 3)[3], 0.25f);
    EXPECT_EQ(out.get(0, 0)[3], 0.5f);
}

TEST(KuwaharaFilterTest, WrapModesEqualFilteringThePaddedImage)
{
    const FilterImage img = randomImage(13, 11, 5);
    osg::ref_ptr<KuwaharaFilter> f = new KuwaharaFilter;
    f->setRadius(3);
    for (WrapMode s : {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror})
        for (WrapMode t : {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror})
            EXPECT_LT(wrapError(*f, img, ImageBorder(s, t), 4), 1e-6f)
                << ImageBorder::name(s) << "/" << ImageBorder::name(t);
}

TEST(KuwaharaFilterTest, BlocksAndUnstableSectorChoiceOnANoisyGradient)
{
    // The known failure regime: on a smooth gradient with noise no sector is clearly better;
    // the choice follows the noise and flips from texel to texel, and the output is a patchwork
    // of sector means offset by about r/2 times the slope (block artefacts). The anisotropic
    // Kuwahara filter weights all sectors smoothly instead.
    const int n = 64;
    FilterImage ramp(n, n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
        {
            const float g = 0.2f + 0.6f * (float(x) + 0.5f * float(y)) / float(n);
            ramp.set(x, y, osg::Vec4f(g, g, g, 1.0f));
        }
    FilterImage noisy = ramp;
    addNoise(noisy, 0.03f, 11);
    osg::ref_ptr<KuwaharaFilter> kuwahara = new KuwaharaFilter;
    kuwahara->setRadius(4);
    osg::ref_ptr<AnisotropicKuwaharaFilter> akf = new AnisotropicKuwaharaFilter;
    akf->setRadius(4);
    std::vector<int> choice;
    naiveKuwahara(noisy, 4, kClamp, &choice);
    const FilterImage k = kuwahara->apply(noisy, kClamp);
    const FilterImage a = akf->apply(noisy, kClamp);
    const int m = 8;
    int flips = 0, pairs = 0;
    for (int y = m; y < n - m; ++y)
        for (int x = m; x < n - m - 1; ++x)
        {
            ++pairs;
            flips += choice[std::size_t(y * n + x)] != choice[std::size_t(y * n + x + 1)];
        }
    const double flipRate = double(flips) / pairs;
    const double roughK = roughness(k, m), roughA = roughness(a, m), roughIn = roughness(noisy, m);
    const double errK = residualSd(k, ramp, m), errA = residualSd(a, ramp, m);
    std::cout
        << "noisy gradient (noise sd 0.03, r = 4): Kuwahara sector changes between horizontal neighbours "
        << flipRate << "; roughness (mean |2nd difference|) input " << roughIn << ", Kuwahara " << roughK
        << ", AKF " << roughA << "; residual sd vs the clean ramp Kuwahara " << errK << ", AKF " << errA
        << std::endl;
    // Measured: flip rate 0.41; roughness input 0.120, Kuwahara 0.052, AKF 0.013; residual sd
    // Kuwahara 0.022, AKF 0.0085.
    EXPECT_GT(flipRate, 0.25);
    EXPECT_GT(roughK, 2.5 * roughA);
    EXPECT_GT(errK, 1.8 * errA);
}

TEST(KuwaharaFilterTest, ParametersRegistryAndValidation)
{
    osg::ref_ptr<ImageFilter> f = FilterRegistry::create("kuwahara:radius=3");
    ASSERT_TRUE(dynamic_cast<KuwaharaFilter*>(f.get()));
    EXPECT_EQ(static_cast<KuwaharaFilter*>(f.get())->getRadius(), 3);
    EXPECT_EQ(f->getParameterString(), "kuwahara:radius=3");
    EXPECT_EQ(f->dependencyRadius(), 6); // two passes of radius r (conservative: reads reach r)
    EXPECT_THROW(f->setParameter("radius", 0.0), std::invalid_argument);
    EXPECT_THROW(f->setParameter("radius", 17.0), std::invalid_argument);
    EXPECT_THROW(f->setParameter("radius", 2.5), std::invalid_argument);
    EXPECT_THROW(f->setParameter("radius", std::string("wide")), std::invalid_argument);
    EXPECT_THROW(f->setParameter("sigma", 2.0), std::invalid_argument);
    try
    {
        f->setParameter("radius", 40.0);
        FAIL();
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("kuwahara"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("radius"), std::string::npos) << e.what();
    }
    const std::vector<GpuFilterPass> passes = f->gpuPasses();
    ASSERT_EQ(passes.size(), 3u);
    EXPECT_EQ(passes[2].inputs, (std::vector<int>{0, 1, -1}));
}

// ---------------------------------------------------------------------------------------------
// Anisotropic Kuwahara

TEST(AnisotropicKuwaharaFilterTest, ConstantStaysConstant)
{
    FilterImage img(24, 20, osg::Vec4f(0.2f, 0.5f, 0.7f, 0.75f));
    osg::ref_ptr<AnisotropicKuwaharaFilter> f = new AnisotropicKuwaharaFilter;
    f->setRadius(4);
    for (int levels : {1, 3})
    {
        f->setLevels(levels);
        const FilterImage out = f->apply(img, ImageBorder(WrapMode::Mirror, WrapMode::Repeat));
        EXPECT_LT(FilterImage::maxAbsDifference(out, img, true), 1e-6f) << "levels " << levels;
    }
}

TEST(AnisotropicKuwaharaFilterTest, KeepsAStraightEdgeSharpAndSmoothsAlongIt)
{
    // A vertical step (0.2 | 0.8 between columns 23 and 24) with noise of sd 0.03.
    const int w = 48, h = 48;
    FilterImage img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const float g = x < 24 ? 0.2f : 0.8f;
            img.set(x, y, osg::Vec4f(g, g, g, 1.0f));
        }
    addNoise(img, 0.03f, 21);
    osg::ref_ptr<AnisotropicKuwaharaFilter> akf = new AnisotropicKuwaharaFilter;
    akf->setRadius(5);
    const FilterImage out = akf->apply(img, kClamp);
    // The tensor sees the edge: A near 1 and the tangent vertical next to it.
    const FilterImage flow = StructureTensor::flow(img, akf->getRho(), kClamp);
    EXPECT_GT(flow.get(23, 24)[2], 0.9f);
    EXPECT_GT(std::fabs(flow.get(23, 24)[1]), 0.99f);
    double m23, s23, m24, s24, m22, s22, min23, sin23;
    columnStats(out, 23, 8, 40, m23, s23);
    columnStats(out, 24, 8, 40, m24, s24);
    columnStats(out, 22, 8, 40, m22, s22);
    columnStats(img, 23, 8, 40, min23, sin23);
    std::cout << "edge: column 22 mean " << m22 << ", 23 mean " << m23 << " sd " << s23 << " (input sd "
              << sin23 << "), 24 mean " << m24 << " sd " << s24 << std::endl;
    // Sharp: the texels on either side of the step keep their side's value (a Gaussian of
    // sigma 2 would give 0.39 and 0.61).
    EXPECT_NEAR(m23, 0.2, 0.03);
    EXPECT_NEAR(m24, 0.8, 0.03);
    EXPECT_NEAR(m22, 0.2, 0.02);
    // Smoothed along the edge: the noise along the columns next to the step drops by 3x or more.
    EXPECT_LT(s23, sin23 / 3);
    EXPECT_LT(s24, sin23 / 3);
    const FilterImage g =
        GaussianFilter::blurAxis(GaussianFilter::blurAxis(img, GaussianFilter::weightsFor(2), 0, kClamp),
                                 GaussianFilter::weightsFor(2), 1, kClamp);
    double gm23, gs23;
    columnStats(g, 23, 8, 40, gm23, gs23);
    EXPECT_GT(gm23, 0.35);
}

TEST(AnisotropicKuwaharaFilterTest, IsotropicWhereTheTensorIsIsotropic)
{
    // Where A = 0 (flat regions, isotropic structure) the ellipse is the disc of radius r and the
    // filter is isotropic: with an isotropic tensor it commutes with transposing the image
    // (the 8 polynomial sectors are symmetric under the square's symmetries).
    const FilterImage img = randomImage(21, 21, 9);
    FilterImage t(21, 21);
    for (int y = 0; y < 21; ++y)
        for (int x = 0; x < 21; ++x)
            t.set(x, y, img.get(y, x));
    osg::ref_ptr<AnisotropicKuwaharaFilter> f = new AnisotropicKuwaharaFilter;
    f->setRadius(4);
    float worst = 0;
    for (int y = 4; y < 17; ++y)
        for (int x = 4; x < 17; ++x)
        {
            const osg::Vec4f a = f->filterTexel(img, x, y, osg::Vec3f(1, 0, 1), kClamp);
            const osg::Vec4f b = f->filterTexel(t, y, x, osg::Vec3f(1, 0, 1), kClamp);
            for (int c = 0; c < 4; ++c)
                worst = std::max(worst, std::fabs(a[c] - b[c]));
        }
    EXPECT_LT(worst, 2e-6f);
    // On isotropic noise the smoothed tensor is weakly anisotropic, and the filter's smoothing
    // has no preferred direction: lag-1 correlations of the output along x and y agree.
    FilterImage noise(64, 64, osg::Vec4f(0.5f, 0.5f, 0.5f, 1.0f));
    addNoise(noise, 0.05f, 31);
    const FilterImage flow = StructureTensor::flow(noise, f->getRho(), kClamp);
    double meanA = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            meanA += flow.get(x, y)[2];
    meanA /= 64.0 * 64.0;
    const FilterImage out = f->apply(noise, kClamp);
    double sxx = 0, sx = 0, sy = 0, mean = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            mean += out.get(x, y)[0];
    mean /= 64.0 * 64.0;
    for (int y = 4; y < 59; ++y)
        for (int x = 4; x < 59; ++x)
        {
            const double c = out.get(x, y)[0] - mean;
            sxx += c * c;
            sx += c * (out.get(x + 1, y)[0] - mean);
            sy += c * (out.get(x, y + 1)[0] - mean);
        }
    std::cout << "isotropic noise: mean A " << meanA << ", lag-1 correlation x " << sx / sxx << ", y "
              << sy / sxx << std::endl;
    EXPECT_LT(meanA, 0.5);
    EXPECT_NEAR(sx / sxx, sy / sxx, 0.1);
}

TEST(AnisotropicKuwaharaFilterTest, ThresholdAndMultiScaleSmoothNoisyFlatRegions)
{
    // A large flat region with noise (sd 0.02 = 5 units) and a step: the threshold h makes all
    // sectors weigh the same below h (smooth output), and the multi-scale filter brings the
    // coarse levels' stronger abstraction into the flat region while the step stays sharp.
    const int n = 64;
    FilterImage clean(n, n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
        {
            const float g = x < 40 ? 0.4f : 0.7f;
            clean.set(x, y, osg::Vec4f(g, g, g, 1.0f));
        }
    FilterImage img = clean;
    addNoise(img, 0.02f, 41);
    osg::ref_ptr<AnisotropicKuwaharaFilter> f = new AnisotropicKuwaharaFilter;
    f->setRadius(3);
    const FilterImage single = f->apply(img, kClamp);
    f->setThreshold(16.0f);
    const FilterImage thresholded = f->apply(img, kClamp);
    f->setThreshold(0.0f);
    f->setLevels(3);
    const FilterImage multi = f->apply(img, kClamp);
    auto flatSd = [&](const FilterImage& o)
    {
        double s = 0, ss = 0;
        int k = 0;
        for (int y = 8; y < n - 8; ++y)
            for (int x = 8; x < 30; ++x)
            {
                s += o.get(x, y)[0];
                ss += double(o.get(x, y)[0]) * o.get(x, y)[0];
                ++k;
            }
        return std::sqrt(ss / k - (s / k) * (s / k));
    };
    double m39, s39, m40, s40;
    columnStats(multi, 39, 8, n - 8, m39, s39);
    columnStats(multi, 40, 8, n - 8, m40, s40);
    std::cout << "noisy flat region sd: input " << flatSd(img) << ", AKF " << flatSd(single) << ", h = 16 "
              << flatSd(thresholded) << ", 3 levels " << flatSd(multi) << "; step columns " << m39 << " | "
              << m40 << std::endl;
    EXPECT_LT(flatSd(thresholded), 0.8 * flatSd(single));
    EXPECT_LT(flatSd(multi), 0.8 * flatSd(single));
    EXPECT_NEAR(m39, 0.4, 0.03);
    EXPECT_NEAR(m40, 0.7, 0.03);
}

TEST(AnisotropicKuwaharaFilterTest, RepeatEqualsFilteringTheTiledImage)
{
    // A repeat-wrapped image filtered equals the centre of the filtered tiling. (Clamp and
    // mirror have no such identity for a multi-pass filter: the intermediate tensor is clamped
    // or mirrored, and mirroring flips the sign of F; the GL tests compare those modes with the
    // GPU instead.)
    const FilterImage img = randomImage(16, 16, 13);
    osg::ref_ptr<AnisotropicKuwaharaFilter> f = new AnisotropicKuwaharaFilter;
    f->setRadius(3);
    f->setRho(1.0f);
    const ImageBorder repeat(WrapMode::Repeat, WrapMode::Repeat);
    // Single scale: reach = Sobel 1 + Gaussian 3 + ellipse 6 = 10 texels; pad 16 (3x3 tiles).
    EXPECT_LT(wrapError(*f, img, repeat, 16), 1e-5f);
    // Multi-scale, 3 levels, r = 2: the reach at level 2 is (1 + 3 + 4) level texels = 32
    // texels; the pyramid of the tiling is the tiling of the pyramid when the padding is a
    // multiple of 2^(levels-1): pad 48 (7x7 tiles).
    f->setRadius(2);
    f->setLevels(3);
    EXPECT_LT(wrapError(*f, img, repeat, 48), 1e-5f);
}

TEST(AnisotropicKuwaharaFilterTest, DownsampleIsTheBinomialPyramidStep)
{
    // Dyadic values: 1, 0 alternating columns: every output texel sums (1 + 3) / 8 = 1/2 of ones
    // in x; rows are constant.
    std::vector<float> v(8 * 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x)
            v[std::size_t(y * 8 + x)] = x % 2 == 0 ? 1.0f : 0.0f;
    const FilterImage d =
        AnisotropicKuwaharaFilter::downsample(grey(8, 4, v), ImageBorder(WrapMode::Repeat, WrapMode::Repeat));
    ASSERT_EQ(d.width(), 4);
    ASSERT_EQ(d.height(), 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x)
            EXPECT_EQ(d.get(x, y)[0], 0.5f);
    // Odd sizes round up: 5x3 -> 3x2; 1x1 stays 1x1.
    EXPECT_EQ(AnisotropicKuwaharaFilter::downsample(FilterImage(5, 3), kClamp).width(), 3);
    EXPECT_EQ(AnisotropicKuwaharaFilter::downsample(FilterImage(5, 3), kClamp).height(), 2);
    EXPECT_EQ(AnisotropicKuwaharaFilter::downsample(FilterImage(1, 1), kClamp).width(), 1);
}

TEST(AnisotropicKuwaharaFilterTest, ParametersRegistryAndValidation)
{
    osg::ref_ptr<ImageFilter> f =
        FilterRegistry::create("akf:radius=4,q=6,alpha=2,rho=1.5,levels=4,threshold=2");
    AnisotropicKuwaharaFilter* a = dynamic_cast<AnisotropicKuwaharaFilter*>(f.get());
    ASSERT_TRUE(a);
    EXPECT_EQ(a->getRadius(), 4.0f);
    EXPECT_EQ(a->getSharpness(), 6.0f);
    EXPECT_EQ(a->getAlpha(), 2.0f);
    EXPECT_EQ(a->getRho(), 1.5f);
    EXPECT_EQ(a->getLevels(), 4);
    EXPECT_EQ(a->getThreshold(), 2.0f);
    EXPECT_EQ(f->getParameterString(), "akf:radius=4,q=6,alpha=2,rho=1.5,levels=4,threshold=2");
    EXPECT_EQ(f->dependencyRadius(), -1); // multi-scale: whole images
    // 3 pyramid passes; per level: Sobel, 2 blurs (the second propagating), filter.
    EXPECT_EQ(f->gpuPasses().size(), 3u + 4u * 4u);
    a->setLevels(1);
    // Single scale: Sobel 1 + two Gaussian passes of ceil(3 rho) = 5 + ellipse floor(2 r) = 8
    // (the engine's conservative sum of pass radii; the true reach is 1 + 5 + 8).
    EXPECT_EQ(f->dependencyRadius(), 1 + 5 + 5 + 8);
    EXPECT_EQ(f->gpuPasses().size(), 4u);
    EXPECT_EQ(osg::ref_ptr<ImageFilter>(FilterRegistry::create("akf"))->getParameterString(),
              "akf:radius=6,q=8,alpha=1,rho=2,levels=1,threshold=0");
    for (const char* bad : {"akf:radius=0.5", "akf:radius=13", "akf:q=0", "akf:alpha=0", "akf:levels=7",
                            "akf:levels=2.5", "akf:threshold=-1", "akf:rho=9", "akf:sigma=1"})
        EXPECT_THROW(FilterRegistry::create(bad), std::invalid_argument) << bad;
}

// ---------------------------------------------------------------------------------------------
// Shock filter

namespace
{
/** A vertical step (0.2 | 0.8 between columns c-1 and c) blurred by a Gaussian of sigma 2. */
FilterImage blurredStep(int w, int h, int c)
{
    FilterImage img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const float v = x < c ? 0.2f : 0.8f;
            img.set(x, y, osg::Vec4f(v, v, v, 1.0f));
        }
    const std::vector<float> g = GaussianFilter::weightsFor(2.0f);
    return GaussianFilter::blurAxis(img, g, 0, kClamp);
}

/** The number of columns whose row-averaged red value lies strictly between the 20 % and 80 %
 *  levels of the 0.2 .. 0.8 step (0: the step jumps between two neighbouring columns). */
int transitionWidth(const FilterImage& img)
{
    int n = 0;
    for (int x = 0; x < img.width(); ++x)
    {
        double m = 0;
        for (int y = 0; y < img.height(); ++y)
            m += img.get(x, y)[0];
        m /= img.height();
        n += m > 0.32 && m < 0.68;
    }
    return n;
}
} // namespace

TEST(ShockFilterTest, ConstantStaysConstant)
{
    FilterImage img(20, 16, osg::Vec4f(0.3f, 0.45f, 0.6f, 0.5f));
    osg::ref_ptr<ShockFilter> f = new ShockFilter;
    f->setIterations(2);
    EXPECT_LT(FilterImage::maxAbsDifference(f->apply(img, ImageBorder(WrapMode::Repeat, WrapMode::Mirror)),
                                            img, true),
              1e-6f);
}

TEST(ShockFilterTest, ShockStepSharpensABlurredEdgeTowardsItsPlateaus)
{
    // One shock step on a blurred step: the dark side (second derivative > 0 along the gradient)
    // is eroded, the bright side dilated; no texel leaves [0.2, 0.8].
    const FilterImage img = blurredStep(32, 8, 16);
    const FilterImage tensor = StructureTensor::smoothedTensor(img, 1.0f, kClamp);
    const FilterImage out = ShockFilter::shock(img, img, tensor, 1.5f, 0.005f, 2.0f, kClamp);
    for (int x = 0; x < 32; ++x)
    {
        const float in = img.get(x, 4)[0], o = out.get(x, 4)[0];
        if (x < 15)
        {
            EXPECT_LE(o, in + 1e-6f) << x;
        }
        if (x > 16)
        {
            EXPECT_GE(o, in - 1e-6f) << x;
        }
        EXPECT_GE(o, 0.2f - 1e-5f);
        EXPECT_LE(o, 0.8f + 1e-5f);
    }
    EXPECT_LT(transitionWidth(out), transitionWidth(img));
    // The whole filter (defaults but 3 iterations): the 20-80 % transition (4 columns for the
    // Gaussian of sigma 2) becomes a jump between neighbouring columns (measured: 0 columns
    // after one shock step already), the plateaus keep their values.
    osg::ref_ptr<ShockFilter> f = new ShockFilter;
    f->setIterations(3);
    const FilterImage all = f->apply(img, kClamp);
    std::cout << "blurred step: transition width input " << transitionWidth(img) << ", one shock step "
              << transitionWidth(out) << ", filter " << transitionWidth(all) << std::endl;
    EXPECT_EQ(transitionWidth(img), 4);
    EXPECT_LE(transitionWidth(all), 1);
    EXPECT_NEAR(all.get(4, 4)[0], 0.2f, 0.01f);
    EXPECT_NEAR(all.get(28, 4)[0], 0.8f, 0.01f);
}

TEST(ShockFilterTest, FlowSmoothingFollowsTheEdgeTangents)
{
    // Vertical stripes (period 8) with noise: smoothing along the tangent (vertical) removes the
    // noise and keeps the stripes' contrast; an isotropic Gaussian of the same sigma would
    // flatten them.
    FilterImage clean(32, 32);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x)
        {
            const float v = (x / 4) % 2 == 0 ? 0.25f : 0.75f;
            clean.set(x, y, osg::Vec4f(v, v, v, 1.0f));
        }
    FilterImage img = clean;
    addNoise(img, 0.04f, 51);
    const ImageBorder repeat(WrapMode::Repeat, WrapMode::Repeat);
    const FilterImage tensor = StructureTensor::smoothedTensor(img, 2.0f, repeat);
    const FilterImage out = ShockFilter::flowSmooth(img, tensor, 3.0f, 22.5f, false, repeat);
    const double before = residualSd(img, clean, 0), after = residualSd(out, clean, 0);
    std::cout << "stripes: residual sd input " << before << ", flow-guided smoothing " << after << std::endl;
    EXPECT_LT(after, before / 2.5);
    double m1, s1, m2, s2;
    columnStats(out, 1, 0, 32, m1, s1);
    columnStats(out, 5, 0, 32, m2, s2);
    EXPECT_NEAR(m1, 0.25, 0.03);
    EXPECT_NEAR(m2, 0.75, 0.03);
}

TEST(ShockFilterTest, RepeatEqualsFilteringTheTiledImage)
{
    const FilterImage img = randomImage(16, 16, 61);
    osg::ref_ptr<ShockFilter> f = new ShockFilter;
    f->setIterations(1);
    f->setSigmaS(2.0f);
    f->setSigmaA(1.0f);
    // Reach: tensor 1 + 3, smoothing 4 + 1, tensor 4, shock 8 + 1, final 2 + 1: about 25 texels.
    EXPECT_LT(wrapError(*f, img, ImageBorder(WrapMode::Repeat, WrapMode::Repeat), 32), 1e-5f);
}

TEST(ShockFilterTest, ParametersRegistryAndValidation)
{
    osg::ref_ptr<ImageFilter> f =
        FilterRegistry::create("shock:iterations=2,sigma_s=4,adaptive=off,sigma_i=1");
    ShockFilter* s = dynamic_cast<ShockFilter*>(f.get());
    ASSERT_TRUE(s);
    EXPECT_EQ(s->getIterations(), 2);
    EXPECT_EQ(s->getSigmaS(), 4.0f);
    EXPECT_FALSE(s->getAdaptive());
    EXPECT_EQ(f->getParameterString(), "shock:iterations=2,sigma_d=1,sigma_s=4,max_angle=22.5,adaptive=off,"
                                       "sigma_i=1,sigma_g=1.5,tau_s=0.005,radius=2,sigma_a=1.5");
    // Per iteration: tensor 3 + smoothing 1 + tensor 3 + luminance blur 2 + shock 1; final 1.
    EXPECT_EQ(f->gpuPasses().size(), 2u * 10u + 1u);
    s->setSigmaI(0.0f);
    EXPECT_EQ(f->gpuPasses().size(), 2u * 8u + 1u);
    s->setIterations(0);
    EXPECT_EQ(f->gpuPasses().size(), 3u + 1u); // tensor and the final smoothing
    s->setSigmaA(0.0f);
    EXPECT_EQ(f->gpuPasses().size(), 1u); // a copy
    const FilterImage img = randomImage(8, 8, 1);
    EXPECT_EQ(FilterImage::maxAbsDifference(f->apply(img, kClamp), img, true), 0.0f);
    for (const char* bad :
         {"shock:iterations=11", "shock:iterations=1.5", "shock:sigma_s=-1", "shock:max_angle=91",
          "shock:sigma_g=0", "shock:adaptive=maybe", "shock:radius=9", "shock:tau=1"})
        EXPECT_THROW(FilterRegistry::create(bad), std::invalid_argument) << bad;
}

TEST(KuwaharaFiltersTest, SerializerRoundTrips)
{
    const std::string dir = loatest::freshDirectory("KuwaharaFiltersRoundTrip");
    osg::ref_ptr<KuwaharaFilter> k = new KuwaharaFilter;
    k->setRadius(7);
    osg::ref_ptr<AnisotropicKuwaharaFilter> a = new AnisotropicKuwaharaFilter;
    a->setRadius(4.5f);
    a->setSharpness(10.0f);
    a->setAlpha(0.5f);
    a->setRho(1.25f);
    a->setLevels(4);
    a->setThreshold(3.0f);
    osg::ref_ptr<ShockFilter> s = new ShockFilter;
    s->setIterations(3);
    s->setSigmaD(1.5f);
    s->setSigmaS(4.0f);
    s->setMaxAngle(30.0f);
    s->setSigmaI(0.5f);
    s->setSigmaG(2.0f);
    s->setTauS(0.01f);
    s->setRadius(3.0f);
    s->setSigmaA(1.0f);
    s->setAdaptive(false);
    for (const char* ext : {"osgt", "osgb"})
    {
        osg::ref_ptr<KuwaharaFilter> kb = roundTrip(*k, dir, ext);
        ASSERT_TRUE(kb.valid());
        EXPECT_EQ(kb->getParameterString(), k->getParameterString());
        osg::ref_ptr<AnisotropicKuwaharaFilter> ab = roundTrip(*a, dir, ext);
        ASSERT_TRUE(ab.valid());
        EXPECT_EQ(ab->getParameterString(), a->getParameterString());
        osg::ref_ptr<ShockFilter> sb = roundTrip(*s, dir, ext);
        ASSERT_TRUE(sb.valid());
        EXPECT_EQ(sb->getParameterString(), s->getParameterString());
    }
}
