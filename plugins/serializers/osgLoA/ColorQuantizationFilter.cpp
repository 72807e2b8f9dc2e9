// Serializer wrapper for osgLoA::ColorQuantizationFilter.
// Values read as written; one out of its range is refused where the filter is used
// (ImageFilter::checkParameters: apply(), gpuPasses(), GpuFilterEngine::run).
#include <osgLoA/filtering/ColorQuantizationFilter>

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

REGISTER_OBJECT_WRAPPER(osgLoA_ColorQuantizationFilter, new osgLoA::ColorQuantizationFilter,
                        osgLoA::ColorQuantizationFilter,
                        "osg::Object osgLoA::ImageFilter osgLoA::ColorQuantizationFilter")
{
    ADD_INT_SERIALIZER(Levels, 8);
    ADD_FLOAT_SERIALIZER(PhiQ, 3.0f);
}
