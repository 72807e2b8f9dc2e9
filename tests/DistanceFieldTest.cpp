// DistanceField without GL: grid sizing, seed rasterization of every region shape, the exact
// Euclidean distance transform against brute force, and jump flooding (JFA, 1+JFA, JFA+2) on the
// CPU against the exact transform, with stated bars and the known failure of plain JFA.
#include <osgLoA/interest/DistanceField>

#include <osg/FrameStamp>
#include <osgUtil/UpdateVisitor>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

using namespace osgLoA;
using DF = DistanceField;

namespace
{
const float kInf = std::numeric_limits<float>::infinity();

template <typename F> std::string invalidArgumentMessage(F f)
{
    try
    {
        f();
    }
    catch (const std::invalid_argument& e)
    {
        return e.what();
    }
    return "(no std::invalid_argument thrown)";
}

/** Distance to the nearest seed by trying every seed, rounded to float as computeExact does. */
DF::Map bruteForce(const DF::Seeds& s)
{
    DF::Map m;
    m.width = s.width;
    m.height = s.height;
    m.distance.assign(s.mask.size(), kInf);
    for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x)
        {
            long long best = -1;
            for (int sy = 0; sy < s.height; ++sy)
                for (int sx = 0; sx < s.width; ++sx)
                    if (s.isSeed(sx, sy))
                    {
                        const long long d2 = (long long)(sx - x) * (sx - x) + (long long)(sy - y) * (sy - y);
                        if (best < 0 || d2 < best) best = d2;
                    }
            if (best >= 0)
                m.distance[std::size_t(y) * std::size_t(s.width) + std::size_t(x)] =
                    float(std::sqrt(double(best)));
        }
    return m;
}

DF::Seeds randomSeeds(std::mt19937& rng, int w, int h, int count)
{
    DF::Seeds s(w, h);
    for (int i = 0; i < count; ++i)
        s.set(int(rng() % unsigned(w)), int(rng() % unsigned(h)));
    return s;
}

/** Every nearest seed named in m is a seed at exactly the distance given. */
void expectNearestConsistent(const DF::Map& m, const DF::Seeds& s)
{
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x)
        {
            const std::size_t i = std::size_t(y) * std::size_t(m.width) + std::size_t(x);
            if (m.nearest[i] == DF::Map::kNoSeed)
            {
                ASSERT_TRUE(std::isinf(m.distance[i]));
                continue;
            }
            const int sx = DF::Map::unpackX(m.nearest[i]), sy = DF::Map::unpackY(m.nearest[i]);
            ASSERT_TRUE(s.isSeed(sx, sy)) << x << "," << y;
            ASSERT_EQ(m.distance[i], float(std::sqrt(double((sx - x) * (sx - x) + (sy - y) * (sy - y)))));
        }
}

// --- an independent "core meets the texel square" test for the seed-rule check below --------

double cross(const osg::Vec2d& o, const osg::Vec2d& a, const osg::Vec2d& b)
{
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}
bool segmentsCross(const osg::Vec2d& a, const osg::Vec2d& b, const osg::Vec2d& c, const osg::Vec2d& d)
{
    return cross(a, b, c) * cross(a, b, d) <= 0.0 && cross(c, d, a) * cross(c, d, b) <= 0.0;
}
bool inBox(const osg::Vec2d& p, const osg::Vec2d& lo, const osg::Vec2d& hi)
{
    return p.x() >= lo.x() && p.x() <= hi.x() && p.y() >= lo.y() && p.y() <= hi.y();
}
bool segmentMeetsSquare(const osg::Vec2d& a, const osg::Vec2d& b, const osg::Vec2d& lo, const osg::Vec2d& hi)
{
    if (inBox(a, lo, hi) || inBox(b, lo, hi)) return true;
    const osg::Vec2d c[4] = {lo, osg::Vec2d(hi.x(), lo.y()), hi, osg::Vec2d(lo.x(), hi.y())};
    for (int i = 0; i < 4; ++i)
        if (segmentsCross(a, b, c[i], c[(i + 1) % 4])) return true;
    return false;
}
bool coreMeetsTexel(const RegionOfInterest& r, const DF::Grid& g, int i, int j)
{
    const osg::Vec2d lo(g.origin.x() + i * g.texelSize, g.origin.y() + j * g.texelSize);
    const osg::Vec2d hi = lo + osg::Vec2d(g.texelSize, g.texelSize);
    const auto& v = r.getVertices();
    switch (r.getShape())
    {
    case RegionOfInterest::CIRCLES:
        for (const auto& c : v)
            if (inBox(c, lo, hi)) return true;
        return false;
    case RegionOfInterest::POLYLINE:
        for (std::size_t k = 0; k + 1 < v.size(); ++k)
            if (segmentMeetsSquare(v[k], v[k + 1], lo, hi)) return true;
        return false;
    case RegionOfInterest::POLYGON:
        for (std::size_t k = 0; k < v.size(); ++k)
            if (segmentMeetsSquare(v[k], v[(k + 1) % v.size()], lo, hi)) return true;
        return false;
    }
    return false;
}

/** The seed rule, texel by texel, with RegionOfInterest::distance and the test above. */
void expectSeedRule(const DF::Grid& g, const DF::RegionList& regions, const DF::Seeds& seeds)
{
    for (int j = 0; j < g.height; ++j)
        for (int i = 0; i < g.width; ++i)
        {
            bool expected = false;
            for (const auto& r : regions)
                expected = expected || r->distance(g.texelCenter(i, j)) == 0.0 || coreMeetsTexel(*r, g, i, j);
            ASSERT_EQ(seeds.isSeed(i, j), expected) << "texel " << i << "," << j;
        }
}

osg::ref_ptr<RegionOfInterest> region(RegionOfInterest::Shape s, RegionOfInterest::Vertices v, double radius)
{
    return new RegionOfInterest(s, v, radius);
}

/** A 4-connected path of seeds joins texels a and b (flood fill over seeds). */
bool fourConnected(const DF::Seeds& s, int ax, int ay, int bx, int by)
{
    std::vector<unsigned char> seen(s.mask.size(), 0);
    std::vector<std::pair<int, int>> stack = {{ax, ay}};
    while (!stack.empty())
    {
        auto [x, y] = stack.back();
        stack.pop_back();
        if (x < 0 || y < 0 || x >= s.width || y >= s.height || !s.isSeed(x, y)) continue;
        unsigned char& v = seen[std::size_t(y) * std::size_t(s.width) + std::size_t(x)];
        if (v) continue;
        v = 1;
        if (x == bx && y == by) return true;
        stack.insert(stack.end(), {{x + 1, y}, {x - 1, y}, {x, y + 1}, {x, y - 1}});
    }
    return false;
}

const DF::Variant kVariants[] = {DF::JFA, DF::ONE_PLUS_JFA, DF::JFA_PLUS_2};
} // namespace

// --- grid -----------------------------------------------------------------------------------

TEST(DistanceFieldTest, GridCoversTheAreaWithTheSmallestGrid)
{
    const DF::Grid g = DF::Grid::cover(osg::BoundingBoxd(0, 0, 0, 100, 50, 30), 0.5);
    EXPECT_EQ(g.width, 200);
    EXPECT_EQ(g.height, 100);
    EXPECT_EQ(g.texelSize, 0.5);
    EXPECT_EQ(g.origin, osg::Vec2d(0, 0));

    // 100.3 x 0.2 world units at 1 per texel: 101 x 1 (not square, partial texels round up).
    const DF::Grid h = DF::Grid::cover(osg::BoundingBoxd(10, 20, 0, 110.3, 20.2, 0), 1.0);
    EXPECT_EQ(h.width, 101);
    EXPECT_EQ(h.height, 1);
    EXPECT_EQ(h.origin, osg::Vec2d(10, 20));
    EXPECT_GE(h.bound().xMax(), 110.3);

    // 100 / 0.1 is 1000 texels, not 1001 (a whole number within 1e-9 is not rounded up).
    EXPECT_EQ(DF::Grid::cover(osg::BoundingBoxd(0, 0, 0, 100, 100, 0), 0.1).width, 1000);
    // A point: one texel.
    const DF::Grid p = DF::Grid::cover(osg::BoundingBoxd(5, 5, 0, 5, 5, 0), 2.0);
    EXPECT_EQ(p.width, 1);
    EXPECT_EQ(p.height, 1);
}

TEST(DistanceFieldTest, GridTexelSizeGrowsAtTheMaximumResolution)
{
    // 10 km x 5 km at 1 m would be 10000 x 5000: clamped to 2048 along x, texel 10000/2048 m.
    const DF::Grid g = DF::Grid::cover(osg::BoundingBoxd(0, 0, 0, 10000, 5000, 0), 1.0);
    EXPECT_EQ(g.width, 2048);
    EXPECT_EQ(g.height, 1024);
    EXPECT_DOUBLE_EQ(g.texelSize, 10000.0 / 2048.0);
    const DF::Grid s = DF::Grid::cover(osg::BoundingBoxd(0, 0, 0, 300, 1000, 0), 0.5, 512);
    EXPECT_EQ(s.height, 512);
    EXPECT_EQ(s.width, 154); // 300 / (1000/512) = 153.6
    EXPECT_GE(s.bound().yMax(), 1000.0);
}

TEST(DistanceFieldTest, GridErrorsNameTheProblem)
{
    EXPECT_NE(invalidArgumentMessage([] { DF::Grid::cover(osg::BoundingBoxd(), 1.0); }).find("empty"),
              std::string::npos);
    const osg::BoundingBoxd a(0, 0, 0, 10, 10, 0);
    for (double t : {0.0, -1.0, std::nan("")})
        EXPECT_NE(invalidArgumentMessage([&] { DF::Grid::cover(a, t); }).find("texel size"),
                  std::string::npos);
    for (int r : {0, DF::kMaxResolution + 1})
        EXPECT_NE(invalidArgumentMessage([&] { DF::Grid::cover(a, 1.0, r); }).find("maximum resolution"),
                  std::string::npos);
    const double inf = std::numeric_limits<double>::infinity();
    EXPECT_NE(invalidArgumentMessage([&] { DF::Grid::cover(osg::BoundingBoxd(0, 0, 0, inf, 1, 0), 1.0); })
                  .find("not finite"),
              std::string::npos);
    EXPECT_NE(invalidArgumentMessage([&] { DF::Grid::clipToRange(a, osg::Vec2d(0, 0), 0.0); }).find("range"),
              std::string::npos);
}

TEST(DistanceFieldTest, GridClippedToTheRangeAroundTheCamera)
{
    const osg::BoundingBoxd area(0, 0, -5, 1000, 1000, 80);
    const osg::BoundingBoxd c = DF::Grid::clipToRange(area, osg::Vec2d(900, 100), 200);
    EXPECT_EQ(c.xMin(), 700);
    EXPECT_EQ(c.xMax(), 1000);
    EXPECT_EQ(c.yMin(), 0);
    EXPECT_EQ(c.yMax(), 300);
    const DF::Grid g = DF::Grid::cover(c, 1.0);
    EXPECT_EQ(g.width, 300);
    EXPECT_EQ(g.height, 300);
    // Disjoint: an invalid box, which cover() refuses.
    const osg::BoundingBoxd none = DF::Grid::clipToRange(area, osg::Vec2d(5000, 5000), 100);
    EXPECT_FALSE(none.valid());
    EXPECT_THROW(DF::Grid::cover(none, 1.0), std::invalid_argument);
}

TEST(DistanceFieldTest, GridMapsWorldToTexture)
{
    const DF::Grid g(osg::Vec2d(-100, 50), 2.0, 100, 50);
    EXPECT_EQ(g.texelCenter(0, 0), osg::Vec2d(-99, 51));
    EXPECT_EQ(g.worldToTexel(osg::Vec2d(-90, 60)), osg::Vec2d(5, 5));
    EXPECT_EQ(g.worldToTexCoord(osg::Vec2d(-100, 50)), osg::Vec2d(0, 0));
    EXPECT_EQ(g.worldToTexCoord(osg::Vec2d(100, 150)), osg::Vec2d(1, 1));
    const osg::Vec4f t = g.textureTransform();
    const osg::Vec2d w(-3.5, 77.25);
    const osg::Vec2d tc = g.worldToTexCoord(w);
    EXPECT_NEAR(w.x() * t.x() + t.z(), tc.x(), 1e-6);
    EXPECT_NEAR(w.y() * t.y() + t.w(), tc.y(), 1e-6);
}

// --- exact EDT ------------------------------------------------------------------------------

TEST(DistanceFieldTest, ExactTransformEqualsBruteForce)
{
    // Max abs error 0: both are the correctly rounded sqrt of the same integer.
    std::mt19937 rng(11);
    for (int t = 0; t < 60; ++t)
    {
        const int w = 1 + int(rng() % 40), h = 1 + int(rng() % 40);
        const int count = int(rng() % unsigned(1 + w * h / (1 + int(rng() % 30))));
        const DF::Seeds s = randomSeeds(rng, w, h, count);
        const DF::Map e = DF::computeExact(s);
        const DF::Map b = bruteForce(s);
        ASSERT_EQ(e.distance, b.distance) << w << "x" << h << " with " << s.count() << " seeds";
        expectNearestConsistent(e, s);
    }
}

TEST(DistanceFieldTest, ExactTransformHandComputed)
{
    DF::Seeds s(10, 10);
    s.set(2, 3);
    const DF::Map m = DF::computeExact(s);
    EXPECT_EQ(m.at(2, 3), 0.0f);
    EXPECT_EQ(m.at(5, 7), 5.0f); // offset (3, 4)
    EXPECT_EQ(m.at(9, 3), 7.0f);
    EXPECT_EQ(m.at(3, 4), std::sqrt(2.0f));
    EXPECT_EQ(m.nearest[7 * 10 + 5], DF::Map::pack(2, 3));
}

TEST(DistanceFieldTest, NoSeedsGiveInfinityAndAllSeedsZero)
{
    const DF::Seeds none(17, 9);
    const DF::Map e = DF::computeExact(none);
    for (float d : e.distance)
        ASSERT_TRUE(std::isinf(d) && d > 0);
    for (DF::Variant v : kVariants)
    {
        const DF::Map j = DF::computeJFA(none, v);
        for (std::size_t i = 0; i < j.distance.size(); ++i)
        {
            ASSERT_TRUE(std::isinf(j.distance[i]));
            ASSERT_EQ(j.nearest[i], DF::Map::kNoSeed);
        }
        EXPECT_EQ(DF::compare(j, e).texels, 0u); // nothing finite to compare
    }
    DF::Seeds all(9, 17);
    std::fill(all.mask.begin(), all.mask.end(), 1);
    for (float d : DF::computeExact(all).distance)
        ASSERT_EQ(d, 0.0f);
    for (float d : DF::computeJFA(all, DF::JFA).distance)
        ASSERT_EQ(d, 0.0f);
    // An empty grid: no texel, no crash.
    EXPECT_TRUE(DF::computeExact(DF::Seeds(0, 0)).distance.empty());
}

TEST(DistanceFieldTest, OneDimensionalGridsAreExactEvenForJumpFlooding)
{
    // In one dimension jump flooding is exact (the nearest seed of a texel is the nearest of
    // its neighbours' nearest seeds); sizes not a power of two check the first step.
    std::mt19937 rng(5);
    for (int n : {1, 2, 3, 5, 17, 100, 1000})
        for (int column = 0; column < 2; ++column)
            for (int t = 0; t < 5; ++t)
            {
                DF::Seeds s(column ? 1 : n, column ? n : 1);
                const int count = t == 0 ? 1 : int(rng() % 5);
                for (int i = 0; i < count; ++i)
                {
                    const int p = t == 0 ? n - 1 : int(rng() % unsigned(n)); // t 0: one seed at the far end
                    column ? s.set(0, p) : s.set(p, 0);
                }
                const DF::Map e = DF::computeExact(s);
                ASSERT_EQ(e.distance, bruteForce(s).distance);
                for (DF::Variant v : kVariants)
                    ASSERT_EQ(DF::computeJFA(s, v).distance, e.distance)
                        << DF::toString(v) << " " << s.width << "x" << s.height;
            }
}

// --- steps ----------------------------------------------------------------------------------

TEST(DistanceFieldTest, StepsFollowTheGridAndTheVariant)
{
    using V = std::vector<int>;
    EXPECT_EQ(DF::steps(DF::JFA, 1024, 1024), (V{512, 256, 128, 64, 32, 16, 8, 4, 2, 1}));
    // Not a power of two: the first step must be >= max/2 so that 2k - 1 >= 999 (256 would not).
    EXPECT_EQ(DF::steps(DF::JFA, 1000, 3), (V{512, 256, 128, 64, 32, 16, 8, 4, 2, 1}));
    EXPECT_EQ(DF::steps(DF::JFA, 3, 1), (V{2, 1}));
    EXPECT_EQ(DF::steps(DF::JFA, 2, 2), (V{1}));
    EXPECT_TRUE(DF::steps(DF::JFA, 1, 1).empty());
    EXPECT_EQ(DF::steps(DF::ONE_PLUS_JFA, 8, 8), (V{1, 4, 2, 1}));
    EXPECT_EQ(DF::steps(DF::JFA_PLUS_2, 8, 8), (V{4, 2, 1, 2, 1}));
    // Only distances up to 100 texels matter: start at 128.
    EXPECT_EQ(DF::steps(DF::JFA, 1024, 1024, 100), (V{128, 64, 32, 16, 8, 4, 2, 1}));
    EXPECT_EQ(DF::steps(DF::JFA, 1024, 1024, 128), (V{128, 64, 32, 16, 8, 4, 2, 1}));
    EXPECT_EQ(DF::steps(DF::JFA, 1024, 1024, 5000).front(), 512);
}

// --- seeds ----------------------------------------------------------------------------------

TEST(DistanceFieldTest, SeedsFollowTheRuleForEveryShape)
{
    // Random regions of every shape, radius 0 to 3 texels, on a grid with a fractional origin:
    // each texel is a seed exactly when its centre is in the region (RegionOfInterest::distance
    // == 0) or the region's core meets its square (an independent segment/square test).
    std::mt19937 rng(21);
    std::uniform_real_distribution<double> coord(-3.0, 53.0), rad(0.0, 3.0);
    const DF::Grid g(osg::Vec2d(0.37, -0.21), 1.0, 48, 40);
    for (int t = 0; t < 40; ++t)
    {
        DF::RegionList regions;
        const auto shape = RegionOfInterest::Shape(t % 3);
        RegionOfInterest::Vertices v;
        const int n = shape == RegionOfInterest::POLYGON ? 3 + int(rng() % 5) : 1 + int(rng() % 5);
        for (int i = 0; i < n; ++i)
            v.push_back(osg::Vec2d(coord(rng), coord(rng)));
        regions.push_back(region(shape, v, t % 4 == 0 ? 0.0 : rad(rng)));
        const DF::Seeds s = DF::rasterize(g, regions);
        expectSeedRule(g, regions, s);
    }
}

TEST(DistanceFieldTest, ThinShapesStillMakeSeeds)
{
    const DF::Grid g(osg::Vec2d(0, 0), 1.0, 32, 32);
    // A point (radius 0) inside texel (7, 9): that texel only.
    DF::Seeds s = DF::rasterize(g, {region(RegionOfInterest::CIRCLES, {osg::Vec2d(7.3, 9.6)}, 0.0)});
    EXPECT_EQ(s.count(), 1u);
    EXPECT_TRUE(s.isSeed(7, 9));
    // A circle of radius 0.2 texel: still its texel.
    s = DF::rasterize(g, {region(RegionOfInterest::CIRCLES, {osg::Vec2d(20.8, 3.1)}, 0.2)});
    EXPECT_EQ(s.count(), 1u);
    EXPECT_TRUE(s.isSeed(20, 3));
    // A route of width 0 along a shallow diagonal: every texel it passes through is a seed and
    // the seeds join its ends 4-connected; no seed lies farther than half a texel diagonal.
    const osg::Vec2d a(1.2, 2.7), b(30.6, 11.4);
    s = DF::rasterize(g, {region(RegionOfInterest::POLYLINE, {a, b}, 0.0)});
    for (int i = 0; i <= 1000; ++i)
    {
        const osg::Vec2d p = a + (b - a) * (i / 1000.0);
        ASSERT_TRUE(s.isSeed(int(p.x()), int(p.y()))) << p.x() << "," << p.y();
    }
    EXPECT_TRUE(fourConnected(s, 1, 2, 30, 11));
    const osg::ref_ptr<RegionOfInterest> line = region(RegionOfInterest::POLYLINE, {a, b}, 0.0);
    for (int j = 0; j < 32; ++j)
        for (int i = 0; i < 32; ++i)
        {
            if (!s.isSeed(i, j)) continue;
            EXPECT_LE(line->distance(g.texelCenter(i, j)), std::sqrt(0.5) + 1e-12);
        }
    // A polygon thinner than a texel between texel centres: its edges still make seeds.
    s = DF::rasterize(g,
                      {region(RegionOfInterest::POLYGON,
                              {osg::Vec2d(4.1, 20.1), osg::Vec2d(14.9, 20.1), osg::Vec2d(14.9, 20.3)}, 0.0)});
    EXPECT_GT(s.count(), 10u);
    EXPECT_TRUE(s.isSeed(10, 20));
}

TEST(DistanceFieldTest, FilledShapesSeedTheirInside)
{
    const DF::Grid g(osg::Vec2d(0, 0), 0.5, 64, 64); // 32 x 32 world units
    // A disc of radius 5 world units (10 texels): about pi r^2 = 314 texels of area 1.
    DF::Seeds s = DF::rasterize(g, {region(RegionOfInterest::CIRCLES, {osg::Vec2d(16, 16)}, 5.0)});
    EXPECT_NEAR(double(s.count()), M_PI * 100.0, 20.0);
    EXPECT_TRUE(s.isSeed(32, 32));
    EXPECT_FALSE(s.isSeed(32, 44)); // 6.25 units away
    // A square polygon [4, 12]^2: its 16 x 16 inside texels plus its boundary.
    s = DF::rasterize(
        g, {region(RegionOfInterest::POLYGON,
                   {osg::Vec2d(4, 4), osg::Vec2d(12, 4), osg::Vec2d(12, 12), osg::Vec2d(4, 12)}, 0.0)});
    for (int j = 8; j < 24; ++j)
        for (int i = 8; i < 24; ++i)
            ASSERT_TRUE(s.isSeed(i, j));
    EXPECT_FALSE(s.isSeed(30, 30));
    // Boundary on texel edges: the closed squares on both sides are touched, 18 x 18 in all.
    EXPECT_EQ(s.count(), 18u * 18u);
}

TEST(DistanceFieldTest, DegenerateAndOutsideRegionsMakeNoSeeds)
{
    const DF::Grid g(osg::Vec2d(0, 0), 1.0, 16, 16);
    const DF::RegionList r = {
        region(RegionOfInterest::POLYLINE, {osg::Vec2d(3, 3)}, 1.0),                  // 1 vertex
        region(RegionOfInterest::POLYGON, {osg::Vec2d(3, 3), osg::Vec2d(5, 5)}, 1.0), // 2 vertices
        region(RegionOfInterest::CIRCLES, {}, 4.0),                                   // none
        region(RegionOfInterest::CIRCLES, {osg::Vec2d(-50, 8)}, 3.0),                 // outside
        nullptr};
    EXPECT_EQ(DF::rasterize(g, r).count(), 0u);
    // Partly outside: only the inside part.
    const DF::Seeds s = DF::rasterize(g, {region(RegionOfInterest::CIRCLES, {osg::Vec2d(-1, 8)}, 3.0)});
    EXPECT_GT(s.count(), 0u);
    EXPECT_TRUE(s.isSeed(0, 8));
    EXPECT_FALSE(s.isSeed(3, 8));
    EXPECT_THROW(DF::rasterize(DF::Grid(), r), std::invalid_argument);
}

// --- jump flooding against the exact transform -----------------------------------------------

TEST(DistanceFieldTest, JumpFloodingMeetsTheBarsOnRandomSeeds)
{
    // 256^2, 20..200 random seeds, 12 seed sets. Measured worst cases of a set: here mean
    // |error| 6.6e-5 texel and 1.5e-5 of the texels off by > 1 texel (plain JFA); over 80 other
    // sets of 20..200 seeds 6.5e-4 and 2.1e-4 (plain JFA; 1+JFA 4.8e-6 and 0, JFA+2 4.5e-5 and
    // 1.5e-5). Bars with a margin of 5x and more over the worst: mean < 0.005 texel, fraction off
    // by > 1 texel < 0.1% (the issue asks for 1+JFA: mean < 0.1, < 0.1%). Every reached distance
    // is that of a real seed, so it is never below the exact one.
    std::mt19937 rng(2012);
    std::size_t wrong[3] = {0, 0, 0};
    for (int t = 0; t < 12; ++t)
    {
        const int count = 20 + int(rng() % 181);
        const DF::Seeds s = randomSeeds(rng, 256, 256, count);
        const DF::Map e = DF::computeExact(s);
        for (int vi = 0; vi < 3; ++vi)
        {
            const DF::Map j = DF::computeJFA(s, kVariants[vi]);
            const DF::Error err = DF::compare(j, e);
            EXPECT_EQ(err.texels, 256u * 256u);
            EXPECT_EQ(err.unreached, 0u);
            EXPECT_LT(err.meanAbs, 0.005) << DF::toString(kVariants[vi]) << " with " << count << " seeds";
            EXPECT_LT(err.fractionOverOne(), 0.001)
                << DF::toString(kVariants[vi]) << " with " << count << " seeds";
            for (std::size_t i = 0; i < j.distance.size(); ++i)
                ASSERT_GE(j.distance[i], e.distance[i]);
            expectNearestConsistent(j, s);
            wrong[vi] += err.wrong;
        }
    }
    // Over all sets, the extra passes reduce the texels in error (measured: JFA 39, 1+JFA 1,
    // JFA+2 0 of 786432).
    EXPECT_GT(wrong[0], 0u);
    EXPECT_LT(wrong[1], wrong[0]);
    EXPECT_LT(wrong[2], wrong[0]);
}

TEST(DistanceFieldTest, PlainJumpFloodingErrsWhereTheExtraPassesDoNot)
{
    // Found by searching random 16^2 sets of 3..5 seeds with computeJFA: plain JFA sends texels
    // to the wrong seed (the documented degradation, Rong & Tan 2006 §4: a texel's nearest
    // seed cannot reach it because the texels on the way were taken by other seeds earlier).
    // Five texels are wrong, one by more than 2 texels; one step-1 pass before (1+JFA) or
    // steps 2 and 1 after (JFA+2) repair all of them.
    DF::Seeds s(16, 16);
    for (auto p : {std::pair<int, int>{11, 12}, {8, 7}, {1, 4}, {9, 12}})
        s.set(p.first, p.second);
    const DF::Map e = DF::computeExact(s);
    const DF::Error jfa = DF::compare(DF::computeJFA(s, DF::JFA), e);
    EXPECT_EQ(jfa.wrong, 5u);
    EXPECT_GT(jfa.maxAbs, 2.0);
    EXPECT_GE(jfa.overOne, 1u);
    EXPECT_EQ(DF::compare(DF::computeJFA(s, DF::ONE_PLUS_JFA), e).wrong, 0u);
    EXPECT_EQ(DF::compare(DF::computeJFA(s, DF::JFA_PLUS_2), e).wrong, 0u);
}

TEST(DistanceFieldTest, AStartingStepFromTheMaximumDistanceKeepsDistancesUpToIt)
{
    // Starting at the power of two >= R: every texel within R of a seed is reached and meets the
    // same bars as the full schedule; every texel beyond holds a distance >= R or +infinity
    // (a reached distance is that of a real seed, never below the exact one).
    std::mt19937 rng(77);
    for (int R : {5, 16, 40})
        for (int t = 0; t < 3; ++t)
        {
            const DF::Seeds s = randomSeeds(rng, 256, 200, 5 + int(rng() % 20));
            const DF::Map e = DF::computeExact(s);
            for (DF::Variant v : kVariants)
            {
                const DF::Map j = DF::computeJFA(s, v, R);
                const DF::Error err = DF::compare(j, e, R);
                EXPECT_EQ(err.unreached, 0u);
                EXPECT_LT(err.meanAbs, 0.005);
                EXPECT_LT(err.fractionOverOne(), 0.001);
                std::size_t beyond = 0, infinite = 0;
                for (std::size_t i = 0; i < e.distance.size(); ++i)
                {
                    ASSERT_GE(j.distance[i], e.distance[i]);
                    if (e.distance[i] > float(R))
                    {
                        ++beyond;
                        ASSERT_GE(j.distance[i], float(R));
                        infinite += std::isinf(j.distance[i]) ? 1 : 0;
                    }
                }
                if (R == 5)
                {
                    EXPECT_GT(infinite, 0u) << "a short schedule leaves far texels unreached";
                }
                (void)beyond;
            }
        }
}

TEST(DistanceFieldTest, CompareCountsUnreachedTexels)
{
    DF::Seeds s(4, 1);
    s.set(0, 0);
    const DF::Map e = DF::computeExact(s);
    DF::Map a = e;
    a.distance[3] = kInf;
    a.distance[2] += 0.5f;
    const DF::Error err = DF::compare(a, e);
    EXPECT_EQ(err.texels, 4u);
    EXPECT_EQ(err.unreached, 1u);
    EXPECT_EQ(err.overOne, 1u);
    EXPECT_EQ(err.wrong, 2u);
    EXPECT_DOUBLE_EQ(err.meanAbs, 0.5 / 3.0);
    EXPECT_DOUBLE_EQ(err.fractionOverOne(), 0.25);
    EXPECT_THROW(DF::compare(a, DF::computeExact(DF::Seeds(3, 1))), std::invalid_argument);
}

// --- capabilities and the node without GL ----------------------------------------------------

TEST(DistanceFieldTest, CapabilityCheckNamesWhatIsMissing)
{
    GLCapabilities caps;
    caps.renderer = "test renderer";
    caps.version = "4.5 (Compatibility Profile)";
    caps.majorVersion = 4;
    caps.minorVersion = 5;
    caps.compatibilityProfile = true;
    caps.maxTextureSize = 16384;
    EXPECT_NO_THROW(DF::checkCapabilities(caps, 2048, 2048));
    caps.maxTextureSize = 1024;
    try
    {
        DF::checkCapabilities(caps, 2048, 512);
        ADD_FAILURE() << "no DistanceFieldError";
    }
    catch (const DistanceFieldError& e)
    {
        EXPECT_NE(std::string(e.what()).find("GL_MAX_TEXTURE_SIZE is 1024"), std::string::npos) << e.what();
    }
    caps.majorVersion = 2;
    caps.minorVersion = 1;
    caps.maxTextureSize = 16384;
    try
    {
        DF::checkCapabilities(caps, 64, 64);
        ADD_FAILURE() << "no DistanceFieldError";
    }
    catch (const DistanceFieldError& e)
    {
        const std::string m = e.what();
        EXPECT_NE(m.find("OpenGL 3.3"), std::string::npos) << m;
        EXPECT_NE(m.find("float render targets"), std::string::npos) << m;
        EXPECT_NE(m.find("test renderer"), std::string::npos) << m;
    }
}

TEST(DistanceFieldTest, NodeBuildsOnePassPerStep)
{
    osg::ref_ptr<DF> field = new DF;
    EXPECT_EQ(field->getNumPasses(), 0u); // no grid yet
    EXPECT_EQ(field->getVariant(), DF::ONE_PLUS_JFA);
    EXPECT_EQ(field->getUnits(), DF::WORLD);
    field->setGrid(DF::Grid(osg::Vec2d(0, 0), 2.0, 300, 200));
    EXPECT_EQ(field->getPassSteps(), DF::steps(DF::ONE_PLUS_JFA, 300, 200));
    EXPECT_EQ(field->getNumPasses(), field->getPassSteps().size() + 1); // + the distance pass
    EXPECT_EQ(field->getNumChildren(), field->getNumPasses());
    EXPECT_EQ(field->getDistanceTexture()->getTextureWidth(), 300);
    field->setVariant(DF::JFA);
    field->setMaxDistance(20.0); // 10 texels: start at 16
    EXPECT_EQ(field->getPassSteps(), (std::vector<int>{16, 8, 4, 2, 1}));
    field->setGrid(DF::Grid(osg::Vec2d(0, 0), 1.0, 1, 1));
    EXPECT_TRUE(field->getPassSteps().empty());
    EXPECT_EQ(field->getNumPasses(), 1u); // the distance pass only
    EXPECT_THROW(field->setMaxDistance(-1.0), std::invalid_argument);
    EXPECT_THROW(field->setSeeds(DF::Seeds(2, 2)), std::invalid_argument);
    EXPECT_THROW(field->setGrid(DF::Grid(osg::Vec2d(0, 0), 1.0, DF::kMaxResolution + 1, 1)),
                 std::invalid_argument);
    osg::ref_ptr<DF> copy = new DF(*field);
    EXPECT_EQ(copy->getNumPasses(), 1u);
    EXPECT_NE(copy->getDistanceTexture(), field->getDistanceTexture());
}

TEST(DistanceFieldTest, TheCpuExactMethodComputesInTheUpdateTraversal)
{
    osg::ref_ptr<DF> field = new DF;
    field->setMethod(DF::CPU_EXACT);
    const DF::Grid grid(osg::Vec2d(10, 20), 0.5, 40, 30);
    field->setGrid(grid);
    EXPECT_EQ(field->getNumPasses(), 0u);
    const DF::RegionList regions = {
        region(RegionOfInterest::CIRCLES, {osg::Vec2d(15, 30)}, 1.0),
        region(RegionOfInterest::POLYLINE, {osg::Vec2d(10, 21), osg::Vec2d(30, 34)}, 0.0)};
    field->setRegions(regions);
    field->setReadBack(true);
    osgUtil::UpdateVisitor update;
    update.setFrameStamp(new osg::FrameStamp);
    field->accept(update);
    EXPECT_EQ(field->getNumComputations(), 1u);
    // The texture's image: the exact distances in world units (texel size 0.5).
    const DF::Map exact = DF::computeExact(DF::rasterize(grid, regions));
    const osg::Image* image = field->getDistanceTexture()->getImage();
    ASSERT_NE(image, nullptr);
    ASSERT_EQ(image->s(), 40);
    ASSERT_EQ(image->t(), 30);
    const auto* d = reinterpret_cast<const float*>(image->data());
    for (std::size_t i = 0; i < exact.distance.size(); ++i)
        ASSERT_EQ(d[i], exact.distance[i] * 0.5f);
    EXPECT_EQ(field->getReadBackMap().nearest, exact.nearest);
    // Unchanged: no computation; a change: one.
    field->accept(update);
    EXPECT_EQ(field->getNumComputations(), 1u);
    field->requestRecompute();
    field->accept(update);
    EXPECT_EQ(field->getNumComputations(), 2u);
    field->setUnits(DF::TEXELS);
    field->accept(update);
    EXPECT_EQ(field->getNumComputations(), 3u);
    EXPECT_EQ(reinterpret_cast<const float*>(image->data())[7], exact.distance[7]);
    // Back to the GPU: passes, and the texture is a render target again (no image).
    field->setMethod(DF::GPU_JUMP_FLOODING);
    EXPECT_GT(field->getNumPasses(), 1u);
    EXPECT_EQ(field->getDistanceTexture()->getImage(), nullptr);
    EXPECT_EQ(field->getDistanceTexture()->getTextureWidth(), 40);

    GLCapabilities caps;
    caps.renderer = "llvmpipe (LLVM 15.0.6, 256 bits)";
    EXPECT_EQ(DF::preferredMethod(caps), DF::CPU_EXACT);
    caps.renderer = "NVIDIA H100 PCIe/PCIe/SSE2";
    EXPECT_EQ(DF::preferredMethod(caps), DF::GPU_JUMP_FLOODING);
}
