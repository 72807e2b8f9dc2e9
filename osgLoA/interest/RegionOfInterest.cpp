// RegionOfInterest: exact distances to circles, routes and polygons on the ground plane.
#include <osgLoA/interest/RegionOfInterest>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace osgLoA
{

namespace
{
/** The squared distance from p to the segment ab (distance() takes one square root of the
 *  smallest: the root is monotonic and correctly rounded, so that is the smallest root). */
double segmentDistance2(const osg::Vec2d& p, const osg::Vec2d& a, const osg::Vec2d& b)
{
    const osg::Vec2d ab = b - a;
    const double len2 = ab.length2();
    const double dot = (p - a) * ab;
    // The nearest point is a + ab t with t = dot / len2 clamped to [0, 1]; the division only
    // where it is not clamped. The same values as clamping the quotient: it is <= 0 (or NaN:
    // 0) exactly when dot is, and >= 1 when dot >= len2.
    if (!(len2 > 0.0) || !(dot > 0.0)) return (p - (a + ab * 0.0)).length2();
    if (dot >= len2) return (p - (a + ab)).length2();
    const double t = dot / len2;
    return (p - (a + ab * t)).length2();
}

// Even-odd rule: a ray towards +x crosses the ring an odd number of times from inside.
bool insideRing(const osg::Vec2d& p, const RegionOfInterest::Vertices& v)
{
    bool inside = false;
    for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++)
    {
        if ((v[i].y() > p.y()) != (v[j].y() > p.y()))
        {
            const double x = v[j].x() + (p.y() - v[j].y()) * (v[i].x() - v[j].x()) / (v[i].y() - v[j].y());
            if (p.x() < x) inside = !inside;
        }
    }
    return inside;
}

std::size_t minimumVertices(RegionOfInterest::Shape s)
{
    return s == RegionOfInterest::POLYGON ? 3 : s == RegionOfInterest::POLYLINE ? 2 : 1;
}
} // namespace

RegionOfInterest::RegionOfInterest() = default;

RegionOfInterest::RegionOfInterest(Shape shape, const Vertices& vertices, double radius)
    : _shape(shape), _vertices(vertices)
{
    setRadius(radius);
}

RegionOfInterest::RegionOfInterest(const RegionOfInterest& other, const osg::CopyOp& copyop)
    : osg::Object(other, copyop), _shape(other._shape), _vertices(other._vertices), _radius(other._radius),
      _placement(other._placement), _placementFeature(other._placementFeature),
      _sceneScale(other._sceneScale), _lineWidth(other._lineWidth), _lineColor(other._lineColor)
{
}

const char* RegionOfInterest::toString(Placement placement)
{
    switch (placement)
    {
    case SCENE_CENTRE:
        return "scene-centre";
    case FEATURE:
        return "feature";
    case LONGEST_STREET:
        return "longest-street";
    default:
        return "absolute";
    }
}

bool RegionOfInterest::parsePlacement(const std::string& name, Placement& placement)
{
    std::string n = name;
    for (char& c : n)
        c = char(std::tolower(static_cast<unsigned char>(c)));
    for (Placement p : {ABSOLUTE, SCENE_CENTRE, FEATURE, LONGEST_STREET})
        if (n == toString(p))
        {
            placement = p;
            return true;
        }
    return false;
}

void RegionOfInterest::setRadius(double radius)
{
    if (!std::isfinite(radius) || radius < 0.0)
        throw std::invalid_argument("region of interest radius " + std::to_string(radius) +
                                    " must be finite and not negative");
    _radius = radius;
}

void RegionOfInterest::setLineWidth(double pixels)
{
    if (!std::isfinite(pixels) || pixels < 0.0 || pixels > kMaxLineWidth)
        throw std::invalid_argument("region of interest line width " + std::to_string(pixels) +
                                    " must be finite and in [0, " + std::to_string(int(kMaxLineWidth)) +
                                    "] pixels");
    _lineWidth = pixels;
}

double RegionOfInterest::distance(const osg::Vec2d& p) const
{
    if (_vertices.size() < minimumVertices(_shape)) return std::numeric_limits<double>::infinity();
    // Squared distances, one square root at the end.
    double d2 = std::numeric_limits<double>::infinity();
    const std::size_t n = _vertices.size();
    switch (_shape)
    {
    case CIRCLES:
        for (const osg::Vec2d& c : _vertices)
            d2 = std::min(d2, (p - c).length2());
        break;
    case POLYLINE:
        for (std::size_t i = 0; i + 1 < n; ++i)
            d2 = std::min(d2, segmentDistance2(p, _vertices[i], _vertices[i + 1]));
        break;
    case POLYGON:
        if (insideRing(p, _vertices)) return 0.0;
        for (std::size_t i = 0, j = n - 1; i < n; j = i++)
            d2 = std::min(d2, segmentDistance2(p, _vertices[j], _vertices[i]));
        break;
    }
    return std::max(0.0, std::sqrt(d2) - _radius);
}

osg::BoundingBoxd RegionOfInterest::bound() const
{
    osg::BoundingBoxd b;
    if (_vertices.size() < minimumVertices(_shape)) return b;
    for (const osg::Vec2d& v : _vertices)
        b.expandBy(osg::Vec3d(v.x(), v.y(), 0.0));
    b._min -= osg::Vec3d(_radius, _radius, 0.0);
    b._max += osg::Vec3d(_radius, _radius, 0.0);
    return b;
}

std::string RegionOfInterest::validate() const
{
    const std::string label =
        std::string(toString(_shape)) + (getName().empty() ? "" : " '" + getName() + "'");
    const std::size_t need = _placement == LONGEST_STREET ? 0 : minimumVertices(_shape);
    if (_vertices.size() < need)
        return label + " has " + std::to_string(_vertices.size()) + " vertices; it needs at least " +
               std::to_string(need);
    for (const osg::Vec2d& v : _vertices)
        if (!std::isfinite(v.x()) || !std::isfinite(v.y())) return label + " has a non-finite vertex";
    if (!std::isfinite(_radius) || _radius < 0.0) return label + " has an invalid radius";
    if (!std::isfinite(_lineWidth) || _lineWidth < 0.0 || _lineWidth > kMaxLineWidth)
        return label + " has a line width outside [0, " + std::to_string(int(kMaxLineWidth)) + "] pixels";
    for (int k = 0; k < 4; ++k)
        if (!std::isfinite(_lineColor[k]) || _lineColor[k] < 0.0f || _lineColor[k] > 1.0f)
            return label + " has a line colour component outside [0, 1]";
    if (_shape == POLYGON)
    {
        double area2 = 0.0;
        for (std::size_t i = 0; i < _vertices.size(); ++i)
        {
            const osg::Vec2d& a = _vertices[i];
            const osg::Vec2d& b = _vertices[(i + 1) % _vertices.size()];
            area2 += a.x() * b.y() - b.x() * a.y();
        }
        if (std::fabs(area2) <= 1e-12 && _placement != LONGEST_STREET) return label + " has zero area";
    }
    return std::string();
}

const char* RegionOfInterest::toString(Shape shape)
{
    switch (shape)
    {
    case CIRCLES:
        return "circles";
    case POLYLINE:
        return "polyline";
    case POLYGON:
        return "polygon";
    }
    return "circles";
}

bool RegionOfInterest::parseShape(const std::string& name, Shape& shape)
{
    std::string n = name;
    std::transform(n.begin(), n.end(), n.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    for (Shape s : {CIRCLES, POLYLINE, POLYGON})
        if (n == toString(s))
        {
            shape = s;
            return true;
        }
    return false;
}

} // namespace osgLoA
