// MipmapFilter (CPU path): per-level pre-filtering, paper 000 Eq. 2.
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/GaussianFilter>
#include <osgLoA/filtering/MipmapFilter>

#include "support/TestSupport.h"

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/ValueObject>
#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>

using osgLoA::FilterImage;
using osgLoA::ImageBorder;
using osgLoA::MipmapFilter;
using osgLoA::WrapMode;

namespace
{

/** A deterministic textured image: two crossing sinusoids of different periods, a few hard
 *  edges and hashed noise (so that every scale has structure and opposite borders differ). */
FilterImage texturedImage(int w, int h, unsigned seed = 1)
{
    FilterImage img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            unsigned n = (unsigned(x) * 73856093u) ^ (unsigned(y) * 19349663u) ^ (seed * 83492791u);
            n = (n ^ (n >> 13)) * 1274126177u;
            const float noise = float((n >> 8) & 0xffff) / 65535.0f - 0.5f;
            const float a = 0.5f + 0.3f * std::sin(0.9f * x + 0.2f * y) * std::cos(0.35f * y);
            const float edge = ((x / 5 + y / 7) % 2) ? 0.15f : -0.15f;
            img.set(
                x, y,
                osg::Vec4f(std::min(1.0f, std::max(0.0f, a + edge + 0.2f * noise)),
                           std::min(1.0f, std::max(0.0f, 0.4f + 0.4f * std::sin(0.13f * x * (1 + seed)) +
                                                             0.1f * noise)),
                           std::min(1.0f, std::max(0.0f, float(x) / float(w) * 0.8f + 0.1f * noise + edge)),
                           1.0f));
        }
    return img;
}

osg::ref_ptr<osgLoA::GaussianFilter> gaussian(float sigma)
{
    osg::ref_ptr<osgLoA::GaussianFilter> g = new osgLoA::GaussianFilter;
    g->setSigma(sigma);
    return g;
}

/** A difference-of-Gaussians-like filter (the edge part of paper 004 §3.1's abstraction):
 *  0.5 + 4 (G_1 - G_1.6), per channel; finite radius, CPU only. */
class DoGLikeFilter : public osgLoA::ImageFilter
{
public:
    DoGLikeFilter() = default;
    DoGLikeFilter(const DoGLikeFilter& o, const osg::CopyOp& c = osg::CopyOp::SHALLOW_COPY)
        : ImageFilter(o, c)
    {
    }
    META_Object(loatest, DoGLikeFilter) std::string filterName() const override { return "test-dog"; }
    FilterImage apply(const FilterImage& in, const ImageBorder& border) const override
    {
        const FilterImage a = osgLoA::GaussianFilter::blurAxis(
            osgLoA::GaussianFilter::blurAxis(in, osgLoA::GaussianFilter::weightsFor(1.0f), 0, border),
            osgLoA::GaussianFilter::weightsFor(1.0f), 1, border);
        const FilterImage b = osgLoA::GaussianFilter::blurAxis(
            osgLoA::GaussianFilter::blurAxis(in, osgLoA::GaussianFilter::weightsFor(1.6f), 0, border),
            osgLoA::GaussianFilter::weightsFor(1.6f), 1, border);
        FilterImage out(in.width(), in.height());
        for (int y = 0; y < in.height(); ++y)
            for (int x = 0; x < in.width(); ++x)
            {
                osg::Vec4f v = osg::Vec4f(0.5f, 0.5f, 0.5f, 0.0f) + (a.get(x, y) - b.get(x, y)) * 4.0f;
                v[3] = in.get(x, y)[3];
                out.set(x, y, v);
            }
        return out;
    }
};

/** Outputs values outside [0, 1] (to test quantization and clamping): 1.5 v - 0.25. */
class StretchFilter : public osgLoA::ImageFilter
{
public:
    StretchFilter() = default;
    StretchFilter(const StretchFilter& o, const osg::CopyOp& c = osg::CopyOp::SHALLOW_COPY)
        : ImageFilter(o, c)
    {
    }
    META_Object(loatest, StretchFilter) std::string filterName() const override { return "test-stretch"; }
    FilterImage apply(const FilterImage& in, const ImageBorder&) const override
    {
        FilterImage out = in;
        for (std::size_t i = 0; i < out.data().size(); ++i)
            if (i % 4 != 3) out.data()[i] = 1.5f * out.data()[i] - 0.25f;
        return out;
    }
};

/** An image tiled n x n (each tile mirrored the way GL_MIRRORED_REPEAT reads it when
 *  mirror is set). */
FilterImage tiled(const FilterImage& img, int n, bool mirror)
{
    const int w = img.width(), h = img.height();
    FilterImage out(w * n, h * n);
    const int c = n / 2;
    const ImageBorder b = mirror ? ImageBorder(WrapMode::Mirror, WrapMode::Mirror)
                                 : ImageBorder(WrapMode::Repeat, WrapMode::Repeat);
    for (int y = 0; y < h * n; ++y)
        for (int x = 0; x < w * n; ++x)
            out.set(x, y, img.fetch(x - c * w, y - c * h, b));
    return out;
}

FilterImage centre(const FilterImage& img, int n)
{
    const int w = img.width() / n, h = img.height() / n, c = n / 2;
    FilterImage out(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            out.set(x, y, img.get(x + c * w, y + c * h));
    return out;
}

FilterImage quantized(FilterImage img)
{
    img.quantize8();
    return img;
}

std::string photoPath(const std::string& name)
{
    for (const std::string& dir : {std::string(LOA_SOURCE_DIR) + "/data/cache/python3-skimage/",
                                   std::string(LOA_SOURCE_DIR) + "/../shared/data/images/"})
    {
        std::ifstream f(dir + name);
        if (f) return dir + name;
    }
    return std::string();
}

} // namespace

TEST(MipmapFilter, LevelCountAndSizes)
{
    EXPECT_EQ(MipmapFilter::levelCount(1, 1), 1);
    EXPECT_EQ(MipmapFilter::levelCount(2, 1), 2);
    EXPECT_EQ(MipmapFilter::levelCount(1024, 1024), 11);
    EXPECT_EQ(MipmapFilter::levelCount(37, 5), 6); // 37x5 18x2 9x1 4x1 2x1 1x1
    EXPECT_EQ(MipmapFilter::levelCount(1, 300), 9);
}

// Eq. 2: level k of the result is F(D^k(T)), exactly in floating point and to the 8-bit
// rounding in the osg::Image; and it is not D^k(F(T)) (filter first, then build the pyramid).
TEST(MipmapFilter, LevelKIsFilterOfDownsampledLevel)
{
    const FilterImage image = texturedImage(64, 48);
    const ImageBorder border(WrapMode::Clamp, WrapMode::Clamp);
    for (int which = 0; which < 2; ++which)
    {
        osg::ref_ptr<osgLoA::ImageFilter> filter;
        if (which == 0)
            filter = gaussian(1.5f);
        else
            filter = new DoGLikeFilter;
        SCOPED_TRACE(filter->filterName());
        osg::ref_ptr<MipmapFilter> mf = new MipmapFilter(filter.get());
        mf->setNumThreads(1);
        const std::vector<FilterImage> levels = mf->filterLevels(image, border);
        const std::vector<FilterImage> pyramid = image.mipPyramid();
        ASSERT_EQ(levels.size(), 7u); // 64x48 .. 1x1
        osg::ref_ptr<osg::Image> img = mf->filterImage(*image.toImage(GL_FLOAT), border);
        ASSERT_TRUE(img->isMipmap());
        const std::vector<FilterImage> stored = MipmapFilter::levelsOf(*img);
        ASSERT_EQ(stored.size(), levels.size());

        const std::vector<FilterImage> filterFirst = filter->apply(image, border).mipPyramid();
        for (std::size_t k = 0; k < levels.size(); ++k)
        {
            const FilterImage expected = filter->apply(pyramid[k], border);
            EXPECT_EQ(FilterImage::maxAbsDifference(levels[k], expected, true), 0.0f) << "level " << k;
            EXPECT_EQ(FilterImage::maxAbsDifference(stored[k], quantized(expected), true), 0.0f)
                << "level " << k;
            const double mean = FilterImage::meanAbsDifference(levels[k], filterFirst[k]);
            const float peak = FilterImage::maxAbsDifference(levels[k], filterFirst[k]);
            std::printf("[ measured ] %s level %zu (%dx%d): |F(D^k T) - D^k(F T)| mean %.4f max %.4f\n",
                        filter->filterName().c_str(), k, levels[k].width(), levels[k].height(), mean, peak);
            if (k == 0)
            {
                EXPECT_EQ(peak, 0.0f); // level 0 is F(T) either way
            }
            else if (k <= 3)
            {
                EXPECT_GT(mean, 0.01) << "per-level filtering must differ from filtering level 0 only";
            }
        }
    }
}

// A real photograph (skimage's chelsea, a 128x128 crop): the same two properties.
TEST(MipmapFilter, RealPhotographEq2)
{
    const std::string path = photoPath("chelsea.png");
    if (path.empty()) GTEST_SKIP() << "chelsea.png not found (run scripts/fetch-test-data)";
    osg::ref_ptr<osg::Image> photo = osgDB::readImageFile(path);
    ASSERT_TRUE(photo.valid()) << path;
    const FilterImage full = FilterImage::fromImage(*photo);
    FilterImage crop(128, 128);
    for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 128; ++x)
            crop.set(x, y, full.get(x + 150, y + 100));
    const ImageBorder border(WrapMode::Mirror, WrapMode::Mirror);
    osg::ref_ptr<DoGLikeFilter> dog = new DoGLikeFilter;
    osg::ref_ptr<MipmapFilter> mf = new MipmapFilter(dog.get());
    const std::vector<FilterImage> levels = mf->filterLevels(crop, border);
    const std::vector<FilterImage> pyramid = crop.mipPyramid();
    const std::vector<FilterImage> filterFirst = dog->apply(crop, border).mipPyramid();
    for (std::size_t k = 0; k < levels.size(); ++k)
    {
        EXPECT_EQ(FilterImage::maxAbsDifference(levels[k], dog->apply(pyramid[k], border)), 0.0f) << k;
        std::printf("[ measured ] chelsea DoG level %zu: |F(D^k T) - D^k(F T)| mean %.4f\n", k,
                    FilterImage::meanAbsDifference(levels[k], filterFirst[k]));
        if (k >= 1 && k <= 3)
        {
            EXPECT_GT(FilterImage::meanAbsDifference(levels[k], filterFirst[k]), 0.01);
        }
    }
}

// Wrap modes: each filtered level of a REPEAT texture equals the centre of the filtered tiling
// of that level (error 0: no seam where the texture repeats); MIRROR likewise with the mirrored
// tiling; a CLAMP texture is not forced to tile.
TEST(MipmapFilter, RepeatLevelsTileSeamlessly)
{
    const FilterImage image = texturedImage(40, 24, 3);
    const std::vector<FilterImage> pyramid = image.mipPyramid();
    osg::ref_ptr<osgLoA::GaussianFilter> g = gaussian(2.0f);
    const int r = osgLoA::GaussianFilter::radiusFor(2.0f);
    osg::ref_ptr<MipmapFilter> mf = new MipmapFilter(g.get());
    mf->setNumThreads(2);
    mf->setSplitLevels(true); // strips of rows: their halos are read through the wrap mode too
    for (WrapMode mode : {WrapMode::Repeat, WrapMode::Mirror})
    {
        SCOPED_TRACE(ImageBorder::name(mode));
        const std::vector<FilterImage> levels = mf->filterLevels(image, ImageBorder(mode, mode));
        for (std::size_t k = 0; k < levels.size(); ++k)
        {
            // Enough tiles that the centre tile's neighbourhood of radius r lies inside.
            const int m = std::min(pyramid[k].width(), pyramid[k].height());
            const int n = 2 * ((r + m - 1) / m) + 1;
            const FilterImage big = g->apply(tiled(pyramid[k], n, mode == WrapMode::Mirror),
                                             ImageBorder(WrapMode::Clamp, WrapMode::Clamp));
            EXPECT_EQ(FilterImage::maxAbsDifference(levels[k], centre(big, n), true), 0.0f) << "level " << k;
        }
    }
    const std::vector<FilterImage> clamped =
        mf->filterLevels(image, ImageBorder(WrapMode::Clamp, WrapMode::Clamp));
    const FilterImage big = g->apply(tiled(pyramid[0], 3, false), ImageBorder());
    const float d = FilterImage::maxAbsDifference(clamped[0], centre(big, 3));
    std::printf("[ measured ] clamp level 0 vs centre of filtered repeat tiling: max %.4f\n", d);
    EXPECT_GT(d, 0.05f);
}

// The result does not depend on the number of threads: levels in parallel for every registered
// filter (their default parameters); strips of rows with wrapped halos (setSplitLevels) for the
// Gaussian, whose CPU reference reads only within its radius.
TEST(MipmapFilter, ThreadCountDoesNotChangeTheResult)
{
    const FilterImage image = texturedImage(150, 90, 5);
    osg::ref_ptr<osgLoA::GaussianFilter> g = gaussian(2.0f);
    for (WrapMode mode : {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror})
    {
        const ImageBorder border(WrapMode::Clamp, mode);
        osg::ref_ptr<MipmapFilter> mf = new MipmapFilter(g.get());
        mf->setNumThreads(1);
        const std::vector<FilterImage> one = mf->filterLevels(image, border);
        for (bool split : {false, true})
            for (unsigned t : {2u, 3u, 8u})
            {
                mf->setNumThreads(t);
                mf->setSplitLevels(split);
                const std::vector<FilterImage> many = mf->filterLevels(image, border);
                ASSERT_EQ(many.size(), one.size());
                for (std::size_t k = 0; k < one.size(); ++k)
                    EXPECT_EQ(FilterImage::maxAbsDifference(one[k], many[k], true), 0.0f)
                        << ImageBorder::name(mode) << " threads " << t << " split " << split << " level "
                        << k;
            }
    }
    const FilterImage small = texturedImage(40, 28, 6);
    for (const std::string& name : osgLoA::FilterRegistry::names())
    {
        osg::ref_ptr<osgLoA::ImageFilter> f = osgLoA::FilterRegistry::create(name);
        osg::ref_ptr<MipmapFilter> mf = new MipmapFilter(f.get());
        const ImageBorder border(WrapMode::Mirror, WrapMode::Clamp);
        mf->setNumThreads(1);
        const std::vector<FilterImage> one = mf->filterLevels(small, border);
        mf->setNumThreads(3);
        const std::vector<FilterImage> three = mf->filterLevels(small, border);
        for (std::size_t k = 0; k < one.size(); ++k)
            EXPECT_EQ(FilterImage::maxAbsDifference(one[k], three[k], true), 0.0f) << name << " level " << k;
    }
}

// Quantization: every stored byte is round(clamp(v, 0, 1) * 255) of the float level.
TEST(MipmapFilter, QuantizesTo8Bits)
{
    const FilterImage image = texturedImage(16, 16, 7);
    osg::ref_ptr<StretchFilter> stretch = new StretchFilter;
    osg::ref_ptr<MipmapFilter> mf = new MipmapFilter(stretch.get());
    const std::vector<FilterImage> levels = mf->filterLevels(image, ImageBorder());
    osg::ref_ptr<osg::Image> img = mf->filterImage(*image.toImage(GL_FLOAT), ImageBorder());
    EXPECT_EQ(img->getPixelFormat(), GLenum(GL_RGBA));
    EXPECT_EQ(img->getDataType(), GLenum(GL_UNSIGNED_BYTE));
    EXPECT_EQ(img->getInternalTextureFormat(), GL_RGBA8);
    EXPECT_EQ(img->getNumMipmapLevels(), 5u);
    int clampedLow = 0, clampedHigh = 0;
    for (unsigned k = 0; k < img->getNumMipmapLevels(); ++k)
    {
        const unsigned char* p = img->getMipmapData(k);
        const std::vector<float>& v = levels[k].data();
        for (std::size_t i = 0; i < v.size(); ++i)
        {
            const long expected = std::lround(std::min(1.0f, std::max(0.0f, v[i])) * 255.0f);
            ASSERT_EQ(long(p[i]), expected) << "level " << k << " value " << i;
            clampedLow += v[i] < 0.0f;
            clampedHigh += v[i] > 1.0f;
        }
    }
    EXPECT_GT(clampedLow, 0);
    EXPECT_GT(clampedHigh, 0);
    // The mipmap offsets are the byte sizes of the levels before.
    const osg::Image::MipmapDataType& offsets = img->getMipmapLevels();
    ASSERT_EQ(offsets.size(), 4u);
    EXPECT_EQ(offsets[0], 16u * 16 * 4);
    EXPECT_EQ(offsets[1], 16u * 16 * 4 + 8 * 8 * 4);
    EXPECT_EQ(offsets[3], 16u * 16 * 4 + 8 * 8 * 4 + 4 * 4 * 4 + 2 * 2 * 4);
    EXPECT_EQ(img->getTotalSizeInBytesIncludingMipmaps(), 4u * (256 + 64 + 16 + 4 + 1));
}

// Odd and non-square sizes, 1-texel-wide levels and a 1x1 image.
TEST(MipmapFilter, OddNonSquareAndTinySizes)
{
    osg::ref_ptr<osgLoA::GaussianFilter> g = gaussian(1.0f);
    osg::ref_ptr<MipmapFilter> mf = new MipmapFilter(g.get());
    mf->setNumThreads(2);
    struct Size
    {
        int w, h;
    };
    for (const Size s : {Size{37, 5}, Size{5, 37}, Size{1, 9}, Size{33, 1}, Size{1, 1}, Size{3, 3}})
    {
        SCOPED_TRACE(std::to_string(s.w) + "x" + std::to_string(s.h));
        const FilterImage image = texturedImage(s.w, s.h, 9);
        const ImageBorder border(WrapMode::Repeat, WrapMode::Mirror);
        osg::ref_ptr<osg::Image> img = mf->filterImage(*image.toImage(GL_FLOAT), border);
        const std::vector<FilterImage> stored = MipmapFilter::levelsOf(*img);
        const std::vector<FilterImage> pyramid = image.mipPyramid();
        ASSERT_EQ(int(stored.size()), MipmapFilter::levelCount(s.w, s.h));
        ASSERT_EQ(stored.size(), pyramid.size());
        int w = s.w, h = s.h;
        for (std::size_t k = 0; k < stored.size(); ++k)
        {
            EXPECT_EQ(stored[k].width(), w);
            EXPECT_EQ(stored[k].height(), h);
            EXPECT_EQ(FilterImage::maxAbsDifference(stored[k], quantized(g->apply(pyramid[k], border)), true),
                      0.0f)
                << "level " << k;
            w = std::max(1, w / 2);
            h = std::max(1, h / 2);
        }
        EXPECT_EQ(stored.back().width(), 1);
        EXPECT_EQ(stored.back().height(), 1);
        if (s.w == 1 && s.h == 1)
        {
            EXPECT_FALSE(img->isMipmap()); // a single level: no mipmap data
        }
    }
}

// Bad input: clear errors naming what is wrong.
TEST(MipmapFilter, EmptyImageAndMissingFilterAreClearErrors)
{
    osg::ref_ptr<osgLoA::GaussianFilter> g = gaussian(1.0f);
    osg::ref_ptr<MipmapFilter> mf = new MipmapFilter(g.get());
    osg::ref_ptr<osg::Image> empty = new osg::Image;
    empty->setFileName("walls/brick.png");
    try
    {
        mf->filterImage(*empty, ImageBorder());
        FAIL() << "no exception";
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("walls/brick.png"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("empty (0x0)"), std::string::npos) << e.what();
    }
    EXPECT_THROW(mf->filterLevels(FilterImage(), ImageBorder()), std::invalid_argument);

    osg::ref_ptr<osg::Texture2D> noImage = new osg::Texture2D;
    noImage->setName("roof");
    try
    {
        mf->filterTexture(*noImage);
        FAIL() << "no exception";
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("texture 'roof' has no image"), std::string::npos) << e.what();
    }

    osg::ref_ptr<osg::Image> packed = new osg::Image;
    packed->allocateImage(4, 4, 1, GL_RGB, GL_UNSIGNED_SHORT_5_6_5);
    packed->setFileName("packed.dds");
    try
    {
        mf->filterImage(*packed, ImageBorder());
        FAIL() << "no exception";
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("packed.dds"), std::string::npos) << e.what();
    }

    osg::ref_ptr<MipmapFilter> none = new MipmapFilter;
    osg::ref_ptr<osg::Image> ok = texturedImage(4, 4).toImage();
    EXPECT_THROW(none->filterImage(*ok, ImageBorder()), std::invalid_argument);
    EXPECT_THROW(MipmapFilter::toMipmappedImage({}), std::invalid_argument);
    EXPECT_THROW(MipmapFilter::toMipmappedImage({FilterImage(4, 4), FilterImage(2, 2)}),
                 std::invalid_argument);
}

// filterTexture: a new texture with the filtered levels and the sampling state they need; the
// wrap modes are the original's and the original is untouched.
TEST(MipmapFilter, FilterTextureSetsSamplingState)
{
    osg::ref_ptr<osg::Image> src = texturedImage(32, 16, 2).toImage();
    src->setFileName("facade.png");
    osg::ref_ptr<osg::Texture2D> tex = new osg::Texture2D(src.get());
    tex->setName("facade");
    tex->setWrap(osg::Texture::WRAP_S, osg::Texture::REPEAT);
    tex->setWrap(osg::Texture::WRAP_T, osg::Texture::MIRROR);
    tex->setUseHardwareMipMapGeneration(true);
    tex->setResizeNonPowerOfTwoHint(true);
    tex->setFilter(osg::Texture::MIN_FILTER, osg::Texture::LINEAR);

    osg::ref_ptr<osgLoA::GaussianFilter> g = gaussian(1.0f);
    osg::ref_ptr<MipmapFilter> mf = new MipmapFilter(g.get());
    MipmapFilter::Result result;
    osg::ref_ptr<osg::Texture2D> out = mf->filterTexture(*tex, &result);
    EXPECT_EQ(result.source, MipmapFilter::CPU);
    EXPECT_EQ(out->getName(), "facade");
    EXPECT_EQ(out->getWrap(osg::Texture::WRAP_S), osg::Texture::REPEAT);
    EXPECT_EQ(out->getWrap(osg::Texture::WRAP_T), osg::Texture::MIRROR);
    EXPECT_EQ(out->getFilter(osg::Texture::MIN_FILTER), osg::Texture::LINEAR_MIPMAP_LINEAR);
    EXPECT_EQ(out->getFilter(osg::Texture::MAG_FILTER), osg::Texture::LINEAR);
    EXPECT_FALSE(out->getUseHardwareMipMapGeneration());
    EXPECT_FALSE(out->getResizeNonPowerOfTwoHint());
    ASSERT_NE(out->getImage(), nullptr);
    EXPECT_TRUE(out->getImage()->isMipmap());
    EXPECT_EQ(out->getImage()->getNumMipmapLevels(), 6u);
    EXPECT_EQ(out->getImage()->getName(), "facade.png");
    std::string spec;
    EXPECT_TRUE(out->getImage()->getUserValue("osgLoA.filter", spec));
    EXPECT_EQ(spec, "gaussian:sigma=1");
    // Filtered with the texture's modes.
    const std::vector<FilterImage> levels =
        mf->filterLevels(FilterImage::fromImage(*src), ImageBorder(WrapMode::Repeat, WrapMode::Mirror));
    EXPECT_EQ(
        FilterImage::maxAbsDifference(MipmapFilter::levelsOf(*out->getImage())[1], quantized(levels[1])),
        0.0f);
    // The original keeps its image and state.
    EXPECT_EQ(tex->getImage(), src.get());
    EXPECT_TRUE(tex->getUseHardwareMipMapGeneration());
    EXPECT_FALSE(src->isMipmap());
}

// An .osgb keeps the levels (written inline), and so reads back the same pyramid.
TEST(MipmapFilter, OsgbKeepsTheLevels)
{
    osg::ref_ptr<osg::Texture2D> tex = new osg::Texture2D(texturedImage(20, 12, 4).toImage().get());
    tex->setWrap(osg::Texture::WRAP_S, osg::Texture::REPEAT);
    osg::ref_ptr<osgLoA::GaussianFilter> g = gaussian(1.0f);
    osg::ref_ptr<MipmapFilter> mf = new MipmapFilter(g.get());
    osg::ref_ptr<osg::Texture2D> out = mf->filterTexture(*tex);
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(osg::createTexturedQuadGeometry(osg::Vec3(), osg::X_AXIS, osg::Y_AXIS));
    geode->getOrCreateStateSet()->setTextureAttributeAndModes(0, out.get());
    const std::string dir = loatest::freshDirectory("MipmapFilter.osgb");
    ASSERT_TRUE(osgDB::writeNodeFile(*geode, dir + "/quad.osgb"));
    osg::ref_ptr<osg::Node> back = osgDB::readNodeFile(dir + "/quad.osgb");
    ASSERT_TRUE(back.valid());
    osg::Texture2D* t = dynamic_cast<osg::Texture2D*>(
        back->getStateSet()->getTextureAttribute(0, osg::StateAttribute::TEXTURE));
    ASSERT_NE(t, nullptr);
    ASSERT_NE(t->getImage(), nullptr);
    ASSERT_TRUE(t->getImage()->isMipmap());
    const std::vector<FilterImage> a = MipmapFilter::levelsOf(*out->getImage()),
                                   b = MipmapFilter::levelsOf(*t->getImage());
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k)
        EXPECT_EQ(FilterImage::maxAbsDifference(a[k], b[k], true), 0.0f) << k;
    EXPECT_EQ(t->getFilter(osg::Texture::MIN_FILTER), osg::Texture::LINEAR_MIPMAP_LINEAR);
    EXPECT_FALSE(t->getUseHardwareMipMapGeneration());
}

// Timing of the CPU path on a stated size (printed; no bar: the machine is shared).
TEST(MipmapFilter, TimingGaussian256)
{
    const FilterImage image = texturedImage(256, 256, 11);
    osg::ref_ptr<osgLoA::GaussianFilter> g = gaussian(2.0f);
    osg::ref_ptr<MipmapFilter> mf = new MipmapFilter(g.get());
    struct Mode
    {
        unsigned threads;
        bool split;
    };
    for (const Mode m : {Mode{1, false}, Mode{2, false}, Mode{2, true}})
    {
        mf->setNumThreads(m.threads);
        mf->setSplitLevels(m.split);
        const auto t0 = std::chrono::steady_clock::now();
        mf->filterLevels(image, ImageBorder(WrapMode::Repeat, WrapMode::Repeat));
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        std::printf(
            "[ measured ] gaussian sigma 2, 256x256 pyramid (9 levels), CPU, %u thread(s)%s: %.1f ms\n",
            m.threads, m.split ? ", levels split into strips" : "", ms);
    }
}
