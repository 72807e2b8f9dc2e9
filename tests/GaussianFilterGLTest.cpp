// The GPU filter engine with the Gaussian filter: GPU passes against the CPU reference (all
// wrap modes), tiled runs equal full runs on the tiles they cover, the tile cache skips filtered
// tiles, and a filter without GPU passes is refused with a clear error.
#include <osgLoA/filtering/GaussianFilter>
#include <osgLoA/filtering/GpuFilterEngine>
#include <osgLoA/render/HeadlessContext>

#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace osgLoA;

namespace
{
using GpuFixture = loatest::GpuFilterFixture;

/** Deterministic texture-like content: sinusoids of several frequencies, a hard edge and noise. */
FilterImage testImage(int w, int h)
{
    FilterImage img(w, h);
    unsigned seed = 12345;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            seed = seed * 1664525u + 1013904223u;
            const float n = float(seed >> 8) / float(1u << 24);
            const float r = 0.5f + 0.4f * std::sin(0.3f * float(x)) * std::cos(0.17f * float(y));
            const float g = x > w / 2 ? 0.9f : 0.1f;
            img.set(x, y, osg::Vec4f(r, g, n, 0.25f + 0.5f * float(x) / float(w)));
        }
    return img;
}
} // namespace

TEST(GaussianFilterGLTest, GpuPassesMatchTheCpuReferenceForEveryWrapMode)
{
    GpuFixture gpu;
    // 45x37: sizes not multiple of the 8x8 tile, so partial tiles are exercised.
    const FilterImage img = testImage(45, 37);
    osg::ref_ptr<GaussianFilter> f = new GaussianFilter;
    f->setSigma(2.5f);
    for (WrapMode s : {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror})
        for (WrapMode t : {WrapMode::Repeat, WrapMode::Mirror})
        {
            const ImageBorder border(s, t);
            const FilterImage cpu = f->apply(img, border);
            const FilterImage out = gpu.engine->filter(*f, img, border);
            // Both sum the same float products in the same order; only fused multiply-adds and the
            // driver's float rounding differ: 1e-5 is far below 8-bit resolution (1/255).
            EXPECT_LT(FilterImage::maxAbsDifference(cpu, out, true), 1e-5f)
                << ImageBorder::name(s) << "/" << ImageBorder::name(t);
            // Alpha passes through unchanged.
            EXPECT_FLOAT_EQ(out.get(10, 10)[3], img.get(10, 10)[3]);
        }
}

TEST(GaussianFilterGLTest, TiledRunsFilterOnlyTheListedTilesAndMatchTheFullRun)
{
    GpuFixture gpu;
    const FilterImage img = testImage(64, 48);
    osg::ref_ptr<GaussianFilter> f = new GaussianFilter;
    f->setSigma(3.0f); // radius 9: each pass reaches beyond a neighbouring tile
    const ImageBorder border(WrapMode::Repeat, WrapMode::Clamp);
    const FilterImage cpu = f->apply(img, border);

    GpuFilterEngine& e = *gpu.engine;
    GpuFilterEngine::Region r;
    r.x = 5; // not at the atlas origin
    r.y = 3;
    r.width = img.width();
    r.height = img.height();
    r.border = border;
    const unsigned src = e.createAtlas(80, 60), dst = e.createAtlas(80, 60);
    e.upload(src, r, img);
    e.upload(dst, r, FilterImage(img.width(), img.height(), osg::Vec4f(-1, -1, -1, -1)));
    // Tile (0, 0) at the left border (its halo wraps to the right edge) and tile (4, 3).
    const std::vector<GpuFilterEngine::Tile> tiles = {{0, 0, 0}, {0, 4, 3}};
    GpuFilterEngine::TileCache cache;
    const GpuFilterEngine::RunStats first = e.run(*f, src, dst, {r}, &tiles, &cache);
    EXPECT_EQ(first.outputTexels, 2u * 64u);
    // Two passes, each dispatched once for border tiles (the listed tiles touch the region's
    // border, so no interior variant runs for the second pass) and possibly once for interior ones.
    EXPECT_GE(first.passes, 2u);
    EXPECT_LE(first.passes, 4u);
    // The horizontal pass covers the tiles' rows dilated by 9 texels: 2 tile rows each.
    EXPECT_GT(first.tiles, 2u);
    const FilterImage out = e.download(dst, r);
    int filtered = 0;
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x)
        {
            const bool listed = (x < 8 && y < 8) || (x / 8 == 4 && y / 8 == 3);
            if (listed)
            {
                ++filtered;
                for (int c = 0; c < 4; ++c)
                    EXPECT_NEAR(out.texel(x, y)[c], cpu.texel(x, y)[c], 1e-5f) << x << "," << y;
            }
            else
                EXPECT_EQ(out.texel(x, y)[0], -1.0f) << "texel " << x << "," << y << " was written";
        }
    EXPECT_EQ(filtered, 128);

    // The same tiles again: all cached, nothing dispatched.
    const GpuFilterEngine::RunStats second = e.run(*f, src, dst, {r}, &tiles, &cache);
    EXPECT_EQ(second.passes, 0u);
    EXPECT_EQ(second.cachedTiles, 2u);
    EXPECT_EQ(cache.doneCount(1, 0), 2u);
}

TEST(GaussianFilterGLTest, RefusesFiltersWithoutGpuPassesAndBadRegions)
{
    GpuFixture gpu;
    struct CpuOnly : public GaussianFilter
    {
        std::vector<GpuFilterPass> gpuPasses() const override { return {}; }
        std::string filterName() const override { return "cpu-only"; }
    };
    osg::ref_ptr<CpuOnly> f = new CpuOnly;
    try
    {
        gpu.engine->filter(*f, testImage(8, 8), ImageBorder());
        FAIL() << "no error";
    }
    catch (const GpuFilterError& e)
    {
        EXPECT_NE(std::string(e.what()).find("'cpu-only' has no GPU implementation"), std::string::npos)
            << e.what();
    }
    const unsigned a = gpu.engine->createAtlas(16, 16);
    GpuFilterEngine::Region r;
    r.width = 20;
    r.height = 4;
    EXPECT_THROW(gpu.engine->upload(a, r, FilterImage(20, 4)), GpuFilterError);
    EXPECT_THROW(gpu.engine->createAtlas(0, 5), GpuFilterError);
}

TEST(GaussianFilterGLTest, AShaderThatFailsToCompileNamesThePass)
{
    GpuFixture gpu;
    struct Broken : public GaussianFilter
    {
        std::vector<GpuFilterPass> gpuPasses() const override
        {
            std::vector<GpuFilterPass> p = GaussianFilter::gpuPasses();
            p[0].defines.clear(); // LOA_RADIUS undefined
            return p;
        }
    };
    osg::ref_ptr<Broken> f = new Broken;
    try
    {
        gpu.engine->filter(*f, testImage(8, 8), ImageBorder());
        FAIL() << "no error";
    }
    catch (const GpuFilterError& e)
    {
        EXPECT_NE(std::string(e.what()).find("loa_filter_gaussian.comp.glsl"), std::string::npos) << e.what();
    }
}
