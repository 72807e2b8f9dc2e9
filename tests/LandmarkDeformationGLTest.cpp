// shaders/loa_landmark.vert.glsl against its CPU twin (LandmarkDeformation): a test program
// calls loa_deformVertex and loa_deformNormal for the vertices of a few features and draws each
// vertex as one point into its own pixel of two float targets (deformed position, deformed
// normal), which are read back and compared with the CPU.
#include "support/TestSupport.h"

#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/render/ShaderLibrary>
#include <osgLoA/transitions/LandmarkDeformation>

#include <osg/Camera>
#include <osg/Geometry>
#include <osg/Program>
#include <osg/Uniform>
#include <osg/io_utils>

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
