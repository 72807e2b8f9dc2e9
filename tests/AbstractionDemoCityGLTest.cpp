// The demo city in every image-space and hybrid abstraction style at 320x240 against golden
// images; frame-to-frame coherence along a short camera move against plain rendering's; a usage
// scenario that draws only the buildings in an abstraction style.
#include <osgLoA/abstraction/AbstractionNode>
#include <osgLoA/abstraction/AbstractionStyleCatalog>
#include <osgLoA/city/CityCameras>
#include <osgLoA/city/CityGenerator>
#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/UsageScenario>
#include <osgLoA/util/ImageCompare>

#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace osgLoA;

namespace
{
const int W = 320, H = 240;

osg::ref_ptr<osg::Group> city()
{
    static osg::ref_ptr<osg::Group> c = CityGenerator(CityParameters()).generate();
    return c;
}

osg::ref_ptr<OffscreenRenderer> renderer(osg::Node* scene)
{
    OffscreenRenderer::Settings s;
    s.width = W;
    s.height = H;
    osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(s);
    r->setSceneData(scene);
    return r;
}

/** The oblique camera turned by `degrees` about the vertical through its centre. */
void look(OffscreenRenderer& r, double degrees)
{
    const CameraPose pose = CityCameras::compute("oblique", *city(), double(W) / H);
    const osg::Quat turn(osg::DegreesToRadians(degrees), osg::Vec3d(0, 0, 1));
    r.setPerspective(pose.fovy);
    r.setViewMatrixAsLookAt(pose.center + turn * (pose.eye - pose.center), pose.center, pose.up);
}

osg::ref_ptr<AbstractionNode> styled(const std::string& name, osg::Node* content)
{
    osg::ref_ptr<AbstractionNode> node = new AbstractionNode;
    node->setStyle(AbstractionStyleCatalog::instance().create(name).get());
    node->addChild(content);
    return node;
}

/** Mean absolute difference over RGB, 8-bit units. */
double meanChange(const osg::Image& a, const osg::Image& b)
{
    double sum = 0.0;
    const std::size_t n = std::size_t(W) * H;
    for (std::size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c)
            sum += std::fabs(double(a.data()[i * 4 + std::size_t(c)]) -
                             double(b.data()[i * 4 + std::size_t(c)]));
    return sum / double(n * 3);
}

class AbstractionDemoCityGLTest : public ::testing::TestWithParam<std::string>
{
};
} // namespace

TEST_P(AbstractionDemoCityGLTest, MatchesGolden)
{
    const std::string style = GetParam();
    osg::ref_ptr<AbstractionNode> node = styled(style, city().get());
    osg::ref_ptr<OffscreenRenderer> r = renderer(node.get());
    look(*r, 0.0);
    osg::ref_ptr<osg::Image> actual = r->renderImage();
    EXPECT_EQ(node->getLastError(), "");
    const std::string name = "abstraction-" + style + "-320x240";
    // As DemoCityImageGLTest, but 1 % failing pixels instead of 0.5 % (matchesAbstractionGolden).
    std::string summary;
    bool skipped = false;
    const bool ok = loatest::matchesAbstractionGolden(name, *actual, summary, skipped);
    if (skipped) GTEST_SKIP() << "LOA_UPDATE_GOLDENS=1: wrote tests/data/golden/" << name << ".png";
    EXPECT_TRUE(ok) << name << ": " << summary;
    // And the style changed the picture: at least 2 % of the pixels differ from plain rendering
    // by more than 16/255.
    osg::ref_ptr<OffscreenRenderer> plain = renderer(city().get());
    look(*plain, 0.0);
    EXPECT_GT(ImageComparison::compare(*actual, *plain->renderImage(), 16).failingFraction, 0.02) << style;
}

INSTANTIATE_TEST_SUITE_P(Styles, AbstractionDemoCityGLTest,
                         ::testing::ValuesIn(AbstractionStyle::builtinNames()),
                         [](const ::testing::TestParamInfo<std::string>& p) { return loatest::paramName(p.param); });

TEST(AbstractionCoherenceGLTest, FrameToFrameChangeAlongACameraMove)
{
    // Five frames turning the oblique camera by 0.25 degrees each; the mean per-pixel change
    // between consecutive frames of a style against plain rendering's. The styles filter each
    // frame alone (no temporal filtering), so the ratio says how much a style amplifies or damps
    // the frame's own change. Measured on llvmpipe (ratio to plain): kuwahara3 0.78, kuwahara5
    // 0.59 (the painterly filter removes texture shimmer: paper 001's "good coherence between
    // frames with little or no flicker"), hybrid-pencil 1.47, pencil 1.69 (strokes in object
    // coordinates move with the surfaces: they change where the surfaces move), adaptive 1.76,
    // dog 2.18, hybrid-toon 3.43 (black lines of full contrast shift by a pixel where the
    // geometry does). Bars: 25 % above the measurement, and below 1 for the painterly filters.
    // A style that flickered (noise or sector choices changing from frame to frame where the
    // scene does not) would change a large share of all pixels each frame and fail.
    auto changes = [](osg::Node* scene)
    {
        osg::ref_ptr<OffscreenRenderer> r = renderer(scene);
        std::vector<osg::ref_ptr<osg::Image>> frames;
        for (int i = 0; i < 5; ++i)
        {
            look(*r, 0.25 * i);
            frames.push_back(r->renderImage());
        }
        double sum = 0.0;
        for (std::size_t i = 1; i < frames.size(); ++i)
            sum += meanChange(*frames[i - 1], *frames[i]);
        return sum / double(frames.size() - 1);
    };
    const double plain = changes(city().get());
    ASSERT_GT(plain, 0.5); // the camera moved
    const std::pair<const char*, double> bars[] = {
        {"kuwahara3", 0.98}, {"kuwahara5", 0.75}, {"hybrid-pencil", 1.85}, {"pencil", 2.1},
        {"adaptive", 2.2},   {"dog", 2.7},        {"hybrid-toon", 4.3}};
    for (const auto& [style, bar] : bars)
    {
        osg::ref_ptr<AbstractionNode> node = styled(style, city().get());
        const double c = changes(node.get());
        std::cout << style << ": mean change " << c << " / 255 per frame, plain " << plain << ", ratio "
                  << c / plain << " (bar " << bar << ")" << std::endl;
        EXPECT_LE(c / plain, bar) << style;
    }
}

TEST(AbstractionScenarioGLTest, OnlyTheConfigurationsFeaturesAreAbstracted)
{
    // Scenario A: buildings in "hybrid-toon", the rest photorealistic; B: all photorealistic; C:
    // buildings hidden. Where B and C differ a building is seen: there A must differ from B,
    // elsewhere A must equal B exactly (the abstraction's weight is 0).
    auto scenario = [](const std::string& buildings)
    {
        osg::ref_ptr<UsageScenario> s = new UsageScenario;
        s->setName("test-" + buildings);
        for (int i = 0; i < 2; ++i)
        {
            osg::ref_ptr<TransitionConfiguration> c = new TransitionConfiguration;
            c->setName(i == 0 ? "buildings" : "rest");
            if (i == 0)
                c->setFeatureTypes({FeatureType::Building});
            else
                c->setFeatureTypes({FeatureType::Generic, FeatureType::Street, FeatureType::Water,
                                    FeatureType::Green, FeatureType::Terrain});
            c->setStyle(i == 0 ? buildings : "photorealistic");
            c->setInterpolation(TransitionConfiguration::OBJECT);
            c->addMetric(new SaliencyMetric(SaliencyMetric::FEATURE_INTEREST, 0.0, 1.0));
            s->addConfiguration(c.get());
        }
        return s;
    };
    auto render = [&](const std::string& buildings)
    {
        osg::ref_ptr<LoANode> loa = new LoANode;
        loa->setScenario(scenario(buildings).get());
        loa->addChild(city().get());
        osg::ref_ptr<osg::Node> top = AbstractionNode::wrapScenario(loa.get());
        EXPECT_EQ(top.get() != loa.get(), buildings == "hybrid-toon");
        osg::ref_ptr<OffscreenRenderer> r = renderer(top.get());
        look(*r, 0.0);
        return r->renderImage();
    };
    osg::ref_ptr<osg::Image> a = render("hybrid-toon"), b = render("photorealistic"), c = render("hidden");
    std::size_t building = 0, changed = 0, outsideChanged = 0;
    for (std::size_t i = 0; i < std::size_t(W) * H; ++i)
    {
        auto differ = [&](const osg::Image& x, const osg::Image& y, int tol)
        {
            for (int k = 0; k < 3; ++k)
                if (std::abs(int(x.data()[i * 4 + std::size_t(k)]) - int(y.data()[i * 4 + std::size_t(k)])) >
                    tol)
                    return true;
            return false;
        };
        if (differ(*b, *c, 0))
        {
            ++building;
            changed += differ(*a, *b, 8);
        }
        else
            outsideChanged += differ(*a, *b, 0);
    }
    std::cout << building << " building pixels, " << changed << " of them changed; " << outsideChanged
              << " other pixels changed" << std::endl;
    EXPECT_GT(building, std::size_t(W * H / 20));
    EXPECT_GT(double(changed), 0.5 * double(building));
    EXPECT_EQ(outsideChanged, 0u);
}

TEST(AbstractionScenarioGLTest, TwoAbstractionStylesInOneScenario)
{
    // Buildings in "hybrid-toon", streets in "kuwahara5", the rest photorealistic: two nested
    // abstraction nodes whose objects share their uniforms (one component each). Masks of the
    // buildings and the streets from scenarios that hide them.
    auto render = [&](const std::string& buildings, const std::string& streets)
    {
        osg::ref_ptr<UsageScenario> s = new UsageScenario;
        s->setName("two");
        const std::pair<std::vector<FeatureType>, std::string> parts[] = {
            {{FeatureType::Building}, buildings},
            {{FeatureType::Street}, streets},
            {{FeatureType::Generic, FeatureType::Water, FeatureType::Green, FeatureType::Terrain},
             "photorealistic"}};
        for (const auto& [types, style] : parts)
        {
            osg::ref_ptr<TransitionConfiguration> c = new TransitionConfiguration;
            c->setName("c" + std::to_string(s->getConfigurations().size()));
            c->setFeatureTypes(types);
            c->setStyle(style);
            c->setInterpolation(TransitionConfiguration::OBJECT);
            c->addMetric(new SaliencyMetric(SaliencyMetric::FEATURE_INTEREST, 0.0, 1.0));
            s->addConfiguration(c.get());
        }
        osg::ref_ptr<LoANode> loa = new LoANode;
        loa->setScenario(s.get());
        loa->addChild(city().get());
        osg::ref_ptr<osg::Node> top = AbstractionNode::wrapScenario(loa.get());
        osg::ref_ptr<OffscreenRenderer> r = renderer(top.get());
        look(*r, 0.0);
        osg::ref_ptr<osg::Image> img = r->renderImage();
        if (AbstractionNode* a = dynamic_cast<AbstractionNode*>(top.get()))
        {
            EXPECT_EQ(a->getLastError(), "");
        }
        return img;
    };
    osg::ref_ptr<osg::Image> both = render("hybrid-toon", "kuwahara5");
    osg::ref_ptr<osg::Image> plain = render("photorealistic", "photorealistic");
    osg::ref_ptr<osg::Image> noBuildings = render("hidden", "photorealistic");
    osg::ref_ptr<osg::Image> noStreets = render("photorealistic", "hidden");
    auto differ = [](const osg::Image& x, const osg::Image& y, std::size_t i, int tol)
    {
        for (std::size_t k = 0; k < 3; ++k)
            if (std::abs(int(x.data()[i * 4 + k]) - int(y.data()[i * 4 + k])) > tol) return true;
        return false;
    };
    std::size_t buildings = 0, buildingsChanged = 0, streets = 0, streetsChanged = 0, rest = 0,
                restChanged = 0;
    for (std::size_t i = 0; i < std::size_t(W) * H; ++i)
    {
        const bool b = differ(*plain, *noBuildings, i, 0), st = differ(*plain, *noStreets, i, 0);
        if (b)
        {
            ++buildings;
            buildingsChanged += differ(*both, *plain, i, 8);
        }
        else if (st)
        {
            ++streets;
            streetsChanged += differ(*both, *plain, i, 2);
        }
        else
        {
            ++rest;
            restChanged += differ(*both, *plain, i, 0);
        }
    }
    std::cout << "buildings " << buildingsChanged << "/" << buildings << " changed, streets "
              << streetsChanged << "/" << streets << ", rest " << restChanged << "/" << rest << std::endl;
    EXPECT_GT(double(buildingsChanged), 0.5 * double(buildings));
    // Kuwahara on the streets' asphalt changes fewer pixels (smooth texture) but many.
    EXPECT_GT(double(streetsChanged), 0.2 * double(streets));
    EXPECT_EQ(restChanged, 0u);
}
