// shaders/loa_landmark.vert.glsl against its CPU twin (LandmarkDeformation), and map sinking in
// whole frames (below). The twin: a test program
// calls loa_deformVertex and loa_deformNormal for the vertices of a few features and draws each
// vertex as one point into its own pixel of two float targets (deformed position, deformed
// normal), which are read back and compared with the CPU.
#include "support/TestSupport.h"
#include "support/TopDownView.h"

#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/render/ShaderLibrary>
#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/transitions/LandmarkDeformation>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/ScenarioLibrary>

#include <osg/Camera>
#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Program>
#include <osg/ShapeDrawable>
#include <osg/Uniform>
#include <osg/io_utils>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

using namespace osgLoA;

namespace
{
typedef LandmarkDeformation LD;

const int kWidth = 16, kHeight = 16;

const char* const kVertex = R"(#version 450 compatibility
vec3 loa_deformVertex(vec3 scenePosition);
vec3 loa_deformNormal(vec3 sceneNormal);
flat out vec3 loa_testPosition;
flat out vec3 loa_testNormal;
void main()
{
    loa_testPosition = loa_deformVertex(gl_Vertex.xyz);
    loa_testNormal = loa_deformNormal(gl_Normal);
    int i = int(gl_MultiTexCoord0.x + 0.5); // the vertex's pixel
    vec2 pixel = vec2(i % 16, i / 16) + 0.5;
    gl_Position = vec4(pixel / vec2(16.0, 16.0) * 2.0 - 1.0, 0.0, 1.0);
}
)";

const char* const kFragment = R"(#version 450 compatibility
flat in vec3 loa_testPosition;
flat in vec3 loa_testNormal;
layout(location = 0) out vec4 loa_outPosition;
layout(location = 1) out vec4 loa_outNormal;
void main()
{
    loa_outPosition = vec4(loa_testPosition, 1.0);
    loa_outNormal = vec4(loa_testNormal, 1.0);
}
)";

struct TestFeature
{
    LD::FeatureInput input;
    std::vector<osg::Vec3d> points;
    std::vector<osg::Vec3d> normals;
    int first = 0;
    osg::ref_ptr<osg::Geometry> geometry;
};

TestFeature makeFeature(const osg::BoundingBoxd& box, bool landmark, const osg::Vec3d& bestView, int& next)
{
    TestFeature f;
    f.input.bound = box;
    f.input.landmark = landmark;
    f.input.bestView = bestView;
    f.input.staticInterest = 1.0;
    f.input.type = FeatureType::Building;
    const osg::Vec3d axes[] = {osg::Vec3d(1, 0, 0), osg::Vec3d(0, 1, 0), osg::Vec3d(0, 0, 1),
                               osg::Vec3d(-0.6, 0.0, 0.8)};
    for (unsigned i = 0; i < 8; ++i)
    {
        f.points.push_back(box.corner(i));
        f.normals.push_back(axes[i % 4]);
    }
    f.points.push_back(box.center());
    f.normals.push_back(osg::Vec3d(0.3, -0.5, 0.2));
    f.first = next;
    next += int(f.points.size());
    f.geometry = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    osg::ref_ptr<osg::Vec3Array> n = new osg::Vec3Array;
    osg::ref_ptr<osg::Vec2Array> index = new osg::Vec2Array;
    for (std::size_t i = 0; i < f.points.size(); ++i)
    {
        v->push_back(osg::Vec3(f.points[i]));
        n->push_back(osg::Vec3(f.normals[i]));
        index->push_back(osg::Vec2(float(f.first + int(i)), 0.0f));
    }
    f.geometry->setVertexArray(v.get());
    f.geometry->setNormalArray(n.get(), osg::Array::BIND_PER_VERTEX);
    f.geometry->setTexCoordArray(0, index.get(), osg::Array::BIND_PER_VERTEX);
    f.geometry->addPrimitiveSet(new osg::DrawArrays(GL_POINTS, 0, GLsizei(v->size())));
    f.geometry->setCullingActive(false);
    return f;
}

osg::ref_ptr<osg::Image> floatImage()
{
    osg::ref_ptr<osg::Image> image = new osg::Image;
    image->allocateImage(kWidth, kHeight, 1, GL_RGBA, GL_FLOAT);
    image->setInternalTextureFormat(GL_RGBA32F_ARB);
    return image;
}

osg::Vec3d pixel(const osg::Image& image, int i)
{
    const float* p = reinterpret_cast<const float*>(image.data()) + 4 * i;
    return osg::Vec3d(p[0], p[1], p[2]);
}

/** The scene: a pre-render camera into two float targets drawing the features' points with
 *  the test program; the deformation's scene-wide uniforms on the camera. */
osg::ref_ptr<osg::Camera> testCamera(std::vector<TestFeature>& features, osg::Image* positions,
                                     osg::Image* normals)
{
    osg::ref_ptr<osg::Camera> cam = new osg::Camera;
    cam->setRenderOrder(osg::Camera::PRE_RENDER);
    cam->setReferenceFrame(osg::Transform::ABSOLUTE_RF);
    cam->setRenderTargetImplementation(osg::Camera::FRAME_BUFFER_OBJECT);
    cam->setViewport(0, 0, kWidth, kHeight);
    cam->setClearColor(osg::Vec4(0, 0, 0, 0));
    cam->setClearMask(GL_COLOR_BUFFER_BIT);
    cam->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    cam->setCullingMode(osg::CullSettings::NO_CULLING);
    cam->setProjectionMatrix(osg::Matrix::identity());
    cam->setViewMatrix(osg::Matrix::identity());
    cam->attach(osg::Camera::COLOR_BUFFER0, positions);
    cam->attach(osg::Camera::COLOR_BUFFER1, normals);
    osg::ref_ptr<osg::Program> program = new osg::Program;
    program->setName("landmark deformation test");
    program->addShader(new osg::Shader(osg::Shader::VERTEX, kVertex));
    program->addShader(ShaderLibrary::createShader("loa_landmark.vert.glsl").get());
    program->addShader(new osg::Shader(osg::Shader::FRAGMENT, kFragment));
    osg::StateSet* ss = cam->getOrCreateStateSet();
    ss->setAttributeAndModes(program.get());
    ss->setMode(GL_DEPTH_TEST, osg::StateAttribute::OFF);
    ss->setMode(GL_BLEND, osg::StateAttribute::OFF);
    ss->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
    for (TestFeature& f : features)
        cam->addChild(f.geometry.get());
    return cam;
}

/** |a - b| per component within 1e-3 of max(1, |b|). */
bool near(const osg::Vec3d& a, const osg::Vec3d& b, double rel)
{
    const double tol = rel * std::max(1.0, b.length());
    return std::fabs(a.x() - b.x()) <= tol && std::fabs(a.y() - b.y()) <= tol &&
           std::fabs(a.z() - b.z()) <= tol;
}

osg::Vec3d unit(osg::Vec3d v)
{
    v.normalize();
    return v;
}
} // namespace

TEST(LandmarkDeformationGLTest, ShaderMatchesTheCpu)
{
    int next = 0;
    std::vector<TestFeature> features;
    // A landmark with a best view east, one without a best view, a non-landmark building
    // (sinks), a landmark of zero height, and one far away (scaled).
    features.push_back(
        makeFeature(osg::BoundingBoxd(100, 200, 0, 110, 220, 30), true, osg::Vec3d(1, 0, 0), next));
    features.push_back(makeFeature(osg::BoundingBoxd(-60, 40, 0, -20, 70, 55), true, osg::Vec3d(), next));
    features.push_back(makeFeature(osg::BoundingBoxd(30, -80, 0, 50, -50, 12), false, osg::Vec3d(), next));
    features.push_back(
        makeFeature(osg::BoundingBoxd(0, 0, 5, 8, 8, 5), true, osg::Vec3d(0.70710678, 0.70710678, 0), next));
    features.push_back(
        makeFeature(osg::BoundingBoxd(400, 600, 0, 420, 640, 80), true, osg::Vec3d(0, -1, 0), next));
    ASSERT_LE(next, kWidth * kHeight);

    osg::ref_ptr<LD> deformation = new LD;
    deformation->setSinkingEnabled(true);
    deformation->setScaleNear(100.0);
    deformation->setScaleFar(900.0);
    deformation->setMaxScale(2.5);
    osg::ref_ptr<osg::Image> positions = floatImage(), normals = floatImage();
    osg::ref_ptr<osg::Camera> cam = testCamera(features, positions.get(), normals.get());

    OffscreenRenderer::Settings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    osg::ref_ptr<OffscreenRenderer> r;
    try
    {
        r = new OffscreenRenderer(settings);
    }
    catch (const HeadlessContextError& e)
    {
        GTEST_SKIP() << "no EGL context: " << e.what();
    }
    r->setSceneData(cam.get());

    // Oblique (about 40 degrees: partly morphed), steep, straight down, and low (no morph).
    const LD::View views[] = {
        LD::View::lookAt(osg::Vec3d(-250, -300, 330), osg::Vec3d(50, 100, 0), osg::Vec3d(0, 0, 1)),
        LD::View::lookAt(osg::Vec3d(300, 100, 700), osg::Vec3d(60, 120, 0), osg::Vec3d(0, 0, 1)),
        LD::View(osg::Vec3d(80, 150, 600), osg::Vec3d(0, 0, -1), osg::Vec3d(0.6, 0.8, 0)),
        LD::View::lookAt(osg::Vec3d(0, -400, 20), osg::Vec3d(0, 0, 10), osg::Vec3d(0, 0, 1))};
    int compared = 0, deformed = 0;
    double worst = 0.0;
    for (int v = 0; v < 4; ++v)
    {
        LD::applyScenario(*cam->getOrCreateStateSet(), deformation.get());
        std::vector<LD::FeatureFrame> frames;
        for (TestFeature& f : features)
        {
            deformation->applyFeature(*f.geometry->getOrCreateStateSet(), f.input, views[v]);
            frames.push_back(deformation->computeFrame(f.input, views[v]));
        }
        r->renderImage();
        for (std::size_t k = 0; k < features.size(); ++k)
        {
            const TestFeature& f = features[k];
            for (std::size_t i = 0; i < f.points.size(); ++i)
            {
                const osg::Vec3d cpu = LD::deform(f.points[i], frames[k]);
                const osg::Vec3d gpu = pixel(*positions, f.first + int(i));
                EXPECT_TRUE(near(gpu, cpu, 1e-3)) << "view " << v << " feature " << k << " vertex " << i
                                                  << ": gpu " << gpu << ", cpu " << cpu;
                const osg::Vec3d n = LD::deformNormal(f.normals[i], frames[k]);
                const osg::Vec3d gpuNormal = pixel(*normals, f.first + int(i));
                EXPECT_TRUE(near(gpuNormal, n, 1e-3)) << "view " << v << " feature " << k << " normal " << i
                                                      << ": gpu " << gpuNormal << ", cpu " << n;
                worst = std::max(worst, (gpu - cpu).length() / std::max(1.0, cpu.length()));
                ++compared;
                deformed += (cpu - f.points[i]).length() > 0.5 ? 1 : 0;
            }
        }
    }
    EXPECT_EQ(compared, 4 * next);
    std::cout << "compared " << compared << " vertices, " << deformed
              << " of them moved by more than 0.5; worst position error " << worst << " (relative)\n";
    EXPECT_GT(deformed, compared / 3) << "most views should deform most vertices";

    // Disabled (a scenario without a deformation): the positions and normals pass unchanged,
    // whatever the features' own uniforms hold.
    LD::applyScenario(*cam->getOrCreateStateSet(), nullptr);
    r->renderImage();
    for (const TestFeature& f : features)
        for (std::size_t i = 0; i < f.points.size(); ++i)
        {
            EXPECT_TRUE(near(pixel(*positions, f.first + int(i)), f.points[i], 1e-6));
            EXPECT_TRUE(near(pixel(*normals, f.first + int(i)), unit(f.normals[i]), 1e-6));
        }
}

// Non-landmarks shrink and sink where a scenario draws them as a map (paper 004 §3.2.2, Figure 1;
// sinkFollowsMapStyles, the view-angle and navigation scenarios of the library): seen from
// straight above, where the view-angle scenario is a map, the frame of a town equals the frame of
// its ground and landmark alone (the houses are under the ground) at 1920x1080, an odd size and in
// an offset viewport; seen from the street, where it is detailed, the houses stand. On West
// Oakland (OpenStreetMap) the same holds for its buildings.
namespace sinking
{
osg::ref_ptr<osg::Node> box(unsigned id, const osg::Vec3& centre, float size, float height, bool landmark)
{
    osg::ref_ptr<osg::Geode> g = new osg::Geode;
    g->addDrawable(
        new osg::ShapeDrawable(new osg::Box(centre + osg::Vec3(0, 0, 0.5f * height), size, size, height)));
    osg::ref_ptr<Feature> f = new Feature(id, FeatureType::Building, "", Feature::MODEL_DATA);
    f->setLandmark(landmark);
    if (landmark) f->setInterest(1.0f);
    Feature::attach(*g, f.get());
    return g;
}

/** Ground 800 m square, a landmark tower at the centre, and (with houses) 36 houses around it. */
osg::ref_ptr<osg::Group> town(bool houses)
{
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(loatest::featureQuad(1, FeatureType::Terrain, "", -400, -400, 400, 400).get());
    root->addChild(box(2, osg::Vec3(0, 0, 0), 30.0f, 120.0f, true).get());
    unsigned id = 10;
    if (houses)
        for (int i = -3; i < 3; ++i)
            for (int j = -3; j < 3; ++j)
                if (i != -1 && i != 0 && j != -1 && j != 0)
                    root->addChild(
                        box(id++, osg::Vec3(60.0f * i + 30.0f, 60.0f * j + 30.0f, 0), 24.0f, 18.0f, false)
                            .get());
    return root;
}

osg::ref_ptr<osg::Image> frame(osg::Node* model, const osg::Vec3d& eye, const osg::Vec3d& centre,
                               const osg::Vec3d& up, int width, int height, const loatest::Viewport& vp,
                               UsageScenario* scenario = nullptr)
{
    osg::ref_ptr<UsageScenario> s = scenario ? scenario : ScenarioLibrary::createBuiltin("view-angle").get();
    return loatest::throughLoA(model, s.get(), width, height, vp,
                               [&](OffscreenRenderer& r)
                               {
                                   r.getCamera()->setProjectionMatrixAsPerspective(40.0, double(vp.w) / vp.h,
                                                                                   5.0, 5000.0);
                                   r.setViewMatrixAsLookAt(eye, centre, up);
                               });
}

long differing(const osg::Image& a, const osg::Image& b)
{
    long n = 0;
    for (int y = 0; y < a.t(); ++y)
        for (int x = 0; x < a.s(); ++x)
        {
            const unsigned char *p = a.data(x, y), *q = b.data(x, y);
            n += std::abs(int(p[0]) - int(q[0])) > 2 || std::abs(int(p[1]) - int(q[1])) > 2 ||
                 std::abs(int(p[2]) - int(q[2])) > 2;
        }
    return n;
}

void expectSunkFromAboveStandingFromTheStreet(int width, int height, const loatest::Viewport& vp)
{
    osg::ref_ptr<osg::Node> withHouses = town(true), without = town(false);
    const std::string size = std::to_string(width) + "x" + std::to_string(height);
    // From 900 m straight above: every view angle is over 60 degrees (map).
    const osg::Vec3d above(0, 0, 900), north(0, 1, 0), up(0, 0, 1);
    osg::ref_ptr<osg::Image> a = frame(withHouses.get(), above, osg::Vec3d(), north, width, height, vp);
    osg::ref_ptr<osg::Image> b = frame(without.get(), above, osg::Vec3d(), north, width, height, vp);
    loatest::keepFrame("map-sinking", *a, "above-" + size);
    const long fromAbove = differing(*a, *b);
    // From the street, 10 m up and 380 m south: angles of 1-5 degrees (detail).
    const osg::Vec3d street(0, -380, 10);
    osg::ref_ptr<osg::Image> c = frame(withHouses.get(), street, osg::Vec3d(0, 0, 10), up, width, height, vp);
    osg::ref_ptr<osg::Image> d = frame(without.get(), street, osg::Vec3d(0, 0, 10), up, width, height, vp);
    loatest::keepFrame("map-sinking", *c, "street-" + size);
    const long fromStreet = differing(*c, *d);
    const double pixels = double(vp.w) * vp.h;
    std::cout << size << ": from above " << fromAbove << " pixels differ, from the street " << fromStreet
              << " (" << 100.0 * fromStreet / pixels << " %)\n";
    EXPECT_EQ(fromAbove, 0);
    EXPECT_GT(double(fromStreet), 0.01 * pixels);
}
} // namespace sinking
using namespace sinking;

TEST(LandmarkDeformationGLTest, HousesSinkInTheMapAndStandInDetailAt1920x1080)
{
    expectSunkFromAboveStandingFromTheStreet(1920, 1080, loatest::Viewport{0, 0, 1920, 1080});
}

TEST(LandmarkDeformationGLTest, HousesSinkInTheMapAndStandInDetailAtAnOddSizeAndInAnOffsetViewport)
{
    expectSunkFromAboveStandingFromTheStreet(641, 359, loatest::Viewport{0, 0, 641, 359});
    expectSunkFromAboveStandingFromTheStreet(577, 343, loatest::Viewport{37, 21, 500, 300});
}

// West Oakland (OpenStreetMap): from 3 km straight above (a map everywhere) the frame equals the
// frame with its buildings hidden (none is a landmark: they are under the ground), and from a low
// oblique camera it does not.
TEST(LandmarkDeformationGLTest, TheBuildingsOfARealOsmFileSinkInTheMap)
{
    const std::string file = std::string(LOA_SOURCE_DIR) + "/data/cache/python-osmnx-doc/West-Oakland.osm";
    if (!osgDB::fileExists(file)) GTEST_SKIP() << file << " is absent: run scripts/fetch-test-data";
    osg::ref_ptr<osg::Node> model = osgDB::readRefNodeFile(file);
    ASSERT_TRUE(model.valid());
    FeatureIndex index(*model);
    std::vector<osg::Node*> buildings;
    for (const FeatureIndex::Entry& e : index.entries())
    {
        osg::ref_ptr<osg::Node> node;
        if (e.feature->getType() == FeatureType::Building && !e.feature->getLandmark() && e.node.lock(node))
            buildings.push_back(node.get());
    }
    ASSERT_GT(buildings.size(), 10u);
    const osg::Vec3d c = model->getBound().center();
    const int w = 1920, h = 1080;
    const loatest::Viewport vp{0, 0, w, h};
    auto both =
        [&](const osg::Vec3d& eye, const osg::Vec3d& at, const osg::Vec3d& up, const std::string& name)
    {
        osg::ref_ptr<osg::Image> shown = frame(model.get(), eye, at, up, w, h, vp);
        for (osg::Node* b : buildings)
            b->setNodeMask(0u);
        osg::ref_ptr<osg::Image> hidden = frame(model.get(), eye, at, up, w, h, vp);
        for (osg::Node* b : buildings)
            b->setNodeMask(~0u);
        loatest::keepFrame("map-sinking", *shown, name);
        return differing(*shown, *hidden);
    };
    const long fromAbove = both(c + osg::Vec3d(0, 0, 3000), c, osg::Vec3d(0, 1, 0), "west-oakland-above");
    const long fromLow = both(c + osg::Vec3d(0, -500, 30), c, osg::Vec3d(0, 0, 1), "west-oakland-low");
    std::cout << "west-oakland (" << buildings.size() << " buildings): from above " << fromAbove
              << " pixels differ, from a low camera " << fromLow << "\n";
    EXPECT_EQ(fromAbove, 0);
    EXPECT_GT(fromLow, 1000);
}

// The sinking follows the scenario's map band, not the deformation's own driver: the distance
// scenario (cartographic beyond 1.19 D) with the view-angle deformation, seen from the street
// (view angles of 1-5 degrees: the driver says "detailed" everywhere). Following the map styles,
// the far houses sink and only the near ones differ from the town without houses; following the
// driver (SinkFollowsMapStyles off), every house stands.
TEST(LandmarkDeformationGLTest, HousesSinkWhereTheScenarioDrawsAMapWhateverItsMetric)
{
    osg::ref_ptr<osg::Node> withHouses = town(true), without = town(false);
    const int w = 960, h = 540;
    const loatest::Viewport vp{0, 0, w, h};
    const osg::Vec3d street(0, -380, 10), at(0, 0, 10), up(0, 0, 1);
    auto scenario = [](bool follow)
    {
        osg::ref_ptr<UsageScenario> s = ScenarioLibrary::createBuiltin("distance");
        osg::ref_ptr<LandmarkDeformation> d = new LandmarkDeformation;
        d->setSinkingEnabled(true);
        d->setSinkFollowsMapStyles(follow);
        s->setLandmarkDeformation(d.get());
        return s;
    };
    osg::ref_ptr<osg::Image> empty = frame(without.get(), street, at, up, w, h, vp, scenario(true).get());
    osg::ref_ptr<osg::Image> following =
        frame(withHouses.get(), street, at, up, w, h, vp, scenario(true).get());
    osg::ref_ptr<osg::Image> driven =
        frame(withHouses.get(), street, at, up, w, h, vp, scenario(false).get());
    loatest::keepFrame("map-sinking", *following, "distance-following-960x540");
    loatest::keepFrame("map-sinking", *driven, "distance-driver-960x540");
    const long byMap = differing(*following, *empty), byDriver = differing(*driven, *empty);
    std::cout << "distance scenario from the street: houses differ on " << byMap
              << " pixels sinking by the map, " << byDriver << " by the driver\n";
    // The near houses stand (most of the pixels: 31,216 at 960x540); the far ones (3,822 pixels,
    // cartographic red, looked at) are gone.
    EXPECT_GT(byMap, 500);
    EXPECT_GT(byDriver - byMap, 2000);
}
