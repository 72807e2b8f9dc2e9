// Serializer wrapper for osgLoA::ClassificationRuleSet.
#include <osgLoA/semantics/ClassificationRuleSet>

#include <osgDB/InputStream>
#include <osgDB/ObjectWrapper>
#include <osgDB/OutputStream>
#include <osgDB/Serializer>

namespace
{
bool checkRules(const osgLoA::ClassificationRuleSet& set)
{
    return !set.getRules().empty();
}

bool readRules(osgDB::InputStream& is, osgLoA::ClassificationRuleSet& set)
{
    unsigned int size = is.readSize();
    is >> is.BEGIN_BRACKET;
    osgLoA::ClassificationRuleSet::Rules rules;
    for (unsigned int i = 0; i < size; ++i)
    {
        osg::ref_ptr<osgLoA::ClassificationRule> rule = is.readObjectOfType<osgLoA::ClassificationRule>();
        if (rule) rules.push_back(rule);
    }
    is >> is.END_BRACKET;
    set.setRules(rules);
    return true;
}

bool writeRules(osgDB::OutputStream& os, const osgLoA::ClassificationRuleSet& set)
{
    const osgLoA::ClassificationRuleSet::Rules& rules = set.getRules();
    os.writeSize(static_cast<unsigned int>(rules.size()));
    os << os.BEGIN_BRACKET << std::endl;
    for (const auto& r : rules)
        os << r.get();
    os << os.END_BRACKET << std::endl;
    return true;
}
} // namespace

// clang-format off
REGISTER_OBJECT_WRAPPER(osgLoA_ClassificationRuleSet, new osgLoA::ClassificationRuleSet, osgLoA::ClassificationRuleSet,
                        "osg::Object osgLoA::ClassificationRuleSet")
{
    ADD_USER_SERIALIZER(Rules);
    ADD_BOOL_SERIALIZER(OverrideModelData, false);
    ADD_BOOL_SERIALIZER(UseAppearance, true);
    ADD_FLOAT_SERIALIZER(AppearanceThreshold, 10.0f);
    ADD_BOOL_SERIALIZER(GroupObjects, true);
    ADD_STRING_SERIALIZER(MergeTouchingTypes, "building");
    ADD_FLOAT_SERIALIZER(MergeTolerance, 0.05f);
}
// clang-format on
