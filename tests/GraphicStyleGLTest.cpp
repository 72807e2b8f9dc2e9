// The built-in styles' fragment shaders on the GL (llvmpipe): each style file is linked with a
// test-only vertex shader and fragment main that call loa_styleColor and write its result, a
// 32x32 quad is rendered, and the colour is compared with the CPU expectation (Brewer colour x
// flat lighting, ColorQuantization of the texel, texture x colour x lighting).
#include "support/TestSupport.h"
#include "support/TopDownView.h"

#include <osgLoA/city/CityCameras>
#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/render/ShaderLibrary>
#include <osgLoA/semantics/FeatureClassifier>
#include <osgLoA/styles/ColorQuantization>
#include <osgLoA/styles/GraphicStyle>
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/styles/ObjectSpaceEdges>

#include <osg/Geometry>
#include <osg/Material>
#include <osg/MatrixTransform>
#include <osg/ShapeDrawable>
#include <osg/Texture2D>
#include <osg/Uniform>
#include <osgDB/ReadFile>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace osgLoA;

namespace
{
constexpr int kSize = 32;
constexpr float kTolerance = 2.0f; // in 1/255

const char* const kHarnessVertex = R"(#version 450 compatibility
uniform mat4 osg_ModelViewMatrix;
uniform mat4 osg_ModelViewProjectionMatrix;
uniform mat3 osg_NormalMatrix;
out vec3 test_scenePosition;
out vec3 test_viewPosition;
out vec3 test_viewNormal;
out vec2 test_texCoord;
out vec4 test_color;
out vec2 loa_texCoord1; // what loa_style.vert.glsl gives the photorealistic style (units 1, 2)
out vec2 loa_texCoord2;
void main()
{
    test_scenePosition = gl_Vertex.xyz;
    test_viewPosition = (osg_ModelViewMatrix * gl_Vertex).xyz;
    test_viewNormal = osg_NormalMatrix * gl_Normal;
    test_texCoord = gl_MultiTexCoord0.xy;
    loa_texCoord1 = gl_MultiTexCoord1.xy;
    loa_texCoord2 = gl_MultiTexCoord2.xy;
    test_color = gl_Color;
    gl_Position = osg_ModelViewProjectionMatrix * gl_Vertex;
}
)";

const char* const kHarnessFragment = R"(#version 450 compatibility
vec4 loa_styleColor(vec3 scenePosition, vec3 viewPosition, vec3 viewNormal, vec2 texCoord, vec4 color);
in vec3 test_scenePosition;
in vec3 test_viewPosition;
in vec3 test_viewNormal;
in vec2 test_texCoord;
in vec4 test_color;
layout(location = 0) out vec4 test_fragColor;
void main()
{
    vec3 n = normalize(test_viewNormal);
    if (!gl_FrontFacing)
        n = -n;
    test_fragColor = loa_styleColor(test_scenePosition, test_viewPosition, n, test_texCoord, test_color);
}
)";

/** The harness program with the style's fragment file (from ShaderLibrary). */
osg::ref_ptr<osg::Program> harnessProgram(const GraphicStyle& style)
{
    osg::ref_ptr<osg::Program> p = new osg::Program;
    p->setName("test_" + style.getName());
    osg::ref_ptr<osg::Shader> v = new osg::Shader(osg::Shader::VERTEX, kHarnessVertex);
    v->setName("test_harness.vert");
    osg::ref_ptr<osg::Shader> f = new osg::Shader(osg::Shader::FRAGMENT, kHarnessFragment);
    f->setName("test_harness.frag");
    p->addShader(v.get());
    p->addShader(f.get());
    p->addShader(ShaderLibrary::createShader("loa_fixed_function.frag.glsl").get());
    p->addShader(ShaderLibrary::createShader(style.getFragmentShader()).get());
    return p;
}

/** A 4x4 RGBA8 texture with nearest filtering (each texel covers 8x8 pixels of the quad). */
osg::ref_ptr<osg::Texture2D> texture(const std::vector<osg::Vec4ub>& texels)
{
    osg::ref_ptr<osg::Image> image = new osg::Image;
    image->allocateImage(4, 4, 1, GL_RGBA, GL_UNSIGNED_BYTE);
    for (int i = 0; i < 16; ++i)
    {
        unsigned char* p = image->data(i % 4, i / 4);
        for (int c = 0; c < 4; ++c)
            p[c] = texels[i][c];
    }
    osg::ref_ptr<osg::Texture2D> t = new osg::Texture2D(image.get());
    t->setFilter(osg::Texture::MIN_FILTER, osg::Texture::NEAREST);
    t->setFilter(osg::Texture::MAG_FILTER, osg::Texture::NEAREST);
    t->setResizeNonPowerOfTwoHint(false);
    return t;
}

struct Quad
{
    osg::Vec3f normal = osg::Vec3f(0, 0, 1); ///< the vertex normal (all four vertices)
    osg::Vec4f color = osg::Vec4f(1, 1, 1, 1);
    bool hasColor = true;
};

/** The full-viewport quad in the plane z = 0, facing the camera, with the style's program and
 *  parameters on its StateSet. */
osg::ref_ptr<osg::Geometry> quad(const GraphicStyle& style, const Quad& q)
{
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    osg::ref_ptr<osg::Vec2Array> t = new osg::Vec2Array;
    for (auto p : {osg::Vec2(-1, -1), osg::Vec2(1, -1), osg::Vec2(1, 1), osg::Vec2(-1, 1)})
    {
        v->push_back(osg::Vec3(p, 0.0f));
        t->push_back((p + osg::Vec2(1, 1)) * 0.5f);
    }
    g->setVertexArray(v.get());
    g->setTexCoordArray(0, t.get(), osg::Array::BIND_PER_VERTEX);
    osg::ref_ptr<osg::Vec3Array> n = new osg::Vec3Array;
    n->push_back(q.normal);
    g->setNormalArray(n.get(), osg::Array::BIND_OVERALL);
    if (q.hasColor)
    {
        osg::ref_ptr<osg::Vec4Array> c = new osg::Vec4Array;
        c->push_back(q.color);
        g->setColorArray(c.get(), osg::Array::BIND_OVERALL);
    }
    g->addPrimitiveSet(new osg::DrawArrays(GL_QUADS, 0, 4));
    osg::StateSet* ss = g->getOrCreateStateSet();
    ss->setAttributeAndModes(harnessProgram(style).get());
    style.applyParameters(*ss);
    ss->addUniform(new osg::Uniform("loa_baseTexture", 0));
    ss->addUniform(new osg::Uniform("loa_hasTexture", false));
    return g;
}

osg::ref_ptr<osg::Image> render(osg::Node* scene)
{
    OffscreenRenderer::Settings s;
    s.width = kSize;
    s.height = kSize;
    s.clearColor = osg::Vec4(0, 0, 0, 0);
    osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(s);
    r->getCamera()->setProjectionMatrixAsOrtho2D(-1, 1, -1, 1);
    r->getCamera()->setViewMatrix(osg::Matrix::identity());
    r->setSceneData(scene);
    return r->renderImage();
}

osg::Vec4f pixel(const osg::Image& img, int x, int y)
{
    const unsigned char* p = img.data(x, y);
    return osg::Vec4f(p[0], p[1], p[2], p[3]);
}

/** Every pixel (or the one at x, y) equals expected (0..1) within kTolerance / 255. */
void expectPixel(const osg::Image& img, int x, int y, const osg::Vec4f& expected, const std::string& what)
{
    const osg::Vec4f p = pixel(img, x, y);
    for (int c = 0; c < 4; ++c)
        EXPECT_NEAR(p[c], expected[c] * 255.0f, kTolerance)
            << what << " at (" << x << ", " << y << ") channel " << c << ": got (" << p[0] << ", " << p[1]
            << ", " << p[2] << ", " << p[3] << "), expected (" << expected[0] * 255 << ", "
            << expected[1] * 255 << ", " << expected[2] * 255 << ", " << expected[3] * 255 << ")";
}

void expectEverywhere(const osg::Image& img, const osg::Vec4f& expected, const std::string& what)
{
    for (int y = 1; y < kSize; y += 5)
        for (int x = 1; x < kSize; x += 5)
            expectPixel(img, x, y, expected, what);
}

osg::Vec4f rgba(const osg::Vec3f& c, float a = 1.0f)
{
    return osg::Vec4f(c, a);
}

osg::Vec3f times(const osg::Vec3f& a, const osg::Vec3f& b)
{
    return osg::Vec3f(a.x() * b.x(), a.y() * b.y(), a.z() * b.z());
}

osg::Vec3f texelColor(const osg::Vec4ub& t)
{
    return osg::Vec3f(t[0] / 255.0f, t[1] / 255.0f, t[2] / 255.0f);
}

float parameterFloat(const GraphicStyle& s, const std::string& name)
{
    float v = 0.0f;
    s.getParameter(name)->get(v);
    return v;
}

// A tilted vertex normal: flat shading must not use it; smooth shading must.
const osg::Vec3f kTilted = osg::Vec3f(-0.6f, 0.0f, 0.8f);
} // namespace

TEST(GraphicStyleGLTest, CartographicIsTheBrewerColourOfTheFeatureTypeFlatShaded)
{
    loatest::setFilePath("");
    osg::ref_ptr<GraphicStyle> style = GraphicStyle::createBuiltin("cartographic");
    const float ambient = parameterFloat(*style, "loa_cartographic_ambient");
    // The face normal of the quad in view space is +z, whatever the vertex normals say.
    const float light = GraphicStyle::lightFactor(osg::Vec3f(0, 0, 1), ambient);
    ASSERT_GT(std::fabs(light - GraphicStyle::lightFactor(kTilted, ambient)), 0.05f);
    for (FeatureType type : kFeatureTypes)
    {
        Quad q;
        q.normal = kTilted;
        q.color = osg::Vec4f(0.2f, 0.9f, 0.4f, 1.0f); // ignored: the colour comes from the type
        osg::ref_ptr<osg::Geometry> g = quad(*style, q);
        g->getOrCreateStateSet()->addUniform(new osg::Uniform("loa_featureType", static_cast<int>(type)));
        osg::ref_ptr<osg::Image> img = render(g.get());
        expectEverywhere(*img, rgba(GraphicStyle::cartographicColor(type) * light), toString(type));
    }
}

TEST(GraphicStyleGLTest, CartographicColoursAreEditableParameters)
{
    loatest::setFilePath("");
    osg::ref_ptr<GraphicStyle> style = GraphicStyle::createBuiltin("cartographic");
    style->getParameter("loa_cartographic_colors")->setElement(3, osg::Vec3f(1.0f, 0.0f, 0.5f));
    style->getParameter("loa_cartographic_ambient")->set(1.0f);
    osg::ref_ptr<osg::Geometry> g = quad(*style, Quad());
    g->getOrCreateStateSet()->addUniform(new osg::Uniform("loa_featureType", 3));
    expectEverywhere(*render(g.get()), osg::Vec4f(1.0f, 0.0f, 0.5f, 1.0f), "edited water colour");
    // An out-of-range type draws as generic.
    osg::ref_ptr<osg::Geometry> g2 = quad(*style, Quad());
    g2->getOrCreateStateSet()->addUniform(new osg::Uniform("loa_featureType", 42));
    expectEverywhere(*render(g2.get()), rgba(GraphicStyle::cartographicColor(FeatureType::Generic)),
                     "type 42");
}

// Untextured surfaces: the abstract style quantizes their (lit) colour as ColorQuantization does.
// (Textured ones show TextureAbstraction's filtered textures: FilterConfigurationGLTest,
// LoARenderFullFrameGLTest.)
TEST(GraphicStyleGLTest, AbstractIsTheCpuQuantizationOfTheColour)
{
    loatest::setFilePath("");
    // Colours spread over hues, lightness and saturation (none on a quantization boundary:
    // checked below on the CPU).
    const std::vector<osg::Vec4ub> colours = {
        {200, 40, 30, 255},   {30, 160, 60, 255},  {40, 70, 210, 255},   {230, 220, 80, 255},
        {128, 128, 128, 255}, {20, 20, 24, 255},   {250, 250, 245, 255}, {150, 90, 60, 255},
        {90, 150, 170, 255},  {170, 60, 140, 255}, {60, 40, 90, 255},    {210, 150, 120, 255},
        {100, 120, 40, 255},  {240, 120, 20, 255}, {70, 90, 110, 255},   {180, 200, 230, 128}};
    for (const int levels : {5, 3})
        for (std::size_t i = 0; i < colours.size(); ++i)
        {
            osg::ref_ptr<GraphicStyle> style = GraphicStyle::createBuiltin("abstract");
            style->getParameter("loa_abstract_levels")->set(levels);
            style->getParameter("loa_abstract_modelLighting")->set(false);
            style->getParameter("loa_abstract_ambient")->set(1.0f); // unlit: the quantized colour itself
            const float step = parameterFloat(*style, "loa_abstract_chromaStep");
            Quad q;
            const osg::Vec3f c = texelColor(colours[i]);
            q.color = osg::Vec4f(c, colours[i][3] / 255.0f);
            osg::ref_ptr<osg::Geometry> g = quad(*style, q);
            g->getOrCreateStateSet()->addUniform(new osg::Uniform("loa_hasTexture", false));
            osg::ref_ptr<osg::Image> img = render(g.get());
            const osg::Vec3f expected = ColorQuantization::quantize(c, levels, step);
            // The colour must not sit on a boundary, where GPU and CPU rounding may differ.
            for (const osg::Vec3f& d : {osg::Vec3f(0.4f, 0.4f, 0.4f), osg::Vec3f(-0.4f, -0.4f, -0.4f),
                                        osg::Vec3f(0.4f, -0.4f, 0.0f), osg::Vec3f(0.0f, 0.4f, -0.4f)})
                ASSERT_LT((ColorQuantization::quantize(c + d / 255.0f, levels, step) - expected).length(),
                          1.5f / 255.0f)
                    << "colour " << i << " is near a quantization boundary; pick another";
            expectPixel(*img, 16, 16, rgba(expected, colours[i][3] / 255.0f),
                        "abstract, " + std::to_string(levels) + " levels, colour " + std::to_string(i));
        }
}

TEST(GraphicStyleGLTest, AbstractIsLitSoftlyAndQuantized)
{
    loatest::setFilePath("");
    osg::ref_ptr<GraphicStyle> style = GraphicStyle::createBuiltin("abstract");
    style->getParameter("loa_abstract_modelLighting")->set(false);
    const float ambient = parameterFloat(*style, "loa_abstract_ambient");
    const float step = parameterFloat(*style, "loa_abstract_chromaStep");
    int levels = 0;
    style->getParameter("loa_abstract_levels")->get(levels);
    Quad q;
    q.normal = kTilted;
    q.color = osg::Vec4f(0.8f, 0.6f, 0.3f, 1.0f);
    osg::ref_ptr<osg::Geometry> g = quad(*style, q);
    g->getOrCreateStateSet()->addUniform(new osg::Uniform("loa_hasTexture", false));
    const osg::Vec3f lit = osg::Vec3f(0.8f, 0.6f, 0.3f) * GraphicStyle::lightFactor(kTilted, ambient);
    expectEverywhere(*render(g.get()), rgba(ColorQuantization::quantize(lit, levels, step)), "abstract, lit");
}

TEST(GraphicStyleGLTest, PhotorealisticIsTextureTimesColourTimesLight)
{
    loatest::setFilePath("");
    osg::ref_ptr<GraphicStyle> style = GraphicStyle::createBuiltin("photorealistic");
    style->getParameter("loa_photorealistic_fixedFunction")->set(false); // the simple lighting
    const float ambient = parameterFloat(*style, "loa_photorealistic_ambient");
    const osg::Vec4ub texel(200, 100, 50, 255);
    Quad q;
    q.normal = kTilted;
    q.color = osg::Vec4f(1.0f, 0.5f, 1.0f, 1.0f);
    osg::ref_ptr<osg::Geometry> g = quad(*style, q);
    osg::StateSet* ss = g->getOrCreateStateSet();
    ss->setTextureAttributeAndModes(0, texture(std::vector<osg::Vec4ub>(16, texel)).get());
    ss->addUniform(new osg::Uniform("loa_hasTexture", true));
    // The demo city's state: a colour-tracking material.
    osg::ref_ptr<osg::Material> m = new osg::Material;
    m->setColorMode(osg::Material::AMBIENT_AND_DIFFUSE);
    ss->setAttributeAndModes(m.get());
    const osg::Vec3f expected =
        times(texelColor(texel), osg::Vec3f(1.0f, 0.5f, 1.0f)) * GraphicStyle::lightFactor(kTilted, ambient);
    expectEverywhere(*render(g.get()), rgba(expected), "photorealistic");
}

TEST(GraphicStyleGLTest, PhotorealisticMatchesThePlainProgram)
{
    // The same textured, coloured, lit quad through loa_plain and through the style.
    loatest::setFilePath("");
    osg::ref_ptr<GraphicStyle> style = GraphicStyle::createBuiltin("photorealistic");
    style->getParameter("loa_photorealistic_fixedFunction")->set(false); // the simple lighting
    std::vector<osg::Vec4ub> texels;
    for (int i = 0; i < 16; ++i)
        texels.push_back(osg::Vec4ub(16 * i, 255 - 12 * i, (37 * i) % 256, 255));
    osg::ref_ptr<osg::Texture2D> tex = texture(texels);
    Quad q;
    q.normal = osg::Vec3f(-0.3f, 0.4f, 0.866f);
    q.color = osg::Vec4f(0.9f, 0.7f, 0.8f, 1.0f);
    osg::ref_ptr<osg::Geometry> styled = quad(*style, q);
    styled->getOrCreateStateSet()->setTextureAttributeAndModes(0, tex.get());
    styled->getOrCreateStateSet()->addUniform(new osg::Uniform("loa_hasTexture", true));
    osg::ref_ptr<osg::Geometry> plain = quad(*style, q);
    osg::StateSet* ps = plain->getOrCreateStateSet();
    ps->setAttributeAndModes(
        ShaderLibrary::createProgram("plain", {"loa_plain.vert.glsl", "loa_plain.frag.glsl"}).get());
    ps->setTextureAttributeAndModes(0, tex.get());
    ps->addUniform(new osg::Uniform("loa_hasTexture", true));
    osg::ref_ptr<osg::Image> a = render(styled.get());
    osg::ref_ptr<osg::Image> b = render(plain.get());
    int worst = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            for (int c = 0; c < 4; ++c)
                worst = std::max(worst, std::abs(int(a->data(x, y)[c]) - int(b->data(x, y)[c])));
    EXPECT_LE(worst, 1) << "photorealistic differs from loa_plain by " << worst << "/255";
}

TEST(GraphicStyleGLTest, PhotorealisticReadsTheOsgMaterialDiffuseWhenAsked)
{
    // gl_FrontMaterial in the compatibility profile: a material with colour mode OFF and a
    // white colour array; fixed-function lighting would use the material's diffuse colour.
    loatest::setFilePath("");
    osg::ref_ptr<GraphicStyle> style = GraphicStyle::createBuiltin("photorealistic");
    style->getParameter("loa_photorealistic_fixedFunction")->set(false); // the simple lighting
    style->getParameter("loa_photorealistic_materialDiffuse")->set(true);
    style->getParameter("loa_photorealistic_ambient")->set(1.0f);
    Quad q;
    q.color = osg::Vec4f(1, 1, 1, 1);
    osg::ref_ptr<osg::Geometry> g = quad(*style, q);
    osg::ref_ptr<osg::Material> m = new osg::Material;
    m->setColorMode(osg::Material::OFF);
    m->setDiffuse(osg::Material::FRONT_AND_BACK, osg::Vec4f(0.25f, 0.5f, 0.75f, 1.0f));
    g->getOrCreateStateSet()->setAttributeAndModes(m.get());
    expectEverywhere(*render(g.get()), osg::Vec4f(0.25f, 0.5f, 0.75f, 1.0f), "material diffuse");

    // Without the switch and without a colour array, the vertex colour is the material's
    // diffuse colour already (osg::Material::apply sets the current colour).
    osg::ref_ptr<GraphicStyle> plain = GraphicStyle::createBuiltin("photorealistic");
    plain->getParameter("loa_photorealistic_fixedFunction")->set(false);
    plain->getParameter("loa_photorealistic_ambient")->set(1.0f);
    Quad noColor;
    noColor.hasColor = false;
    osg::ref_ptr<osg::Geometry> g2 = quad(*plain, noColor);
    g2->getOrCreateStateSet()->setAttributeAndModes(m.get());
    expectEverywhere(*render(g2.get()), osg::Vec4f(0.25f, 0.5f, 0.75f, 1.0f), "current colour");
}

TEST(GraphicStyleGLTest, BlueprintIsAFlatBlueGroundLitSlightly)
{
    loatest::setFilePath("");
    osg::ref_ptr<GraphicStyle> style = GraphicStyle::createBuiltin("blueprint");
    osg::Vec3f ground;
    style->getParameter("loa_blueprint_color")->get(ground);
    const float ambient = parameterFloat(*style, "loa_blueprint_ambient");
    Quad q;
    q.normal = kTilted;
    q.color = osg::Vec4f(0.1f, 0.9f, 0.1f, 1.0f); // ignored
    osg::ref_ptr<osg::Geometry> g = quad(*style, q);
    g->getOrCreateStateSet()->setTextureAttributeAndModes(
        0, texture(std::vector<osg::Vec4ub>(16, osg::Vec4ub(255, 0, 0, 255))).get());
    g->getOrCreateStateSet()->addUniform(new osg::Uniform("loa_hasTexture", true)); // ignored
    expectEverywhere(*render(g.get()), rgba(ground * GraphicStyle::lightFactor(kTilted, ambient)),
                     "blueprint");
}

// --- object-space edges (osgLoA::ObjectSpaceEdges) ------------------------------------------------

namespace
{
/** "object-edges" with 2 px black lines and the image-space edges and unsharp masking off, and
 *  the same without object edges (width 0, colour of no consequence): only object edges differ. */
void registerEdgeStyles()
{
    GraphicStyleCatalog& catalog = GraphicStyleCatalog::instance();
    if (catalog.prototype("test-object-edges")) return;
    for (bool on : {true, false})
    {
        osg::ref_ptr<GraphicStyle> s = catalog.create("object-edges");
        s->setName(on ? "test-object-edges" : "test-object-edges-off");
        s->setEdgeStrength(0.0f);
        s->setUnsharpMaskStrength(0.0f);
        s->getParameter("loa_objectEdges_width")->set(on ? 2.0f : -2.0f);
        s->getParameter("loa_objectEdges_color")->set(osg::Vec3f(0, 0, 0));
        catalog.add(*s);
    }
}

osg::ref_ptr<osg::Node> genericFeature(osg::Drawable* d)
{
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(d);
    return loatest::asFeature(geode.get(), 1, FeatureType::Generic);
}

/** Distance from p to segment ab. */
double segmentDistance(const osg::Vec2d& p, const osg::Vec2d& a, const osg::Vec2d& b)
{
    const osg::Vec2d ab = b - a;
    const double t = std::max(0.0, std::min(1.0, ((p - a) * ab) / (ab * ab)));
    return (a + ab * t - p).length();
}

struct EdgeFrames
{
    osg::ref_ptr<osg::Image> on, off;
};
EdgeFrames edgeFrames(osg::Node* scene, int w, int h, const loatest::Viewport& vp, const osg::Matrixd& view,
                      double fovy)
{
    registerEdgeStyles();
    EdgeFrames f;
    for (bool on : {true, false})
    {
        osg::ref_ptr<osg::Image> img = loatest::throughLoA(
            scene,
            ScenarioLibrary::createHomogeneous(on ? "test-object-edges" : "test-object-edges-off").get(), w,
            h, vp,
            [&](OffscreenRenderer& r)
            {
                r.getCamera()->setProjectionMatrixAsPerspective(fovy, double(vp.w) / vp.h, 1.0, 500.0);
                r.getCamera()->setViewMatrix(view);
            });
        (on ? f.on : f.off) = img;
    }
    return f;
}

void expectCubeEdges(int w, int h, const loatest::Viewport& vp, bool mirrored = false)
{
    // A cube of side 10 seen from a corner: its 9 visible edges (the outline's 6 and the 3 at the
    // near corner) drawn, the faces' diagonals not. Mirrored (x -> -x: the same cube, its
    // triangles' winding turned over by the transform) the same.
    osg::ref_ptr<osg::ShapeDrawable> cube = new osg::ShapeDrawable(new osg::Box(osg::Vec3(0, 0, 5), 10.0f));
    osg::ref_ptr<osg::Node> scene = genericFeature(cube.get());
    if (mirrored)
    {
        osg::ref_ptr<osg::MatrixTransform> mirror =
            new osg::MatrixTransform(osg::Matrixd::scale(-1.0, 1.0, 1.0));
        mirror->addChild(scene.get());
        scene = mirror;
    }
    const osg::Matrixd view =
        osg::Matrixd::lookAt(osg::Vec3d(24, -30, 26), osg::Vec3d(0, 0, 5), osg::Vec3d(0, 0, 1));
    const double fovy = 40.0;
    const EdgeFrames f = edgeFrames(scene.get(), w, h, vp, view, fovy);
    const std::string name = std::to_string(w) + "x" + std::to_string(h) + "-" + std::to_string(vp.x) +
                             (mirrored ? "-mirrored" : "");
    loatest::keepFrame("object-edges", *f.on, "cube-" + name);
    const osg::Matrixd mvp = view * osg::Matrixd::perspective(fovy, double(vp.w) / vp.h, 1.0, 500.0);
    auto project = [&](const osg::Vec3d& p)
    {
        const osg::Vec3d c = p * mvp;
        return osg::Vec2d((c.x() * 0.5 + 0.5) * vp.w, (c.y() * 0.5 + 0.5) * vp.h);
    };
    // Corners: x, y in {-5, 5}, z in {0, 10}; the eye sees the +x, -y and +z faces.
    auto corner = [&](int x, int y, int z) { return project(osg::Vec3d(5.0 * x, 5.0 * y, 10.0 * z)); };
    const std::vector<std::pair<osg::Vec2d, osg::Vec2d>> visible = {
        {corner(1, -1, 1), corner(1, 1, 1)},    {corner(1, -1, 1), corner(-1, -1, 1)},
        {corner(1, -1, 1), corner(1, -1, 0)},   {corner(1, 1, 1), corner(-1, 1, 1)},
        {corner(-1, 1, 1), corner(-1, -1, 1)},  {corner(1, 1, 1), corner(1, 1, 0)},
        {corner(-1, -1, 1), corner(-1, -1, 0)}, {corner(1, 1, 0), corner(1, -1, 0)},
        {corner(1, -1, 0), corner(-1, -1, 0)}};
    long changed = 0, far = 0;
    std::vector<std::vector<bool>> hit(visible.size());
    for (auto& v : hit)
        v.assign(101, false);
    for (int y = vp.y; y < vp.y + vp.h; ++y)
        for (int x = vp.x; x < vp.x + vp.w; ++x)
        {
            const unsigned char *p = f.on->data(x, y), *q = f.off->data(x, y);
            if (std::max({std::abs(p[0] - q[0]), std::abs(p[1] - q[1]), std::abs(p[2] - q[2])}) <= 8)
                continue;
            ++changed;
            const osg::Vec2d c(x - vp.x + 0.5, y - vp.y + 0.5);
            double best = 1e9;
            for (std::size_t e = 0; e < visible.size(); ++e)
            {
                const double d = segmentDistance(c, visible[e].first, visible[e].second);
                best = std::min(best, d);
                if (d < 2.5)
                {
                    const osg::Vec2d ab = visible[e].second - visible[e].first;
                    const double t = ((c - visible[e].first) * ab) / (ab * ab);
                    hit[e][std::size_t(std::max(0.0, std::min(1.0, t)) * 100.0 + 0.5)] = true;
                }
            }
            far += best > 2.5;
        }
    std::cout << "object edges cube " << name << ": " << changed << " changed pixels, " << far
              << " farther than 2.5 px from a visible edge\n";
    EXPECT_EQ(far, 0) << name;
    for (std::size_t e = 0; e < visible.size(); ++e)
    {
        int covered = 0;
        for (int t = 5; t <= 95; ++t)
            covered += hit[e][std::size_t(t)];
        EXPECT_GE(covered, 82) << name << " edge " << e; // 90 % of 91 samples
    }
}
} // namespace

TEST(ObjectSpaceEdgesGLTest, CubeEdgesAt1920x1080AnOddSizeAndAnOffsetViewport)
{
    expectCubeEdges(1920, 1080, loatest::Viewport{0, 0, 1920, 1080});
    expectCubeEdges(641, 359, loatest::Viewport{0, 0, 641, 359});
    expectCubeEdges(577, 343, loatest::Viewport{37, 21, 500, 300});
    expectCubeEdges(641, 359, loatest::Viewport{0, 0, 641, 359}, true);
}

TEST(ObjectSpaceEdgesGLTest, ASmoothCylinderShowsItsSilhouettesNotItsFacets)
{
    // A cylinder of 40 facets (9 degrees apart: no creases) seen from the side: lines along its two
    // outlines and its cap, none across its side.
    osg::ref_ptr<osg::TessellationHints> hints = new osg::TessellationHints;
    hints->setDetailRatio(1.0f);
    osg::ref_ptr<osg::ShapeDrawable> cyl =
        new osg::ShapeDrawable(new osg::Cylinder(osg::Vec3(0, 0, 10), 4.0f, 20.0f), hints.get());
    osg::ref_ptr<osg::Node> scene = genericFeature(cyl.get());
    const int w = 641, h = 359;
    const osg::Matrixd view =
        osg::Matrixd::lookAt(osg::Vec3d(0, -40, 12), osg::Vec3d(0, 0, 10), osg::Vec3d(0, 0, 1));
    const EdgeFrames f = edgeFrames(scene.get(), w, h, loatest::Viewport{0, 0, w, h}, view, 45.0);
    loatest::keepFrame("object-edges", *f.on, "cylinder-641x359");
    // The row through the cylinder's middle (z = 10): where it changes.
    const osg::Matrixd mvp = view * osg::Matrixd::perspective(45.0, double(w) / h, 1.0, 500.0);
    const int row = int((osg::Vec3d(0, 0, 10) * mvp).y() * 0.5 * h + 0.5 * h);
    std::vector<int> xs;
    for (int x = 0; x < w; ++x)
    {
        const unsigned char *p = f.on->data(x, row), *q = f.off->data(x, row);
        if (std::max({std::abs(p[0] - q[0]), std::abs(p[1] - q[1]), std::abs(p[2] - q[2])}) > 8)
            xs.push_back(x);
    }
    // The outline from the eye (0, -40): tangent points at x = +-4 sqrt(1 - 16/1600) = +-3.98.
    const double xt = 4.0 * std::sqrt(1.0 - 16.0 / 1600.0), yt = -16.0 / 40.0;
    const double left = (osg::Vec3d(-xt, yt, 10) * mvp).x() * 0.5 * w + 0.5 * w,
                 right = (osg::Vec3d(xt, yt, 10) * mvp).x() * 0.5 * w + 0.5 * w;
    int nearLeft = 0, nearRight = 0, elsewhere = 0;
    for (int x : xs)
    {
        if (std::fabs(x + 0.5 - left) < 4.0)
            ++nearLeft;
        else if (std::fabs(x + 0.5 - right) < 4.0)
            ++nearRight;
        else
            ++elsewhere;
    }
    std::cout << "object edges cylinder: row " << row << ", outline at " << left << " and " << right << ": "
              << nearLeft << " and " << nearRight << " changed pixels there, " << elsewhere << " elsewhere\n";
    EXPECT_GE(nearLeft, 1);
    EXPECT_GE(nearRight, 1);
    EXPECT_EQ(elsewhere, 0);
}

TEST(ObjectSpaceEdgesGLTest, ARealScenesGenericFeaturesGetTheirEdges)
{
    // TORCS street-1: 668 generic features by hand (barriers, trucks, grandstands, posts, signs):
    // lines appear on them and nowhere else.
    const std::string file = std::string(LOA_SOURCE_DIR) + "/data/test-scenes/torcs-street-1.osgt";
    if (!osgDB::fileExists(std::string(LOA_SOURCE_DIR) + "/data/cache/torcs-data"))
        GTEST_SKIP() << "the TORCS models are absent: run scripts/fetch-test-data";
    osg::ref_ptr<osg::Node> model = osgDB::readRefNodeFile(file);
    ASSERT_TRUE(model.valid());
    FeatureClassifier().classify(*model);
    registerEdgeStyles();
    // The generic features in magenta, without image-space edges (they darken thin posts whole).
    GraphicStyleCatalog& catalog = GraphicStyleCatalog::instance();
    if (!catalog.prototype("test-generic-mask-flat"))
    {
        osg::ref_ptr<GraphicStyle> mask = catalog.create(loatest::typeMaskStyle(FeatureType::Generic));
        mask->setName("test-generic-mask-flat");
        mask->setEdgeStrength(0.0f);
        mask->setUnsharpMaskStrength(0.0f);
        catalog.add(*mask);
    }
    const int w = 1920, h = 1080;
    osg::ref_ptr<osg::Image> frames[3];
    const std::string styles[3] = {"test-object-edges", "test-object-edges-off", "test-generic-mask-flat"};
    for (int i = 0; i < 3; ++i)
        frames[i] = loatest::throughLoA(model.get(), ScenarioLibrary::createHomogeneous(styles[i]).get(), w,
                                        h, loatest::Viewport{0, 0, w, h},
                                        [&](OffscreenRenderer& r)
                                        {
                                            const CameraPose pose =
                                                CityCameras::compute("street", *model, double(w) / h);
                                            r.setPerspective(pose.fovy);
                                            r.setViewMatrixAsLookAt(pose.eye, pose.center, pose.up);
                                        });
    loatest::keepFrame("object-edges", *frames[0], "torcs-street-1-1920x1080");
    long changed = 0, onGeneric = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const unsigned char *p = frames[0]->data(x, y), *q = frames[1]->data(x, y);
            if (std::max({std::abs(p[0] - q[0]), std::abs(p[1] - q[1]), std::abs(p[2] - q[2])}) <= 8)
                continue;
            ++changed;
            bool generic = false;
            for (int j = std::max(0, y - 2); j <= std::min(h - 1, y + 2) && !generic; ++j)
                for (int i = std::max(0, x - 2); i <= std::min(w - 1, x + 2) && !generic; ++i)
                {
                    const unsigned char* m = frames[2]->data(i, j);
                    generic = m[0] > m[1] + 30 && m[2] > m[1] + 30;
                }
            onGeneric += generic;
        }
    std::cout << "object edges on TORCS street-1: " << changed << " pixels changed, " << onGeneric
              << " on generic features (within 2 px)\n";
    EXPECT_GT(changed, 1000);
    EXPECT_GT(double(onGeneric), 0.99 * double(changed));
}
