// The palette lookup on the GL (llvmpipe) against the CPU (paper 003, issue 8 items 3 and 5):
// textured quads drawn one texel per pixel (nearest filtering, orthographic) with the standalone
// program (PaletteMapping::createProgram) after PaletteMapping::attach, every pixel compared
// with PaletteLookup::map of its texel at the level the strategy gives (static, depth,
// orientation, interest; per-object overrides); and the "palette" graphic style linked into the
// LoA pipeline's programs.
#include "support/TestSupport.h"

#include <osgLoA/palette/PaletteLookup>
#include <osgLoA/palette/PaletteMapping>
#include <osgLoA/palette/PaletteStyle>
#include <osgLoA/palette/TexturePalette>
#include <osgLoA/render/HeadlessContext>
#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/render/ShaderLibrary>
#include <osgLoA/styles/GraphicStyleCatalog>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Texture2D>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <random>
#include <set>

using namespace osgLoA;

namespace
{
constexpr int T = 32; // texture side = quad side in pixels

/** A T x T texture of 64 distinct random colours (nearest filtering, no mipmaps). */
osg::ref_ptr<osg::Texture2D> noiseTexture()
{
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> byte(0, 255);
    std::vector<osg::Vec3ub> colours;
    std::set<unsigned> seen;
    while (colours.size() < 64)
    {
        const osg::Vec3ub c(byte(rng), byte(rng), byte(rng));
        if (seen.insert(c[0] << 16 | c[1] << 8 | c[2]).second) colours.push_back(c);
    }
    osg::ref_ptr<osg::Image> img = new osg::Image;
    img->allocateImage(T, T, 1, GL_RGBA, GL_UNSIGNED_BYTE, 1);
    std::uniform_int_distribution<int> pick(0, 63);
    for (int y = 0; y < T; ++y)
        for (int x = 0; x < T; ++x)
        {
            // Every colour at least once (the first 64 texels), then random.
            const osg::Vec3ub& c = colours[y * T + x < 64 ? y * T + x : pick(rng)];
            unsigned char* p = img->data(x, y);
            p[0] = c[0];
            p[1] = c[1];
            p[2] = c[2];
            p[3] = 255;
        }
    osg::ref_ptr<osg::Texture2D> t = new osg::Texture2D(img.get());
    t->setFilter(osg::Texture::MIN_FILTER, osg::Texture::NEAREST);
    t->setFilter(osg::Texture::MAG_FILTER, osg::Texture::NEAREST);
    t->setResizeNonPowerOfTwoHint(false);
    return t;
}

/** A T x T quad from (x0, y0) at depth -z, normal n, white, the texture on its own StateSet. */
osg::ref_ptr<osg::Geometry> quad(float x0, float y0, float z, const osg::Vec3& n, osg::Texture2D* tex)
{
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    osg::ref_ptr<osg::Vec2Array> t = new osg::Vec2Array;
    for (auto p : {osg::Vec2(0, 0), osg::Vec2(1, 0), osg::Vec2(1, 1), osg::Vec2(0, 1)})
    {
        v->push_back(osg::Vec3(x0 + p.x() * T, y0 + p.y() * T, -z));
        t->push_back(p);
    }
    g->setVertexArray(v.get());
    g->setTexCoordArray(0, t.get(), osg::Array::BIND_PER_VERTEX);
    osg::ref_ptr<osg::Vec3Array> na = new osg::Vec3Array;
    na->push_back(n);
    g->setNormalArray(na.get(), osg::Array::BIND_OVERALL);
    osg::ref_ptr<osg::Vec4Array> c = new osg::Vec4Array;
    c->push_back(osg::Vec4(1, 1, 1, 1));
    g->setColorArray(c.get(), osg::Array::BIND_OVERALL);
    g->addPrimitiveSet(new osg::DrawArrays(GL_QUADS, 0, 4));
    g->getOrCreateStateSet()->setTextureAttributeAndModes(0, tex);
    return g;
}

/** Renders `scene` into a width x T image, view identity, orthographic over x in
 *  [-width/2, width/2], y in [-T/2, T/2], depth [1, 2000]. */
struct Renderer
{
    osg::ref_ptr<OffscreenRenderer> r;
    explicit Renderer(int width)
    {
        OffscreenRenderer::Settings s;
        s.width = width;
        s.height = T;
        s.clearColor = osg::Vec4(0, 0, 0, 0);
        r = new OffscreenRenderer(s);
        r->getCamera()->setProjectionMatrixAsOrtho(-width / 2.0, width / 2.0, -T / 2.0, T / 2.0, 1.0, 2000.0);
        r->getCamera()->setViewMatrix(osg::Matrix::identity());
        r->getCamera()->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    }
};

/** The standalone program on the root, unlit. */
void useProgram(osg::Node& root, int strategy)
{
    osg::StateSet* ss = root.getOrCreateStateSet();
    ss->setAttributeAndModes(PaletteMapping::createProgram().get());
    ss->addUniform(new osg::Uniform("loa_baseTexture", 0));
    ss->addUniform(new osg::Uniform("loa_palette_lit", false));
    ss->addUniform(new osg::Uniform("loa_palette_strategy", strategy));
}

struct Region
{
    unsigned pixels = 0, mismatches = 0, distinct = 0;
    int worst = 0; // largest channel difference in 1/255
};

/** Compares pixels x in [x0, x0 + T) with map(palette, level, texel(x - x0, y)); level 0: the
 *  texel itself (no palette). */
Region compare(const osg::Image& img, int x0, const osg::Image& texture, const osg::Image& palette,
               unsigned level)
{
    Region r;
    std::set<unsigned> colours;
    for (int y = 0; y < T; ++y)
        for (int x = 0; x < T; ++x)
        {
            const unsigned char* t = texture.data(x, y);
            const osg::Vec3f texel = osg::Vec3f(t[0], t[1], t[2]) / 255.0f;
            const osg::Vec3f expected = (level ? PaletteLookup::map(palette, level, texel) : texel) * 255.0f;
            const unsigned char* p = img.data(x0 + x, y);
            colours.insert(p[0] << 16 | p[1] << 8 | p[2]);
            int diff = 0;
            for (int c = 0; c < 3; ++c)
                diff = std::max(diff, int(std::lround(std::fabs(p[c] - expected[c]))));
            ++r.pixels;
            if (diff > 1) ++r.mismatches;
            r.worst = std::max(r.worst, diff);
        }
    r.distinct = unsigned(colours.size());
    return r;
}

/** At most 0.5 % of the pixels may differ by more than 1/255: texels whose Lab distances to
 *  two palette colours are equal within float rounding (GPU pow/cbrt differ from libm in the
 *  last bits) can pick the other colour. 1/255 covers the Lab -> sRGB round trip of the winner
 *  on the GPU against the 8-bit colour the CPU returns. */
void expectMatches(const Region& r, const std::string& what)
{
    std::cout << what << ": " << r.mismatches << " of " << r.pixels << " pixels over 1/255 (worst " << r.worst
              << "/255), " << r.distinct << " distinct colours" << std::endl;
    EXPECT_LE(r.mismatches, r.pixels / 200) << what;
}

float smoothstep(float e0, float e1, float x)
{
    const float t = std::min(std::max((x - e0) / (e1 - e0), 0.0f), 1.0f);
    return t * t * (3.0f - 2.0f * t);
}
} // namespace

TEST(PaletteLookupGLTest, StaticLevelsOnTheGpuEqualTheCpuLookup)
{
    loatest::setFilePath(std::getenv("OSG_FILE_PATH") ? std::getenv("OSG_FILE_PATH") : "");
    osg::ref_ptr<osg::Texture2D> tex = noiseTexture();
    osg::ref_ptr<osg::Geode> root = new osg::Geode;
    osg::ref_ptr<osg::Geometry> g = quad(-T / 2.0f, -T / 2.0f, 10.0f, osg::Vec3(0, 0, 1), tex.get());
    root->addDrawable(g.get());
    ASSERT_EQ(PaletteMapping::attach(*root), 1u);
    TexturePalette* palette = PaletteMapping::paletteOf(*g->getStateSet());
    ASSERT_TRUE(palette);
    const unsigned K = palette->getLevels();
    EXPECT_EQ(K, 64u);
    useProgram(*root, 0);
    osg::ref_ptr<osg::Uniform> level = new osg::Uniform("loa_palette_level", 1);
    level->setDataVariance(osg::Object::DYNAMIC);
    root->getStateSet()->addUniform(level.get());
    Renderer r(T);
    r.r->setSceneData(root.get());
    for (unsigned l : {1u, 2u, 4u, 8u, K})
    {
        level->set(int(l));
        osg::ref_ptr<osg::Image> img = r.r->renderImage();
        const Region reg = compare(*img, 0, *tex->getImage(), *palette->getPaletteImage(), l);
        expectMatches(reg, "static level " + std::to_string(l));
        EXPECT_LE(reg.distinct, l);
    }
    // Out of range: clamped to [1, K].
    level->set(0);
    EXPECT_EQ(compare(*r.r->renderImage(), 0, *tex->getImage(), *palette->getPaletteImage(), 1).mismatches,
              0u);
    level->set(1000);
    EXPECT_LE(compare(*r.r->renderImage(), 0, *tex->getImage(), *palette->getPaletteImage(), K).mismatches,
              unsigned(T * T / 200));
    // Without a palette: the texture itself.
    g->getStateSet()->addUniform(new osg::Uniform("loa_hasPalette", false));
    level->set(2);
    const Region plain = compare(*r.r->renderImage(), 0, *tex->getImage(), *palette->getPaletteImage(), 0);
    EXPECT_EQ(plain.mismatches, 0u);
    EXPECT_EQ(plain.distinct, 64u);
}

namespace
{
/** Two quads side by side (left: pixels x < T, right: x >= T), the palette attached, the
 *  standalone program with `strategy`; setup edits the quads' StateSets; returns the image and
 *  the texture / palette. */
struct TwoQuads
{
    osg::ref_ptr<osg::Texture2D> tex = noiseTexture();
    osg::ref_ptr<osg::Geode> root = new osg::Geode;
    osg::ref_ptr<osg::Geometry> left, right;
    TexturePalette* palette = nullptr;
    TwoQuads(float zLeft, float zRight, const osg::Vec3& nLeft, const osg::Vec3& nRight, int strategy)
    {
        left = quad(-float(T), -T / 2.0f, zLeft, nLeft, tex.get());
        right = quad(0.0f, -T / 2.0f, zRight, nRight, tex.get());
        root->addDrawable(left.get());
        root->addDrawable(right.get());
        PaletteMapping::attach(*root);
        palette = PaletteMapping::paletteOf(*left->getStateSet());
        useProgram(*root, strategy);
    }
    osg::ref_ptr<osg::Image> render()
    {
        Renderer r(2 * T);
        r.r->setSceneData(root.get());
        return r.r->renderImage();
    }
    Region region(const osg::Image& img, bool isLeft, unsigned level)
    {
        return compare(img, isLeft ? 0 : T, *tex->getImage(), *palette->getPaletteImage(), level);
    }
};
} // namespace

TEST(PaletteLookupGLTest, DepthStrategy)
{
    loatest::setFilePath(std::getenv("OSG_FILE_PATH") ? std::getenv("OSG_FILE_PATH") : "");
    TwoQuads q(60.0f, 390.0f, osg::Vec3(0, 0, 1), osg::Vec3(0, 0, 1), 1);
    ASSERT_TRUE(q.palette);
    osg::StateSet* ss = q.root->getStateSet();
    ss->addUniform(new osg::Uniform("loa_palette_levelNear", 32));
    ss->addUniform(new osg::Uniform("loa_palette_levelFar", 4));
    ss->addUniform(new osg::Uniform("loa_palette_near", 50.0f));
    ss->addUniform(new osg::Uniform("loa_palette_far", 400.0f));
    // By hand: depth 60 -> smoothstep 0.0024 -> 31.93 -> 32; depth 390 -> 0.9976 -> 4.07 -> 4.
    const float nearLevel = 32.0f + (4.0f - 32.0f) * smoothstep(50, 400, 60);
    const float farLevel = 32.0f + (4.0f - 32.0f) * smoothstep(50, 400, 390);
    EXPECT_EQ(std::lround(nearLevel), 32);
    EXPECT_EQ(std::lround(farLevel), 4);
    osg::ref_ptr<osg::Image> img = q.render();
    const Region n = q.region(*img, true, 32), f = q.region(*img, false, 4);
    expectMatches(n, "depth 60 (level 32)");
    expectMatches(f, "depth 390 (level 4)");
    EXPECT_LE(n.distinct, 32u);
    EXPECT_GT(n.distinct, 4u);
    EXPECT_LE(f.distinct, 4u);
}

TEST(PaletteLookupGLTest, OrientationStrategy)
{
    loatest::setFilePath(std::getenv("OSG_FILE_PATH") ? std::getenv("OSG_FILE_PATH") : "");
    // Left faces the eye (|cos| >= 0.9994 at depth 1000 within 36 units of the axis); right is
    // turned 60 degrees about y (|cos| in [0.5, 0.53]).
    TwoQuads q(1000.0f, 1000.0f, osg::Vec3(0, 0, 1), osg::Vec3(0.8660254f, 0, 0.5f), 2);
    ASSERT_TRUE(q.palette);
    q.root->getStateSet()->addUniform(new osg::Uniform("loa_palette_levelLow", 4));
    q.root->getStateSet()->addUniform(new osg::Uniform("loa_palette_levelHigh", 12));
    // By hand: left 4 + 8 * 0.9994 = 11.995 -> 12; right 4 + 8 * [0.5, 0.53] in [8, 8.24] -> 8.
    osg::ref_ptr<osg::Image> img = q.render();
    const Region a = q.region(*img, true, 12), b = q.region(*img, false, 8);
    expectMatches(a, "frontal (level 12)");
    expectMatches(b, "60 degrees (level 8)");
    EXPECT_LE(a.distinct, 12u);
    EXPECT_LE(b.distinct, 8u);
    EXPECT_GT(a.distinct, 8u);
}

TEST(PaletteLookupGLTest, StaticPerObjectOverridesAndInterest)
{
    loatest::setFilePath(std::getenv("OSG_FILE_PATH") ? std::getenv("OSG_FILE_PATH") : "");
    {
        TwoQuads q(10.0f, 10.0f, osg::Vec3(0, 0, 1), osg::Vec3(0, 0, 1), 0);
        ASSERT_TRUE(q.palette);
        q.root->getStateSet()->addUniform(new osg::Uniform("loa_palette_level", 8));
        q.left->getStateSet()->addUniform(new osg::Uniform("loa_palette_level", 2)); // this object: 2
        osg::ref_ptr<osg::Image> img = q.render();
        const Region a = q.region(*img, true, 2), b = q.region(*img, false, 8);
        expectMatches(a, "static, object override (level 2)");
        expectMatches(b, "static, scene level (level 8)");
        EXPECT_LE(a.distinct, 2u);
        EXPECT_LE(b.distinct, 8u);
        EXPECT_GT(b.distinct, 2u);
    }
    {
        TwoQuads q(10.0f, 10.0f, osg::Vec3(0, 0, 1), osg::Vec3(0, 0, 1), 3);
        ASSERT_TRUE(q.palette);
        q.root->getStateSet()->addUniform(new osg::Uniform("loa_palette_levelLow", 4));
        q.root->getStateSet()->addUniform(new osg::Uniform("loa_palette_levelHigh", 32));
        q.left->getStateSet()->addUniform(new osg::Uniform("loa_featureInterest", 0.25f)); // 4 + 28/4 = 11
        q.right->getStateSet()->addUniform(new osg::Uniform("loa_featureInterest", 1.0f)); // 32
        osg::ref_ptr<osg::Image> img = q.render();
        const Region a = q.region(*img, true, 11), b = q.region(*img, false, 32);
        expectMatches(a, "interest 0.25 (level 11)");
        expectMatches(b, "interest 1 (level 32)");
        EXPECT_LE(a.distinct, 11u);
        EXPECT_LE(b.distinct, 32u);
    }
}

TEST(PaletteLookupGLTest, PaletteStyleLinksIntoThePipelinePrograms)
{
    loatest::setFilePath(std::getenv("OSG_FILE_PATH") ? std::getenv("OSG_FILE_PATH") : "");
    ASSERT_TRUE(GraphicStyleCatalog::instance().contains("palette"));
    osg::ref_ptr<GraphicStyle> style = GraphicStyleCatalog::instance().create("palette");
    osg::ref_ptr<HeadlessContext> context = new HeadlessContext;
    ASSERT_TRUE(context->realize());
    ASSERT_TRUE(context->makeCurrent());
    // As TransitionRenderer::program builds them: its vertex shaders, loa_transition.frag.glsl,
    // the alpha test, the style, the A-buffer writer for that pass, and loa_pass.frag.glsl with
    // the pass define.
    const std::vector<std::string> common = {"loa_style.vert.glsl", "loa_landmark.vert.glsl",
                                             "loa_transition.frag.glsl", "loa_material_alpha.frag.glsl"};
    for (const std::string define : {"LOA_PASS_GBUFFER_COLOR", "LOA_PASS_ABUFFER", "LOA_PASS_PINGPONG"})
    {
        osg::ref_ptr<osg::Program> p = style->createProgram(common);
        if (define == "LOA_PASS_ABUFFER")
            p->addShader(ShaderLibrary::createShader("loa_abuffer_write.frag.glsl").get());
        std::string text = ShaderLibrary::getSource("loa_pass.frag.glsl").text;
        text.insert(text.find('\n') + 1, "#define " + define + " 1\n");
        p->addShader(new osg::Shader(osg::Shader::FRAGMENT, text));
        const std::vector<ShaderDiagnostic> d = ShaderLibrary::check(*p, *context->getState());
        for (const ShaderDiagnostic& e : d)
            ADD_FAILURE() << define << ": " << e.message();
    }
    context->releaseContext();
    context->close();
}

namespace
{
// A test-only vertex shader and fragment main around the style's loa_styleColor (as
// GraphicStyleGLTest's harness).
const char* const kHarnessVertex = R"(#version 450 compatibility
uniform mat4 osg_ModelViewMatrix;
uniform mat4 osg_ModelViewProjectionMatrix;
uniform mat3 osg_NormalMatrix;
out vec3 test_viewPosition;
out vec3 test_viewNormal;
out vec2 test_texCoord;
out vec4 test_color;
void main()
{
    test_viewPosition = (osg_ModelViewMatrix * gl_Vertex).xyz;
    test_viewNormal = osg_NormalMatrix * gl_Normal;
    test_texCoord = gl_MultiTexCoord0.xy;
    test_color = gl_Color;
    gl_Position = osg_ModelViewProjectionMatrix * gl_Vertex;
}
)";
const char* const kHarnessFragment = R"(#version 450 compatibility
vec4 loa_styleColor(vec3 scenePosition, vec3 viewPosition, vec3 viewNormal, vec2 texCoord, vec4 color);
// Stands in for loa_transition.frag.glsl's scenario interest (the test uses the static strategy).
float loa_featureInterestOf(int j, vec3 p) { return 1.0; }
in vec3 test_viewPosition;
in vec3 test_viewNormal;
in vec2 test_texCoord;
in vec4 test_color;
layout(location = 0) out vec4 test_fragColor;
void main()
{
    test_fragColor = loa_styleColor(vec3(0.0), test_viewPosition, normalize(test_viewNormal), test_texCoord,
                                    test_color);
}
)";
} // namespace

TEST(PaletteLookupGLTest, PaletteStyleIsTheCpuLookupLitLikePhotorealistic)
{
    loatest::setFilePath(std::getenv("OSG_FILE_PATH") ? std::getenv("OSG_FILE_PATH") : "");
    osg::ref_ptr<GraphicStyle> style = GraphicStyleCatalog::instance().create("palette");
    style->getParameter("loa_palette_strategy")->set(0);
    style->getParameter("loa_palette_level")->set(4);
    osg::ref_ptr<osg::Texture2D> tex = noiseTexture();
    osg::ref_ptr<osg::Geode> root = new osg::Geode;
    const osg::Vec3 normal = osg::Vec3(0.6f, 0.0f, 0.8f); // light factor 0.35 + 0.65 * 0.823 = 0.885
    osg::ref_ptr<osg::Geometry> g = quad(-T / 2.0f, -T / 2.0f, 10.0f, normal, tex.get());
    root->addDrawable(g.get());
    ASSERT_EQ(PaletteMapping::attach(*root), 1u);
    const osg::Image& palette = *PaletteMapping::paletteOf(*g->getStateSet())->getPaletteImage();
    osg::ref_ptr<osg::Program> p = new osg::Program;
    p->addShader(new osg::Shader(osg::Shader::VERTEX, kHarnessVertex));
    p->addShader(new osg::Shader(osg::Shader::FRAGMENT, kHarnessFragment));
    p->addShader(ShaderLibrary::createShader(style->getFragmentShader()).get());
    osg::StateSet* ss = root->getOrCreateStateSet();
    ss->setAttributeAndModes(p.get());
    style->applyParameters(*ss);
    ss->addUniform(new osg::Uniform("loa_baseTexture", 0));
    ss->addUniform(new osg::Uniform("loa_hasTexture", true));
    const float light = GraphicStyle::lightFactor(normal, 0.35f);
    for (const bool withPalette : {true, false})
    {
        if (!withPalette) g->getStateSet()->addUniform(new osg::Uniform("loa_hasPalette", false));
        Renderer r(T);
        r.r->setSceneData(root.get());
        osg::ref_ptr<osg::Image> img = r.r->renderImage();
        unsigned over = 0;
        int worst = 0;
        for (int y = 0; y < T; ++y)
            for (int x = 0; x < T; ++x)
            {
                const unsigned char* t = tex->getImage()->data(x, y);
                const osg::Vec3f texel = osg::Vec3f(t[0], t[1], t[2]) / 255.0f;
                const osg::Vec3f expected =
                    (withPalette ? PaletteLookup::map(palette, 4, texel) : texel) * light * 255.0f;
                int diff = 0;
                for (int c = 0; c < 3; ++c)
                    diff = std::max(diff, int(std::lround(std::fabs(img->data(x, y)[c] - expected[c]))));
                worst = std::max(worst, diff);
                if (diff > 1) ++over;
            }
        std::cout << (withPalette ? "style, level 4, lit" : "style without palette, lit") << ": " << over
                  << " of " << T * T << " pixels over 1/255 (worst " << worst << "/255)" << std::endl;
        EXPECT_LE(over, unsigned(T * T / 200));
    }
}
