// libFuzzer target: arbitrary bytes as a scenario file, read by ScenarioLibrary::readData (the
// guarded entry every scenario reader uses), in process: .osgt and .osgb through
// BoundedObjectReader (OSG's ASCII reader on a throwing stream, OSG's InputStream with our
// bounded binary iterator) with our serializer wrappers (osgdb_serializers_osgloa); a scenario that comes
// out (a UsageScenario, or the one a LoANode carries, as ScenarioLibrary::readFile accepts) is
// validated, and when it validates it is bound to a small fixed scene and evaluated, and the
// evaluator's promises are checked (interest in [0,1], weights normalized, a weighted match may
// draw).
//
// Build and run: scripts/fuzz (FUZZ_SECONDS, default 30). Seed corpus: data/scenarios/*.osgt and
// tests/fuzz/corpus/scenario (binary copies).
#include <osgLoA/semantics/Feature>
#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/ScenarioEvaluator>
#include <osgLoA/transitions/ScenarioLibrary>
#include <osgLoA/transitions/UsageScenario>
#include <osgLoA/util/BoundedObjectReader>

#include "FuzzSupport.h"

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Group>
#include <osg/Notify>
#include <osgDB/ObjectWrapper>
#include <osgDB/Registry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

namespace
{
using namespace osgLoA;

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

struct Scene
{
    osg::ref_ptr<osg::Group> root = fuzz::smallCity(true);
    FeatureIndex index;
    Scene()
    {
        index.build(*root);
        index.updateBounds();
    }
};

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    static Scene scene;
    // XML scenario files are parsed by the helper process loa-scenario-parse (OSG's XML reader
    // is not bounded in process), a spawn per input: outside what this target measures.
    if (BoundedObjectReader::formatOf(
            std::string(reinterpret_cast<const char*>(data), std::min<std::size_t>(size, 64))) ==
        BoundedObjectReader::Format::Xml)
        return 0;

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
