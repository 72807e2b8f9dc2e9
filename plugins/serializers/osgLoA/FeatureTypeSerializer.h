// Serializes a property of type osgLoA::FeatureType (an enum class) by its names: "building",
// "street", ... (the ADD_ENUM_VALUE macros need class-scoped enumerators).
#ifndef OSGLOA_SERIALIZERS_FEATURETYPESERIALIZER_H
#define OSGLOA_SERIALIZERS_FEATURETYPESERIALIZER_H 1

#include <osgLoA/semantics/FeatureType>

#include "EnumByNameSerializer.h"

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

namespace osgLoA
{
template <class C>
void addFeatureTypeSerializer(osgDB::ObjectWrapper* wrapper, const char* name,
                              FeatureType (C::*getter)() const, void (C::*setter)(FeatureType))
{
    // Unknown names and out-of-range numbers fail the read with a message.
    typedef EnumByNameSerializer<C, FeatureType> Serializer;
    osg::ref_ptr<Serializer> serializer =
        new Serializer(wrapper->getName(), name, FeatureType::Generic, getter, setter);
    for (FeatureType t : kFeatureTypes)
        serializer->add(toString(t), t);
    wrapper->addSerializer(serializer.get(), osgDB::BaseSerializer::RW_ENUM);
}
} // namespace osgLoA

#endif
