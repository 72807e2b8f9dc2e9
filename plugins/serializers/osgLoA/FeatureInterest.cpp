// Serializer wrapper for osgLoA::FeatureInterest (.osgt/.osgb/.osgx). The two maps are user
// serializers: a count, then one "type interest" or "id interest" pair per line. Types are
// written by name (FeatureType's toString), so the files do not depend on enum values.
#include <osgLoA/semantics/FeatureInterest>

#include <osgDB/InputStream>
#include <osgDB/ObjectWrapper>
#include <osgDB/OutputStream>
#include <osgDB/Serializer>

#include <cmath>
#include <string>

namespace
{
bool inUnit(float v)
{
    return !std::isnan(v) && v >= 0.0f && v <= 1.0f;
}

bool checkTypeInterests(const osgLoA::FeatureInterest& fi)
{
    return !fi.getTypeInterests().empty();
}

bool readTypeInterests(osgDB::InputStream& is, osgLoA::FeatureInterest& fi)
{
    osgLoA::FeatureInterest::TypeInterests m;
    const unsigned size = is.readSize();
    is >> is.BEGIN_BRACKET;
    for (unsigned i = 0; i < size; ++i)
    {
        std::string name;
        float value = 0.0f;
        is >> name >> value;
        osgLoA::FeatureType type;
        if (!osgLoA::parseFeatureType(name, type))
        {
            is.throwException("FeatureInterest: unknown feature type '" + name + "'");
            return false;
        }
        if (!inUnit(value))
        {
            is.throwException("FeatureInterest: interest " + std::to_string(value) + " of type " + name +
                              " is outside [0,1]");
            return false;
        }
        m[type] = value;
    }
    is >> is.END_BRACKET;
    fi.setTypeInterests(m);
    return true;
}

bool writeTypeInterests(osgDB::OutputStream& os, const osgLoA::FeatureInterest& fi)
{
    const osgLoA::FeatureInterest::TypeInterests& m = fi.getTypeInterests();
    os.writeSize(m.size());
    os << os.BEGIN_BRACKET << std::endl;
    for (const auto& kv : m)
        os << std::string(osgLoA::toString(kv.first)) << kv.second << std::endl;
    os << os.END_BRACKET << std::endl;
    return true;
}

bool checkFeatureInterests(const osgLoA::FeatureInterest& fi)
{
    return !fi.getFeatureInterests().empty();
}

bool readFeatureInterests(osgDB::InputStream& is, osgLoA::FeatureInterest& fi)
{
    osgLoA::FeatureInterest::FeatureInterests m;
    const unsigned size = is.readSize();
    is >> is.BEGIN_BRACKET;
    for (unsigned i = 0; i < size; ++i)
    {
        unsigned id = 0;
        float value = 0.0f;
        is >> id >> value;
        if (!inUnit(value))
        {
            is.throwException("FeatureInterest: interest " + std::to_string(value) + " of feature " +
                              std::to_string(id) + " is outside [0,1]");
            return false;
        }
        m[id] = value;
    }
    is >> is.END_BRACKET;
    fi.setFeatureInterests(m);
    return true;
}

bool writeFeatureInterests(osgDB::OutputStream& os, const osgLoA::FeatureInterest& fi)
{
    const osgLoA::FeatureInterest::FeatureInterests& m = fi.getFeatureInterests();
    os.writeSize(m.size());
    os << os.BEGIN_BRACKET << std::endl;
    for (const auto& kv : m)
        os << kv.first << kv.second << std::endl;
    os << os.END_BRACKET << std::endl;
    return true;
}
// The scalar fields are user serializers too, so that a value outside [0,1] in a file fails the
// read (InputStream::throwException) instead of throwing std::invalid_argument out of osgDB.
bool checkDefaultInterest(const osgLoA::FeatureInterest& fi)
{
    return fi.getDefaultInterest() != 0.0f;
}

bool readDefaultInterest(osgDB::InputStream& is, osgLoA::FeatureInterest& fi)
{
    float value = 0.0f;
    is >> value;
    if (!inUnit(value))
    {
        is.throwException("FeatureInterest: default interest " + std::to_string(value) + " is outside [0,1]");
        return false;
    }
    fi.setDefaultInterest(value);
    return true;
}

bool writeDefaultInterest(osgDB::OutputStream& os, const osgLoA::FeatureInterest& fi)
{
    os << fi.getDefaultInterest() << std::endl;
    return true;
}

bool checkLandmarkThreshold(const osgLoA::FeatureInterest& fi)
{
    return fi.getLandmarkThreshold() != 0.8f;
}

bool readLandmarkThreshold(osgDB::InputStream& is, osgLoA::FeatureInterest& fi)
{
    float value = 0.8f;
    is >> value;
    if (!inUnit(value))
    {
        is.throwException("FeatureInterest: landmark threshold " + std::to_string(value) +
                          " is outside [0,1]");
        return false;
    }
    fi.setLandmarkThreshold(value);
    return true;
}

bool writeLandmarkThreshold(osgDB::OutputStream& os, const osgLoA::FeatureInterest& fi)
{
    os << fi.getLandmarkThreshold() << std::endl;
    return true;
}
} // namespace

// clang-format off
REGISTER_OBJECT_WRAPPER(osgLoA_FeatureInterest, new osgLoA::FeatureInterest, osgLoA::FeatureInterest,
                        "osg::Object osgLoA::FeatureInterest")
{
    ADD_USER_SERIALIZER(TypeInterests);
    ADD_USER_SERIALIZER(FeatureInterests);
    ADD_USER_SERIALIZER(DefaultInterest);
    ADD_BOOL_SERIALIZER(KeepExistingInterest, false);
    ADD_USER_SERIALIZER(LandmarkThreshold);
}
// clang-format on
