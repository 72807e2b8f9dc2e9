// Colour schemes per sub-type drawn (osgLoA::ColorScheme through the transition renderer): flat
// quads of known sub-types, top-down, take exactly the scheme's colour times the flat-shading
// factor computed by hand, under a scenario naming the scheme and in every cartographic style;
// without a scheme they keep their type's colour; on West Oakland (OpenStreetMap) the 5 secondary
// roads, counted by hand, are drawn in the major-road colour and the 18 minor ones in theirs.
#include "support/TestSupport.h"
#include "support/TopDownView.h"

#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/semantics/Feature>
#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/styles/ColorScheme>
#include <osgLoA/styles/GraphicStyle>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/ScenarioLibrary>

#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <map>

using namespace osgLoA;

namespace
{
osg::ref_ptr<osg::Node> quad(unsigned id, FeatureType type, const std::string& subType, double x0, double y0)
{
    return loatest::featureQuad(id, type, subType, x0, y0, x0 + 20, y0 + 20);
}

/** The scene drawn top-down through a scenario that draws everything in `style` under `scheme`
 *  (empty: none). */
osg::ref_ptr<osg::Image> draw(osg::Node* scene, const std::string& style, const std::string& scheme, int w,
                              int h, const loatest::Viewport& vp, const osg::BoundingBoxd& view)
{
    osg::ref_ptr<UsageScenario> s = ScenarioLibrary::createHomogeneous(style);
    s->setColorScheme(scheme);
    return loatest::topDown(scene, s.get(), w, h, vp, view);
}

void expectSchemeColours(int w, int h, const loatest::Viewport& vp)
{
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    scene->addChild(quad(1, FeatureType::Green, "coniferous", 0, 0).get());
    scene->addChild(quad(2, FeatureType::Street, "major", 30, 0).get());
    scene->addChild(quad(3, FeatureType::Building, "landmark", 60, 0).get());
    scene->addChild(quad(4, FeatureType::Green, "tree", 90, 0).get()); // not in the scheme
    // A building word on a street: the scheme colours it for buildings only.
    scene->addChild(quad(5, FeatureType::Street, "residential", 120, 0).get());
    const osg::BoundingBoxd view(-5, -5, 0, 145, 25, 0);
    // Flat shading, top-down: the face normal is the view axis, (0, 0, 1) in view space; the light
    // (0.3, 0.5, 0.8) normalized gives n.l = 0.8 / 0.98995 = 0.80812, factor 0.6 + 0.4 n.l.
    const double light = 0.6 + 0.4 * 0.8 / std::sqrt(0.3 * 0.3 + 0.5 * 0.5 + 0.8 * 0.8);
    const ColorScheme::Scheme& b = *ColorScheme::find("brewer-subtypes");
    struct Probe
    {
        double x;
        FeatureType type;
        std::string subType;
        osg::Vec3f typeColor;
    };
    const Probe probes[] = {
        {10, FeatureType::Green, "coniferous", GraphicStyle::cartographicColor(FeatureType::Green)},
        {40, FeatureType::Street, "major", GraphicStyle::cartographicColor(FeatureType::Street)},
        {70, FeatureType::Building, "landmark", GraphicStyle::cartographicColor(FeatureType::Building)},
        {100, FeatureType::Green, "tree", GraphicStyle::cartographicColor(FeatureType::Green)},
        {130, FeatureType::Street, "residential", GraphicStyle::cartographicColor(FeatureType::Street)}};
    for (const char* style : {"cartographic", "waterlining", "relief"})
        for (const std::string& scheme : {std::string("brewer-subtypes"), std::string()})
        {
            osg::ref_ptr<osg::Image> img = draw(scene.get(), style, scheme, w, h, vp, view);
            const std::string label = std::string(style) + " scheme '" + scheme + "' " + std::to_string(w) +
                                      "x" + std::to_string(h) + " viewport " + std::to_string(vp.x);
            if (w == 1920 && std::string(style) == "cartographic" && !scheme.empty())
                loatest::keepFrame("color-scheme", *img, "quads-1920x1080");
            for (const Probe& p : probes)
            {
                const osg::Vec3f c =
                    scheme.empty() ? p.typeColor : ColorScheme::colorOf(b, p.type, p.subType, p.typeColor);
                // The probe's 8 x 8 m centre (away from the edges the compositor draws).
                long off = 0, n = 0;
                for (double y = 6; y <= 14; y += 0.5)
                    for (double x = p.x - 4; x <= p.x + 4; x += 0.5)
                    {
                        const int px = vp.x + int((x + 5) / 150.0 * vp.w),
                                  py = vp.y + int((y + 5) / 30.0 * vp.h);
                        const unsigned char* q = img->data(px, py);
                        ++n;
                        for (int k = 0; k < 3; ++k)
                            off += std::fabs(q[k] - 255.0 * c[k] * light) > 2.0 ? 1 : 0;
                    }
                EXPECT_EQ(off, 0) << label << " " << p.subType << ": expected " << 255.0 * c[0] * light
                                  << ", " << 255.0 * c[1] * light << ", " << 255.0 * c[2] * light << " (" << n
                                  << " pixels)";
            }
        }
}
} // namespace

TEST(ColorSchemeGLTest, SubTypesTakeTheSchemesColourAt1920x1080)
{
    expectSchemeColours(1920, 1080, loatest::Viewport{0, 0, 1920, 1080});
}

TEST(ColorSchemeGLTest, SubTypesTakeTheSchemesColourAtAnOddSizeAndInAnOffsetViewport)
{
    expectSchemeColours(641, 359, loatest::Viewport{0, 0, 641, 359});
    expectSchemeColours(577, 343, loatest::Viewport{37, 21, 500, 300});
}

TEST(ColorSchemeGLTest, RoadClassesOfARealOsmFile)
{
    const std::string file = std::string(LOA_SOURCE_DIR) + "/data/cache/python-osmnx-doc/West-Oakland.osm";
    if (!osgDB::fileExists(file)) GTEST_SKIP() << file << " is absent: run scripts/fetch-test-data";
    osg::ref_ptr<osg::Node> model = osgDB::readRefNodeFile(file);
    ASSERT_TRUE(model.valid());
    // Counted by hand in the file: 31 highway ways, 5 secondary (major), 9 residential, 3
    // unclassified, 6 service (minor), 7 footway, 1 cycleway (path).
    std::map<std::string, int> classes;
    const FeatureIndex index(*model);
    for (const FeatureIndex::Entry& e : index.entries())
        if (e.feature->getType() == FeatureType::Street) ++classes[e.feature->getSubType()];
    EXPECT_EQ(classes, (std::map<std::string, int>{{"major", 5}, {"minor", 18}, {"path", 8}}));
    osg::ComputeBoundsVisitor cbv;
    model->accept(cbv);
    const osg::BoundingBox bb = cbv.getBoundingBox();
    const int w = 1920, h = 1080;
    const double half =
        0.5 * std::max((bb.xMax() - bb.xMin()) * h / double(w), double(bb.yMax() - bb.yMin()));
    const osg::Vec3d c = bb.center();
    const osg::BoundingBoxd view(c.x() - half * w / h, c.y() - half, 0, c.x() + half * w / h, c.y() + half,
                                 0);
    osg::ref_ptr<osg::Image> img =
        draw(model.get(), "cartographic", "brewer-subtypes", w, h, loatest::Viewport{0, 0, w, h}, view);
    loatest::keepFrame("color-scheme", *img, "west-oakland-1920x1080");
    const ColorScheme::Scheme& b = *ColorScheme::find("brewer-subtypes");
    const osg::Vec3f street = GraphicStyle::cartographicColor(FeatureType::Street);
    const osg::Vec3f majorC = ColorScheme::colorOf(b, FeatureType::Street, "major", street),
                     minorC = ColorScheme::colorOf(b, FeatureType::Street, "minor", street);
    const double light = 0.6 + 0.4 * 0.8 / std::sqrt(0.3 * 0.3 + 0.5 * 0.5 + 0.8 * 0.8);
    long majorPixels = 0, minorPixels = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const unsigned char* q = img->data(x, y);
            auto is = [&](const osg::Vec3f& col)
            {
                for (int k = 0; k < 3; ++k)
                    if (std::fabs(q[k] - 255.0 * col[k] * light) > 3.0) return false;
                return true;
            };
            majorPixels += is(majorC);
            minorPixels += is(minorC);
        }
    std::cout << "West Oakland, brewer-subtypes: " << majorPixels << " pixels of major roads, " << minorPixels
              << " of minor ones\n";
    EXPECT_GT(majorPixels, 2000);
    EXPECT_GT(minorPixels, 2000);
}
