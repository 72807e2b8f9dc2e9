// ScenarioEvaluator (paper 004 §3.2.1, Algorithm 1's matching): small hand-built scenes with
// hand-computed interest and weights for object, group and fragment interpolation,
// normalization, visibility, interest overrides, focus and region metrics, bind errors, and
// that evaluate() allocates nothing (a counting global operator new below).
#include "support/TestSupport.h"

#include <osgLoA/semantics/Feature>
#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/semantics/FeatureInterest>
#include <osgLoA/transitions/ScenarioEvaluator>
#include <osgLoA/transitions/ScenarioLibrary>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Group>

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <random>
#include <stdexcept>
#include <vector>

// --- allocation counting ----------------------------------------------------------------------
// Replaces the global allocation functions of this test binary (shared libraries' calls bind to
// them too), so a test can count what a call allocates. Not inlined: GCC would otherwise pair
// the inlined free() with the `new` it sees and warn (-Wmismatched-new-delete).
namespace
{
std::atomic<unsigned long> gAllocations{0};
}

__attribute__((noinline)) void* operator new(std::size_t n)
{
    gAllocations.fetch_add(1, std::memory_order_relaxed);
    if (void* p = std::malloc(n ? n : 1)) return p;
    throw std::bad_alloc();
}
__attribute__((noinline)) void* operator new[](std::size_t n)
{
    return operator new(n);
}
__attribute__((noinline)) void operator delete(void* p) noexcept
{
    std::free(p);
}
__attribute__((noinline)) void operator delete[](void* p) noexcept
{
    std::free(p);
}
__attribute__((noinline)) void operator delete(void* p, std::size_t) noexcept
{
    std::free(p);
}
__attribute__((noinline)) void operator delete[](void* p, std::size_t) noexcept
{
    std::free(p);
}

using namespace osgLoA;

namespace
{
typedef SaliencyMetric M;
typedef TransitionConfiguration TC;

using loatest::boxGeode;

Feature* addBox(osg::Group& parent, unsigned id, FeatureType type, const osg::Vec3& minimum,
                const osg::Vec3& maximum, const std::string& subType = "")
{
    osg::ref_ptr<osg::Geode> g = boxGeode(minimum, maximum);
    Feature* f = Feature::attach(*g, new Feature(id, type, subType));
    parent.addChild(g.get());
    return f;
}

osg::ref_ptr<TC> configuration(const std::string& name, FeatureType type, TC::Interpolation mode,
                               const BlendFunction& blend, M* metric)
{
    osg::ref_ptr<TC> c = new TC;
    c->setName(name);
    c->addFeatureType(type);
    c->setStyle("photorealistic");
    c->setInterpolation(mode);
    c->setBlendFunction(blend);
    c->addMetric(metric);
    return c;
}

/** Bound scene: keeps the graph alive next to its index. */
struct Scene
{
    osg::ref_ptr<osg::Group> root = new osg::Group;
    FeatureIndex index;
    void finish()
    {
        index.build(*root);
        index.updateBounds();
    }
};

const ScenarioEvaluator::Match& matchOf(const ScenarioEvaluator& e, unsigned featureId, unsigned k)
{
    const int i = e.findFeature(featureId);
    EXPECT_GE(i, 0) << featureId;
    const ScenarioEvaluator::FeatureState& f = e.features()[i];
    EXPECT_LT(k, f.numMatches);
    return e.matchesOf(f)[k];
}
} // namespace

// Object interpolation: the interest is evaluated once, at the centre of the feature's box.
TEST(ScenarioEvaluatorTest, ObjectModeEvaluatesAtTheBoxCentre)
{
    Scene s;
    addBox(*s.root, 1, FeatureType::Building, osg::Vec3(195, -5, 0),
           osg::Vec3(205, 5, 10)); // centre (200,0,5)
    s.finish();
    osg::ref_ptr<UsageScenario> scenario = new UsageScenario;
    scenario->addConfiguration(configuration("photo", FeatureType::Building, TC::OBJECT,
                                             BlendFunction(0.25f, 0.75f, 1.0f, 1.0f),
                                             new M(M::VIEW_DISTANCE, 100, 300))
                                   .get());
    scenario->addConfiguration(configuration("abstract", FeatureType::Building, TC::OBJECT,
                                             BlendFunction(0.0f, 0.0f, 0.25f, 0.75f),
                                             new M(M::VIEW_DISTANCE, 100, 300))
                                   .get());
    osg::ref_ptr<ScenarioEvaluator> e = new ScenarioEvaluator;
    e->bind(scenario.get(), s.index);
    ASSERT_EQ(e->features().size(), 1u);
    ASSERT_EQ(e->features()[0].numMatches, 2u);
    // Eye (-25,0,5): distance to the centre 225 -> interest 1 - (225-100)/200 = 0.375.
    // photo: smoothstep(0.25, 0.75, 0.375), t = 0.25 -> 0.15625; abstract: 1 - 0.15625 = 0.84375.
    // Their sum is 1, so the normalized weights equal the raw ones.
    e->evaluate(osg::Vec3d(-25, 0, 5));
    const ScenarioEvaluator::Match& photo = matchOf(*e, 1, 0);
    const ScenarioEvaluator::Match& abstract = matchOf(*e, 1, 1);
    EXPECT_EQ(photo.point, osg::Vec3d(200, 0, 5));
    EXPECT_EQ(photo.configuration, 0u);
    EXPECT_EQ(abstract.configuration, 1u);
    EXPECT_FALSE(photo.fragment);
    EXPECT_NEAR(photo.interest, 0.375f, 1e-6f);
    EXPECT_NEAR(abstract.interest, 0.375f, 1e-6f);
    EXPECT_NEAR(photo.rawWeight, 0.15625f, 1e-6f);
    EXPECT_NEAR(abstract.rawWeight, 0.84375f, 1e-6f);
    EXPECT_NEAR(photo.weight, 0.15625f, 1e-6f);
    EXPECT_NEAR(abstract.weight, 0.84375f, 1e-6f);
    EXPECT_TRUE(photo.mayContribute);
    EXPECT_TRUE(abstract.mayContribute);
    // Eye (0,0,5): distance 200 -> interest 0.5 -> t = 0.5 -> 0.5 each.
    e->evaluate(osg::Vec3d(0, 0, 5));
    EXPECT_NEAR(matchOf(*e, 1, 0).weight, 0.5f, 1e-6f);
    EXPECT_NEAR(matchOf(*e, 1, 1).weight, 0.5f, 1e-6f);
    // Eye (350,0,5): distance 150 -> 0.75 -> photo 1, abstract 0 (and may not contribute).
    e->evaluate(osg::Vec3d(350, 0, 5));
    EXPECT_EQ(matchOf(*e, 1, 0).weight, 1.0f);
    EXPECT_EQ(matchOf(*e, 1, 1).weight, 0.0f);
    EXPECT_FALSE(matchOf(*e, 1, 1).mayContribute);
    EXPECT_EQ(e->getStatistics().visibleFeatures, 1u);
    EXPECT_EQ(e->getStatistics().matches, 2u);
    EXPECT_EQ(e->getStatistics().contributing, 1u);
    EXPECT_EQ(e->getStatistics().undrawnFeatures, 0u);

    // With only the photo configuration, a raw weight of 0.15625 is normalized to 1.
    scenario->getConfigurations().pop_back();
    e->bind(scenario.get(), s.index);
    e->evaluate(osg::Vec3d(-25, 0, 5));
    EXPECT_NEAR(matchOf(*e, 1, 0).rawWeight, 0.15625f, 1e-6f);
    EXPECT_EQ(matchOf(*e, 1, 0).weight, 1.0f);
}

// Group interpolation: the features of a group (same enclosing feature and sub-type) share the
// centre of their union box; an explicit group focus replaces it.
TEST(ScenarioEvaluatorTest, GroupModeSharesTheFocusPoint)
{
    Scene s;
    osg::ref_ptr<osg::Group> wood = new osg::Group;
    Feature::attach(*wood, new Feature(10, FeatureType::Green, "mixed forest"));
    s.root->addChild(wood.get());
    for (unsigned i = 0; i < 3; ++i) // deciduous trees at x = 0, 10, 20, boxes 2x2x10
        addBox(*wood, 11 + i, FeatureType::Green, osg::Vec3(10.0f * i - 1, -1, 0),
               osg::Vec3(10.0f * i + 1, 1, 10), "deciduous");
    addBox(*wood, 14, FeatureType::Green, osg::Vec3(29, -1, 0), osg::Vec3(31, 1, 10), "coniferous");
    osg::ref_ptr<osg::Group> park = new osg::Group;
    Feature::attach(*park, new Feature(20, FeatureType::Green, "park"));
    s.root->addChild(park.get());
    addBox(*park, 21, FeatureType::Green, osg::Vec3(99, -1, 0), osg::Vec3(101, 1, 10), "deciduous");
    s.finish();

    osg::ref_ptr<TC> trees = configuration("trees", FeatureType::Green, TC::GROUP, BlendFunction(),
                                           new M(M::VIEW_DISTANCE, 100, 300));
    trees->setSubTypes({"deciduous", "coniferous"}); // the wood and the park themselves do not match
    osg::ref_ptr<UsageScenario> scenario = new UsageScenario;
    scenario->addConfiguration(trees.get());
    osg::ref_ptr<ScenarioEvaluator> e = new ScenarioEvaluator;
    e->bind(scenario.get(), s.index);
    EXPECT_EQ(e->features()[e->findFeature(10)].numMatches, 0u);
    EXPECT_EQ(e->features()[e->findFeature(20)].numMatches, 0u);

    // Eye (10,-150,5).
    e->evaluate(osg::Vec3d(10, -150, 5));
    // The wood's deciduous trees: union box [-1,21]x[-1,1]x[0,10], centre (10,0,5), distance
    // 150 -> 1 - 50/200 = 0.75, the same for all three.
    for (unsigned id : {11u, 12u, 13u})
    {
        EXPECT_EQ(matchOf(*e, id, 0).point, osg::Vec3d(10, 0, 5)) << id;
        EXPECT_NEAR(matchOf(*e, id, 0).interest, 0.75f, 1e-6f) << id;
    }
    // The coniferous tree is its own group: centre (30,0,5), distance sqrt(20² + 150²) =
    // 151.3275 -> 1 - 51.3275/200 = 0.743362.
    EXPECT_EQ(matchOf(*e, 14, 0).point, osg::Vec3d(30, 0, 5));
    EXPECT_NEAR(matchOf(*e, 14, 0).interest, 0.743362f, 1e-5f);
    // The park's deciduous tree has another enclosing feature: centre (100,0,5), distance
    // sqrt(90² + 150²) = 174.9286 -> 1 - 74.9286/200 = 0.625357.
    EXPECT_EQ(matchOf(*e, 21, 0).point, osg::Vec3d(100, 0, 5));
    EXPECT_NEAR(matchOf(*e, 21, 0).interest, 0.625357f, 1e-5f);

    // An explicit group focus point is used by every match of the configuration.
    trees->setHasGroupFocus(true);
    trees->setGroupFocus(osg::Vec3d(0, 0, 0));
    e->bind(scenario.get(), s.index);
    e->evaluate(osg::Vec3d(0, -250, 0)); // distance 250 -> 1 - 150/200 = 0.25
    for (unsigned id : {11u, 12u, 13u, 14u, 21u})
    {
        EXPECT_EQ(matchOf(*e, id, 0).point, osg::Vec3d(0, 0, 0)) << id;
        EXPECT_NEAR(matchOf(*e, id, 0).interest, 0.25f, 1e-6f) << id;
    }
}

namespace
{
/** A terrain box [-500,500]² x [0,1] under an eye at (0,0,200), view distance 100..300:
 *    centre (0,0,0.5): distance 199.5 -> interest 1 - 99.5/200 = 0.5025;
 *    nearest point (0,0,1): distance 199 -> 1 - 99/200 = 0.505 (the highest on the box);
 *    the far corners are beyond 300 -> 0 (the lowest). */
struct FragmentScene : Scene
{
    osg::ref_ptr<UsageScenario> scenario = new UsageScenario;
    FragmentScene()
    {
        addBox(*root, 1, FeatureType::Terrain, osg::Vec3(-500, -500, 0), osg::Vec3(500, 500, 1));
        finish();
        // 0: valid from 0.504: zero at the centre, but the box reaches 0.505.
        scenario->addConfiguration(configuration("reaches", FeatureType::Terrain, TC::FRAGMENT,
                                                 BlendFunction(0.504f, 0.6f, 1.0f, 1.0f),
                                                 new M(M::VIEW_DISTANCE, 100, 300))
                                       .get());
        // 1: valid from 0.506: no point of the box gets there.
        scenario->addConfiguration(configuration("never", FeatureType::Terrain, TC::FRAGMENT,
                                                 BlendFunction(0.506f, 0.6f, 1.0f, 1.0f),
                                                 new M(M::VIEW_DISTANCE, 100, 300))
                                       .get());
        // 2: fades out over 0.5..0.6.
        scenario->addConfiguration(configuration("low", FeatureType::Terrain, TC::FRAGMENT,
                                                 BlendFunction(0.0f, 0.0f, 0.5f, 0.6f),
                                                 new M(M::VIEW_DISTANCE, 100, 300))
                                       .get());
    }
};
} // namespace

// Fragment interpolation: centre values for reports, and a conservative mayContribute.
TEST(ScenarioEvaluatorTest, FragmentModeReportsCentreValuesAndConservativeFlags)
{
    FragmentScene s;
    osg::ref_ptr<ScenarioEvaluator> e = new ScenarioEvaluator;
    e->bind(s.scenario.get(), s.index);
    e->evaluate(osg::Vec3d(0, 0, 200));
    const ScenarioEvaluator::Match& reaches = matchOf(*e, 1, 0);
    const ScenarioEvaluator::Match& never = matchOf(*e, 1, 1);
    const ScenarioEvaluator::Match& low = matchOf(*e, 1, 2);
    EXPECT_TRUE(reaches.fragment);
    EXPECT_EQ(reaches.point, osg::Vec3d(0, 0, 0.5));
    EXPECT_NEAR(reaches.interest, 0.5025f, 1e-6f);
    EXPECT_EQ(reaches.rawWeight, 0.0f); // 0.5025 < 0.504 at the centre ...
    EXPECT_TRUE(reaches.mayContribute); // ... but (0,0,1) has 0.505 > 0.504
    EXPECT_EQ(never.rawWeight, 0.0f);
    EXPECT_FALSE(never.mayContribute); // 0.505 < 0.506 everywhere
    // low: 1 - smoothstep(0.5, 0.6, 0.5025): t = 0.025 -> 0.000625·2.95 = 0.00184375 -> 0.99815625.
    EXPECT_NEAR(low.rawWeight, 0.99815625f, 1e-6f);
    EXPECT_TRUE(low.mayContribute);
    EXPECT_EQ(low.weight, 1.0f); // the only non-zero raw weight
    EXPECT_EQ(reaches.weight, 0.0f);
    EXPECT_EQ(e->getStatistics().contributing, 2u);

    // The point that makes 'reaches' contribute really does: interest 0.505, weight > 0.
    const TC& c = *s.scenario->getConfigurations()[0];
    const double top = c.interestAt(osg::Vec3d(0, 0, 1), e->getView(), 0.0);
    EXPECT_NEAR(top, 0.505, 1e-12);
    EXPECT_GT(c.getBlendFunction().weight(float(top)), 0.0f);
}

// mayContribute against sampling the box: never false where a sampled point has weight > 0
// (the renderer would skip a draw that shows), for random eyes.
TEST(ScenarioEvaluatorTest, FragmentMayContributeIsConservative)
{
    FragmentScene s;
    osg::ref_ptr<ScenarioEvaluator> e = new ScenarioEvaluator;
    e->bind(s.scenario.get(), s.index);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> xy(-800.0, 800.0), z(0.0, 400.0), u(0.0, 1.0);
    const osg::BoundingBoxd& box = e->features()[0].bound;
    int skipped = 0;
    for (int trial = 0; trial < 200; ++trial)
    {
        e->evaluate(osg::Vec3d(xy(rng), xy(rng), z(rng)));
        const ScenarioEvaluator::Match* m = e->matchesOf(e->features()[0]);
        for (unsigned k = 0; k < 3; ++k)
        {
            const TC& c = *s.scenario->getConfigurations()[m[k].configuration];
            bool sampled = false;
            for (int i = 0; i < 400 && !sampled; ++i)
            {
                const osg::Vec3d p(box.xMin() + u(rng) * (box.xMax() - box.xMin()),
                                   box.yMin() + u(rng) * (box.yMax() - box.yMin()),
                                   i % 2 ? box.zMax() : box.zMin());
                sampled = c.getBlendFunction().weight(float(c.interestAt(p, e->getView(), 0.0))) > 0.0f;
            }
            if (sampled)
            {
                EXPECT_TRUE(m[k].mayContribute) << "trial " << trial << " configuration " << k;
            }
            if (!m[k].mayContribute) ++skipped;
        }
    }
    EXPECT_GT(skipped, 0); // the false side was exercised too
}

// The weights of a drawn feature sum to 1; a feature whose matches all weigh 0 is not drawn.
TEST(ScenarioEvaluatorTest, WeightsAreNormalized)
{
    Scene s;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> c(-600.0f, 600.0f), size(2.0f, 60.0f);
    const FeatureType types[] = {FeatureType::Building, FeatureType::Street,  FeatureType::Water,
                                 FeatureType::Green,    FeatureType::Terrain, FeatureType::Generic};
    for (unsigned i = 0; i < 60; ++i)
    {
        const osg::Vec3 lo(c(rng), c(rng), 0.0f);
        addBox(*s.root, i + 1, types[i % 6], lo, lo + osg::Vec3(size(rng), size(rng), size(rng)));
    }
    s.finish();
    osg::ref_ptr<UsageScenario> scenario = ScenarioLibrary::createBuiltin("distance");
    osg::ref_ptr<ScenarioEvaluator> e = new ScenarioEvaluator;
    e->bind(scenario.get(), s.index);
    std::uniform_real_distribution<double> eye(-1500.0, 1500.0), h(2.0, 800.0);
    unsigned drawn = 0;
    for (int trial = 0; trial < 50; ++trial)
    {
        e->evaluate(osg::Vec3d(eye(rng), eye(rng), h(rng)));
        for (const ScenarioEvaluator::FeatureState& f : e->features())
        {
            EXPECT_EQ(f.numMatches, 3u); // three levels for each type
            const ScenarioEvaluator::Match* m = e->matchesOf(f);
            double sum = 0.0, raw = 0.0;
            for (unsigned k = 0; k < f.numMatches; ++k)
            {
                sum += m[k].weight;
                raw += m[k].rawWeight;
            }
            if (raw > 0.0)
            {
                EXPECT_NEAR(sum, 1.0, 1e-6);
                ++drawn;
            }
            else
                EXPECT_EQ(sum, 0.0);
        }
    }
    EXPECT_EQ(drawn, 50u * 60u); // the three levels cover the whole axis: every feature drawn

    // A configuration valid only from interest 0.9, seen from far away: interest 0, weight 0.
    Scene one;
    addBox(*one.root, 1, FeatureType::Building, osg::Vec3(0, 0, 0), osg::Vec3(10, 10, 10));
    addBox(*one.root, 2, FeatureType::Building, osg::Vec3(2000, 0, 0), osg::Vec3(2010, 10, 10));
    one.finish();
    osg::ref_ptr<UsageScenario> narrow = new UsageScenario;
    narrow->addConfiguration(configuration("near-only", FeatureType::Building, TC::OBJECT,
                                           BlendFunction(0.9f, 0.9f, 1.0f, 1.0f),
                                           new M(M::VIEW_DISTANCE, 100, 300))
                                 .get());
    e->bind(narrow.get(), one.index);
    e->evaluate(osg::Vec3d(5, 5, 50)); // feature 1: distance 45 -> 1; feature 2: ~2000 -> 0
    EXPECT_EQ(matchOf(*e, 1, 0).weight, 1.0f);
    EXPECT_EQ(matchOf(*e, 2, 0).interest, 0.0f);
    EXPECT_EQ(matchOf(*e, 2, 0).rawWeight, 0.0f);
    EXPECT_EQ(matchOf(*e, 2, 0).weight, 0.0f);
    EXPECT_FALSE(matchOf(*e, 2, 0).mayContribute);
    EXPECT_EQ(e->getStatistics().visibleFeatures, 2u);
    EXPECT_EQ(e->getStatistics().undrawnFeatures, 1u);
    EXPECT_EQ(e->getStatistics().contributing, 1u);
}

// Invisible features are neither evaluated nor counted; their last values stay as they were.
TEST(ScenarioEvaluatorTest, VisibilityMask)
{
    Scene s;
    for (unsigned i = 0; i < 3; ++i)
        addBox(*s.root, i + 1, FeatureType::Building, osg::Vec3(100.0f * i, 0, 0),
               osg::Vec3(100.0f * i + 10, 10, 10));
    s.finish();
    osg::ref_ptr<UsageScenario> scenario = ScenarioLibrary::createBuiltin("distance");
    osg::ref_ptr<ScenarioEvaluator> e = new ScenarioEvaluator;
    e->bind(scenario.get(), s.index);
    e->evaluate(osg::Vec3d(0, 0, 100));
    const std::vector<ScenarioEvaluator::Match> before = e->matches();
    const unsigned char visible[] = {1, 0, 1};
    e->evaluate(osg::Vec3d(800, 0, 300), visible);
    EXPECT_TRUE(e->features()[0].visible);
    EXPECT_FALSE(e->features()[1].visible);
    EXPECT_TRUE(e->features()[2].visible);
    EXPECT_EQ(e->getStatistics().visibleFeatures, 2u);
    EXPECT_EQ(e->getStatistics().matches, 6u); // 3 each
    const ScenarioEvaluator::FeatureState& hidden = e->features()[1];
    for (unsigned k = 0; k < hidden.numMatches; ++k)
    {
        const ScenarioEvaluator::Match& now = e->matches()[hidden.firstMatch + k];
        const ScenarioEvaluator::Match& then = before[hidden.firstMatch + k];
        EXPECT_EQ(now.interest, then.interest);
        EXPECT_EQ(now.rawWeight, then.rawWeight);
        EXPECT_EQ(now.weight, then.weight);
    }
    // The visible ones did change (the eye moved 800 m away).
    EXPECT_NE(e->matches()[0].interest, before[0].interest);
    // Nothing visible: nothing counted.
    const unsigned char none[] = {0, 0, 0};
    e->evaluate(osg::Vec3d(0, 0, 100), none);
    EXPECT_EQ(e->getStatistics().visibleFeatures, 0u);
    EXPECT_EQ(e->getStatistics().matches, 0u);
    EXPECT_EQ(e->getStatistics().undrawnFeatures, 0u);
}

// The scenario's interest overrides decide the static interest, and through it the scope.
TEST(ScenarioEvaluatorTest, InterestOverridesChangeStaticInterestAndScope)
{
    Scene s;
    addBox(*s.root, 1, FeatureType::Building, osg::Vec3(0, 0, 0), osg::Vec3(10, 10, 10))->setInterest(0.2f);
    addBox(*s.root, 2, FeatureType::Building, osg::Vec3(50, 0, 0), osg::Vec3(60, 10, 10))->setInterest(0.2f);
    s.finish();
    osg::ref_ptr<UsageScenario> scenario = new UsageScenario;
    osg::ref_ptr<TC> landmarks = configuration("landmarks", FeatureType::Building, TC::OBJECT,
                                               BlendFunction(), new M(M::FEATURE_INTEREST, 0, 0));
    landmarks->setInterestRange(osg::Vec2f(0.8f, 1.0f));
    osg::ref_ptr<TC> others = configuration("others", FeatureType::Building, TC::OBJECT, BlendFunction(),
                                            new M(M::FEATURE_INTEREST, 0, 0));
    others->setInterestRange(osg::Vec2f(0.0f, 0.79f));
    scenario->addConfiguration(landmarks.get());
    scenario->addConfiguration(others.get());
    osg::ref_ptr<ScenarioEvaluator> e = new ScenarioEvaluator;

    // Without overrides: the features' own 0.2 -> 'others'.
    e->bind(scenario.get(), s.index);
    e->evaluate(osg::Vec3d());
    EXPECT_FLOAT_EQ(e->features()[0].staticInterest, 0.2f);
    ASSERT_EQ(e->features()[0].numMatches, 1u);
    EXPECT_EQ(matchOf(*e, 1, 0).configuration, 1u);
    EXPECT_NEAR(matchOf(*e, 1, 0).interest, 0.2f, 1e-7f);

    // Buildings 0.9 by type, feature 2 0.5 by id: feature 1 becomes a landmark, feature 2 stays.
    osg::ref_ptr<FeatureInterest> fi = new FeatureInterest;
    fi->setTypeInterest(FeatureType::Building, 0.9f);
    fi->setFeatureInterest(2, 0.5f);
    scenario->setInterest(fi.get());
    e->bind(scenario.get(), s.index);
    e->evaluate(osg::Vec3d());
    EXPECT_FLOAT_EQ(e->features()[0].staticInterest, 0.9f);
    EXPECT_FLOAT_EQ(e->features()[1].staticInterest, 0.5f);
    ASSERT_EQ(e->features()[0].numMatches, 1u);
    EXPECT_EQ(matchOf(*e, 1, 0).configuration, 0u);
    EXPECT_NEAR(matchOf(*e, 1, 0).interest, 0.9f, 1e-7f); // the feature-interest metric sees 0.9
    EXPECT_EQ(matchOf(*e, 2, 0).configuration, 1u);
    EXPECT_NEAR(matchOf(*e, 2, 0).interest, 0.5f, 1e-7f);
    // The scene itself is unchanged.
    EXPECT_FLOAT_EQ(s.index.find(1)->feature->getInterest(), 0.2f);
}

// FOCUS measures against the focus feature's box, REGION against the scenario's regions.
TEST(ScenarioEvaluatorTest, FocusAndRegionMetrics)
{
    Scene s;
    addBox(*s.root, 1, FeatureType::Building, osg::Vec3(0, 0, 0), osg::Vec3(10, 10, 10));  // the focus
    addBox(*s.root, 2, FeatureType::Building, osg::Vec3(12, 13, 4), osg::Vec3(14, 15, 6)); // centre (13,14,5)
    addBox(*s.root, 3, FeatureType::Building, osg::Vec3(29, 39, 0), osg::Vec3(31, 41, 0)); // centre (30,40,0)
    s.finish();
    osg::ref_ptr<UsageScenario> scenario = new UsageScenario;
    scenario->setFocusFeature(1);
    scenario->addRegion(new RegionOfInterest(RegionOfInterest::CIRCLES, {{0.0, 0.0}}, 10.0));
    scenario->addConfiguration(
        configuration("focus", FeatureType::Building, TC::OBJECT, BlendFunction(), new M(M::FOCUS, 0, 10))
            .get());
    scenario->addConfiguration(
        configuration("region", FeatureType::Building, TC::OBJECT, BlendFunction(), new M(M::REGION, 0, 80))
            .get());
    osg::ref_ptr<ScenarioEvaluator> e = new ScenarioEvaluator;
    e->bind(scenario.get(), s.index);
    e->evaluate(osg::Vec3d(0, 0, 1000));
    EXPECT_EQ(e->getView().focus._min, osg::Vec3d(0, 0, 0));
    EXPECT_EQ(e->getView().focus._max, osg::Vec3d(10, 10, 10));
    // Feature 2's centre (13,14,5) is (3,4,0) from the focus box: 5 -> 1 - 5/10 = 0.5.
    EXPECT_NEAR(matchOf(*e, 2, 0).interest, 0.5f, 1e-6f);
    EXPECT_EQ(matchOf(*e, 1, 0).interest, 1.0f); // inside the focus
    // Feature 3's centre (30,40) is 50 from (0,0), 40 from the disc: 1 - 40/80 = 0.5.
    EXPECT_NEAR(matchOf(*e, 3, 1).interest, 0.5f, 1e-6f);
}

// A feature without geometry has no bound and so no match; it is still visible and undrawn.
TEST(ScenarioEvaluatorTest, FeaturesWithoutGeometryHaveNoMatch)
{
    Scene s;
    osg::ref_ptr<osg::Group> empty = new osg::Group;
    Feature::attach(*empty, new Feature(5, FeatureType::Building));
    s.root->addChild(empty.get());
    s.finish();
    osg::ref_ptr<ScenarioEvaluator> e = new ScenarioEvaluator;
    e->bind(ScenarioLibrary::createBuiltin("distance").get(), s.index);
    EXPECT_EQ(e->findFeature(5), 0);
    EXPECT_EQ(e->findFeature(6), -1);
    EXPECT_FALSE(e->features()[0].bound.valid());
    EXPECT_EQ(e->features()[0].numMatches, 0u);
    e->evaluate(osg::Vec3d());
    EXPECT_EQ(e->getStatistics().visibleFeatures, 1u);
    EXPECT_EQ(e->getStatistics().undrawnFeatures, 1u);
}

TEST(ScenarioEvaluatorTest, BindThrowsOnAnInvalidScenario)
{
    Scene s;
    addBox(*s.root, 1, FeatureType::Building, osg::Vec3(0, 0, 0), osg::Vec3(1, 1, 1));
    s.finish();
    osg::ref_ptr<ScenarioEvaluator> e = new ScenarioEvaluator;
    EXPECT_FALSE(e->isBound());
    EXPECT_THROW(e->evaluate(osg::Vec3d()), std::logic_error);

    osg::ref_ptr<UsageScenario> bad = new UsageScenario;
    bad->setName("bad");
    auto message = [&](const UsageScenario* scenario) -> std::string
    {
        try
        {
            e->bind(scenario, s.index);
        }
        catch (const std::invalid_argument& x)
        {
            return x.what();
        }
        return "(no exception)";
    };
    EXPECT_EQ(message(bad.get()),
              "usage scenario 'bad' is not valid: the scenario has no transition configuration");
    EXPECT_EQ(message(nullptr), "no usage scenario to bind");
    osg::ref_ptr<TC> c = configuration("odd", FeatureType::Building, TC::OBJECT, BlendFunction(),
                                       new M(M::VIEW_DISTANCE, 300, 100));
    c->setStyle("watercolour");
    bad->addConfiguration(c.get());
    EXPECT_EQ(message(bad.get()), "usage scenario 'bad' is not valid: configuration 'odd': unknown graphic "
                                  "style 'watercolour' (and 1 more)");
    EXPECT_FALSE(e->isBound());
    // A valid one binds, and keeps the scenario and its revision.
    c->setStyle("photorealistic");
    c->addMetric(new M(M::VIEW_DISTANCE, 100, 300));
    bad->dirty();
    EXPECT_EQ(message(bad.get()), "(no exception)");
    EXPECT_TRUE(e->isBound());
    EXPECT_EQ(e->getScenario(), bad.get());
    EXPECT_EQ(e->getBoundRevision(), 1u);
}

// After bind, evaluate() allocates nothing (it runs every frame).
TEST(ScenarioEvaluatorTest, EvaluateAllocatesNothing)
{
    Scene s;
    osg::ref_ptr<osg::Group> wood = new osg::Group;
    Feature::attach(*wood, new Feature(1000, FeatureType::Green, "wood"));
    s.root->addChild(wood.get());
    for (unsigned i = 0; i < 200; ++i)
    {
        const osg::Vec3 lo(float(i % 20) * 30.0f - 300.0f, float(i / 20) * 30.0f - 150.0f, 0.0f);
        addBox(i % 3 ? *s.root : *wood, i + 1, kFeatureTypes[i % 6], lo, lo + osg::Vec3(10, 10, 5 + i % 7),
               i % 2 ? "deciduous" : "");
    }
    s.finish();
    std::vector<unsigned char> visible(s.index.size(), 1);
    visible[3] = 0;
    for (const std::string& name : ScenarioLibrary::builtinNames())
    {
        osg::ref_ptr<UsageScenario> scenario = ScenarioLibrary::createBuiltin(name);
        osg::ref_ptr<ScenarioEvaluator> e = new ScenarioEvaluator;
        const unsigned long beforeBind = gAllocations.load();
        e->bind(scenario.get(), s.index);
        EXPECT_GT(gAllocations.load(), beforeBind) << "the counter works: bind allocates";
        const unsigned long before = gAllocations.load();
        e->evaluate(osg::Vec3d(10, -400, 150));
        e->evaluate(osg::Vec3d(-50, 20, 600), visible.data());
        const unsigned long after = gAllocations.load();
        EXPECT_EQ(after - before, 0u) << name;
        EXPECT_GT(e->getStatistics().matches, 0u) << name;
    }
}
