// Procedural pencil tone textures (paper 002 §3.1, a tonal art map after Praun et al. 2001): each
// layer's mean tone within 0.02 of 0.25 + 0.75 k / (levels - 1); nesting (darker layers pixelwise
// <= lighter ones); seamless tiling; determinism per seed; refused arguments.
#include <osgLoA/abstraction/PencilTextures>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

using namespace osgLoA;

namespace
{
std::string refusal(void (*f)())
{
    try
    {
        f();
    }
    catch (const std::invalid_argument& e)
    {
        return e.what();
    }
    return "";
}

/** Mean |I(xa, y) - I(xb, y + 1)| over the rows (y + 1 wrapped), in [0, 1], of layer k (red
 *  channel): columns compared one row apart, along the 45-degree hatching direction, where a
 *  stroke crossing from xa to xb = xa + 1 keeps its tone. */
double columnDifference(const osg::Image& img, int k, int xa, int xb)
{
    double sum = 0.0;
    for (int y = 0; y < img.t(); ++y)
        sum += std::abs(int(img.data(xa, y, k)[0]) - int(img.data(xb, (y + 1) % img.t(), k)[0]));
    return sum / (255.0 * img.t());
}

/** The same for rows ya and yb, compared one column apart. */
double rowDifference(const osg::Image& img, int k, int ya, int yb)
{
    double sum = 0.0;
    for (int x = 0; x < img.s(); ++x)
        sum += std::abs(int(img.data(x, ya, k)[0]) - int(img.data((x + 1) % img.s(), yb, k)[0]));
    return sum / (255.0 * img.s());
}

TEST(PencilTexturesTest, LayersReachTheirTargetTones)
{
    EXPECT_FLOAT_EQ(PencilTextures::targetTone(0, 4), 0.25f);
    EXPECT_FLOAT_EQ(PencilTextures::targetTone(1, 4), 0.5f);
    EXPECT_FLOAT_EQ(PencilTextures::targetTone(3, 4), 1.0f);
    EXPECT_FLOAT_EQ(PencilTextures::targetTone(2, 5), 0.625f);
    for (int levels : {2, 4, 8})
    {
        osg::ref_ptr<osg::Image> img = PencilTextures::create(levels, 128, 7);
        ASSERT_TRUE(img.valid());
        EXPECT_EQ(img->s(), 128);
        EXPECT_EQ(img->t(), 128);
        EXPECT_EQ(img->r(), levels);
        EXPECT_EQ(img->getPixelFormat(), GLenum(GL_RGBA));
        EXPECT_EQ(img->getDataType(), GLenum(GL_UNSIGNED_BYTE));
        for (int k = 0; k < levels; ++k)
        {
            const double mean = PencilTextures::meanTone(*img, k);
            const double target = PencilTextures::targetTone(k, levels);
            // Bar 0.02 (brief); a layer stops within one stroke (about 0.5 / size = 0.004) of the
            // target, below it.
            EXPECT_NEAR(mean, target, 0.02) << "levels " << levels << " layer " << k;
            EXPECT_LE(mean, target + 1.0 / 255.0) << "levels " << levels << " layer " << k;
            std::cout << "levels " << levels << " layer " << k << ": mean " << mean << " target " << target
                      << "\n";
        }
        // The lightest layer is white paper; alpha is 255 everywhere.
        const unsigned char* top = img->data(0, 0, levels - 1);
        const unsigned char* bottom = img->data(0, 0, 0);
        for (int i = 0; i < 128 * 128; ++i)
        {
            EXPECT_EQ(top[4 * i], 255) << i;
            ASSERT_EQ(bottom[4 * i + 3], 255) << i;
            ASSERT_EQ(bottom[4 * i], bottom[4 * i + 1]);
            ASSERT_EQ(bottom[4 * i], bottom[4 * i + 2]);
        }
    }
    // The default size, as the renderer uses it.
    osg::ref_ptr<osg::Image> big = PencilTextures::create(4);
    EXPECT_EQ(big->s(), 256);
    for (int k = 0; k < 4; ++k)
        EXPECT_NEAR(PencilTextures::meanTone(*big, k), PencilTextures::targetTone(k, 4), 0.02) << k;
}

TEST(PencilTexturesTest, DarkerLayersHoldEveryStrokeOfLighterOnes)
{
    osg::ref_ptr<osg::Image> img = PencilTextures::create(6, 64, 3);
    std::size_t violations = 0, darker = 0;
    for (int k = 0; k + 1 < 6; ++k)
    {
        const unsigned char* dark = img->data(0, 0, k);
        const unsigned char* light = img->data(0, 0, k + 1);
        for (int i = 0; i < 64 * 64; ++i)
        {
            violations += dark[4 * i] > light[4 * i] ? 1 : 0;
            darker += dark[4 * i] < light[4 * i] ? 1 : 0;
        }
    }
    EXPECT_EQ(violations, 0u);
    EXPECT_GT(darker, 0u); // the layers do differ
}

/** Where the wrap seam of layer k (last line against the first) and lines half the image apart
 *  fall in the distribution of the interior neighbour pairs: (value - mean) / sd. */
struct SeamScore
{
    double seamZ;
    double farZ;
};

SeamScore seamScore(const osg::Image& img, int k, bool columns)
{
    const int size = columns ? img.s() : img.t();
    auto diff = [&](int a, int b)
    { return columns ? columnDifference(img, k, a, b) : rowDifference(img, k, a, b); };
    double sum = 0.0, sum2 = 0.0, far = 0.0;
    for (int x = 0; x + 1 < size; ++x)
    {
        const double d = diff(x, x + 1);
        sum += d;
        sum2 += d * d;
        far += diff(x, (x + size / 2) % size);
    }
    const double n = size - 1, mean = sum / n, sd = std::sqrt(std::max(1e-12, sum2 / n - mean * mean));
    return SeamScore{(diff(size - 1, 0) - mean) / sd, (far / n - mean) / sd};
}
} // namespace

TEST(PencilTexturesTest, LayersTileSeamlessly)
{
    // The wrap seam (last column against the first, last row against the first) must look like
    // any interior seam between neighbouring columns (rows). Measure: mean absolute difference
    // of the two lines compared along the hatching direction (columnDifference), as a z-score
    // against the size - 1 interior neighbour pairs. Bars: |z| <= 4 for every seam of one
    // texture (over 180 seams of 60 seeds the z-scores measured mean 0.13, sd 1.09, max 3.04),
    // and the mean z over 20 seeds' 120 seams within +-0.5 (about 3.5 standard errors: no
    // systematic seam). Control: lines half the image apart, which are independent (what the
    // seam of a texture drawn without wrap-around would be), score z > 4 on average, so the bar
    // tells a seam from a cut.
    osg::ref_ptr<osg::Image> img = PencilTextures::create(4, 128, 11);
    for (int k = 0; k < 3; ++k) // the layers with strokes (k = 3 is white)
        for (bool columns : {true, false})
        {
            const SeamScore s = seamScore(*img, k, columns);
            std::cout << "seed 11 layer " << k << (columns ? " columns" : " rows") << ": seam z " << s.seamZ
                      << ", lines size/2 apart z " << s.farZ << "\n";
            EXPECT_LE(std::abs(s.seamZ), 4.0) << k << " " << columns;
            EXPECT_GT(s.farZ, 4.0) << k << " " << columns;
        }
    double zSum = 0.0;
    int count = 0;
    for (unsigned seed = 100; seed < 120; ++seed)
    {
        osg::ref_ptr<osg::Image> t = PencilTextures::create(4, 128, seed);
        for (int k = 0; k < 3; ++k)
            for (bool columns : {true, false})
            {
                zSum += seamScore(*t, k, columns).seamZ;
                ++count;
            }
    }
    std::cout << "mean seam z over " << count << " seams: " << zSum / count << "\n";
    EXPECT_LE(std::abs(zSum / count), 0.5);
}

TEST(PencilTexturesTest, DeterministicPerSeedAndLayerCopies)
{
    osg::ref_ptr<osg::Image> a = PencilTextures::create(3, 32, 5), b = PencilTextures::create(3, 32, 5);
    osg::ref_ptr<osg::Image> c = PencilTextures::create(3, 32, 6);
    ASSERT_EQ(a->getTotalSizeInBytes(), 32u * 32u * 3u * 4u);
    EXPECT_EQ(std::memcmp(a->data(), b->data(), a->getTotalSizeInBytes()), 0);
    EXPECT_NE(std::memcmp(a->data(), c->data(), a->getTotalSizeInBytes()), 0);
    for (int k = 0; k < 3; ++k)
    {
        osg::ref_ptr<osg::Image> l = PencilTextures::layer(*a, k);
        EXPECT_EQ(l->r(), 1);
        EXPECT_EQ(l->s(), 32);
        EXPECT_EQ(std::memcmp(l->data(), a->data(0, 0, k), 32 * 32 * 4), 0) << k;
    }
}

TEST(PencilTexturesTest, BadArgumentsAreRefused)
{
    EXPECT_NE(refusal([] { PencilTextures::create(1); }).find("levels"), std::string::npos);
    EXPECT_NE(refusal([] { PencilTextures::create(17); }).find("levels"), std::string::npos);
    EXPECT_NE(refusal([] { PencilTextures::create(4, 8); }).find("size"), std::string::npos);
    EXPECT_NE(refusal([] { PencilTextures::create(4, 5000); }).find("size"), std::string::npos);
    EXPECT_NE(refusal([] { PencilTextures::targetTone(0, 1); }).find("levels"), std::string::npos);
    EXPECT_NE(refusal([] { PencilTextures::targetTone(-1, 4); }).find("k -1"), std::string::npos);
    EXPECT_NE(refusal([] { PencilTextures::targetTone(4, 4); }).find("k 4"), std::string::npos);
    EXPECT_NE(refusal(
                  []
                  {
                      osg::ref_ptr<osg::Image> img = PencilTextures::create(2, 16);
                      PencilTextures::layer(*img, 2);
                  })
                  .find("k 2"),
              std::string::npos);
    EXPECT_NE(refusal(
                  []
                  {
                      osg::ref_ptr<osg::Image> img = new osg::Image;
                      img->allocateImage(4, 4, 1, GL_RGB, GL_UNSIGNED_BYTE);
                      PencilTextures::meanTone(*img, 0);
                  })
                  .find("stack"),
              std::string::npos);
}
