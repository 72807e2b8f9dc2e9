// Serializer wrapper for osgLoA::AbstractionNode: a group (its children are the scene) that keeps
// its abstraction style. The style is read as an osgLoA::AbstractionStyle (another class fails the
// read, CheckedObjectSerializer); a style the node refuses (AbstractionStyle::validate) fails the
// read with the node's message instead of throwing out of osgDB. Scenario weighting refers to a
// live LoA node and is not serialized (AbstractionNode::wrapScenario rebuilds it).
#include <osgLoA/abstraction/AbstractionNode>

#include "BoundedListSerializer.h"

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

REGISTER_OBJECT_WRAPPER(osgLoA_AbstractionNode, new osgLoA::AbstractionNode, osgLoA::AbstractionNode,
                        "osg::Object osg::Node osg::Group osgLoA::AbstractionNode")
{
    ADD_REFUSABLE_OBJECT_SERIALIZER(Style, osgLoA::AbstractionStyle, NULL);
    ADD_BOOL_SERIALIZER(Enabled, true);
}
