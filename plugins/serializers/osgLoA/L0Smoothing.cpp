// Serializer wrapper for osgLoA::L0Smoothing.
// Values read as written; one out of its range is refused where the filter is used
// (ImageFilter::checkParameters: apply(), gpuPasses(), GpuFilterEngine::run).
#include <osgLoA/filtering/L0Smoothing>

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

REGISTER_OBJECT_WRAPPER(osgLoA_L0Smoothing, new osgLoA::L0Smoothing, osgLoA::L0Smoothing,
                        "osg::Object osgLoA::ImageFilter osgLoA::L0Smoothing")
{
    ADD_FLOAT_SERIALIZER(Lambda, 0.02f);
    ADD_FLOAT_SERIALIZER(Kappa, 2.0f);
    ADD_FLOAT_SERIALIZER(BetaMax, 1e5f);
}
