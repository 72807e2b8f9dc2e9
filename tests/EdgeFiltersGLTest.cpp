// The edge filters' GPU passes (shaders/loa_filter_sobel, loa_filter_canny) against their CPU
// references: Sobel magnitudes to float rounding on a photograph crop and a procedural image
// under every wrap mode; Canny edge maps identical to the bounded-hysteresis CPU reference;
// weak chains shorter than the hysteresis iteration count matching exact hysteresis and longer
// ones cut; a tiled run equal to the full run on the listed tiles.
#include <osgLoA/filtering/CannyFilter>
#include <osgLoA/filtering/GpuFilterEngine>
#include <osgLoA/filtering/SobelFilter>

#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <cmath>
#include <iostream>

using namespace osgLoA;

namespace
{
using GpuFixture = loatest::GpuFilterFixture;

/** Procedural content: a sinusoid, a hard diagonal edge, a disc, a gradient, noise and a
 *  varying alpha; 45 x 37 so that tiles are partial. */
FilterImage proceduralImage(int w = 45, int h = 37)
{
    FilterImage img(w, h);
    unsigned seed = 4242;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            seed = seed * 1664525u + 1013904223u;
            const float n = float(seed >> 8) / float(1u << 24) - 0.5f;
            const float dx = float(x) - 0.6f * float(w), dy = float(y) - 0.4f * float(h);
            const float disc = dx * dx + dy * dy < 64.0f ? 0.3f : 0.0f;
            const float r = 0.45f + 0.3f * std::sin(0.4f * float(x)) * std::cos(0.27f * float(y)) + 0.04f * n;
            const float g = (float(x) + 0.7f * float(y) > 30.0f ? 0.8f : 0.2f) - disc;
            const float b = float(y) / float(h) + 0.06f * n + disc;
            img.set(x, y, osg::Vec4f(r, g, b, 0.25f + 0.5f * float(x) / float(w)));
        }
    return img;
}

std::vector<std::pair<std::string, FilterImage>> testImages()
{
    std::vector<std::pair<std::string, FilterImage>> images;
    const FilterImage photo = loatest::photoCrop("astronaut.png", 180, 60, 64, 48);
    if (!photo.empty())
        images.push_back({"astronaut", photo});
    else
        std::cout << "astronaut.png not found: photograph case skipped" << std::endl;
    images.push_back({"procedural", proceduralImage()});
    return images;
}

const WrapMode kModes[3] = {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror};

/** Texels whose R differs, and whether alpha passed through exactly. */
int differing(const FilterImage& a, const FilterImage& b)
{
    int n = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x)
            n += a.get(x, y)[0] != b.get(x, y)[0];
    return n;
}

int edgeCount(const FilterImage& edges)
{
    int n = 0;
    for (int y = 0; y < edges.height(); ++y)
        for (int x = 0; x < edges.width(); ++x)
            n += edges.get(x, y)[0] == 0.0f;
    return n;
}

/** One context and engine for the suite (llvmpipe compiles each program once). */
class EdgeFiltersGLTest : public ::testing::Test
{
protected:
    static void SetUpTestSuite() { s_gpu = new GpuFixture; }
    static void TearDownTestSuite()
    {
        delete s_gpu;
        s_gpu = nullptr;
    }
    GpuFixture& gpu() { return *s_gpu; }
    static GpuFixture* s_gpu;
};
GpuFixture* EdgeFiltersGLTest::s_gpu = nullptr;
} // namespace

TEST_F(EdgeFiltersGLTest, SobelGpuMatchesTheCpuReference)
{
    osg::ref_ptr<SobelFilter> f = new SobelFilter;
    for (const auto& [name, img] : testImages())
        for (WrapMode m : kModes)
        {
            const ImageBorder border(m, m == WrapMode::Clamp ? WrapMode::Repeat : m);
            f->setThreshold(0.0f);
            const FilterImage cpu = f->apply(img, border);
            const FilterImage onGpu = gpu().engine->filter(*f, img, border);
            const float d = FilterImage::maxAbsDifference(cpu, onGpu, true);
            std::cout << "sobel " << name << " " << ImageBorder::name(border.s) << "/"
                      << ImageBorder::name(border.t) << ": max |M diff| " << d << std::endl;
            // The same float operations in a different order (the driver may fuse multiply-adds):
            // M <= sqrt(2), so a few ulps of 2 are ~1e-6; 1e-5 leaves room. Alpha is copied.
            EXPECT_LE(d, 1e-5f) << name;
            // Threshold mode: texels differ only where M lies within that rounding of t.
            f->setThreshold(0.1f);
            const FilterImage ecpu = f->apply(img, border), egpu = gpu().engine->filter(*f, img, border);
            int unexplained = 0;
            for (int y = 0; y < img.height(); ++y)
                for (int x = 0; x < img.width(); ++x)
                    if (ecpu.get(x, y)[0] != egpu.get(x, y)[0] && std::fabs(cpu.get(x, y)[0] - 0.1f) > 1e-5f)
                        ++unexplained;
            EXPECT_EQ(unexplained, 0) << name;
            EXPECT_GT(edgeCount(ecpu), 0) << name;
            float alpha = 0;
            for (int y = 0; y < img.height(); ++y)
                for (int x = 0; x < img.width(); ++x)
                    alpha = std::max(alpha, std::fabs(egpu.get(x, y)[3] - img.get(x, y)[3]));
            EXPECT_EQ(alpha, 0.0f);
        }
}

TEST_F(EdgeFiltersGLTest, CannyGpuEqualsTheBoundedHysteresisReference)
{
    osg::ref_ptr<CannyFilter> f = new CannyFilter; // sigma 1, 0.1 / 0.2, 8 iterations
    for (const auto& [name, img] : testImages())
        for (WrapMode m : kModes)
        {
            const ImageBorder border(m, m == WrapMode::Clamp ? WrapMode::Mirror : m);
            const FilterImage onGpu = gpu().engine->filter(*f, img, border);
            const FilterImage bounded = f->applyBoundedHysteresis(img, border, f->getHysteresisIterations());
            const FilterImage exact = f->apply(img, border);
            const int d = differing(onGpu, bounded);
            std::cout << "canny " << name << " " << ImageBorder::name(border.s) << "/"
                      << ImageBorder::name(border.t) << ": " << edgeCount(onGpu) << " edge texels, " << d
                      << " differ from the bounded reference, " << differing(onGpu, exact)
                      << " from exact hysteresis" << std::endl;
            // After the 8-bit rounding every step is integer arithmetic, exact on both sides;
            // the smoothing is computed operation for operation alike (`precise` on the GPU).
            EXPECT_EQ(d, 0) << name;
            EXPECT_GT(edgeCount(onGpu), 20) << name;
            float alpha = 0;
            for (int y = 0; y < img.height(); ++y)
                for (int x = 0; x < img.width(); ++x)
                    alpha = std::max(alpha, std::fabs(onGpu.get(x, y)[3] - img.get(x, y)[3]));
            EXPECT_EQ(alpha, 0.0f);
        }
}

TEST_F(EdgeFiltersGLTest, HysteresisChainsWithinTheIterationCountMatchExactHysteresis)
{
    // Rows 0..5 black, rows 6..11 at 0.5 for x < 20 (a strong step: M = 0.5 >= high 0.4) and
    // 0.25 beyond (weak: 0.2 <= M < 0.4), 64 wide. The weak part of row 5 starts two steps from
    // the strong part (EdgeFiltersTest: (20, 6) then (21, 5)) and runs to x = 63: texel
    // (21 + i, 5) is i + 2 steps away, the chain's far end 44 steps.
    FilterImage img(64, 12);
    for (int y = 0; y < 12; ++y)
        for (int x = 0; x < 64; ++x)
        {
            const float v = y < 6 ? 0.0f : (x < 20 ? 0.5f : 0.25f);
            img.set(x, y, osg::Vec4f(v, v, v, 1.0f));
        }
    osg::ref_ptr<CannyFilter> f = new CannyFilter;
    f->setSigma(0.0f);
    f->setLow(0.2f);
    f->setHigh(0.4f);
    const ImageBorder border;
    const FilterImage exact = f->apply(img, border);
    for (int n : {0, 8, 64})
    {
        f->setHysteresisIterations(n);
        const FilterImage onGpu = gpu().engine->filter(*f, img, border);
        EXPECT_EQ(differing(onGpu, f->applyBoundedHysteresis(img, border, n)), 0) << n;
        int weakKept = 0;
        for (int x = 21; x < 64; ++x)
            weakKept += onGpu.get(x, 5)[0] == 0.0f;
        std::cout << "chain of 43 weak texels, " << n << " iterations: " << weakKept << " kept on the GPU, "
                  << differing(onGpu, exact) << " texels differ from exact hysteresis" << std::endl;
        if (n == 64)
        {
            EXPECT_EQ(differing(onGpu, exact), 0);
            EXPECT_EQ(weakKept, 43);
        }
        else if (n == 8)
        {
            EXPECT_EQ(weakKept, n - 1); // distances 2..8: x = 21..27
            EXPECT_EQ(differing(onGpu, exact), 43 - (n - 1));
        }
        else
        {
            // No propagation: every weak texel is dropped: the 43 of row 5, (20, 6), and the
            // weak vertical edge x = 19, y = 7..11 below the strong (19, 6).
            EXPECT_EQ(weakKept, 0);
            EXPECT_EQ(differing(onGpu, exact), 43 + 1 + 5);
        }
    }
}

TEST_F(EdgeFiltersGLTest, TiledRunMatchesTheFullRunOnTheListedTiles)
{
    // dependencyRadius = 2 * 3 + 2 + 8 = 16 texels: the engine dilates the listed tiles by that
    // through the passes; a border tile (its halo wraps) and an inner one.
    const FilterImage img = proceduralImage(48, 40);
    osg::ref_ptr<CannyFilter> f = new CannyFilter;
    ASSERT_EQ(f->dependencyRadius(), 16);
    GpuFilterEngine& e = *gpu().engine;
    GpuFilterEngine::Region r;
    r.x = 3;
    r.y = 5;
    r.width = img.width();
    r.height = img.height();
    r.border = ImageBorder(WrapMode::Repeat, WrapMode::Clamp);
    const unsigned src = e.createAtlas(56, 48), full = e.createAtlas(56, 48), part = e.createAtlas(56, 48);
    e.upload(src, r, img);
    e.upload(part, r, FilterImage(img.width(), img.height(), osg::Vec4f(-1, -1, -1, -1)));
    const std::vector<GpuFilterEngine::Tile> tiles = {{0, 0, 0}, {0, 3, 2}};
    e.run(*f, src, full, {r});
    const GpuFilterEngine::RunStats stats = e.run(*f, src, part, {r}, &tiles);
    const FilterImage a = e.download(full, r), b = e.download(part, r);
    int differ = 0, edges = 0;
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x)
            if ((x < 8 && y < 8) || (x / 8 == 3 && y / 8 == 2))
            {
                for (int c = 0; c < 4; ++c)
                    differ += a.texel(x, y)[c] != b.texel(x, y)[c];
                edges += a.texel(x, y)[0] == 0.0f;
            }
    EXPECT_EQ(differ, 0);
    EXPECT_GT(edges, 0); // the tiles hold edges, so the comparison means something
    EXPECT_EQ(stats.outputTexels, 128u);
    EXPECT_EQ(b.get(20, 20)[0], -1.0f) << "an unlisted tile was written";
    // The full run equals the CPU's bounded reference on the same region.
    EXPECT_EQ(differing(a, f->applyBoundedHysteresis(img, r.border, 8)), 0);
    for (unsigned atlas : {src, full, part})
        e.destroyAtlas(atlas);
}
