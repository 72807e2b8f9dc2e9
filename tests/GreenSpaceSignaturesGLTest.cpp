// Green-space signatures drawn through the LoA pipeline (paper 004 Figure 8B; osgLoA::
// GreenSpaceSignatures): top-down, the symbols the frame shows are those the CPU twin places, at
// 1920x1080, an odd size and in an offset viewport; in a perspective view they keep their size on
// screen near and far and stand upright; 3D vegetation gives way to its signatures; on the demo
// city and a real OpenStreetMap file (Debian's python-osmnx documentation) the style differs from
// flat cartographic on green spaces only.
#include "support/TestSupport.h"
#include "support/TopDownView.h"

#include <osgLoA/city/CityGenerator>
#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/semantics/Feature>
#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/styles/GreenSpaceSignatures>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/ScenarioLibrary>

#include <osg/Geode>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <vector>

using namespace osgLoA;
using GSS = GreenSpaceSignatures;

namespace
{
using loatest::Viewport;

void keep(const osg::Image& image, const std::string& name)
{
    loatest::keepFrame("signatures", image, name);
}

/** A green feature of this sub-type over [x0, x1] x [y0, y1]. */
osg::ref_ptr<osg::Node> green(const std::string& subType, double x0, double y0, double x1, double y1)
{
    return loatest::featureQuad(1, FeatureType::Green, subType, x0, y0, x1, y1);
}

int maxChannelDiff(const osg::Image& a, const osg::Image& b, int x, int y)
{
    const unsigned char *p = a.data(x, y), *q = b.data(x, y);
    return std::max(
        {std::abs(int(p[0]) - int(q[0])), std::abs(int(p[1]) - int(q[1])), std::abs(int(p[2]) - int(q[2]))});
}

/** Top-down: the frame's symbol pixels against the CPU twin's, pixel by pixel. */
void expectSymbolsOfTheTwin(int width, int height, const Viewport& vp)
{
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    scene->addChild(green("mixed", 0, 0, 60, 40).get());
    scene->addChild(
        loatest::asFeature(loatest::planeQuad(70, 0, 90, 40).get(), 2, FeatureType::Building).get());
    const osg::BoundingBoxd view(-5, -5, 0, 95, 45, 0);
    osg::ref_ptr<osg::Image> sig = loatest::topDown(scene.get(), "signatures", width, height, vp, view);
    osg::ref_ptr<osg::Image> flat = loatest::topDown(scene.get(), "cartographic", width, height, vp, view);
    const std::string label = std::to_string(width) + "x" + std::to_string(height) + " viewport " +
                              std::to_string(vp.x) + "," + std::to_string(vp.y) + " " + std::to_string(vp.w) +
                              "x" + std::to_string(vp.h);
    keep(*sig, "twin-" + std::to_string(width) + "x" + std::to_string(height) + "-" + std::to_string(vp.x));
    const double sx = 100.0 / vp.w, sy = 50.0 / vp.h, sigma = std::max(sx, sy);
    const GSS::Projector project = [&](const osg::Vec3d& w)
    { return osg::Vec3d(vp.x + (w.x() + 5.0) / sx, vp.y + (w.y() + 5.0) / sy, 0.0); };
    long symbolPixels = 0, glPixels = 0, mismatched = 0, building = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
        {
            const int diff = maxChannelDiff(*sig, *flat, x, y);
            const bool inside = x >= vp.x && x < vp.x + vp.w && y >= vp.y && y < vp.y + vp.h;
            if (!inside) continue; // (drawn by topDown's first, full-target frame)
            const osg::Vec2d pixel(x + 0.5, y + 0.5);
            const osg::Vec3d world(-5.0 + (pixel.x() - vp.x) * sx, -5.0 + (pixel.y() - vp.y) * sy, 0.0);
            if (world.x() > 70.5 && world.x() < 89.5 && world.y() > 0.5 && world.y() < 39.5)
            {
                building += diff > 0;
                continue;
            }
            // Green ground away from its borders (the compositor's edges lie on them).
            if (!(world.x() > 1.0 && world.x() < 59.0 && world.y() > 1.0 && world.y() < 39.0)) continue;
            const GSS::Sample s =
                GSS::sample(GSS::MIXED, world, osg::Vec3d(0, 0, 1), pixel, sigma, project, GSS::Parameters());
            const bool gl = diff > 24;
            glPixels += gl;
            if (s.alpha > 0.5) ++symbolPixels;
            // Anti-aliased rims (alpha 0.1-0.9) may fall either side of the threshold.
            if (s.alpha > 0.1 && s.alpha < 0.9) continue;
            mismatched += gl != (s.alpha >= 0.9);
        }
    std::cout << "signatures " << label << ": " << symbolPixels << " symbol pixels in the twin, " << glPixels
              << " in the frame, " << mismatched << " disagree away from rims\n";
    EXPECT_GT(symbolPixels, 2000L * vp.w * vp.h / (1920L * 1080L)) << label;
    EXPECT_LE(double(mismatched), 0.01 * double(symbolPixels)) << label;
    EXPECT_EQ(building, 0) << label << ": the building changed";
}

struct Blob
{
    int x0, y0, x1, y1;
    long area;
};

/** Connected components (4-neighbours) of a pixel mask. */
std::vector<Blob> blobs(const std::vector<unsigned char>& mask, int w, int h)
{
    std::vector<int> label(mask.size(), -1);
    std::vector<Blob> out;
    std::vector<int> stack;
    for (int start = 0; start < w * h; ++start)
    {
        if (!mask[std::size_t(start)] || label[std::size_t(start)] >= 0) continue;
        Blob b{w, h, -1, -1, 0};
        stack.push_back(start);
        label[std::size_t(start)] = int(out.size());
        while (!stack.empty())
        {
            const int p = stack.back();
            stack.pop_back();
            const int x = p % w, y = p / w;
            b.x0 = std::min(b.x0, x), b.x1 = std::max(b.x1, x), b.y0 = std::min(b.y0, y),
            b.y1 = std::max(b.y1, y);
            ++b.area;
            for (const int q :
                 {x > 0 ? p - 1 : -1, x + 1 < w ? p + 1 : -1, y > 0 ? p - w : -1, y + 1 < h ? p + w : -1})
                if (q >= 0 && mask[std::size_t(q)] && label[std::size_t(q)] < 0)
                {
                    label[std::size_t(q)] = int(out.size());
                    stack.push_back(q);
                }
        }
        out.push_back(b);
    }
    return out;
}

double median(std::vector<double> v)
{
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    return v[v.size() / 2];
}
} // namespace

TEST(GreenSpaceSignaturesGLTest, SymbolsAreTheTwinsAt1920x1080)
{
    expectSymbolsOfTheTwin(1920, 1080, Viewport{0, 0, 1920, 1080});
}

TEST(GreenSpaceSignaturesGLTest, SymbolsAreTheTwinsAtAnOddSizeAndInAnOffsetViewport)
{
    expectSymbolsOfTheTwin(641, 359, Viewport{0, 0, 641, 359});
    expectSymbolsOfTheTwin(577, 343, Viewport{37, 21, 500, 300});
}

// A perspective view 45 degrees down over a coniferous forest floor: symbols near the camera and
// far from it have the same height on screen (a flat decal would shrink with distance and be
// foreshortened), and stand upright (taller than wide, as the symbol is: 0.98 by 0.6).
TEST(GreenSpaceSignaturesGLTest, SymbolsKeepTheirSizeOnScreenAndStandUpright)
{
    const int w = 1280, h = 720;
    osg::ref_ptr<osg::Node> forest = green("coniferous", -300, -300, 300, 300);
    auto frame = [&](const std::string& style)
    {
        osg::ref_ptr<LoANode> loa = new LoANode;
        loa->setScenario(ScenarioLibrary::createHomogeneous(style).get());
        loa->addChild(forest.get());
        OffscreenRenderer::Settings s;
        s.width = w;
        s.height = h;
        osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(s);
        r->setSceneData(loa.get());
        r->getCamera()->setProjectionMatrixAsPerspective(50.0, double(w) / h, 1.0, 2000.0);
        r->setViewMatrixAsLookAt(osg::Vec3d(0, -60, 60), osg::Vec3d(0, 0, 0), osg::Vec3d(0, 0, 1));
        return r->renderImage();
    };
    osg::ref_ptr<osg::Image> sig = frame("signatures"), flat = frame("cartographic");
    keep(*sig, "perspective-1280x720");
    std::vector<unsigned char> mask(std::size_t(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            mask[std::size_t(y) * w + x] = maxChannelDiff(*sig, *flat, x, y) > 40 ? 1 : 0;
    const GSS::Parameters p;
    // Single symbols (not two merged): at most one symbol tall and wide.
    std::vector<double> nearH, farH, nearRatio, farRatio;
    for (const Blob& b : blobs(mask, w, h))
    {
        const double bh = b.y1 - b.y0 + 1, bw = b.x1 - b.x0 + 1;
        if (b.area < 20 || bh > 1.4 * p.symbolPixels || bw > 0.9 * p.symbolPixels) continue;
        (b.y0 < h / 3 ? nearH : b.y0 > 2 * h / 3 ? farH : nearRatio).push_back(bh);
        if (b.y0 < h / 3) nearRatio.push_back(bh / bw);
        if (b.y0 > 2 * h / 3) farRatio.push_back(bh / bw);
    }
    // (Window rows count from the bottom: the near ground is at the bottom.)
    std::cout << "signatures perspective: " << nearH.size() << " symbols near, median height "
              << median(nearH) << " px, h/w " << median(nearRatio) << "; " << farH.size()
              << " far, median height " << median(farH) << " px, h/w " << median(farRatio) << "\n";
    ASSERT_GT(nearH.size(), 10u);
    ASSERT_GT(farH.size(), 10u);
    // 0.98 of 11 px plus the 1 px of outline and anti-aliasing: 11-13 px, near and far alike.
    EXPECT_NEAR(median(nearH), 12.0, 1.5);
    EXPECT_NEAR(median(farH), 12.0, 1.5);
    EXPECT_GT(median(nearRatio), 1.3);
    EXPECT_GT(median(farRatio), 1.3);
}

// A green feature with a tree: the crown gives way to the ground and its signatures, so the frame
// is exactly that of the same feature without the tree (cartographic shows the crown).
TEST(GreenSpaceSignaturesGLTest, VegetationGivesWayToItsSignatures)
{
    const int w = 641, h = 359;
    const Viewport vp{0, 0, w, h};
    const osg::BoundingBoxd view(-10, -10, 0, 90, 46, 10);
    auto park = [&](bool tree)
    {
        osg::ref_ptr<osg::Geode> geode = new osg::Geode;
        geode->addDrawable(loatest::planeQuad(0, 0, 80, 36).get());
        if (tree) geode->addDrawable(loatest::planeQuad(30, 10, 40, 20, 0, 0, 8).get());
        osg::ref_ptr<osg::Group> g = new osg::Group;
        g->addChild(geode.get());
        Feature::attach(*g, new Feature(1, FeatureType::Green, "park"));
        return osg::ref_ptr<osg::Node>(g);
    };
    osg::ref_ptr<osg::Node> with = park(true), without = park(false);
    osg::ref_ptr<osg::Image> a = loatest::topDown(with.get(), "signatures", w, h, vp, view);
    osg::ref_ptr<osg::Image> b = loatest::topDown(without.get(), "signatures", w, h, vp, view);
    osg::ref_ptr<osg::Image> c = loatest::topDown(with.get(), "cartographic", w, h, vp, view);
    osg::ref_ptr<osg::Image> d = loatest::topDown(without.get(), "cartographic", w, h, vp, view);
    keep(*a, "vegetation-641x359");
    long differ = 0, crown = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            differ += maxChannelDiff(*a, *b, x, y) > 0;
            crown += maxChannelDiff(*c, *d, x, y) > 8;
        }
    std::cout << "signatures: " << differ << " pixels differ with the tree; cartographic shows " << crown
              << " pixels of it\n";
    EXPECT_EQ(differ, 0);
    EXPECT_GT(crown, 2000); // 10 x 10 m of 100 x 56 m at 641 px: about 4,100 pixels
}

TEST(GreenSpaceSignaturesGLTest, DiffersFromCartographicOnGreenSpacesOnlyInTheDemoCity)
{
    osg::ref_ptr<osg::Node> city = CityGenerator(CityParameters()).generate();
    const loatest::MaskedDifference d = loatest::differenceInMask(city.get(), "signatures", "cartographic",
                                                                  loatest::typeMaskStyle(FeatureType::Green),
                                                                  1920, 1080, "signatures", "demo-city");
    EXPECT_EQ(d.outside, 0);
    ASSERT_GT(d.inside, 0);
    EXPECT_GT(double(d.changed), 0.05 * d.inside);
}

TEST(GreenSpaceSignaturesGLTest, DiffersFromCartographicOnGreenSpacesOnlyInARealOsmFile)
{
    const std::string file = std::string(LOA_SOURCE_DIR) + "/data/cache/python-osmnx-doc/West-Oakland.osm";
    if (!osgDB::fileExists(file)) GTEST_SKIP() << file << " is absent: run scripts/fetch-test-data";
    osg::ref_ptr<osg::Node> model = osgDB::readRefNodeFile(file);
    ASSERT_TRUE(model.valid());
    // The file's green areas, counted by hand: one closed way leisure=park and one
    // leisure=playground, both drawn as grass. (kirchberg.osm, the other osmnx sample, has none
    // the reader can build: its forest relation's one outer way and its grassland way are cut open
    // by the extract's bounds.)
    std::map<std::string, int> subTypes;
    osg::BoundingBoxd parks;
    const FeatureIndex index(*model);
    for (const FeatureIndex::Entry& e : index.entries())
        if (e.feature->getType() == FeatureType::Green)
        {
            ++subTypes[e.feature->getSubType()];
            const osg::BoundingBoxf& b = e.feature->getBound();
            parks.expandBy(osg::Vec3d(b._min));
            parks.expandBy(osg::Vec3d(b._max));
        }
    // Framed on the parks and their surroundings (the whole extract makes them a few pixels).
    ASSERT_TRUE(parks.valid());
    const osg::Vec3d c = parks.center(), half = (parks._max - parks._min) * 1.5;
    const osg::BoundingBoxd frame(c - half, c + half);
    EXPECT_EQ(subTypes, (std::map<std::string, int>{{"park", 1}, {"playground", 1}}));
    const loatest::MaskedDifference d = loatest::differenceInMask(
        model.get(), "signatures", "cartographic", loatest::typeMaskStyle(FeatureType::Green), 1920, 1080,
        "signatures", "west-oakland", &frame);
    EXPECT_EQ(d.outside, 0);
    ASSERT_GT(d.inside, 0);
    EXPECT_GT(double(d.changed), 0.05 * d.inside);
}
