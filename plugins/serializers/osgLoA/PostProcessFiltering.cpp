// Serializer wrapper for osgLoA::PostProcessFiltering: a group (its children are the scene) that
// keeps its filter and settings. The filter is read as an osgLoA::ImageFilter (another class fails
// the read, CheckedObjectSerializer); a filter without GPU passes, which the node refuses, fails
// the read with the node's message instead of throwing out of osgDB.
#include <osgLoA/filtering/PostProcessFiltering>

#include "BoundedListSerializer.h"

#include <osgDB/InputStream>
#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

#include <stdexcept>

namespace
{
typedef osgLoA::PostProcessFiltering Node;

class FilterSerializer : public osgLoA::CheckedObjectSerializer<Node, osgLoA::ImageFilter>
{
public:
    using CheckedObjectSerializer::CheckedObjectSerializer;
    bool read(osgDB::InputStream& is, osg::Object& obj) override
    {
        try
        {
            return CheckedObjectSerializer::read(is, obj);
        }
        catch (const std::invalid_argument& e)
        {
            is.throwException(e.what());
            return false;
        }
    }
};
} // namespace

REGISTER_OBJECT_WRAPPER(osgLoA_PostProcessFiltering, new osgLoA::PostProcessFiltering,
                        osgLoA::PostProcessFiltering,
                        "osg::Object osg::Node osg::Group osgLoA::PostProcessFiltering")
{
    wrapper->addSerializer(new FilterSerializer(wrapper->getName(), "Filter", "osgLoA::ImageFilter", NULL,
                                                &MyClass::getFilter, &MyClass::setFilter),
                           osgDB::BaseSerializer::RW_OBJECT);
    ADD_BOOL_SERIALIZER(Enabled, true);
    ADD_BOOL_SERIALIZER(MeasureFilterTime, false);
}
