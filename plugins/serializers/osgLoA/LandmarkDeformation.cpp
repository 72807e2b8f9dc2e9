// Serializer wrapper for osgLoA::LandmarkDeformation (.osgt/.osgb/.osgx). The driver's kind reads
// by name only (EnumByNameSerializer); the sink types are written by name (FeatureType's
// toString) and an unknown name fails the read. Values out of range read as they are and make
// UsageScenario::validate() fail (the deformation itself never produces NaN from them).
#include <osgLoA/transitions/LandmarkDeformation>

#include "BoundedListSerializer.h"
#include "EnumByNameSerializer.h"

#include <osgDB/InputStream>
#include <osgDB/ObjectWrapper>
#include <osgDB/OutputStream>
#include <osgDB/Serializer>

namespace
{
constexpr unsigned kMaxSinkTypes = 1u << 8;

bool checkSinkTypes(const osgLoA::LandmarkDeformation& d)
{
    return d.getSinkTypes() != osgLoA::LandmarkDeformation::FeatureTypes{osgLoA::FeatureType::Building};
}

bool readSinkTypes(osgDB::InputStream& is, osgLoA::LandmarkDeformation& d)
{
    const unsigned size = is.readSize();
    if (size > kMaxSinkTypes)
    {
        is.throwException("LandmarkDeformation: implausible sink type count " + std::to_string(size));
        return false;
    }
    osgLoA::LandmarkDeformation::FeatureTypes types;
    is >> is.BEGIN_BRACKET;
    for (unsigned i = 0; i < size && !is.getException(); ++i)
    {
        std::string name;
        is >> name;
        osgLoA::FeatureType t;
        if (!osgLoA::parseFeatureType(name, t))
        {
            is.throwException("LandmarkDeformation: unknown feature type '" + name + "'");
            return false;
        }
        types.push_back(t);
    }
    is >> is.END_BRACKET;
    d.setSinkTypes(types);
    return true;
}

bool writeSinkTypes(osgDB::OutputStream& os, const osgLoA::LandmarkDeformation& d)
{
    os.writeSize(d.getSinkTypes().size());
    os << os.BEGIN_BRACKET << std::endl;
    for (osgLoA::FeatureType t : d.getSinkTypes())
        os << std::string(osgLoA::toString(t)) << std::endl;
    os << os.END_BRACKET << std::endl;
    return true;
}
bool checkMapStyles(const osgLoA::LandmarkDeformation& d)
{
    return d.getMapStyles() != osgLoA::LandmarkDeformation::defaultMapStyles();
}

bool readMapStyles(osgDB::InputStream& is, osgLoA::LandmarkDeformation& d)
{
    osgLoA::LandmarkDeformation::StyleNames names;
    if (!osgLoA::readBoundedStrings(is, "LandmarkDeformation: implausible map style", kMaxSinkTypes, names))
        return false;
    d.setMapStyles(names);
    return true;
}

bool writeMapStyles(osgDB::OutputStream& os, const osgLoA::LandmarkDeformation& d)
{
    return osgLoA::writeStrings(os, d.getMapStyles());
}
} // namespace

REGISTER_OBJECT_WRAPPER(osgLoA_LandmarkDeformation, new osgLoA::LandmarkDeformation,
                        osgLoA::LandmarkDeformation, "osg::Object osgLoA::LandmarkDeformation")
{
    ADD_BOOL_SERIALIZER(ScalingEnabled, true);
    ADD_BOOL_SERIALIZER(RotationEnabled, true);
    ADD_BOOL_SERIALIZER(FlatteningEnabled, true);
    ADD_BOOL_SERIALIZER(BillboardEnabled, true);
    ADD_BOOL_SERIALIZER(SinkingEnabled, false);
    ADD_DOUBLE_SERIALIZER(ScaleNear, 200.0);
    ADD_DOUBLE_SERIALIZER(ScaleFar, 1000.0);
    ADD_DOUBLE_SERIALIZER(MaxScale, 2.0);
    ADD_DOUBLE_SERIALIZER(InterestFadeBegin, 0.6);
    ADD_DOUBLE_SERIALIZER(InterestFadeEnd, 0.9);
    {
        typedef osgLoA::EnumByNameSerializer<MyClass, osgLoA::SaliencyMetric::Kind> MySerializer;
        osg::ref_ptr<MySerializer> serializer =
            new MySerializer(wrapper->getName(), "DriverKind", osgLoA::SaliencyMetric::VIEW_ANGLE,
                             &MyClass::getDriverKind, &MyClass::setDriverKind);
        ADD_ENUM_CLASS_VALUE(osgLoA::SaliencyMetric, VIEW_DISTANCE);
        ADD_ENUM_CLASS_VALUE(osgLoA::SaliencyMetric, VIEW_ANGLE);
        ADD_ENUM_CLASS_VALUE(osgLoA::SaliencyMetric, REGION);
        ADD_ENUM_CLASS_VALUE(osgLoA::SaliencyMetric, FOCUS);
        ADD_ENUM_CLASS_VALUE(osgLoA::SaliencyMetric, FEATURE_INTEREST);
        wrapper->addSerializer(serializer.get(), osgDB::BaseSerializer::RW_ENUM);
    }
    ADD_DOUBLE_SERIALIZER(DriverNear, 25.0);
    ADD_DOUBLE_SERIALIZER(DriverFar, 60.0);
    ADD_DOUBLE_SERIALIZER(MaxTiltDegrees, 80.0);
    ADD_USER_SERIALIZER(SinkTypes);
    ADD_DOUBLE_SERIALIZER(ShrinkFactor, 0.5);
    ADD_DOUBLE_SERIALIZER(SinkFactor, 1.0);
    // Issue 19 (non-landmarks sink where the scenario draws a map): after the older fields.
    ADD_BOOL_SERIALIZER(SinkFollowsMapStyles, false);
    ADD_USER_SERIALIZER(MapStyles);
}
