// Serializer wrappers for osgLoA::FilterConfiguration and its osgLoA::FilterChannel entries
// (.osgt/.osgb/.osgx). Channels are a bounded list of FilterChannel objects; a channel's
// per-feature-type filters are written by type name ("building", "water", ...), each with TRUE
// and the filter object, or FALSE for "none" (the type stays unfiltered). Unknown type names,
// objects that are not ImageFilters and implausible counts fail the read with a message.
#include <osgLoA/filtering/FilterConfiguration>

#include "BoundedListSerializer.h"

#include <osgDB/InputStream>
#include <osgDB/ObjectWrapper>
#include <osgDB/OutputStream>
#include <osgDB/Serializer>

namespace
{
typedef osgLoA::FilterChannel Channel;

bool checkTypeFilters(const Channel& c)
{
    return !c.getTypeFilters().empty();
}

bool readTypeFilters(osgDB::InputStream& is, Channel& c)
{
    const unsigned size = is.readSize();
    if (is.getException()) return false;
    if (size > 64) // six types; anything larger is a broken file
    {
        is.throwException("FilterChannel: implausible TypeFilters count " + std::to_string(size));
        return false;
    }
    Channel::TypeFilters filters;
    is >> is.BEGIN_BRACKET;
    for (unsigned i = 0; i < size && !is.getException(); ++i)
    {
        std::string name;
        is.readWrappedString(name);
        osgLoA::FeatureType type;
        if (!is.getException() && !osgLoA::parseFeatureType(name, type))
        {
            is.throwException("FilterChannel: unknown feature type '" + name + "' in TypeFilters");
            break;
        }
        bool hasFilter = false;
        is >> hasFilter;
        if (is.getException()) break;
        osg::ref_ptr<osgLoA::ImageFilter> filter;
        if (hasFilter)
        {
            if (!is.isBinary()) is >> is.BEGIN_BRACKET;
            osg::ref_ptr<osg::Object> object = is.readObject();
            if (is.getException()) break;
            filter = dynamic_cast<osgLoA::ImageFilter*>(object.get());
            if (!filter)
            {
                is.throwException(
                    "FilterChannel: TypeFilters entry '" + name + "': expected an osgLoA::ImageFilter, got " +
                    (object.valid() ? std::string(object->libraryName()) + "::" + object->className()
                                    : std::string("no object (an unknown class)")));
                break;
            }
            if (!is.isBinary()) is >> is.END_BRACKET;
        }
        filters[type] = filter;
    }
    if (is.getException())
    {
        if (!is.isBinary()) is.advanceToCurrentEndBracket();
        return false;
    }
    is >> is.END_BRACKET;
    c.setTypeFilters(filters);
    return true;
}

bool writeTypeFilters(osgDB::OutputStream& os, const Channel& c)
{
    const Channel::TypeFilters& filters = c.getTypeFilters();
    os.writeSize(static_cast<unsigned int>(filters.size()));
    os << os.BEGIN_BRACKET << std::endl;
    for (const auto& kv : filters)
    {
        os.writeWrappedString(osgLoA::toString(kv.first));
        const bool hasFilter = kv.second.valid();
        os << hasFilter;
        if (hasFilter)
        {
            if (!os.isBinary()) os << os.BEGIN_BRACKET << std::endl;
            os.writeObject(kv.second.get());
            if (!os.isBinary()) os << os.END_BRACKET;
        }
        os << std::endl;
    }
    os << os.END_BRACKET << std::endl;
    return true;
}
} // namespace

// Two wrappers in one file: each in its own namespace (each declares its MyClass).
namespace filter_channel_wrapper
{
REGISTER_OBJECT_WRAPPER(osgLoA_FilterChannel, new osgLoA::FilterChannel, osgLoA::FilterChannel,
                        "osg::Object osgLoA::FilterChannel")
{
    ADD_UINT_SERIALIZER(Unit, 0u);
    ADD_INT_SERIALIZER(FilteredUnit, -1);
    ADD_STRING_SERIALIZER(SamplerUniform, "");
    ADD_STRING_SERIALIZER(FlagUniform, "");
    ADD_CHECKED_OBJECT_SERIALIZER(DefaultFilter, osgLoA::ImageFilter, NULL);
    ADD_USER_SERIALIZER(TypeFilters);
}
} // namespace filter_channel_wrapper

namespace filter_configuration_wrapper
{
REGISTER_OBJECT_WRAPPER(osgLoA_FilterConfiguration, new osgLoA::FilterConfiguration,
                        osgLoA::FilterConfiguration, "osg::Object osgLoA::FilterConfiguration")
{
    ADD_BOUNDED_LIST_SERIALIZER(Channels, osgLoA::FilterConfiguration::Channels, osgLoA::FilterChannel);
}
} // namespace filter_configuration_wrapper
