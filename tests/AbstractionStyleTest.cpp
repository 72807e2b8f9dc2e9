// Abstraction focus and styles (papers 001, 002): the focus weight phi = 1 - smoothstep(inner,
// outer, d) with screen and object-space distances, the per-pixel parameters of the adaptive
// built-ins at phi = 0, 0.5, 1 (hand-computed), validate() refusing each bad field by name, the
// built-ins, copies, and write-read-write round trips of a modified style with its focus.
#include "support/TestSupport.h"

#include <osgLoA/abstraction/AbstractionFocus>
#include <osgLoA/abstraction/AbstractionStyle>

#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>

using namespace osgLoA;

namespace
{
std::string fileBytes(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/** The message of the invalid_argument validate() throws, or "" when it does not throw. */
std::string refusal(const std::function<void()>& f)
{
    try
    {
        f();
    }
    catch (const std::invalid_argument& e)
    {
        return e.what();
    }
    return "";
}
} // namespace

TEST(AbstractionFocusTest, SmoothstepAndFocusWeightAtTheRadii)
{
    EXPECT_FLOAT_EQ(AbstractionFocus::smoothstep(0.0f, 1.0f, 0.5f), 0.5f);
    EXPECT_FLOAT_EQ(AbstractionFocus::smoothstep(0.0f, 1.0f, 0.25f), 0.15625f); // 0.0625 * 2.5
    EXPECT_FLOAT_EQ(AbstractionFocus::smoothstep(0.0f, 1.0f, -3.0f), 0.0f);
    EXPECT_FLOAT_EQ(AbstractionFocus::smoothstep(0.0f, 1.0f, 7.0f), 1.0f);
    EXPECT_FLOAT_EQ(AbstractionFocus::smoothstep(0.2f, 0.2f, 0.1f), 0.0f);
    EXPECT_FLOAT_EQ(AbstractionFocus::smoothstep(0.2f, 0.2f, 0.2f), 1.0f);

    osg::ref_ptr<AbstractionFocus> f = new AbstractionFocus; // inner 0.1, outer 0.5
    EXPECT_EQ(f->getMode(), AbstractionFocus::SCREEN_POINT);
    EXPECT_EQ(f->getScreenPoint(), osg::Vec2f(0.5f, 0.5f));
    EXPECT_FLOAT_EQ(f->getInnerRadius(), 0.1f);
    EXPECT_FLOAT_EQ(f->getOuterRadius(), 0.5f);
    EXPECT_FLOAT_EQ(f->focusWeight(0.0f), 1.0f);
    EXPECT_FLOAT_EQ(f->focusWeight(0.1f), 1.0f);     // inner
    EXPECT_FLOAT_EQ(f->focusWeight(0.3f), 0.5f);     // midpoint
    EXPECT_FLOAT_EQ(f->focusWeight(0.2f), 0.84375f); // t = 0.25: 1 - 0.15625
    EXPECT_FLOAT_EQ(f->focusWeight(0.5f), 0.0f);     // outer
    EXPECT_FLOAT_EQ(f->focusWeight(2.0f), 0.0f);
    EXPECT_FLOAT_EQ(f->focusWeight(std::numeric_limits<float>::quiet_NaN()), 0.0f);
    f->setInnerRadius(0.2f);
    f->setOuterRadius(0.2f);
    EXPECT_FLOAT_EQ(f->focusWeight(0.1f), 1.0f);
    EXPECT_FLOAT_EQ(f->focusWeight(0.2f), 0.0f);
    EXPECT_FLOAT_EQ(f->focusWeight(0.3f), 0.0f);
}

TEST(AbstractionFocusTest, ScreenDistanceAndObjectImportance)
{
    // 100 x 100: the diagonal is 100 sqrt(2); the focus point (0.5, 0.5) is pixel (50, 50).
    osg::ref_ptr<AbstractionFocus> f = new AbstractionFocus;
    const osg::Vec2f fp = f->focusPixel(100, 100);
    EXPECT_EQ(fp, osg::Vec2f(50.0f, 50.0f));
    EXPECT_NEAR(AbstractionFocus::screenDistance(osg::Vec2f(50.5f, 50.5f), fp, 100, 100), 0.005f, 1e-7f);
    EXPECT_NEAR(AbstractionFocus::screenDistance(osg::Vec2f(0.5f, 0.5f), fp, 100, 100), 0.495f, 1e-6f);
    EXPECT_NEAR(AbstractionFocus::screenDistance(osg::Vec2f(100.0f, 50.0f), fp, 100, 100), 0.35355339f,
                1e-6f);
    EXPECT_NEAR(AbstractionFocus::screenDistance(osg::Vec2f(0.0f, 0.0f), osg::Vec2f(40.0f, 30.0f), 80, 60),
                0.5f,
                1e-7f); // 50 / 100
    EXPECT_NE(refusal(
                  [] {
                      AbstractionFocus::screenDistance({0, 0}, {0, 0}, 0, 10);
                  })
                  .find("width"),
              std::string::npos);
    EXPECT_NE(refusal(
                  [] {
                      AbstractionFocus::screenDistance({0, 0}, {0, 0}, 10, -1);
                  })
                  .find("height"),
              std::string::npos);

    // Scene diameter 100: distances 0.05, 0.3 and 0.6 diameters.
    const osg::Vec3d focus(10.0, 20.0, 30.0);
    EXPECT_FLOAT_EQ(f->objectImportance(focus + osg::Vec3d(0, 0, 5), focus, 100.0), 1.0f);
    EXPECT_FLOAT_EQ(f->objectImportance(focus + osg::Vec3d(18, 24, 0), focus, 100.0), 0.5f); // |(18,24)| = 30
    EXPECT_FLOAT_EQ(f->objectImportance(focus + osg::Vec3d(0, 60, 0), focus, 100.0), 0.0f);
    EXPECT_FLOAT_EQ(f->objectImportance(focus, focus, 0.0), 1.0f);
    EXPECT_FLOAT_EQ(f->objectImportance(focus + osg::Vec3d(1, 0, 0), focus, 0.0), 0.0f);
    EXPECT_FLOAT_EQ(f->objectImportance(focus + osg::Vec3d(1, 0, 0), focus, -4.0), 0.0f);
}

TEST(AbstractionFocusTest, ValidateRefusesBadRadii)
{
    const float nan = std::numeric_limits<float>::quiet_NaN();
    struct Case
    {
        std::function<void(AbstractionFocus&)> set;
        const char* field;
    };
    const Case cases[] = {
        {[](AbstractionFocus& f) { f.setInnerRadius(-0.1f); }, "innerRadius"},
        {[&](AbstractionFocus& f) { f.setInnerRadius(nan); }, "innerRadius"},
        {[](AbstractionFocus& f) { f.setOuterRadius(-1.0f); }, "outerRadius"},
        {[&](AbstractionFocus& f) { f.setOuterRadius(nan); }, "outerRadius"},
        {[](AbstractionFocus& f) { f.setInnerRadius(0.6f); }, "innerRadius 0.600000 is above outerRadius"},
        {[](AbstractionFocus& f) { f.setMode(AbstractionFocus::Mode(3)); }, "mode"},
        {[&](AbstractionFocus& f) { f.setScreenPoint(osg::Vec2f(nan, 0)); }, "screenPoint"},
    };
    EXPECT_EQ(refusal(
                  []
                  {
                      osg::ref_ptr<AbstractionFocus> f = new AbstractionFocus;
                      f->validate();
                  }),
              "");
    for (const Case& c : cases)
    {
        osg::ref_ptr<AbstractionFocus> f = new AbstractionFocus;
        c.set(*f);
        const std::string m = refusal([&] { f->validate(); });
        EXPECT_NE(m.find(c.field), std::string::npos) << c.field << ": '" << m << "'";
    }
}

TEST(AbstractionStyleTest, DefaultsAndQueries)
{
    osg::ref_ptr<AbstractionStyle> s = new AbstractionStyle;
    EXPECT_NO_THROW(s->validate());
    EXPECT_EQ(s->getNormalPass(), AbstractionStyle::LIT);
    EXPECT_EQ(s->getCelLevels(), 4);
    EXPECT_FLOAT_EQ(s->getDogRatio(), 1.6f);
    EXPECT_FLOAT_EQ(s->getEdgeOpacityFar(), 0.2f);
    EXPECT_EQ(s->getCelLevelsFar(), 8);
    EXPECT_FALSE(s->needsIdPass());
    EXPECT_FALSE(s->needsShadingPass());
    EXPECT_FALSE(s->needsPainterly());
    EXPECT_FALSE(s->needsEdges());
    s->setSilhouettes(true);
    EXPECT_TRUE(s->needsIdPass());
    EXPECT_TRUE(s->needsEdges());
    s->setSilhouettes(false);
    s->setAdaptivity(AbstractionStyle::OBJECT_FOCUS);
    EXPECT_TRUE(s->needsIdPass());
    EXPECT_FALSE(s->needsEdges());
    s->setShading(AbstractionStyle::PENCIL);
    EXPECT_TRUE(s->needsShadingPass());
    s->setKuwaharaRadius(1);
    EXPECT_TRUE(s->needsPainterly());

    ASSERT_TRUE(s->getFocus());
    s->setFocus(nullptr);
    ASSERT_TRUE(s->getFocus());
    EXPECT_FLOAT_EQ(s->getFocus()->getOuterRadius(), 0.5f);

    // Copies: shallow shares the focus, DEEP_COPY_OBJECTS clones it.
    s->getFocus()->setObjectId(7);
    osg::ref_ptr<AbstractionStyle> shallow = new AbstractionStyle(*s);
    osg::ref_ptr<AbstractionStyle> deep = new AbstractionStyle(*s, osg::CopyOp::DEEP_COPY_OBJECTS);
    EXPECT_EQ(shallow->getFocus(), s->getFocus());
    EXPECT_NE(deep->getFocus(), s->getFocus());
    EXPECT_EQ(deep->getFocus()->getObjectId(), 7u);
    EXPECT_EQ(deep->getShading(), AbstractionStyle::PENCIL);
    EXPECT_EQ(deep->getKuwaharaRadius(), 1);
}

TEST(AbstractionStyleTest, PixelParametersOfTheAdaptiveBuiltins)
{
    // "adaptive": SCREEN_FOCUS, iterations 3 far / 0 at the focus, edge opacity 0.1 far / 1,
    // bleaching 0.6. Cel levels, Sobel threshold and shading share are not adaptive.
    osg::ref_ptr<AbstractionStyle> a = AbstractionStyle::createBuiltin("adaptive");
    struct Expect
    {
        float phi, lambda, edge, bleach, sobel, share;
        int cel;
    };
    const Expect screen[] = {{0.0f, 3.0f, 0.1f, 0.6f, 0.2f, 1.0f, 4},
                             {0.5f, 1.5f, 0.55f, 0.3f, 0.2f, 1.0f, 4},
                             {1.0f, 0.0f, 1.0f, 0.0f, 0.2f, 1.0f, 4}};
    for (const Expect& e : screen)
    {
        const AbstractionStyle::PixelParameters p = a->pixelParameters(e.phi);
        EXPECT_FLOAT_EQ(p.lambda, e.lambda) << e.phi;
        EXPECT_FLOAT_EQ(p.edgeOpacity, e.edge) << e.phi;
        EXPECT_FLOAT_EQ(p.bleach, e.bleach) << e.phi;
        EXPECT_FLOAT_EQ(p.sobelThreshold, e.sobel) << e.phi;
        EXPECT_FLOAT_EQ(p.shadingShare, e.share) << e.phi;
        EXPECT_EQ(p.celLevels, e.cel) << e.phi;
    }
    // "adaptive-hybrid-toon": OBJECT_FOCUS, iterations 2 far / 1 at the focus, cel levels 8 far /
    // 3 at the focus (mix 5.5 rounds to 6), Sobel 0.4 far / 0.1, share 1 far / 0.5, edge
    // opacity 1 everywhere, no bleaching.
    osg::ref_ptr<AbstractionStyle> t = AbstractionStyle::createBuiltin("adaptive-hybrid-toon");
    const Expect object[] = {{0.0f, 2.0f, 1.0f, 0.0f, 0.4f, 1.0f, 8},
                             {0.5f, 1.5f, 1.0f, 0.0f, 0.25f, 0.75f, 6},
                             {1.0f, 1.0f, 1.0f, 0.0f, 0.1f, 0.5f, 3}};
    for (const Expect& e : object)
    {
        const AbstractionStyle::PixelParameters p = t->pixelParameters(e.phi);
        EXPECT_FLOAT_EQ(p.lambda, e.lambda) << e.phi;
        EXPECT_FLOAT_EQ(p.edgeOpacity, e.edge) << e.phi;
        EXPECT_FLOAT_EQ(p.bleach, e.bleach) << e.phi;
        EXPECT_FLOAT_EQ(p.sobelThreshold, e.sobel) << e.phi;
        EXPECT_FLOAT_EQ(p.shadingShare, e.share) << e.phi;
        EXPECT_EQ(p.celLevels, e.cel) << e.phi;
    }
    // phi outside [0, 1] is clamped; UNIFORM ignores phi (strongest level everywhere).
    EXPECT_FLOAT_EQ(t->pixelParameters(4.0f).lambda, 1.0f);
    EXPECT_FLOAT_EQ(t->pixelParameters(-1.0f).lambda, 2.0f);
    EXPECT_FLOAT_EQ(t->pixelParameters(std::numeric_limits<float>::quiet_NaN()).lambda, 2.0f);
    osg::ref_ptr<AbstractionStyle> k = AbstractionStyle::createBuiltin("kuwahara-dog");
    k->setKuwaharaIterations(3);
    k->setBleaching(0.4f);
    EXPECT_FLOAT_EQ(k->pixelParameters(1.0f).lambda, 3.0f);
    EXPECT_FLOAT_EQ(k->pixelParameters(1.0f).bleach, 0.4f);
}

TEST(AbstractionStyleTest, BuiltinsCreateAndValidate)
{
    ASSERT_EQ(AbstractionStyle::builtinNames().size(), 14u);
    for (const std::string& name : AbstractionStyle::builtinNames())
    {
        osg::ref_ptr<AbstractionStyle> s = AbstractionStyle::createBuiltin(name);
        ASSERT_TRUE(s.valid()) << name;
        EXPECT_EQ(s->getName(), name);
        EXPECT_FALSE(s->getDescription().empty()) << name;
        EXPECT_NO_THROW(s->validate()) << name;
    }
    EXPECT_NE(refusal([] { AbstractionStyle::createBuiltin("watercolour"); }).find("watercolour"),
              std::string::npos);

    osg::ref_ptr<AbstractionStyle> s = AbstractionStyle::createBuiltin("dog");
    EXPECT_EQ(s->getEdgeDetector(), AbstractionStyle::DOG);
    EXPECT_EQ(s->getEdgeSource(), AbstractionStyle::NORMAL_IMAGE);
    EXPECT_FALSE(s->needsPainterly());
    EXPECT_EQ(AbstractionStyle::createBuiltin("kuwahara3")->getKuwaharaRadius(), 2);
    EXPECT_EQ(AbstractionStyle::createBuiltin("kuwahara5")->getKuwaharaRadius(), 4);
    s = AbstractionStyle::createBuiltin("adaptive-segmented");
    EXPECT_TRUE(s->getSegmentation());
    EXPECT_TRUE(s->needsIdPass());
    EXPECT_EQ(s->getFocus()->getMode(), AbstractionFocus::OBJECT);
    EXPECT_FLOAT_EQ(s->getBleaching(), 0.6f);
    s = AbstractionStyle::createBuiltin("cel");
    EXPECT_EQ(s->getNormalPass(), AbstractionStyle::UNSHADED);
    EXPECT_EQ(s->getCombination(), AbstractionStyle::SHADING_ONLY);
    s = AbstractionStyle::createBuiltin("hybrid-toon");
    EXPECT_EQ(s->getShading(), AbstractionStyle::CEL);
    EXPECT_EQ(s->getCombination(), AbstractionStyle::TOON);
    EXPECT_EQ(s->getEdgeDetector(), AbstractionStyle::SOBEL);
    EXPECT_TRUE(s->getSilhouettes());
    EXPECT_FLOAT_EQ(s->getBrightening(), 1.5f);
    s = AbstractionStyle::createBuiltin("adaptive-hybrid-pencil");
    EXPECT_EQ(s->getShading(), AbstractionStyle::PENCIL);
    EXPECT_EQ(s->getCombination(), AbstractionStyle::PENCIL_SKETCH);
    EXPECT_EQ(s->getEdgeDetector(), AbstractionStyle::NO_EDGES);
    EXPECT_FALSE(s->needsEdges());
    EXPECT_EQ(s->getAdaptivity(), AbstractionStyle::OBJECT_FOCUS);
    EXPECT_EQ(s->getFocus()->getMode(), AbstractionFocus::OBJECT);
    EXPECT_FLOAT_EQ(s->getPencilGamma(), 2.0f);
    // Each built-in has its own focus.
    EXPECT_NE(AbstractionStyle::createBuiltin("adaptive")->getFocus(),
              AbstractionStyle::createBuiltin("adaptive")->getFocus());
}

TEST(AbstractionStyleTest, ValidateRefusesEachBadField)
{
    typedef AbstractionStyle S;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    struct Case
    {
        std::function<void(S&)> set;
        const char* field;
    };
    const Case cases[] = {
        {[](S& s) { s.setNormalPass(S::NormalPass(2)); }, "normalPass"},
        {[](S& s) { s.setShading(S::Shading(3)); }, "shading"},
        {[](S& s) { s.setCelLevels(1); }, "celLevels"},
        {[](S& s) { s.setCelLevels(17); }, "celLevels"},
        {[](S& s) { s.setPencilLevels(9); }, "pencilLevels"},
        {[](S& s) { s.setAmbient(1.5f); }, "ambient"},
        {[](S& s) { s.setPencilScale(0.0f); }, "pencilScale"},
        {[](S& s) { s.setPencilScale(65.0f); }, "pencilScale"},
        {[](S& s) { s.setPencilAnisotropy(0.5f); }, "pencilAnisotropy"},
        {[](S& s) { s.setPencilAnisotropy(17.0f); }, "pencilAnisotropy"},
        {[](S& s) { s.setKuwaharaRadius(-1); }, "kuwaharaRadius"},
        {[](S& s) { s.setKuwaharaRadius(17); }, "kuwaharaRadius"},
        {[](S& s) { s.setKuwaharaIterations(0); }, "kuwaharaIterations"},
        {[](S& s) { s.setKuwaharaIterations(4); }, "kuwaharaIterations"},
        {[](S& s) { s.setKuwaharaIterationsFocus(2); }, "kuwaharaIterationsFocus"}, // above iterations 1
        {[](S& s) { s.setKuwaharaIterationsFocus(-1); }, "kuwaharaIterationsFocus"},
        {[](S& s) { s.setEdgeDetector(S::EdgeDetector(4)); }, "edgeDetector"},
        {[](S& s) { s.setEdgeSource(S::EdgeSource(-1)); }, "edgeSource"},
        {[](S& s) { s.setDogSigma(0.0f); }, "dogSigma"},
        {[](S& s) { s.setDogRatio(1.0f); }, "dogRatio"},
        {[](S& s) { s.setDogRatio(4.5f); }, "dogRatio"},
        {[](S& s) { s.setDogTau(1.01f); }, "dogTau"},
        {[](S& s) { s.setSobelThreshold(0.0f); }, "sobelThreshold"},
        {[](S& s) { s.setSobelThresholdFar(5.0f); }, "sobelThresholdFar"},
        {[](S& s) { s.setCannyLow(-0.1f); }, "cannyLow"},
        {[](S& s) { s.setCannyHigh(4.5f); }, "cannyHigh"},
        {[](S& s) { s.setCannyLow(0.3f); }, "cannyLow 0.300000 is above cannyHigh"},
        {[&](S& s) { s.setEdgeOpacity(nan); }, "edgeOpacity"},
        {[](S& s) { s.setEdgeOpacityFar(-0.5f); }, "edgeOpacityFar"},
        {[](S& s) { s.setCombination(S::Combination(4)); }, "combination"},
        {[](S& s) { s.setBrightening(4.5f); }, "brightening"},
        {[](S& s) { s.setPencilGamma(0.05f); }, "pencilGamma"},
        {[](S& s) { s.setAdaptivity(S::Adaptivity(3)); }, "adaptivity"},
        {[](S& s) { s.setBleaching(1.5f); }, "bleaching"},
        {[](S& s) { s.setCelLevelsFar(1); }, "celLevelsFar"},
        {[](S& s) { s.setShadingAtFocus(-0.1f); }, "shadingAtFocus"},
        {[](S& s) { s.getFocus()->setInnerRadius(-1.0f); }, "AbstractionFocus: innerRadius"},
    };
    for (const Case& c : cases)
    {
        osg::ref_ptr<S> s = new S;
        c.set(*s);
        const std::string m = refusal([&] { s->validate(); });
        // "AbstractionStyle: FIELD " so that celLevels does not match celLevelsFar's message.
        const std::string want = std::string(c.field).find(':') == std::string::npos
                                     ? std::string("AbstractionStyle: ") + c.field + " "
                                     : std::string(c.field);
        EXPECT_NE(m.find(want), std::string::npos) << c.field << ": '" << m << "'";
    }
    // The boundaries themselves are accepted.
    osg::ref_ptr<S> s = new S;
    s->setCelLevels(16);
    s->setPencilLevels(2);
    s->setPencilScale(64.0f);
    s->setKuwaharaRadius(16);
    s->setKuwaharaIterations(3);
    s->setKuwaharaIterationsFocus(3);
    s->setDogRatio(4.0f);
    s->setDogTau(0.0f);
    s->setCannyLow(0.2f);
    s->setPencilGamma(0.1f);
    s->setBrightening(0.0f);
    EXPECT_NO_THROW(s->validate());
}

TEST(AbstractionStyleTest, ModifiedStyleSurvivesOsgtAndOsgbRoundTrips)
{
    const std::string dir = loatest::freshDirectory("AbstractionStyleTest");
    osg::ref_ptr<AbstractionStyle> s = new AbstractionStyle;
    s->setName("mine");
    s->setDescription("every field changed");
    s->setNormalPass(AbstractionStyle::UNSHADED);
    s->setShading(AbstractionStyle::PENCIL);
    s->setCelLevels(5);
    s->setPencilLevels(6);
    s->setAmbient(0.25f);
    s->setPencilScale(3.5f);
    s->setPencilAnisotropy(8.0f);
    s->setKuwaharaRadius(3);
    s->setKuwaharaIterations(3);
    s->setKuwaharaIterationsFocus(2);
    s->setEdgeDetector(AbstractionStyle::CANNY);
    s->setEdgeSource(AbstractionStyle::NORMAL_IMAGE);
    s->setDogSigma(1.5f);
    s->setDogRatio(2.0f);
    s->setDogTau(0.95f);
    s->setSobelThreshold(0.3f);
    s->setSobelThresholdFar(0.7f);
    s->setCannyLow(0.05f);
    s->setCannyHigh(0.4f);
    s->setSilhouettes(true);
    s->setEdgeOpacity(0.75f);
    s->setEdgeOpacityFar(0.125f);
    s->setCombination(AbstractionStyle::PENCIL_SKETCH);
    s->setBrightening(1.25f);
    s->setPencilGamma(3.0f);
    s->setAdaptivity(AbstractionStyle::OBJECT_FOCUS);
    s->setSegmentation(true);
    s->setBleaching(0.5f);
    s->setCelLevelsFar(12);
    s->setShadingAtFocus(0.375f);
    AbstractionFocus* f = s->getFocus();
    f->setName("focus");
    f->setMode(AbstractionFocus::WORLD_POINT);
    f->setScreenPoint(osg::Vec2f(0.25f, 0.75f));
    f->setWorldPoint(osg::Vec3d(12.5, -3.25, 100.0));
    f->setObjectId(42);
    f->setInnerRadius(0.05f);
    f->setOuterRadius(0.4f);
    ASSERT_NO_THROW(s->validate());
    for (const char* ext : {"osgt", "osgb"})
    {
        const std::string first = dir + "/style-first." + ext, second = dir + "/style-second." + ext;
        ASSERT_TRUE(osgDB::writeObjectFile(*s, first)) << first;
        osg::ref_ptr<AbstractionStyle> b =
            dynamic_cast<AbstractionStyle*>(osgDB::readRefObjectFile(first).get());
        ASSERT_TRUE(b.valid()) << first;
        ASSERT_TRUE(osgDB::writeObjectFile(*b, second));
        EXPECT_EQ(fileBytes(first), fileBytes(second)) << ext;
        EXPECT_EQ(b->getName(), "mine");
        EXPECT_EQ(b->getDescription(), "every field changed");
        EXPECT_EQ(b->getNormalPass(), AbstractionStyle::UNSHADED);
        EXPECT_EQ(b->getShading(), AbstractionStyle::PENCIL);
        EXPECT_EQ(b->getCelLevels(), 5);
        EXPECT_EQ(b->getPencilLevels(), 6);
        EXPECT_FLOAT_EQ(b->getAmbient(), 0.25f);
        EXPECT_FLOAT_EQ(b->getPencilScale(), 3.5f);
        EXPECT_FLOAT_EQ(b->getPencilAnisotropy(), 8.0f);
        EXPECT_EQ(b->getKuwaharaRadius(), 3);
        EXPECT_EQ(b->getKuwaharaIterations(), 3);
        EXPECT_EQ(b->getKuwaharaIterationsFocus(), 2);
        EXPECT_EQ(b->getEdgeDetector(), AbstractionStyle::CANNY);
        EXPECT_EQ(b->getEdgeSource(), AbstractionStyle::NORMAL_IMAGE);
        EXPECT_FLOAT_EQ(b->getDogSigma(), 1.5f);
        EXPECT_FLOAT_EQ(b->getDogRatio(), 2.0f);
        EXPECT_FLOAT_EQ(b->getDogTau(), 0.95f);
        EXPECT_FLOAT_EQ(b->getSobelThreshold(), 0.3f);
        EXPECT_FLOAT_EQ(b->getSobelThresholdFar(), 0.7f);
        EXPECT_FLOAT_EQ(b->getCannyLow(), 0.05f);
        EXPECT_FLOAT_EQ(b->getCannyHigh(), 0.4f);
        EXPECT_TRUE(b->getSilhouettes());
        EXPECT_FLOAT_EQ(b->getEdgeOpacity(), 0.75f);
        EXPECT_FLOAT_EQ(b->getEdgeOpacityFar(), 0.125f);
        EXPECT_EQ(b->getCombination(), AbstractionStyle::PENCIL_SKETCH);
        EXPECT_FLOAT_EQ(b->getBrightening(), 1.25f);
        EXPECT_FLOAT_EQ(b->getPencilGamma(), 3.0f);
        EXPECT_EQ(b->getAdaptivity(), AbstractionStyle::OBJECT_FOCUS);
        EXPECT_TRUE(b->getSegmentation());
        EXPECT_FLOAT_EQ(b->getBleaching(), 0.5f);
        EXPECT_EQ(b->getCelLevelsFar(), 12);
        EXPECT_FLOAT_EQ(b->getShadingAtFocus(), 0.375f);
        const AbstractionFocus* g = b->getFocus();
        ASSERT_TRUE(g);
        EXPECT_EQ(g->getName(), "focus");
        EXPECT_EQ(g->getMode(), AbstractionFocus::WORLD_POINT);
        EXPECT_EQ(g->getScreenPoint(), osg::Vec2f(0.25f, 0.75f));
        EXPECT_EQ(g->getWorldPoint(), osg::Vec3d(12.5, -3.25, 100.0));
        EXPECT_EQ(g->getObjectId(), 42u);
        EXPECT_FLOAT_EQ(g->getInnerRadius(), 0.05f);
        EXPECT_FLOAT_EQ(g->getOuterRadius(), 0.4f);
        EXPECT_NO_THROW(b->validate());
    }
    if (::testing::Test::HasFailure()) std::cout << fileBytes(dir + "/style-first.osgt");

    // A default style reads back with the defaults (only the focus is written).
    osg::ref_ptr<AbstractionStyle> d = new AbstractionStyle;
    ASSERT_TRUE(osgDB::writeObjectFile(*d, dir + "/default.osgt"));
    osg::ref_ptr<AbstractionStyle> db =
        dynamic_cast<AbstractionStyle*>(osgDB::readRefObjectFile(dir + "/default.osgt").get());
    ASSERT_TRUE(db.valid());
    EXPECT_FLOAT_EQ(db->getDogTau(), 0.99f);
    EXPECT_EQ(db->getCelLevelsFar(), 8);
    ASSERT_TRUE(db->getFocus());
    EXPECT_FLOAT_EQ(db->getFocus()->getInnerRadius(), 0.1f);
}

TEST(AbstractionStyleTest, MalformedFilesFailTheRead)
{
    const std::string dir = loatest::freshDirectory("AbstractionStyleTest-bad");
    osg::ref_ptr<AbstractionStyle> s = AbstractionStyle::createBuiltin("hybrid-toon");
    ASSERT_TRUE(osgDB::writeObjectFile(*s, dir + "/good.osgt"));
    const std::string good = fileBytes(dir + "/good.osgt");
    struct Edit
    {
        const char* from;
        const char* to;
    };
    const Edit edits[] = {{"Combination TOON", "Combination TOONY"},
                          {"Shading CEL", "Shading 7"},
                          {"osgLoA::AbstractionFocus", "osg::Group"}};
    for (const Edit& e : edits)
    {
        const std::size_t at = good.find(e.from);
        ASSERT_NE(at, std::string::npos) << e.from << "\n" << good;
        std::string bad = good;
        bad.replace(at, std::string(e.from).size(), e.to);
        const std::string path = dir + "/bad.osgt";
        std::ofstream(path) << bad;
        osg::ref_ptr<osg::Object> back = osgDB::readRefObjectFile(path);
        const AbstractionStyle* b = dynamic_cast<const AbstractionStyle*>(back.get());
        EXPECT_FALSE(b) << e.to;
    }
}
