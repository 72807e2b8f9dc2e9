// Streets as on a map (paper 004 §3.2.3; osgLoA::StreetPresentation): road classes from sub-types
// and widths, the casing coverage, and the street map (edge distances, texel counts, widths)
// against values computed by hand for quads of known size.
#include "support/TopDownView.h"

#include <osgLoA/semantics/FeatureSubType>
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/styles/StreetPresentation>

#include <osg/Group>

#include <gtest/gtest.h>

#include <cmath>

using namespace osgLoA;
using SP = StreetPresentation;

namespace
{
osg::ref_ptr<osg::Node> road(unsigned id, const std::string& subType, double x0, double y0, double x1,
                             double y1)
{
    return loatest::featureQuad(id, FeatureType::Street, subType, x0, y0, x1, y1);
}
} // namespace

TEST(StreetPresentationTest, RoadClasses)
{
    EXPECT_EQ(SP::classOf("major", 0.0), SP::MAJOR);
    EXPECT_EQ(SP::classOf("Primary", 0.0), SP::MAJOR);
    EXPECT_EQ(SP::classOf("residential", 20.0), SP::MINOR); // the model's word wins over the width
    EXPECT_EQ(SP::classOf("footway", 0.0), SP::PATH);
    EXPECT_EQ(SP::classOf("railway", 0.0), SP::RAIL);
    // CityGML/CityJSON "road" and unnamed streets: by width (7.5 and 3.5 m).
    EXPECT_EQ(SP::classOf("road", 12.0), SP::MAJOR);
    EXPECT_EQ(SP::classOf("road", 7.5), SP::MAJOR);
    EXPECT_EQ(SP::classOf("road", 7.0), SP::MINOR);
    EXPECT_EQ(SP::classOf("", 6.0), SP::MINOR);
    EXPECT_EQ(SP::classOf("", 3.0), SP::PATH);
    EXPECT_EQ(SP::classOf("road", 0.0), SP::UNKNOWN);
    // The shader's class codes are FeatureSubType's.
    EXPECT_EQ(FeatureSubType::code("major"), 32);
    EXPECT_EQ(FeatureSubType::code("minor"), 33);
    EXPECT_EQ(FeatureSubType::code("path"), 34);
    EXPECT_EQ(FeatureSubType::code("rail"), 35);
    EXPECT_EQ(FeatureSubType::code("railway"), 36);
    EXPECT_EQ(FeatureSubType::code("track"), 37);
    // Casing: 1 px on pixels of 0.1 m: full at the edge, half at 0.15 m... (1 + 1/2 - d / 0.1).
    EXPECT_DOUBLE_EQ(SP::casingCoverage(0.0, 0.1, 1.0), 1.0);
    EXPECT_NEAR(SP::casingCoverage(0.1, 0.1, 1.0), 0.5, 1e-12);
    EXPECT_DOUBLE_EQ(SP::casingCoverage(0.2, 0.1, 1.0), 0.0);
    EXPECT_NEAR(SP::casingCoverage(0.2, 0.1, 2.0), 0.5, 1e-12);
    EXPECT_DOUBLE_EQ(SP::casingCoverage(0.0, 0.1, 0.0), 0.0);   // paths: no casing
    EXPECT_DOUBLE_EQ(SP::casingCoverage(-0.05, 0.1, 1.0), 1.0); // on the edge, within interpolation
    // The style maps sub-type codes to classes as classOf does (the shader's only source).
    osg::ref_ptr<GraphicStyle> style = GraphicStyleCatalog::instance().create("streets");
    const osg::Uniform* classes = style->getParameter("loa_streets_classOf");
    ASSERT_NE(classes, nullptr);
    int k = 0;
    for (const char* word :
         {"major", "minor", "path", "rail", "railway", "track", "residential", "river", ""})
    {
        classes->getElement(unsigned(FeatureSubType::code(word)), k);
        EXPECT_EQ(k, int(SP::classOf(word, 0.0))) << word;
    }
    EXPECT_NE(GraphicStyleCatalog::instance().create("streets"), nullptr);
}

TEST(StreetPresentationTest, StreetMapDistancesAndWidths)
{
    // A 100 x 10 m street, a 60 x 4 m one beside it, and an L of two 6 m streets meeting.
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(road(1, "road", 0, 0, 100, 10).get());
    root->addChild(road(2, "", 0, 20, 60, 24).get());
    root->addChild(road(3, "", 0, 40, 50, 46).get());
    root->addChild(road(4, "", 44, 46, 50, 90).get());
    const SP::StreetMap map = SP::computeStreetMap(*root);
    ASSERT_TRUE(map.valid());
    EXPECT_EQ(map.streetFeatures, 4u);
    EXPECT_EQ(map.triangles, 8u);
    // Texels of 0.1 m (100 / 2046 is finer than the minimum); texel centres inside the streets
    // (closed): 1000 x 100 + 600 x 40 + 500 x 60 + 60 x 440 (the L's two arms; they meet at
    // y = 46, shared by neither's centres).
    EXPECT_DOUBLE_EQ(map.grid.texelSize, 0.1);
    EXPECT_EQ(map.streetTexels, std::size_t(100000 + 24000 + 30000 + 26400));
    // The signed distance to the nearest edge: 5 m on the wide street's centre line, 2 m on the
    // narrow one's, -5 m half-way between them, 0 on an edge (within a texel).
    EXPECT_NEAR(map.sample(50.0, 5.0), 5.0, 0.1);
    EXPECT_NEAR(map.sample(30.0, 22.0), 2.0, 0.1);
    EXPECT_NEAR(map.sample(50.0, 15.0), -5.0, 0.1);
    EXPECT_NEAR(map.sample(50.0, 10.0), 0.0, 0.02);
    EXPECT_NEAR(map.sample(0.0, 5.0), 0.0, 0.02);
    // The L's joint is one surface: at the seam (47, 46) the nearest edge is 3 m away, not 0.
    EXPECT_NEAR(map.sample(47.0, 46.0), 3.0, 0.15);
    // Widths: 2 p90 / 0.9 of each street's distances.
    ASSERT_EQ(map.widths.size(), 4u);
    EXPECT_NEAR(map.widths[0].second, 10.0, 0.3);
    EXPECT_NEAR(map.widths[1].second, 4.0, 0.3);
    EXPECT_NEAR(map.widths[3].second, 6.0, 0.4);
    EXPECT_EQ(SP::classOf("road", map.widths[0].second), SP::MAJOR);
    EXPECT_EQ(SP::classOf("", map.widths[1].second), SP::MINOR);
    // No street: no map; impossible parameters: an error naming them.
    osg::ref_ptr<osg::Group> bare = new osg::Group;
    bare->addChild(loatest::asFeature(loatest::planeQuad(0, 0, 1, 1).get(), 9, FeatureType::Terrain).get());
    EXPECT_FALSE(SP::computeStreetMap(*bare).valid());
    EXPECT_THROW(SP::computeStreetMap(*root, 2), std::invalid_argument);
    EXPECT_THROW(SP::computeStreetMap(*root, 64, std::nan("")), std::invalid_argument);
}
