// The abstract graphic style with per-level filtered textures (FilterConfiguration, paper 000
// §4.4): where apply() bound a filtered diffuse texture, loa_style_abstract.frag.glsl shows it
// (not the colour-quantized original); where a feature type's filter is none, the style falls back
// to the quantization. Checked with the style's shader in a test harness (as GraphicStyleGLTest)
// and through the LoA node's TransitionRenderer.
#include "support/TestSupport.h"

#include <osgLoA/filtering/FilterConfiguration>
#include <osgLoA/filtering/GaussianFilter>
#include <osgLoA/filtering/MipmapFilter>
#include <osgLoA/interest/SaliencyMetric>
#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/render/ShaderLibrary>
#include <osgLoA/semantics/Feature>
#include <osgLoA/styles/ColorQuantization>
#include <osgLoA/styles/GraphicStyle>
#include <osgLoA/transitions/BlendFunction>
#include <osgLoA/styles/StylePreparation>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/TransitionConfiguration>
#include <osgLoA/transitions/UsageScenario>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Texture2D>

#include <gtest/gtest.h>

#include <cmath>

using namespace osgLoA;

namespace
{
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
in vec3 test_viewPosition;
in vec3 test_viewNormal;
in vec2 test_texCoord;
in vec4 test_color;
layout(location = 0) out vec4 test_fragColor;
void main()
{
    test_fragColor = loa_styleColor(vec3(0.0), test_viewPosition, normalize(test_viewNormal), test_texCoord, test_color);
}
)";

/** Texels over hues, lightness and saturation (those of GraphicStyleGLTest). */
const std::vector<osg::Vec4ub> kTexels = {
    {200, 40, 30, 255},   {30, 160, 60, 255},  {40, 70, 210, 255},   {230, 220, 80, 255},
    {128, 128, 128, 255}, {20, 20, 24, 255},   {250, 250, 245, 255}, {150, 90, 60, 255},
    {90, 150, 170, 255},  {170, 60, 140, 255}, {60, 40, 90, 255},    {210, 150, 120, 255},
    {100, 120, 40, 255},  {240, 120, 20, 255}, {70, 90, 110, 255},   {180, 200, 230, 255}};

/** The 4x4 texture of kTexels, nearest filtering (each texel covers 8x8 pixels of a quad). */
osg::ref_ptr<osg::Texture2D> texture()
{
    osg::ref_ptr<osg::Image> image = new osg::Image;
    image->allocateImage(4, 4, 1, GL_RGBA, GL_UNSIGNED_BYTE);
    for (int i = 0; i < 16; ++i)
        for (int c = 0; c < 4; ++c)
            image->data(i % 4, i / 4)[c] = kTexels[std::size_t(i)][c];
    osg::ref_ptr<osg::Texture2D> t = new osg::Texture2D(image.get());
    t->setFilter(osg::Texture::MIN_FILTER, osg::Texture::NEAREST);
    t->setFilter(osg::Texture::MAG_FILTER, osg::Texture::NEAREST);
    t->setWrap(osg::Texture::WRAP_S, osg::Texture::REPEAT);
    t->setWrap(osg::Texture::WRAP_T, osg::Texture::REPEAT);
    t->setResizeNonPowerOfTwoHint(false);
    return t;
}

/** A quad [x0, x0 + 1] x [-1, 1] facing the camera, textured with t, as a feature of `type`. */
osg::ref_ptr<osg::Geode> quadFeature(float x0, FeatureType type, unsigned id, osg::Texture2D* t)
{
    osg::ref_ptr<osg::Geometry> g =
        osg::createTexturedQuadGeometry(osg::Vec3(x0, -1, 0), osg::Vec3(1, 0, 0), osg::Vec3(0, 2, 0));
    osg::ref_ptr<osg::Vec4Array> c = new osg::Vec4Array;
    c->push_back(osg::Vec4(1, 1, 1, 1));
    g->setColorArray(c.get(), osg::Array::BIND_OVERALL);
    osg::ref_ptr<osg::Vec3Array> n = new osg::Vec3Array;
    n->push_back(osg::Vec3(0, 0, 1));
    g->setNormalArray(n.get(), osg::Array::BIND_OVERALL);
    g->getOrCreateStateSet()->setTextureAttributeAndModes(0, t);
    g->getOrCreateStateSet()->addUniform(new osg::Uniform("loa_hasTexture", true));
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(g.get());
    Feature::attach(*geode, new Feature(id, type));
    return geode;
}

osg::Vec3f pixel(const osg::Image& img, int x, int y)
{
    const unsigned char* p = img.data(x, y);
    return osg::Vec3f(p[0], p[1], p[2]) / 255.0f;
}

float maxDiff(const osg::Vec3f& a, const osg::Vec3f& b)
{
    return std::max({std::fabs(a.x() - b.x()), std::fabs(a.y() - b.y()), std::fabs(a.z() - b.z())});
}
} // namespace

TEST(FilterConfigurationGLTest, TheAbstractStyleShowsTheFilteredTextureAndTheRestAsItIs)
{
    // Left: a building whose diffuse filter (a Gaussian of sigma 8, repeat-wrapped, on a 4x4
    // texture) makes every texel the texture's mean; right: water, whose filter is none.
    osg::ref_ptr<osg::Texture2D> t = texture();
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(quadFeature(-1.0f, FeatureType::Building, 1, t.get()));
    root->addChild(quadFeature(0.0f, FeatureType::Water, 2, t.get()));
    osg::ref_ptr<FilterConfiguration> config = FilterConfiguration::createDefault();
    osg::ref_ptr<GaussianFilter> blur = new GaussianFilter;
    blur->setSigma(8.0f);
    config->getChannel("diffuse")->setDefaultFilter(blur.get());
    config->getChannel("diffuse")->setTypeFilter(FeatureType::Water, nullptr);
    const FilterConfiguration::Report report = config->apply(*root);
    ASSERT_EQ(report.stateSets, 1u);
    ASSERT_EQ(report.unfiltered, 1u);

    osg::ref_ptr<GraphicStyle> style = GraphicStyle::createBuiltin("abstract");
    style->getParameter("loa_abstract_modelLighting")->set(false);
    style->getParameter("loa_abstract_ambient")->set(1.0f); // unlit: the colour itself
    int levels = 0;
    style->getParameter("loa_abstract_levels")->get(levels);
    float step = 0.0f;
    style->getParameter("loa_abstract_chromaStep")->get(step);
    osg::ref_ptr<osg::Program> program = new osg::Program;
    program->addShader(new osg::Shader(osg::Shader::VERTEX, kHarnessVertex));
    program->addShader(new osg::Shader(osg::Shader::FRAGMENT, kHarnessFragment));
    program->addShader(ShaderLibrary::createShader("loa_fixed_function.frag.glsl").get());
    program->addShader(ShaderLibrary::createShader(style->getFragmentShader()).get());
    osg::StateSet* ss = root->getOrCreateStateSet();
    ss->setAttributeAndModes(program.get());
    style->applyParameters(*ss);
    ss->addUniform(new osg::Uniform("loa_baseTexture", 0));

    OffscreenRenderer::Settings s;
    s.width = 64;
    s.height = 32;
    s.clearColor = osg::Vec4(0, 0, 0, 0);
    osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(s);
    r->getCamera()->setProjectionMatrixAsOrtho2D(-1, 1, -1, 1);
    r->getCamera()->setViewMatrix(osg::Matrix::identity());
    r->setSceneData(root.get());
    osg::ref_ptr<osg::Image> img = r->renderImage();

    // The filtered texture: all texels the mean (within rounding).
    const osg::Texture2D* filtered = dynamic_cast<const osg::Texture2D*>(
        root->getChild(0)->asGeode()->getDrawable(0)->getStateSet()->getTextureAttribute(
            3, osg::StateAttribute::TEXTURE));
    ASSERT_TRUE(filtered);
    const FilterImage level0 = MipmapFilter::levelsOf(*filtered->getImage()).front();
    osg::Vec3f mean;
    for (const osg::Vec4ub& texel : kTexels)
        mean += osg::Vec3f(texel[0], texel[1], texel[2]) / (255.0f * 16.0f);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
        {
            const osg::Vec4f v = level0.get(x, y);
            ASSERT_LT(maxDiff(osg::Vec3f(v[0], v[1], v[2]), mean), 2.0f / 255.0f);
        }
    int differFromQuantized = 0;
    for (int i = 0; i < 16; ++i)
    {
        const int px = (i % 4) * 8 + 4, py = (i / 4) * 8 + 4;
        const osg::Vec3f texel(kTexels[std::size_t(i)][0] / 255.0f, kTexels[std::size_t(i)][1] / 255.0f,
                               kTexels[std::size_t(i)][2] / 255.0f);
        const osg::Vec3f quantized = ColorQuantization::quantize(texel, levels, step);
        // Left (building): the filtered texture, 2/255 (8-bit rounding of the texture and of
        // the output).
        const osg::Vec3f left = pixel(*img, px, py);
        EXPECT_LT(maxDiff(left, mean), 2.5f / 255.0f) << "building, texel " << i;
        if (maxDiff(left, quantized) > 10.0f / 255.0f) ++differFromQuantized;
        // Right (water, no filter): the texture as it is, not quantized per texel (the fallback
        // samples 2 mip levels coarser, which under this magnification is level 0).
        const osg::Vec3f right = pixel(*img, 32 + px, py);
        EXPECT_LT(maxDiff(right, texel), 2.5f / 255.0f) << "water, texel " << i;
    }
    // The output follows the filtered texture, not the quantized original.
    EXPECT_GE(differFromQuantized, 14);
}

TEST(FilterConfigurationGLTest, TheLoANodeDrawsFilteredTexturesInTheAbstractStyle)
{
    // A textured ground feature drawn in the abstract style by the LoA node: with the user's own
    // filter configuration (a Gaussian that flattens the texture) the ground is one colour and
    // the node keeps that configuration; without one, the node prepares the style itself
    // (StylePreparation: TextureAbstraction's colour and outline pyramids, 2 textures).
    struct Frame
    {
        osg::ref_ptr<osg::Image> image;
        StylePreparation::Report report;
    };
    auto render = [](bool filter)
    {
        osg::ref_ptr<osg::Texture2D> t = texture();
        osg::ref_ptr<osg::Geode> ground = quadFeature(-1.0f, FeatureType::Green, 1, t.get());
        ground->getDrawable(0)->getStateSet()->removeUniform("loa_hasTexture"); // the renderer's job
        if (filter)
        {
            osg::ref_ptr<FilterConfiguration> config = FilterConfiguration::createDefault();
            osg::ref_ptr<GaussianFilter> blur = new GaussianFilter;
            blur->setSigma(8.0f);
            config->getChannel("diffuse")->setDefaultFilter(blur.get());
            config->apply(*ground);
        }
        osg::ref_ptr<UsageScenario> s = new UsageScenario;
        s->setName("abstract");
        osg::ref_ptr<TransitionConfiguration> c = new TransitionConfiguration;
        c->setName("abstract");
        c->setStyle("abstract");
        c->setFeatureTypes({FeatureType::Green});
        c->setBlendFunction(BlendFunction(0.0f, 0.0f, 1.0f, 1.0f));
        c->addMetric(new SaliencyMetric(SaliencyMetric::FEATURE_INTEREST, 0, 0));
        s->addConfiguration(c.get());
        osg::ref_ptr<LoANode> loa = new LoANode;
        StylePreparation::Options o;
        o.cacheDir = "-";
        o.progress = [](const std::string&) {};
        loa->setStylePreparationOptions(o);
        loa->setScenario(s.get());
        loa->addChild(ground.get());
        OffscreenRenderer::Settings rs;
        rs.width = 32;
        rs.height = 32;
        osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(rs);
        r->setSceneData(loa.get());
        r->setViewMatrixAsLookAt(osg::Vec3d(-0.5, 0, 3), osg::Vec3d(-0.5, 0, 0), osg::Vec3d(0, 1, 0));
        r->setPerspective(30.0);
        Frame f;
        f.image = r->renderImage();
        f.report = loa->getStylePreparationReport();
        return f;
    };
    // The spread of the colours over the centre of the quad (away from its edges).
    auto spread = [](const osg::Image& img)
    {
        float lo = 3.0f, hi = 0.0f;
        for (int y = 10; y < 22; ++y)
            for (int x = 12; x < 20; ++x)
            {
                const osg::Vec3f p = pixel(img, x, y);
                lo = std::min(lo, p.x() + p.y() + p.z());
                hi = std::max(hi, p.x() + p.y() + p.z());
            }
        return hi - lo;
    };
    const Frame filtered = render(true), automatic = render(false);
    EXPECT_LT(spread(*filtered.image), 6.0f / 255.0f);
    EXPECT_TRUE(filtered.report.styles.empty()); // the user's configuration is kept
    ASSERT_EQ(automatic.report.styles, std::vector<std::string>{"abstract"});
    EXPECT_EQ(automatic.report.abstractTextures, 2u);
    EXPECT_EQ(automatic.report.skipped, 0u);
}
