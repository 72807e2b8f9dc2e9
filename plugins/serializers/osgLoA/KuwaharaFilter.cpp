// Serializer wrapper for osgLoA::KuwaharaFilter (.osgt/.osgb/.osgx). A radius outside [1, 16]
// reads as it is; the filter clamps it when it runs.
#include <osgLoA/filtering/KuwaharaFilter>

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

REGISTER_OBJECT_WRAPPER(osgLoA_KuwaharaFilter, new osgLoA::KuwaharaFilter, osgLoA::KuwaharaFilter,
                        "osg::Object osgLoA::ImageFilter osgLoA::KuwaharaFilter")
{
    ADD_INT_SERIALIZER(Radius, 4);
}
