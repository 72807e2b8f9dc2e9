// Serializer wrapper for osgLoA::RegionOfInterest (.osgt/.osgb/.osgx). The radius is a user
// serializer so that a negative or non-finite value fails the read with a message instead of
// throwing out of osgDB; the shape reads by name only (EnumByNameSerializer) and the vertex
// count is bounded (BoundedListSerializer.h). The line width is checked like the radius.
#include <osgLoA/interest/RegionOfInterest>

#include "BoundedListSerializer.h"
#include "EnumByNameSerializer.h"

#include <osgDB/InputStream>
#include <osgDB/ObjectWrapper>
#include <osgDB/OutputStream>
#include <osgDB/Serializer>

#include <cmath>
#include <string>

namespace
{
bool checkRadius(const osgLoA::RegionOfInterest& r)
{
    return r.getRadius() != 0.0;
}

/** Reads a double into v. After an earlier field failed, the bytes here are not this value:
 *  nothing is read and that first error is kept. `problem(v)` is empty for a valid value, else
 *  the message the read fails with. */
template <class Problem> bool readChecked(osgDB::InputStream& is, double& v, const Problem& problem)
{
    if (is.getException()) return false;
    is >> v;
    const std::string message = problem(v);
    if (message.empty()) return true;
    is.throwException(message);
    return false;
}

bool readRadius(osgDB::InputStream& is, osgLoA::RegionOfInterest& r)
{
    double v = 0.0;
    if (!readChecked(is, v,
                     [](double x)
                     {
                         return std::isfinite(x) && x >= 0.0
                                    ? std::string()
                                    : "RegionOfInterest: radius " + std::to_string(x) +
                                          " must be finite and >= 0";
                     }))
        return false;
    r.setRadius(v);
    return true;
}

bool writeRadius(osgDB::OutputStream& os, const osgLoA::RegionOfInterest& r)
{
    os << r.getRadius() << std::endl;
    return true;
}

bool checkLineWidth(const osgLoA::RegionOfInterest& r)
{
    return r.getLineWidth() != 0.0;
}

bool readLineWidth(osgDB::InputStream& is, osgLoA::RegionOfInterest& r)
{
    const double most = osgLoA::RegionOfInterest::kMaxLineWidth;
    double v = 0.0;
    if (!readChecked(is, v,
                     [most](double x)
                     {
                         return std::isfinite(x) && x >= 0.0 && x <= most
                                    ? std::string()
                                    : "RegionOfInterest: line width " + std::to_string(x) +
                                          " must be finite and in [0, " + std::to_string(int(most)) +
                                          "] pixels";
                     }))
        return false;
    r.setLineWidth(v);
    return true;
}

bool writeLineWidth(osgDB::OutputStream& os, const osgLoA::RegionOfInterest& r)
{
    os << r.getLineWidth() << std::endl;
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
    // Issue 19 (the route drawn on the map): after the older fields. The colour is checked by
    // validate() (UsageScenario::validate), as every reader of scenario files calls it.
    ADD_USER_SERIALIZER(LineWidth);
    ADD_VEC4F_SERIALIZER(LineColor, osgLoA::RegionOfInterest::defaultLineColor());
}
