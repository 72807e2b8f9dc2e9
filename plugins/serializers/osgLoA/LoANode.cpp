// Serializer wrapper for osgLoA::LoANode: a group that keeps its usage scenario, so that
// `osgconv city.osgb.loa city-loa.osgb` writes a scene that opens with its scenario.
#include <osgLoA/transitions/LoANode>

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

REGISTER_OBJECT_WRAPPER(osgLoA_LoANode, new osgLoA::LoANode, osgLoA::LoANode,
                        "osg::Object osg::Node osg::Group osgLoA::LoANode")
{
    ADD_OBJECT_SERIALIZER(Scenario, osgLoA::UsageScenario, NULL);
}
