// Serializer wrapper for osgLoA::DeferredTexturing: a group whose settings (setup, budget, fade,
// lighting, the filter as an object) are saved with the scene. The mode reads by name only
// (EnumByNameSerializer). The filter must be an osgLoA::ImageFilter with GPU passes: another
// class, or a CPU-only filter (which DeferredTexturing::setFilter refuses), fails the read with a
// message instead of throwing out of osgDB.
#include <osgLoA/filtering/DeferredTexturing>
#include <osgLoA/styles/GraphicStyle>

#include "BoundedListSerializer.h"
#include "EnumByNameSerializer.h"

#include <osgDB/InputStream>
#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

namespace
{
/** ObjectSerializer of the filter whose read checks the class and the GPU passes. */
class FilterSerializer : public osgDB::ObjectSerializer<osgLoA::DeferredTexturing, osgLoA::ImageFilter>
{
public:
    typedef osgDB::ObjectSerializer<osgLoA::DeferredTexturing, osgLoA::ImageFilter> ParentType;
    FilterSerializer()
        : ParentType("Filter", nullptr, &osgLoA::DeferredTexturing::getFilter,
                     &osgLoA::DeferredTexturing::setFilter)
    {
    }

    bool read(osgDB::InputStream& is, osg::Object& obj) override
    {
        osgLoA::DeferredTexturing& node = OBJECT_CAST<osgLoA::DeferredTexturing&>(obj);
        if (is.getException()) return true; // an earlier property failed; that error stands
        const bool text = !is.isBinary();
        if (text && !is.matchString(_name)) return true;
        bool hasObject = false;
        is >> hasObject;
        if (is.getException()) return false;
        if (!hasObject) return true;
        if (text) is >> is.BEGIN_BRACKET;
        osg::ref_ptr<osg::Object> entry = is.readObject();
        if (is.getException()) return osgLoA::serializer_detail::failInsideBrackets(is);
        osgLoA::ImageFilter* filter = dynamic_cast<osgLoA::ImageFilter*>(entry.get());
        if (!filter)
        {
            is.throwException("DeferredTexturing: Filter: expected an osgLoA::ImageFilter, got " +
                              osgLoA::serializer_detail::describeObject(entry.get()));
            return osgLoA::serializer_detail::failInsideBrackets(is);
        }
        if (!filter->hasGpuImplementation())
        {
            is.throwException(
                "DeferredTexturing: Filter: filter '" + filter->filterName() +
                "' has no GPU implementation and cannot filter per frame; apply it ahead of time "
                "(MipmapFilter)");
            return osgLoA::serializer_detail::failInsideBrackets(is);
        }
        if (text) is >> is.END_BRACKET;
        if (is.getException()) return false;
        node.setFilter(filter);
        return true;
    }
};
} // namespace

REGISTER_OBJECT_WRAPPER(osgLoA_DeferredTexturing, new osgLoA::DeferredTexturing, osgLoA::DeferredTexturing,
                        "osg::Object osg::Node osg::Group osgLoA::DeferredTexturing")
{
    BEGIN_ENUM_BY_NAME_SERIALIZER(Mode, PER_FRAGMENT_CACHED);
    ADD_ENUM_VALUE(PER_LEVEL_CACHED);
    ADD_ENUM_VALUE(PER_FRAGMENT);
    ADD_ENUM_VALUE(PER_FRAGMENT_CACHED);
    END_ENUM_SERIALIZER();
    ADD_UINT_SERIALIZER(BudgetTexels, 0u);
    ADD_UINT_SERIALIZER(FadeFrames, 4u);
    ADD_BOOL_SERIALIZER(TimeFiltering, false);
    ADD_FLOAT_SERIALIZER(Ambient, 0.35f);
    ADD_VEC3F_SERIALIZER(LightDirection, osgLoA::GraphicStyle::defaultLightDirection());
    wrapper->addSerializer(new FilterSerializer, osgDB::BaseSerializer::RW_OBJECT);
}
