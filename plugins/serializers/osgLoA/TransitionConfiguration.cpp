// Serializer wrapper for osgLoA::TransitionConfiguration (.osgt/.osgb/.osgx). Feature types
// are written by name (FeatureType's toString) and sub-types as quoted strings, so the files
// neither depend on enum values nor break on spaces. The enums read by name only
// (EnumByNameSerializer) and the metrics list is bounded and type-checked (BoundedListSerializer.h).
#include <osgLoA/transitions/TransitionConfiguration>

#include "BoundedListSerializer.h"
#include "EnumByNameSerializer.h"

#include <osgDB/InputStream>
#include <osgDB/ObjectWrapper>
#include <osgDB/OutputStream>
#include <osgDB/Serializer>

namespace
{
// A count larger than any sane file holds is an error, not a reason to loop for minutes.
constexpr unsigned kMaxListSize = 1u << 16;

bool checkFeatureTypes(const osgLoA::TransitionConfiguration& c)
{
    return !c.getFeatureTypes().empty();
}

bool readFeatureTypes(osgDB::InputStream& is, osgLoA::TransitionConfiguration& c)
{
    const unsigned size = is.readSize();
    if (size > kMaxListSize)
    {
        is.throwException("TransitionConfiguration: implausible feature type count " + std::to_string(size));
        return false;
    }
    osgLoA::TransitionConfiguration::FeatureTypes types;
    is >> is.BEGIN_BRACKET;
    for (unsigned i = 0; i < size && !is.getException(); ++i)
    {
        std::string name;
        is >> name;
        osgLoA::FeatureType t;
        if (!osgLoA::parseFeatureType(name, t))
        {
            is.throwException("TransitionConfiguration: unknown feature type '" + name + "'");
            return false;
        }
        types.push_back(t);
    }
    is >> is.END_BRACKET;
    c.setFeatureTypes(types);
    return true;
}

bool writeFeatureTypes(osgDB::OutputStream& os, const osgLoA::TransitionConfiguration& c)
{
    os.writeSize(c.getFeatureTypes().size());
    os << os.BEGIN_BRACKET << std::endl;
    for (osgLoA::FeatureType t : c.getFeatureTypes())
        os << std::string(osgLoA::toString(t)) << std::endl;
    os << os.END_BRACKET << std::endl;
    return true;
}

bool checkSubTypes(const osgLoA::TransitionConfiguration& c)
{
    return !c.getSubTypes().empty();
}

bool readSubTypes(osgDB::InputStream& is, osgLoA::TransitionConfiguration& c)
{
    osgLoA::TransitionConfiguration::SubTypes subTypes;
    if (!osgLoA::readBoundedStrings(is, "TransitionConfiguration: implausible sub-type", kMaxListSize,
                                    subTypes))
        return false;
    c.setSubTypes(subTypes);
    return true;
}

bool writeSubTypes(osgDB::OutputStream& os, const osgLoA::TransitionConfiguration& c)
{
    return osgLoA::writeStrings(os, c.getSubTypes());
}
} // namespace

REGISTER_OBJECT_WRAPPER(osgLoA_TransitionConfiguration, new osgLoA::TransitionConfiguration,
                        osgLoA::TransitionConfiguration, "osg::Object osgLoA::TransitionConfiguration")
{
    ADD_USER_SERIALIZER(FeatureTypes);
    ADD_USER_SERIALIZER(SubTypes);
    ADD_VEC2F_SERIALIZER(LodRange, osg::Vec2f(0.0f, 4.0f));
    ADD_VEC2F_SERIALIZER(InterestRange, osg::Vec2f(0.0f, 1.0f));
    ADD_STRING_SERIALIZER(Style, "");
    BEGIN_ENUM_BY_NAME_SERIALIZER(Interpolation, OBJECT);
    ADD_ENUM_VALUE(FRAGMENT);
    ADD_ENUM_VALUE(OBJECT);
    ADD_ENUM_VALUE(GROUP);
    END_ENUM_SERIALIZER();
    ADD_BOOL_SERIALIZER(HasGroupFocus, false);
    ADD_VEC3D_SERIALIZER(GroupFocus, osg::Vec3d());
    BEGIN_ENUM_BY_NAME_SERIALIZER(Combination, WEIGHTED_MEAN);
    ADD_ENUM_VALUE(WEIGHTED_MEAN);
    ADD_ENUM_VALUE(MINIMUM);
    ADD_ENUM_VALUE(MAXIMUM);
    END_ENUM_SERIALIZER();
    ADD_BOUNDED_LIST_SERIALIZER(Metrics, osgLoA::TransitionConfiguration::Metrics, osgLoA::SaliencyMetric);
    ADD_VEC2F_SERIALIZER(FadeIn, osg::Vec2f(0.0f, 0.0f));
    ADD_VEC2F_SERIALIZER(FadeOut, osg::Vec2f(1.0f, 1.0f));
}
