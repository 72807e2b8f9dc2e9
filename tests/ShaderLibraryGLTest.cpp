// Shader compile and link errors are reported with name, stage and log, and stop the render.
#include "support/TestSupport.h"

#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/render/ShaderLibrary>

#include <osg/Geometry>
#include <osg/Uniform>
#include <osgDB/Registry>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>

using namespace osgLoA;

namespace
{

osg::ref_ptr<osg::Node> quadWithPlainProgram()
{
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    for (auto p : {osg::Vec3(-1, -1, 0), osg::Vec3(1, -1, 0), osg::Vec3(1, 1, 0), osg::Vec3(-1, 1, 0)})
        v->push_back(p);
    g->setVertexArray(v.get());
    osg::ref_ptr<osg::Vec3Array> n = new osg::Vec3Array;
    n->push_back(osg::Vec3(0, 0, 1));
    g->setNormalArray(n.get(), osg::Array::BIND_OVERALL);
    osg::ref_ptr<osg::Vec4Array> c = new osg::Vec4Array;
    c->push_back(osg::Vec4(1.0f, 0.5f, 0.25f, 1.0f));
    g->setColorArray(c.get(), osg::Array::BIND_OVERALL);
    g->addPrimitiveSet(new osg::DrawArrays(GL_QUADS, 0, 4));
    osg::StateSet* ss = g->getOrCreateStateSet();
    ss->setAttributeAndModes(
        ShaderLibrary::createProgram("plain", {"loa_plain.vert.glsl", "loa_plain.frag.glsl"}).get());
    ss->addUniform(new osg::Uniform("loa_hasTexture", false));
    ss->addUniform(new osg::Uniform("loa_ambient", 1.0f));
    return g;
}

osg::ref_ptr<OffscreenRenderer> renderer()
{
    OffscreenRenderer::Settings s;
    s.width = 16;
    s.height = 16;
    s.clearColor = osg::Vec4(0, 0, 0, 1);
    osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(s);
    r->getCamera()->setProjectionMatrixAsOrtho2D(-1, 1, -1, 1);
    r->getCamera()->setViewMatrix(osg::Matrix::identity());
    return r;
}
/** Renders the plain quad with loa_plain.frag.glsl overridden by fragmentSource and returns
 *  the ShaderError it must throw (a failed test when it renders instead). */
ShaderError renderWithBrokenFragment(const std::string& name, const std::string& fragmentSource)
{
    const std::string dir = loatest::freshDirectory(name);
    std::ofstream(dir + "/loa_plain.frag.glsl") << fragmentSource;
    loatest::setFilePath(dir);
    auto r = renderer();
    r->setSceneData(quadWithPlainProgram().get());
    loatest::setFilePath("");
    try
    {
        r->renderImage();
    }
    catch (const ShaderError& e)
    {
        return e;
    }
    ADD_FAILURE() << name << ": a broken program rendered an image";
    return ShaderError({});
}
} // namespace

TEST(ShaderLibraryGLTest, TheEmbeddedPlainProgramLinksAndShades)
{
    loatest::setFilePath("");
    auto r = renderer();
    r->setSceneData(quadWithPlainProgram().get());
    osg::ref_ptr<osg::Image> img = r->renderImage();
    // ambient 1, no texture: exactly the vertex colour (1, 0.5, 0.25) -> (255, 128, 64) +-1.
    const unsigned char* p = img->data(8, 8);
    EXPECT_NEAR(p[0], 255, 1);
    EXPECT_NEAR(p[1], 128, 1);
    EXPECT_NEAR(p[2], 64, 1);
}

TEST(ShaderLibraryGLTest, ACompileErrorNamesShaderStageAndLogAndStopsTheRender)
{
    const ShaderError e = renderWithBrokenFragment(
        "ShaderCompileError", "#version 450 compatibility\nvoid main() { this is not glsl; }\n");
    ASSERT_EQ(e.diagnostics().size(), 1u);
    const ShaderDiagnostic& d = e.diagnostics()[0];
    EXPECT_EQ(d.programName, "plain");
    EXPECT_EQ(d.shaderName, "loa_plain.frag.glsl");
    EXPECT_EQ(d.stage, "fragment");
    std::string log = d.log;
    std::transform(log.begin(), log.end(), log.begin(), ::tolower);
    EXPECT_NE(log.find("error"), std::string::npos) << d.log;
    EXPECT_NE(std::string(e.what()).find("loa_plain.frag.glsl"), std::string::npos);
}

TEST(ShaderLibraryGLTest, ALinkErrorIsReportedAsSuch)
{
    // Both stages compile, but the fragment stage reads an input no stage writes.
    const ShaderError e = renderWithBrokenFragment(
        "ShaderLinkError", "#version 450 compatibility\nin vec4 loa_neverWritten;\nout vec4 c;\n"
                           "void main() { c = loa_neverWritten; }\n");
    ASSERT_EQ(e.diagnostics().size(), 1u);
    EXPECT_EQ(e.diagnostics()[0].stage, "link");
    EXPECT_FALSE(e.diagnostics()[0].log.empty());
}
