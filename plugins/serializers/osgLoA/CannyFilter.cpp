// Serializer wrapper for osgLoA::CannyFilter (.osgt/.osgb/.osgx). Values outside their ranges,
// or low > high, read as they are; checkParameters (apply, GpuFilterEngine::run) refuses them.
#include <osgLoA/filtering/CannyFilter>

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

REGISTER_OBJECT_WRAPPER(osgLoA_CannyFilter, new osgLoA::CannyFilter, osgLoA::CannyFilter,
                        "osg::Object osgLoA::ImageFilter osgLoA::CannyFilter")
{
    ADD_FLOAT_SERIALIZER(Sigma, 1.0f);
    ADD_FLOAT_SERIALIZER(Low, 0.1f);
    ADD_FLOAT_SERIALIZER(High, 0.2f);
    ADD_INT_SERIALIZER(HysteresisIterations, 8);
}
