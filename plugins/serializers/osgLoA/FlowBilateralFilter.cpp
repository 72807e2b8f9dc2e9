// Serializer wrapper for osgLoA::FlowBilateralFilter. Numbers read as written; an out-of-range
// value is refused where the filter is used (ImageFilter::checkParameters). The edge overlay
// reads by name only (EnumByNameSerializer).
#include <osgLoA/filtering/FlowBilateralFilter>

#include "EnumByNameSerializer.h"

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

// clang-format off
REGISTER_OBJECT_WRAPPER(osgLoA_FlowBilateralFilter, new osgLoA::FlowBilateralFilter, osgLoA::FlowBilateralFilter,
                        "osg::Object osgLoA::ImageFilter osgLoA::FlowBilateralFilter")
{
    ADD_FLOAT_SERIALIZER(Rho, 2.0f);
    ADD_INT_SERIALIZER(Ne, 1);
    ADD_INT_SERIALIZER(Na, 4);
    ADD_FLOAT_SERIALIZER(SigmaD, 4.0f);
    ADD_FLOAT_SERIALIZER(SigmaR, 5.0f);
    BEGIN_ENUM_BY_NAME_SERIALIZER(Edges, NO_EDGES);
        ADD_ENUM_VALUE(NO_EDGES);
        ADD_ENUM_VALUE(FDOG_EDGES);
    END_ENUM_SERIALIZER();
}
