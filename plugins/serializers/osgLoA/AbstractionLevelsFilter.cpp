// Serializer wrapper for osgLoA::AbstractionLevelsFilter (.osgt/.osgb/.osgx). Values outside their
// ranges read as they are; the filter refuses them when it runs (checkParameters).
#include <osgLoA/abstraction/AbstractionLevelsFilter>

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

REGISTER_OBJECT_WRAPPER(osgLoA_AbstractionLevelsFilter, new osgLoA::AbstractionLevelsFilter,
                        osgLoA::AbstractionLevelsFilter,
                        "osg::Object osgLoA::ImageFilter osgLoA::AbstractionLevelsFilter")
{
    ADD_INT_SERIALIZER(Radius, 2);
    ADD_INT_SERIALIZER(Iterations, 3);
    ADD_INT_SERIALIZER(IterationsFocus, 0);
}
