// Serializer wrapper for osgLoA::SaliencyMetric (.osgt/.osgb/.osgx). The kind reads by name only
// (EnumByNameSerializer): an unknown name or number fails the read.
#include <osgLoA/interest/SaliencyMetric>

#include "EnumByNameSerializer.h"

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

REGISTER_OBJECT_WRAPPER(osgLoA_SaliencyMetric, new osgLoA::SaliencyMetric, osgLoA::SaliencyMetric,
                        "osg::Object osgLoA::SaliencyMetric")
{
    BEGIN_ENUM_BY_NAME_SERIALIZER(Kind, VIEW_DISTANCE);
    ADD_ENUM_VALUE(VIEW_DISTANCE);
    ADD_ENUM_VALUE(VIEW_ANGLE);
    ADD_ENUM_VALUE(REGION);
    ADD_ENUM_VALUE(FOCUS);
    ADD_ENUM_VALUE(FEATURE_INTEREST);
    END_ENUM_SERIALIZER();
    ADD_DOUBLE_SERIALIZER(Near, 0.0);
    ADD_DOUBLE_SERIALIZER(Far, 1000.0);
    ADD_DOUBLE_SERIALIZER(Weight, 1.0);
    BEGIN_ENUM_BY_NAME_SERIALIZER(Scale, ABSOLUTE);
    ADD_ENUM_VALUE(ABSOLUTE);
    ADD_ENUM_VALUE(SCENE);
    ADD_ENUM_VALUE(VIEW);
    END_ENUM_SERIALIZER();
}
