// shaders/loa_transition.frag.glsl against its CPU twin (TransitionConfiguration::interestAt,
// BlendFunction): the interest debug view of a ground plane and two buildings is rendered
// headless and every pixel compared with the CPU's interest at the point the pixel sees.
#include "support/TestSupport.h"

#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/semantics/Feature>
#include <osgLoA/transitions/InterestDebugView>
#include <osgLoA/transitions/LoANode>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/ShapeDrawable>

#include <gtest/gtest.h>

#include <cmath>

using namespace osgLoA;

namespace
{
osg::ref_ptr<osg::Node> feature(osg::Drawable* d, unsigned id, FeatureType type)
{
    osg::ref_ptr<osg::Geode> g = new osg::Geode;
    g->addDrawable(d);
    Feature::attach(*g, new Feature(id, type));
    return g;
}

// A 400 m x 400 m ground quad at z = 0, split into cells so that llvmpipe's interpolation is
// over small triangles (it is exact for a plane anyway).
osg::ref_ptr<osg::Geometry> ground()
{
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    const int n = 8;
    const float s = 200.0f;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
        {
            const float x0 = -s + 2 * s * i / n, x1 = -s + 2 * s * (i + 1) / n;
            const float y0 = -s + 2 * s * j / n, y1 = -s + 2 * s * (j + 1) / n;
            for (const osg::Vec3& q : {osg::Vec3(x0, y0, 0), osg::Vec3(x1, y0, 0), osg::Vec3(x1, y1, 0),
                                       osg::Vec3(x0, y0, 0), osg::Vec3(x1, y1, 0), osg::Vec3(x0, y1, 0)})
                v->push_back(q);
        }
    g->setVertexArray(v.get());
    g->addPrimitiveSet(new osg::DrawArrays(GL_TRIANGLES, 0, GLsizei(v->size())));
    return g;
}

osg::ref_ptr<UsageScenario> scenario()
{
    typedef SaliencyMetric M;
    osg::ref_ptr<UsageScenario> s = new UsageScenario;
    s->setName("shader-test");
    // Terrain per fragment: distance (near 40, far 260) blended 1:1 with the view angle
    // (near 20, far 70 degrees).
    osg::ref_ptr<TransitionConfiguration> t = new TransitionConfiguration;
    t->setName("terrain");
    t->setStyle("photorealistic");
    t->addFeatureType(FeatureType::Terrain);
    t->setInterpolation(TransitionConfiguration::FRAGMENT);
    t->addMetric(new M(M::VIEW_DISTANCE, 40.0, 260.0, 1.0));
    t->addMetric(new M(M::VIEW_ANGLE, 20.0, 70.0, 1.0));
    s->addConfiguration(t.get());
    // Buildings per object: distance only.
    osg::ref_ptr<TransitionConfiguration> b = new TransitionConfiguration;
    b->setName("buildings");
    b->setStyle("photorealistic");
    b->addFeatureType(FeatureType::Building);
    b->setInterpolation(TransitionConfiguration::OBJECT);
    b->addMetric(new M(M::VIEW_DISTANCE, 40.0, 260.0, 1.0));
    s->addConfiguration(b.get());
    return s;
}
} // namespace

TEST(TransitionShaderGLTest, FragmentInterestMatchesTheCpuPerPixel)
{
    osg::ref_ptr<LoANode> node = new LoANode;
    node->addChild(feature(ground().get(), 1, FeatureType::Terrain).get());
    node->addChild(feature(new osg::ShapeDrawable(new osg::Box(osg::Vec3(-60, 60, 15), 20, 20, 30)), 2,
                           FeatureType::Building)
                       .get());
    node->addChild(feature(new osg::ShapeDrawable(new osg::Box(osg::Vec3(70, 40, 10), 20, 20, 20)), 3,
                           FeatureType::Building)
                       .get());
    osg::ref_ptr<UsageScenario> sc = scenario();
    node->setScenario(sc.get());
    const osg::Vec3d eye(0, -150, 80), center(0, 40, 0), up(0, 0, 1);
    node->evaluate(eye);
    osg::ref_ptr<osg::Group> view = InterestDebugView::create(*node);

    OffscreenRenderer::Settings settings;
    settings.width = 160;
    settings.height = 120;
    osg::ref_ptr<OffscreenRenderer> r;
    try
    {
        r = new OffscreenRenderer(settings);
    }
    catch (const HeadlessContextError& e)
    {
        GTEST_SKIP() << "no EGL context: " << e.what();
    }
    r->setSceneData(view.get());
    r->setPerspective(50.0);
    r->setViewMatrixAsLookAt(eye, center, up);
    osg::ref_ptr<osg::Image> image = r->renderImage();

    // Unproject pixel centres to rays; where a ray meets the ground inside the quad before any
    // building's box, the pixel shows the terrain's per-fragment interest.
    const osg::Matrixd vp = r->getCamera()->getViewMatrix() * r->getCamera()->getProjectionMatrix();
    const osg::Matrixd inv = osg::Matrixd::inverse(vp);
    const ScenarioEvaluator& e = *node->getEvaluator();
    const TransitionConfiguration& terrain = *sc->getConfigurations()[0];
    int compared = 0, worst = 0;
    double sumDiff = 0.0;
    for (int y = 0; y < settings.height; ++y)
        for (int x = 0; x < settings.width; ++x)
        {
            const double nx = (x + 0.5) / settings.width * 2 - 1, ny = (y + 0.5) / settings.height * 2 - 1;
            const osg::Vec3d a = osg::Vec3d(nx, ny, -1) * inv, b = osg::Vec3d(nx, ny, 1) * inv;
            const osg::Vec3d dir = b - a;
            if (dir.z() >= 0) continue;
            const double t = -a.z() / dir.z();
            const osg::Vec3d p = a + dir * t;
            if (std::fabs(p.x()) > 195 || std::fabs(p.y()) > 195) continue; // off (or at the rim of) the quad
            const unsigned char* px = image->data(x, y);
            // Skip pixels covered by a building (red channel equals the grey of the terrain
            // only on the ground; buildings are near-flat grey too, so test by geometry).
            bool hidden = false;
            for (const auto& f : e.features())
                if (f.bound.valid() && f.bound.zMax() > 1.0)
                {
                    // Does the segment eye -> p pass through the (slightly grown) box?
                    osg::BoundingBoxd g = f.bound;
                    g.expandBy(g._min - osg::Vec3d(2, 2, 0));
                    g.expandBy(g._max + osg::Vec3d(2, 2, 2));
                    for (int k = 0; k <= 200 && !hidden; ++k)
                        hidden = g.contains(eye + (p - eye) * (k / 200.0));
                }
            if (hidden) continue;
            const double cpu = terrain.interestAt(p, e.getView(), 0.0);
            const int expected = int(std::lround((1.0 - cpu) * 255.0));
            const int diff = std::abs(int(px[0]) - expected);
            worst = std::max(worst, diff);
            sumDiff += diff;
            ++compared;
        }
    // Bar: 8-bit quantization (0.5/255) plus float32 against double arithmetic (the view-angle
    // atan and the distance differ below 1e-5 of the range): at most 2/255 anywhere, mean below
    // 0.6/255.
    ASSERT_GT(compared, settings.width * settings.height / 3) << "the ground should fill much of the view";
    EXPECT_LE(worst, 2);
    EXPECT_LT(sumDiff / compared, 0.6);

    // The buildings show their CPU (object-mode) interest as a flat grey: look at the pixel
    // where each box's centre projects.
    for (const auto& f : e.features())
    {
        if (!(f.bound.valid() && f.bound.zMax() > 1.0)) continue;
        const osg::Vec3d c = f.bound.center() * vp;
        const int x = int((c.x() + 1) / 2 * settings.width), y = int((c.y() + 1) / 2 * settings.height);
        ASSERT_TRUE(x >= 0 && x < settings.width && y >= 0 && y < settings.height);
        const ScenarioEvaluator::Match& m = e.matchesOf(f)[0];
        EXPECT_NEAR(image->data(x, y)[0], (1.0 - m.interest) * 255.0, 1.0) << "feature entry " << f.entry;
        EXPECT_GT(m.interest, 0.0f);
        EXPECT_LT(m.interest, 1.0f);
    }
}

namespace
{
osg::ref_ptr<OffscreenRenderer> makeRenderer(int w, int h)
{
    OffscreenRenderer::Settings settings;
    settings.width = w;
    settings.height = h;
    return new OffscreenRenderer(settings);
}

// The ground point seen through pixel (x, y), or false when the ray misses the ground quad.
bool groundPoint(const osg::Matrixd& inverseViewProjection, int x, int y, int w, int h, osg::Vec3d& p)
{
    const double nx = (x + 0.5) / w * 2 - 1, ny = (y + 0.5) / h * 2 - 1;
    const osg::Vec3d a = osg::Vec3d(nx, ny, -1) * inverseViewProjection,
                     b = osg::Vec3d(nx, ny, 1) * inverseViewProjection;
    const osg::Vec3d dir = b - a;
    if (dir.z() >= 0) return false;
    p = a + dir * (-a.z() / dir.z());
    return std::fabs(p.x()) < 195 && std::fabs(p.y()) < 195;
}
} // namespace

// The region metric per fragment reads the LoA node's jump-flooding distance map; per pixel it
// must agree with the CPU's exact distance to the regions within the map's documented error.
TEST(TransitionShaderGLTest, FragmentRegionInterestFollowsTheDistanceMap)
{
    typedef SaliencyMetric M;
    osg::ref_ptr<LoANode> node = new LoANode;
    node->addChild(feature(ground().get(), 1, FeatureType::Terrain).get());
    osg::ref_ptr<UsageScenario> sc = new UsageScenario;
    sc->setName("regions");
    sc->addRegion(new RegionOfInterest(RegionOfInterest::CIRCLES, {{-60.0, 40.0}}, 25.0));
    sc->addRegion(new RegionOfInterest(RegionOfInterest::POLYLINE,
                                       {{-150.0, -120.0}, {20.0, -60.0}, {150.0, 120.0}}, 4.0));
    osg::ref_ptr<TransitionConfiguration> t = new TransitionConfiguration;
    t->setName("terrain");
    t->setStyle("photorealistic");
    t->addFeatureType(FeatureType::Terrain);
    t->setInterpolation(TransitionConfiguration::FRAGMENT);
    t->addMetric(new M(M::REGION, 0.0, 64.0));
    sc->addConfiguration(t.get());
    node->setScenario(sc.get());
    const osg::Vec3d eye(0, -260, 230), center(0, 0, 0), up(0, 0, 1);
    node->bind();
    ASSERT_NE(node->getDistanceField(), nullptr) << "a fragment-mode region metric needs the map";
    const DistanceField::Grid grid = node->getDistanceField()->getGrid();
    // Texels of a 64th of the ramp (1 m), over the ground's 400 m: 400 x 400, no larger.
    EXPECT_DOUBLE_EQ(grid.texelSize, 1.0);
    EXPECT_EQ(grid.width, 400);
    EXPECT_EQ(grid.height, 400);
    node->evaluate(eye);
    osg::ref_ptr<osg::Group> view = InterestDebugView::create(*node);

    osg::ref_ptr<OffscreenRenderer> r;
    try
    {
        r = makeRenderer(200, 150);
    }
    catch (const HeadlessContextError& e)
    {
        GTEST_SKIP() << "no EGL context: " << e.what();
    }
    r->setSceneData(view.get());
    r->setPerspective(50.0);
    r->setViewMatrixAsLookAt(eye, center, up);
    osg::ref_ptr<osg::Image> image = r->renderImage();
    EXPECT_EQ(node->getDistanceField()->getNumComputations(), 1u);

    const osg::Matrixd inv =
        osg::Matrixd::inverse(r->getCamera()->getViewMatrix() * r->getCamera()->getProjectionMatrix());
    const ScenarioEvaluator& e = *node->getEvaluator();
    // Bar: the map's distance is the seed rasterization's (-0.71 .. +1.41 texels,
    // docs/distance-field.md) plus bilinear filtering between texel centres (up to half a texel
    // diagonal, 0.71) away from the exact distance: 2.12 m over a 64 m ramp is 0.033 of
    // interest, 8.5/255; plus 1/255 of quantization. Mean well below: most pixels are
    // saturated (0 or 1) or on smooth slopes.
    int compared = 0, worst = 0, ramped = 0;
    double sum = 0.0;
    for (int y = 0; y < 150; ++y)
        for (int x = 0; x < 200; ++x)
        {
            osg::Vec3d p;
            if (!groundPoint(inv, x, y, 200, 150, p)) continue;
            const double cpu = t->interestAt(p, e.getView(), 0.0);
            const int diff = std::abs(int(image->data(x, y)[0]) - int(std::lround((1.0 - cpu) * 255.0)));
            worst = std::max(worst, diff);
            sum += diff;
            ++compared;
            ramped += cpu > 0.05 && cpu < 0.95 ? 1 : 0;
        }
    ASSERT_GT(compared, 200 * 150 / 3);
    EXPECT_GT(ramped, compared / 10) << "the view should show the ramps around the regions";
    EXPECT_LE(worst, 10);
    EXPECT_LT(sum / compared, 1.5);
}

// In a viewer, the node evaluates in every cull, from the camera's eye, and only features in
// the view frustum count as visible.
TEST(TransitionShaderGLTest, CullEvaluatesVisibleFeaturesFromTheEye)
{
    osg::ref_ptr<LoANode> node = new LoANode;
    node->addChild(feature(new osg::ShapeDrawable(new osg::Box(osg::Vec3(0, 100, 10), 20, 20, 20)), 2,
                           FeatureType::Building)
                       .get());
    node->addChild(feature(new osg::ShapeDrawable(new osg::Box(osg::Vec3(0, -400, 10), 20, 20, 20)), 3,
                           FeatureType::Building)
                       .get());
    node->setScenario(scenario().get());
    osg::ref_ptr<OffscreenRenderer> r;
    try
    {
        r = makeRenderer(64, 48);
    }
    catch (const HeadlessContextError& e)
    {
        GTEST_SKIP() << "no EGL context: " << e.what();
    }
    r->setSceneData(node.get());
    r->setPerspective(40.0);
    const osg::Vec3d eye(0, -100, 30);
    r->setViewMatrixAsLookAt(eye, osg::Vec3d(0, 100, 10), osg::Vec3d(0, 0, 1));
    r->timeFrames(3); // a warm-up frame and 3 timed ones
    EXPECT_EQ(node->getEvaluationCount(), 4u);
    const ScenarioEvaluator& e = *node->getEvaluator();
    EXPECT_NEAR((e.getView().eye - eye).length(), 0.0, 1e-6);
    const int front = e.findFeature(2), behind = e.findFeature(3);
    ASSERT_GE(front, 0);
    ASSERT_GE(behind, 0);
    EXPECT_TRUE(e.features()[front].visible);
    EXPECT_FALSE(e.features()[behind].visible) << "the box 300 m behind the camera is culled";
    // Object mode at the box centre: distance sqrt(0 + 200^2 + 20^2) = 200.998 m on the ramp
    // 40..260 gives 1 - 160.998/220 = 0.26819.
    EXPECT_NEAR(e.matchesOf(e.features()[front])[0].interest,
                1.0 - (std::sqrt(200.0 * 200.0 + 20.0 * 20.0) - 40.0) / 220.0, 1e-5);
}
