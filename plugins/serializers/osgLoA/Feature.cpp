// Serializer wrapper for osgLoA::Feature (.osgt/.osgb/.osgx).
#include <osgLoA/semantics/Feature>

#include "BoundedListSerializer.h"
#include "FeatureTypeSerializer.h"

#include "EnumByNameSerializer.h"

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

// clang-format off
REGISTER_OBJECT_WRAPPER(osgLoA_Feature, new osgLoA::Feature, osgLoA::Feature, "osg::Object osgLoA::Feature")
{
    ADD_UINT_SERIALIZER(Id, 0u);
    osgLoA::addFeatureTypeSerializer<MyClass>(wrapper, "Type", &MyClass::getType, &MyClass::setType);
    ADD_STRING_SERIALIZER(SubType, "");
    BEGIN_ENUM_BY_NAME_SERIALIZER(Source, UNCLASSIFIED);
        ADD_ENUM_VALUE(UNCLASSIFIED);
        ADD_ENUM_VALUE(MODEL_DATA);
        ADD_ENUM_VALUE(RULE);
        ADD_ENUM_VALUE(APPEARANCE);
        ADD_ENUM_VALUE(USER);
    END_ENUM_SERIALIZER();
    ADD_FLOAT_SERIALIZER(Interest, 0.0f);
    ADD_BOOL_SERIALIZER(Landmark, false);
    ADD_VEC3F_SERIALIZER(BestViewDirection, osg::Vec3f());
    ADD_BOUNDINGBOXF_SERIALIZER(Bound, osg::BoundingBoxf());
    ADD_FLOAT_SERIALIZER(Lod, -1.0f);
    ADD_STRING_SERIALIZER(SourceId, "");
    ADD_STRING_SERIALIZER(SourceType, "");
    // Issue 19 (routes along the street network): after the older fields; the vertex count is
    // bounded like a region's.
    ADD_BOUNDED_VECTOR_SERIALIZER(Centreline, osgLoA::Feature::Centreline, osgDB::BaseSerializer::RW_VEC2D, 1);
    // Issue 19 (street labels): the name a map prints.
    ADD_STRING_SERIALIZER(Label, "");
}
// clang-format on
