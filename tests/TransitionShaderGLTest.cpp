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
