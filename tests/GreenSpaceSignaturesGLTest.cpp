// Green-space signatures drawn through the LoA pipeline (paper 004 Figure 8B; osgLoA::
// GreenSpaceSignatures): top-down, the symbols the frame shows are those the CPU twin places, at
// 1920x1080, an odd size and in an offset viewport; in a perspective view they keep their size on
// screen near and far and stand upright; 3D vegetation gives way to its signatures; on the demo
// city and a real OpenStreetMap file (Debian's python-osmnx documentation) the style differs from
// flat cartographic on green spaces only.
#include "support/TestSupport.h"
#include "support/TopDownView.h"

#include <osgLoA/city/CityCameras>
#include <osgLoA/city/CityGenerator>
#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/semantics/Feature>
#include <osgLoA/semantics/FeatureClassifier>
#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/styles/GreenSpaceSignatures>
#include <osgLoA/styles/TreeSilhouettes>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/ScenarioLibrary>

#include <cstring>
#include <osg/Geode>
#include <osg/ShapeDrawable>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

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

// --- tree silhouettes (osgLoA::TreeSilhouettes, paper 004 Figure 8C) -------------------------------

namespace
{
/** "trees" with leaves of radius 1 and density 0.005 (4-5 leaves on a 40 x 40 triangle), no
 *  minimum size on screen: the leaves of the twin test. */
std::string twinTrees()
{
    const std::string name = "test-trees-twin";
    if (!GraphicStyleCatalog::instance().prototype(name))
    {
        osg::ref_ptr<GraphicStyle> t = GraphicStyleCatalog::instance().create("trees");
        t->setName(name);
        t->getParameter("loa_trees_leafRadius")->set(1.0f);
        t->getParameter("loa_trees_density")->set(0.005f);
        t->getParameter("loa_trees_minPixels")->set(0.0f);
        GraphicStyleCatalog::instance().add(*t);
    }
    return name;
}

/** A crown under a green feature: the drawable named TreeCrown. */
osg::ref_ptr<osg::Node> crownFeature(osg::Drawable* crown, unsigned id)
{
    crown->setName("TreeCrown");
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(crown);
    osg::ref_ptr<osg::Group> g = new osg::Group;
    g->addChild(geode.get());
    Feature::attach(*g, new Feature(id, FeatureType::Green, "deciduous"));
    return g;
}

void expectLeavesOfTheTwin(int w, int h, const Viewport& vp)
{
    // One crown triangle, seen from above: each leaf a disc of radius 1 at the twin's point.
    const osg::Vec3d a(0, 0, 0), b(40, 0, 0), c(0, 40, 0);
    osg::ref_ptr<osg::Geometry> tri = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    for (const osg::Vec3d& p : {a, b, c})
        v->push_back(osg::Vec3(p));
    tri->setVertexArray(v.get());
    osg::ref_ptr<osg::Vec3Array> n = new osg::Vec3Array;
    n->push_back(osg::Vec3(0, 0, 1));
    tri->setNormalArray(n.get(), osg::Array::BIND_OVERALL);
    tri->addPrimitiveSet(new osg::DrawArrays(GL_TRIANGLES, 0, 3));
    osg::ref_ptr<osg::Node> scene = crownFeature(tri.get(), 1);
    const double aspect = double(vp.w) / vp.h;
    const osg::BoundingBoxd view(-5, -5, -1, -5 + 50 * aspect, 45, 1);
    osg::ref_ptr<osg::Image> img = loatest::topDown(scene.get(), twinTrees(), w, h, vp, view);
    const std::string name = std::to_string(w) + "x" + std::to_string(h) + "-" + std::to_string(vp.x);
    keep(*img, "trees-twin-" + name);
    const std::uint32_t hash = TreeSilhouettes::triangleHash(a, b, c);
    const int count = TreeSilhouettes::spriteCount(800.0, 0.005, hash);
    const double scale = vp.h / 50.0; // pixels per unit
    std::vector<osg::Vec2d> twin;
    for (int k = 0; k < count; ++k)
    {
        const osg::Vec3d bc = TreeSilhouettes::spriteBarycentric(hash, k);
        const osg::Vec3d p = a * bc.x() + b * bc.y() + c * bc.z();
        twin.emplace_back((p.x() + 5.0) * scale, (p.y() + 5.0) * scale);
    }
    // Leaf pixels: those not of the clear colour (0.2, 0.3, 0.4), per nearest twin leaf.
    std::vector<osg::Vec2d> sum(twin.size());
    std::vector<long> pixels(twin.size(), 0);
    long stray = 0;
    for (int y = vp.y; y < vp.y + vp.h; ++y)
        for (int x = vp.x; x < vp.x + vp.w; ++x)
        {
            const unsigned char* p = img->data(x, y);
            if (std::abs(p[0] - 51) + std::abs(p[1] - 77) + std::abs(p[2] - 102) < 12) continue;
            const osg::Vec2d q(x - vp.x + 0.5, y - vp.y + 0.5);
            std::size_t best = 0;
            for (std::size_t k = 1; k < twin.size(); ++k)
                if ((twin[k] - q).length() < (twin[best] - q).length()) best = k;
            if (twin.empty() || (twin[best] - q).length() > scale + 1.5)
            {
                ++stray;
                continue;
            }
            sum[best] += q;
            ++pixels[best];
        }
    std::cout << "trees twin " << name << ": " << count << " leaves, " << stray << " stray pixels\n";
    EXPECT_GE(count, 4);
    EXPECT_EQ(stray, 0) << name;
    const double disc = 3.14159265 * scale * scale;
    for (std::size_t k = 0; k < twin.size(); ++k)
    {
        ASSERT_GT(pixels[k], 0) << name << " leaf " << k;
        const osg::Vec2d centroid = sum[k] / double(pixels[k]);
        EXPECT_LT((centroid - twin[k]).length(), 0.75) << name << " leaf " << k;
        EXPECT_NEAR(double(pixels[k]), disc, 0.1 * disc + 4.0 * scale) << name << " leaf " << k;
    }
}

/** Dark pixels inside a crown (7 x 7 neighbourhood all crown) and the share of dark pixels on its
 *  outline, seen level from `distance` with the crown (radius 4) filling 60 % of the height. */
struct CrownOutlines
{
    long interior = 0, interiorDark = 0, outline = 0, outlineDark = 0;
};
CrownOutlines crownOutlines(double distance, int w, int h)
{
    osg::ref_ptr<osg::TessellationHints> hints = new osg::TessellationHints;
    hints->setDetailRatio(2.0f);
    osg::ref_ptr<osg::ShapeDrawable> sphere =
        new osg::ShapeDrawable(new osg::Sphere(osg::Vec3(0, 0, 10), 4.0f), hints.get());
    osg::ref_ptr<osg::Node> scene = crownFeature(sphere.get(), 1);
    const double fovy = 2.0 * std::atan(4.0 / (0.6 * distance)) * 180.0 / 3.14159265358979;
    const Viewport vp{0, 0, w, h};
    osg::ref_ptr<osg::Image> img = loatest::throughLoA(
        scene.get(), ScenarioLibrary::createHomogeneous("trees").get(), w, h, vp,
        [&](OffscreenRenderer& r)
        {
            r.setPerspective(fovy);
            r.setViewMatrixAsLookAt(osg::Vec3d(0, -distance, 10), osg::Vec3d(0, 0, 10), osg::Vec3d(0, 0, 1));
        });
    keep(*img, "trees-crown-" + std::to_string(int(distance)) + "m");
    auto crown = [&](int x, int y)
    {
        const unsigned char* p = img->data(x, y);
        return std::abs(p[0] - 51) + std::abs(p[1] - 77) + std::abs(p[2] - 102) >= 12;
    };
    CrownOutlines o;
    for (int y = 4; y < h - 4; ++y)
        for (int x = 4; x < w - 4; ++x)
        {
            if (!crown(x, y)) continue;
            bool inside = true, border = false;
            for (int j = -3; j <= 3; ++j)
                for (int i = -3; i <= 3; ++i)
                {
                    const bool c = crown(x + i, y + j);
                    inside = inside && c;
                    if (std::abs(i) <= 1 && std::abs(j) <= 1 && !c) border = true;
                }
            const unsigned char* p = img->data(x, y);
            const bool dark = p[0] + p[1] + p[2] < 3 * 60;
            if (inside)
            {
                ++o.interior;
                o.interiorDark += dark;
            }
            if (border)
            {
                ++o.outline;
                o.outlineDark += dark;
            }
        }
    return o;
}
} // namespace

TEST(TreeSilhouettesGLTest, LeavesWhereTheTwinPutsThemAt1920x1080AnOddSizeAndAnOffsetViewport)
{
    expectLeavesOfTheTwin(1920, 1080, Viewport{0, 0, 1920, 1080});
    expectLeavesOfTheTwin(641, 359, Viewport{0, 0, 641, 359});
    expectLeavesOfTheTwin(577, 343, Viewport{37, 21, 500, 300});
}

TEST(TreeSilhouettesGLTest, InnerOutlinesFadeWithDistanceTheSilhouetteStays)
{
    // Deussen & Strothotte's view-dependent abstraction: the same crown at the same size on screen,
    // 12 m and 400 m away. Near, leaves in front of others by a few percent of the distance are
    // outlined inside the crown; far, the relative depth steps are 33 times smaller and only the
    // silhouette is drawn.
    const CrownOutlines near = crownOutlines(12.0, 641, 359), far = crownOutlines(400.0, 641, 359);
    std::cout << "trees crown: near " << near.interiorDark << " of " << near.interior
              << " interior pixels dark, " << near.outlineDark << " of " << near.outline << " outline; far "
              << far.interiorDark << " of " << far.interior << ", " << far.outlineDark << " of "
              << far.outline << "\n";
    ASSERT_GT(near.interior, 10000);
    ASSERT_GT(far.interior, 10000);
    EXPECT_GT(near.interiorDark, 5 * far.interiorDark + 100);
    EXPECT_LT(double(far.interiorDark), 0.01 * double(far.interior));
    EXPECT_GT(double(near.outlineDark), 0.5 * double(near.outline));
    EXPECT_GT(double(far.outlineDark), 0.5 * double(far.outline));
}

TEST(TreeSilhouettesGLTest, TreeCardsOfARealBlockBecomeLeavesWhereTheyShowFoliage)
{
    const std::string file = std::string(LOA_SOURCE_DIR) + "/data/test-scenes/opencity-block.osgt";
    if (!osgDB::fileExists(std::string(LOA_SOURCE_DIR) + "/data/cache/opencity-data/pine2/pine2.ac"))
        GTEST_SKIP() << "the OpenCity models are absent: run scripts/fetch-test-data";
    osg::ref_ptr<osg::Node> block = osgDB::readRefNodeFile(file);
    ASSERT_TRUE(block.valid());
    FeatureClassifier().classify(*block); // as loa-render and the loa plugin do
    const int w = 1920, h = 1080;
    auto render = [&](const std::string& style)
    {
        osg::ref_ptr<LoANode> loa = new LoANode;
        loa->setScenario(ScenarioLibrary::createHomogeneous(style).get());
        loa->addChild(block.get());
        OffscreenRenderer::Settings st;
        st.width = w;
        st.height = h;
        osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(st);
        r->setSceneData(loa.get());
        const CameraPose pose = CityCameras::compute("oblique", *block, double(w) / h);
        r->setPerspective(pose.fovy);
        r->setViewMatrixAsLookAt(pose.eye, pose.center, pose.up);
        osg::ref_ptr<osg::Image> img = r->renderImage();
        EXPECT_EQ(loa->getBindError(), "");
        return img;
    };
    osg::ref_ptr<osg::Image> trees = render("trees"), flat = render("cartographic"),
                             mask = render(loatest::typeMaskStyle(FeatureType::Green));
    keep(*trees, "trees-opencity-block-1920x1080");
    // Pixels that change lie on or near green features (leaves reach a little beyond the cards'
    // foliage), and the leaves cover a part of every tree.
    long changed = 0, nearGreen = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const unsigned char *p = trees->data(x, y), *q = flat->data(x, y);
            if (std::max({std::abs(p[0] - q[0]), std::abs(p[1] - q[1]), std::abs(p[2] - q[2])}) <= 8)
                continue;
            ++changed;
            bool green = false;
            for (int j = std::max(0, y - 12); j <= std::min(h - 1, y + 12) && !green; ++j)
                for (int i = std::max(0, x - 12); i <= std::min(w - 1, x + 12) && !green; ++i)
                {
                    const unsigned char* m = mask->data(i, j);
                    green = m[0] > m[1] + 30 && m[2] > m[1] + 30;
                }
            nearGreen += green;
        }
    std::cout << "trees on the OpenCity block: " << changed << " pixels changed, " << nearGreen
              << " of them within 12 px of green features\n";
    EXPECT_GT(changed, 2000);
    EXPECT_GT(double(nearGreen), 0.98 * double(changed));
}

TEST(TreeSilhouettesGLTest, AScenarioFileNamesTheNewStyles)
{
    // A scenario file whose configurations name trees, object-edges and streets (labels): written,
    // read back and bound to the demo city without a bind error, each style drawing.
    // The homogeneous scenario's configuration (a metric, full weight), once per type and style.
    osg::ref_ptr<UsageScenario> base = ScenarioLibrary::createHomogeneous("cartographic");
    ASSERT_FALSE(base->getConfigurations().empty());
    osg::ref_ptr<UsageScenario> s = new UsageScenario;
    s->setName("new-styles");
    const std::pair<const char*, FeatureType> parts[] = {
        {"trees", FeatureType::Green},        {"object-edges", FeatureType::Generic},
        {"streets", FeatureType::Street},     {"cartographic", FeatureType::Building},
        {"cartographic", FeatureType::Water}, {"cartographic", FeatureType::Terrain}};
    for (const auto& p : parts)
    {
        osg::ref_ptr<TransitionConfiguration> c =
            osg::clone(base->getConfigurations().front().get(), osg::CopyOp::DEEP_COPY_ALL);
        c->setName(std::string(p.first) + "-" + toString(p.second));
        c->setStyle(p.first);
        c->setFeatureTypes({p.second});
        s->addConfiguration(c.get());
    }
    const std::string path = loatest::freshDirectory("TreeSilhouettesScenario") + "/new-styles.osgt";
    ASSERT_TRUE(osgDB::writeObjectFile(*s, path));
    osg::ref_ptr<UsageScenario> back = dynamic_cast<UsageScenario*>(osgDB::readRefObjectFile(path).get());
    ASSERT_TRUE(back.valid());
    ASSERT_EQ(back->getConfigurations().size(), 6u);
    EXPECT_EQ(back->getConfigurations()[0]->getStyle(), "trees");
    EXPECT_EQ(back->getConfigurations()[1]->getStyle(), "object-edges");
    osg::ref_ptr<osg::Node> city = CityGenerator(CityParameters::small()).generate();
    const osg::BoundingBoxd view = loatest::framedView(city.get(), 640, 360);
    osg::ref_ptr<osg::Image> img =
        loatest::topDown(city.get(), back.get(), 640, 360, Viewport{0, 0, 640, 360}, view);
    osg::ref_ptr<osg::Image> flat =
        loatest::topDown(city.get(), "cartographic", 640, 360, Viewport{0, 0, 640, 360}, view);
    long differing = 0;
    for (int y = 0; y < 360; ++y)
        for (int x = 0; x < 640; ++x)
            differing += std::memcmp(img->data(x, y), flat->data(x, y), 3) != 0;
    EXPECT_GT(differing, 1000); // labels, leaves and casings
}
