// Serializer wrapper for osgLoA::AbstractionStyle (.osgt/.osgb/.osgx). Enums read by name only
// (EnumByNameSerializer): an unknown name or number fails the read. The focus is an
// osgLoA::AbstractionFocus or the read fails (CheckedObjectSerializer); a file without one keeps
// the default focus. Numbers read as they are; values out of range make
// AbstractionStyle::validate() fail (as LandmarkDeformation's wrapper does).
#include <osgLoA/abstraction/AbstractionStyle>

#include "BoundedListSerializer.h"
#include "EnumByNameSerializer.h"

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

REGISTER_OBJECT_WRAPPER(osgLoA_AbstractionStyle, new osgLoA::AbstractionStyle, osgLoA::AbstractionStyle,
                        "osg::Object osgLoA::AbstractionStyle")
{
    ADD_STRING_SERIALIZER(Description, "");
    BEGIN_ENUM_BY_NAME_SERIALIZER(NormalPass, LIT);
    ADD_ENUM_VALUE(LIT);
    ADD_ENUM_VALUE(UNSHADED);
    END_ENUM_SERIALIZER();
    BEGIN_ENUM_BY_NAME_SERIALIZER(Shading, NO_SHADING);
    ADD_ENUM_VALUE(NO_SHADING);
    ADD_ENUM_VALUE(CEL);
    ADD_ENUM_VALUE(PENCIL);
    END_ENUM_SERIALIZER();
    ADD_INT_SERIALIZER(CelLevels, 4);
    ADD_INT_SERIALIZER(PencilLevels, 4);
    ADD_FLOAT_SERIALIZER(Ambient, 0.35f);
    ADD_FLOAT_SERIALIZER(PencilScale, 1.0f);
    ADD_FLOAT_SERIALIZER(PencilAnisotropy, 1.0f);
    ADD_INT_SERIALIZER(KuwaharaRadius, 0);
    ADD_INT_SERIALIZER(KuwaharaIterations, 1);
    ADD_INT_SERIALIZER(KuwaharaIterationsFocus, 0);
    BEGIN_ENUM_BY_NAME_SERIALIZER(EdgeDetector, NO_EDGES);
    ADD_ENUM_VALUE(NO_EDGES);
    ADD_ENUM_VALUE(DOG);
    ADD_ENUM_VALUE(SOBEL);
    ADD_ENUM_VALUE(CANNY);
    END_ENUM_SERIALIZER();
    BEGIN_ENUM_BY_NAME_SERIALIZER(EdgeSource, ABSTRACTED_IMAGE);
    ADD_ENUM_VALUE(ABSTRACTED_IMAGE);
    ADD_ENUM_VALUE(NORMAL_IMAGE);
    END_ENUM_SERIALIZER();
    ADD_FLOAT_SERIALIZER(DogSigma, 1.0f);
    ADD_FLOAT_SERIALIZER(DogRatio, 1.6f);
    ADD_FLOAT_SERIALIZER(DogTau, 0.99f);
    ADD_FLOAT_SERIALIZER(DogEpsilon, -1.0f);
    ADD_FLOAT_SERIALIZER(SobelThreshold, 0.2f);
    ADD_FLOAT_SERIALIZER(SobelThresholdFar, 0.5f);
    ADD_FLOAT_SERIALIZER(CannyLow, 0.1f);
    ADD_FLOAT_SERIALIZER(CannyHigh, 0.2f);
    ADD_BOOL_SERIALIZER(Silhouettes, false);
    ADD_FLOAT_SERIALIZER(EdgeOpacity, 1.0f);
    ADD_FLOAT_SERIALIZER(EdgeOpacityFar, 0.2f);
    BEGIN_ENUM_BY_NAME_SERIALIZER(Combination, OVERLAY);
    ADD_ENUM_VALUE(OVERLAY);
    ADD_ENUM_VALUE(SHADING_ONLY);
    ADD_ENUM_VALUE(TOON);
    ADD_ENUM_VALUE(PENCIL_SKETCH);
    END_ENUM_SERIALIZER();
    ADD_FLOAT_SERIALIZER(Brightening, 1.5f);
    ADD_FLOAT_SERIALIZER(PencilGamma, 2.0f);
    BEGIN_ENUM_BY_NAME_SERIALIZER(Adaptivity, UNIFORM);
    ADD_ENUM_VALUE(UNIFORM);
    ADD_ENUM_VALUE(SCREEN_FOCUS);
    ADD_ENUM_VALUE(OBJECT_FOCUS);
    END_ENUM_SERIALIZER();
    ADD_BOOL_SERIALIZER(Segmentation, false);
    ADD_FLOAT_SERIALIZER(Bleaching, 0.0f);
    ADD_INT_SERIALIZER(CelLevelsFar, 8);
    ADD_FLOAT_SERIALIZER(ShadingAtFocus, 0.5f);
    ADD_CHECKED_OBJECT_SERIALIZER(Focus, osgLoA::AbstractionFocus, NULL);
}
