// The relief presentation of terrain (paper 004 Figure 8D; osgLoA::ReliefPresentation): the CPU
// twins of the shader's slope direction, slope, shade, stroke density and cell sizes, against
// values computed by hand for planes of known gradient.
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/styles/ReliefPresentation>

#include <gtest/gtest.h>

#include <cmath>

using namespace osgLoA;

namespace
{
/** The upward unit normal of the plane z = a x + b y: (-a, -b, 1) / sqrt(a^2 + b^2 + 1). */
osg::Vec3d planeNormal(double a, double b)
{
    osg::Vec3d n(-a, -b, 1.0);
    n.normalize();
    return n;
}
} // namespace

TEST(ReliefPresentationTest, SlopeLinesFollowTheAnalyticGradient)
{
    // z = 0.3 x + 0.1 y rises towards (0.3, 0.1): steepest descent is -(0.3, 0.1) / 0.31623.
    const osg::Vec2d d = ReliefPresentation::downhill(planeNormal(0.3, 0.1));
    EXPECT_NEAR(d.x(), -0.9486833, 1e-6);
    EXPECT_NEAR(d.y(), -0.3162278, 1e-6);
    // The normal's sign does not matter (a terrain drawn with its faces the other way).
    const osg::Vec2d flipped = ReliefPresentation::downhill(-planeNormal(0.3, 0.1));
    EXPECT_NEAR(flipped.x(), d.x(), 1e-12);
    EXPECT_NEAR(flipped.y(), d.y(), 1e-12);
    // tan of the slope angle is the gradient's length.
    EXPECT_NEAR(ReliefPresentation::slope(planeNormal(0.3, 0.1)), std::sqrt(0.1), 1e-9);
    EXPECT_NEAR(ReliefPresentation::slope(planeNormal(0.0, -2.0)), 2.0, 1e-9);
    const osg::Vec2d north = ReliefPresentation::downhill(planeNormal(0.0, -2.0)); // falls to +y
    EXPECT_NEAR(north.x(), 0.0, 1e-12);
    EXPECT_NEAR(north.y(), 1.0, 1e-12);
    // Flat ground: no slope, the documented direction; a zero normal counts as flat.
    EXPECT_EQ(ReliefPresentation::slope(osg::Vec3d(0, 0, 1)), 0.0);
    EXPECT_EQ(ReliefPresentation::downhill(osg::Vec3d(0, 0, 1)), osg::Vec2d(0.0, -1.0));
    EXPECT_EQ(ReliefPresentation::slope(osg::Vec3d(0, 0, 0)), 0.0);
}

TEST(ReliefPresentationTest, ShadeComesFromTheNorthWest)
{
    const ReliefPresentation::Parameters p; // light (-0.5, 0.5, 0.7071): north-west, 45 degrees up
    // Flat ground: 1 - 0.7071.
    EXPECT_NEAR(ReliefPresentation::shade(osg::Vec3d(0, 0, 1), p), 1.0 - 0.70710678, 1e-6);
    // A 45-degree slope facing north-west (normal (-0.5, 0.5, 0.7071)) is fully lit; one facing
    // south-east (normal (0.5, -0.5, 0.7071)) gets n.l = -0.25 - 0.25 + 0.5 = 0: full shade.
    EXPECT_NEAR(ReliefPresentation::shade(osg::Vec3d(-0.5, 0.5, 0.70710678), p), 0.0, 1e-6);
    EXPECT_NEAR(ReliefPresentation::shade(osg::Vec3d(0.5, -0.5, 0.70710678), p), 1.0, 1e-6);
}

TEST(ReliefPresentationTest, DensityGrowsWithSlopeAndCellsFollowTheScreen)
{
    const ReliefPresentation::Parameters p; // minSlope 0.05, maxSlope 0.5, cellPixels 14
    EXPECT_EQ(ReliefPresentation::density(0.0, p), 0.0);
    EXPECT_EQ(ReliefPresentation::density(0.05, p), 0.0);
    EXPECT_NEAR(ReliefPresentation::density(0.275, p), 0.5, 1e-6); // the parameters are floats
    EXPECT_EQ(ReliefPresentation::density(0.5, p), 1.0);
    EXPECT_EQ(ReliefPresentation::density(3.0, p), 1.0);
    // 0.1 world units per pixel: the target cell is 1.4 units, between 1 and 2, weight
    // log2(1.4) = 0.48543 on the larger.
    const osg::Vec3d c = ReliefPresentation::cellSizes(0.1, p);
    EXPECT_EQ(c.x(), 1.0);
    EXPECT_EQ(c.y(), 2.0);
    EXPECT_NEAR(c.z(), 0.4854268, 1e-6);
    // Twice as far (0.2 per pixel): the sizes double and the weight stays: the same density on
    // screen.
    const osg::Vec3d far = ReliefPresentation::cellSizes(0.2, p);
    EXPECT_EQ(far.x(), 2.0);
    EXPECT_EQ(far.y(), 4.0);
    EXPECT_NEAR(far.z(), c.z(), 1e-12);
}

TEST(ReliefPresentationTest, TheStyleIsInTheCatalog)
{
    osg::ref_ptr<GraphicStyle> s = GraphicStyleCatalog::instance().create("relief");
    ASSERT_TRUE(s.valid());
    EXPECT_EQ(s->getFragmentShader(), "loa_style_relief.frag.glsl");
    float cell = 0.0f;
    ASSERT_TRUE(s->getParameter("loa_relief_cellPixels") &&
                s->getParameter("loa_relief_cellPixels")->get(cell));
    EXPECT_FLOAT_EQ(cell, ReliefPresentation::Parameters().cellPixels);
    EXPECT_TRUE(s->getParameter("loa_cartographic_colors"));
}
