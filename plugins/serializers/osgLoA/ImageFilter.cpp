// Serializer wrapper for the abstract osgLoA::ImageFilter: it has no fields of its own (each
// filter's wrapper adds its parameters); it names the class so that .osgt/.osgb files can hold
// any filter where an ImageFilter is expected.
#include <osgLoA/filtering/ImageFilter>

#include <osgDB/ObjectWrapper>

REGISTER_OBJECT_WRAPPER(osgLoA_ImageFilter, /* abstract */ 0, osgLoA::ImageFilter,
                        "osg::Object osgLoA::ImageFilter")
{
    (void)wrapper; // no serializers of its own (clang's -Wunused-parameter)
}
