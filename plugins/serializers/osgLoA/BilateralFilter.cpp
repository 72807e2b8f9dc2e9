// Serializer wrapper for osgLoA::BilateralFilter.
// The colour space and the range norm read by name only (EnumByNameSerializer).
// Values read as written; one out of its range is refused where the filter is used
// (ImageFilter::checkParameters: apply(), gpuPasses(), GpuFilterEngine::run).
#include <osgLoA/filtering/BilateralFilter>

#include "EnumByNameSerializer.h"

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

// clang-format off
REGISTER_OBJECT_WRAPPER(osgLoA_BilateralFilter, new osgLoA::BilateralFilter, osgLoA::BilateralFilter,
                        "osg::Object osgLoA::ImageFilter osgLoA::BilateralFilter")
{
    ADD_FLOAT_SERIALIZER(SigmaD, 3.0f);
    ADD_FLOAT_SERIALIZER(SigmaR, 0.1f);
    ADD_INT_SERIALIZER(Radius, 0);
    BEGIN_ENUM_BY_NAME_SERIALIZER(ColorSpace, RGB);
        ADD_ENUM_VALUE(RGB);
        ADD_ENUM_VALUE(LAB);
    END_ENUM_SERIALIZER();
    BEGIN_ENUM_BY_NAME_SERIALIZER(RangeNorm, L2);
        ADD_ENUM_VALUE(L2);
        ADD_ENUM_VALUE(L1);
    END_ENUM_SERIALIZER();
}
// clang-format on
