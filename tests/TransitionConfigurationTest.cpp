// TransitionConfiguration (paper 004 §3.1 "Transition Configuration", §3.2.1): scope rules,
// the combination of saliency metrics (with hand-computed numbers), interest bounds over
// boxes, and validation messages.
#include <osgLoA/transitions/TransitionConfiguration>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using namespace osgLoA;

namespace
{
typedef SaliencyMetric M;
typedef TransitionConfiguration TC;

osg::ref_ptr<Feature> feature(FeatureType type, const std::string& subType = "", float lod = -1.0f)
{
    osg::ref_ptr<Feature> f = new Feature(1, type, subType);
    f->setLod(lod);
    return f;
}

osg::ref_ptr<TC> validConfiguration(const std::string& name)
{
    osg::ref_ptr<TC> c = new TC;
    c->setName(name);
    c->addFeatureType(FeatureType::Building);
    c->setStyle("photorealistic");
    c->addMetric(new M(M::VIEW_DISTANCE, 100.0, 300.0));
    return c;
}

SaliencyView viewFrom(const osg::Vec3d& eye)
{
    SaliencyView v;
    v.eye = eye;
    return v;
}

/** The paper's example (§3.2.1, "a weighted blending between view distance and view angle ...
 *  to prevent high detail presentations in bird's eye views with a near viewing distance"): the
 *  built-in view-angle scenario's metrics, angle 25..60 degrees weight 3, distance 200..1200 m
 *  weight 1. */
osg::ref_ptr<TC> birdsEyeConfiguration(TC::Combination combination)
{
    osg::ref_ptr<TC> c = validConfiguration("detail");
    c->setMetrics({new M(M::VIEW_ANGLE, 25.0, 60.0, 3.0), new M(M::VIEW_DISTANCE, 200.0, 1200.0, 1.0)});
    c->setCombination(combination);
    return c;
}
} // namespace

TEST(TransitionConfigurationTest, TypesAreKeptSortedAndUnique)
{
    osg::ref_ptr<TC> c = new TC;
    c->setFeatureTypes({FeatureType::Water, FeatureType::Building, FeatureType::Water});
    c->addFeatureType(FeatureType::Generic);
    c->addFeatureType(FeatureType::Building);
    EXPECT_EQ(c->getFeatureTypes(),
              (TC::FeatureTypes{FeatureType::Generic, FeatureType::Building, FeatureType::Water}));
    EXPECT_TRUE(c->hasFeatureType(FeatureType::Water));
    EXPECT_FALSE(c->hasFeatureType(FeatureType::Street));
    c->setAllFeatureTypes();
    EXPECT_EQ(c->getFeatureTypes().size(), 6u);
}

TEST(TransitionConfigurationTest, MatchesTypesSubTypesLodAndInterestScope)
{
    osg::ref_ptr<TC> c = new TC;
    c->setFeatureTypes({FeatureType::Building, FeatureType::Green});
    // Types.
    EXPECT_TRUE(c->matches(*feature(FeatureType::Building), 0.5f));
    EXPECT_TRUE(c->matches(*feature(FeatureType::Green), 0.5f));
    EXPECT_FALSE(c->matches(*feature(FeatureType::Street), 0.5f));
    EXPECT_FALSE(c->matches(*feature(FeatureType::Generic), 0.5f));
    // An empty type set matches nothing (it is an error, not "all").
    EXPECT_FALSE(osg::ref_ptr<TC>(new TC)->matches(*feature(FeatureType::Building), 0.5f));
    // Sub-types: empty = any; else one of them, exactly (spaces are part of the name).
    EXPECT_TRUE(c->matches(*feature(FeatureType::Green, "coniferous"), 0.5f));
    c->setSubTypes({"deciduous", "mixed forest"});
    EXPECT_TRUE(c->matches(*feature(FeatureType::Green, "deciduous"), 0.5f));
    EXPECT_TRUE(c->matches(*feature(FeatureType::Green, "mixed forest"), 0.5f));
    EXPECT_FALSE(c->matches(*feature(FeatureType::Green, "coniferous"), 0.5f));
    EXPECT_FALSE(c->matches(*feature(FeatureType::Green, "mixed"), 0.5f));
    EXPECT_FALSE(c->matches(*feature(FeatureType::Green, ""), 0.5f));
    c->setSubTypes({});
    // LoD range [1, 2], closed; unknown LoD (-1) matches any range.
    c->setLodRange(osg::Vec2f(1.0f, 2.0f));
    EXPECT_TRUE(c->matches(*feature(FeatureType::Building, "", 1.0f), 0.5f));
    EXPECT_TRUE(c->matches(*feature(FeatureType::Building, "", 2.0f), 0.5f));
    EXPECT_TRUE(c->matches(*feature(FeatureType::Building, "", 1.5f), 0.5f));
    EXPECT_FALSE(c->matches(*feature(FeatureType::Building, "", 2.2f), 0.5f));
    EXPECT_FALSE(c->matches(*feature(FeatureType::Building, "", 0.0f), 0.5f));
    EXPECT_TRUE(c->matches(*feature(FeatureType::Building, "", -1.0f), 0.5f));
    // Static-interest scope [0.8, 1] (landmarks): a scope reaching 1 includes 1.
    c->setInterestRange(osg::Vec2f(0.8f, 1.0f));
    EXPECT_TRUE(c->matches(*feature(FeatureType::Building), 0.8f));
    EXPECT_TRUE(c->matches(*feature(FeatureType::Building), 1.0f));
    EXPECT_FALSE(c->matches(*feature(FeatureType::Building), 0.79f));
    EXPECT_FALSE(c->matches(*feature(FeatureType::Building), 0.0f));
    // Below 1 the scope is half-open, [min, max), like a hard fade: [0, 0.8) and [0.8, 1]
    // split the features without overlap or gap.
    osg::ref_ptr<TC> rest = new TC;
    rest->addFeatureType(FeatureType::Building);
    rest->setInterestRange(osg::Vec2f(0.0f, 0.8f));
    EXPECT_TRUE(rest->matches(*feature(FeatureType::Building), 0.0f));
    EXPECT_TRUE(rest->matches(*feature(FeatureType::Building), 0.79f));
    EXPECT_FALSE(rest->matches(*feature(FeatureType::Building), 0.8f));
    for (int i = 0; i <= 100; ++i)
    {
        const float si = float(i) / 100.0f;
        EXPECT_NE(rest->matches(*feature(FeatureType::Building), si),
                  c->matches(*feature(FeatureType::Building), si))
            << si;
    }
    // All rules together: right type and interest, wrong LoD -> no match.
    EXPECT_FALSE(c->matches(*feature(FeatureType::Building, "", 3.0f), 0.9f));
}

TEST(TransitionConfigurationTest, AddMetricReplacesTheSameKind)
{
    osg::ref_ptr<TC> c = new TC;
    c->addMetric(new M(M::VIEW_DISTANCE, 1.0, 2.0));
    c->addMetric(new M(M::VIEW_ANGLE, 10.0, 20.0));
    M* replacement = c->addMetric(new M(M::VIEW_DISTANCE, 5.0, 6.0));
    ASSERT_EQ(c->getMetrics().size(), 2u);
    EXPECT_EQ(c->getMetric(M::VIEW_DISTANCE), replacement);
    EXPECT_EQ(c->getMetric(M::VIEW_DISTANCE)->getNear(), 5.0);
    EXPECT_EQ(c->getMetric(M::REGION), nullptr);
    EXPECT_EQ(c->addMetric(nullptr), nullptr);
}

// Eye at (0,0,100) over a point (0,0,0): a near bird's-eye view.
//   angle 90 -> m_angle = 0 (beyond far 60); distance 100 -> m_dist = 1 (within near 200)
//   WEIGHTED_MEAN (3·0 + 1·1)/4 = 0.25: not full detail, as the paper asks;
//   MINIMUM 0; MAXIMUM 1.
// Eye at (0,0,100) over (100,0,0): angle 45 -> m_angle = 1 - (45-25)/35 = 0.428571;
//   distance 141.42 -> 1. WEIGHTED_MEAN (3·0.428571 + 1)/4 = 0.571429; MINIMUM 0.428571.
// Eye at (0,0,20) over (700,0,0): angle atan(20/700) = 1.64 -> 1; distance sqrt(490000+400) =
//   700.2857 -> 1 - 500.2857/1000 = 0.499714. WEIGHTED_MEAN (3 + 0.499714)/4 = 0.874929.
TEST(TransitionConfigurationTest, InterestAtCombinesTheMetrics)
{
    const SaliencyView top = viewFrom(osg::Vec3d(0, 0, 100));
    const SaliencyView low = viewFrom(osg::Vec3d(0, 0, 20));
    const osg::Vec3d below(0, 0, 0), oblique(100, 0, 0), far(700, 0, 0);
    osg::ref_ptr<TC> mean = birdsEyeConfiguration(TC::WEIGHTED_MEAN);
    osg::ref_ptr<TC> minimum = birdsEyeConfiguration(TC::MINIMUM);
    osg::ref_ptr<TC> maximum = birdsEyeConfiguration(TC::MAXIMUM);
    EXPECT_NEAR(mean->interestAt(below, top, 0.0), 0.25, 1e-12);
    EXPECT_NEAR(minimum->interestAt(below, top, 0.0), 0.0, 1e-12);
    EXPECT_NEAR(maximum->interestAt(below, top, 0.0), 1.0, 1e-12);
    const double angle45 = 1.0 - 20.0 / 35.0; // 0.428571
    EXPECT_NEAR(mean->interestAt(oblique, top, 0.0), (3.0 * angle45 + 1.0) / 4.0, 1e-12);
    EXPECT_NEAR(mean->interestAt(oblique, top, 0.0), 0.571429, 1e-6);
    EXPECT_NEAR(minimum->interestAt(oblique, top, 0.0), 0.428571, 1e-6);
    EXPECT_NEAR(maximum->interestAt(oblique, top, 0.0), 1.0, 1e-12);
    EXPECT_NEAR(mean->interestAt(far, low, 0.0), 0.874929, 1e-6);
    EXPECT_NEAR(minimum->interestAt(far, low, 0.0), 0.499714, 1e-6);
    // With the photorealistic fade-in of the built-in scenario (0.4..0.6), the near bird's-eye
    // view (0.25) draws no detail at all, the oblique one (0.571429) mostly:
    // t = 0.171429/0.2 = 0.857143 -> t²(3-2t) = 0.734694·1.285714 = 0.944606.
    mean->setBlendFunction(BlendFunction(0.4f, 0.6f, 1.0f, 1.0f));
    EXPECT_EQ(mean->getBlendFunction().weight(float(mean->interestAt(below, top, 0.0))), 0.0f);
    EXPECT_NEAR(mean->getBlendFunction().weight(float(mean->interestAt(oblique, top, 0.0))), 0.944606, 1e-5);
}

TEST(TransitionConfigurationTest, InterestAtEdgeCases)
{
    const SaliencyView v = viewFrom(osg::Vec3d(0, 0, 100));
    // No metric: 0.
    EXPECT_EQ(osg::ref_ptr<TC>(new TC)->interestAt(osg::Vec3d(), v, 1.0), 0.0);
    // All weights 0 under WEIGHTED_MEAN: 0; MINIMUM/MAXIMUM ignore weights.
    osg::ref_ptr<TC> c = new TC;
    c->setMetrics({new M(M::FEATURE_INTEREST, 0.0, 0.0, 0.0), new M(M::VIEW_DISTANCE, 0.0, 200.0, 0.0)});
    // feature interest 0.8; distance 100 -> 1 - 100/200 = 0.5.
    EXPECT_EQ(c->interestAt(osg::Vec3d(), v, 0.8), 0.0);
    c->setCombination(TC::MINIMUM);
    EXPECT_NEAR(c->interestAt(osg::Vec3d(), v, 0.8), 0.5, 1e-12);
    c->setCombination(TC::MAXIMUM);
    EXPECT_NEAR(c->interestAt(osg::Vec3d(), v, 0.8), 0.8, 1e-6);
    // Unequal weights 1 and 3: (1·0.8 + 3·0.5)/4 = 0.575.
    c->setMetrics({new M(M::FEATURE_INTEREST, 0.0, 0.0, 1.0), new M(M::VIEW_DISTANCE, 0.0, 200.0, 3.0)});
    c->setCombination(TC::WEIGHTED_MEAN);
    EXPECT_NEAR(c->interestAt(osg::Vec3d(), v, 0.8), 0.575, 1e-6);
    // A null metric is skipped.
    c->getMetrics().push_back(nullptr);
    EXPECT_NEAR(c->interestAt(osg::Vec3d(), v, 0.8), 0.575, 1e-6);
}

// interestRange bounds interestAt at every point of the box, for each combination.
TEST(TransitionConfigurationTest, InterestRangeContainsInterestAt)
{
    std::vector<osg::ref_ptr<RegionOfInterest>> regions = {
        new RegionOfInterest(RegionOfInterest::POLYLINE, {{-200, -100}, {0, 50}, {150, 50}}, 5.0),
        new RegionOfInterest(RegionOfInterest::POLYGON, {{100, -200}, {250, -200}, {250, -50}})};
    std::mt19937 rng(99);
    std::uniform_real_distribution<double> c(-300.0, 300.0), s(0.0, 150.0), h(-20.0, 400.0), u(0.0, 1.0);
    const std::vector<std::vector<osg::ref_ptr<M>>> metricSets = {
        {new M(M::VIEW_DISTANCE, 50.0, 400.0)},
        {new M(M::VIEW_ANGLE, 25.0, 60.0, 3.0), new M(M::VIEW_DISTANCE, 200.0, 1200.0, 1.0)},
        {new M(M::REGION, 10.0, 150.0, 2.0), new M(M::FOCUS, 0.0, 100.0, 0.5),
         new M(M::FEATURE_INTEREST, 0.0, 0.0, 1.0)},
        {new M(M::VIEW_ANGLE, 10.0, 10.0), new M(M::REGION, 0.0, 0.0)}};
    for (int trial = 0; trial < 300; ++trial)
    {
        SaliencyView v = viewFrom(osg::Vec3d(c(rng), c(rng), h(rng)));
        v.regions = &regions;
        const osg::Vec3d f(c(rng), c(rng), 0.0);
        v.focus = osg::BoundingBoxd(f, f + osg::Vec3d(20, 20, 30));
        const osg::Vec3d lo(c(rng), c(rng), c(rng) * 0.1);
        const osg::BoundingBoxd box(lo, lo + osg::Vec3d(s(rng), s(rng), s(rng) * 0.3));
        const double featureInterest = u(rng);
        for (const auto& metrics : metricSets)
            for (TC::Combination comb : {TC::WEIGHTED_MEAN, TC::MINIMUM, TC::MAXIMUM})
            {
                osg::ref_ptr<TC> conf = new TC;
                conf->setMetrics(metrics);
                conf->setCombination(comb);
                double iLo = 0.0, iHi = 0.0;
                conf->interestRange(box, v, featureInterest, iLo, iHi);
                ASSERT_LE(iLo, iHi);
                EXPECT_GE(iLo, 0.0);
                EXPECT_LE(iHi, 1.0);
                for (int k = 0; k < 40; ++k)
                {
                    const osg::Vec3d p(box.xMin() + u(rng) * (box.xMax() - box.xMin()),
                                       box.yMin() + u(rng) * (box.yMax() - box.yMin()),
                                       box.zMin() + u(rng) * (box.zMax() - box.zMin()));
                    const double i = conf->interestAt(p, v, featureInterest);
                    EXPECT_GE(i, iLo) << TC::toString(comb) << " trial " << trial;
                    EXPECT_LE(i, iHi) << TC::toString(comb) << " trial " << trial;
                }
            }
    }
    // No metric: [0, 0].
    double iLo = 1.0, iHi = 1.0;
    osg::ref_ptr<TC>(new TC)->interestRange(osg::BoundingBoxd(0, 0, 0, 1, 1, 1), viewFrom(osg::Vec3d()), 0.5,
                                            iLo, iHi);
    EXPECT_EQ(iLo, 0.0);
    EXPECT_EQ(iHi, 0.0);
}

TEST(TransitionConfigurationTest, ValidateMessages)
{
    EXPECT_TRUE(validConfiguration("ok")->validate().empty());

    osg::ref_ptr<TC> c = validConfiguration("bad");
    c->setFeatureTypes({});
    EXPECT_EQ(c->validate(), std::vector<std::string>{"configuration 'bad': empty scope: no feature type"});

    c = validConfiguration("bad");
    c->setStyle("watercolour");
    EXPECT_EQ(c->validate(),
              std::vector<std::string>{"configuration 'bad': unknown graphic style 'watercolour'"});
    c->setStyle("");
    EXPECT_EQ(c->validate(), std::vector<std::string>{"configuration 'bad': no graphic style"});

    c = validConfiguration("bad");
    c->setMetrics({new M(M::VIEW_DISTANCE, 1.0, 2.0), new M(M::VIEW_ANGLE, 1.0, 2.0),
                   new M(M::VIEW_DISTANCE, 3.0, 4.0)});
    EXPECT_EQ(c->validate(), std::vector<std::string>{"configuration 'bad': two view-distance metrics"});

    c = validConfiguration("bad");
    c->setLodRange(osg::Vec2f(3.0f, 1.0f));
    EXPECT_EQ(c->validate(),
              std::vector<std::string>{"configuration 'bad': LoD range [3, 1] is inverted or not finite"});

    c = validConfiguration("bad");
    c->setInterestRange(osg::Vec2f(0.9f, 0.2f));
    EXPECT_EQ(c->validate(),
              std::vector<std::string>{
                  "configuration 'bad': interest scope [0.9, 0.2] is empty, inverted or outside [0, 1]"});
    c->setInterestRange(osg::Vec2f(0.5f, 1.5f));
    EXPECT_EQ(c->validate().size(), 1u);
    c->setInterestRange(osg::Vec2f(0.5f, 0.5f)); // half-open: empty
    EXPECT_EQ(c->validate(),
              std::vector<std::string>{
                  "configuration 'bad': interest scope [0.5, 0.5] is empty, inverted or outside [0, 1]"});

    c = validConfiguration("bad");
    c->setBlendFunction(BlendFunction(0.2f, 0.6f, 0.4f, 0.8f));
    EXPECT_EQ(c->validate(),
              std::vector<std::string>{"configuration 'bad': fade-in interval [0.2, 0.6] overlaps "
                                       "fade-out interval [0.4, 0.8]"});

    c = validConfiguration("bad");
    c->setMetrics({});
    EXPECT_EQ(c->validate(), std::vector<std::string>{"configuration 'bad': no saliency metric"});
    c->setMetrics({nullptr});
    EXPECT_EQ(c->validate(), std::vector<std::string>{"configuration 'bad': a null saliency metric"});

    c = validConfiguration("bad");
    c->setMetrics({new M(M::VIEW_DISTANCE, 300.0, 100.0)});
    EXPECT_EQ(c->validate(),
              std::vector<std::string>{
                  "configuration 'bad': view-distance metric is inverted: near 300 > far 100"});

    c = validConfiguration("bad");
    c->setHasGroupFocus(true);
    EXPECT_EQ(c->validate(),
              std::vector<std::string>{
                  "configuration 'bad': a group focus point is set but the interpolation is object"});
    c->setInterpolation(TC::GROUP);
    EXPECT_TRUE(c->validate().empty());

    // Every problem is reported, each once; an unnamed configuration says so.
    osg::ref_ptr<TC> all = new TC;
    all->setStyle("watercolour");
    all->setLodRange(osg::Vec2f(2.0f, 1.0f));
    const std::vector<std::string> problems = all->validate();
    EXPECT_EQ(problems, (std::vector<std::string>{
                            "configuration '(unnamed)': empty scope: no feature type",
                            "configuration '(unnamed)': unknown graphic style 'watercolour'",
                            "configuration '(unnamed)': LoD range [2, 1] is inverted or not finite",
                            "configuration '(unnamed)': no saliency metric"}));
}

TEST(TransitionConfigurationTest, CopyConstructorCopiesEveryFieldAndTheMetrics)
{
    osg::ref_ptr<TC> c = birdsEyeConfiguration(TC::MAXIMUM);
    c->setSubTypes({"mixed forest"});
    c->setLodRange(osg::Vec2f(1.0f, 2.5f));
    c->setInterestRange(osg::Vec2f(0.1f, 0.9f));
    c->setInterpolation(TC::GROUP);
    c->setHasGroupFocus(true);
    c->setGroupFocus(osg::Vec3d(1, 2, 3));
    c->setBlendFunction(BlendFunction(0.1f, 0.2f, 0.3f, 0.4f));
    osg::ref_ptr<TC> d = new TC(*c, osg::CopyOp::DEEP_COPY_ALL);
    EXPECT_EQ(d->getName(), "detail");
    EXPECT_EQ(d->getFeatureTypes(), c->getFeatureTypes());
    EXPECT_EQ(d->getSubTypes(), c->getSubTypes());
    EXPECT_EQ(d->getLodRange(), c->getLodRange());
    EXPECT_EQ(d->getInterestRange(), c->getInterestRange());
    EXPECT_EQ(d->getStyle(), "photorealistic");
    EXPECT_EQ(d->getInterpolation(), TC::GROUP);
    EXPECT_TRUE(d->getHasGroupFocus());
    EXPECT_EQ(d->getGroupFocus(), osg::Vec3d(1, 2, 3));
    EXPECT_EQ(d->getCombination(), TC::MAXIMUM);
    EXPECT_EQ(d->getBlendFunction(), BlendFunction(0.1f, 0.2f, 0.3f, 0.4f));
    ASSERT_EQ(d->getMetrics().size(), 2u);
    EXPECT_NE(d->getMetrics()[0].get(), c->getMetrics()[0].get()); // deep copy
    EXPECT_EQ(d->getMetrics()[0]->getKind(), M::VIEW_ANGLE);
    EXPECT_EQ(d->getMetrics()[0]->getWeight(), 3.0);
}

TEST(TransitionConfigurationTest, ModeNames)
{
    TC::Interpolation mode = TC::OBJECT;
    EXPECT_TRUE(TC::parseInterpolation("Fragment", mode));
    EXPECT_EQ(mode, TC::FRAGMENT);
    EXPECT_TRUE(TC::parseInterpolation("group", mode));
    EXPECT_EQ(mode, TC::GROUP);
    EXPECT_FALSE(TC::parseInterpolation("vertex", mode));
    TC::Combination comb = TC::MINIMUM;
    EXPECT_TRUE(TC::parseCombination("WEIGHTED_MEAN", comb));
    EXPECT_EQ(comb, TC::WEIGHTED_MEAN);
    EXPECT_TRUE(TC::parseCombination("maximum", comb));
    EXPECT_EQ(comb, TC::MAXIMUM);
    EXPECT_FALSE(TC::parseCombination("median", comb));
    EXPECT_STREQ(TC::toString(TC::MINIMUM), "minimum");
    EXPECT_STREQ(TC::toString(TC::OBJECT), "object");
}
