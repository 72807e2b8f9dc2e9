// Serializer wrapper for osgLoA::PostProcessFiltering: a group (its children are the scene) that
// keeps its filter and settings. The filter is read as an osgLoA::ImageFilter (another class fails
// the read, CheckedObjectSerializer); a filter without GPU passes, which the node refuses, fails
// the read with the node's message instead of throwing out of osgDB.
#include <osgLoA/filtering/PostProcessFiltering>

#include "BoundedListSerializer.h"

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

REGISTER_OBJECT_WRAPPER(osgLoA_PostProcessFiltering, new osgLoA::PostProcessFiltering,
                        osgLoA::PostProcessFiltering,
                        "osg::Object osg::Node osg::Group osgLoA::PostProcessFiltering")
{
    ADD_REFUSABLE_OBJECT_SERIALIZER(Filter, osgLoA::ImageFilter, NULL);
    ADD_BOOL_SERIALIZER(Enabled, true);
    ADD_BOOL_SERIALIZER(MeasureFilterTime, false);
}
