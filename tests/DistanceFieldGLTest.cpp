// DistanceField on the GPU (needs an OpenGL context: label gl): the render-to-texture passes
// against the CPU jump flooding (bit for bit) and the exact transform (the same bars as the CPU
// test), and the scene-graph node, which recomputes only after a change.
#include <osgLoA/interest/DistanceField>
#include <osgLoA/render/OffscreenRenderer>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <random>

using namespace osgLoA;
using DF = DistanceField;

namespace
{
osg::ref_ptr<OffscreenRenderer> smallRenderer()
{
    OffscreenRenderer::Settings s;
    s.width = 1; // the master camera draws nothing; the passes are pre-render cameras
    s.height = 1;
    return new OffscreenRenderer(s);
}

DF::Seeds randomSeeds(std::mt19937& rng, int w, int h, int count)
{
    DF::Seeds s(w, h);
    for (int i = 0; i < count; ++i)
        s.set(int(rng() % unsigned(w)), int(rng() % unsigned(h)));
    return s;
}

/** Nearest seeds bit for bit. Distances: the same float where the driver's sqrt is correctly
 *  rounded (llvmpipe; then bit for bit); GLSL 4.50 allows sqrt 3 ULP, so elsewhere the bar is
 *  4e-7 relative (3.4 ULP of a float). */
void expectSameAsCpu(const DF::Map& gpu, const DF::Map& cpu, bool exactSqrt, const std::string& what)
{
    ASSERT_EQ(gpu.width, cpu.width) << what;
    ASSERT_EQ(gpu.height, cpu.height) << what;
    std::size_t nearestDiffer = 0, distanceDiffer = 0;
    for (std::size_t i = 0; i < cpu.distance.size(); ++i)
    {
        nearestDiffer += gpu.nearest[i] != cpu.nearest[i] ? 1 : 0;
        const float g = gpu.distance[i], c = cpu.distance[i];
        const bool same =
            exactSqrt ? (g == c || (std::isinf(g) && std::isinf(c)))
                      : (std::isinf(c) ? std::isinf(g) : std::fabs(g - c) <= 4e-7f * std::max(c, 1.0f));
        distanceDiffer += same ? 0 : 1;
    }
    EXPECT_EQ(nearestDiffer, 0u) << what;
    EXPECT_EQ(distanceDiffer, 0u) << what;
}

const DF::Variant kVariants[] = {DF::JFA, DF::ONE_PLUS_JFA, DF::JFA_PLUS_2};
} // namespace

TEST(DistanceFieldGLTest, GpuPassesEqualTheCpuJumpFlooding)
{
    osg::ref_ptr<OffscreenRenderer> r = smallRenderer();
    const bool exactSqrt = r->getCapabilities().isSoftwareRenderer();
    std::mt19937 rng(3);
    struct Case
    {
        std::string name;
        DF::Seeds seeds;
        int maxDistance;
    };
    std::vector<Case> cases;
    cases.push_back({"64x48 random", randomSeeds(rng, 64, 48, 12), 0});
    // Widths that are not multiples of 4: the last packed texel is partly outside the grid.
    cases.push_back({"301x17 random", randomSeeds(rng, 301, 17, 6), 0});
    cases.push_back({"70x1 random", randomSeeds(rng, 70, 1, 3), 0});
    cases.push_back({"7x9 random", randomSeeds(rng, 7, 9, 2), 0});
    cases.push_back({"1x1 seed", randomSeeds(rng, 1, 1, 1), 0});
    cases.push_back({"1x70 random", randomSeeds(rng, 1, 70, 3), 0});
    cases.push_back({"40x40 no seed", DF::Seeds(40, 40), 0});
    cases.push_back({"256x256 limited to 20", randomSeeds(rng, 256, 256, 30), 20});
    DF::Seeds failing(16, 16); // plain JFA errs here (DistanceFieldTest)
    for (auto p : {std::pair<int, int>{11, 12}, {8, 7}, {1, 4}, {9, 12}})
        failing.set(p.first, p.second);
    cases.push_back({"16x16 JFA failure", failing, 0});
    for (const Case& c : cases)
        for (DF::Variant v : kVariants)
        {
            const std::string what = c.name + " " + DF::toString(v);
            const DF::Map gpu = DF::computeGPU(*r, c.seeds, v, c.maxDistance);
            expectSameAsCpu(gpu, DF::computeJFA(c.seeds, v, c.maxDistance), exactSqrt, what);
        }
}

TEST(DistanceFieldGLTest, GpuPassesMeetTheBarsAgainstTheExactTransform)
{
    // The bars of DistanceFieldTest.JumpFloodingMeetsTheBarsOnRandomSeeds: mean < 0.005 texel,
    // fraction off by > 1 texel < 0.1%, no unreached texel, never below the exact distance.
    osg::ref_ptr<OffscreenRenderer> r = smallRenderer();
    std::mt19937 rng(99);
    for (int t = 0; t < 2; ++t)
    {
        const DF::Seeds s = randomSeeds(rng, 256, 256, t == 0 ? 20 : 200);
        const DF::Map exact = DF::computeExact(s);
        for (DF::Variant v : kVariants)
        {
            const DF::Map gpu = DF::computeGPU(*r, s, v);
            const DF::Error e = DF::compare(gpu, exact);
            EXPECT_EQ(e.unreached, 0u) << DF::toString(v);
            EXPECT_LT(e.meanAbs, 0.005) << DF::toString(v);
            EXPECT_LT(e.fractionOverOne(), 0.001) << DF::toString(v);
            for (std::size_t i = 0; i < gpu.distance.size(); ++i)
                ASSERT_GE(gpu.distance[i], exact.distance[i] * (1.0f - 4e-7f));
        }
    }
}

TEST(DistanceFieldGLTest, TheNodeRecomputesOnlyAfterAChange)
{
    osg::ref_ptr<OffscreenRenderer> r = smallRenderer();
    osg::ref_ptr<DF> field = new DF;
    DF::checkCapabilities(r->getCapabilities(), 96, 64);
    const DF::Grid grid = DF::Grid::cover(osg::BoundingBoxd(0, 0, 0, 192, 128, 0), 2.0); // 96 x 64
    field->setGrid(grid);
    field->setRegions({new RegionOfInterest(RegionOfInterest::CIRCLES, {osg::Vec2d(40, 40)}, 6.0)});
    field->setReadBack(true);
    r->setSceneData(field.get());
    const unsigned passes = field->getNumPasses();
    ASSERT_EQ(passes, DF::steps(DF::ONE_PLUS_JFA, 96, 64).size() + 1); // + the distance pass

    r->renderImage();
    EXPECT_EQ(field->getNumComputations(), 1u);
    EXPECT_EQ(field->getNumPassesDrawn(), passes);
    // World units: texel distance x 2; the same as the CPU flooding of the same seeds.
    const DF::Map cpu = DF::computeJFA(field->getSeeds(), DF::ONE_PLUS_JFA);
    const DF::Map& map = field->getReadBackMap();
    ASSERT_EQ(map.distance.size(), cpu.distance.size());
    for (std::size_t i = 0; i < cpu.distance.size(); ++i)
        ASSERT_NEAR(map.distance[i], cpu.distance[i] * 2.0f, 1e-5f * std::max(1.0f, cpu.distance[i]));

    // Unchanged: three frames, no pass.
    for (int i = 0; i < 3; ++i)
        r->renderImage();
    EXPECT_EQ(field->getNumComputations(), 1u);
    EXPECT_EQ(field->getNumPassesDrawn(), passes);

    // Each kind of change: one computation in the next frame, then quiet again.
    unsigned expected = 1;
    auto expectOneMore = [&](const char* change)
    {
        const unsigned drawnBefore = field->getNumPassesDrawn();
        r->renderImage();
        r->renderImage();
        ++expected;
        EXPECT_EQ(field->getNumComputations(), expected) << change;
        EXPECT_EQ(field->getNumPassesDrawn(), drawnBefore + field->getNumPasses()) << change;
    };
    field->addRegion(
        new RegionOfInterest(RegionOfInterest::POLYLINE, {osg::Vec2d(0, 100), osg::Vec2d(190, 90)}));
    expectOneMore("addRegion");
    field->getRegions()[0]->setRadius(10.0);
    field->dirtyRegions();
    expectOneMore("dirtyRegions");
    field->setVariant(DF::JFA_PLUS_2);
    expectOneMore("setVariant");
    field->setUnits(DF::TEXELS);
    expectOneMore("setUnits");
    field->requestRecompute();
    expectOneMore("requestRecompute");

    // A grid moved by 10 m: the same passes, run again on the regions seen from there.
    osg::Node* firstPass = field->getChild(0);
    DF::Grid moved = grid;
    moved.origin += osg::Vec2d(10.0, -10.0);
    field->setGrid(moved);
    expectOneMore("setGrid (moved)");
    EXPECT_EQ(field->getChild(0), firstPass);
    const DF::Map cpuMoved = DF::computeJFA(DF::rasterize(moved, field->getRegions()), DF::JFA_PLUS_2);
    EXPECT_EQ(field->getReadBackMap().distance, cpuMoved.distance);

    // A new grid: the texture follows its size and the distances the new seeds.
    const DF::Grid larger = DF::Grid::cover(osg::BoundingBoxd(0, 0, 0, 192, 128, 0), 1.0); // 192 x 128
    field->setGrid(larger);
    expectOneMore("setGrid");
    EXPECT_EQ(field->getDistanceTexture()->getTextureWidth(), 192);
    const DF::Map& m2 = field->getReadBackMap();
    ASSERT_EQ(m2.width, 192);
    const DF::Map cpu2 = DF::computeJFA(DF::rasterize(larger, field->getRegions()), DF::JFA_PLUS_2);
    for (std::size_t i = 0; i < cpu2.distance.size(); ++i)
        ASSERT_NEAR(m2.distance[i], cpu2.distance[i], 1e-5f * std::max(1.0f, cpu2.distance[i]));
}

TEST(DistanceFieldGLTest, TheMapApproximatesTheDistanceToTheRegions)
{
    // End to end in world units: regions -> seeds -> GPU 1+JFA -> texture, against the exact
    // distance D of each texel centre to the regions (RegionOfInterest::distance). The map M
    // measures to seed texel centres. Bounds of the seed rule (docs/distance-field.md), in
    // texels t: M >= D - sqrt(1/2) t (a seed lies within half a texel diagonal of a region) and
    // M <= D + sqrt(2) t (within sqrt(2) t of every region point a seed lies), plus the JFA
    // error (none here). Measured: -0.71 .. +0.98 texel, mean |M - D| 0.28 texel.
    osg::ref_ptr<OffscreenRenderer> r = smallRenderer();
    const DF::Grid grid = DF::Grid::cover(osg::BoundingBoxd(-100, -50, 0, 300, 250, 0), 2.5); // 160 x 120
    const DF::RegionList regions = {
        new RegionOfInterest(
            RegionOfInterest::POLYLINE,
            {osg::Vec2d(-80, 0), osg::Vec2d(40, 30), osg::Vec2d(120, 200), osg::Vec2d(290, 210)}, 4.0),
        new RegionOfInterest(RegionOfInterest::CIRCLES, {osg::Vec2d(200, 20), osg::Vec2d(-60, 200)}, 15.0),
        new RegionOfInterest(RegionOfInterest::POLYGON, {osg::Vec2d(150, 60), osg::Vec2d(230, 70),
                                                         osg::Vec2d(210, 140), osg::Vec2d(160, 120)})};
    osg::ref_ptr<DF> field = new DF;
    field->setGrid(grid);
    field->setRegions(regions);
    field->setReadBack(true);
    r->setSceneData(field.get());
    r->renderImage();
    const DF::Map& m = field->getReadBackMap();
    ASSERT_EQ(m.width, grid.width);
    double sum = 0.0, lowest = 0.0, highest = 0.0;
    for (int j = 0; j < grid.height; ++j)
        for (int i = 0; i < grid.width; ++i)
        {
            double exact = std::numeric_limits<double>::infinity();
            for (const auto& reg : regions)
                exact = std::min(exact, reg->distance(grid.texelCenter(i, j)));
            const double err = (double(m.at(i, j)) - exact) / grid.texelSize;
            sum += std::fabs(err);
            lowest = std::min(lowest, err);
            highest = std::max(highest, err);
        }
    EXPECT_GE(lowest, -std::sqrt(0.5) - 1e-4);
    EXPECT_LE(highest, std::sqrt(2.0) + 1e-4);
    const double mean = sum / (grid.width * grid.height);
    EXPECT_LT(mean, 0.5);
    std::cout << "map - region distance: " << lowest << " .. " << highest << " texel, mean |.| " << mean
              << " texel\n";
}
