// The LoA node's rendering (TransitionRenderer, docs/rendering.md): Algorithm 1's draws per
// configuration and feature, zero-weight culling, the blend of two styles at one surface, and
// golden images of the demo city under the library's scenarios and of every cartographic style.
#include "support/TestSupport.h"
#include "support/TopDownView.h"

#include <osgLoA/city/CityCameras>
#include <osgLoA/city/CityGenerator>
#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/semantics/Feature>
#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/styles/GraphicStyle>
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/ScenarioLibrary>
#include <osgLoA/util/ImageCompare>

#include <osg/ComputeBoundsVisitor>
#include <osg/Geode>
#include <osg/Geometry>
#include <osg/ShapeDrawable>
#include <osg/Texture2D>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

using namespace osgLoA;
typedef SaliencyMetric M;

namespace
{
osg::ref_ptr<osg::Node> boxFeature(unsigned id, FeatureType type, const osg::Vec3& centre, float size)
{
    osg::ref_ptr<osg::Geode> g = new osg::Geode;
    osg::ref_ptr<osg::ShapeDrawable> d = new osg::ShapeDrawable(new osg::Box(centre, size));
    d->setColor(osg::Vec4(0.8f, 0.8f, 0.8f, 1.0f));
    g->addDrawable(d.get());
    Feature::attach(*g, new Feature(id, type));
    return g;
}

// A flat ground quad feature of side 2 s at z = 0, normal up.
osg::ref_ptr<osg::Node> groundFeature(unsigned id, FeatureType type, float s, float interest)
{
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    for (const osg::Vec3& p :
         {osg::Vec3(-s, -s, 0), osg::Vec3(s, -s, 0), osg::Vec3(s, s, 0), osg::Vec3(-s, s, 0)})
        v->push_back(p);
    g->setVertexArray(v.get());
    osg::ref_ptr<osg::Vec3Array> n = new osg::Vec3Array(osg::Array::BIND_OVERALL);
    n->push_back(osg::Vec3(0, 0, 1));
    g->setNormalArray(n.get());
    osg::ref_ptr<osg::Vec4Array> c = new osg::Vec4Array(osg::Array::BIND_OVERALL);
    c->push_back(osg::Vec4(1, 1, 1, 1));
    g->setColorArray(c.get());
    g->addPrimitiveSet(new osg::DrawArrays(GL_QUADS, 0, 4));
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(g.get());
    osg::ref_ptr<Feature> f = new Feature(id, type);
    f->setInterest(interest);
    Feature::attach(*geode, f.get());
    return geode;
}

osg::ref_ptr<TransitionConfiguration> config(const std::string& style, const BlendFunction& blend,
                                             const TransitionConfiguration::FeatureTypes& types, M* metric)
{
    osg::ref_ptr<TransitionConfiguration> c = new TransitionConfiguration;
    c->setName(style);
    c->setStyle(style);
    c->setFeatureTypes(types);
    c->setInterpolation(TransitionConfiguration::OBJECT);
    c->setBlendFunction(blend);
    c->addMetric(metric);
    return c;
}

osg::ref_ptr<OffscreenRenderer> renderer(int w, int h, osg::Node* scene, const osg::Vec3d& eye,
                                         const osg::Vec3d& centre)
{
    OffscreenRenderer::Settings s;
    s.width = w;
    s.height = h;
    s.clearColor = osg::Vec4(0, 0, 0, 1);
    osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(s);
    r->setSceneData(scene);
    r->setPerspective(40.0);
    r->setViewMatrixAsLookAt(eye, centre, osg::Vec3d(0, 0, 1));
    return r;
}

/** 64x64 over black, straight down on the ground plane z = 0, x and y in -12..12. */
osg::ref_ptr<osg::Image> renderFromAbove(osg::Node* scene)
{
    OffscreenRenderer::Settings s;
    s.width = 64;
    s.height = 64;
    s.clearColor = osg::Vec4(0, 0, 0, 1);
    osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(s);
    r->setSceneData(scene);
    r->getCamera()->setProjectionMatrixAsOrtho(-12, 12, -12, 12, 1, 100);
    r->getCamera()->setViewMatrixAsLookAt(osg::Vec3d(0, 0, 50), osg::Vec3d(0, 0, 0), osg::Vec3d(0, 1, 0));
    return r->renderImage();
}

unsigned count(const std::vector<TransitionRenderer::Draw>& draws, unsigned id,
               TransitionRenderer::Draw::Kind kind, int configuration)
{
    return unsigned(std::count_if(draws.begin(), draws.end(),
                                  [&](const TransitionRenderer::Draw& d) {
                                      return d.featureId == id && d.kind == kind &&
                                             d.configuration == configuration;
                                  }));
}
} // namespace

// Algorithm 1: three buildings at 50 m, 300 m and 550 m from the eye along the view; near
// photorealistic (interest >= 0.6), far cartographic (interest <= 0.4), a smooth transition in
// between; water matches no configuration; one building is outside the view frustum. The
// building in transition is drawn fused (both styles opaque, an opaque material): one draw in
// the G-buffer pass; with fusing off, through the A-buffer.
TEST(TransitionRendererGLTest, Algorithm1DrawsMatchingFeaturesAndCullsZeroWeights)
{
    osg::ref_ptr<UsageScenario> s = new UsageScenario;
    s->setName("test");
    const TransitionConfiguration::FeatureTypes buildings = {FeatureType::Building};
    // Interest: 1 at <= 0 m, 0 at >= 600 m: 50 m -> 0.917, 300 m -> 0.5, 550 m -> 0.083.
    s->addConfiguration(config("photorealistic", BlendFunction(0.4f, 0.6f, 1.0f, 1.0f), buildings,
                               new M(M::VIEW_DISTANCE, 0.0, 600.0)));
    s->addConfiguration(config("cartographic", BlendFunction(0.0f, 0.0f, 0.4f, 0.6f), buildings,
                               new M(M::VIEW_DISTANCE, 0.0, 600.0)));
    osg::ref_ptr<LoANode> loa = new LoANode;
    loa->setScenario(s.get());
    loa->addChild(boxFeature(1, FeatureType::Building, osg::Vec3(0, 50, 0), 10));
    loa->addChild(boxFeature(2, FeatureType::Building, osg::Vec3(0, 300, 0), 10));
    loa->addChild(boxFeature(3, FeatureType::Building, osg::Vec3(0, 550, 0), 10));
    loa->addChild(boxFeature(4, FeatureType::Water, osg::Vec3(10, 200, 0), 10));
    loa->addChild(boxFeature(5, FeatureType::Building, osg::Vec3(0, -300, 0), 10)); // behind the eye
    loa->getRenderer()->setRecordDraws(true);
    auto r = renderer(64, 48, loa.get(), osg::Vec3d(0, 0, 0), osg::Vec3d(0, 1, 0));
    r->renderImage();
    const auto& draws = loa->getRenderer()->getDraws();
    typedef TransitionRenderer::Draw D;
    {
        EXPECT_EQ(count(draws, 1, D::SHARED, 0), 1u);
        EXPECT_EQ(count(draws, 3, D::SHARED, 1), 1u);
        ASSERT_EQ(count(draws, 2, D::FUSED, -1), 1u);
        for (const D& d : draws)
        {
            if (d.kind == D::FUSED)
            {
                EXPECT_EQ(d.configurations, 3u); // configurations 0 and 1
            }
        }
        EXPECT_EQ(draws.size(), 3u);
        const TransitionRenderer::Statistics& st = loa->getRenderer()->getStatistics();
        EXPECT_EQ(st.drawnFeatures, 3u);
        EXPECT_EQ(st.sharedDraws, 2u);
        EXPECT_EQ(st.fusedDraws, 1u);
        EXPECT_EQ(st.fusedPrograms, 1u);
        EXPECT_EQ(st.depthOnlyDraws, 0u);
        EXPECT_EQ(st.aBufferDraws, 0u);
        EXPECT_FALSE(st.aBuffer);
    }
    TransitionRenderer::Settings rs = loa->getRenderer()->getSettings();
    rs.fuseStyles = false;
    loa->getRenderer()->setSettings(rs);
    r->renderImage();
    // Near and far: one draw each, in the G-buffer pass, in their one style.
    EXPECT_EQ(count(draws, 1, D::SHARED, 0), 1u);
    EXPECT_EQ(count(draws, 3, D::SHARED, 1), 1u);
    // In the transition: depth-only front surface plus one A-buffer draw per configuration.
    EXPECT_EQ(count(draws, 2, D::DEPTH_ONLY, -1), 1u);
    EXPECT_EQ(count(draws, 2, D::A_BUFFER, 0), 1u);
    EXPECT_EQ(count(draws, 2, D::A_BUFFER, 1), 1u);
    // Nothing else: the water matches no configuration, building 5 is not visible.
    EXPECT_EQ(draws.size(), 5u);
    const TransitionRenderer::Statistics& st = loa->getRenderer()->getStatistics();
    EXPECT_EQ(st.drawnFeatures, 3u);
    EXPECT_EQ(st.sharedDraws, 2u);
    EXPECT_EQ(st.aBufferDraws, 2u);
    EXPECT_TRUE(st.aBuffer);
    EXPECT_FALSE(st.pingPongBuffer);

    // Move the eye so that every building is outside the transition: no A-buffer at all.
    r->setViewMatrixAsLookAt(osg::Vec3d(0, 140, 0), osg::Vec3d(0, 1000, 0), osg::Vec3d(0, 0, 1));
    r->renderImage();
    EXPECT_FALSE(loa->getRenderer()->getStatistics().aBuffer);
    EXPECT_EQ(loa->getRenderer()->getStatistics().aBufferDraws, 0u);
}

// Fusing draws a feature in transition once only where one program can blend its styles; else
// the A-buffer, as before (docs/rendering.md): a building at 300 m between two configurations
// (weights 1 - smoothstep and smoothstep of the interest 0.5 around 0.4..0.6: 0.5 each).
TEST(TransitionRendererGLTest, FusingFallsBackToTheABufferWhereOneProgramCannotBlend)
{
    GraphicStyleCatalog& catalog = GraphicStyleCatalog::instance();
    osg::ref_ptr<GraphicStyle> dark = catalog.create("cartographic");
    dark->setName("test-cartographic-dark");
    dark->getParameters()->getUniform("loa_cartographic_ambient")->set(0.2f);
    catalog.add(*dark);
    osg::ref_ptr<GraphicStyle> same = catalog.create("cartographic");
    same->setName("test-cartographic-same");
    catalog.add(*same);
    struct Case
    {
        std::vector<const char*> styles;
        bool fused;
    };
    const Case cases[] = {
        {{"photorealistic", "cartographic"}, true},
        {{"cartographic", "test-cartographic-same"}, true},  // one shader, the same parameters
        {{"cartographic", "test-cartographic-dark"}, false}, // one uniform, two values
        {{"cartographic", "hidden"}, false},                 // fading to nothing: translucent
        {{"blueprint", "cartographic", "photorealistic", "test-cartographic-same"}, true},
        {{"blueprint", "cartographic", "photorealistic", "test-cartographic-same", "abstract"}, false}, // > 4
    };
    const TransitionConfiguration::FeatureTypes buildings = {FeatureType::Building};
    for (const Case& c : cases)
    {
        std::string label;
        for (const char* st : c.styles)
            label += std::string(label.empty() ? "" : "+") + st;
        osg::ref_ptr<UsageScenario> s = new UsageScenario;
        s->setName("fusing");
        // Every configuration fades in over 0.4..0.6 of interest and none fades out: all have
        // the same weight at 0.5 (normalized: 1 / n each).
        for (const char* st : c.styles)
            s->addConfiguration(config(st, BlendFunction(0.4f, 0.6f, 1.0f, 1.0f), buildings,
                                       new M(M::VIEW_DISTANCE, 0.0, 600.0)));
        osg::ref_ptr<LoANode> loa = new LoANode;
        loa->setScenario(s.get());
        loa->addChild(boxFeature(2, FeatureType::Building, osg::Vec3(0, 300, 0), 10));
        auto r = renderer(64, 48, loa.get(), osg::Vec3d(0, 0, 0), osg::Vec3d(0, 1, 0));
        r->renderImage();
        const TransitionRenderer::Statistics& st = loa->getRenderer()->getStatistics();
        unsigned visible = 0;
        for (const char* name : c.styles)
            visible += std::string(name) == "hidden" ? 0u : 1u;
        EXPECT_EQ(st.fusedDraws, c.fused ? 1u : 0u) << label;
        EXPECT_EQ(st.aBufferDraws, c.fused ? 0u : visible) << label;
        EXPECT_EQ(st.aBuffer, !c.fused) << label;
    }
}

// The fused blend of two styles is their weighted sum: a box of feature interest 0.5 between
// two configurations of weights smoothstep(0, 1, 0.5) = 0.5 and 1 - 0.5, against the mean of the
// two frames that draw it in one style each (computed here; edges and unsharp masking off, since
// the compositor's edge blend is not linear in the weights). Fused and single-style draws share
// the G-buffer pass and its coverage, so the bar is 2/255 per channel on every pixel. Then the
// same frame through the A-buffer (fusing off, one sample per pixel): 2/255 inside the faces, a
// mean of 1/255 over the whole frame. At edges and silhouettes the two differ by design: the
// A-buffer keeps fragments of faces just behind the front one (front-surface tolerance
// 2 fwidth(z)) and merges them, and covers some silhouette pixels the G-buffer leaves empty
// (its approximation there, docs/abuffer.md); the fused draw is the single-style draw's coverage.
// Pairs: two different styles, and two configurations of one style (one evaluation of it: the
// style's own image).
TEST(TransitionRendererGLTest, FusedStylesEqualTheWeightedSumOfTheStyles)
{
    auto box = []()
    {
        osg::ref_ptr<osg::Node> node = boxFeature(2, FeatureType::Building, osg::Vec3(0, 60, 0), 20);
        Feature::get(*node)->setInterest(0.5f);
        return node;
    };
    auto frame = [&](const std::vector<std::pair<std::string, BlendFunction>>& configs, bool fuse,
                     TransitionRenderer::Statistics* stats)
    {
        osg::ref_ptr<UsageScenario> s = new UsageScenario;
        s->setName("fused");
        const TransitionConfiguration::FeatureTypes buildings = {FeatureType::Building};
        for (const auto& c : configs)
            s->addConfiguration(config(c.first, c.second, buildings, new M(M::FEATURE_INTEREST, 0, 0)));
        osg::ref_ptr<LoANode> loa = new LoANode;
        loa->setScenario(s.get());
        loa->addChild(box().get());
        TransitionRenderer::Settings rs = loa->getRenderer()->getSettings();
        rs.fuseStyles = fuse;
        rs.edges = false;
        rs.unsharpMasking = false;
        // The A-buffer with one sample per pixel: coverage at the pixel centre, as the G-buffer's
        // (4 samples on llvmpipe anti-alias the silhouettes against the background).
        rs.samples = 1;
        rs.maxPasses = 8;
        loa->getRenderer()->setSettings(rs);
        auto r = renderer(96, 64, loa.get(), osg::Vec3d(-20, 5, 25), osg::Vec3d(0, 60, 0));
        osg::ref_ptr<osg::Image> img = r->renderImage();
        if (stats) *stats = loa->getRenderer()->getStatistics();
        return img;
    };
    const BlendFunction always(0.0f, 0.0f, 1.0f, 1.0f), rising(0.0f, 1.0f, 1.0f, 1.0f),
        falling(0.0f, 0.0f, 0.0f, 1.0f);
    for (const std::pair<std::string, std::string>& styles :
         {std::make_pair(std::string("photorealistic"), std::string("cartographic")),
          std::make_pair(std::string("cartographic"), std::string("cartographic"))})
    {
        const std::string label = styles.first + "+" + styles.second;
        osg::ref_ptr<osg::Image> a = frame({{styles.first, always}}, true, nullptr);
        osg::ref_ptr<osg::Image> b = frame({{styles.second, always}}, true, nullptr);
        TransitionRenderer::Statistics fusedStats, aBufferStats;
        osg::ref_ptr<osg::Image> fused =
            frame({{styles.first, rising}, {styles.second, falling}}, true, &fusedStats);
        osg::ref_ptr<osg::Image> blended =
            frame({{styles.first, rising}, {styles.second, falling}}, false, &aBufferStats);
        EXPECT_EQ(fusedStats.fusedDraws, 1u) << label;
        EXPECT_EQ(fusedStats.aBufferDraws, 0u) << label;
        EXPECT_EQ(aBufferStats.fusedDraws, 0u) << label;
        EXPECT_EQ(aBufferStats.aBufferDraws, 2u) << label;
        int worst = 0, covered = 0;
        for (int y = 0; y < fused->t(); ++y)
            for (int x = 0; x < fused->s(); ++x)
            {
                const unsigned char* pa = a->data(x, y);
                covered += (pa[0] | pa[1] | pa[2]) != 0 ? 1 : 0;
                for (int c = 0; c < 3; ++c)
                {
                    const int expected = (int(a->data(x, y)[c]) + int(b->data(x, y)[c]) + 1) / 2;
                    worst = std::max(worst, std::abs(int(fused->data(x, y)[c]) - expected));
                }
            }
        EXPECT_GT(covered, 400) << "the box covers too little of the frame to compare";
        EXPECT_LE(worst, 2) << label;
        if (styles.first != styles.second)
        {
            EXPECT_NE(a->data(48, 32)[0], b->data(48, 32)[0]); // the two styles differ there
        }
        // Against the A-buffer: inside faces (pixels whose 3x3 neighbourhood is flat, within
        // 8/255, in both single-style frames) 2/255; over the whole frame a mean of 1/255.
        int inside = 0, worstInside = 0;
        for (int y = 1; y + 1 < fused->t(); ++y)
            for (int x = 1; x + 1 < fused->s(); ++x)
            {
                bool flat = (a->data(x, y)[0] | a->data(x, y)[1] | a->data(x, y)[2]) != 0;
                for (int j = -1; j <= 1 && flat; ++j)
                    for (int i = -1; i <= 1 && flat; ++i)
                        for (const osg::Image* img : {a.get(), b.get()})
                            for (int c = 0; c < 3; ++c)
                                flat = flat && std::abs(int(img->data(x + i, y + j)[c]) -
                                                        int(img->data(x, y)[c])) <= 8;
                if (!flat) continue;
                ++inside;
                for (int c = 0; c < 3; ++c)
                    worstInside = std::max(worstInside,
                                           std::abs(int(fused->data(x, y)[c]) - int(blended->data(x, y)[c])));
            }
        EXPECT_GT(inside, 300) << label;
        EXPECT_LE(worstInside, 2) << label << " against the A-buffer inside faces";
        const auto cmp = ImageComparison::compare(*fused, *blended, 16);
        EXPECT_LE(cmp.meanDifference, 1.0) << label << " against the A-buffer: " << cmp.summary();
        if (worst > 2 || worstInside > 2 || cmp.meanDifference > 1.0)
        {
            loatest::saveFailure("fused-" + label + "-fused", *fused, cmp.difference.get());
            loatest::saveFailure("fused-" + label + "-abuffer", *blended, nullptr);
        }
    }
}

// Two styles whose shaders define a helper of one name (with different bodies) are fused into one
// program: each style's functions are renamed for it, so the program links and each style keeps
// its own helper. Red and blue at weights 0.5 each blend to (0.5, 0, 0.5); edges and unsharp
// masking off, unlit colours.
TEST(TransitionRendererGLTest, FusedStylesMayDefineHelpersOfOneName)
{
    const std::string dir = loatest::freshDirectory("FusedHelpers");
    const char* body =
        "#version 450 compatibility\n"
        "vec3 loa_test_colour() { return vec3(%s); }\n"
        "vec4 loa_styleColor(vec3 scenePosition, vec3 viewPosition, vec3 viewNormal, vec2 texCoord,\n"
        "                    vec4 color)\n"
        "{\n    return vec4(loa_test_colour(), 1.0);\n}\n";
    for (const std::pair<const char*, const char*>& style :
         {std::make_pair("testred", "1.0, 0.0, 0.0"), std::make_pair("testblue", "0.0, 0.0, 1.0")})
    {
        char text[512];
        std::snprintf(text, sizeof(text), body, style.second);
        std::ofstream(dir + "/loa_style_" + style.first + ".frag.glsl") << text;
        osg::ref_ptr<GraphicStyle> g = new GraphicStyle;
        g->setName(style.first);
        g->setFragmentShader(std::string("loa_style_") + style.first + ".frag.glsl");
        g->setOpaque(true);
        g->setUsesTexture(false);
        GraphicStyleCatalog::instance().add(*g);
    }
    loatest::setFilePath(dir);
    osg::ref_ptr<UsageScenario> s = new UsageScenario;
    s->setName("helpers");
    const TransitionConfiguration::FeatureTypes types = {FeatureType::Green};
    s->addConfiguration(
        config("testred", BlendFunction(0.0f, 1.0f, 1.0f, 1.0f), types, new M(M::FEATURE_INTEREST, 0, 0)));
    s->addConfiguration(
        config("testblue", BlendFunction(0.0f, 0.0f, 0.0f, 1.0f), types, new M(M::FEATURE_INTEREST, 0, 0)));
    osg::ref_ptr<LoANode> loa = new LoANode;
    loa->setScenario(s.get());
    loa->addChild(groundFeature(1, FeatureType::Green, 100.0f, 0.5f));
    TransitionRenderer::Settings rs = loa->getRenderer()->getSettings();
    rs.edges = false;
    rs.unsharpMasking = false;
    loa->getRenderer()->setSettings(rs);
    osg::ref_ptr<osg::Image> img;
    try
    {
        img = renderer(48, 32, loa.get(), osg::Vec3d(0, -30, 40), osg::Vec3d(0, 0, 0))->renderImage();
    }
    catch (const std::exception& e)
    {
        loatest::setFilePath("");
        FAIL() << "the fused program did not link: " << e.what();
    }
    loatest::setFilePath("");
    EXPECT_EQ(loa->getRenderer()->getStatistics().fusedDraws, 1u);
    const unsigned char* p = img->data(24, 16);
    EXPECT_NEAR(p[0], 128, 2);
    EXPECT_NEAR(p[1], 0, 2);
    EXPECT_NEAR(p[2], 128, 2);
}

// A style that ignores the texture keeps the shape of alpha-blended cut-outs: a ground quad whose
// texture is transparent (alpha 0) on its left half and opaque on its right, blended (GL_BLEND),
// drawn in every built-in visible style. The left half shows the background (black) in every
// style, the right half the style's colour. (Before, cartographic and blueprint drew the whole
// quad: loa-bench's frame check found TORCS street-1's tree cards and skyline drawn as solid
// quads, 2.6 % more of the frame covered than plain rendering.)
TEST(TransitionRendererGLTest, StylesKeepTheShapeOfAlphaBlendedCutOuts)
{
    osg::ref_ptr<osg::Image> texture = new osg::Image;
    texture->allocateImage(16, 16, 1, GL_RGBA, GL_UNSIGNED_BYTE);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
        {
            unsigned char* p = texture->data(x, y);
            p[0] = 200, p[1] = 180, p[2] = 60, p[3] = x < 8 ? 0 : 255;
        }
    for (const char* style : {"photorealistic", "cartographic", "blueprint", "abstract"})
    {
        osg::ref_ptr<osg::Node> ground = groundFeature(1, FeatureType::Green, 10.0f, 0.5f);
        osg::ref_ptr<osg::Geometry> quad = ground->asGroup()->getChild(0)->asGeometry();
        ASSERT_TRUE(quad.valid());
        osg::ref_ptr<osg::Vec2Array> uv = new osg::Vec2Array;
        for (const osg::Vec2& t : {osg::Vec2(0, 0), osg::Vec2(1, 0), osg::Vec2(1, 1), osg::Vec2(0, 1)})
            uv->push_back(t);
        quad->setTexCoordArray(0, uv.get());
        osg::ref_ptr<osg::Texture2D> tex = new osg::Texture2D(texture.get());
        tex->setFilter(osg::Texture::MIN_FILTER, osg::Texture::NEAREST);
        tex->setFilter(osg::Texture::MAG_FILTER, osg::Texture::NEAREST);
        osg::StateSet* ss = quad->getOrCreateStateSet();
        ss->setTextureAttributeAndModes(0, tex.get());
        ss->setMode(GL_BLEND, osg::StateAttribute::ON);
        ss->setRenderingHint(osg::StateSet::TRANSPARENT_BIN);
        osg::ref_ptr<LoANode> loa = new LoANode;
        loa->setScenario(ScenarioLibrary::createHomogeneous(style).get());
        loa->addChild(ground.get());
        TransitionRenderer::Settings rs = loa->getRenderer()->getSettings();
        rs.edges = false;
        rs.unsharpMasking = false;
        loa->getRenderer()->setSettings(rs);
        // Straight down on the quad, which fills the middle of the frame.
        osg::ref_ptr<osg::Image> img = renderFromAbove(loa.get());
        EXPECT_GT(loa->getRenderer()->getStatistics().aBufferDraws, 0u) << style; // blended: the A-buffer
        long long leftCovered = 0, rightCovered = 0;
        for (int y = 12; y < 52; ++y)
            for (int x = 8; x < 56; ++x)
            {
                if (std::abs(x - 32) < 3) continue; // the texel boundary
                const unsigned char* p = img->data(x, y);
                const bool covered = (p[0] | p[1] | p[2]) > 8;
                (x < 32 ? leftCovered : rightCovered) += covered ? 1 : 0;
            }
        EXPECT_EQ(leftCovered, 0) << style << ": the transparent half was drawn";
        EXPECT_GT(rightCovered, 700) << style << ": the opaque half is missing";
    }
}

// The ping-pong buffer serves forests of opaque materials only (paper 004 §4.4: it "only resolves
// this issue if features are rendered opaquely"); its pass keeps one fragment per pixel and
// alpha-tests at 0.5. A forest whose material blends goes through the A-buffer with its alpha.
// Two forest quads side by side, in transition between two styles (weights 0.5 and 0.5), over
// black: the opaque one is drawn in the ping-pong buffer, the one of alpha 0.3 in the A-buffer and
// shows at about 0.3 of the opaque one's brightness. (Before, the ping-pong pass took both and cut
// the translucent quad away: opencity-block's alpha-blended tree fringes were lost, 0.47 % of the
// street view.)
TEST(TransitionRendererGLTest, ForestsOfBlendedMaterialsGoThroughTheABufferNotThePingPongBuffer)
{
    osg::ref_ptr<UsageScenario> s = new UsageScenario;
    s->setName("forests");
    const TransitionConfiguration::FeatureTypes types = {FeatureType::Green};
    s->addConfiguration(config("photorealistic", BlendFunction(0.0f, 1.0f, 1.0f, 1.0f), types,
                               new M(M::FEATURE_INTEREST, 0, 0)));
    s->addConfiguration(config("cartographic", BlendFunction(0.0f, 0.0f, 0.0f, 1.0f), types,
                               new M(M::FEATURE_INTEREST, 0, 0)));
    osg::ref_ptr<LoANode> loa = new LoANode;
    loa->setScenario(s.get());
    for (int i = 0; i < 2; ++i)
    {
        osg::ref_ptr<osg::Node> quad = groundFeature(unsigned(i + 1), FeatureType::Green, 4.5f, 0.5f);
        Feature::get(*quad)->setSubType("deciduous");
        osg::Geometry* g = quad->asGroup()->getChild(0)->asGeometry();
        osg::Vec3Array* v = static_cast<osg::Vec3Array*>(g->getVertexArray());
        for (osg::Vec3& p : *v)
            p.x() += i == 0 ? -5.5f : 5.5f;
        if (i == 1)
        {
            (*static_cast<osg::Vec4Array*>(g->getColorArray()))[0].a() = 0.3f;
            g->getOrCreateStateSet()->setMode(GL_BLEND, osg::StateAttribute::ON);
            g->getOrCreateStateSet()->setRenderingHint(osg::StateSet::TRANSPARENT_BIN);
        }
        loa->addChild(quad.get());
    }
    TransitionRenderer::Settings rs = loa->getRenderer()->getSettings();
    rs.fuseStyles = false; // else the opaque forest is fused and no ping-pong pass is drawn
    rs.edges = false;
    rs.unsharpMasking = false;
    loa->getRenderer()->setSettings(rs);
    loa->getRenderer()->setRecordDraws(true);
    osg::ref_ptr<osg::Image> img = renderFromAbove(loa.get());
    typedef TransitionRenderer::Draw D;
    const auto& draws = loa->getRenderer()->getDraws();
    EXPECT_EQ(count(draws, 1, D::PING_PONG, 0) + count(draws, 1, D::PING_PONG, 1), 2u);
    EXPECT_EQ(count(draws, 2, D::PING_PONG, 0) + count(draws, 2, D::PING_PONG, 1), 0u);
    EXPECT_EQ(count(draws, 2, D::A_BUFFER, 0) + count(draws, 2, D::A_BUFFER, 1), 2u);
    EXPECT_TRUE(loa->getRenderer()->getStatistics().pingPongBuffer);
    // Mean brightness of the middle of each quad (x 8..24 and 40..56 of 64, y 16..48).
    auto brightness = [&](int x0)
    {
        double sum = 0.0;
        for (int y = 16; y < 48; ++y)
            for (int x = x0; x < x0 + 16; ++x)
                for (int c = 0; c < 3; ++c)
                    sum += img->data(x, y)[c];
        return sum / (16.0 * 32.0 * 3.0);
    };
    const double opaque = brightness(8), translucent = brightness(40);
    ASSERT_GT(opaque, 40.0);
    EXPECT_NEAR(translucent / opaque, 0.3, 0.06) << opaque << " " << translucent;
}

// Two styles of one surface with weights 0.5 and 0.5 compose to the mean of the two styles'
// images (the A-buffer's same-surface merge), within 2/255; the paper's literal Algorithm 2
// (no merge) lets the background through instead.
TEST(TransitionRendererGLTest, TwoHalfWeightsOfOneSurfaceGiveTheMeanOfTheStyles)
{
    auto scene = [](float interest, bool merge)
    {
        osg::ref_ptr<UsageScenario> s = new UsageScenario;
        s->setName("half");
        const TransitionConfiguration::FeatureTypes types = {FeatureType::Green};
        // feature interest i: weight smoothstep(0, 1, i) and 1 - smoothstep(0, 1, i).
        s->addConfiguration(config("cartographic", BlendFunction(0.0f, 1.0f, 1.0f, 1.0f), types,
                                   new M(M::FEATURE_INTEREST, 0, 0)));
        s->addConfiguration(config("blueprint", BlendFunction(0.0f, 0.0f, 0.0f, 1.0f), types,
                                   new M(M::FEATURE_INTEREST, 0, 0)));
        osg::ref_ptr<LoANode> loa = new LoANode;
        loa->setScenario(s.get());
        loa->addChild(groundFeature(1, FeatureType::Green, 100.0f, interest));
        TransitionRenderer::Settings rs = loa->getRenderer()->getSettings();
        rs.mergeSurfaces = merge;
        rs.unsharpMasking = false;
        rs.fuseStyles = false; // the A-buffer's merge is what this test is about
        loa->getRenderer()->setSettings(rs);
        return loa;
    };
    const osg::Vec3d eye(0, -30, 40), centre(0, 0, 0);
    osg::ref_ptr<osg::Image> a = renderer(48, 32, scene(1.0f, true).get(), eye, centre)->renderImage();
    osg::ref_ptr<osg::Image> b = renderer(48, 32, scene(0.0f, true).get(), eye, centre)->renderImage();
    osg::ref_ptr<osg::Image> half = renderer(48, 32, scene(0.5f, true).get(), eye, centre)->renderImage();
    int worst = 0;
    for (int y = 4; y < 28; ++y)
        for (int x = 4; x < 44; ++x)
            for (int c = 0; c < 3; ++c)
            {
                const int expected = (int(a->data(x, y)[c]) + int(b->data(x, y)[c]) + 1) / 2;
                worst = std::max(worst, std::abs(int(half->data(x, y)[c]) - expected));
            }
    EXPECT_LE(worst, 2);
    EXPECT_NE(a->data(24, 16)[2], b->data(24, 16)[2]); // the two styles differ there

    // Literal Algorithm 2: mix(mix(black, A, 0.5), B, 0.5) = A/4 + B/2 on a black background.
    osg::ref_ptr<osg::Image> literal = renderer(48, 32, scene(0.5f, false).get(), eye, centre)->renderImage();
    int darker = 0;
    for (int c = 0; c < 3; ++c)
        darker += int(half->data(24, 16)[c]) - int(literal->data(24, 16)[c]);
    EXPECT_GT(darker, 20);
}

namespace
{
/** The frame against tests/data/golden/NAME.png (LOA_UPDATE_GOLDENS=1 writes it instead). */
void expectGolden(const std::string& name, const osg::Image& actual)
{
    osg::ref_ptr<osg::Image> golden = loatest::goldenOrUpdate(name + ".png", actual);
    if (!golden)
    {
        std::cout << "LOA_UPDATE_GOLDENS=1: wrote tests/data/golden/" << name << ".png\n";
        return;
    }
    // The bars of DemoCityImageGLTest: a channel may differ by 16/255 before its pixel fails
    // (llvmpipe builds round filtering and blending differently); mean <= 1/255; at most 0.5%
    // failing pixels (silhouette and texel flips at edges).
    const auto cmp = ImageComparison::compare(actual, *golden, 16);
    const bool ok = cmp.sizesMatch && cmp.meanDifference <= 1.0 && cmp.failingFraction <= 0.005;
    if (!ok) loatest::saveFailure(name, actual, cmp.difference.get());
    EXPECT_TRUE(ok) << name << ": " << cmp.summary();
}

/** Renders the demo city under a library scenario from a named camera at 320x240 and compares
 *  with the golden; `stats` gets the LoA node's statistics of the frame. */
void compareScenarioGolden(const std::string& scenario, const std::string& camera = "oblique",
                           TransitionRenderer::Statistics* stats = nullptr)
{
    OffscreenRenderer::Settings s;
    s.width = 320;
    s.height = 240;
    osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(s);
    osg::ref_ptr<osg::Group> city = CityGenerator(CityParameters()).generate();
    osg::ref_ptr<LoANode> loa = new LoANode;
    loa->setScenario(ScenarioLibrary::createBuiltin(scenario).get());
    loa->addChild(city.get());
    r->setSceneData(loa.get());
    const CameraPose pose = CityCameras::compute(camera, *city, 320.0 / 240.0);
    r->setPerspective(pose.fovy);
    r->setViewMatrixAsLookAt(pose.eye, pose.center, pose.up);
    osg::ref_ptr<osg::Image> actual = r->renderImage();
    if (stats) *stats = loa->getRenderer()->getStatistics();
    expectGolden("scenario-" + scenario + "-" + camera + "-320x240", *actual);
    EXPECT_GT(loa->getRenderer()->getStatistics().drawnFeatures, 100u);
}
} // namespace

TEST(TransitionRendererGLTest, DistanceScenarioMatchesGolden)
{
    compareScenarioGolden("distance");
}

// From the street, the view distance runs through all three levels: features in transition
// are drawn fused (their styles are opaque; from the oblique camera everything is far:
// cartographic). The golden was made on the A-buffer path.
TEST(TransitionRendererGLTest, DistanceScenarioFromTheStreetMatchesGolden)
{
    TransitionRenderer::Statistics st;
    compareScenarioGolden("distance", "street", &st);
    EXPECT_GT(st.fusedDraws, 10u);
    EXPECT_GE(st.fusedPrograms, 2u); // near/middle and middle/far transitions
    EXPECT_EQ(st.aBufferDraws, 0u);
    EXPECT_GT(st.sharedDraws, 0u);
}

TEST(TransitionRendererGLTest, ViewAngleScenarioMatchesGolden)
{
    compareScenarioGolden("view-angle");
}

TEST(TransitionRendererGLTest, RouteScenarioMatchesGolden)
{
    compareScenarioGolden("route");
}

TEST(TransitionRendererGLTest, CircularRoiScenarioMatchesGolden)
{
    compareScenarioGolden("circular-roi");
}

// The map scenarios of issue 19: every cartographic device, the route line, sunk buildings.
TEST(TransitionRendererGLTest, LandscapeAndNavigationScenariosMatchGoldens)
{
    compareScenarioGolden("landscape");
    compareScenarioGolden("navigation");
}

// The blend weights specialized to the scenario's interest groups (LOA_INTEREST_GROUPS,
// LOA_METRICS, set by TransitionUniforms::applyScenario) are the generic path's: the same image
// with the defines removed (2 groups of 2 configurations each and object-mode configurations in
// the route scenario; view-angle has one group of two metrics).
TEST(TransitionRendererGLTest, SpecializedBlendWeightsEqualTheGenericOnes)
{
    for (const char* scenario : {"view-angle", "route"})
    {
        OffscreenRenderer::Settings s;
        s.width = 160;
        s.height = 120;
        osg::ref_ptr<OffscreenRenderer> r;
        try
        {
            r = new OffscreenRenderer(s);
        }
        catch (const std::exception& e)
        {
            GTEST_SKIP() << "no EGL context: " << e.what();
        }
        osg::ref_ptr<osg::Group> city = CityGenerator(CityParameters()).generate();
        osg::ref_ptr<LoANode> loa = new LoANode;
        loa->setScenario(ScenarioLibrary::createBuiltin(scenario).get());
        loa->addChild(city.get());
        r->setSceneData(loa.get());
        const CameraPose pose = CityCameras::compute("oblique", *city, 160.0 / 120.0);
        r->setPerspective(pose.fovy);
        r->setViewMatrixAsLookAt(pose.eye, pose.center, pose.up);
        osg::ref_ptr<osg::Image> specialized = r->renderImage();
        ASSERT_TRUE(loa->getStateSet() != nullptr);
        const osg::StateSet::DefineList& defines = loa->getStateSet()->getDefineList();
        ASSERT_EQ(defines.count("LOA_INTEREST_GROUPS"), 1u) << scenario;
        EXPECT_EQ(defines.find("LOA_INTEREST_GROUPS")->second.first, "1") << scenario;
        loa->getStateSet()->removeDefine("LOA_INTEREST_GROUPS");
        loa->getStateSet()->removeDefine("LOA_METRICS");
        osg::ref_ptr<osg::Image> generic = r->renderImage();
        const auto cmp = ImageComparison::compare(*specialized, *generic, 1);
        EXPECT_TRUE(cmp.sizesMatch);
        EXPECT_LE(cmp.failingFraction, 0.0005) << scenario << ": " << cmp.summary();
        EXPECT_LE(cmp.meanDifference, 0.05) << scenario << ": " << cmp.summary();
    }
}

// Goldens of the cartographic styles (paper 004 Figure 8: waterlining, signatures, relief; §3.2.3:
// streets, and flat cartographic), each drawing the whole scene: the demo city from its oblique
// camera and West Oakland (OpenStreetMap, a real scene) top-down, at 320x240, against
// tests/data/golden/cartographic-*.png. What each style changes and where is checked exactly by
// its own tests (CPU twins, masks); these catch any change of the picture.
namespace
{
const char* const kCartographicStyles[] = {"cartographic", "waterlining", "relief",      "signatures",
                                           "streets",      "trees",       "object-edges"};
} // namespace

TEST(TransitionRendererGLTest, EveryCartographicStyleMatchesGoldensOnTheDemoCity)
{
    osg::ref_ptr<osg::Group> city = CityGenerator(CityParameters()).generate();
    for (const char* style : kCartographicStyles)
    {
        SCOPED_TRACE(style);
        OffscreenRenderer::Settings s;
        s.width = 320;
        s.height = 240;
        osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(s);
        osg::ref_ptr<LoANode> loa = new LoANode;
        loa->setScenario(ScenarioLibrary::createHomogeneous(style).get());
        loa->addChild(city.get());
        r->setSceneData(loa.get());
        const CameraPose pose = CityCameras::compute("oblique", *city, 320.0 / 240.0);
        r->setPerspective(pose.fovy);
        r->setViewMatrixAsLookAt(pose.eye, pose.center, pose.up);
        osg::ref_ptr<osg::Image> actual = r->renderImage();
        EXPECT_EQ(loa->getBindError(), "");
        expectGolden(std::string("cartographic-") + style + "-demo-city-oblique-320x240", *actual);
    }
}

TEST(TransitionRendererGLTest, EveryCartographicStyleMatchesGoldensOnARealOsmFile)
{
    const std::string file = std::string(LOA_SOURCE_DIR) + "/data/cache/python-osmnx-doc/West-Oakland.osm";
    if (!osgDB::fileExists(file)) GTEST_SKIP() << file << " is absent: run scripts/fetch-test-data";
    osg::ref_ptr<osg::Node> model = osgDB::readRefNodeFile(file);
    ASSERT_TRUE(model.valid());
    osg::ComputeBoundsVisitor cbv;
    model->accept(cbv);
    const osg::BoundingBoxd b = cbv.getBoundingBox();
    // 600 m x 450 m around its buildings (with its parks and the streets between them).
    osg::BoundingBoxd buildings;
    const FeatureIndex index(*model);
    for (const FeatureIndex::Entry& e : index.entries())
        if (e.feature->getType() == FeatureType::Building && e.feature->getBound().valid())
            buildings.expandBy(osg::BoundingBoxd(e.feature->getBound()._min, e.feature->getBound()._max));
    ASSERT_TRUE(buildings.valid());
    const osg::Vec3d c = buildings.center();
    const osg::BoundingBoxd view(c.x() - 300.0, c.y() - 225.0, b.zMin(), c.x() + 300.0, c.y() + 225.0,
                                 b.zMax());
    for (const char* style : kCartographicStyles)
    {
        SCOPED_TRACE(style);
        osg::ref_ptr<osg::Image> actual =
            loatest::topDown(model.get(), style, 320, 240, loatest::Viewport{0, 0, 320, 240}, view);
        expectGolden(std::string("cartographic-") + style + "-west-oakland-top-320x240", *actual);
    }
}
