// Serializer wrapper for osgLoA::UsageScenario (.osgt/.osgb/.osgx): a scenario library entry. The
// lists are bounded and type-checked, the interest type-checked (BoundedListSerializer.h).
#include <osgLoA/transitions/UsageScenario>

#include "BoundedListSerializer.h"

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

REGISTER_OBJECT_WRAPPER(osgLoA_UsageScenario, new osgLoA::UsageScenario, osgLoA::UsageScenario,
                        "osg::Object osgLoA::UsageScenario")
{
    ADD_STRING_SERIALIZER(Description, "");
    ADD_CHECKED_OBJECT_SERIALIZER(Interest, osgLoA::FeatureInterest, NULL);
    ADD_BOUNDED_LIST_SERIALIZER(Configurations, osgLoA::UsageScenario::Configurations,
                                osgLoA::TransitionConfiguration);
    ADD_BOUNDED_LIST_SERIALIZER(Regions, osgLoA::UsageScenario::Regions, osgLoA::RegionOfInterest);
    ADD_UINT_SERIALIZER(FocusFeature, 0u);
    // Last, so that text files written before it read as before (no deformation).
    ADD_CHECKED_OBJECT_SERIALIZER(LandmarkDeformation, osgLoA::LandmarkDeformation, NULL);
    ADD_BOOL_SERIALIZER(FocusTallestLandmark, false); // issue 18: after the older fields
    ADD_STRING_SERIALIZER(ColorScheme, "");           // issue 19: after the older fields
}
