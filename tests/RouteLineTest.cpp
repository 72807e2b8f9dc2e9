// RouteLine's CPU side against hand-computed values: which regions become which segments, the
// distance in pixels through the screen derivatives of the ground position, the colour of the
// line, its casing and its anti-aliased rim; RegionOfInterest's line width and colour checks.
#include <osgLoA/interest/RegionOfInterest>
#include <osgLoA/transitions/RouteLine>
#include <osgLoA/transitions/UsageScenario>

#include <osg/Texture2D>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace osgLoA;
typedef RegionOfInterest R;

namespace
{
osg::ref_ptr<R> drawn(R::Shape shape, const R::Vertices& v, double radius, double width)
{
    osg::ref_ptr<R> r = new R(shape, v, radius);
    r->setLineWidth(width);
    return r;
}
} // namespace

TEST(RouteLineTest, RegionsBecomeSegments)
{
    std::vector<osg::ref_ptr<R>> regions = {
        drawn(R::POLYLINE, {{0, 0}, {10, 0}, {10, 5}}, 2.0, 6.0),      // 2 segments
        drawn(R::POLYGON, {{0, 0}, {4, 0}, {4, 4}, {0, 4}}, 0.0, 3.0), // 4, closed
        drawn(R::CIRCLES, {{100, 100}, {-50, 0}}, 10.0, 2.0),          // 2 x 64 chords
        drawn(R::CIRCLES, {{0, 0}}, 0.0, 2.0),                         // radius 0: none
        drawn(R::POLYLINE, {{0, 0}, {1, 1}}, 0.0, 0.0),                // not drawn
        drawn(R::POLYLINE, {{0, 0}}, 0.0, 5.0),                        // degenerate
    };
    const RouteLine::Segments s = RouteLine::collect(regions);
    ASSERT_EQ(s.size(), 2u + 4u + 2u * 64u);
    EXPECT_EQ(s[1].a, osg::Vec2d(10, 0));
    EXPECT_EQ(s[1].b, osg::Vec2d(10, 5));
    EXPECT_EQ(s[0].width, 6.0);
    EXPECT_EQ(s[0].color, R::defaultLineColor());
    EXPECT_EQ(s[5].a, osg::Vec2d(0, 4)); // the ring's closing segment
    EXPECT_EQ(s[5].b, osg::Vec2d(0, 0));
    for (std::size_t k = 6; k < s.size(); ++k)
    {
        const osg::Vec2d c = k < 6 + 64 ? osg::Vec2d(100, 100) : osg::Vec2d(-50, 0);
        EXPECT_NEAR((s[k].a - c).length(), 10.0, 1e-9);
        EXPECT_NEAR((s[k].b - c).length(), 10.0, 1e-9);
        // 64 chords: each 2 r sin(pi / 64) long.
        EXPECT_NEAR((s[k].b - s[k].a).length(), 20.0 * std::sin(osg::PI / 64.0), 1e-9);
    }
}

TEST(RouteLineTest, PixelDistanceIsMeasuredInTheWindow)
{
    const RouteLine::Segments s = RouteLine::collect({drawn(R::POLYLINE, {{0, 0}, {10, 0}}, 0.0, 6.0)});
    // Orthographic, 2 px a unit both ways: 2 units off the line are 4 px.
    const osg::Vec2d unit(1.0, 1.0);
    RouteLine::Nearest n = RouteLine::nearest(s, osg::Vec3d(5, 2, 0), osg::Matrixd::scale(2, 2, 1), unit);
    EXPECT_EQ(n.index, 0);
    EXPECT_DOUBLE_EQ(n.pixels, 4.0);
    // Squeezed along y (a slanted view): 0.5 px a unit: 1 px.
    n = RouteLine::nearest(s, osg::Vec3d(5, 2, 0), osg::Matrixd::scale(2, 0.5, 1), unit);
    EXPECT_DOUBLE_EQ(n.pixels, 1.0);
    // Past the end: (13, 4) is 3, 4 units from (10, 0): at 2 and 0.5 px a unit, 6 and 2 px.
    n = RouteLine::nearest(s, osg::Vec3d(13, 4, 0), osg::Matrixd::scale(2, 0.5, 1), unit);
    EXPECT_DOUBLE_EQ(n.pixels, std::sqrt(36.0 + 4.0));
    // On the line: 0 px. The viewport's scale multiplies.
    EXPECT_EQ(RouteLine::nearest(s, osg::Vec3d(5, 0, 0), osg::Matrixd::scale(2, 2, 1), unit).pixels, 0.0);
    EXPECT_DOUBLE_EQ(
        RouteLine::nearest(s, osg::Vec3d(5, 2, 0), osg::Matrixd::identity(), osg::Vec2d(10, 30)).pixels,
        60.0);

    // Perspective: an eye at height 1 looking along +y (clip x = x, y = z, w = y): the ground
    // point (0, 2, -1) is at NDC (0, -0.5); a line across at y = 4 at NDC y = -0.25; at 100 px
    // per NDC unit, 25 px apart (a linear estimate from the ground's scale at the point, 50 px a
    // unit along y there, would say 2 units = 100 px).
    const osg::Matrixd persp(1, 0, 0, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0, 0, 0);
    const RouteLine::Segments across =
        RouteLine::collect({drawn(R::POLYLINE, {{-10, 4}, {10, 4}}, 0.0, 6.0)});
    n = RouteLine::nearest(across, osg::Vec3d(0, 2, -1), persp, osg::Vec2d(100, 100));
    EXPECT_EQ(n.index, 0);
    EXPECT_NEAR(n.pixels, 25.0, 1e-9);
    // A line running from behind the eye to in front of it: clipped at the near side; the
    // point lies on its projection (screen x = 0).
    const RouteLine::Segments along = RouteLine::collect({drawn(R::POLYLINE, {{0, -5}, {0, 4}}, 0.0, 6.0)});
    n = RouteLine::nearest(along, osg::Vec3d(0, 2, -1), persp, osg::Vec2d(100, 100));
    EXPECT_EQ(n.index, 0);
    EXPECT_NEAR(n.pixels, 0.0, 1e-6);
    // Wholly behind the eye: none.
    const RouteLine::Segments behind =
        RouteLine::collect({drawn(R::POLYLINE, {{-10, -3}, {10, -3}}, 0.0, 6.0)});
    EXPECT_EQ(RouteLine::nearest(behind, osg::Vec3d(0, 2, -1), persp, osg::Vec2d(100, 100)).index, -1);
    // The nearest in pixels, not in scene units: of two lines 1 and 2 units away, the one whose
    // direction of approach the view squeezes is nearer on screen.
    const RouteLine::Segments two = RouteLine::collect({drawn(R::POLYLINE, {{4, -10}, {4, 10}}, 0.0, 6.0),
                                                        drawn(R::POLYLINE, {{-10, 2}, {10, 2}}, 0.0, 6.0)});
    n = RouteLine::nearest(two, osg::Vec3d(3, 0, 0), osg::Matrixd::scale(10, 0.1, 1), unit);
    EXPECT_EQ(n.index, 1);
    EXPECT_DOUBLE_EQ(n.pixels, 0.2);
    EXPECT_EQ(RouteLine::nearest({}, osg::Vec3d(), osg::Matrixd::identity(), unit).index, -1);

    // Off-axis, from behind the eye: (-4, -5) to (4, 4) at height -1 crosses w = 0 at t = 5/9.
    // Clipped where w = 0.05 x 2 (the point's own w is 2): t = 5.1/9, at x = -4 + 8 x 5.1/9
    // = 0.5333, NDC (5.3333, -10); the far end (4, 4) at NDC (1, -0.25). The point (0, 2, -1)
    // is at NDC (0, -0.5): its distance to that segment, times 100 px.
    const RouteLine::Segments diagonal =
        RouteLine::collect({drawn(R::POLYLINE, {{-4, -5}, {4, 4}}, 0.0, 6.0)});
    n = RouteLine::nearest(diagonal, osg::Vec3d(0, 2, -1), persp, osg::Vec2d(100, 100));
    ASSERT_EQ(n.index, 0);
    const osg::Vec2d a(0.53333333333333333 / 0.1, -10.0), b(1.0, -0.25), q(0.0, -0.5);
    const osg::Vec2d ab = b - a;
    const double t = std::clamp(((q - a) * ab) / (ab * ab), 0.0, 1.0);
    EXPECT_NEAR(n.pixels, 100.0 * (a + ab * t - q).length(), 1e-6);
    // The segment chosen is the one that covers the point most (half width minus distance): a
    // wide route 3 px away (margin 10 - 3) wins over a 1 px line through the point (margin 0.5).
    const RouteLine::Segments both = RouteLine::collect({drawn(R::POLYLINE, {{-10, 0}, {10, 0}}, 0.0, 1.0),
                                                         drawn(R::POLYLINE, {{-10, 3}, {10, 3}}, 0.0, 20.0)});
    n = RouteLine::nearest(both, osg::Vec3d(0, 0, 0), osg::Matrixd::identity(), unit);
    EXPECT_EQ(n.index, 1);
    EXPECT_DOUBLE_EQ(n.pixels, 3.0);
}

TEST(RouteLineTest, ShadeHasAFillACasingAndAnAntiAliasedRim)
{
    RouteLine::Segment s;
    s.width = 6.0;
    s.color = osg::Vec4f(0.2f, 0.4f, 0.8f, 1.0f);
    const osg::Vec3f ground(1.0f, 1.0f, 1.0f);
    // Centre: the colour.
    EXPECT_EQ(RouteLine::shade(ground, 0.0, s), osg::Vec3f(0.2f, 0.4f, 0.8f));
    EXPECT_EQ(RouteLine::shade(ground, 1.5, s), osg::Vec3f(0.2f, 0.4f, 0.8f)); // fill up to 3 - 1.5
    // 2.75 px: the fill's coverage is 3 - 0.5 - 2.75 < 0 -> casing, coverage 3.5 - 2.75 = 0.75.
    const osg::Vec3f casing = osg::Vec3f(0.2f, 0.4f, 0.8f) * 0.55f;
    osg::Vec3f c = RouteLine::shade(ground, 2.75, s);
    for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(c[k], 0.25f + 0.75f * casing[k], 1e-6f) << k;
    // Half way between fill and casing: 2.25 px -> fill coverage 0.25.
    c = RouteLine::shade(ground, 2.25, s);
    EXPECT_NEAR(c[2], 0.8f * (0.55f * 0.75f + 0.25f), 1e-6f);
    // 3.5 px and beyond: the ground.
    EXPECT_EQ(RouteLine::shade(ground, 3.5, s), ground);
    EXPECT_EQ(RouteLine::shade(ground, 100.0, s), ground);
    // Narrow lines (< 4 px) have no casing; opacity scales the coverage.
    s.width = 3.0;
    s.color.a() = 0.5f;
    c = RouteLine::shade(ground, 1.0, s); // coverage 1 x 0.5
    EXPECT_NEAR(c[0], 0.5f + 0.5f * 0.2f, 1e-6f);
}

TEST(RouteLineTest, ApplySetsTheTextureLayoutAndClearsIt)
{
    osg::ref_ptr<osg::StateSet> ss = new osg::StateSet;
    RouteLine::Segments segments =
        RouteLine::collect({drawn(R::POLYLINE, {{-3, 1}, {7, 1}, {7, 9}}, 0.0, 8.0)});
    RouteLine::apply(*ss, segments);
    int count = 0, rows = 0;
    ASSERT_TRUE(ss->getUniform("loa_routeLineCount")->get(count));
    ASSERT_TRUE(ss->getUniform("loa_routeLineRows")->get(rows));
    EXPECT_EQ(count, 2);
    EXPECT_EQ(rows, 1);
    auto* t = dynamic_cast<osg::Texture2D*>(
        ss->getTextureAttribute(RouteLine::kUnit, osg::StateAttribute::TEXTURE));
    ASSERT_NE(t, nullptr);
    const osg::Image* image = t->getImage();
    ASSERT_EQ(image->s(), 2);
    ASSERT_EQ(image->t(), 3); // end points, colours, widths
    const float* geometry = reinterpret_cast<const float*>(image->data(1, 0));
    EXPECT_EQ(osg::Vec4f(geometry[0], geometry[1], geometry[2], geometry[3]), osg::Vec4f(7, 1, 7, 9));
    const float* color = reinterpret_cast<const float*>(image->data(1, 1));
    EXPECT_EQ(color[2], R::defaultLineColor().b());
    EXPECT_EQ(*reinterpret_cast<const float*>(image->data(0, 2)), 8.0f);
    // 4097 segments: two rows a group, the second holding one.
    segments.assign(4097, segments[0]);
    segments[4096].a.set(40, 40);
    RouteLine::apply(*ss, segments);
    t = dynamic_cast<osg::Texture2D*>(
        ss->getTextureAttribute(RouteLine::kUnit, osg::StateAttribute::TEXTURE));
    ASSERT_EQ(t->getImage()->s(), RouteLine::kTextureWidth);
    ASSERT_EQ(t->getImage()->t(), 6);
    EXPECT_EQ(*reinterpret_cast<const float*>(t->getImage()->data(0, 1)), 40.0f);
    // More than kMaxSegments: refused, nothing changed.
    RouteLine::Segments many(std::size_t(RouteLine::kMaxSegments) + 1, segments[0]);
    try
    {
        RouteLine::apply(*ss, many);
        ADD_FAILURE() << "too many segments accepted";
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("8193 segments to draw, more than the 8192"), std::string::npos)
            << e.what();
    }
    ss->getUniform("loa_routeLineCount")->get(count);
    EXPECT_EQ(count, 4097);
    // None: count 0 and no texture.
    RouteLine::apply(*ss, {});
    ss->getUniform("loa_routeLineCount")->get(count);
    EXPECT_EQ(count, 0);
    EXPECT_EQ(ss->getTextureAttribute(RouteLine::kUnit, osg::StateAttribute::TEXTURE), nullptr);
}

TEST(RouteLineTest, RegionLineWidthAndColourAreChecked)
{
    osg::ref_ptr<R> r = new R(R::POLYLINE, {{0, 0}, {1, 0}});
    EXPECT_EQ(r->getLineWidth(), 0.0);
    r->setLineWidth(64.0);
    EXPECT_THROW(r->setLineWidth(64.5), std::invalid_argument);
    EXPECT_THROW(r->setLineWidth(-0.5), std::invalid_argument);
    EXPECT_THROW(r->setLineWidth(std::nan("")), std::invalid_argument);
    EXPECT_EQ(r->getLineWidth(), 64.0);
    EXPECT_EQ(r->validate(), "");
    r->setName("to the station");
    r->setLineColor(osg::Vec4f(0.5f, 1.5f, 0.0f, 1.0f));
    EXPECT_EQ(r->validate(), "polyline 'to the station' has a line colour component outside [0, 1]");
    // A scenario with such a region does not validate.
    osg::ref_ptr<UsageScenario> s = new UsageScenario;
    s->addRegion(r.get());
    bool named = false;
    for (const std::string& e : s->validate().errors)
        named = named || e.find("line colour") != std::string::npos;
    EXPECT_TRUE(named);
    // Copies keep the line.
    r->setLineColor(osg::Vec4f(0.5f, 0.5f, 0.0f, 1.0f));
    osg::ref_ptr<R> copy = new R(*r);
    EXPECT_EQ(copy->getLineWidth(), 64.0);
    EXPECT_EQ(copy->getLineColor(), osg::Vec4f(0.5f, 0.5f, 0.0f, 1.0f));
}
