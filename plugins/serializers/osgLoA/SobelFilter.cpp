// Serializer wrapper for osgLoA::SobelFilter (.osgt/.osgb/.osgx). A threshold outside [0, 4]
// reads as it is; checkParameters (apply, GpuFilterEngine::run) refuses it.
#include <osgLoA/filtering/SobelFilter>

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

REGISTER_OBJECT_WRAPPER(osgLoA_SobelFilter, new osgLoA::SobelFilter, osgLoA::SobelFilter,
                        "osg::Object osgLoA::ImageFilter osgLoA::SobelFilter")
{
    ADD_FLOAT_SERIALIZER(Threshold, 0.0f);
}
