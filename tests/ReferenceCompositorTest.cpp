// ReferenceCompositor (the CPU reference of the A-buffer resolve) against hand-computed values,
// and the A-buffer memory numbers (ABufferMemory) against the paper's formula (004 §4.3).
#include <osgLoA/compositing/ReferenceCompositor>
#include <osgLoA/compositing/StencilRoutedABuffer>

#include <gtest/gtest.h>

using namespace osgLoA;
using RC = ReferenceCompositor;

namespace
{
RC::Fragment frag(float r, float g, float b, float a, float depth)
{
    RC::Fragment f;
    f.color.set(r, g, b, a);
    f.depth = depth;
    return f;
}

void expectVec(const osg::Vec4f& actual, const osg::Vec4f& expected, const char* what)
{
    for (int i = 0; i < 4; ++i)
        EXPECT_NEAR(actual[i], expected[i], 1e-6f) << what << " channel " << i;
}

const osg::Vec4f kBlue(0.0f, 0.0f, 1.0f, 1.0f);
const RC::Fragment kRedHalfNear = frag(1, 0, 0, 0.5f, 0.2f);
const RC::Fragment kGreenHalfFar = frag(0, 1, 0, 0.5f, 0.6f);
} // namespace

TEST(ReferenceCompositorTest, OneLayer)
{
    const RC rc;
    // mix((0,0,1), (1,0,0), 0.5) = (0.5, 0, 0.5); premultiplied (0.5, 0, 0, 0.5).
    expectVec(rc.compositeOver({kRedHalfNear}, kBlue), osg::Vec4f(0.5f, 0.0f, 0.5f, 1.0f), "over");
    expectVec(rc.composite({kRedHalfNear}), osg::Vec4f(0.5f, 0.0f, 0.0f, 0.5f), "premultiplied");
    expectVec(rc.composite(RC::FragmentList()), osg::Vec4f(0, 0, 0, 0), "no fragment");
    expectVec(rc.compositeOver(RC::FragmentList(), kBlue), kBlue, "no fragment over");
}

TEST(ReferenceCompositorTest, TwoLayersInEitherArrivalOrder)
{
    const RC rc;
    // Far green first: (0, 0.5, 0.5); then near red: (0.5, 0.25, 0.25).
    for (const RC::FragmentList& f :
         {RC::FragmentList{kRedHalfNear, kGreenHalfFar}, RC::FragmentList{kGreenHalfFar, kRedHalfNear}})
    {
        expectVec(rc.compositeOver(f, kBlue), osg::Vec4f(0.5f, 0.25f, 0.25f, 1.0f), "over");
        expectVec(rc.composite(f), osg::Vec4f(0.5f, 0.25f, 0.0f, 0.75f), "premultiplied");
    }
}

TEST(ReferenceCompositorTest, ThreeLayersWithAnOpaqueBack)
{
    const RC rc;
    const RC::FragmentList f = {kGreenHalfFar, frag(0, 0, 1, 1.0f, 0.9f), kRedHalfNear};
    // Blue (opaque) hides the background: (0,0,1) -> green (0, .5, .5) -> red (.5, .25, .25).
    expectVec(rc.compositeOver(f, osg::Vec4f(1, 1, 0, 1)), osg::Vec4f(0.5f, 0.25f, 0.25f, 1.0f), "over");
    expectVec(rc.composite(f), osg::Vec4f(0.5f, 0.25f, 0.25f, 1.0f), "premultiplied");
    // Premultiplied over the background equals the paper's mix chain.
    const osg::Vec4f bg(0.2f, 0.4f, 0.6f, 1.0f);
    const RC::FragmentList g = {kGreenHalfFar, frag(0.3f, 0.1f, 0.9f, 0.25f, 0.9f), kRedHalfNear};
    const osg::Vec4f p = rc.composite(g);
    const osg::Vec4f over = rc.compositeOver(g, bg);
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(p[i] + bg[i] * (1.0f - p.a()), over[i], 1e-6f);
    EXPECT_EQ(rc.layers(g).size(), 3u);
    EXPECT_FLOAT_EQ(rc.layers(g)[0].depth, 0.2f);
    EXPECT_FLOAT_EQ(rc.layers(g)[2].depth, 0.9f);
}

TEST(ReferenceCompositorTest, EqualDepthsMergeIntoOneSurface)
{
    const RC rc(1e-6f);
    const RC::Fragment a = frag(1, 0, 0, 0.5f, 0.5f), b = frag(0, 1, 0, 0.5f, 0.5f);
    // Alpha-weighted mean (0.5, 0.5, 0), alpha 0.5 + 0.5 = 1: no background left.
    ASSERT_EQ(rc.layers({a, b}).size(), 1u);
    expectVec(rc.compositeOver({a, b}, kBlue), osg::Vec4f(0.5f, 0.5f, 0.0f, 1.0f), "merged");
    expectVec(rc.compositeOver({b, a}, kBlue), osg::Vec4f(0.5f, 0.5f, 0.0f, 1.0f), "merged, other order");
    // Unequal weights: (0.2 (1,0,0) + 0.6 (0,0,1)) / 0.8 = (0.25, 0, 0.75), alpha 0.8.
    const RC::FragmentList l = rc.layers({frag(1, 0, 0, 0.2f, 0.5f), frag(0, 0, 1, 0.6f, 0.5f)});
    ASSERT_EQ(l.size(), 1u);
    expectVec(l[0].color, osg::Vec4f(0.25f, 0.0f, 0.75f, 0.8f), "weighted mean");
    // Alphas sum above 1 are capped.
    EXPECT_FLOAT_EQ(rc.layers({frag(1, 0, 0, 0.7f, 0.5f), frag(0, 1, 0, 0.7f, 0.5f)})[0].color.a(), 1.0f);
    // Anchored at the nearest fragment of the surface: 0.5, +0.6e-6 merge; +1.2e-6 does not.
    EXPECT_EQ(rc.layers({frag(1, 0, 0, 0.5f, 0.5f), frag(1, 0, 0, 0.5f, 0.5000006f),
                         frag(1, 0, 0, 0.5f, 0.5000012f)})
                  .size(),
              2u);
}

TEST(ReferenceCompositorTest, NegativeEpsilonIsTheLiteralAlgorithmAndLeaksTheBackground)
{
    const RC literal(-1.0f);
    const RC::Fragment a = frag(1, 0, 0, 0.5f, 0.5f), b = frag(0, 1, 0, 0.5f, 0.5f);
    // A transition at weights 0.5 / 0.5 at one depth. Equal depths keep arrival order [a, b];
    // back to front b then a: (0,0,1) -> (0, .5, .5) -> (.5, .25, .25): 25 % background.
    ASSERT_EQ(literal.layers({a, b}).size(), 2u);
    expectVec(literal.compositeOver({a, b}, kBlue), osg::Vec4f(0.5f, 0.25f, 0.25f, 1.0f), "literal");
    expectVec(literal.composite({a, b}), osg::Vec4f(0.5f, 0.25f, 0.0f, 0.75f), "literal premultiplied");
    // The merged result has no blue at all.
    EXPECT_FLOAT_EQ(RC(0.0f).compositeOver({a, b}, kBlue).b(), 0.0f);
}

TEST(ReferenceCompositorTest, TransparentFragmentsAreDroppedAndArrivalPrefixesKept)
{
    const RC rc;
    const RC::FragmentList f = {frag(1, 1, 1, 0.0f, 0.1f), kRedHalfNear, kGreenHalfFar,
                                frag(0, 0, 1, 0.3f, 0.05f)};
    EXPECT_EQ(rc.layers(f).size(), 3u);
    const RC::FragmentList first2 = RC::firstInArrivalOrder(f, 2); // the transparent one takes no sample
    ASSERT_EQ(first2.size(), 2u);
    EXPECT_FLOAT_EQ(first2[0].depth, 0.2f);
    EXPECT_FLOAT_EQ(first2[1].depth, 0.6f);
    EXPECT_EQ(RC::firstInArrivalOrder(f, 10).size(), 3u);
}

TEST(ReferenceCompositorTest, WholeImages)
{
    RC::FragmentImage img(3, 2);
    img.at(1, 0) = {kRedHalfNear};
    img.at(2, 1) = {kRedHalfNear, kGreenHalfFar};
    const RC rc;
    const std::vector<osg::Vec4f> p = rc.compositePremultiplied(img);
    ASSERT_EQ(p.size(), 6u);
    expectVec(p[1], osg::Vec4f(0.5f, 0, 0, 0.5f), "pixel (1,0)");
    expectVec(p[5], osg::Vec4f(0.5f, 0.25f, 0, 0.75f), "pixel (2,1)");
    const osg::ref_ptr<osg::Image> out = rc.compositeImage(img, kBlue);
    ASSERT_EQ(out->s(), 3);
    ASSERT_EQ(out->t(), 2);
    EXPECT_EQ(int(out->data(0, 0)[2]), 255);
    EXPECT_EQ(int(out->data(1, 0)[0]), 128); // 0.5 * 255 = 127.5 rounds up
    EXPECT_EQ(int(out->data(2, 1)[1]), 64);  // 0.25 * 255 = 63.75
    EXPECT_EQ(int(out->data(2, 1)[3]), 255);
    const RC::FragmentImage one = RC::firstInArrivalOrder(img, 1);
    EXPECT_EQ(one.at(2, 1).size(), 1u);
}

TEST(ReferenceCompositorTest, ABufferMemoryAt1920x1080With8Samples)
{
    // Per sample per layer: RGBA8 colour + DEPTH24_STENCIL8 = 8 bytes (the paper's 2 words).
    EXPECT_EQ(ABufferMemory::kBytesPerSamplePerLayer, 8u);
    const ABufferMemory one = ABufferMemory::of(1920, 1080, 8, 1);
    EXPECT_EQ(one.bytesPerLayer(), 132710400u); // 1920 * 1080 * 8 * 8
    EXPECT_EQ(one.bytes(), 132710400u);
    EXPECT_DOUBLE_EQ(one.megabytes(), 126.5625);
    // The paper: M = W H (2N + 7) / 262144 MB = 2073600 * 23 / 262144.
    EXPECT_DOUBLE_EQ(ABufferMemory::paperMegabytes(1920, 1080, 8), 181.93359375);
    EXPECT_DOUBLE_EQ(ABufferMemory::paperABufferMegabytes(1920, 1080, 8), 126.5625);
    // Three routing passes: three layers.
    EXPECT_EQ(ABufferMemory::of(1920, 1080, 8, 3).bytes(), 398131200u);
    EXPECT_DOUBLE_EQ(ABufferMemory::of(1920, 1080, 8, 3).megabytes(), 379.6875);
}

TEST(ReferenceCompositorTest, StencilPassLimitAndSampleChecks)
{
    // p N + N + 1 <= 255 for the last pass p = limit - 1.
    EXPECT_EQ(StencilRoutedABuffer::stencilPassLimit(1), 254);
    EXPECT_EQ(StencilRoutedABuffer::stencilPassLimit(4), 63);
    EXPECT_EQ(StencilRoutedABuffer::stencilPassLimit(8), 31);
    for (int n : {1, 2, 3, 4, 8, 16, 32})
    {
        const int l = StencilRoutedABuffer::stencilPassLimit(n);
        EXPECT_LE((l - 1) * n + n + 1, 255) << n;
        EXPECT_GT(l * n + n + 1, 255) << n;
    }
    GLCapabilities caps;
    caps.maxSamples = 4;
    caps.maxColorTextureSamples = 4;
    caps.maxDepthTextureSamples = 4;
    EXPECT_EQ(StencilRoutedABuffer::clampSamples(8, caps), 4);
    EXPECT_EQ(StencilRoutedABuffer::clampSamples(2, caps), 2);
    EXPECT_NO_THROW(StencilRoutedABuffer::checkSamples(4, caps));
    EXPECT_THROW(StencilRoutedABuffer::checkSamples(8, caps), std::invalid_argument);
    EXPECT_THROW(StencilRoutedABuffer::checkSamples(0, caps), std::invalid_argument);
}
