// The filter framework without GL: wrap modes, the area-weighted mip pyramid, image conversion,
// the Gaussian filter's CPU reference against hand-computed values, the registry's
// "NAME:key=value+..." syntax and its errors, and serializer round trips.
#include <osgLoA/filtering/FilterChain>
#include <osgLoA/filtering/FilterImage>
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/GaussianFilter>

#include "support/TestSupport.h"

#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

using namespace osgLoA;

TEST(ImageFilterTest, WrapIndexFollowsGLWrapModes)
{
    // n = 4: repeat ... 2 3 | 0 1 2 3 | 0 1; mirrored repeat ... 1 0 | 0 1 2 3 | 3 2 ...; clamp.
    const int repeat[] = {2, 3, 0, 1, 2, 3, 0, 1};
    const int mirror[] = {1, 0, 0, 1, 2, 3, 3, 2};
    const int clamp[] = {0, 0, 0, 1, 2, 3, 3, 3};
    for (int i = -2; i < 6; ++i)
    {
        EXPECT_EQ(wrapIndex(i, 4, WrapMode::Repeat), repeat[i + 2]) << i;
        EXPECT_EQ(wrapIndex(i, 4, WrapMode::Mirror), mirror[i + 2]) << i;
        EXPECT_EQ(wrapIndex(i, 4, WrapMode::Clamp), clamp[i + 2]) << i;
    }
    EXPECT_EQ(wrapIndex(-9, 4, WrapMode::Mirror), 0); // -9 mod 8 = 7 -> 8-1-7 = 0
    EXPECT_EQ(wrapIndex(-13, 4, WrapMode::Repeat), 3);
    EXPECT_EQ(wrapIndex(5, 1, WrapMode::Mirror), 0);
}

TEST(ImageFilterTest, DownsampleIsAnAreaWeightedBoxFilter)
{
    FilterImage img(5, 2);
    for (int x = 0; x < 5; ++x)
    {
        img.set(x, 0, osg::Vec4f(float(x), 0, 0, 1));
        img.set(x, 1, osg::Vec4f(float(x) + 10, 0, 0, 1));
    }
    const FilterImage d = img.downsample();
    ASSERT_EQ(d.width(), 2);
    ASSERT_EQ(d.height(), 1);
    // Output texel 0 covers input [0, 2.5): (0 + 1 + 0.5 * 2) / 2.5 = 0.8 per row; rows average
    // 0.8 and 10.8 -> 5.8. Texel 1 covers [2.5, 5): (0.5 * 2 + 3 + 4) / 2.5 = 3.2 -> 8.2.
    EXPECT_NEAR(d.get(0, 0)[0], 5.8f, 1e-5f);
    EXPECT_NEAR(d.get(1, 0)[0], 8.2f, 1e-5f);
    EXPECT_NEAR(d.get(1, 0)[3], 1.0f, 1e-6f);
    const std::vector<FilterImage> pyr = FilterImage(37, 6).mipPyramid();
    ASSERT_EQ(pyr.size(), 6u); // 37x6, 18x3, 9x1, 4x1, 2x1, 1x1
    EXPECT_EQ(pyr[1].width(), 18);
    EXPECT_EQ(pyr[1].height(), 3);
    EXPECT_EQ(pyr[2].height(), 1);
    EXPECT_EQ(pyr[5].width(), 1);
}

TEST(ImageFilterTest, ConvertsImageFormatsAndRejectsBadOnes)
{
    osg::ref_ptr<osg::Image> grey = new osg::Image;
    grey->allocateImage(2, 1, 1, GL_LUMINANCE, GL_UNSIGNED_BYTE);
    grey->data()[0] = 0;
    grey->data()[1] = 255;
    const FilterImage g = FilterImage::fromImage(*grey);
    EXPECT_EQ(g.get(1, 0), osg::Vec4f(1, 1, 1, 1));
    EXPECT_EQ(g.get(0, 0), osg::Vec4f(0, 0, 0, 1));
    osg::ref_ptr<osg::Image> bgra = new osg::Image;
    bgra->allocateImage(1, 1, 1, GL_BGRA, GL_UNSIGNED_BYTE);
    const unsigned char px[4] = {255, 0, 51, 102};
    std::copy(px, px + 4, bgra->data());
    const FilterImage b = FilterImage::fromImage(*bgra);
    EXPECT_NEAR(b.get(0, 0)[0], 0.2f, 1e-6f);
    EXPECT_NEAR(b.get(0, 0)[2], 1.0f, 1e-6f);
    EXPECT_NEAR(b.get(0, 0)[3], 0.4f, 1e-6f);
    // Back to 8 bits rounds.
    osg::ref_ptr<osg::Image> back = b.toImage();
    EXPECT_EQ(back->data()[0], 51);
    EXPECT_EQ(back->data()[2], 255);

    osg::ref_ptr<osg::Image> empty = new osg::Image;
    empty->setFileName("nothing.png");
    try
    {
        FilterImage::fromImage(*empty);
        FAIL();
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("'nothing.png' is empty"), std::string::npos) << e.what();
    }
    // S3TC is decoded (one DXT1 block, every texel colour 0 = pure red); other compressed
    // formats are refused, naming the format.
    unsigned char block[8] = {0x00, 0xF8, 0x1F, 0x00, 0x00, 0x00, 0x00, 0x00};
    osg::ref_ptr<osg::Image> dxt = new osg::Image;
    dxt->setImage(4, 4, 1, GL_COMPRESSED_RGB_S3TC_DXT1_EXT, GL_COMPRESSED_RGB_S3TC_DXT1_EXT, GL_UNSIGNED_BYTE,
                  block, osg::Image::NO_DELETE);
    const FilterImage red = FilterImage::fromImage(*dxt);
    EXPECT_FLOAT_EQ(red.texel(3, 3)[0], 1.0f);
    EXPECT_FLOAT_EQ(red.texel(3, 3)[1], 0.0f);
    EXPECT_FLOAT_EQ(red.texel(3, 3)[3], 1.0f);
    osg::ref_ptr<const osg::Image> rgb = FilterImage::toRGB8(*dxt);
    EXPECT_EQ(rgb->getPixelFormat(), GLenum(GL_RGB));
    EXPECT_EQ(int(rgb->data(2, 1)[0]), 255);
    osg::ref_ptr<osg::Image> rgtc = new osg::Image;
    rgtc->setImage(4, 4, 1, GL_COMPRESSED_RED_RGTC1_EXT, GL_COMPRESSED_RED_RGTC1_EXT, GL_UNSIGNED_BYTE, block,
                   osg::Image::NO_DELETE);
    try
    {
        FilterImage::fromImage(*rgtc);
        ADD_FAILURE() << "RGTC was accepted";
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("compressed pixel format 0x8dbb"), std::string::npos) << e.what();
    }
    EXPECT_THROW(FilterImage(-1, 3), std::invalid_argument);
    EXPECT_THROW(FilterImage(FilterImage::maxDimension() + 1, 1), std::invalid_argument);
}

TEST(ImageFilterTest, GaussianImpulseResponseIsTheNormalizedKernel)
{
    // sigma 1: radius 3, w(k) = exp(-k^2/2) / (1 + 2 sum_{k=1..3} exp(-k^2/2)).
    const std::vector<float> w = GaussianFilter::weightsFor(1.0f);
    ASSERT_EQ(w.size(), 4u);
    const double s = 1 + 2 * (std::exp(-0.5) + std::exp(-2.0) + std::exp(-4.5));
    EXPECT_NEAR(w[0], 1 / s, 1e-7);
    EXPECT_NEAR(w[2], std::exp(-2.0) / s, 1e-7);
    FilterImage impulse(9, 9, osg::Vec4f(0, 0, 0, 0.5f));
    impulse.set(4, 4, osg::Vec4f(1, 1, 1, 0.5f));
    osg::ref_ptr<GaussianFilter> f = new GaussianFilter;
    f->setSigma(1.0f);
    const FilterImage out = f->apply(impulse, ImageBorder());
    for (int y = 0; y < 9; ++y)
        for (int x = 0; x < 9; ++x)
        {
            const int dx = std::abs(x - 4), dy = std::abs(y - 4);
            const float expected = dx <= 3 && dy <= 3 ? w[std::size_t(dx)] * w[std::size_t(dy)] : 0.0f;
            EXPECT_NEAR(out.get(x, y)[1], expected, 1e-7f) << x << "," << y;
            EXPECT_EQ(out.get(x, y)[3], 0.5f); // alpha passes through
        }
    // sigma 0 copies.
    f->setSigma(0.0f);
    EXPECT_EQ(FilterImage::maxAbsDifference(f->apply(impulse, ImageBorder()), impulse, true), 0.0f);
}

TEST(ImageFilterTest, RepeatWrapEqualsTheCentreOfTheFilteredTiling)
{
    FilterImage img(7, 5);
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 7; ++x)
            img.set(x, y, osg::Vec4f(float((x * 3 + y * 5) % 7) / 7.0f, float(x) / 7.0f, float(y) / 5.0f, 1));
    FilterImage tiled(21, 15);
    for (int y = 0; y < 15; ++y)
        for (int x = 0; x < 21; ++x)
            tiled.set(x, y, img.get(x % 7, y % 5));
    osg::ref_ptr<GaussianFilter> f = new GaussianFilter;
    f->setSigma(1.5f); // radius 5: reaches past the 7x5 image, into the neighbouring copies only
    const FilterImage a = f->apply(img, ImageBorder(WrapMode::Repeat, WrapMode::Repeat));
    const FilterImage b = f->apply(tiled, ImageBorder(WrapMode::Clamp, WrapMode::Clamp));
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 7; ++x)
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(a.get(x, y)[c], b.get(x + 7, y + 5)[c], 1e-6f);
    // A constant image stays constant under every mode.
    const FilterImage flat(6, 6, osg::Vec4f(0.3f, 0.6f, 0.9f, 1));
    for (WrapMode m : {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror})
        EXPECT_LT(FilterImage::maxAbsDifference(f->apply(flat, ImageBorder(m, m)), flat), 1e-6f);
}

TEST(ImageFilterTest, RegistryParsesSpecificationsAndNamesErrors)
{
    osg::ref_ptr<ImageFilter> f = FilterRegistry::create("gaussian:sigma=1.5");
    ASSERT_TRUE(dynamic_cast<GaussianFilter*>(f.get()));
    EXPECT_FLOAT_EQ(static_cast<GaussianFilter*>(f.get())->getSigma(), 1.5f);
    EXPECT_EQ(f->getParameterString(), "gaussian:sigma=1.5");
    // The canonical string parses back to the same filter.
    EXPECT_EQ(FilterRegistry::create(f->getParameterString())->getParameterString(), f->getParameterString());

    osg::ref_ptr<ImageFilter> chain = FilterRegistry::create("gaussian:sigma=1 + gaussian");
    ASSERT_TRUE(dynamic_cast<FilterChain*>(chain.get()));
    EXPECT_EQ(chain->getParameterString(), "gaussian:sigma=1+gaussian:sigma=2");
    EXPECT_EQ(chain->gpuPasses().size(), 4u);
    EXPECT_EQ(chain->gpuPasses()[2].inputs,
              std::vector<int>{1}); // the second filter reads the first's output
    EXPECT_EQ(chain->dependencyRadius(), 3 + 3 + 6 + 6);

    auto message = [](const std::string& spec)
    {
        try
        {
            FilterRegistry::create(spec);
        }
        catch (const std::invalid_argument& e)
        {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message("gausian").find("unknown filter 'gausian' (known: "), std::string::npos);
    EXPECT_NE(message("gausian").find("gaussian"), std::string::npos);
    EXPECT_EQ(message("gaussian:sigma=40"), "gaussian: parameter sigma = 40 is not a number in [0, 32]");
    EXPECT_EQ(message("gaussian:sigma=abc"), "gaussian: parameter sigma = 'abc' is not a number in [0, 32]");
    EXPECT_EQ(message("gaussian:radius=3"), "gaussian: unknown parameter 'radius' (known: sigma)");
    EXPECT_EQ(message("gaussian:sigma"), "gaussian: parameter 'sigma' has no value (write key=value)");
    EXPECT_EQ(message(" "), "empty filter specification");
    EXPECT_EQ(message("gaussian:sigma=nan"), "gaussian: parameter sigma = nan is not a number in [0, 32]");
}

TEST(ImageFilterTest, FiltersRoundTripThroughOsgtAndOsgb)
{
    const std::string dir = loatest::freshDirectory("ImageFilterTest");
    osg::ref_ptr<FilterChain> chain = new FilterChain;
    osg::ref_ptr<GaussianFilter> a = new GaussianFilter, b = new GaussianFilter;
    a->setSigma(0.75f);
    b->setSigma(4.0f);
    chain->addFilter(a.get());
    chain->addFilter(b.get());
    for (const char* ext : {"osgt", "osgb"})
    {
        const std::string first = dir + "/chain-first." + ext, second = dir + "/chain-second." + ext;
        ASSERT_TRUE(osgDB::writeObjectFile(*chain, first));
        osg::ref_ptr<FilterChain> back = dynamic_cast<FilterChain*>(osgDB::readRefObjectFile(first).get());
        ASSERT_TRUE(back.valid()) << first;
        EXPECT_EQ(back->getParameterString(), chain->getParameterString());
        ASSERT_TRUE(osgDB::writeObjectFile(*back, second));
        std::ifstream fa(first, std::ios::binary), fb(second, std::ios::binary);
        std::stringstream sa, sb;
        sa << fa.rdbuf();
        sb << fb.rdbuf();
        EXPECT_EQ(sa.str(), sb.str()) << ext;
    }
    // A file with an impossible sigma reads, and is refused where it would be used.
    const std::string bad = dir + "/bad.osgt";
    {
        std::ifstream in(dir + "/chain-first.osgt");
        std::stringstream s;
        s << in.rdbuf();
        std::string text = s.str();
        const std::string::size_type at = text.find("Sigma 4");
        ASSERT_NE(at, std::string::npos) << text;
        text.replace(at, 7, "Sigma 4000");
        std::ofstream(bad) << text;
    }
    osg::ref_ptr<FilterChain> back = dynamic_cast<FilterChain*>(osgDB::readRefObjectFile(bad).get());
    ASSERT_TRUE(back.valid());
    try
    {
        back->checkParameters();
        FAIL();
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_EQ(std::string(e.what()), "gaussian: parameter sigma = 4000 is not a number in [0, 32]");
    }
}
