// libFuzzer target: arbitrary bytes as a classification rule set (.osgt, .osgb), read by
// ClassificationRuleSet::readData (BoundedObjectReader, then validate(), as `--rules FILE` and a
// .loa file's "rules" read them), then used as the tools use it: before the default rules, and
// alone, each classifying a small city whose parts carry only names. Every classification must
// count each unit once: by a rule, by appearance, or unclassified.
//
// Build and run: scripts/fuzz (FUZZ_TARGETS=RuleSetFuzzer). Seed corpus: tests/fuzz/corpus/rules.
#include <osgLoA/semantics/ClassificationRuleSet>
#include <osgLoA/semantics/FeatureClassifier>

#include <osg/Notify>
#include <osgDB/Registry>

#include "FuzzSupport.h"

#include <cstdint>
#include <stdexcept>
#include <string>

namespace
{
const char* const kTarget = "RuleSetFuzzer";

void classifyWith(osgLoA::ClassificationRuleSet* rules)
{
    osg::ref_ptr<osg::Group> city = fuzz::smallCity(false);
    osgLoA::FeatureClassifier::Report r;
    try
    {
        r = osgLoA::FeatureClassifier(rules).classify(*city);
    }
    catch (const std::invalid_argument&)
    {
        fuzz::fail(kTarget, "a rule set that validated was refused by the classifier");
    }
    if (r.units == 0) fuzz::fail(kTarget, "no units classified");
    // The city carries no model data: each unit is classified by a rule, by appearance, or not.
    if (r.byRule + r.byAppearance + r.unclassified != r.units)
        fuzz::fail(kTarget, "units counted wrongly: " + r.summary());
}
} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    osg::setNotifyLevel(osg::FATAL);
    if (!osgDB::Registry::instance()->getObjectWrapperManager()->findWrapper("osgLoA::ClassificationRuleSet"))
        fuzz::fail(kTarget,
                   "no wrapper for osgLoA::ClassificationRuleSet (is OSG_LIBRARY_PATH the build's lib?)");
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    osg::ref_ptr<osgLoA::ClassificationRuleSet> user;
    try
    {
        user = osgLoA::ClassificationRuleSet::readData(std::string(reinterpret_cast<const char*>(data), size),
                                                       "fuzz.osgt");
    }
    catch (const std::exception& e)
    {
        if (std::string(e.what()).empty()) fuzz::fail(kTarget, "an error without a message");
        return 0;
    }
    classifyWith(osgLoA::ClassificationRuleSet::withDefaults(*user).get());
    classifyWith(user.get());
    return 0;
}
