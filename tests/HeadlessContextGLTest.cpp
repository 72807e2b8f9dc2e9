// The EGL context: creation, the capabilities it reports, and multisampled FBOs (OSG 3.6.5 fix).
#include <osgLoA/render/OffscreenRenderer>

#include <osg/GLExtensions>
#include <osg/Geometry>

#include <gtest/gtest.h>

#include <set>

using namespace osgLoA;

namespace
{
/** A white triangle with slanted edges over a black background, unlit. */
osg::ref_ptr<osg::Node> slantedTriangle()
{
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    v->push_back(osg::Vec3(-0.8f, -0.7f, 0));
    v->push_back(osg::Vec3(0.9f, -0.5f, 0));
    v->push_back(osg::Vec3(-0.2f, 0.85f, 0));
    g->setVertexArray(v.get());
    osg::ref_ptr<osg::Vec4Array> c = new osg::Vec4Array;
    c->push_back(osg::Vec4(1, 1, 1, 1));
    g->setColorArray(c.get(), osg::Array::BIND_OVERALL);
    g->addPrimitiveSet(new osg::DrawArrays(GL_TRIANGLES, 0, 3));
    g->getOrCreateStateSet()->setMode(GL_LIGHTING, osg::StateAttribute::OFF | osg::StateAttribute::PROTECTED);
    return g;
}

std::set<int> redValues(const osg::Image& img)
{
    std::set<int> s;
    for (int y = 0; y < img.t(); ++y)
        for (int x = 0; x < img.s(); ++x)
            s.insert(img.data(x, y)[0]);
    return s;
}

osg::ref_ptr<osg::Image> renderTriangle(int samples)
{
    OffscreenRenderer::Settings s;
    s.width = 64;
    s.height = 64;
    s.samples = samples;
    s.clearColor = osg::Vec4(0, 0, 0, 1);
    osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(s);
    r->setSceneData(slantedTriangle().get());
    r->getCamera()->setProjectionMatrixAsOrtho2D(-1, 1, -1, 1);
    r->getCamera()->setViewMatrix(osg::Matrix::identity());
    return r->renderImage();
}
} // namespace

TEST(HeadlessContextGLTest, CreatesACompatibilityContextAndReportsLimits)
{
    osg::ref_ptr<HeadlessContext> ctx = new HeadlessContext;
    ASSERT_TRUE(ctx->valid());
    ASSERT_TRUE(ctx->realize());
    const GLCapabilities& c = ctx->getCapabilities();
    EXPECT_FALSE(c.vendor.empty());
    EXPECT_FALSE(c.renderer.empty());
    EXPECT_FALSE(c.glslVersion.empty());
    EXPECT_TRUE(c.versionAtLeast(3, 3)) << c.version;
    EXPECT_TRUE(c.compatibilityProfile) << c.version;
    EXPECT_GE(c.maxSamples, 4); // 4 on llvmpipe, 8 or more on GPUs
    EXPECT_GE(c.maxTextureSize, 4096);
    EXPECT_GT(c.extensions.size(), 50u);
    // Compute support is what the version and extension string say, nothing else.
    EXPECT_EQ(c.computeShaders, c.versionAtLeast(4, 3) || c.hasExtension("GL_ARB_compute_shader"));
    if (c.computeShaders)
    {
        EXPECT_GE(c.maxComputeWorkGroupInvocations, 128);
    }
    EXPECT_EQ(c.bindlessTextures, c.hasExtension("GL_ARB_bindless_texture"));
    if (c.isSoftwareRenderer())
    {
        EXPECT_EQ(c.maxSamples, 4) << "llvmpipe measured 4 (ARCHITECTURE.md §4)";
        EXPECT_FALSE(c.bindlessTextures);
    }
    EXPECT_NE(c.toJson().find("\"max_samples\": " + std::to_string(c.maxSamples)), std::string::npos);
    EXPECT_TRUE(ctx->getPlatform() == "surfaceless" || ctx->getPlatform() == "device" ||
                ctx->getPlatform() == "default");
}

TEST(HeadlessContextGLTest, InstallsTheMultisampleCoverageFix)
{
    osg::ref_ptr<HeadlessContext> ctx = new HeadlessContext;
    ASSERT_TRUE(ctx->realize());
    const bool nv = ctx->getCapabilities().hasExtension("GL_NV_framebuffer_multisample_coverage");
    osg::GLExtensions* ext = osg::GLExtensions::Get(ctx->getState()->getContextID(), false);
    ASSERT_NE(ext, nullptr);
    if (!nv)
    {
        EXPECT_EQ(ext->glRenderbufferStorageMultisampleCoverageNV, nullptr);
    }
}

// Without samples a white triangle on black has only 0 and 255; with 4 samples its slanted
// edges get intermediate coverage values. Without the coverage fix the multisampled FBO is
// incomplete and nothing is drawn at all.
TEST(HeadlessContextGLTest, MultisampledFboRendersAntialiasedEdges)
{
    const auto aliased = redValues(*renderTriangle(0));
    EXPECT_EQ(aliased, (std::set<int>{0, 255}));
    const auto smooth = redValues(*renderTriangle(4));
    EXPECT_TRUE(smooth.count(255)) << "the multisampled FBO drew nothing";
    EXPECT_TRUE(smooth.count(0));
    EXPECT_GE(smooth.size(), 4u) << "no intermediate edge coverage: samples were not used";
}

TEST(HeadlessContextGLTest, SampleCountsAboveTheLimitAreRefused)
{
    OffscreenRenderer::Settings s;
    s.width = 8;
    s.height = 8;
    s.samples = 64;
    try
    {
        osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(s);
        FAIL() << "64 samples were accepted";
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("GL_MAX_SAMPLES"), std::string::npos) << e.what();
    }
}

TEST(HeadlessContextGLTest, TimesFramesAfterAWarmUp)
{
    OffscreenRenderer::Settings s;
    s.width = 32;
    s.height = 32;
    osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(s);
    r->setSceneData(slantedTriangle().get());
    const FrameTimes t = r->timeFrames(5);
    ASSERT_EQ(t.milliseconds.size(), 5u);
    EXPECT_GT(t.min(), 0.0);
    EXPECT_LE(t.min(), t.median());
    EXPECT_LE(t.median(), t.max());
}
