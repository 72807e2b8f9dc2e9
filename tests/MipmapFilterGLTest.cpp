// MipmapFilter's GPU path: every level filtered by GpuFilterEngine in one pyramid atlas
// matches the CPU path.
#include <osgLoA/filtering/GaussianFilter>
#include <osgLoA/filtering/GpuFilterEngine>
#include <osgLoA/filtering/MipmapFilter>
#include <osgLoA/render/HeadlessContext>

#include "support/TestSupport.h"

#include <osg/Geode>
#include <osg/Geometry>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>

using namespace osgLoA;

namespace
{
using GpuFixture = loatest::GpuFilterFixture;

FilterImage texturedImage(int w, int h)
{
    FilterImage img(w, h);
    unsigned seed = 777;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            seed = seed * 1664525u + 1013904223u;
            const float n = float(seed >> 8) / float(1u << 24);
            img.set(x, y,
                    osg::Vec4f(0.5f + 0.4f * std::sin(0.7f * float(x)) * std::cos(0.23f * float(y)),
                               ((x / 6 + y / 4) % 2) ? 0.85f : 0.2f, n, 0.5f + 0.5f * float(y) / float(h)));
        }
    return img;
}

/** A CPU-only filter (no GPU passes): inverts RGB. */
class InvertFilter : public ImageFilter
{
public:
    InvertFilter() = default;
    InvertFilter(const InvertFilter& o, const osg::CopyOp& c = osg::CopyOp::SHALLOW_COPY) : ImageFilter(o, c)
    {
    }
    META_Object(loatest, InvertFilter) std::string filterName() const override { return "test-invert"; }
    FilterImage apply(const FilterImage& in, const ImageBorder&) const override
    {
        FilterImage out = in;
        for (std::size_t i = 0; i < out.data().size(); ++i)
            if (i % 4 != 3) out.data()[i] = 1.0f - out.data()[i];
        return out;
    }
};
} // namespace

// Levels of 45x37 .. 1x1 (partial tiles, odd sizes, 1-texel levels) and of a 64x4 strip (more
// stacked levels than level 0 is tall), every wrap mode: within 2/255 of the CPU path before
// quantization, and the 8-bit levels at most 1 apart.
TEST(MipmapFilterGLTest, GpuLevelsMatchTheCpuPath)
{
    GpuFixture gpu;
    osg::ref_ptr<GaussianFilter> g = new GaussianFilter;
    g->setSigma(2.0f);
    osg::ref_ptr<MipmapFilter> cpu = new MipmapFilter(g.get());
    osg::ref_ptr<MipmapFilter> onGpu = new MipmapFilter(g.get());
    onGpu->setEngine(gpu.engine.get());
    struct Size
    {
        int w, h;
    };
    float worst = 0.0f;
    for (const Size s : {Size{45, 37}, Size{64, 4}})
        for (WrapMode mode : {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror})
        {
            const FilterImage image = texturedImage(s.w, s.h);
            const ImageBorder border(mode, mode == WrapMode::Clamp ? WrapMode::Repeat : mode);
            const std::vector<FilterImage> a = cpu->filterLevels(image, border);
            const std::vector<FilterImage> b = onGpu->filterLevels(image, border);
            ASSERT_EQ(a.size(), b.size());
            for (std::size_t k = 0; k < a.size(); ++k)
            {
                const float d = FilterImage::maxAbsDifference(a[k], b[k], true);
                worst = std::max(worst, d);
                EXPECT_LE(d, 2.0f / 255.0f)
                    << s.w << "x" << s.h << " " << ImageBorder::name(mode) << " level " << k;
            }
            MipmapFilter::Result r;
            osg::ref_ptr<osg::Image> ia = cpu->filterImage(*image.toImage(GL_FLOAT), border);
            osg::ref_ptr<osg::Image> ib = onGpu->filterImage(*image.toImage(GL_FLOAT), border, &r);
            EXPECT_EQ(r.source, MipmapFilter::GPU);
            ASSERT_EQ(ia->getTotalSizeInBytesIncludingMipmaps(), ib->getTotalSizeInBytesIncludingMipmaps());
            int maxByte = 0;
            for (unsigned i = 0; i < ia->getTotalSizeInBytesIncludingMipmaps(); ++i)
                maxByte = std::max(maxByte, std::abs(int(ia->data()[i]) - int(ib->data()[i])));
            EXPECT_LE(maxByte, 1);
        }
    std::printf(
        "[ measured ] GPU vs CPU pyramid levels, gaussian sigma 2: max |diff| %.3g (bar 2/255 = %.3g)\n",
        worst, 2.0 / 255.0);
}

// A filter without GPU passes runs on the CPU even with an engine; GPU results go through the
// cache like CPU results.
TEST(MipmapFilterGLTest, CpuOnlyFilterAndCacheWithAnEngine)
{
    GpuFixture gpu;
    osg::ref_ptr<InvertFilter> inv = new InvertFilter;
    osg::ref_ptr<MipmapFilter> mf = new MipmapFilter(inv.get());
    mf->setEngine(gpu.engine.get());
    MipmapFilter::Result r;
    mf->filterImage(*texturedImage(16, 8).toImage(), ImageBorder(), &r);
    EXPECT_EQ(r.source, MipmapFilter::CPU);

    osg::ref_ptr<FilterCache> cache = new FilterCache(loatest::freshDirectory("MipmapFilterGL.cache"));
    osg::ref_ptr<GaussianFilter> g = new GaussianFilter;
    osg::ref_ptr<MipmapFilter> cached = new MipmapFilter(g.get(), cache.get());
    cached->setEngine(gpu.engine.get());
    osg::ref_ptr<osg::Image> img = texturedImage(40, 40).toImage();
    osg::ref_ptr<osg::Image> first = cached->filterImage(*img, ImageBorder(), &r);
    EXPECT_EQ(r.source, MipmapFilter::GPU);
    EXPECT_TRUE(r.stored);
    osg::ref_ptr<osg::Image> second = cached->filterImage(*img, ImageBorder(), &r);
    EXPECT_EQ(r.source, MipmapFilter::CACHE);
    EXPECT_EQ(std::memcmp(first->data(), second->data(), first->getTotalSizeInBytesIncludingMipmaps()), 0);
}

// Timing on a stated size (printed; llvmpipe on a shared 2-core machine, no bar).
TEST(MipmapFilterGLTest, TimingGaussian512)
{
    GpuFixture gpu;
    osg::ref_ptr<GaussianFilter> g = new GaussianFilter;
    g->setSigma(2.0f);
    osg::ref_ptr<MipmapFilter> mf = new MipmapFilter(g.get());
    mf->setEngine(gpu.engine.get());
    const FilterImage image = texturedImage(512, 512);
    mf->filterLevels(image, ImageBorder()); // warm-up: compiles the passes
    const auto t0 = std::chrono::steady_clock::now();
    mf->filterLevels(image, ImageBorder(WrapMode::Repeat, WrapMode::Repeat));
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    std::printf(
        "[ measured ] gaussian sigma 2, 512x512 pyramid (10 levels), GPU engine (upload, run, download): "
        "%.1f ms\n",
        ms);
}

// loa-prefilter --gpu fills the cache with the same pyramids as the CPU run, within one 8-bit
// step (the 2/255 bar; measured: identical bytes on llvmpipe).
TEST(MipmapFilterGLTest, LoaPrefilterGpuMatchesCpu)
{
    const std::string exe = LOA_PREFILTER_EXE;
    if (!osgDB::fileExists(exe)) GTEST_SKIP() << "loa-prefilter not built: " << exe;
    const std::string dir = loatest::freshDirectory("MipmapFilterGL.prefilter");
    osg::ref_ptr<osg::Group> root = new osg::Group;
    const osg::Texture::WrapMode modes[] = {osg::Texture::REPEAT, osg::Texture::CLAMP_TO_EDGE,
                                            osg::Texture::MIRROR};
    for (int i = 0; i < 3; ++i)
    {
        osg::ref_ptr<osg::Texture2D> t =
            new osg::Texture2D(texturedImage(24 + 7 * i, 20 - 3 * i).toImage().get());
        t->setWrap(osg::Texture::WRAP_S, modes[i]);
        t->setWrap(osg::Texture::WRAP_T, modes[(i + 1) % 3]);
        osg::ref_ptr<osg::Geode> g = new osg::Geode;
        g->addDrawable(osg::createTexturedQuadGeometry(osg::Vec3(float(i), 0, 0), osg::X_AXIS, osg::Y_AXIS));
        g->getOrCreateStateSet()->setTextureAttributeAndModes(0, t.get());
        root->addChild(g.get());
    }
    ASSERT_TRUE(osgDB::writeNodeFile(*root, dir + "/model.osgb"));
    std::string out;
    const std::string base = "'" + exe + "' '" + dir + "/model.osgb' --filter gaussian:sigma=1.5 --cache '";
    ASSERT_EQ(loatest::run(base + dir + "/cpu'", out), 0) << out;
    ASSERT_EQ(loatest::run(base + dir + "/gpu' --gpu --export '" + dir + "/gpu.osgb'", out), 0) << out;
    EXPECT_NE(out.find("on the GPU"), std::string::npos) << out;
    EXPECT_NE(out.find("3 filtered"), std::string::npos) << out;
    osg::ref_ptr<FilterCache> cpu = new FilterCache(dir + "/cpu"), gpu = new FilterCache(dir + "/gpu");
    osg::ref_ptr<GaussianFilter> g = new GaussianFilter;
    g->setSigma(1.5f);
    osg::ref_ptr<osg::Node> back = osgDB::readNodeFile(dir + "/gpu.osgb");
    ASSERT_TRUE(back.valid());
    int compared = 0;
    for (unsigned i = 0; i < root->getNumChildren(); ++i)
    {
        osg::Texture2D* t = dynamic_cast<osg::Texture2D*>(
            root->getChild(i)->getStateSet()->getTextureAttribute(0, osg::StateAttribute::TEXTURE));
        const FilterCacheKey key = FilterCache::makeKey(*t->getImage(), ImageBorder::of(*t), *g);
        osg::ref_ptr<osg::Image> a = cpu->load(key), b = gpu->load(key);
        ASSERT_TRUE(a.valid() && b.valid());
        ASSERT_EQ(a->getTotalSizeInBytesIncludingMipmaps(), b->getTotalSizeInBytesIncludingMipmaps());
        int maxByte = 0;
        for (unsigned k = 0; k < a->getTotalSizeInBytesIncludingMipmaps(); ++k)
            maxByte = std::max(maxByte, std::abs(int(a->data()[k]) - int(b->data()[k])));
        EXPECT_LE(maxByte, 1) << i;
        ++compared;
    }
    EXPECT_EQ(compared, 3);
}
