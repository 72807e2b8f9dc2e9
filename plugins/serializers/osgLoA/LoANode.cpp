// Serializer wrapper for osgLoA::LoANode: a group that keeps its usage scenario, so that
// `osgconv city.osgb.loa city-loa.osgb` writes a scene that opens with its scenario. A scenario of
// another class fails the read (CheckedObjectSerializer).
#include <osgLoA/transitions/LoANode>

#include "BoundedListSerializer.h"

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

REGISTER_OBJECT_WRAPPER(osgLoA_LoANode, new osgLoA::LoANode, osgLoA::LoANode,
                        "osg::Object osg::Node osg::Group osgLoA::LoANode")
{
    ADD_CHECKED_OBJECT_SERIALIZER(Scenario, osgLoA::UsageScenario, NULL);
}
