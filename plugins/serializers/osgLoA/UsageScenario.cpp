// Serializer wrapper for osgLoA::UsageScenario (.osgt/.osgb/.osgx): a scenario library entry.
#include <osgLoA/transitions/UsageScenario>

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

REGISTER_OBJECT_WRAPPER(osgLoA_UsageScenario, new osgLoA::UsageScenario, osgLoA::UsageScenario,
                        "osg::Object osgLoA::UsageScenario")
{
    ADD_STRING_SERIALIZER(Description, "");
    ADD_OBJECT_SERIALIZER(Interest, osgLoA::FeatureInterest, NULL);
    ADD_LIST_SERIALIZER(Configurations, osgLoA::UsageScenario::Configurations);
    ADD_LIST_SERIALIZER(Regions, osgLoA::UsageScenario::Regions);
    ADD_UINT_SERIALIZER(FocusFeature, 0u);
}
