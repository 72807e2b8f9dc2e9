// Serializer wrapper for osgLoA::RegionOfInterest (.osgt/.osgb/.osgx). The radius is a user
// serializer so that a negative or non-finite value fails the read with a message instead of
// throwing out of osgDB; the shape reads by name only (EnumByNameSerializer) and the vertex
// count is bounded (BoundedListSerializer.h).
#include <osgLoA/interest/RegionOfInterest>

#include "BoundedListSerializer.h"
#include "EnumByNameSerializer.h"

#include <osgDB/InputStream>
#include <osgDB/ObjectWrapper>
#include <osgDB/OutputStream>
#include <osgDB/Serializer>

#include <cmath>

namespace
{
bool checkRadius(const osgLoA::RegionOfInterest& r)
{
    return r.getRadius() != 0.0;
}

bool readRadius(osgDB::InputStream& is, osgLoA::RegionOfInterest& r)
{
    double v = 0.0;
    is >> v;
    if (!std::isfinite(v) || v < 0.0)
    {
        is.throwException("RegionOfInterest: radius " + std::to_string(v) + " must be finite and >= 0");
        return false;
    }
    r.setRadius(v);
    return true;
}

bool writeRadius(osgDB::OutputStream& os, const osgLoA::RegionOfInterest& r)
{
    os << r.getRadius() << std::endl;
    return true;
}
} // namespace

REGISTER_OBJECT_WRAPPER(osgLoA_RegionOfInterest, new osgLoA::RegionOfInterest, osgLoA::RegionOfInterest,
                        "osg::Object osgLoA::RegionOfInterest")
{
    BEGIN_ENUM_BY_NAME_SERIALIZER(Shape, CIRCLES);
    ADD_ENUM_VALUE(CIRCLES);
    ADD_ENUM_VALUE(POLYLINE);
    ADD_ENUM_VALUE(POLYGON);
    END_ENUM_SERIALIZER();
    ADD_BOUNDED_VECTOR_SERIALIZER(Vertices, osgLoA::RegionOfInterest::Vertices,
                                  osgDB::BaseSerializer::RW_VEC2D, 1);
    ADD_USER_SERIALIZER(Radius);
    BEGIN_ENUM_BY_NAME_SERIALIZER(Placement, ABSOLUTE);
    ADD_ENUM_VALUE(ABSOLUTE);
    ADD_ENUM_VALUE(SCENE_CENTRE);
    ADD_ENUM_VALUE(FEATURE);
    ADD_ENUM_VALUE(LONGEST_STREET);
    END_ENUM_SERIALIZER();
    ADD_UINT_SERIALIZER(PlacementFeature, 0u);
    ADD_BOOL_SERIALIZER(SceneScale, false);
}
