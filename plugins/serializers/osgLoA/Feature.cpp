// Serializer wrapper for osgLoA::Feature (.osgt/.osgb/.osgx).
#include <osgLoA/semantics/Feature>

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

// clang-format off
REGISTER_OBJECT_WRAPPER(osgLoA_Feature, new osgLoA::Feature, osgLoA::Feature, "osg::Object osgLoA::Feature")
{
    ADD_UINT_SERIALIZER(Id, 0u);
    {
        typedef osgDB::EnumSerializer<MyClass, osgLoA::FeatureType, void> TypeSerializer;
        osg::ref_ptr<TypeSerializer> serializer =
            new TypeSerializer("Type", osgLoA::FeatureType::Generic, &MyClass::getType, &MyClass::setType);
        for (osgLoA::FeatureType t : osgLoA::kFeatureTypes)
            serializer->add(osgLoA::toString(t), t);
        wrapper->addSerializer(serializer.get(), osgDB::BaseSerializer::RW_ENUM);
    }
    ADD_STRING_SERIALIZER(SubType, "");
    BEGIN_ENUM_SERIALIZER(Source, UNCLASSIFIED);
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
}
// clang-format on
