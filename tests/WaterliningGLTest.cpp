// Waterlining drawn through the LoA pipeline (paper 004 Figure 8A; osgLoA::Waterlining): the lines
// a frame shows lie where the CPU twin puts them, at 1920x1080, an odd size and in an offset
// viewport, and the style differs from flat cartographic on water and nowhere else, on a made-up
// pond, the demo city and the real OpenCity block.
#include "support/TestSupport.h"
#include "support/TopDownView.h"

#include <osgLoA/city/CityCameras>
#include <osgLoA/city/CityGenerator>
#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/semantics/Feature>
#include <osgLoA/semantics/FeatureClassifier>
#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/styles/Waterlining>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/ScenarioLibrary>
#include <osgLoA/transitions/TransitionRenderer>
#include <osgLoA/transitions/UsageScenario>
#include <osgLoA/util/ImageFile>

#include <osg/Geometry>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace osgLoA;

namespace
{
using loatest::Viewport;

osg::ref_ptr<osg::Node> quadFeature(double x0, double y0, double x1, double y1, double z, unsigned id,
                                    FeatureType type)
{
    return loatest::asFeature(loatest::planeQuad(x0, y0, x1, y1, 0.0, 0.0, z).get(), id, type);
}

/** A 40 x 20 m pond (100..140, 50..70) on a 60 x 40 m terrain. */
osg::ref_ptr<osg::Group> pondScene()
{
    osg::ref_ptr<osg::Group> model = new osg::Group;
    model->addChild(quadFeature(100, 50, 140, 70, 0.0, 1, FeatureType::Water));
    model->addChild(quadFeature(90, 40, 150, 80, -0.05, 2, FeatureType::Terrain));
    return model;
}

void keep(const osg::Image& image, const std::string& name)
{
    loatest::keepFrame("waterlining", image, name);
}

int channelDifference(const osg::Image& a, const osg::Image& b, int x, int y)
{
    const unsigned char *p = a.data(x, y), *q = b.data(x, y);
    return std::max(
        {std::abs(int(p[0]) - int(q[0])), std::abs(int(p[1]) - int(q[1])), std::abs(int(p[2]) - int(q[2]))});
}

/** The pond drawn with waterlines against the CPU twin: every pixel's line coverage, measured as
 *  the fraction of the way from the cartographic frame's water colour to the line colour, is
 *  Waterlining::lineCoverage of the CPU shoreline map at the pixel centre; outside the pond the
 *  two frames are the same. */
void expectLinesWhereTheTwinPutsThem(int width, int height, const Viewport& vp)
{
    const std::string label =
        std::to_string(width) + "x" + std::to_string(height) + (vp.x || vp.y ? " (viewport offset)" : "");
    osg::ref_ptr<osg::Group> model = pondScene();
    // The view: the terrain's extent at the viewport's aspect, centred on the pond.
    const double aspect = double(vp.w) / vp.h;
    const double halfH = 25.0, halfW = std::max(35.0, halfH * aspect);
    const double hH = halfW / aspect;
    const osg::BoundingBoxd view(120 - halfW, 60 - hH, 0, 120 + halfW, 60 + hH, 0);
    osg::ref_ptr<osg::Image> lines = loatest::topDown(model.get(), "waterlining", width, height, vp, view);
    osg::ref_ptr<osg::Image> flat =
        loatest::topDown(pondScene().get(), "cartographic", width, height, vp, view);
    ASSERT_TRUE(lines.valid() && flat.valid()) << label;
    const Waterlining::ShoreMap map = Waterlining::computeShoreMap(*model);
    ASSERT_TRUE(map.valid());
    const Waterlining::Lines twin;
    const double px = (view.xMax() - view.xMin()) / vp.w; // world units per pixel (square pixels)
    const osg::Vec3f lineColor = osg::Vec3f(31, 120, 180) / 255.0f;
    long water = 0, compared = 0, off = 0, linePixels = 0, twinLinePixels = 0, outsideDiffering = 0;
    double sumError = 0.0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
        {
            const double wx = view.xMin() + (x - vp.x + 0.5) * px, wy = view.yMin() + (y - vp.y + 0.5) * px;
            const bool inViewport = x >= vp.x && x < vp.x + vp.w && y >= vp.y && y < vp.y + vp.h;
            const bool inPond = inViewport && wx > 100 && wx < 140 && wy > 50 && wy < 70;
            if (!inPond)
            {
                // Outside the pond (one pixel of margin: its silhouette) the styles agree.
                const bool nearPond = inViewport && wx > 100 - 1.5 * px && wx < 140 + 1.5 * px &&
                                      wy > 50 - 1.5 * px && wy < 70 + 1.5 * px;
                if (!nearPond && channelDifference(*lines, *flat, x, y) > 2) ++outsideDiffering;
                continue;
            }
            ++water;
            // Three pixels from the shore the compositor's edges and depth unsharp masking (the
            // same in both styles) darken the water colour: the measure needs the plain colour.
            const double shore = std::min({wx - 100, 140 - wx, wy - 50, 70 - wy});
            if (shore < 3.5 * px) continue;
            const unsigned char *p = lines->data(x, y), *b = flat->data(x, y);
            const osg::Vec3f base(b[0] / 255.0f, b[1] / 255.0f, b[2] / 255.0f);
            const osg::Vec3f got(p[0] / 255.0f, p[1] / 255.0f, p[2] / 255.0f);
            const osg::Vec3f towards = lineColor - base;
            const double measured = ((got - base) * towards) / (towards * towards);
            const double expected = Waterlining::lineCoverage(map.sample(wx, wy), px, twin);
            const double e = std::fabs(measured - expected);
            sumError += e;
            ++compared;
            if (e > 0.25) ++off;
            if (measured > 0.5) ++linePixels;
            if (expected > 0.5) ++twinLinePixels;
        }
    std::cout << "waterlining " << label << ": " << water << " water pixels, " << compared << " compared, "
              << off << " off the twin by more than 0.25, mean error " << (compared ? sumError / compared : 0)
              << ", " << linePixels << " on lines (the twin: " << twinLinePixels << "); " << outsideDiffering
              << " differing outside the pond\n";
    if (width == 1920) keep(*lines, "pond-1920x1080");
    EXPECT_EQ(outsideDiffering, 0) << label;
    ASSERT_GT(compared, 0) << label;
    // Lines are drawn, as many line pixels as the twin puts there (within 2 %).
    EXPECT_GT(twinLinePixels, compared / 100) << label;
    EXPECT_NEAR(double(linePixels), double(twinLinePixels), 0.02 * twinLinePixels) << label;
    EXPECT_LE(double(off), 0.01 * compared) << label;
    EXPECT_LE(sumError / compared, 0.03) << label;
}

/** A real or generated scene top-down: waterlining differs from cartographic in its water
 *  features' pixels (more than minShare of them: a floor that says lines are drawn; where they lie
 *  is the pond test's business) and nowhere else. */
void expectDifferenceOnWaterOnly(const std::string& name, osg::Node* model, int width, int height,
                                 double half, double minShare)
{
    // The water features' footprint, from the feature index (the model's coordinates).
    FeatureIndex index(*model);
    index.updateBounds();
    osg::BoundingBoxd waterBox;
    for (const FeatureIndex::Entry& e : index.entries())
        if (e.feature->getType() == FeatureType::Water)
        {
            const osg::BoundingBoxf& b = e.feature->getBound();
            waterBox.expandBy(osg::Vec3d(b._min));
            waterBox.expandBy(osg::Vec3d(b._max));
        }
    ASSERT_TRUE(waterBox.valid()) << name << ": no water feature";
    // The view: 2 half x 2 half aspect units around the water's centre.
    const double aspect = double(width) / height;
    const osg::Vec3d c = waterBox.center();
    const osg::BoundingBoxd view(c.x() - half * aspect, c.y() - half, 0, c.x() + half * aspect, c.y() + half,
                                 0);
    const Viewport vp{0, 0, width, height};
    osg::ref_ptr<osg::Image> lines = loatest::topDown(model, "waterlining", width, height, vp, view);
    osg::ref_ptr<osg::Image> flat = loatest::topDown(model, "cartographic", width, height, vp, view);
    ASSERT_TRUE(lines.valid() && flat.valid());
    const double px = 2.0 * half / height;
    long inBox = 0, differingIn = 0, differingOut = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
        {
            const double wx = view.xMin() + (x + 0.5) * px, wy = view.yMin() + (y + 0.5) * px;
            const bool in = wx >= waterBox.xMin() - 2 * px && wx <= waterBox.xMax() + 2 * px &&
                            wy >= waterBox.yMin() - 2 * px && wy <= waterBox.yMax() + 2 * px;
            const bool differs = channelDifference(*lines, *flat, x, y) > 2;
            if (in)
            {
                // Water in the flat frame: the cartographic blue (128, 177, 211), shaded.
                const unsigned char* f = flat->data(x, y);
                if (f[2] > f[0] + 40 && f[2] > f[1])
                {
                    ++inBox;
                    differingIn += differs;
                }
            }
            else
                differingOut += differs;
        }
    std::cout << "waterlining " << name << " " << width << "x" << height << ": " << differingIn << " of "
              << inBox << " water pixels differ from cartographic, " << differingOut
              << " outside the water's box\n";
    keep(*lines, name + "-" + std::to_string(width) + "x" + std::to_string(height));
    keep(*flat, name + "-" + std::to_string(width) + "x" + std::to_string(height) + "-cartographic");
    EXPECT_EQ(differingOut, 0) << name;
    EXPECT_GT(double(differingIn), minShare * inBox) << name;
}
} // namespace

TEST(WaterliningGLTest, LinesLieWhereTheTwinPutsThemAt1920x1080)
{
    expectLinesWhereTheTwinPutsThem(1920, 1080, Viewport{0, 0, 1920, 1080});
}

TEST(WaterliningGLTest, LinesLieWhereTheTwinPutsThemAtAnOddSizeAndInAnOffsetViewport)
{
    expectLinesWhereTheTwinPutsThem(641, 359, Viewport{0, 0, 641, 359});
    expectLinesWhereTheTwinPutsThem(577, 343, Viewport{37, 21, 500, 300});
}

TEST(WaterliningGLTest, DiffersFromCartographicOnWaterOnlyInTheDemoCity)
{
    osg::ref_ptr<osg::Node> city = CityGenerator(CityParameters()).generate();
    // The river through the city: 120 m of it.
    expectDifferenceOnWaterOnly("demo-city", city.get(), 960, 540, 60.0, 0.02);
}

TEST(WaterliningGLTest, DiffersFromCartographicOnWaterOnlyInARealScene)
{
    const std::string path = std::string(LOA_SOURCE_DIR) + "/data/test-scenes/opencity-block.osgt";
    if (!osgDB::fileExists(path))
        GTEST_SKIP() << "opencity-block is not extracted: run scripts/fetch-test-data";
    osg::ref_ptr<osg::Node> model = osgDB::readRefNodeFile(path);
    ASSERT_TRUE(model.valid());
    osg::ref_ptr<osg::Group> group = new osg::Group;
    group->addChild(model.get());
    FeatureClassifier().classify(*group);
    // The 10 m pond and its neighbours.
    expectDifferenceOnWaterOnly("opencity-block", group.get(), 1920, 1080, 15.0, 0.02);
}

// The map styles blend with each other and with the cartographic style they build on: the distance
// scenario with its three levels drawn as waterlining, relief and cartographic fuses their shaders
// into one program per combination (each style's copy of loa_cartographic.glsl renamed), on the
// demo city's oblique view.
TEST(WaterliningGLTest, FusesWithTheOtherCartographicStyles)
{
    osg::ref_ptr<UsageScenario> s = ScenarioLibrary::createBuiltin("distance");
    // Its levels (for area and object features): photorealistic, abstract, cartographic.
    for (auto& c : s->getConfigurations())
    {
        if (c->getStyle() == "photorealistic") c->setStyle("waterlining");
        if (c->getStyle() == "abstract") c->setStyle("relief");
    }
    osg::ref_ptr<LoANode> loa = new LoANode;
    loa->setScenario(s.get());
    loa->addChild(CityGenerator(CityParameters()).generate());
    OffscreenRenderer::Settings rs;
    rs.width = 641;
    rs.height = 359;
    osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(rs);
    r->setSceneData(loa.get());
    const CameraPose pose = CityCameras::compute("oblique", *loa->getChild(0), 641.0 / 359.0);
    r->setPerspective(pose.fovy);
    r->setViewMatrixAsLookAt(pose.eye, pose.center, pose.up);
    osg::ref_ptr<osg::Image> image = r->renderImage();
    ASSERT_TRUE(image.valid());
    EXPECT_EQ(loa->getBindError(), "");
    const TransitionRenderer::Statistics st = loa->getRenderer()->getStatistics();
    std::cout << "waterlining, relief and cartographic fused: " << st.fusedDraws << " draws, "
              << st.fusedPrograms << " programs\n";
    EXPECT_GT(st.fusedDraws, 10u);
    EXPECT_GE(st.fusedPrograms, 2u);
}
