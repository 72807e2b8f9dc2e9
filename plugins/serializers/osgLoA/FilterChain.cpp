// Serializer wrapper for osgLoA::FilterChain: the filters in order, read with a bounded count and
// only ImageFilter entries (BoundedListSerializer.h).
#include <osgLoA/filtering/FilterChain>

#include "BoundedListSerializer.h"

#include <osgDB/ObjectWrapper>

REGISTER_OBJECT_WRAPPER(osgLoA_FilterChain, new osgLoA::FilterChain, osgLoA::FilterChain,
                        "osg::Object osgLoA::ImageFilter osgLoA::FilterChain")
{
    ADD_BOUNDED_LIST_SERIALIZER(Filters, osgLoA::FilterChain::Filters, osgLoA::ImageFilter);
}
