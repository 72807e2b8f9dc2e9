// The LoA render over the whole frame at every size (issue: "the LoA render right on real scenes at
// every size"): the stencil-routed A-buffer against the CPU ReferenceCompositor at 1920x1080, at
// an odd size and with a viewport offset; "photorealistic is the model" (a scenario drawing every
// feature photorealistically renders what OSG's fixed-function pipeline renders, on the demo city
// and on real scenes); depth unsharp masking that never blackens a far surface; no background
// leaking into multi-style frames. Needs an OpenGL context (label gl).
#include "support/TestSupport.h"

#include <osgLoA/city/CityCameras>
#include <osgLoA/city/CityGenerator>
#include <osgLoA/city/CityTextures>
#include <osgLoA/compositing/ReferenceCompositor>
#include <osgLoA/compositing/StencilRoutedABuffer>
#include <osgLoA/render/GLCapabilities>
#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/semantics/Feature>
#include <osgLoA/semantics/FeatureClassifier>
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/styles/StylePreparation>
#include <osgLoA/transitions/LandmarkDeformation>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/ScenarioLibrary>
#include <osgLoA/util/ImageCompare>
#include <osgLoA/util/ImageFile>

#include <osg/AlphaFunc>
#include <osg/BlendFunc>
#include <osg/Geode>
#include <osg/Geometry>
#include <osg/MatrixTransform>
#include <osg/ShapeDrawable>
#include <osg/TexEnv>
#include <osg/TexMat>
#include <osg/Texture2D>
#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <random>

using namespace osgLoA;
using RC = ReferenceCompositor;

namespace
{
// ------------------------------------------------------------------------------------------
// A-buffer: K quads of different x extents (so that the depth complexity varies from 1 to K
// across the frame) at distinct depths, in a scrambled order, orthographic view [-1, 1]^2 with
// window depth = distance / 10.
struct Layer
{
    float x0, x1, distance;
    osg::Vec4 color;
};

std::vector<Layer> staircase(int k, unsigned seed)
{
    std::mt19937 rng(seed);
    std::vector<int> order(std::size_t(k), 0);
    for (int i = 0; i < k; ++i)
        order[std::size_t(i)] = i;
    std::shuffle(order.begin(), order.end(), rng);
    std::vector<Layer> layers;
    for (int i = 0; i < k; ++i)
    {
        Layer l;
        // Layer i covers x in [-1 + 1.8 i / k, 1]: complexity 1 at the left edge ... k at the right.
        l.x0 = -1.0f + 1.8f * float(i) / float(k) - (i == 0 ? 0.5f : 0.0f);
        l.x1 = 1.5f;
        l.distance = 1.0f + 0.5f * float(order[std::size_t(i)]);
        l.color.set(float(rng() % 256) / 255.0f, float(rng() % 256) / 255.0f, float(rng() % 256) / 255.0f,
                    float(40 + rng() % 180) / 255.0f);
        layers.push_back(l);
    }
    return layers;
}

osg::ref_ptr<osg::Geometry> quad(const Layer& l)
{
    return loatest::depthQuad(l.x0, l.x1, 1.5f, l.distance, l.color);
}

struct Viewport
{
    int x, y, w, h;
};

/** The reference frame: background outside the viewport, the composited layers inside. */
osg::ref_ptr<osg::Image> referenceFrame(int width, int height, const Viewport& vp,
                                        const std::vector<Layer>& layers, const osg::Vec4& background)
{
    RC::FragmentImage img(width, height);
    for (int y = vp.y; y < vp.y + vp.h; ++y)
        for (int x = vp.x; x < vp.x + vp.w; ++x)
        {
            const float cx = (float(x - vp.x) + 0.5f) / float(vp.w) * 2.0f - 1.0f;
            for (const Layer& l : layers)
                if (cx >= l.x0 && cx <= l.x1)
                {
                    RC::Fragment f;
                    f.color = l.color;
                    f.depth = l.distance / 10.0f;
                    img.at(x, y).push_back(f);
                }
        }
    return RC().compositeImage(img, background);
}

struct Difference
{
    int worst = 0;
    long long failing = 0; ///< pixels with a channel off by more than `tolerance`
};

/** Pixels with a channel off by more than tolerance; channels 4 compares alpha too (the
 *  A-buffer's composited alpha), 3 only what is seen. */
Difference compareFrames(const osg::Image& a, const osg::Image& b, int tolerance, int channels = 4)
{
    Difference d;
    for (int y = 0; y < a.t(); ++y)
        for (int x = 0; x < a.s(); ++x)
        {
            int m = 0;
            for (int c = 0; c < channels; ++c)
                m = std::max(m, std::abs(int(a.data(x, y)[c]) - int(b.data(x, y)[c])));
            d.worst = std::max(d.worst, m);
            if (m > tolerance) ++d.failing;
        }
    return d;
}

void runABufferCase(int width, int height, const Viewport& vp, const std::string& name)
{
    const osg::Vec4 background(51 / 255.0f, 102 / 255.0f, 153 / 255.0f, 1.0f);
    OffscreenRenderer::Settings s;
    s.width = width;
    s.height = height;
    s.clearColor = background;
    osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(s);
    osg::Camera* cam = r->getCamera();
    cam->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    cam->setProjectionMatrixAsOrtho(-1.0, 1.0, -1.0, 1.0, 0.0, 10.0);
    cam->setViewMatrix(osg::Matrix::identity());
    osg::ref_ptr<StencilRoutedABuffer> ab = new StencilRoutedABuffer(4, 3);
    ab->getRoutedStateSet()->setAttribute(StencilRoutedABuffer::createVertexColorProgram().get());
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(ab->getCamera());
    root->addChild(ab->createResolveNode().get());
    r->setSceneData(root.get());
    // Frame 1 over the whole target with nothing routed: the background everywhere (what lies
    // outside an offset viewport afterwards).
    r->renderImage();
    cam->setViewport(vp.x, vp.y, vp.w, vp.h);
    std::vector<Layer> layers = staircase(10, unsigned(width * 7 + height));
    // Edges on pixel boundaries: on llvmpipe the A-buffer routes by raster coverage, exact inside
    // pixels and documented as approximate where an edge cuts a pixel (StencilRoutedABuffer).
    for (Layer& l : layers)
        l.x0 = -1.0f + 2.0f * std::round((l.x0 + 1.0f) * 0.5f * float(vp.w)) / float(vp.w);
    for (const Layer& l : layers)
        ab->getRoutedGroup()->addChild(quad(l).get());
    osg::ref_ptr<osg::Image> gpu = r->renderImage();
    osg::ref_ptr<osg::Image> ref = referenceFrame(width, height, vp, layers, background);
    const Difference d = compareFrames(*gpu, *ref, 1);
    const ABufferFrameStatistics st = ab->getLastFrameStatistics();
    if (d.failing > 0)
    {
        loatest::saveFailure("abuffer-full-frame-" + name, *gpu, nullptr);
        for (int x = 0; x < width; ++x)
            for (int y = 0; y < height; y += std::max(1, height / 3))
            {
                int m = 0;
                for (int c = 0; c < 4; ++c)
                    m = std::max(m, std::abs(int(gpu->data(x, y)[c]) - int(ref->data(x, y)[c])));
                if (m > 1)
                    std::cout << name << ": (" << x << ", " << y << ") gpu " << int(gpu->data(x, y)[0]) << ","
                              << int(gpu->data(x, y)[1]) << "," << int(gpu->data(x, y)[2]) << " reference "
                              << int(ref->data(x, y)[0]) << "," << int(ref->data(x, y)[1]) << ","
                              << int(ref->data(x, y)[2]) << "\n";
            }
    }
    // The bar of StencilRoutedABufferGLTest: 1/255 per channel, every pixel of the frame (10
    // fragments at most per pixel fit N = 4 x 3 passes: nothing is lost).
    EXPECT_EQ(d.failing, 0) << name << ": worst " << d.worst << "/255";
    EXPECT_EQ(st.passes, 3) << name;
    EXPECT_FALSE(st.truncated) << name;
    EXPECT_EQ(st.width, vp.x + vp.w) << name;
    EXPECT_EQ(st.height, vp.y + vp.h) << name;
    // The overflow counts cover the whole viewport: after pass 1 every pixel with more than 4
    // fragments is counted (the reference's count, over the whole frame).
    long long deep = 0;
    for (int x = 0; x < vp.w; ++x)
    {
        const float cx = (float(x) + 0.5f) / float(vp.w) * 2.0f - 1.0f;
        int k = 0;
        for (const Layer& l : layers)
            k += (cx >= l.x0 && cx <= l.x1) ? 1 : 0;
        if (k > 4) deep += vp.h;
    }
    ASSERT_GE(st.overflowPixels.size(), 2u) << name;
    EXPECT_EQ((long long)(st.overflowPixels[0]), deep) << name;
}

// ------------------------------------------------------------------------------------------
// Scenes: the demo city and the real test scenes (scripts/fetch-test-data).

/** One graphic style for every feature: the LoA pipeline with nothing to blend. */
osg::ref_ptr<UsageScenario> homogeneous(const std::string& style)
{
    return ScenarioLibrary::createHomogeneous(style);
}

struct TestScene
{
    std::string name;
    osg::ref_ptr<osg::Node> model;
    bool city = false; ///< the demo city: its named cameras apply
};

/** The real test scenes that scripts/fetch-test-data extracts from Debian packages (see
 *  docs/test-scenes.md), classified by the default rules; missing ones are left out. */
std::vector<TestScene> realScenes()
{
    std::vector<TestScene> scenes;
    const std::string root = std::string(LOA_SOURCE_DIR) + "/data/";
    const std::pair<const char*, const char*> candidates[] = {
        {"torcs-street-1", "test-scenes/torcs-street-1.osgt"},
        {"opencity-block", "test-scenes/opencity-block.osgt"},
    };
    for (const auto& c : candidates)
    {
        const std::string path = root + c.second;
        if (!osgDB::fileExists(path)) continue;
        osg::ref_ptr<osg::Node> model = osgDB::readRefNodeFile(path);
        if (!model) continue;
        osg::ref_ptr<osg::Group> group = new osg::Group;
        group->addChild(model.get());
        FeatureClassifier().classify(*group);
        scenes.push_back({c.first, group, false});
    }
    return scenes;
}

TestScene demoCity()
{
    return {"demo-city", CityGenerator(CityParameters()).generate(), true};
}

struct Pose
{
    osg::Vec3d eye, center, up;
    double fovy = 45.0;
};

Pose poseOf(const TestScene& scene, const std::string& camera, double aspect)
{
    Pose p;
    if (scene.city)
    {
        const CameraPose c = CityCameras::compute(camera, *scene.model, aspect);
        p.eye = c.eye;
        p.center = c.center;
        p.up = c.up;
        p.fovy = c.fovy;
        return p;
    }
    OffscreenRenderer::framingPose(scene.model->getBound(), p.fovy, aspect, p.eye, p.center, p.up);
    if (camera == "near")
    {
        // Closer than the framing pose: textured surfaces large enough on screen to show their
        // texture detail (the abstract style's tests).
        const osg::BoundingSphere bs = scene.model->getBound();
        p.center = bs.center();
        p.eye = bs.center() + osg::Vec3d(0.18, -0.3, 0.16) * bs.radius();
        p.up = osg::Vec3d(0, 0, 1);
    }
    if (camera == "top")
    {
        const osg::BoundingSphere bs = scene.model->getBound();
        p.center = bs.center();
        p.eye = bs.center() + osg::Vec3d(0.0, -0.01 * bs.radius(), 2.6 * bs.radius());
        p.up = osg::Vec3d(0, 1, 0);
    }
    return p;
}

osg::ref_ptr<osg::Image> renderFrame(osg::Node* root, const TestScene& scene, const std::string& camera,
                                     int width, int height, const Viewport* vp, const osg::Vec4& clear)
{
    OffscreenRenderer::Settings s;
    s.width = width;
    s.height = height;
    s.clearColor = clear;
    osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(s);
    r->setSceneData(root);
    const double aspect = vp ? double(vp->w) / vp->h : double(width) / height;
    const Pose p = poseOf(scene, camera, aspect);
    r->setPerspective(p.fovy);
    if (vp)
    {
        r->renderImage(); // the whole target once: what stays outside the viewport
        r->getCamera()->setViewport(vp->x, vp->y, vp->w, vp->h);
        r->getCamera()->setProjectionMatrixAsPerspective(p.fovy, aspect, 1.0, 10000.0);
    }
    r->setViewMatrixAsLookAt(p.eye, p.center, p.up);
    return r->renderImage();
}

osg::ref_ptr<LoANode> loaNode(osg::Node* model, UsageScenario* scenario)
{
    osg::ref_ptr<LoANode> loa = new LoANode;
    loa->setScenario(scenario);
    loa->addChild(model);
    return loa;
}

/** Writes a frame the test made into the build's test-output folder (to look at). */
void keep(const osg::Image& image, const std::string& name)
{
    const std::string dir = std::string(LOA_TEST_OUTPUT_DIR) + "/full-frame";
    osgDB::makeDirectory(dir);
    ImageFile::write(dir + "/" + name + ".png", image);
}
} // namespace

TEST(LoARenderFullFrameGLTest, ABufferMatchesTheReferenceAt1920x1080)
{
    runABufferCase(1920, 1080, {0, 0, 1920, 1080}, "1920x1080");
}

TEST(LoARenderFullFrameGLTest, ABufferMatchesTheReferenceAtAnOddSize)
{
    runABufferCase(1001, 667, {0, 0, 1001, 667}, "1001x667");
}

TEST(LoARenderFullFrameGLTest, ABufferMatchesTheReferenceInAnOffsetViewport)
{
    runABufferCase(1001, 667, {123, 45, 850, 601}, "offset");
}

// "Photorealistic is the model": every feature in the photorealistic style through the whole LoA
// pipeline (G-buffer, compositing) against OSG's fixed-function render of the same graph. Bar:
// mean channel difference <= 1/255 and at most 1 % of the pixels with an RGB channel off by more
// than 8/255 (the style lights per fragment where the fixed function lights per vertex, and the
// LoA node fits its own depth range: curved surfaces and coplanar decals may differ slightly;
// with blended materials, as the real scenes have them (OSG's ac reader blends every texture with
// alpha), the A-buffer composites per fragment in depth order where OSG sorts whole drawables
// back to front, and merges blended surfaces within the merge epsilon of each other (a pond quad
// on the ground) by their weights instead of blending one over the other). Measured on the real
// scenes: 0.07-0.45 %. The frame buffer's alpha is not compared: the fixed function blends it
// with the blend function, the compositing writes opaque pixels.
namespace
{
void expectIdentity(const TestScene& scene, const std::string& camera, int width, int height,
                    const Viewport* vp, double failingBar = 0.01)
{
    const osg::Vec4 clear(0.62f, 0.75f, 0.90f, 1.0f);
    const std::string name = scene.name + "-" + camera + "-" + std::to_string(width) + "x" +
                             std::to_string(height) + (vp ? "-offset" : "");
    osg::ref_ptr<osg::Image> plain = renderFrame(scene.model.get(), scene, camera, width, height, vp, clear);
    osg::ref_ptr<UsageScenario> photo = homogeneous("photorealistic");
    osg::ref_ptr<LoANode> loa = loaNode(scene.model.get(), photo.get());
    osg::ref_ptr<osg::Image> styled = renderFrame(loa.get(), scene, camera, width, height, vp, clear);
    keep(*plain, "identity-" + name + "-plain");
    keep(*styled, "identity-" + name + "-photorealistic");
    // RGB: what is seen (blended materials leave different alpha in the frame buffer: the fixed
    // function blends alpha with the blend function, the compositing writes opaque pixels).
    const Difference d = compareFrames(*plain, *styled, 8, 3);
    double mean = 0.0;
    for (int y = 0; y < plain->t(); ++y)
        for (int x = 0; x < plain->s(); ++x)
            for (int c = 0; c < 3; ++c)
                mean += std::abs(int(plain->data(x, y)[c]) - int(styled->data(x, y)[c]));
    mean /= 3.0 * plain->s() * plain->t();
    const double fraction = double(d.failing) / (double(plain->s()) * plain->t());
    std::cout << "identity " << name << ": mean " << mean << "/255, " << 100.0 * fraction
              << " % over 8/255, worst " << d.worst << "/255, features drawn "
              << loa->getRenderer()->getStatistics().drawnFeatures << "\n";
    EXPECT_LE(mean, 1.0) << name;
    EXPECT_LE(fraction, failingBar) << name;
}
} // namespace

TEST(LoARenderFullFrameGLTest, PhotorealisticIsThePlainRenderOfTheDemoCity)
{
    const TestScene city = demoCity();
    expectIdentity(city, "oblique", 1920, 1080, nullptr);
    expectIdentity(city, "street", 1001, 667, nullptr);
    const Viewport vp{61, 37, 900, 600};
    expectIdentity(city, "street", 1001, 667, &vp);
}

TEST(LoARenderFullFrameGLTest, PhotorealisticIsThePlainRenderOfRealScenes)
{
    const std::vector<TestScene> scenes = realScenes();
    if (scenes.empty()) GTEST_SKIP() << "no real test scene: run scripts/fetch-test-data";
    for (const TestScene& scene : scenes)
    {
        expectIdentity(scene, "oblique", 1920, 1080, nullptr);
        const Viewport vp{61, 37, 900, 600};
        expectIdentity(scene, "top", 1001, 667, &vp);
    }
}

// Texture state the test scenes lack, each on a quad of its own (a feature each): a base texture
// with a luminance lightmap on unit 1 tiled by a texture matrix (MODULATE), an S3TC (DXT1)
// texture, a blended luminance-alpha texture, a base texture with an ADD texture on unit 2, and an
// alpha-tested card (AlphaFunc, 20 m above the others, overlapping two of them).
// The photorealistic style combines units 0-2 as the fixed function does
// (FixedFunctionUniforms::kUnits); same bars as the demo city.
namespace
{
osg::ref_ptr<osg::Image> image(int w, int h, GLenum format,
                               const std::function<void(int, int, unsigned char*)>& f)
{
    osg::ref_ptr<osg::Image> img = new osg::Image;
    img->allocateImage(w, h, 1, format, GL_UNSIGNED_BYTE);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            f(x, y, img->data(x, y));
    return img;
}

osg::ref_ptr<osg::Geode> texturedQuadFeature(float x0, float y0, unsigned id)
{
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    osg::ref_ptr<osg::Vec2Array> t = new osg::Vec2Array;
    for (const osg::Vec2& c : {osg::Vec2(0, 0), osg::Vec2(1, 0), osg::Vec2(1, 1), osg::Vec2(0, 1)})
    {
        v->push_back(osg::Vec3(x0 + 90.0f * c.x(), y0 + 90.0f * c.y(), 0.0f));
        t->push_back(c);
    }
    g->setVertexArray(v.get());
    for (unsigned unit = 0; unit < 3; ++unit)
        g->setTexCoordArray(unit, t.get(), osg::Array::BIND_PER_VERTEX);
    osg::ref_ptr<osg::Vec3Array> n = new osg::Vec3Array(1);
    (*n)[0] = osg::Vec3(0, 0, 1);
    g->setNormalArray(n.get(), osg::Array::BIND_OVERALL);
    osg::ref_ptr<osg::Vec4Array> c = new osg::Vec4Array(1);
    (*c)[0] = osg::Vec4(1, 1, 1, 1);
    g->setColorArray(c.get(), osg::Array::BIND_OVERALL);
    g->addPrimitiveSet(new osg::DrawArrays(GL_QUADS, 0, 4));
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(g.get());
    Feature::attach(*geode, new Feature(id, FeatureType::Building));
    return geode;
}
} // namespace

TEST(LoARenderFullFrameGLTest, PhotorealisticIsThePlainRenderOfEveryTextureState)
{
    auto checker = image(8, 8, GL_RGB,
                         [](int x, int y, unsigned char* p)
                         { p[0] = (x + y) % 2 ? 220 : 60, p[1] = 40 + 20 * x, p[2] = 200 - 20 * y; });
    auto lightmap =
        image(4, 4, GL_LUMINANCE, [](int x, int y, unsigned char* p) { *p = 80 + 40 * x + 5 * y; });
    auto la = image(4, 4, GL_LUMINANCE_ALPHA,
                    [](int x, int y, unsigned char* p) { p[0] = 60 + 50 * y, p[1] = 100 + 50 * x; });
    auto glow =
        image(4, 4, GL_RGB, [](int x, int y, unsigned char* p) { p[0] = 15 * x, p[1] = 10 * y, p[2] = 30; });
    // One 8x4 DXT1 image: two blocks, red/blue and green/white, rows of indices 0..3.
    static unsigned char blocks[16] = {0x00, 0xF8, 0x1F, 0x00, 0x00, 0x55, 0xAA, 0xFF,
                                       0xE0, 0x07, 0xFF, 0xFF, 0xFF, 0xAA, 0x55, 0x00};
    osg::ref_ptr<osg::Image> dxt = new osg::Image;
    dxt->setImage(8, 4, 1, GL_COMPRESSED_RGB_S3TC_DXT1_EXT, GL_COMPRESSED_RGB_S3TC_DXT1_EXT, GL_UNSIGNED_BYTE,
                  blocks, osg::Image::NO_DELETE);
    auto texture = [](osg::Image* img)
    {
        osg::ref_ptr<osg::Texture2D> t = new osg::Texture2D(img);
        t->setWrap(osg::Texture::WRAP_S, osg::Texture::REPEAT);
        t->setWrap(osg::Texture::WRAP_T, osg::Texture::REPEAT);
        t->setFilter(osg::Texture::MIN_FILTER, osg::Texture::LINEAR);
        t->setFilter(osg::Texture::MAG_FILTER, osg::Texture::NEAREST);
        return t;
    };
    osg::ref_ptr<osg::Group> g = new osg::Group;
    osg::ref_ptr<osg::Geode> lightmapped = texturedQuadFeature(-100, -100, 1);
    osg::StateSet* s1 = lightmapped->getOrCreateStateSet();
    s1->setTextureAttributeAndModes(0, texture(checker.get()).get());
    s1->setTextureAttributeAndModes(1, texture(lightmap.get()).get());
    s1->setTextureAttribute(1, new osg::TexMat(osg::Matrix::scale(2, 2, 1)));
    osg::ref_ptr<osg::Geode> compressed = texturedQuadFeature(10, -100, 2);
    compressed->getOrCreateStateSet()->setTextureAttributeAndModes(0, texture(dxt.get()).get());
    osg::ref_ptr<osg::Geode> blended = texturedQuadFeature(-100, 10, 3);
    osg::StateSet* s3 = blended->getOrCreateStateSet();
    s3->setTextureAttributeAndModes(0, texture(la.get()).get());
    s3->setAttributeAndModes(new osg::BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA));
    s3->setRenderingHint(osg::StateSet::TRANSPARENT_BIN);
    osg::ref_ptr<osg::Geode> added = texturedQuadFeature(10, 10, 4);
    osg::StateSet* s4 = added->getOrCreateStateSet();
    s4->setTextureAttributeAndModes(0, texture(checker.get()).get());
    s4->setTextureAttributeAndModes(2, texture(glow.get()).get());
    s4->setTextureAttribute(2, new osg::TexEnv(osg::TexEnv::ADD));
    // A ground plane below, so that the blended quad has something behind it.
    osg::ref_ptr<osg::Geode> ground = new osg::Geode;
    // (Well below: the A-buffer merges blended surfaces within its merge epsilon of each other.)
    osg::ref_ptr<osg::ShapeDrawable> plane =
        new osg::ShapeDrawable(new osg::Box(osg::Vec3(0, 0, -40), 260, 260, 2));
    plane->setColor(osg::Vec4(0.5f, 0.55f, 0.5f, 1.0f));
    ground->addDrawable(plane.get());
    Feature::attach(*ground, new Feature(5, FeatureType::Terrain));
    // An alpha-tested card (osg::AlphaFunc GREATER 0.5, no blending): a tree's shape cut from a quad.
    auto cutout = image(8, 8, GL_RGBA,
                        [](int x, int y, unsigned char* p)
                        {
                            p[0] = 40, p[1] = 120 + 10 * y, p[2] = 50,
                            p[3] = (x - 3.5) * (x - 3.5) + (y - 3.5) * (y - 3.5) < 9 ? 255 : 0;
                        });
    osg::ref_ptr<osg::Geode> card = texturedQuadFeature(-45, -45, 6);
    osg::StateSet* s6 = card->getOrCreateStateSet();
    s6->setTextureAttributeAndModes(0, texture(cutout.get()).get());
    s6->setAttributeAndModes(new osg::AlphaFunc(osg::AlphaFunc::GREATER, 0.5f));
    osg::ref_ptr<osg::MatrixTransform> lifted = new osg::MatrixTransform(osg::Matrix::translate(0, 0, 20));
    lifted->addChild(card.get());
    for (osg::Node* n : std::initializer_list<osg::Node*>{lightmapped.get(), compressed.get(), blended.get(),
                                                          added.get(), ground.get(), lifted.get()})
        g->addChild(n);
    const TestScene scene{"texture-states", g, false};
    expectIdentity(scene, "top", 1920, 1080, nullptr);
    const Viewport vp{61, 37, 900, 600};
    expectIdentity(scene, "oblique", 1001, 667, &vp);
}

// Depth unsharp masking (Luft et al. 2006, paper 004 §3.2.4) as the compositing has it: a far
// ground plane beside a near box keeps at least 1 - 0.4 (loa_unsharpMaxDarkening) of its colour
// at the box's silhouette, and is darkened there (the effect is on).
TEST(LoARenderFullFrameGLTest, UnsharpMaskingNeverBlackensAFarSurface)
{
    auto scene = [](bool unsharp)
    {
        osg::ref_ptr<osg::Group> g = new osg::Group;
        osg::ref_ptr<osg::Geode> ground = new osg::Geode;
        osg::ref_ptr<osg::ShapeDrawable> plane =
            new osg::ShapeDrawable(new osg::Box(osg::Vec3(0, 0, -1), 2000, 2000, 2));
        plane->setColor(osg::Vec4(0.8f, 0.8f, 0.8f, 1.0f));
        ground->addDrawable(plane.get());
        Feature::attach(*ground, new Feature(1, FeatureType::Terrain));
        osg::ref_ptr<osg::Geode> box = new osg::Geode;
        osg::ref_ptr<osg::ShapeDrawable> b =
            new osg::ShapeDrawable(new osg::Box(osg::Vec3(0, -300, 60), 40, 40, 120));
        b->setColor(osg::Vec4(0.8f, 0.8f, 0.8f, 1.0f));
        box->addDrawable(b.get());
        Feature::attach(*box, new Feature(2, FeatureType::Building));
        g->addChild(ground.get());
        g->addChild(box.get());
        osg::ref_ptr<LoANode> loa = loaNode(g.get(), homogeneous("cartographic").get());
        TransitionRenderer::Settings rs = loa->getRenderer()->getSettings();
        rs.unsharpMasking = unsharp;
        rs.edges = false;
        loa->getRenderer()->setSettings(rs);
        return loa;
    };
    auto render = [&](bool unsharp)
    {
        osg::ref_ptr<LoANode> loa = scene(unsharp);
        OffscreenRenderer::Settings s;
        s.width = 480;
        s.height = 320;
        osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(s);
        r->setSceneData(loa.get());
        r->setPerspective(40.0);
        r->setViewMatrixAsLookAt(osg::Vec3d(0, -520, 90), osg::Vec3d(0, 0, 0), osg::Vec3d(0, 0, 1));
        return r->renderImage();
    };
    osg::ref_ptr<osg::Image> off = render(false);
    osg::ref_ptr<osg::Image> on = render(true);
    keep(*on, "unsharp-on");
    double worstRatio = 1.0, sumRatio = 0.0;
    int counted = 0;
    for (int y = 0; y < on->t(); ++y)
        for (int x = 0; x < on->s(); ++x)
        {
            const int lumOff = int(off->data(x, y)[0]) + off->data(x, y)[1] + off->data(x, y)[2];
            const int lumOn = int(on->data(x, y)[0]) + on->data(x, y)[1] + on->data(x, y)[2];
            if (lumOff < 30) continue;
            const double ratio = double(lumOn) / double(lumOff);
            worstRatio = std::min(worstRatio, ratio);
            if (ratio < 0.99)
            {
                sumRatio += ratio;
                ++counted;
            }
        }
    std::cout << "unsharp: worst ratio " << worstRatio << ", " << counted << " darkened pixels\n";
    EXPECT_GE(worstRatio, 0.6 - 2.0 / 255.0); // at most 40 % darker: never black
    EXPECT_GT(counted, 50);                   // the effect is there, around the box
    EXPECT_LT(worstRatio, 0.97);
}

// No leaks: pixels of the background colour inside what a single-style frame covers, in the
// multi-style frames of every library scenario and camera. Bar: at most 0.05 % of the frame's
// pixels more than the single-style (homogeneous photorealistic) frame has.
namespace
{
long long backgroundPixels(const osg::Image& img, const osg::Image* covered)
{
    long long n = 0;
    for (int y = 0; y < img.t(); ++y)
        for (int x = 0; x < img.s(); ++x)
        {
            const unsigned char* p = img.data(x, y);
            const bool bg = p[0] == 255 && p[1] == 0 && p[2] == 255;
            if (!bg) continue;
            if (covered)
            {
                const unsigned char* q = covered->data(x, y);
                if (q[0] == 255 && q[1] == 0 && q[2] == 255) continue; // background there too
            }
            ++n;
        }
    return n;
}

void expectNoLeaks(const TestScene& scene, const std::vector<std::string>& cameras, int width, int height)
{
    const osg::Vec4 magenta(1, 0, 1, 1);
    for (const std::string& camera : cameras)
    {
        osg::ref_ptr<LoANode> single = loaNode(scene.model.get(), homogeneous("photorealistic").get());
        osg::ref_ptr<osg::Image> ref =
            renderFrame(single.get(), scene, camera, width, height, nullptr, magenta);
        for (const std::string& name : ScenarioLibrary::builtinNames())
        {
            // Buildings that sink where a scenario draws a map (view-angle, navigation: §3.2.2)
            // uncover what was behind them, the sky included, by design (LandmarkDeformationGLTest):
            // here sinking is off, so that what shows the background is a compositing leak.
            osg::ref_ptr<UsageScenario> scenario = ScenarioLibrary::createBuiltin(name);
            if (LandmarkDeformation* d = scenario->getLandmarkDeformation()) d->setSinkingEnabled(false);
            osg::ref_ptr<LoANode> loa = loaNode(scene.model.get(), scenario.get());
            osg::ref_ptr<osg::Image> img =
                renderFrame(loa.get(), scene, camera, width, height, nullptr, magenta);
            const long long leaks = backgroundPixels(*img, ref.get());
            const double bar = 0.0005 * width * height;
            std::cout << "leaks " << scene.name << " " << camera << " " << name << ": " << leaks << " (bar "
                      << bar << ")\n";
            if (leaks > bar) keep(*img, "leaks-" + scene.name + "-" + camera + "-" + name);
            EXPECT_LE(double(leaks), bar) << scene.name << " " << camera << " " << name;
        }
    }
}
} // namespace

TEST(LoARenderFullFrameGLTest, NoBackgroundLeaksInTheDemoCity)
{
    expectNoLeaks(demoCity(), {"oblique", "street", "top"}, 800, 450);
}

TEST(LoARenderFullFrameGLTest, NoBackgroundLeaksInRealScenes)
{
    const std::vector<TestScene> scenes = realScenes();
    if (scenes.empty()) GTEST_SKIP() << "no real test scene: run scripts/fetch-test-data";
    for (const TestScene& scene : scenes)
        expectNoLeaks(scene, {"oblique", "top"}, 800, 450);
}

// ------------------------------------------------------------------------------------------
// Fused styles (TransitionRenderer::Settings::fuseStyles, docs/rendering.md): a feature in
// transition whose styles are all opaque is drawn once, its styles blended per fragment, where
// the A-buffer path drew it once per style and merged the fragments. Both give the same frame
// away from edges: for every library scenario, on the demo city and the real test scenes, the
// frame with fusing on is compared with the frame with fusing off (the A-buffer with one sample
// per pixel) over the whole frame. A pixel fails when a channel differs by more than 16/255 (the
// golden bar). Bars: mean difference <= 1/255; failing pixels away from edges (no pixel of the
// 3x3 neighbourhood differs from the centre by more than 24/255 in either frame) at most 0.05 %
// of the frame (the no-leak bar). At edges the two differ by design: the A-buffer keeps and
// merges fragments of faces just behind the front one (front-surface tolerance 2 fwidth(z)) and
// covers some silhouette pixels the G-buffer leaves empty; the fused draw has the single-style
// draw's coverage (measured on the demo city, oblique, 641x359: 98 % of the 1.0-1.2 % failing
// pixels are at edges). TransitionRendererGLTest.FusedStylesEqualTheWeightedSumOfTheStyles checks
// the fused blend itself against an independent reference, to 2/255 on every pixel.
namespace
{
struct FusedCount
{
    unsigned fused = 0, frames = 0;
};

struct EdgeSplit
{
    long long failing = 0, failingAwayFromEdges = 0;
};

EdgeSplit compareAwayFromEdges(const osg::Image& x, const osg::Image& y)
{
    auto differs = [](const unsigned char* p, const unsigned char* q, int by)
    {
        for (int c = 0; c < 3; ++c)
            if (std::abs(int(p[c]) - int(q[c])) > by) return true;
        return false;
    };
    EdgeSplit e;
    for (int j = 0; j < x.t(); ++j)
        for (int i = 0; i < x.s(); ++i)
        {
            if (!differs(x.data(i, j), y.data(i, j), 16)) continue;
            ++e.failing;
            bool edge = false;
            for (int dj = -1; dj <= 1 && !edge; ++dj)
                for (int di = -1; di <= 1 && !edge; ++di)
                {
                    const int ni = std::clamp(i + di, 0, x.s() - 1), nj = std::clamp(j + dj, 0, x.t() - 1);
                    edge = differs(x.data(ni, nj), x.data(i, j), 24) ||
                           differs(y.data(ni, nj), y.data(i, j), 24);
                }
            if (!edge) ++e.failingAwayFromEdges;
        }
    return e;
}

void expectFusedEqualsABuffer(const TestScene& scene, const std::vector<std::string>& scenarios,
                              const std::vector<std::string>& cameras, int width, int height,
                              const Viewport* vp, FusedCount& count)
{
    const osg::Vec4 clear(0.2f, 0.3f, 0.4f, 1.0f);
    for (const std::string& camera : cameras)
        for (const std::string& name : scenarios)
        {
            osg::ref_ptr<osg::Image> frames[2];
            TransitionRenderer::Statistics stats[2];
            for (int fuse = 0; fuse < 2; ++fuse)
            {
                osg::ref_ptr<LoANode> loa =
                    loaNode(scene.model.get(), ScenarioLibrary::createBuiltin(name).get());
                TransitionRenderer::Settings rs = loa->getRenderer()->getSettings();
                rs.fuseStyles = fuse == 1;
                // The reference is the exact per-pixel linked lists, the default A-buffer on
                // llvmpipe (one geometry pass: the oblique demo city took 2.2 s a frame through
                // 8 stencil-routed passes at 641x359, 0.49 s with the lists). The routed methods
                // agree with each other (OITMethodsAgree*). One sample per pixel: exact coverage
                // at pixel centres, as the G-buffer's.
                rs.oit = OrderIndependentTransparency::LINKED_LIST;
                rs.samples = 1;
                rs.maxPasses = 8;
                loa->getRenderer()->setSettings(rs);
                frames[fuse] = renderFrame(loa.get(), scene, camera, width, height, vp, clear);
                stats[fuse] = loa->getRenderer()->getStatistics();
            }
            const std::string label = scene.name + " " + camera + " " + name + " " + std::to_string(width) +
                                      "x" + std::to_string(height) + (vp ? " (viewport offset)" : "");
            // Fusing changes how features in transition are drawn, not which: the features the
            // A-buffer path drew in transition are the fused ones plus those still routed.
            EXPECT_EQ(stats[0].drawnFeatures, stats[1].drawnFeatures) << label;
            EXPECT_EQ(stats[1].fusedDraws + stats[1].depthOnlyDraws, stats[0].depthOnlyDraws) << label;
            EXPECT_EQ(stats[0].fusedDraws, 0u) << label;
            EXPECT_LE(stats[1].aBufferDraws, stats[0].aBufferDraws) << label;
            count.fused += stats[1].fusedDraws;
            ++count.frames;
            const auto cmp = ImageComparison::compare(*frames[1], *frames[0], 16);
            const EdgeSplit split = compareAwayFromEdges(*frames[1], *frames[0]);
            const double pixels = double(frames[0]->s()) * frames[0]->t();
            // Against the linked lists, at most 36 pixels of a frame (0.016 %) differ by more
            // than 16/255, all on silhouettes (measured on the demo city and the real scenes).
            const bool ok = cmp.sizesMatch && cmp.meanDifference <= 0.5 &&
                            double(cmp.failingPixels) <= 0.0005 * pixels &&
                            double(split.failingAwayFromEdges) <= 0.0001 * pixels;
            std::cout << "fused " << label << ": " << stats[1].fusedDraws << " fused draws ("
                      << stats[1].fusedPrograms << " programs), A-buffer draws " << stats[0].aBufferDraws
                      << " -> " << stats[1].aBufferDraws << "; " << cmp.summary() << "; away from edges "
                      << split.failingAwayFromEdges << " failing (bars: " << 0.0005 * pixels
                      << " in the frame, " << 0.0001 * pixels << " away from edges)\n";
            std::string file =
                "fused-" + scene.name + "-" + camera + "-" + name + "-" + std::to_string(width);
            if (vp) file += "-viewport";
            if (!ok || width == 1920 || std::getenv("LOA_KEEP_FRAMES"))
            {
                keep(*frames[1], file + "-fused");
                keep(*frames[0], file + "-abuffer");
            }
            EXPECT_TRUE(ok) << label << ": " << cmp.summary();
        }
}
} // namespace

TEST(LoARenderFullFrameGLTest, FusedStylesEqualTheABufferOnTheDemoCity)
{
    FusedCount count;
    // Every library scenario from the street and oblique cameras at an odd size; the scenario
    // with the most features in transition at 1920x1080, and in an offset viewport.
    expectFusedEqualsABuffer(demoCity(), ScenarioLibrary::builtinNames(), {"street", "oblique"}, 641, 359,
                             nullptr, count);
    expectFusedEqualsABuffer(demoCity(), {"distance"}, {"street"}, 1920, 1080, nullptr, count);
    const Viewport vp{37, 21, 500, 300};
    expectFusedEqualsABuffer(demoCity(), {"route"}, {"oblique"}, 577, 343, &vp, count);
    // Not vacuous: the street views put dozens of features in transition.
    EXPECT_GT(count.fused, 100u) << "over " << count.frames << " frames";
}

TEST(LoARenderFullFrameGLTest, FusedStylesEqualTheABufferOnRealScenes)
{
    const std::vector<TestScene> scenes = realScenes();
    if (scenes.empty()) GTEST_SKIP() << "no real test scene: run scripts/fetch-test-data";
    for (const TestScene& scene : scenes)
    {
        FusedCount count;
        expectFusedEqualsABuffer(scene, ScenarioLibrary::builtinNames(), {"oblique", "top"}, 481, 271,
                                 nullptr, count);
        EXPECT_GT(count.fused, 0u) << scene.name << ": no feature was drawn fused in " << count.frames
                                   << " frames";
    }
}

// ------------------------------------------------------------------------------------------
// The paper's abstract style (paper 004 §3.1; TextureAbstraction, StylePreparation): textures
// abstracted per mip level, colour and outlines blended at render time, prepared once per
// model with a progress line; it removes detail on every test scene.
namespace
{
/** Detail measures over the pixels covered (not the clear colour) in both frames, with their 3x3
 *  neighbourhoods: `energy` is the mean of min(|L|, 16)^2, L the 4-neighbour Laplacian of the
 *  luma (0..255): the frame's fine high-frequency energy, texture grain and noise; the clamp
 *  keeps the few strong geometric edges (silhouettes, windows, which both styles draw) from
 *  dominating it. `speckle` is the fraction of pixels whose luma lies more than 16/255 above or
 *  below all 8 neighbours (isolated dots, what per-texel quantization made). */
struct Detail
{
    double energy = 0.0, speckle = 0.0;
    long long pixels = 0;
};

double luma(const osg::Image& img, int x, int y)
{
    const unsigned char* p = img.data(x, y);
    return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
}

Detail detailOf(const osg::Image& img, const osg::Image& maskA, const osg::Image& maskB,
                const osg::Vec4& clear)
{
    auto isClear = [&](const osg::Image& m, int x, int y)
    {
        const unsigned char* p = m.data(x, y);
        for (int c = 0; c < 3; ++c)
            if (std::abs(int(p[c]) - int(std::lround(clear[c] * 255.0f))) > 2) return false;
        return true;
    };
    Detail d;
    long long speckles = 0;
    for (int y = 1; y + 1 < img.t(); ++y)
        for (int x = 1; x + 1 < img.s(); ++x)
        {
            bool covered = true;
            for (int j = -1; j <= 1 && covered; ++j)
                for (int i = -1; i <= 1 && covered; ++i)
                    covered = !isClear(maskA, x + i, y + j) && !isClear(maskB, x + i, y + j);
            if (!covered) continue;
            const double c = luma(img, x, y);
            const double lap = 4.0 * c - luma(img, x - 1, y) - luma(img, x + 1, y) - luma(img, x, y - 1) -
                               luma(img, x, y + 1);
            const double clamped = std::min(std::fabs(lap), 16.0);
            d.energy += clamped * clamped;
            bool above = true, below = true;
            for (int j = -1; j <= 1; ++j)
                for (int i = -1; i <= 1; ++i)
                    if (i || j)
                    {
                        const double n = luma(img, x + i, y + j);
                        above = above && c > n + 16.0;
                        below = below && c < n - 16.0;
                    }
            if (above || below) ++speckles;
            ++d.pixels;
        }
    if (d.pixels)
    {
        d.energy /= double(d.pixels);
        d.speckle = double(speckles) / double(d.pixels);
    }
    return d;
}

std::string filterCacheDir()
{
    const std::string dir = std::string(LOA_TEST_OUTPUT_DIR) + "/filter-cache";
    osgDB::makeDirectory(dir);
    return dir;
}

osg::ref_ptr<osg::Image> styledFrame(const TestScene& scene, const std::string& style,
                                     const std::string& camera, int width, int height, const osg::Vec4& clear,
                                     bool edges)
{
    osg::ref_ptr<UsageScenario> s = homogeneous(style);
    osg::ref_ptr<LoANode> loa = loaNode(scene.model.get(), s.get());
    StylePreparation::Options o;
    o.cacheDir = filterCacheDir();
    o.progress = [](const std::string&) {};
    loa->setStylePreparationOptions(o);
    TransitionRenderer::Settings rs = loa->getRenderer()->getSettings();
    rs.edges = edges;
    loa->getRenderer()->setSettings(rs);
    return renderFrame(loa.get(), scene, camera, width, height, nullptr, clear);
}

/** Texture detail: the abstract style's colour (outlines and G-buffer edges off, so that only
 *  the texture abstraction differs) against photorealistic, both without edges; dots: the whole
 *  abstract style (colour, DoG outlines, edges) against photorealistic with its edges. */
void expectAbstraction(const TestScene& scene, const std::string& camera, int width, int height)
{
    const osg::Vec4 clear(0.62f, 0.75f, 0.90f, 1.0f);
    const std::string name =
        scene.name + "-" + camera + "-" + std::to_string(width) + "x" + std::to_string(height);
    if (!GraphicStyleCatalog::instance().contains("abstract-colour-only"))
    {
        osg::ref_ptr<GraphicStyle> colourOnly = GraphicStyleCatalog::instance().create("abstract");
        colourOnly->setName("abstract-colour-only");
        colourOnly->getParameter("loa_abstract_outlineBlend")->set(0.0f);
        GraphicStyleCatalog::instance().add(*colourOnly);
    }
    osg::ref_ptr<osg::Image> photo =
        styledFrame(scene, "photorealistic", camera, width, height, clear, false);
    osg::ref_ptr<osg::Image> colour =
        styledFrame(scene, "abstract-colour-only", camera, width, height, clear, false);
    osg::ref_ptr<osg::Image> full = styledFrame(scene, "abstract", camera, width, height, clear, true);
    keep(*photo, "abstract-" + name + "-photorealistic");
    keep(*colour, "abstract-" + name + "-colour-only");
    keep(*full, "abstract-" + name + "-abstract");
    const Detail p = detailOf(*photo, *photo, *colour, clear);
    const Detail c = detailOf(*colour, *photo, *colour, clear);
    const Detail a = detailOf(*full, *photo, *full, clear);
    std::cout << "abstract " << name << ": high-frequency energy of the abstracted colour " << c.energy
              << " (photorealistic " << p.energy << ", ratio " << c.energy / p.energy
              << "), with outlines and edges " << a.energy << "; dots " << 100.0 * a.speckle
              << " % (photorealistic " << 100.0 * p.speckle << " %), " << p.pixels << " covered pixels\n";
    ASSERT_GT(p.pixels, (long long)(width)*height / 20)
        << name << ": the scene covers too little of the frame";
    // Bars: the abstracted colour keeps at most 80 % of the photorealistic frame's fine
    // high-frequency energy (measured 53-77 %), the whole style with its outlines and edges less
    // than all of it (measured 60-96 %: the lines are the point of the style); the whole style
    // makes at most twice the photorealistic frame's isolated dots plus 0.05 % of the pixels
    // (per-texel quantization of a raw texture made dots all over textured ground).
    EXPECT_LT(c.energy, 0.8 * p.energy) << name;
    EXPECT_LT(a.energy, p.energy) << name;
    EXPECT_LE(a.speckle, 2.0 * p.speckle + 0.0005) << name;
}
} // namespace

TEST(LoARenderFullFrameGLTest, AbstractStyleRemovesDetailOnTheDemoCity)
{
    const TestScene city = demoCity();
    expectAbstraction(city, "street", 1920, 1080);
    expectAbstraction(city, "oblique", 640, 360);
}

TEST(LoARenderFullFrameGLTest, AbstractStyleRemovesDetailOnRealScenes)
{
    const std::vector<TestScene> scenes = realScenes();
    if (scenes.empty()) GTEST_SKIP() << "no real test scene: run scripts/fetch-test-data";
    for (const TestScene& scene : scenes)
        expectAbstraction(scene, "near", scene.name == "torcs-street-1" ? 1920 : 801,
                          scene.name == "torcs-street-1" ? 1080 : 451);
}

// Prepared once per model: the first preparation filters every texture of the demo city (two
// filtered textures each: colour and outline; 6 facade styles + 8 surface kinds by hand from
// CityTextures) with a progress line, a second preparation of the same model does nothing, and
// a second model with the same textures reads every pyramid from the cache.
TEST(LoARenderFullFrameGLTest, AbstractStyleIsPreparedOncePerModelWithProgress)
{
    const std::string dir = loatest::freshDirectory("filter-cache-once");
    osg::ref_ptr<UsageScenario> abstract = homogeneous("abstract");
    std::vector<std::string> lines;
    StylePreparation::Options o;
    o.cacheDir = dir;
    o.progress = [&](const std::string& l) { lines.push_back(l); };
    ASSERT_EQ(CityTextures::facadeStyles().size(), 6u);
    const unsigned expected = 2u * (6u + 8u);

    osg::ref_ptr<osg::Node> city = CityGenerator(CityParameters()).generate();
    const StylePreparation::Report first = StylePreparation::prepare(*city, *abstract, o);
    ASSERT_EQ(first.styles, std::vector<std::string>{"abstract"});
    EXPECT_EQ(first.abstractTextures, expected);
    EXPECT_EQ(first.abstractFromCache, 0u);
    EXPECT_EQ(first.skipped, 0u);
    ASSERT_GE(lines.size(), 2u);
    EXPECT_NE(lines.front().find("0/" + std::to_string(expected)), std::string::npos) << lines.front();
    EXPECT_NE(lines.back().find(std::to_string(expected) + "/" + std::to_string(expected) + " done"),
              std::string::npos)
        << lines.back();
    EXPECT_EQ(StylePreparation::preparedStyles(*city), std::vector<std::string>{"abstract"});

    lines.clear();
    const StylePreparation::Report again = StylePreparation::prepare(*city, *abstract, o);
    EXPECT_TRUE(again.styles.empty());
    EXPECT_EQ(again.abstractTextures, 0u);
    EXPECT_TRUE(lines.empty());

    osg::ref_ptr<osg::Node> second = CityGenerator(CityParameters()).generate();
    const StylePreparation::Report cached = StylePreparation::prepare(*second, *abstract, o);
    EXPECT_EQ(cached.abstractTextures, expected);
    EXPECT_EQ(cached.abstractFromCache, expected);
}

// ------------------------------------------------------------------------------------------
// Issue 21 item 3: the order-independent transparency methods in the LoA pipeline. The frames of
// the A-buffer path (fuse off, so every feature in transition is routed) with per-pixel linked
// lists equal those of the stencil-routed A-buffer (one sample per pixel: both keep one fragment
// per pixel centre) within the compositing bar, over the whole frame; weighted blended OIT is
// measured (approximate by design) and must still draw every pixel the others draw; auto
// selection tries the exact methods and keeps the cheaper one.
namespace
{
osg::ref_ptr<osg::Image> frameWithOIT(const TestScene& scene, const std::string& scenario,
                                      const std::string& camera, int width, int height, const Viewport* vp,
                                      OrderIndependentTransparency::Method m)
{
    osg::ref_ptr<LoANode> loa = loaNode(scene.model.get(), ScenarioLibrary::createBuiltin(scenario).get());
    TransitionRenderer::Settings rs = loa->getRenderer()->getSettings();
    rs.fuseStyles = false;
    rs.samples = 1;
    rs.maxPasses = 16;
    rs.oit = m;
    loa->getRenderer()->setSettings(rs);
    osg::ref_ptr<osg::Image> f =
        renderFrame(loa.get(), scene, camera, width, height, vp, osg::Vec4(0.2f, 0.3f, 0.4f, 1));
    EXPECT_EQ(loa->getRenderer()->getABuffer()->getMethod(), m);
    EXPECT_GT(loa->getRenderer()->getStatistics().aBufferDraws, 0u) << scene.name << " " << scenario;
    return f;
}

void expectMethodsAgree(const TestScene& scene, const std::string& scenario, const std::string& camera,
                        int width, int height, const Viewport* vp = nullptr)
{
    using OIT = OrderIndependentTransparency;
    const osg::ref_ptr<osg::Image> stencil =
        frameWithOIT(scene, scenario, camera, width, height, vp, OIT::STENCIL_ROUTED);
    const osg::ref_ptr<osg::Image> list =
        frameWithOIT(scene, scenario, camera, width, height, vp, OIT::LINKED_LIST);
    const osg::ref_ptr<osg::Image> weighted =
        frameWithOIT(scene, scenario, camera, width, height, vp, OIT::WEIGHTED_BLENDED);
    const std::string label = scene.name + " " + camera + " " + scenario + " " + std::to_string(width) + "x" +
                              std::to_string(height) + (vp ? " (viewport offset)" : "");
    const auto cmp = ImageComparison::compare(*list, *stencil, 16);
    const EdgeSplit split = compareAwayFromEdges(*list, *stencil);
    const double pixels = double(width) * height;
    std::cout << "linked-list against stencil-routed, " << label << ": " << cmp.summary()
              << "; away from edges " << split.failingAwayFromEdges << "\n";
    EXPECT_TRUE(cmp.sizesMatch && cmp.meanDifference <= 1.0 && split.failingAwayFromEdges <= 0.0005 * pixels)
        << label << ": " << cmp.summary();
    // Weighted blended: nearly the same coverage (few pixels left at the clear colour where the
    // exact frame has content), colours approximate.
    const auto wcmp = ImageComparison::compare(*weighted, *stencil, 16);
    int holes = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
        {
            const unsigned char* s = stencil->data(x, y);
            const unsigned char* w = weighted->data(x, y);
            const bool sClear =
                std::abs(s[0] - 51) <= 1 && std::abs(s[1] - 77) <= 1 && std::abs(s[2] - 102) <= 1;
            const bool wClear =
                std::abs(w[0] - 51) <= 1 && std::abs(w[1] - 77) <= 1 && std::abs(w[2] - 102) <= 1;
            holes += !sClear && wClear;
        }
    std::cout << "weighted-blended against stencil-routed, " << label << ": " << wcmp.summary() << "; "
              << holes << " pixels left at the clear colour\n";
    // Measured: 82-286 such pixels (0.014 % of the frame at 1920x1080 to 0.10 % at 641x359), on
    // building silhouettes against the sky, where the exact methods draw the building
    // (docs/abuffer.md: not explained yet). Bar: 0.2 % of the frame. And it is further from the
    // stencil-routed frame than the linked lists are (it is the approximate one).
    EXPECT_LE(holes, int(0.002 * pixels)) << label;
    EXPECT_GT(wcmp.meanDifference, cmp.meanDifference) << label;
    if (width == 1920 || std::getenv("LOA_KEEP_FRAMES"))
    {
        const std::string file =
            "oit-" + scene.name + "-" + camera + "-" + scenario + "-" + std::to_string(width);
        keep(*stencil, file + "-stencil-routed");
        keep(*list, file + "-linked-list");
        keep(*weighted, file + "-weighted-blended");
    }
}
} // namespace

TEST(LoARenderFullFrameGLTest, OITMethodsAgreeOnTheDemoCity)
{
    const TestScene city = demoCity();
    expectMethodsAgree(city, "distance", "street", 1920, 1080);
    expectMethodsAgree(city, "view-angle", "oblique", 641, 359);
    const Viewport vp{37, 21, 500, 300};
    expectMethodsAgree(city, "route", "oblique", 577, 343, &vp);
}

TEST(LoARenderFullFrameGLTest, OITMethodsAgreeOnRealScenes)
{
    const std::vector<TestScene> scenes = realScenes();
    if (scenes.empty()) GTEST_SKIP() << "no real test scene: run scripts/fetch-test-data";
    for (const TestScene& scene : scenes)
        expectMethodsAgree(scene, "distance", "oblique", 481, 271);
}

// On a renderer whose stencil routing goes by raster coverage (llvmpipe: StencilRoutedABuffer::
// rasterCoverageByDefault), a surface that covers only some samples of a pixel desynchronises the
// samples' stencil counts and a fragment in front can be lost (docs/abuffer.md). On
// opencity-block's street view every building blends (AC3D materials), so the whole city is
// routed: with 4-sample stencil routing the edges of the houses behind the near facade showed as
// bright lines over it. The default A-buffer there is the linked lists (Settings::
// approximateStencilRouting): the facade equals the fixed function's. The left facade is the
// region x < 0.198 W, y 0.463..0.954 H of the frame; "differs" is more than 24/255 in a channel.
TEST(LoARenderFullFrameGLTest, DefaultOITDrawsNoHiddenEdgesOverAFacadeOfARealScene)
{
    const std::vector<TestScene> scenes = realScenes();
    TestScene scene;
    for (const TestScene& t : scenes)
        if (t.name == "opencity-block") scene = t;
    if (!scene.model) GTEST_SKIP() << "opencity-block is not extracted: run scripts/fetch-test-data";
    // The street camera as loa-render computes it for any model (CityCameras), not the framing
    // pose the other real-scene tests use.
    scene.city = true;
    const TestScene* it = &scene;
    const int w = 960, h = 540;
    const osg::Vec4 clear(0.62f, 0.75f, 0.90f, 1.0f);
    osg::ref_ptr<osg::Image> plain = renderFrame(it->model.get(), *it, "street", w, h, nullptr, clear);
    auto frame = [&](bool approximate, OrderIndependentTransparency::Method& used)
    {
        osg::ref_ptr<LoANode> loa =
            loaNode(it->model.get(), ScenarioLibrary::createHomogeneous("photorealistic").get());
        TransitionRenderer::Settings rs = loa->getRenderer()->getSettings();
        rs.approximateStencilRouting = approximate;
        loa->getRenderer()->setSettings(rs);
        osg::ref_ptr<osg::Image> f = renderFrame(loa.get(), *it, "street", w, h, nullptr, clear);
        used = loa->getRenderer()->getOITInUse();
        EXPECT_GT(loa->getRenderer()->getStatistics().aBufferDraws, 10u);
        return f;
    };
    auto differing = [&](const osg::Image& img)
    {
        int n = 0;
        for (int y = int(0.463 * h); y < int(0.954 * h); ++y)
            for (int x = 0; x < int(0.198 * w); ++x)
                for (int c = 0; c < 3; ++c)
                    if (std::abs(int(img.data(x, y)[c]) - int(plain->data(x, y)[c])) > 24)
                    {
                        ++n;
                        break;
                    }
        return n;
    };
    OrderIndependentTransparency::Method byDefault, forced;
    osg::ref_ptr<osg::Image> exact = frame(false, byDefault), stencil = frame(true, forced);
    const bool raster = StencilRoutedABuffer::rasterCoverageByDefault(GLCapabilities::lastQueriedRenderer());
    EXPECT_EQ(byDefault, raster ? OrderIndependentTransparency::LINKED_LIST
                                : OrderIndependentTransparency::STENCIL_ROUTED);
    EXPECT_EQ(forced, OrderIndependentTransparency::STENCIL_ROUTED);
    const int pixels = int(0.198 * w) * (int(0.954 * h) - int(0.463 * h));
    std::cout << "facade pixels differing from the fixed function: default " << differing(*exact)
              << ", stencil-routed " << differing(*stencil) << " of " << pixels << "\n";
    EXPECT_LE(differing(*exact), 2);
    if (raster)
    {
        EXPECT_GT(differing(*stencil), 10)
            << "stencil routing by raster coverage drew the facade exactly: "
               "update docs/abuffer.md and Settings::approximateStencilRouting";
    }
    keep(*exact, "facade-opencity-block-street-default");
    keep(*stencil, "facade-opencity-block-street-stencil-routed");
}

TEST(LoARenderFullFrameGLTest, AutoOITTriesTheExactMethodsAndKeepsTheCheaper)
{
    const std::vector<TestScene> scenes = realScenes();
    const TestScene scene = scenes.empty() ? demoCity() : scenes.front();
    osg::ref_ptr<LoANode> loa = loaNode(scene.model.get(), ScenarioLibrary::createBuiltin("distance").get());
    TransitionRenderer::Settings rs = loa->getRenderer()->getSettings();
    rs.fuseStyles = false;
    rs.oitAuto = true;
    // Both methods: on llvmpipe stencil routing with 4 samples is approximate at silhouettes and
    // would not be tried by default (checked below).
    rs.approximateStencilRouting = true;
    loa->getRenderer()->setSettings(rs);
    OffscreenRenderer::Settings s;
    s.width = 320;
    s.height = 180;
    osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(s);
    r->setSceneData(loa.get());
    const Pose p = poseOf(scene, "oblique", 320.0 / 180.0);
    r->setPerspective(p.fovy);
    r->setViewMatrixAsLookAt(p.eye, p.center, p.up);
    // Trials of 5 measured frames each, one dropped after every switch, results a frame late.
    for (int i = 0; i < 30 && !loa->getRenderer()->getOITSelection().hasChosen(); ++i)
        r->renderImage();
    const OITAutoSelection& sel = loa->getRenderer()->getOITSelection();
    ASSERT_TRUE(sel.hasChosen()) << scene.name;
    ASSERT_EQ(sel.getMedians().size(), 2u);
    EXPECT_GT(sel.getMedians()[0], 0.0);
    EXPECT_GT(sel.getMedians()[1], 0.0);
    const auto cheaper = sel.getMedians()[0] <= sel.getMedians()[1]
                             ? OrderIndependentTransparency::STENCIL_ROUTED
                             : OrderIndependentTransparency::LINKED_LIST;
    r->renderImage();
    EXPECT_EQ(loa->getRenderer()->getABuffer()->getMethod(), cheaper);
    std::cout << scene.name << ": routed passes " << sel.getMedians()[0] << " ms stencil-routed, "
              << sel.getMedians()[1] << " ms linked-list (median GPU time); kept "
              << OrderIndependentTransparency::methodName(cheaper) << "\n";

    // Without approximateStencilRouting, on a renderer that routes by raster coverage, auto tries
    // the exact methods only: the linked lists.
    if (StencilRoutedABuffer::rasterCoverageByDefault(r->getCapabilities()))
    {
        osg::ref_ptr<LoANode> exact =
            loaNode(scene.model.get(), ScenarioLibrary::createBuiltin("distance").get());
        TransitionRenderer::Settings es = exact->getRenderer()->getSettings();
        es.fuseStyles = false;
        es.oitAuto = true;
        exact->getRenderer()->setSettings(es);
        ASSERT_EQ(exact->getRenderer()->getOITSelection().getCandidates().size(), 1u);
        EXPECT_EQ(exact->getRenderer()->getOITSelection().getCandidates()[0],
                  OrderIndependentTransparency::LINKED_LIST);
    }
}
