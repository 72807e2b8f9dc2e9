// Waterlining (paper 004 §3.2.3, Figure 8A; osgLoA::Waterlining): the line intervals and their
// coverage against hand-computed values, and the shoreline map of water features against the
// analytic distance to a rectangle's edges.
#include "support/TestSupport.h"
#include "support/TopDownView.h"

#include <osgLoA/semantics/Feature>
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/styles/StylePreparation>
#include <osgLoA/styles/Waterlining>
#include <osgLoA/transitions/ScenarioLibrary>
#include <osgLoA/transitions/UsageScenario>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/MatrixTransform>
#include <osg/ValueObject>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace osgLoA;

namespace
{
/** A horizontal quad x0..x1 by y0..y1 at height z. */
osg::ref_ptr<osg::Geometry> quad(double x0, double y0, double x1, double y1, double z = 0.0)
{
    return loatest::planeQuad(x0, y0, x1, y1, 0.0, 0.0, z);
}

osg::ref_ptr<osg::Node> feature(osg::Node* child, unsigned id, FeatureType type)
{
    return loatest::asFeature(child, id, type);
}

/** Distance from (x, y) inside the rectangle to its nearest edge. */
double insideDistance(double x, double y, double x0, double y0, double x1, double y1)
{
    return std::min({x - x0, x1 - x, y - y0, y1 - y});
}
} // namespace

TEST(WaterliningTest, LinesLieAtWideningIntervals)
{
    Waterlining::Lines l;
    l.spacing = 2.0f; // exponent 1.5 (the default)
    EXPECT_DOUBLE_EQ(Waterlining::lineDistance(0, l), 0.0);
    EXPECT_DOUBLE_EQ(Waterlining::lineDistance(1, l), 2.0);
    EXPECT_NEAR(Waterlining::lineDistance(2, l), 2.0 * 2.8284271247, 1e-9); // 2 * 2^1.5
    EXPECT_NEAR(Waterlining::lineDistance(4, l), 16.0, 1e-9);               // 2 * 4^1.5
    // The intervals widen: d2 - d1 = 3.657 < d3 - d2 = 4.735 < d4 - d3 = 5.608.
    double previous = 0.0;
    for (int k = 1; k < 5; ++k)
    {
        const double gap = Waterlining::lineDistance(k + 1, l) - Waterlining::lineDistance(k, l);
        EXPECT_GT(gap, previous) << k;
        previous = gap;
    }
}

TEST(WaterliningTest, CoverageIsABoxFilteredLineOfItsWidth)
{
    Waterlining::Lines l; // width 1.5 px, count 5, fade 0.6, shoreline on
    l.spacing = 2.0f;
    const double px = 0.25; // world units per pixel
    // (The parameters are floats: fade 0.6f is 0.6 to 1e-8.)
    // On line 2 (d = 5.657): full coverage times its strength 1 - 0.6 * 1/4 = 0.85.
    const double d2 = Waterlining::lineDistance(2, l);
    EXPECT_NEAR(Waterlining::lineCoverage(d2, px, l), 0.85, 1e-7);
    // Half a pixel off the centre: 0.75 + 0.5 - 0.5 = 0.75 of the pixel, times 0.85.
    EXPECT_NEAR(Waterlining::lineCoverage(d2 + 0.5 * px, px, l), 0.75 * 0.85, 1e-7);
    // 1.25 pixels off: nothing (the line's edge is 0.75 px from its centre, plus the pixel's half).
    EXPECT_NEAR(Waterlining::lineCoverage(d2 + 1.25 * px, px, l), 0.0, 1e-12);
    // Line 1 at full strength, line 5 at 1 - 0.6 = 0.4, beyond the last line nothing.
    EXPECT_NEAR(Waterlining::lineCoverage(2.0, px, l), 1.0, 1e-9);
    EXPECT_NEAR(Waterlining::lineCoverage(Waterlining::lineDistance(5, l), px, l), 0.4, 1e-7);
    EXPECT_EQ(Waterlining::lineCoverage(Waterlining::lineDistance(6, l), px, l), 0.0);
    // The shoreline at d = 0, unless switched off.
    EXPECT_NEAR(Waterlining::lineCoverage(0.0, px, l), 1.0, 1e-9);
    l.shoreline = false;
    EXPECT_EQ(Waterlining::lineCoverage(0.0, px, l), 0.0);
    // A pixel of 2 units centred 1 unit from line 1 (d = 2): the line spans 0.5 .. 3.5, the pixel
    // 2 .. 4, so 1.5 of its 2 units are covered.
    EXPECT_NEAR(Waterlining::lineCoverage(3.0, 2.0, l), 0.75, 1e-12);
    // Impossible input: nothing.
    EXPECT_EQ(Waterlining::lineCoverage(-1.0, px, l), 0.0);
    EXPECT_EQ(Waterlining::lineCoverage(2.0, 0.0, l), 0.0);
    EXPECT_EQ(Waterlining::lineCoverage(std::nan(""), px, l), 0.0);
    l.spacing = 0.0f;
    EXPECT_EQ(Waterlining::lineCoverage(2.0, px, l), 0.0);
}

// A 40 x 20 m pond at (100..140, 50..70) under a transform that moves it by (+10, -5), beside a
// building that must not count: the map's distances are the distances to the pond's edges.
TEST(WaterliningTest, ShoreMapOfARectangularPondIsItsDistanceToTheEdges)
{
    osg::ref_ptr<osg::Group> model = new osg::Group;
    osg::ref_ptr<osg::MatrixTransform> moved = new osg::MatrixTransform(osg::Matrix::translate(10, -5, 0));
    moved->addChild(feature(quad(90, 55, 130, 75).get(), 1, FeatureType::Water));
    model->addChild(moved.get());
    model->addChild(feature(quad(0, 0, 30, 30, 10).get(), 2, FeatureType::Building));

    const int resolution = 402; // 400 texels across the 40 m side: 0.1 m
    const Waterlining::ShoreMap map = Waterlining::computeShoreMap(*model, resolution);
    ASSERT_TRUE(map.valid());
    EXPECT_EQ(map.waterFeatures, 1u);
    EXPECT_EQ(map.triangles, 2u);
    EXPECT_NEAR(map.grid.texelSize, 0.1, 1e-9);
    // 400 x 200 water texels, and one land texel of margin around them.
    EXPECT_EQ(map.waterTexels, std::size_t(400 * 200));
    EXPECT_EQ(map.grid.width, 402);
    EXPECT_EQ(map.grid.height, 202);
    const double x0 = 100, y0 = 50, x1 = 140, y1 = 70;
    // The exact transform measures to the nearest land texel centre: half a texel beyond the
    // edge, so the map reads the edge distance + 0.05 m (+- rounding of the bilinear fetch).
    for (const osg::Vec2d p : {osg::Vec2d(120, 60), osg::Vec2d(103, 60), osg::Vec2d(120, 52.5),
                               osg::Vec2d(138.25, 69.1), osg::Vec2d(111.11, 63.37)})
    {
        const double expected = insideDistance(p.x(), p.y(), x0, y0, x1, y1) + 0.05;
        EXPECT_NEAR(map.sample(p.x(), p.y()), expected, 0.06) << p.x() << ", " << p.y();
    }
    // Centre: 10 m from the long edges.
    EXPECT_NEAR(map.sample(120, 60), 10.05, 0.06);
    // Outside the pond: land, distance 0.
    EXPECT_EQ(map.sample(99.9, 49.9), 0.0f);
    EXPECT_EQ(map.sample(0, 0), 0.0f);
}

// A river whose polygon reaches under its banks: the terrain above the water surface hides it, and
// the shore is where the water emerges. Water at z = 0 over 0..40 x 0..20; terrain banks at z = 1
// over x < 5 and x > 35, and terrain at z = -1 (under the water) between them.
TEST(WaterliningTest, TheShoreIsWhereTheWaterEmergesFromTheTerrain)
{
    osg::ref_ptr<osg::Group> model = new osg::Group;
    model->addChild(feature(quad(0, 0, 40, 20).get(), 1, FeatureType::Water));
    model->addChild(feature(quad(-10, -5, 5, 25, 1.0).get(), 2, FeatureType::Terrain));
    model->addChild(feature(quad(35, -5, 50, 25, 1.0).get(), 3, FeatureType::Terrain));
    model->addChild(feature(quad(5, -5, 35, 25, -1.0).get(), 4, FeatureType::Terrain));
    const Waterlining::ShoreMap map = Waterlining::computeShoreMap(*model, 402); // 0.1 m texels
    ASSERT_TRUE(map.valid());
    EXPECT_EQ(map.triangles, 2u); // the terrain's triangles are not water
    // 300 x 200 texels emerge (x 5..35).
    EXPECT_EQ(map.waterTexels, std::size_t(300 * 200));
    // 3 m from the west bank's edge at x = 5 (+ half a texel to the land texel's centre), 10 m
    // from the north and south shores in the middle.
    EXPECT_NEAR(map.sample(8, 10), 3.05, 0.06);
    EXPECT_NEAR(map.sample(20, 10), 10.05, 0.06);
    EXPECT_NEAR(map.sample(33, 10), 2.05, 0.06);
    EXPECT_EQ(map.sample(2, 10), 0.0f); // under the bank
}

// A small pond takes the texels its lines need, not the full resolution: a 10 m pond at the
// default 0.1 m minimum is 100 texels across (+ 2 of margin), not 2048.
TEST(WaterliningTest, ASmallPondTakesNoMoreTexelsThanItNeeds)
{
    osg::ref_ptr<osg::Group> model = new osg::Group;
    model->addChild(feature(quad(0, 0, 10, 10).get(), 1, FeatureType::Water));
    const Waterlining::ShoreMap map = Waterlining::computeShoreMap(*model);
    ASSERT_TRUE(map.valid());
    EXPECT_NEAR(map.grid.texelSize, 0.1, 1e-12);
    EXPECT_EQ(map.grid.width, 102);
    EXPECT_EQ(map.grid.height, 102);
    EXPECT_NEAR(map.sample(5, 5), 5.05, 0.06);
    // Without the floor, the full resolution.
    EXPECT_EQ(Waterlining::computeShoreMap(*model, 2048, 0.0).grid.width, 2048);
}

TEST(WaterliningTest, AModelWithoutWaterHasNoMapAndPreparationSaysSo)
{
    osg::ref_ptr<osg::Group> model = new osg::Group;
    model->addChild(feature(quad(0, 0, 30, 30).get(), 2, FeatureType::Green));
    // A water feature seen only edge-on (a vertical quad) has no ground footprint.
    osg::ref_ptr<osg::Geometry> wall = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    v->push_back(osg::Vec3(0, 0, 0));
    v->push_back(osg::Vec3(10, 0, 0));
    v->push_back(osg::Vec3(10, 0, 5));
    wall->setVertexArray(v.get());
    wall->addPrimitiveSet(new osg::DrawArrays(GL_TRIANGLES, 0, 3));
    model->addChild(feature(wall.get(), 3, FeatureType::Water));
    const Waterlining::ShoreMap map = Waterlining::computeShoreMap(*model);
    EXPECT_FALSE(map.valid());
    EXPECT_EQ(map.waterFeatures, 1u);
    EXPECT_EQ(map.triangles, 0u);

    osg::ref_ptr<UsageScenario> scenario = ScenarioLibrary::createHomogeneous("waterlining");
    StylePreparation::Options o;
    o.progress = [](const std::string&) {};
    const StylePreparation::Report r = StylePreparation::prepare(*model, *scenario, o);
    ASSERT_EQ(r.messages.size(), 1u);
    EXPECT_NE(r.messages[0].find("no water surface"), std::string::npos) << r.messages[0];
    EXPECT_FALSE(model->getStateSet() && model->getStateSet()->getUniform("loa_hasWaterDistance"));
    EXPECT_THROW(Waterlining::computeShoreMap(*model, 2), std::invalid_argument);
    EXPECT_THROW(Waterlining::computeShoreMap(*model, 64, -1.0), std::invalid_argument);
    EXPECT_THROW(Waterlining::computeShoreMap(*model, 64, std::nan("")), std::invalid_argument);
}

TEST(WaterliningTest, PreparationBindsTheMapOnceOnTheModel)
{
    osg::ref_ptr<osg::Group> model = new osg::Group;
    model->addChild(feature(quad(0, 0, 50, 20).get(), 1, FeatureType::Water));
    osg::ref_ptr<UsageScenario> scenario = ScenarioLibrary::createHomogeneous("waterlining");
    EXPECT_EQ(StylePreparation::stylesNeeded(*scenario), std::vector<std::string>{"waterlining"});
    std::vector<std::string> lines;
    StylePreparation::Options o;
    o.progress = [&](const std::string& line) { lines.push_back(line); };
    const StylePreparation::Report r = StylePreparation::prepare(*model, *scenario, o);
    EXPECT_EQ(r.waterFeatures, 1u);
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_NE(lines[0].find("shoreline map of 1 water feature(s), 2 triangles"), std::string::npos)
        << lines[0];
    osg::StateSet* ss = model->getStateSet();
    ASSERT_TRUE(ss);
    bool has = false;
    ASSERT_TRUE(ss->getUniform("loa_hasWaterDistance") && ss->getUniform("loa_hasWaterDistance")->get(has));
    EXPECT_TRUE(has);
    EXPECT_TRUE(ss->getTextureAttribute(Waterlining::kUnit, osg::StateAttribute::TEXTURE));
    // A second preparation does nothing.
    lines.clear();
    const StylePreparation::Report again = StylePreparation::prepare(*model, *scenario, o);
    EXPECT_TRUE(again.styles.empty());
    EXPECT_TRUE(lines.empty());
}

TEST(WaterliningTest, TheStyleIsInTheCatalogWithItsParameters)
{
    osg::ref_ptr<GraphicStyle> s = GraphicStyleCatalog::instance().create("waterlining");
    ASSERT_TRUE(s.valid());
    EXPECT_EQ(s->getFragmentShader(), "loa_style_waterlining.frag.glsl");
    float spacing = 0.0f;
    ASSERT_TRUE(s->getParameter("loa_waterlining_spacing") &&
                s->getParameter("loa_waterlining_spacing")->get(spacing));
    EXPECT_FLOAT_EQ(spacing, Waterlining::Lines().spacing);
    // The cartographic base's parameters too.
    EXPECT_TRUE(s->getParameter("loa_cartographic_colors"));
    EXPECT_TRUE(s->getOpaque());
    EXPECT_FALSE(s->getUsesTexture());
}
