// Serializer wrapper for osgLoA::AnisotropicKuwaharaFilter (.osgt/.osgb/.osgx). Values outside
// the parameter ranges read as they are; the filter clamps them when it runs.
#include <osgLoA/filtering/AnisotropicKuwaharaFilter>

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

REGISTER_OBJECT_WRAPPER(osgLoA_AnisotropicKuwaharaFilter, new osgLoA::AnisotropicKuwaharaFilter,
                        osgLoA::AnisotropicKuwaharaFilter,
                        "osg::Object osgLoA::ImageFilter osgLoA::AnisotropicKuwaharaFilter")
{
    ADD_FLOAT_SERIALIZER(Radius, 6.0f);
    ADD_FLOAT_SERIALIZER(Sharpness, 8.0f);
    ADD_FLOAT_SERIALIZER(Alpha, 1.0f);
    ADD_FLOAT_SERIALIZER(Rho, 2.0f);
    ADD_INT_SERIALIZER(Levels, 1);
    ADD_FLOAT_SERIALIZER(Threshold, 0.0f);
}
