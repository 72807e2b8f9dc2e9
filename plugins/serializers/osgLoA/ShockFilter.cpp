// Serializer wrapper for osgLoA::ShockFilter (.osgt/.osgb/.osgx). Values outside the parameter
// ranges read as they are; the filter clamps them when it runs.
#include <osgLoA/filtering/ShockFilter>

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

REGISTER_OBJECT_WRAPPER(osgLoA_ShockFilter, new osgLoA::ShockFilter, osgLoA::ShockFilter,
                        "osg::Object osgLoA::ImageFilter osgLoA::ShockFilter")
{
    ADD_INT_SERIALIZER(Iterations, 5);
    ADD_FLOAT_SERIALIZER(SigmaD, 1.0f);
    ADD_FLOAT_SERIALIZER(SigmaS, 6.0f);
    ADD_FLOAT_SERIALIZER(MaxAngle, 22.5f);
    ADD_BOOL_SERIALIZER(Adaptive, true);
    ADD_FLOAT_SERIALIZER(SigmaI, 0.0f);
    ADD_FLOAT_SERIALIZER(SigmaG, 1.5f);
    ADD_FLOAT_SERIALIZER(TauS, 0.005f);
    ADD_FLOAT_SERIALIZER(Radius, 2.0f);
    ADD_FLOAT_SERIALIZER(SigmaA, 1.5f);
}
