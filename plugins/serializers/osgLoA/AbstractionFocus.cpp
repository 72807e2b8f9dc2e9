// Serializer wrapper for osgLoA::AbstractionFocus (.osgt/.osgb/.osgx). The mode reads by name only
// (EnumByNameSerializer): an unknown name or number fails the read. Radii read as they are; a
// negative or crossed pair makes AbstractionFocus::validate() (and AbstractionStyle::validate())
// fail.
#include <osgLoA/abstraction/AbstractionFocus>

#include "EnumByNameSerializer.h"

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

REGISTER_OBJECT_WRAPPER(osgLoA_AbstractionFocus, new osgLoA::AbstractionFocus, osgLoA::AbstractionFocus,
                        "osg::Object osgLoA::AbstractionFocus")
{
    BEGIN_ENUM_BY_NAME_SERIALIZER(Mode, SCREEN_POINT);
    ADD_ENUM_VALUE(SCREEN_POINT);
    ADD_ENUM_VALUE(WORLD_POINT);
    ADD_ENUM_VALUE(OBJECT);
    END_ENUM_SERIALIZER();
    ADD_VEC2F_SERIALIZER(ScreenPoint, osg::Vec2f(0.5f, 0.5f));
    ADD_VEC3D_SERIALIZER(WorldPoint, osg::Vec3d(0.0, 0.0, 0.0));
    ADD_UINT_SERIALIZER(ObjectId, 0u);
    ADD_FLOAT_SERIALIZER(InnerRadius, 0.1f);
    ADD_FLOAT_SERIALIZER(OuterRadius, 0.5f);
}
