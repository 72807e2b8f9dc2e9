// Serializer wrapper for osgLoA::GaussianFilter. Sigma reads as written; an out-of-range value is
// refused where the filter is used (ImageFilter::checkParameters).
#include <osgLoA/filtering/GaussianFilter>

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

REGISTER_OBJECT_WRAPPER(osgLoA_GaussianFilter, new osgLoA::GaussianFilter, osgLoA::GaussianFilter,
                        "osg::Object osgLoA::ImageFilter osgLoA::GaussianFilter")
{
    ADD_FLOAT_SERIALIZER(Sigma, 2.0f);
}
