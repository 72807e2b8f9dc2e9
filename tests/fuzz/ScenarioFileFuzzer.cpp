// libFuzzer target: arbitrary bytes as a scenario file, read by ScenarioLibrary::readData (the
// guarded entry every scenario reader uses), which hands them to OSG's own reader
// for .osgt/.osgb/.osgx (osgdb_osg's ReaderWriter, which tells the three formats apart by
// their header) with our serializer wrappers (osgdb_serializers_osgloa); a scenario that comes
// out (a UsageScenario, or the one a LoANode carries, as ScenarioLibrary::readFile accepts) is
// validated, and when it validates it is bound to a small fixed scene and evaluated, and the
// evaluator's promises are checked (interest in [0,1], weights normalized, a weighted match may
// draw).
//
// Build and run: scripts/fuzz (FUZZ_SECONDS, default 30). Seed corpus: data/scenarios/*.osgt.
#include <osgLoA/semantics/Feature>
#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/ScenarioEvaluator>
#include <osgLoA/transitions/ScenarioLibrary>
#include <osgLoA/transitions/UsageScenario>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Group>
#include <osg/Notify>
#include <osgDB/ObjectWrapper>
#include <osgDB/Registry>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

namespace
{
using namespace osgLoA;

osg::ref_ptr<osg::Geode> box(const osg::Vec3& minimum, const osg::Vec3& maximum)
{
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    for (int i = 0; i < 8; ++i)
        v->push_back(osg::Vec3(i & 1 ? maximum.x() : minimum.x(), i & 2 ? maximum.y() : minimum.y(),
                               i & 4 ? maximum.z() : minimum.z()));
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    g->setVertexArray(v.get());
    g->addPrimitiveSet(new osg::DrawArrays(GL_POINTS, 0, 8));
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(g.get());
    return geode;
}

osg::Geode* addFeature(osg::Group& parent, Feature* f, const osg::Vec3& minimum, const osg::Vec3& maximum)
{
    osg::ref_ptr<osg::Geode> g = box(minimum, maximum);
    Feature::attach(*g, f);
    parent.addChild(g.get());
    return g.get();
}

/** Every feature type, sub-types, a known and an unknown LoD, a landmark, a wood of trees (a
 *  nested group), and feature 1 (the blueprint scenario's focus object). */
struct Scene
{
    osg::ref_ptr<osg::Group> root = new osg::Group;
    FeatureIndex index;

    Scene()
    {
        osg::ref_ptr<Feature> landmark = new Feature(1, FeatureType::Building, "church");
        landmark->setInterest(1.0f);
        landmark->setLod(2.0f);
        addFeature(*root, landmark.get(), osg::Vec3(-10, -10, 0), osg::Vec3(10, 10, 40));
        addFeature(*root, new Feature(2, FeatureType::Building), osg::Vec3(100, 0, 0),
                   osg::Vec3(120, 20, 15));
        addFeature(*root, new Feature(3, FeatureType::Street, "major"), osg::Vec3(-500, -4, 0),
                   osg::Vec3(500, 4, 0.2f));
        addFeature(*root, new Feature(4, FeatureType::Water, "river"), osg::Vec3(-500, 200, -1),
                   osg::Vec3(500, 260, 0));
        addFeature(*root, new Feature(5, FeatureType::Terrain), osg::Vec3(-500, -500, -5),
                   osg::Vec3(500, 500, 0));
        addFeature(*root, new Feature(6, FeatureType::Generic), osg::Vec3(-300, -300, 0),
                   osg::Vec3(-299, -299, 3));
        osg::ref_ptr<osg::Group> wood = new osg::Group;
        Feature::attach(*wood, new Feature(7, FeatureType::Green, "mixed forest"));
        root->addChild(wood.get());
        for (unsigned i = 0; i < 4; ++i)
            addFeature(*wood, new Feature(8 + i, FeatureType::Green, i % 2 ? "coniferous" : "deciduous"),
                       osg::Vec3(300.0f + 10.0f * i, 300, 0), osg::Vec3(304.0f + 10.0f * i, 304, 12));
        index.build(*root);
        index.updateBounds();
    }
};

[[noreturn]] void fail(const char* what, double value)
{
    std::fprintf(stderr, "ScenarioFileFuzzer: %s (%g)\n", what, value);
    std::abort();
}

void checkEvaluation(const ScenarioEvaluator& e)
{
    for (const ScenarioEvaluator::FeatureState& f : e.features())
    {
        if (!f.visible) continue;
        const ScenarioEvaluator::Match* m = e.matchesOf(f);
        double sum = 0.0;
        bool anyRaw = false;
        for (unsigned k = 0; k < f.numMatches; ++k)
        {
            if (!(m[k].interest >= 0.0f && m[k].interest <= 1.0f))
                fail("interest outside [0,1]", m[k].interest);
            if (!(m[k].rawWeight >= 0.0f && m[k].rawWeight <= 1.0f))
                fail("raw weight outside [0,1]", m[k].rawWeight);
            if (m[k].rawWeight > 0.0f && !m[k].mayContribute)
                fail("weighted match may not contribute", m[k].rawWeight);
            sum += m[k].weight;
            anyRaw = anyRaw || m[k].rawWeight > 0.0f;
        }
        if (anyRaw && std::fabs(sum - 1.0) > 1e-5) fail("normalized weights do not sum to 1", sum);
        if (!anyRaw && sum != 0.0) fail("weights of an undrawn feature are not 0", sum);
    }
}
} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    osg::setNotifyLevel(osg::FATAL); // malformed input makes OSG warn on every field
    // Load the reader and our wrappers now, so that their coverage counters exist from the start.
    if (!osgDB::Registry::instance()->getReaderWriterForExtension("osgt"))
        fail("no osgt reader (osgdb_osg plugin missing)", 0.0);
    if (!osgDB::Registry::instance()->getObjectWrapperManager()->findWrapper("osgLoA::UsageScenario"))
        fail("no wrapper for osgLoA::UsageScenario (is OSG_LIBRARY_PATH the build's lib?)", 0.0);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    static Scene scene;

    // The guarded entry point every reader of scenario files goes through.
    osg::ref_ptr<UsageScenario> scenario;
    try
    {
        scenario = ScenarioLibrary::readData(std::string(reinterpret_cast<const char*>(data), size), "fuzz");
    }
    catch (const ScenarioError&)
    {
        return 0;
    }
    if (!scenario) return 0;
    if (!scenario->validate().ok()) return 0;

    osg::ref_ptr<ScenarioEvaluator> evaluator = new ScenarioEvaluator;
    evaluator->bind(scenario.get(), scene.index); // validated: must not throw
    evaluator->evaluate(osg::Vec3d(-250.0, -400.0, 120.0));
    checkEvaluation(*evaluator);
    std::vector<unsigned char> visible(evaluator->features().size());
    for (std::size_t i = 0; i < visible.size(); ++i)
        visible[i] = i % 2;
    evaluator->evaluate(osg::Vec3d(0.0, 0.0, 2000.0), visible.data());
    checkEvaluation(*evaluator);
    return 0;
}
