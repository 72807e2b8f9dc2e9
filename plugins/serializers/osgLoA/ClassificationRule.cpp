// Serializer wrapper for osgLoA::ClassificationRule.
#include <osgLoA/semantics/ClassificationRule>

#include "FeatureTypeSerializer.h"

#include "EnumByNameSerializer.h"

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

// clang-format off
REGISTER_OBJECT_WRAPPER(osgLoA_ClassificationRule, new osgLoA::ClassificationRule, osgLoA::ClassificationRule,
                        "osg::Object osgLoA::ClassificationRule")
{
    BEGIN_ENUM_BY_NAME_SERIALIZER(Field, ANY);
        ADD_ENUM_VALUE(NODE_NAME);
        ADD_ENUM_VALUE(NODE_DESCRIPTION);
        ADD_ENUM_VALUE(USER_VALUE);
        ADD_ENUM_VALUE(MATERIAL_NAME);
        ADD_ENUM_VALUE(TEXTURE_FILE);
        ADD_ENUM_VALUE(IMPORTER_SEMANTICS);
        ADD_ENUM_VALUE(ANY);
    END_ENUM_SERIALIZER();
    ADD_STRING_SERIALIZER(UserValueKey, "");
    BEGIN_ENUM_BY_NAME_SERIALIZER(Syntax, GLOB);
        ADD_ENUM_VALUE(GLOB);
        ADD_ENUM_VALUE(REGEX);
        ADD_ENUM_VALUE(TOKENS);
    END_ENUM_SERIALIZER();
    ADD_STRING_SERIALIZER(Pattern, "");
    ADD_BOOL_SERIALIZER(CaseSensitive, false);
    osgLoA::addFeatureTypeSerializer<MyClass>(wrapper, "Type", &MyClass::getType, &MyClass::setType);
    ADD_STRING_SERIALIZER(SubType, "");
    ADD_BOOL_SERIALIZER(Inheritable, true);
    ADD_BOOL_SERIALIZER(OverridesModelData, false);
}
// clang-format on
