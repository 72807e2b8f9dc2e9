// The route drawn on the ground (osgLoA::RouteLine, shaders/loa_route_line.glsl): top-down, every
// pixel of the frame equals the CPU twin (RouteLine::nearest and shade over the frame without the
// line) at 1920x1080, an odd size and in an offset viewport; a building's roof and a slope
// steeper than 60 degrees on the route keep their colour; in perspective the line is as wide in
// pixels near as far; on West Oakland (OpenStreetMap) the library's route scenario draws its route
// along the streets, pixel for pixel as the twin says.
#include "support/TestSupport.h"
#include "support/TopDownView.h"

#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/transitions/RouteLine>
#include <osgLoA/transitions/ScenarioLibrary>

#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>

using namespace osgLoA;

namespace
{
int maxDiff(const unsigned char* p, const unsigned char* q)
{
    return std::max(
        {std::abs(int(p[0]) - int(q[0])), std::abs(int(p[1]) - int(q[1])), std::abs(int(p[2]) - int(q[2]))});
}

osg::ref_ptr<UsageScenario> withLine(const std::string& style, const RegionOfInterest::Vertices& route,
                                     double width)
{
    osg::ref_ptr<UsageScenario> s = ScenarioLibrary::createHomogeneous(style);
    osg::ref_ptr<RegionOfInterest> r = new RegionOfInterest(RegionOfInterest::POLYLINE, route);
    r->setName("route");
    r->setLineWidth(width);
    s->addRegion(r.get());
    return s;
}

/** The frame's pixels against the twin: frame = shade(plain, nearest) wherever `onGround` says the
 *  line may be drawn, frame = plain elsewhere. Returns the pixels differing by more than 3/255
 *  and counts the line's pixels (twin coverage > 0) into `linePixels`. */
long compareWithTwin(const osg::Image& frame, const osg::Image& plain, const RouteLine::Segments& segments,
                     const osg::BoundingBoxd& view, const loatest::Viewport& vp,
                     const std::function<bool(const osg::Vec2d&)>& onGround, long& linePixels)
{
    // topDown's camera: orthographic over the view's x/y, looking down.
    const double top = view.zMax() + 500.0;
    const osg::Matrixd sceneToClip =
        osg::Matrixd::lookAt(osg::Vec3d(0, 0, top), osg::Vec3d(0, 0, 0), osg::Vec3d(0, 1, 0)) *
        osg::Matrixd::ortho(view.xMin(), view.xMax(), view.yMin(), view.yMax(), 1.0,
                            top - view.zMin() + 10.0);
    const osg::Vec2d pixelsPerNdc(0.5 * vp.w, 0.5 * vp.h);
    const double sx = (view.xMax() - view.xMin()) / vp.w, sy = (view.yMax() - view.yMin()) / vp.h;
    long bad = 0;
    linePixels = 0;
    for (int y = 0; y < frame.t(); ++y)
        for (int x = 0; x < frame.s(); ++x)
        {
            const unsigned char *p = frame.data(x, y), *q = plain.data(x, y);
            unsigned char expect[3] = {q[0], q[1], q[2]};
            const bool inside = x >= vp.x && y >= vp.y && x < vp.x + vp.w && y < vp.y + vp.h;
            const osg::Vec2d w(view.xMin() + (x - vp.x + 0.5) * sx, view.yMin() + (y - vp.y + 0.5) * sy);
            if (inside && onGround(w))
            {
                const RouteLine::Nearest n =
                    RouteLine::nearest(segments, osg::Vec3d(w, 0.0), sceneToClip, pixelsPerNdc);
                const RouteLine::Segment& s = segments[std::size_t(n.index)];
                if (n.pixels < 0.5 * s.width + 0.5) ++linePixels;
                const osg::Vec3f c =
                    RouteLine::shade(osg::Vec3f(q[0], q[1], q[2]) / 255.0f, n.pixels, s) * 255.0f;
                for (int k = 0; k < 3; ++k)
                    expect[k] = (unsigned char)std::lround(c[k]);
            }
            if (maxDiff(p, expect) > 3 && ++bad <= 8)
                std::cout << "  differs at " << x << "," << y << " (" << w.x() << ", " << w.y()
                          << "): " << int(p[0]) << " " << int(p[1]) << " " << int(p[2]) << " vs "
                          << int(expect[0]) << " " << int(expect[1]) << " " << int(expect[2]) << "\n";
        }
    return bad;
}

// Terrain over [0, 200] x [0, 120]; a building roof (z = 10) and a 71.6-degree slope across the
// route; the route an L: along y = 50 from x = 20 to 150, then north to y = 100.
void expectTwin(int width, int height, const loatest::Viewport& vp)
{
    osg::ref_ptr<osg::Group> model = new osg::Group;
    model->addChild(loatest::featureQuad(1, FeatureType::Terrain, "", -10, -10, 210, 130).get());
    model->addChild(loatest::asFeature(loatest::planeQuad(60.3, 44.3, 80.1, 55.7, 0.0, 0.0, 10.0).get(), 2,
                                       FeatureType::Building)
                        .get());
    model->addChild(loatest::asFeature(loatest::planeQuad(100.1, 40.2, 104.9, 60.3, 3.0, 0.0, -300.3).get(),
                                       3, FeatureType::Terrain)
                        .get());
    const RegionOfInterest::Vertices route = {{20.0, 50.0}, {150.0, 50.0}, {150.0, 100.0}};
    const double aspect = double(vp.w) / vp.h;
    const osg::BoundingBoxd view(0.0, 60.0 - 100.0 / aspect, -1.0, 200.0, 60.0 + 100.0 / aspect, 20.0);
    osg::ref_ptr<osg::Image> plain =
        loatest::topDown(model.get(), withLine("photorealistic", route, 0.0).get(), width, height, vp, view);
    osg::ref_ptr<osg::Image> line =
        loatest::topDown(model.get(), withLine("photorealistic", route, 6.0).get(), width, height, vp, view);
    osg::ref_ptr<UsageScenario> s = withLine("photorealistic", route, 6.0);
    const RouteLine::Segments segments = RouteLine::collect(s->getRegions());
    ASSERT_EQ(segments.size(), 2u);
    auto onGround = [](const osg::Vec2d& p)
    {
        const bool roof = p.x() > 60.3 && p.x() < 80.1 && p.y() > 44.3 && p.y() < 55.7;
        const bool steep = p.x() > 100.1 && p.x() < 104.9 && p.y() > 40.2 && p.y() < 60.3;
        return !roof && !steep;
    };
    long linePixels = 0;
    const long bad = compareWithTwin(*line, *plain, segments, view, vp, onGround, linePixels);
    const std::string size = std::to_string(width) + "x" + std::to_string(height);
    loatest::keepFrame("route-line", *line, "twin-" + size);
    // The line's length in pixels (less the parts under the roof and the slope) times 6 or 7
    // (its width, plus a row of rim where its edges fall between pixel centres), plus the caps.
    const double perUnit = vp.w / 200.0;
    const double visible = (130.0 + 50.0 - (80.1 - 60.3) - (104.9 - 100.1)) * perUnit;
    std::cout << size << ": " << linePixels << " line pixels (about " << long(visible * 7.0) << "), " << bad
              << " differ from the twin\n";
    EXPECT_GE(double(linePixels), visible * 6.0);
    EXPECT_LE(double(linePixels), visible * 7.0 + 80.0);
    EXPECT_EQ(bad, 0);
    // The line's centre is its colour; its rim the casing (0.55 of it).
    const double sy = (view.yMax() - view.yMin()) / vp.h;
    const int cx = vp.x + int(40.0 * perUnit), cy = vp.y + int((50.0 - view.yMin()) / sy);
    const unsigned char* centre = line->data(cx, cy);
    EXPECT_NEAR(centre[0], 55, 2);
    EXPECT_NEAR(centre[1], 126, 2);
    EXPECT_NEAR(centre[2], 184, 2);
}
} // namespace

TEST(RouteLineGLTest, EveryPixelIsTheTwinsAt1920x1080)
{
    expectTwin(1920, 1080, loatest::Viewport{0, 0, 1920, 1080});
}

TEST(RouteLineGLTest, EveryPixelIsTheTwinsAtAnOddSizeAndInAnOffsetViewport)
{
    expectTwin(641, 359, loatest::Viewport{0, 0, 641, 359});
    expectTwin(577, 343, loatest::Viewport{37, 21, 500, 300});
}

// A ground plane seen from 10 m up, looking north: two east-west routes at 20 m and 150 m. In the
// frame's middle column each is a run of 6 or 7 changed pixels (6 px wide, anti-aliased rims),
// near and far alike, while the ground's own scale differs 7-fold between them.
TEST(RouteLineGLTest, AsWideInPixelsNearAsFarInPerspective)
{
    osg::ref_ptr<osg::Node> ground =
        loatest::featureQuad(1, FeatureType::Terrain, "", -2000, -100, 2000, 3000);
    for (const auto& size : {std::pair<int, int>(1920, 1080), std::pair<int, int>(641, 359)})
    {
        const int w = size.first, h = size.second;
        auto frame = [&](double width)
        {
            osg::ref_ptr<UsageScenario> s = ScenarioLibrary::createHomogeneous("photorealistic");
            for (double y : {20.0, 150.0})
            {
                osg::ref_ptr<RegionOfInterest> r =
                    new RegionOfInterest(RegionOfInterest::POLYLINE, {{-500.0, y}, {500.0, y}});
                r->setLineWidth(width);
                s->addRegion(r.get());
            }
            return loatest::throughLoA(
                ground.get(), s.get(), w, h, loatest::Viewport{0, 0, w, h},
                [&](OffscreenRenderer& r)
                {
                    r.getCamera()->setProjectionMatrixAsPerspective(40.0, double(w) / h, 1.0, 5000.0);
                    r.setViewMatrixAsLookAt(osg::Vec3d(0, -10, 10), osg::Vec3d(0, 200, 0),
                                            osg::Vec3d(0, 0, 1));
                });
        };
        osg::ref_ptr<osg::Image> plain = frame(0.0), line = frame(6.0);
        loatest::keepFrame("route-line", *line, "perspective-" + std::to_string(w) + "x" + std::to_string(h));
        std::vector<int> runs;
        int run = 0;
        for (int y = 0; y < h; ++y)
        {
            const bool changed = maxDiff(line->data(w / 2, y), plain->data(w / 2, y)) > 8;
            if (changed)
                ++run;
            else if (run)
                runs.push_back(run), run = 0;
        }
        if (run) runs.push_back(run);
        for (int r : runs)
            std::cout << w << "x" << h << ": run of " << r << "\n";
        ASSERT_EQ(runs.size(), 2u) << w << "x" << h;
        for (int r : runs)
        {
            EXPECT_GE(r, 6) << w << "x" << h;
            EXPECT_LE(r, 7) << w << "x" << h;
        }
    }
}

// In perspective, with the route running under the camera and behind it (the case where a segment
// crosses the eye plane and is clipped): every pixel whose ground point (the pixel centre's ray
// met with z = 0) is on the ground quad equals the twin's colour within 3/255, but for at most
// 0.5 % of the line's pixels (float against double on the one-pixel rims).
TEST(RouteLineGLTest, EveryPixelIsTheTwinsInPerspectiveWithTheRouteUnderTheCamera)
{
    osg::ref_ptr<osg::Node> ground =
        loatest::featureQuad(1, FeatureType::Terrain, "", -2000, -100, 2000, 3000);
    const RegionOfInterest::Vertices route = {{-60.0, -60.0}, {40.0, 30.0}, {40.0, 300.0}};
    for (const auto& size : {std::pair<int, int>(1920, 1080), std::pair<int, int>(641, 359)})
    {
        const int w = size.first, h = size.second;
        const osg::Vec3d eye(0, -10, 10), centre(0, 200, 0), up(0, 0, 1);
        const osg::Matrixd view = osg::Matrixd::lookAt(eye, centre, up);
        const osg::Matrixd projection = osg::Matrixd::perspective(40.0, double(w) / h, 1.0, 5000.0);
        auto frame = [&](double width)
        {
            return loatest::throughLoA(ground.get(), withLine("photorealistic", route, width).get(), w, h,
                                       loatest::Viewport{0, 0, w, h},
                                       [&](OffscreenRenderer& r)
                                       {
                                           r.getCamera()->setProjectionMatrix(projection);
                                           r.setViewMatrixAsLookAt(eye, centre, up);
                                       });
        };
        osg::ref_ptr<osg::Image> plain = frame(0.0), line = frame(6.0);
        const std::string name = std::to_string(w) + "x" + std::to_string(h);
        loatest::keepFrame("route-line", *line, "under-the-camera-" + name);
        const RouteLine::Segments segments =
            RouteLine::collect(withLine("photorealistic", route, 6.0)->getRegions());
        const osg::Matrixd sceneToClip = view * projection, clipToScene = osg::Matrixd::inverse(sceneToClip);
        long linePixels = 0, bad = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
            {
                const double nx = (x + 0.5) / w * 2.0 - 1.0, ny = (y + 0.5) / h * 2.0 - 1.0;
                const osg::Vec3d nearPoint = osg::Vec3d(nx, ny, -1.0) * clipToScene;
                const osg::Vec3d farPoint = osg::Vec3d(nx, ny, 1.0) * clipToScene;
                const osg::Vec3d d = farPoint - nearPoint;
                if (!(d.z() < 0.0)) continue; // the sky
                const osg::Vec3d p = nearPoint + d * (-nearPoint.z() / d.z());
                if (p.y() < -100.0 || p.y() > 3000.0 || std::fabs(p.x()) > 2000.0) continue;
                const RouteLine::Nearest n =
                    RouteLine::nearest(segments, p, sceneToClip, osg::Vec2d(0.5 * w, 0.5 * h));
                if (n.index < 0 || n.pixels >= 3.5) continue;
                ++linePixels;
                const unsigned char* q = plain->data(x, y);
                const osg::Vec3f c = RouteLine::shade(osg::Vec3f(q[0], q[1], q[2]) / 255.0f, n.pixels,
                                                      segments[std::size_t(n.index)]) *
                                     255.0f;
                const unsigned char expect[3] = {(unsigned char)std::lround(c[0]),
                                                 (unsigned char)std::lround(c[1]),
                                                 (unsigned char)std::lround(c[2])};
                bad += maxDiff(line->data(x, y), expect) > 3;
            }
        // Outside the line nothing changes.
        long outside = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                outside += maxDiff(line->data(x, y), plain->data(x, y)) > 3;
        std::cout << name << ": " << linePixels << " line pixels, " << bad << " differ from the twin; "
                  << outside << " changed pixels in all\n";
        EXPECT_GT(linePixels, 1000) << name; // 5,562 at 1920x1080, 1,881 at 641x359
        EXPECT_LE(double(bad), 0.005 * linePixels) << name;
        EXPECT_LE(outside, linePixels) << name;
    }
}

// West Oakland (python-osmnx's documentation, OpenStreetMap): the route scenario of the library
// places its route along the longest chain of streets (ScenarioFitting) and draws it. Every pixel
// equals the twin's except where the route crosses something that is not ground (a building or a
// wall): at most 2 % of the line's pixels; the line's middle (its central 2 px) lies on streets
// (98 % or more; the line, 6 px = 9 m here, is wider than a residential street).
TEST(RouteLineGLTest, TheRouteScenarioDrawsItsRouteAlongTheStreetsOfARealOsmFile)
{
    const std::string file = std::string(LOA_SOURCE_DIR) + "/data/cache/python-osmnx-doc/West-Oakland.osm";
    if (!osgDB::fileExists(file)) GTEST_SKIP() << file << " is absent: run scripts/fetch-test-data";
    osg::ref_ptr<osg::Node> model = osgDB::readRefNodeFile(file);
    ASSERT_TRUE(model.valid());
    osg::ref_ptr<UsageScenario> route = ScenarioLibrary::createBuiltin("route");
    ASSERT_EQ(route->getRegions().size(), 1u);
    EXPECT_EQ(route->getRegions()[0]->getLineWidth(), 6.0);
    osg::ref_ptr<UsageScenario> noLine = osg::clone(route.get(), osg::CopyOp::DEEP_COPY_ALL);
    noLine->getRegions()[0]->setLineWidth(0.0);

    // The route as fitted to the model.
    osg::ref_ptr<LoANode> probe = new LoANode;
    probe->setScenario(route.get());
    probe->addChild(model.get());
    probe->bind();
    ASSERT_EQ(probe->getBindError(), "");
    const RouteLine::Segments segments =
        RouteLine::collect(probe->getEvaluator()->getScenario()->getRegions());
    for (const RouteLine::Segment& s : segments)
        std::cout << "  segment " << s.a.x() << "," << s.a.y() << " -> " << s.b.x() << "," << s.b.y() << "\n";
    ASSERT_GE(segments.size(), 1u);

    const int w = 1920, h = 1080;
    const osg::BoundingBoxd view = loatest::framedView(model.get(), w, h);
    const loatest::Viewport vp{0, 0, w, h};
    osg::ref_ptr<osg::Image> plain = loatest::topDown(model.get(), noLine.get(), w, h, vp, view);
    osg::ref_ptr<osg::Image> line = loatest::topDown(model.get(), route.get(), w, h, vp, view);
    osg::ref_ptr<osg::Image> streets =
        loatest::topDown(model.get(), loatest::typeMaskStyle(FeatureType::Street), w, h, vp, view);
    loatest::keepFrame("route-line", *line, "west-oakland-route");
    long linePixels = 0;
    const long bad = compareWithTwin(
        *line, *plain, segments, view, vp, [](const osg::Vec2d&) { return true; }, linePixels);
    // The line's middle (within 1 px of its centre line, by the twin) on the street mask.
    const osg::Matrixd sceneToClip = osg::Matrixd::lookAt(osg::Vec3d(0, 0, view.zMax() + 500.0),
                                                          osg::Vec3d(0, 0, 0), osg::Vec3d(0, 1, 0)) *
                                     osg::Matrixd::ortho(view.xMin(), view.xMax(), view.yMin(), view.yMax(),
                                                         1.0, 510.0 + view.zMax() - view.zMin());
    long middle = 0, onStreet = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const osg::Vec3d p(view.xMin() + (x + 0.5) * (view.xMax() - view.xMin()) / w,
                               view.yMin() + (y + 0.5) * (view.yMax() - view.yMin()) / h, 0.0);
            if (RouteLine::nearest(segments, p, sceneToClip, osg::Vec2d(0.5 * w, 0.5 * h)).pixels >= 1.0)
                continue;
            ++middle;
            const unsigned char* m = streets->data(x, y);
            onStreet += m[0] > m[1] + 30 && m[2] > m[1] + 30;
        }
    std::cout << "west-oakland: " << segments.size() << " segments, " << linePixels << " line pixels, " << bad
              << " differ from the twin; " << onStreet << " of the " << middle
              << " pixels of its middle on streets\n";
    ASSERT_GT(linePixels, 1000);
    EXPECT_LE(double(bad), 0.02 * linePixels);
    EXPECT_GE(double(onStreet), 0.98 * middle);
}
