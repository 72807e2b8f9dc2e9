// Serializer wrapper for osgLoA::DomainTransformFilter.
// Values read as written; one out of its range is refused where the filter is used
// (ImageFilter::checkParameters: apply(), gpuPasses(), GpuFilterEngine::run).
#include <osgLoA/filtering/DomainTransformFilter>

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

REGISTER_OBJECT_WRAPPER(osgLoA_DomainTransformFilter, new osgLoA::DomainTransformFilter,
                        osgLoA::DomainTransformFilter,
                        "osg::Object osgLoA::ImageFilter osgLoA::DomainTransformFilter")
{
    ADD_FLOAT_SERIALIZER(SigmaS, 30.0f);
    ADD_FLOAT_SERIALIZER(SigmaR, 0.25f);
    ADD_INT_SERIALIZER(Iterations, 3);
}
