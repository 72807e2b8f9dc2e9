// Serializer wrapper for osgLoA::GuidedFilter.
// Values read as written; one out of its range is refused where the filter is used
// (ImageFilter::checkParameters: apply(), gpuPasses(), GpuFilterEngine::run).
#include <osgLoA/filtering/GuidedFilter>

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

REGISTER_OBJECT_WRAPPER(osgLoA_GuidedFilter, new osgLoA::GuidedFilter, osgLoA::GuidedFilter,
                        "osg::Object osgLoA::ImageFilter osgLoA::GuidedFilter")
{
    ADD_INT_SERIALIZER(Radius, 4);
    ADD_FLOAT_SERIALIZER(Eps, 0.01f);
}
