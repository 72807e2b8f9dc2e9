// UsageScenario (paper 004 §3.1 "Scenario Definition"): validation errors and warnings, the
// static interest under overrides, and the deep copy.
#include <osgLoA/transitions/ScenarioLibrary>
#include <osgLoA/transitions/UsageScenario>

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

using namespace osgLoA;

namespace
{
typedef SaliencyMetric M;
typedef TransitionConfiguration TC;

osg::ref_ptr<TC> configuration(const std::string& name, const TC::FeatureTypes& types, M* metric,
                               const std::string& style = "photorealistic")
{
    osg::ref_ptr<TC> c = new TC;
    c->setName(name);
    c->setFeatureTypes(types);
    c->setStyle(style);
    c->addMetric(metric);
    return c;
}

osg::ref_ptr<TC> everything(const std::string& name)
{
    osg::ref_ptr<TC> c = configuration(name, {}, new M(M::VIEW_DISTANCE, 100, 300));
    c->setAllFeatureTypes();
    return c;
}

bool contains(const std::vector<std::string>& list, const std::string& s)
{
    return std::find(list.begin(), list.end(), s) != list.end();
}

std::string join(const std::vector<std::string>& list)
{
    std::string out;
    for (const std::string& s : list)
        out += s + "\n";
    return out;
}
} // namespace

TEST(UsageScenarioTest, AScenarioWithoutConfigurationIsAnError)
{
    osg::ref_ptr<UsageScenario> s = new UsageScenario;
    const UsageScenario::Validation v = s->validate();
    EXPECT_FALSE(v.ok());
    EXPECT_EQ(v.errors, std::vector<std::string>{"the scenario has no transition configuration"});
    EXPECT_TRUE(v.warnings.empty()) << join(v.warnings); // no "type not drawn" noise on top
}

TEST(UsageScenarioTest, AtMostMaxConfigurations)
{
    osg::ref_ptr<UsageScenario> s = new UsageScenario;
    for (unsigned i = 0; i < UsageScenario::kMaxConfigurations; ++i)
        s->addConfiguration(everything("c" + std::to_string(i)).get());
    EXPECT_TRUE(s->validate().ok()) << join(s->validate().errors);
    s->addConfiguration(everything("one-too-many").get());
    const UsageScenario::Validation v = s->validate();
    EXPECT_EQ(v.errors,
              std::vector<std::string>{
                  "the scenario has 17 configurations; the renderer's fragment stage holds at most 16"});
}

TEST(UsageScenarioTest, RegionMetricNeedsAUsableRegion)
{
    osg::ref_ptr<UsageScenario> s = new UsageScenario;
    osg::ref_ptr<TC> c = configuration("route", {}, new M(M::REGION, 10, 100));
    c->setAllFeatureTypes();
    s->addConfiguration(c.get());
    EXPECT_EQ(s->validate().errors,
              std::vector<std::string>{
                  "configuration 'route': uses the region metric but the scenario has no usable region"});
    // A degenerate region is reported itself and does not count as usable.
    osg::ref_ptr<RegionOfInterest> bad = new RegionOfInterest(RegionOfInterest::POLYGON, {{0, 0}, {1, 1}});
    bad->setName("old town");
    s->addRegion(bad.get());
    EXPECT_EQ(s->validate().errors,
              (std::vector<std::string>{
                  "region: polygon 'old town' has 2 vertices; it needs at least 3",
                  "configuration 'route': uses the region metric but the scenario has no usable region"}));
    // One usable region is enough for the metric; the bad one is still an error.
    s->addRegion(new RegionOfInterest(RegionOfInterest::POLYLINE, {{0, 0}, {100, 0}}, 5.0));
    EXPECT_EQ(s->validate().errors,
              std::vector<std::string>{"region: polygon 'old town' has 2 vertices; it needs at least 3"});
    s->getRegions().erase(s->getRegions().begin());
    EXPECT_TRUE(s->validate().ok()) << join(s->validate().errors);
    s->addRegion(nullptr);
    EXPECT_EQ(s->validate().errors, std::vector<std::string>{"a null region of interest"});
}

TEST(UsageScenarioTest, FocusMetricNeedsAFocusObject)
{
    osg::ref_ptr<UsageScenario> s = new UsageScenario;
    osg::ref_ptr<TC> c = configuration("blueprint", {}, new M(M::FOCUS, 10, 100), "blueprint");
    c->setAllFeatureTypes();
    s->addConfiguration(c.get());
    EXPECT_EQ(s->validate().errors,
              std::vector<std::string>{
                  "configuration 'blueprint': uses the focus metric but the scenario has no focus object"});
    s->setFocusFeature(42);
    EXPECT_TRUE(s->validate().ok()) << join(s->validate().errors);
}

TEST(UsageScenarioTest, UndrawnTypesAndDuplicateNamesAreWarnings)
{
    osg::ref_ptr<UsageScenario> s = new UsageScenario;
    s->addConfiguration(
        configuration("a", {FeatureType::Building, FeatureType::Water}, new M(M::VIEW_DISTANCE, 1, 2)).get());
    // 'hidden' draws nothing: its street type still counts as undrawn.
    s->addConfiguration(
        configuration("a", {FeatureType::Street}, new M(M::VIEW_DISTANCE, 1, 2), "hidden").get());
    const UsageScenario::Validation v = s->validate();
    EXPECT_TRUE(v.ok()) << join(v.errors);
    EXPECT_TRUE(contains(v.warnings, "two configurations are named 'a'")) << join(v.warnings);
    for (const char* t : {"street", "green", "terrain", "generic"})
        EXPECT_TRUE(contains(v.warnings, std::string("no configuration draws ") + t +
                                             " features: they will not be drawn"))
            << t << "\n"
            << join(v.warnings);
    EXPECT_FALSE(contains(v.warnings, "no configuration draws building features: they will not be drawn"));
    EXPECT_FALSE(contains(v.warnings, "no configuration draws water features: they will not be drawn"));
    EXPECT_EQ(v.warnings.size(), 5u) << join(v.warnings);
    // Unnamed configurations are not "duplicates" of each other.
    osg::ref_ptr<UsageScenario> unnamed = new UsageScenario;
    unnamed->addConfiguration(everything("").get());
    unnamed->addConfiguration(everything("").get());
    EXPECT_TRUE(unnamed->validate().warnings.empty()) << join(unnamed->validate().warnings);
}

TEST(UsageScenarioTest, ConfigurationErrorsAreCollected)
{
    osg::ref_ptr<UsageScenario> s = new UsageScenario;
    s->addConfiguration(nullptr);
    osg::ref_ptr<TC> c = everything("odd");
    c->setStyle("watercolour");
    s->addConfiguration(c.get());
    EXPECT_EQ(s->validate().errors,
              (std::vector<std::string>{"a null transition configuration",
                                        "configuration 'odd': unknown graphic style 'watercolour'"}));
}

TEST(UsageScenarioTest, EveryBuiltinScenarioValidatesWithoutWarnings)
{
    for (const std::string& name : ScenarioLibrary::builtinNames())
    {
        const UsageScenario::Validation v = ScenarioLibrary::createBuiltin(name)->validate();
        EXPECT_TRUE(v.ok()) << name << ": " << join(v.errors);
        EXPECT_TRUE(v.warnings.empty()) << name << ": " << join(v.warnings);
    }
}

TEST(UsageScenarioTest, StaticInterestAndLookups)
{
    osg::ref_ptr<UsageScenario> s = new UsageScenario;
    osg::ref_ptr<Feature> f = new Feature(3, FeatureType::Water);
    f->setInterest(0.4f);
    EXPECT_FLOAT_EQ(s->staticInterestOf(*f), 0.4f); // no overrides: the feature's own
    osg::ref_ptr<FeatureInterest> fi = new FeatureInterest;
    fi->setTypeInterest(FeatureType::Water, 0.7f);
    s->setInterest(fi.get());
    EXPECT_FLOAT_EQ(s->staticInterestOf(*f), 0.7f);
    fi->setFeatureInterest(3, 0.1f);
    EXPECT_FLOAT_EQ(s->staticInterestOf(*f), 0.1f);
    EXPECT_FLOAT_EQ(f->getInterest(), 0.4f); // the feature is not changed

    TC* c = s->addConfiguration(everything("x").get());
    EXPECT_EQ(s->findConfiguration("x"), c);
    EXPECT_EQ(s->findConfiguration("y"), nullptr);
    const unsigned r = s->getRevision();
    s->dirty();
    EXPECT_EQ(s->getRevision(), r + 1);
}

TEST(UsageScenarioTest, DeepCopyCopiesEverything)
{
    osg::ref_ptr<UsageScenario> s = ScenarioLibrary::createBuiltin("route");
    osg::ref_ptr<FeatureInterest> fi = new FeatureInterest;
    fi->setTypeInterest(FeatureType::Green, 0.3f);
    s->setInterest(fi.get());
    s->setFocusFeature(7);
    osg::ref_ptr<UsageScenario> d = new UsageScenario(*s, osg::CopyOp::DEEP_COPY_ALL);
    EXPECT_EQ(d->getName(), s->getName());
    EXPECT_EQ(d->getDescription(), s->getDescription());
    EXPECT_EQ(d->getFocusFeature(), 7u);
    ASSERT_TRUE(d->getInterest());
    EXPECT_NE(d->getInterest(), s->getInterest());
    EXPECT_FLOAT_EQ(d->getInterest()->getTypeInterest(FeatureType::Green), 0.3f);
    ASSERT_EQ(d->getConfigurations().size(), s->getConfigurations().size());
    for (std::size_t i = 0; i < s->getConfigurations().size(); ++i)
    {
        const TC* a = s->getConfigurations()[i].get();
        const TC* b = d->getConfigurations()[i].get();
        EXPECT_NE(a, b);
        EXPECT_EQ(a->getName(), b->getName());
        EXPECT_EQ(a->getFeatureTypes(), b->getFeatureTypes());
        EXPECT_EQ(a->getBlendFunction(), b->getBlendFunction());
        ASSERT_EQ(a->getMetrics().size(), b->getMetrics().size());
        EXPECT_NE(a->getMetrics()[0].get(), b->getMetrics()[0].get());
        EXPECT_EQ(a->getMetrics()[0]->getKind(), b->getMetrics()[0]->getKind());
    }
    ASSERT_EQ(d->getRegions().size(), 1u);
    EXPECT_NE(d->getRegions()[0].get(), s->getRegions()[0].get());
    EXPECT_EQ(d->getRegions()[0]->getVertices(), s->getRegions()[0]->getVertices());
    EXPECT_EQ(d->getRegions()[0]->getRadius(), s->getRegions()[0]->getRadius());
    // Editing the copy leaves the original alone.
    d->getConfigurations()[0]->setStyle("abstract");
    d->getConfigurations()[0]->getMetrics()[0]->setNear(0.1);
    d->getRegions()[0]->setRadius(99.0);
    d->getInterest()->setTypeInterest(FeatureType::Green, 0.9f);
    EXPECT_EQ(s->getConfigurations()[0]->getStyle(), "photorealistic");
    EXPECT_EQ(s->getConfigurations()[0]->getMetrics()[0]->getNear(), 0.03); // route: in units of S
    EXPECT_EQ(s->getRegions()[0]->getRadius(), 0.01);
    EXPECT_FLOAT_EQ(s->getInterest()->getTypeInterest(FeatureType::Green), 0.3f);
    EXPECT_TRUE(d->validate().ok());
}

// OSG's convention: a shallow copy shares the configurations, regions and overrides; only a
// deep copy clones them.
TEST(UsageScenarioTest, ShallowCopySharesChildren)
{
    osg::ref_ptr<UsageScenario> s = ScenarioLibrary::createBuiltin("route");
    s->setInterest(new FeatureInterest);
    osg::ref_ptr<UsageScenario> shallow = new UsageScenario(*s, osg::CopyOp::SHALLOW_COPY);
    EXPECT_EQ(shallow->getConfigurations()[0].get(), s->getConfigurations()[0].get());
    EXPECT_EQ(shallow->getRegions()[0].get(), s->getRegions()[0].get());
    EXPECT_EQ(shallow->getInterest(), s->getInterest());
    osg::ref_ptr<TransitionConfiguration> c =
        new TransitionConfiguration(*s->getConfigurations()[0], osg::CopyOp::SHALLOW_COPY);
    EXPECT_EQ(c->getMetrics()[0].get(), s->getConfigurations()[0]->getMetrics()[0].get());
    osg::ref_ptr<UsageScenario> deep = new UsageScenario(*s, osg::CopyOp::DEEP_COPY_ALL);
    EXPECT_NE(deep->getConfigurations()[0].get(), s->getConfigurations()[0].get());
    EXPECT_NE(deep->getConfigurations()[0]->getMetrics()[0].get(),
              s->getConfigurations()[0]->getMetrics()[0].get());
}
