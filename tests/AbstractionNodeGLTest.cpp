// AbstractionNode (papers 001, 002) on small synthetic scenes under an orthographic camera that
// maps one scene unit to one pixel: each stage of the frame against a CPU reference computed on
// the plainly rendered frame (Kuwahara, Sobel, the focus levels), hand-computed values (cel
// levels, the toon formula, the focus pixel), the ID pass (silhouettes between objects of the
// same colour, segmentation of the focus object) and the pencil texture's object-space frame.
#include <osgLoA/abstraction/AbstractionFocus>
#include <osgLoA/abstraction/AbstractionFormulas>
#include <osgLoA/abstraction/AbstractionLevelsFilter>
#include <osgLoA/abstraction/AbstractionNode>
#include <osgLoA/abstraction/AbstractionStyle>
#include <osgLoA/abstraction/PencilTextures>
#include <osgLoA/filtering/DoGFilter>
#include <osgLoA/filtering/FilterImage>
#include <osgLoA/filtering/KuwaharaFilter>
#include <osgLoA/filtering/SobelFilter>
#include <osgLoA/render/OffscreenRenderer>

#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <osg/AlphaFunc>
#include <osg/BlendFunc>
#include <osg/Geode>
#include <osg/Geometry>
#include <osg/MatrixTransform>
#include <osg/Texture2D>

#include <cmath>
#include <fstream>
#include <iostream>

using namespace osgLoA;

namespace
{
const int W = 64, H = 48;

/** A noisy RGBA8 texture (few exact ties for Kuwahara), nearest-filtered: the quad below maps
 *  one texel to one pixel, so the rendered frame holds the texels exactly. */
osg::ref_ptr<osg::Texture2D> noiseTexture()
{
    osg::ref_ptr<osg::Image> img = new osg::Image;
    img->allocateImage(W, H, 1, GL_RGBA, GL_UNSIGNED_BYTE);
    unsigned seed = 17;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
        {
            seed = seed * 1664525u + 1013904223u;
            const int n = int((seed >> 24) % 40u);
            unsigned char* p = img->data(x, y);
            const bool dark = (x / 8 + y / 6) % 2 == 0;
            p[0] = static_cast<unsigned char>((dark ? 60 : 190) + n);
            p[1] = static_cast<unsigned char>(100 + n + 2 * x);
            p[2] = static_cast<unsigned char>((x + 3 * y) % 7 < 3 ? 40 + n : 200 - n);
            p[3] = 255;
        }
    osg::ref_ptr<osg::Texture2D> t = new osg::Texture2D(img.get());
    t->setFilter(osg::Texture::MIN_FILTER, osg::Texture::NEAREST);
    t->setFilter(osg::Texture::MAG_FILTER, osg::Texture::NEAREST);
    t->setResizeNonPowerOfTwoHint(false);
    return t;
}

/** An axis-aligned quad [x0, x1] x [y0, y1] at depth z with one colour and one normal. */
osg::ref_ptr<osg::Geometry> quad(float x0, float y0, float x1, float y1, float z, const osg::Vec4& color,
                                 const osg::Vec3& normal = osg::Vec3(0, 0, 1), bool texCoords = false)
{
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    v->push_back(osg::Vec3(x0, y0, z));
    v->push_back(osg::Vec3(x1, y0, z));
    v->push_back(osg::Vec3(x1, y1, z));
    v->push_back(osg::Vec3(x0, y1, z));
    g->setVertexArray(v.get());
    osg::ref_ptr<osg::Vec4Array> c = new osg::Vec4Array(1);
    (*c)[0] = color;
    g->setColorArray(c.get(), osg::Array::BIND_OVERALL);
    osg::ref_ptr<osg::Vec3Array> n = new osg::Vec3Array(1);
    (*n)[0] = normal;
    g->setNormalArray(n.get(), osg::Array::BIND_OVERALL);
    if (texCoords)
    {
        osg::ref_ptr<osg::Vec2Array> t = new osg::Vec2Array;
        t->push_back(osg::Vec2(x0 / W, y0 / H));
        t->push_back(osg::Vec2(x1 / W, y0 / H));
        t->push_back(osg::Vec2(x1 / W, y1 / H));
        t->push_back(osg::Vec2(x0 / W, y1 / H));
        g->setTexCoordArray(0, t.get());
    }
    g->addPrimitiveSet(new osg::DrawArrays(GL_QUADS, 0, 4));
    return g;
}

/** The noise texture over the whole window. */
osg::ref_ptr<osg::Node> texturedScene()
{
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    osg::ref_ptr<osg::Geometry> g = quad(0, 0, W, H, -1, osg::Vec4(1, 1, 1, 1), osg::Vec3(0, 0, 1), true);
    g->getOrCreateStateSet()->setTextureAttributeAndModes(0, noiseTexture().get());
    geode->addDrawable(g.get());
    geode->getOrCreateStateSet()->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
    return geode;
}

/** Two quads of one colour side by side (drawables 1 and 2), a third tilted one (drawable 3). */
osg::ref_ptr<osg::Node> quadsScene()
{
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(quad(4, 8, 24, 40, -1, osg::Vec4(0.8f, 0.6f, 0.4f, 1)).get());
    // Behind the first (a silhouette separates objects where the surface is discontinuous).
    geode->addDrawable(quad(24, 8, 40, 40, -2, osg::Vec4(0.8f, 0.6f, 0.4f, 1)).get());
    osg::Vec3 tilted(0, -1, 1);
    tilted.normalize();
    geode->addDrawable(quad(44, 8, 60, 40, -1, osg::Vec4(0.8f, 0.6f, 0.4f, 1), tilted).get());
    geode->getOrCreateStateSet()->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
    return geode;
}

osg::ref_ptr<OffscreenRenderer> renderer()
{
    OffscreenRenderer::Settings s;
    s.width = W;
    s.height = H;
    s.clearColor = osg::Vec4(0.0f, 0.0f, 0.0f, 1.0f);
    osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(s);
    r->getCamera()->setProjectionMatrixAsOrtho(0, W, 0, H, 0.1, 10);
    r->getCamera()->setViewMatrix(osg::Matrix::identity());
    r->getCamera()->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    return r;
}

osg::ref_ptr<osg::Image> render(osg::Node* scene)
{
    osg::ref_ptr<OffscreenRenderer> r = renderer();
    r->setSceneData(scene);
    return r->renderImage();
}

osg::ref_ptr<osg::Image> renderStyled(osg::Node* content, AbstractionStyle* style,
                                      AbstractionNode::FrameStatistics* stats = nullptr)
{
    osg::ref_ptr<AbstractionNode> node = new AbstractionNode;
    node->setStyle(style);
    node->addChild(content);
    osg::ref_ptr<osg::Image> img = render(node.get());
    EXPECT_EQ(node->getLastError(), "");
    if (stats) *stats = node->getLastFrameStatistics();
    return img;
}

osg::Vec3f pixel(const osg::Image& img, int x, int y)
{
    const unsigned char* p = img.data(x, y);
    return osg::Vec3f(p[0], p[1], p[2]) / 255.0f;
}

/** Fraction of pixels whose RGB differs from the reference by more than tol, and the largest
 *  difference. */
std::pair<double, float> compare(const osg::Image& img, const FilterImage& ref, float tol)
{
    std::size_t over = 0;
    float worst = 0.0f;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
        {
            const osg::Vec3f a = pixel(img, x, y);
            const osg::Vec4f b = ref.get(x, y);
            float d = 0.0f;
            for (int c = 0; c < 3; ++c)
                d = std::max(d, std::fabs(a[c] - std::clamp(b[c], 0.0f, 1.0f)));
            worst = std::max(worst, d);
            over += d > tol;
        }
    return {double(over) / double(W * H), worst};
}

osg::ref_ptr<AbstractionStyle> plainStyle()
{
    osg::ref_ptr<AbstractionStyle> s = new AbstractionStyle;
    s->setName("test");
    return s;
}
} // namespace

TEST(AbstractionNodeGLTest, KuwaharaStylesFilterTheRenderedFrame)
{
    osg::ref_ptr<osg::Node> scene = texturedScene();
    const FilterImage frame = FilterImage::fromImage(*render(scene.get()));
    const ImageBorder clamp(WrapMode::Clamp, WrapMode::Clamp);
    for (const char* name : {"kuwahara3", "kuwahara5"})
    {
        osg::ref_ptr<AbstractionStyle> style = AbstractionStyle::createBuiltin(name);
        AbstractionNode::FrameStatistics st;
        osg::ref_ptr<osg::Image> out = renderStyled(scene.get(), style.get(), &st);
        osg::ref_ptr<KuwaharaFilter> k = new KuwaharaFilter;
        k->setRadius(style->getKuwaharaRadius());
        FilterImage ref = frame;
        for (int i = 0; i < style->getKuwaharaIterations(); ++i)
            ref = k->apply(ref, clamp);
        const auto [fraction, worst] = compare(*out, ref, 1.0f / 255.0f);
        std::cout << name << ": " << fraction * 100.0 << " % of pixels over 1/255, max " << worst * 255.0f
                  << "/255; " << st.passes << " pass(es), " << st.filterRuns << " filter run(s)" << std::endl;
        // The frame is exact (nearest texels), so the GPU filters what the CPU does; 8-bit output
        // rounds by 1/2; sector flips at float near-ties are rare (KuwaharaFiltersGLTest): 0.5 %.
        EXPECT_LE(fraction, 0.005) << name;
        EXPECT_EQ(st.passes, 1u);     // the normal pass only: no ID or shading pass
        EXPECT_EQ(st.filterRuns, 1u); // the Kuwahara levels, no edge detector
        // And it did something: the result is not the frame.
        EXPECT_GT(compare(*out, frame, 4.0f / 255.0f).first, 0.3) << name;
    }
}

TEST(AbstractionNodeGLTest, SobelEdgesAreOverlaidOnTheFrame)
{
    osg::ref_ptr<osg::Node> scene = texturedScene();
    const FilterImage frame = FilterImage::fromImage(*render(scene.get()));
    osg::ref_ptr<AbstractionStyle> style = AbstractionStyle::createBuiltin("sobel");
    style->setSobelThreshold(0.15f);
    osg::ref_ptr<osg::Image> out = renderStyled(scene.get(), style.get());
    const ImageBorder clamp(WrapMode::Clamp, WrapMode::Clamp);
    FilterImage ref = frame;
    std::size_t lines = 0, ambiguous = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
        {
            const float m = SobelFilter::magnitude(frame, x, y, clamp);
            ambiguous += std::fabs(m - 0.15f) < 1e-4f;
            const float e = m >= 0.15f ? 0.0f : 1.0f;
            lines += e == 0.0f;
            const osg::Vec4f c = frame.get(x, y);
            const float a = style->getEdgeOpacity() * (1.0f - e); // overlay with bleaching 0
            ref.set(x, y, osg::Vec4f(c[0] * (1 - a), c[1] * (1 - a), c[2] * (1 - a), 1));
        }
    const auto [fraction, worst] = compare(*out, ref, 1.0f / 255.0f);
    std::cout << "sobel: " << lines << " line pixels, " << fraction * 100.0 << " % over 1/255" << std::endl;
    EXPECT_GT(lines, 100u);
    EXPECT_LE(double(fraction), double(ambiguous) / double(W * H) + 1e-9);
}

TEST(AbstractionNodeGLTest, AbstractionLevelFollowsTheDistanceToTheFocus)
{
    osg::ref_ptr<osg::Node> scene = texturedScene();
    const FilterImage frame = FilterImage::fromImage(*render(scene.get()));
    osg::ref_ptr<AbstractionStyle> style = plainStyle();
    style->setAdaptivity(AbstractionStyle::SCREEN_FOCUS);
    style->setKuwaharaRadius(2);
    style->setKuwaharaIterations(3);
    style->setKuwaharaIterationsFocus(0);
    style->getFocus()->setScreenPoint(osg::Vec2f(0.25f, 0.5f));
    style->getFocus()->setInnerRadius(0.1f);
    style->getFocus()->setOuterRadius(0.6f);
    AbstractionNode::FrameStatistics st;
    osg::ref_ptr<osg::Image> out = renderStyled(scene.get(), style.get(), &st);
    EXPECT_FLOAT_EQ(st.focusPixel.x(), 16.0f);
    EXPECT_FLOAT_EQ(st.focusPixel.y(), 24.0f);
    // CPU: phi from the focus's own function, into alpha, through the levels filter.
    FilterImage withPhi = frame;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
        {
            const float d =
                AbstractionFocus::screenDistance(osg::Vec2f(x + 0.5f, y + 0.5f), st.focusPixel, W, H);
            osg::Vec4f c = withPhi.get(x, y);
            c[3] = style->getFocus()->focusWeight(d);
            withPhi.set(x, y, c);
        }
    osg::ref_ptr<AbstractionLevelsFilter> levels = new AbstractionLevelsFilter;
    const FilterImage ref = levels->apply(withPhi, ImageBorder(WrapMode::Clamp, WrapMode::Clamp));
    const auto [fraction, worst] = compare(*out, ref, 1.0f / 255.0f);
    std::cout << "focus levels: " << fraction * 100.0 << " % over 1/255, max " << worst * 255.0f << "/255"
              << std::endl;
    EXPECT_LE(fraction, 0.01);
    // At the focus (phi = 1 within 0.1 of the diagonal = 8 pixels) the frame is untouched.
    for (int y = 22; y < 27; ++y)
        for (int x = 14; x < 19; ++x)
            EXPECT_EQ(pixel(*out, x, y),
                      osg::Vec3f(frame.get(x, y)[0], frame.get(x, y)[1], frame.get(x, y)[2]));
}

TEST(AbstractionNodeGLTest, SilhouettesSeparateObjectsOfOneColour)
{
    osg::ref_ptr<osg::Node> scene = quadsScene();
    osg::ref_ptr<AbstractionStyle> style = AbstractionStyle::createBuiltin("sobel");
    osg::ref_ptr<osg::Image> noSil = renderStyled(scene.get(), style.get());
    style->setSilhouettes(true);
    AbstractionNode::FrameStatistics st;
    osg::ref_ptr<osg::Image> sil = renderStyled(scene.get(), style.get(), &st);
    EXPECT_EQ(st.passes, 2u); // normal + ID
    // Columns 23 and 24 are the two sides of the boundary between drawables 1 and 2 (one colour):
    // Sobel sees nothing there, the ID pass a one-pixel line on the right side (column 24).
    for (int y = 10; y < 38; ++y)
    {
        EXPECT_GT(pixel(*noSil, 23, y).x(), 0.5f) << y;
        EXPECT_GT(pixel(*noSil, 24, y).x(), 0.5f) << y;
        EXPECT_GT(pixel(*sil, 23, y).x(), 0.5f) << y;
        EXPECT_EQ(pixel(*sil, 24, y), osg::Vec3f(0, 0, 0)) << y;
        EXPECT_GT(pixel(*sil, 14, y).x(), 0.5f) << y; // inside drawable 1: no line
    }
}

// Objects that tile one surface (a game level's terrain pieces: coplanar, touching) meet without
// a silhouette; the same two objects one behind the other get one.
TEST(AbstractionNodeGLTest, SilhouettesSkipObjectsTilingOneSurface)
{
    osg::ref_ptr<osg::Geode> tiles = new osg::Geode;
    tiles->addDrawable(quad(4, 8, 24, 40, -1, osg::Vec4(0.8f, 0.6f, 0.4f, 1)).get());
    tiles->addDrawable(quad(24, 8, 40, 40, -1, osg::Vec4(0.8f, 0.6f, 0.4f, 1)).get());
    tiles->getOrCreateStateSet()->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
    osg::ref_ptr<AbstractionStyle> style = AbstractionStyle::createBuiltin("sobel");
    style->setSilhouettes(true);
    osg::ref_ptr<osg::Image> out = renderStyled(tiles.get(), style.get());
    for (int y = 10; y < 38; ++y)
    {
        EXPECT_GT(pixel(*out, 23, y).x(), 0.5f) << y;
        EXPECT_GT(pixel(*out, 24, y).x(), 0.5f) << y;
        EXPECT_EQ(pixel(*out, 4, y), osg::Vec3f(0, 0, 0)) << y; // against the background: a line
        EXPECT_GT(pixel(*out, 14, y).x(), 0.5f) << y;
    }
}

// An alpha-tested card (a tree billboard): a quad over x in [8, 40] whose texture is transparent
// left of x = 24. The ID pass respects the alpha test, so the silhouette against the background
// runs at x = 24, where the visible part starts, not around the whole quad (the "boxes around
// tree cards" of real scenes); the same holds for a blended card (OSG's ac reader blends RGBA
// textures instead of alpha-testing them).
TEST(AbstractionNodeGLTest, SilhouettesFollowTheAlphaOfCards)
{
    osg::ref_ptr<osg::Image> img = new osg::Image;
    img->allocateImage(W, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE);
    for (int x = 0; x < W; ++x)
    {
        unsigned char* p = img->data(x, 0);
        p[0] = 200, p[1] = 200, p[2] = 200, p[3] = x < 24 ? 0 : 255;
    }
    osg::ref_ptr<osg::Texture2D> tex = new osg::Texture2D(img.get());
    tex->setFilter(osg::Texture::MIN_FILTER, osg::Texture::NEAREST);
    tex->setFilter(osg::Texture::MAG_FILTER, osg::Texture::NEAREST);
    for (const bool blended : {false, true})
    {
        osg::ref_ptr<osg::Geode> card = new osg::Geode;
        osg::ref_ptr<osg::Geometry> g = quad(8, 8, 40, 40, -1, osg::Vec4(1, 1, 1, 1), osg::Vec3(0, 0, 1), true);
        osg::StateSet* ss = g->getOrCreateStateSet();
        ss->setTextureAttributeAndModes(0, tex.get());
        if (blended)
        {
            ss->setAttributeAndModes(new osg::BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA));
            ss->setRenderingHint(osg::StateSet::TRANSPARENT_BIN); // as OSG's readers set it
        }
        else
            ss->setAttributeAndModes(new osg::AlphaFunc(osg::AlphaFunc::GREATER, 0.5f));
        card->addDrawable(g.get());
        // A white wall behind the card: where the card is transparent the wall shows, without a line.
        card->addDrawable(quad(0, 0, W, H, -5, osg::Vec4(1, 1, 1, 1)).get());
        card->getOrCreateStateSet()->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
        osg::ref_ptr<AbstractionStyle> style = AbstractionStyle::createBuiltin("sobel");
        style->setEdgeDetector(AbstractionStyle::NO_EDGES);
        style->setSilhouettes(true);
        osg::ref_ptr<osg::Image> out = renderStyled(card.get(), style.get());
        const std::string what = blended ? "blended card" : "alpha-tested card";
        for (int y = 10; y < 38; ++y)
        {
            EXPECT_GT(pixel(*out, 8, y).x(), 0.9f) << what << ", y " << y; // the wall, no box edge
            EXPECT_GT(pixel(*out, 16, y).x(), 0.9f) << what << ", y " << y;
            EXPECT_EQ(pixel(*out, 24, y), osg::Vec3f(0, 0, 0)) << what << ", y " << y; // the silhouette
            EXPECT_GT(pixel(*out, 30, y).x(), 0.5f) << what << ", y " << y;            // the card
        }
    }
}

TEST(AbstractionNodeGLTest, SegmentationKeepsTheFocusObjectUnabstracted)
{
    // Two textured objects; the focus object 2 (right half) keeps level 0, the rest gets three
    // Kuwahara iterations (radii 0: no distance falloff, only the segmentation).
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    osg::ref_ptr<osg::Texture2D> tex = noiseTexture();
    for (float x0 : {0.0f, 32.0f})
    {
        osg::ref_ptr<osg::Geometry> g =
            quad(x0, 0, x0 + 32, H, -1, osg::Vec4(1, 1, 1, 1), osg::Vec3(0, 0, 1), true);
        g->getOrCreateStateSet()->setTextureAttributeAndModes(0, tex.get());
        geode->addDrawable(g.get());
    }
    geode->getOrCreateStateSet()->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
    const FilterImage frame = FilterImage::fromImage(*render(geode.get()));
    osg::ref_ptr<AbstractionStyle> style = AbstractionStyle::createBuiltin("adaptive-segmented");
    style->setEdgeDetector(AbstractionStyle::NO_EDGES);
    style->setBleaching(0.0f);
    style->getFocus()->setMode(AbstractionFocus::OBJECT);
    style->getFocus()->setObjectId(2);
    style->getFocus()->setInnerRadius(0.0f);
    style->getFocus()->setOuterRadius(0.0f);
    AbstractionNode::FrameStatistics st;
    osg::ref_ptr<osg::Image> out = renderStyled(geode.get(), style.get(), &st);
    EXPECT_EQ(st.focusObject, 1); // index of drawable number 2
    osg::ref_ptr<KuwaharaFilter> k = new KuwaharaFilter;
    k->setRadius(style->getKuwaharaRadius());
    const ImageBorder clamp(WrapMode::Clamp, WrapMode::Clamp);
    FilterImage far = frame;
    for (int i = 0; i < style->getKuwaharaIterations(); ++i)
        far = k->apply(far, clamp);
    std::size_t focusExact = 0, farClose = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
        {
            const osg::Vec3f p = pixel(*out, x, y);
            if (x >= 32)
                focusExact += p == osg::Vec3f(frame.get(x, y)[0], frame.get(x, y)[1], frame.get(x, y)[2]);
            else
                farClose += std::fabs(p.x() - far.get(x, y)[0]) <= 1.0f / 255.0f;
        }
    EXPECT_EQ(focusExact, std::size_t(32 * H));
    EXPECT_GE(double(farClose), 0.99 * 32 * H);
}

TEST(AbstractionNodeGLTest, CelShadingQuantizesTheGouraudShade)
{
    osg::ref_ptr<osg::Node> scene = quadsScene();
    osg::ref_ptr<AbstractionStyle> style = AbstractionStyle::createBuiltin("cel");
    style->setCelLevels(4);
    style->setAmbient(0.35f);
    AbstractionNode::FrameStatistics st;
    osg::ref_ptr<osg::Image> out = renderStyled(scene.get(), style.get(), &st);
    EXPECT_EQ(st.passes, 2u); // unshaded normal + shading
    // Light (0.3, 0.5, 0.8) normalized. Flat quad n = (0, 0, 1): n.l = 0.8 / 0.98995 = 0.80812,
    // s = 0.35 + 0.65 * 0.80812 = 0.87528, k = floor(3.50) = 3, C = 1. Tilted n = (0, -1, 1)/sqrt 2:
    // n.l = 0.3 / 1.4 = 0.21429, s = 0.48929, k = 1, C = 0.5.
    const osg::Vec3f colour(0.8f, 0.6f, 0.4f);
    const osg::Vec3f flat = pixel(*out, 14, 20), tilted = pixel(*out, 52, 20);
    for (int c = 0; c < 3; ++c)
    {
        EXPECT_NEAR(flat[c], colour[c] * 1.0f, 1.0f / 255.0f);
        EXPECT_NEAR(tilted[c], colour[c] * 0.5f, 1.0f / 255.0f);
    }
    EXPECT_FLOAT_EQ(AbstractionFormulas::celQuantize(0.48929f, 4), 0.5f);
    EXPECT_FLOAT_EQ(AbstractionFormulas::celQuantize(0.87528f, 4), 1.0f);
}

TEST(AbstractionNodeGLTest, ToonStyleIsPainterlyTimesSigmaTimesCelTimesEdges)
{
    osg::ref_ptr<osg::Node> scene = quadsScene();
    osg::ref_ptr<AbstractionStyle> style = AbstractionStyle::createBuiltin("hybrid-toon");
    style->setCelLevels(4);
    style->setAmbient(0.35f);
    AbstractionNode::FrameStatistics st;
    osg::ref_ptr<osg::Image> out = renderStyled(scene.get(), style.get(), &st);
    EXPECT_EQ(st.passes, 3u);     // unshaded normal + ID + shading
    EXPECT_EQ(st.filterRuns, 2u); // Kuwahara + Sobel
    // Inside the quads P is the colour (Kuwahara of a constant), E = 1:
    // F = clamp(P 1.5 C): flat C = 1 -> (1, 0.9, 0.6); tilted C = 0.5 -> (0.6, 0.45, 0.3).
    const osg::Vec3f colour(0.8f, 0.6f, 0.4f);
    for (int c = 0; c < 3; ++c)
    {
        EXPECT_NEAR(pixel(*out, 14, 20)[c], AbstractionFormulas::toon(colour, 1.0f, 1.0f, 1.5f)[c],
                    1.0f / 255.0f);
        EXPECT_NEAR(pixel(*out, 52, 20)[c], AbstractionFormulas::toon(colour, 0.5f, 1.0f, 1.5f)[c],
                    1.0f / 255.0f);
    }
    EXPECT_NEAR(pixel(*out, 14, 20).x(), 1.0f, 1e-6f); // clamped
    // The silhouette between the two same-coloured quads is black (E = 0).
    EXPECT_EQ(pixel(*out, 24, 20), osg::Vec3f(0, 0, 0));
}

TEST(AbstractionNodeGLTest, PencilToneIsTheLevelsLayerInObjectCoordinates)
{
    osg::ref_ptr<osg::Node> scene = quadsScene();
    osg::ref_ptr<AbstractionStyle> style = AbstractionStyle::createBuiltin("pencil");
    style->setPencilLevels(4);
    style->setAmbient(0.35f);
    style->setPencilScale(1.0f / 64.0f); // 4 texels per pixel
    osg::ref_ptr<osg::Image> out = renderStyled(scene.get(), style.get());
    // Tilted quad: diffuse n.l = 0.214, level 0 of 4: tone 0.25; flat quad: n.l = 0.808, level 3,
    // white paper 1.0.
    double tilted = 0.0, flat = 0.0;
    int n = 0;
    for (int y = 10; y < 38; ++y)
        for (int x = 46; x < 58; ++x, ++n)
        {
            tilted += pixel(*out, x, y).x();
            flat += pixel(*out, x - 40, y).x();
        }
    tilted /= n;
    flat /= n;
    std::cout << "pencil: mean tone tilted " << tilted << " (target " << PencilTextures::targetTone(0, 4)
              << "), flat " << flat << std::endl;
    // The mean over a 12 x 28 pixel window (48 x 112 of the 256 x 256 texels, mipmapped) follows
    // the layer's mean within the strokes' local variation: 0.08.
    EXPECT_NEAR(tilted, PencilTextures::targetTone(0, 4), 0.08);
    EXPECT_NEAR(flat, PencilTextures::targetTone(3, 4), 0.02);

    // No shower-door effect: moving the object moves its strokes with it. Shift the scene by
    // 3 pixels: the shifted image equals the original, shifted.
    osg::ref_ptr<osg::MatrixTransform> moved = new osg::MatrixTransform(osg::Matrix::translate(3, 0, 0));
    moved->addChild(scene.get());
    // The transform changes model coordinates too; the strokes follow the model, so compare
    // the same object points: pixel (x + 3) of the moved image against pixel x.
    osg::ref_ptr<osg::Image> shifted = renderStyled(moved.get(), style.get());
    int same = 0, total = 0;
    for (int y = 10; y < 38; ++y)
        for (int x = 46; x < 56; ++x, ++total)
            same += std::fabs(pixel(*shifted, x + 3, y).x() - pixel(*out, x, y).x()) <= 1.0f / 255.0f;
    EXPECT_EQ(same, total);
}

TEST(AbstractionNodeGLTest, WorldAndObjectFociProjectToTheirPixels)
{
    osg::ref_ptr<osg::Node> scene = quadsScene();
    osg::ref_ptr<AbstractionStyle> style = AbstractionStyle::createBuiltin("adaptive");
    style->getFocus()->setMode(AbstractionFocus::WORLD_POINT);
    style->getFocus()->setWorldPoint(osg::Vec3d(20, 30, -1));
    AbstractionNode::FrameStatistics st;
    renderStyled(scene.get(), style.get(), &st);
    EXPECT_NEAR(st.focusPixel.x(), 20.0f, 1e-3f);
    EXPECT_NEAR(st.focusPixel.y(), 30.0f, 1e-3f);
    style->getFocus()->setMode(AbstractionFocus::OBJECT);
    style->getFocus()->setObjectId(3); // the tilted quad, centre (52, 24)
    renderStyled(scene.get(), style.get(), &st);
    EXPECT_NEAR(st.focusPixel.x(), 52.0f, 1e-3f);
    EXPECT_NEAR(st.focusPixel.y(), 24.0f, 1e-3f);
    // An id that is not there is an error, not a silently different picture.
    style->getFocus()->setObjectId(99);
    osg::ref_ptr<AbstractionNode> node = new AbstractionNode;
    node->setStyle(style.get());
    node->addChild(scene.get());
    render(node.get());
    EXPECT_NE(node->getLastError().find("99"), std::string::npos) << node->getLastError();
}

TEST(AbstractionNodeGLTest, ViewportOffsetReadsTheNodesOwnTargets)
{
    // The same view in a 54 x 42 window, and in the 54 x 42 viewport at (10, 6) of a 64 x 48 one:
    // the composite reads its viewport-sized targets from the viewport's origin.
    osg::ref_ptr<osg::Node> scene = texturedScene();
    auto view = [&](int ox, int oy, int ww, int wh)
    {
        OffscreenRenderer::Settings s;
        s.width = ww;
        s.height = wh;
        s.clearColor = osg::Vec4(0, 0, 0, 1);
        osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(s);
        r->getCamera()->setViewport(ox, oy, 54, 42);
        r->getCamera()->setProjectionMatrixAsOrtho(0, 54, 0, 42, 0.1, 10);
        r->getCamera()->setViewMatrix(osg::Matrix::identity());
        r->getCamera()->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
        osg::ref_ptr<AbstractionNode> node = new AbstractionNode;
        node->setStyle(AbstractionStyle::createBuiltin("kuwahara3").get());
        node->addChild(scene.get());
        r->setSceneData(node.get());
        return r->renderImage();
    };
    osg::ref_ptr<osg::Image> alone = view(0, 0, 54, 42), offset = view(10, 6, 64, 48);
    int differing = 0;
    for (int y = 0; y < 42; ++y)
        for (int x = 0; x < 54; ++x)
            differing += pixel(*alone, x, y) != pixel(*offset, x + 10, y + 6);
    EXPECT_EQ(differing, 0);
}

TEST(AbstractionNodeGLTest, StyleEditedInPlaceTakesEffectAndIsChecked)
{
    osg::ref_ptr<osg::Node> scene = texturedScene();
    // The references first: two renderers alive at once would share GL object slots (one
    // context id), and the first one's destruction would release the other's objects.
    osg::ref_ptr<AbstractionStyle> five = AbstractionStyle::createBuiltin("kuwahara3");
    five->setKuwaharaRadius(4);
    osg::ref_ptr<osg::Image> fresh = renderStyled(scene.get(), five.get());
    osg::ref_ptr<osg::Image> plain = render(scene.get());

    osg::ref_ptr<AbstractionStyle> style = AbstractionStyle::createBuiltin("kuwahara3");
    osg::ref_ptr<AbstractionNode> node = new AbstractionNode;
    node->setStyle(style.get());
    node->addChild(scene.get());
    osg::ref_ptr<OffscreenRenderer> r = renderer();
    r->setSceneData(node.get());
    osg::ref_ptr<osg::Image> first = r->renderImage();
    style->setKuwaharaRadius(4); // in place, no setStyle
    osg::ref_ptr<osg::Image> second = r->renderImage();
    int changed = 0, same = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
        {
            changed += pixel(*first, x, y) != pixel(*second, x, y);
            same += pixel(*second, x, y) == pixel(*fresh, x, y);
        }
    EXPECT_GT(changed, W * H / 4);
    EXPECT_EQ(same, W * H);
    // An impossible value set in place is reported and the children are drawn unabstracted.
    style->setKuwaharaIterations(7);
    osg::ref_ptr<osg::Image> refused = r->renderImage();
    EXPECT_NE(node->getLastError().find("kuwaharaIterations"), std::string::npos) << node->getLastError();
    int plainSame = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            plainSame += pixel(*refused, x, y) == pixel(*plain, x, y);
    EXPECT_EQ(plainSame, W * H);
    // Fixed again: the error clears.
    style->setKuwaharaIterations(1);
    r->renderImage();
    EXPECT_EQ(node->getLastError(), "");
}

TEST(AbstractionNodeGLTest, AFailedImageStageShowsTheNormalFrame)
{
    // A broken levels shader on OSG_FILE_PATH: the engine cannot build the pass. The error is
    // reported and the frame is the normal pass, not undefined texels.
    const std::string dir = loatest::freshDirectory("AbstractionBrokenShader");
    std::ofstream(dir + "/loa_filter_abstraction_levels.comp.glsl") << "#version 430\nthis is not GLSL\n";
    loatest::setFilePath(dir);
    osg::ref_ptr<osg::Node> scene = texturedScene();
    osg::ref_ptr<AbstractionStyle> style = AbstractionStyle::createBuiltin("adaptive");
    style->setEdgeDetector(AbstractionStyle::NO_EDGES);
    style->setBleaching(0.0f);
    osg::ref_ptr<AbstractionNode> node = new AbstractionNode;
    node->setStyle(style.get());
    node->addChild(scene.get());
    osg::ref_ptr<osg::Image> out = render(node.get());
    loatest::setFilePath("");
    EXPECT_NE(node->getLastError().find("loa_filter_abstraction_levels"), std::string::npos)
        << node->getLastError();
    osg::ref_ptr<osg::Image> plain = render(scene.get());
    int same = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            same += pixel(*out, x, y) == pixel(*plain, x, y);
    EXPECT_EQ(same, W * H);
}

TEST(AbstractionNodeGLTest, DoGEdgesOfTheFrameMatchTheCpuFilter)
{
    osg::ref_ptr<osg::Node> scene = texturedScene();
    const FilterImage frame = FilterImage::fromImage(*render(scene.get()));
    osg::ref_ptr<AbstractionStyle> style = AbstractionStyle::createBuiltin("dog");
    osg::ref_ptr<osg::Image> out = renderStyled(scene.get(), style.get());
    osg::ref_ptr<DoGFilter> dog = new DoGFilter;
    dog->setFlow(false);
    dog->setSigmaE(style->getDogSigma());
    dog->setK(style->getDogRatio());
    dog->setTau(style->getDogTau());
    dog->setEpsilon(style->getDogEpsilon());
    dog->setMode(DoGFilter::EDGES);
    EXPECT_FLOAT_EQ(style->getDogRatio(), 1.6f); // the Marr-Hildreth ratio of paper 001
    const FilterImage edges = dog->apply(frame, ImageBorder(WrapMode::Clamp, WrapMode::Clamp));
    FilterImage ref = frame;
    std::size_t lines = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
        {
            const osg::Vec3f c = AbstractionFormulas::overlay(
                osg::Vec3f(frame.get(x, y)[0], frame.get(x, y)[1], frame.get(x, y)[2]), edges.get(x, y)[0],
                style->getEdgeOpacity(), 0.0f);
            lines += edges.get(x, y)[0] < 0.5f;
            ref.set(x, y, osg::Vec4f(c, 1.0f));
        }
    const auto [fraction, worst] = compare(*out, ref, 2.0f / 255.0f);
    std::cout << "dog: " << lines << " line pixels, " << fraction * 100.0 << " % over 2/255, max "
              << worst * 255.0f << "/255" << std::endl;
    EXPECT_GT(lines, 50u);
    // The DoG's tanh threshold is steep (phi 2 per L* unit): float differences of 1e-5 in L*
    // move a pixel on it by at most 1e-4 of grey; 2/255 leaves room for 8-bit output rounding.
    EXPECT_LE(fraction, 0.002);
}

TEST(AbstractionNodeGLTest, HybridPencilIsPainterlyTimesPencilToneToTheGamma)
{
    // Constant-coloured quads: P is the colour inside them (Kuwahara of a constant); S is what
    // the pencil style shows. F = P S^2 per pixel (paper 002 Eq. 2).
    osg::ref_ptr<osg::Node> scene = quadsScene();
    osg::ref_ptr<AbstractionStyle> pencil = AbstractionStyle::createBuiltin("pencil");
    osg::ref_ptr<AbstractionStyle> hybrid = AbstractionStyle::createBuiltin("hybrid-pencil");
    for (AbstractionStyle* s : {pencil.get(), hybrid.get()})
        s->setPencilScale(1.0f / 64.0f);
    osg::ref_ptr<osg::Image> S = renderStyled(scene.get(), pencil.get()),
                             F = renderStyled(scene.get(), hybrid.get());
    const osg::Vec3f colour(0.8f, 0.6f, 0.4f);
    int checked = 0, within = 0;
    for (int y = 12; y < 36; ++y)
        for (int x = 48; x < 56; ++x, ++checked) // inside the tilted quad, away from its edges
        {
            const osg::Vec3f expected = AbstractionFormulas::pencilSketch(colour, pixel(*S, x, y).x(), 2.0f);
            bool ok = true;
            for (int c = 0; c < 3; ++c)
                ok = ok && std::fabs(pixel(*F, x, y)[c] - expected[c]) <= 2.0f / 255.0f;
            within += ok;
        }
    EXPECT_EQ(within, checked);
}
