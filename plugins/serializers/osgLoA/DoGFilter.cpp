// Serializer wrapper for osgLoA::DoGFilter. Numbers read as written; an out-of-range value is
// refused where the filter is used (ImageFilter::checkParameters). The mode reads by name only
// (EnumByNameSerializer).
#include <osgLoA/filtering/DoGFilter>

#include "EnumByNameSerializer.h"

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

// clang-format off
REGISTER_OBJECT_WRAPPER(osgLoA_DoGFilter, new osgLoA::DoGFilter, osgLoA::DoGFilter,
                        "osg::Object osgLoA::ImageFilter osgLoA::DoGFilter")
{
    ADD_FLOAT_SERIALIZER(SigmaE, 1.0f);
    ADD_FLOAT_SERIALIZER(K, 1.6f);
    ADD_FLOAT_SERIALIZER(Tau, 0.99f);
    ADD_FLOAT_SERIALIZER(Epsilon, 0.0f);
    ADD_FLOAT_SERIALIZER(Phi, 2.0f);
    ADD_FLOAT_SERIALIZER(SigmaM, 3.0f);
    ADD_FLOAT_SERIALIZER(Rho, 2.0f);
    ADD_BOOL_SERIALIZER(Flow, true);
    BEGIN_ENUM_BY_NAME_SERIALIZER(Mode, EDGES);
        ADD_ENUM_VALUE(EDGES);
        ADD_ENUM_VALUE(XDOG);
    END_ENUM_SERIALIZER();
}
