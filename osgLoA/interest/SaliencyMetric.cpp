// SaliencyMetric: view distance, vertical view angle, region, focus and feature interest, each
// mapped to [0,1] by a near/far ramp.
#include <osgLoA/interest/SaliencyMetric>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <sstream>

namespace osgLoA
{

namespace
{
constexpr double kInf = std::numeric_limits<double>::infinity();

double boxDistance(const osg::Vec3d& p, const osg::BoundingBoxd& b)
{
    const double dx = std::max(0.0, std::max(b.xMin() - p.x(), p.x() - b.xMax()));
    const double dy = std::max(0.0, std::max(b.yMin() - p.y(), p.y() - b.yMax()));
    const double dz = std::max(0.0, std::max(b.zMin() - p.z(), p.z() - b.zMax()));
    return std::sqrt(dx * dx + dy * dy + dz * dz);
}

double regionDistance(const osg::Vec3d& p, const SaliencyView& view)
{
    double d = kInf;
    if (view.regions)
        for (const auto& r : *view.regions)
            if (r.valid()) d = std::min(d, r->distance(osg::Vec2d(p.x(), p.y())));
    return d;
}

constexpr double kPi = 3.14159265358979323846;

double degrees(double radians)
{
    return radians * 180.0 / kPi;
}

/** The horizontal distance (x, y) from the eye to p. */
double horizontalDistance(const osg::Vec3d& p, const osg::Vec3d& eye)
{
    const double dx = p.x() - eye.x(), dy = p.y() - eye.y();
    return std::sqrt(dx * dx + dy * dy);
}

/** The horizontal distances from the eye to the nearest and the farthest point of the box. */
void horizontalRange(const osg::BoundingBoxd& box, const osg::Vec3d& e, double& hMin, double& hMax)
{
    const double hx = std::max(0.0, std::max(box.xMin() - e.x(), e.x() - box.xMax()));
    const double hy = std::max(0.0, std::max(box.yMin() - e.y(), e.y() - box.yMax()));
    hMin = std::sqrt(hx * hx + hy * hy);
    const double fx = std::max(std::fabs(e.x() - box.xMin()), std::fabs(e.x() - box.xMax()));
    const double fy = std::max(std::fabs(e.y() - box.yMin()), std::fabs(e.y() - box.yMax()));
    hMax = std::sqrt(fx * fx + fy * fy);
}

/** REGION and FOCUS over a box from the value q at its centre: the distance changes no faster
 *  than the point moves, so it stays within the box's horizontal (REGION) or full (FOCUS)
 *  half-diagonal of q. */
void centreRange(SaliencyMetric::Kind kind, const osg::BoundingBoxd& box, double q, double& qMin,
                 double& qMax)
{
    const osg::Vec3d half = (box._max - box._min) * 0.5;
    const double r =
        kind == SaliencyMetric::REGION ? std::sqrt(half.x() * half.x() + half.y() * half.y()) : half.length();
    qMin = std::max(0.0, q - r);
    qMax = q + r;
}
} // namespace

SaliencyMetric::SaliencyMetric() = default;

SaliencyMetric::SaliencyMetric(Kind kind, double nearValue, double farValue, double weight)
    : _kind(kind), _weight(weight)
{
    setNear(nearValue);
    setFar(farValue);
}

SaliencyMetric::SaliencyMetric(const SaliencyMetric& other, const osg::CopyOp& copyop)
    : osg::Object(other, copyop), _kind(other._kind), _near(other._near), _far(other._far),
      _weight(other._weight), _scale(other._scale), _tanNear(other._tanNear), _tanFar(other._tanFar)
{
}

double SaliencyMetric::tangentOf(double angle)
{
    return angle >= 0.0 && angle <= 89.0 ? std::tan(angle * kPi / 180.0) : -1.0;
}

double SaliencyMetric::angleInterest(double dz, double h) const
{
    // The angle atan2(dz, h) is at most near where dz <= h tan(near) and at least far where
    // dz >= h tan(far): there the ramp is saturated and needs no arc tangent. The relative
    // margin of 1e-9 (far above the rounding of atan2 and tan, for angles up to 89 degrees)
    // leaves the points right at the ends of the ramp to the exact path, so the result is the
    // same as ramp(angle); NaN fails every comparison and takes the exact path too.
    if (_tanNear >= 0.0 && dz <= h * _tanNear * (1.0 - 1e-9)) return 1.0;
    if (_tanFar >= 0.0 && _near <= _far && dz >= h * _tanFar * (1.0 + 1e-9)) return 0.0;
    return ramp(degrees(std::atan2(dz, h)), _near, _far);
}

double SaliencyMetric::measure(const osg::Vec3d& p, const SaliencyView& view, double featureInterest) const
{
    switch (_kind)
    {
    case VIEW_DISTANCE:
        return (p - view.eye).length();
    case VIEW_ANGLE:
        return degrees(std::atan2(std::max(0.0, view.eye.z() - p.z()), horizontalDistance(p, view.eye)));
    case REGION:
        return regionDistance(p, view);
    case FOCUS:
        return view.focus.valid() ? boxDistance(p, view.focus) : kInf;
    case FEATURE_INTEREST:
        return featureInterest;
    }
    return 0.0;
}

void SaliencyMetric::measureRange(const osg::BoundingBoxd& box, const SaliencyView& view,
                                  double featureInterest, double& qMin, double& qMax) const
{
    const osg::Vec3d& e = view.eye;
    switch (_kind)
    {
    case VIEW_DISTANCE:
    {
        qMin = boxDistance(e, box);
        const double dx = std::max(std::fabs(e.x() - box.xMin()), std::fabs(e.x() - box.xMax()));
        const double dy = std::max(std::fabs(e.y() - box.yMin()), std::fabs(e.y() - box.yMax()));
        const double dz = std::max(std::fabs(e.z() - box.zMin()), std::fabs(e.z() - box.zMax()));
        qMax = std::sqrt(dx * dx + dy * dy + dz * dz);
        return;
    }
    case VIEW_ANGLE:
    {
        // The angle grows with the height difference and falls with the horizontal distance,
        // so its extremes lie at the box's top/bottom and nearest/farthest horizontal points.
        double hMin = 0.0, hMax = 0.0;
        horizontalRange(box, e, hMin, hMax);
        qMin = degrees(std::atan2(std::max(0.0, e.z() - box.zMax()), hMax));
        qMax = degrees(std::atan2(std::max(0.0, e.z() - box.zMin()), hMin));
        return;
    }
    case REGION:
    case FOCUS:
        centreRange(_kind, box, measure(box.center(), view, featureInterest), qMin, qMax);
        return;
    case FEATURE_INTEREST:
        qMin = qMax = featureInterest;
        return;
    }
}

double SaliencyMetric::evaluate(const osg::Vec3d& p, const SaliencyView& view, double featureInterest) const
{
    if (_kind == VIEW_ANGLE)
        return angleInterest(std::max(0.0, view.eye.z() - p.z()), horizontalDistance(p, view.eye));
    return interest(measure(p, view, featureInterest));
}

void SaliencyMetric::interestRange(const osg::BoundingBoxd& box, const SaliencyView& view,
                                   double featureInterest, double& lo, double& hi) const
{
    if (_kind == VIEW_ANGLE)
    {
        // measureRange's extremes, turned into interest without the arc tangent where the
        // ramp is saturated: the lowest interest at the steepest angle, the highest at the
        // flattest.
        const osg::Vec3d& e = view.eye;
        double hMin = 0.0, hMax = 0.0;
        horizontalRange(box, e, hMin, hMax);
        lo = angleInterest(std::max(0.0, e.z() - box.zMin()), hMin);
        hi = angleInterest(std::max(0.0, e.z() - box.zMax()), hMax);
        return;
    }
    double qMin = 0.0, qMax = 0.0;
    measureRange(box, view, featureInterest, qMin, qMax);
    lo = interest(qMax);
    hi = interest(qMin);
}

void SaliencyMetric::evaluateOverBox(const osg::BoundingBoxd& box, const SaliencyView& view,
                                     double featureInterest, double& atCentre, double& lo, double& hi) const
{
    if (_kind == REGION || _kind == FOCUS)
    {
        const double q = measure(box.center(), view, featureInterest);
        double qMin = 0.0, qMax = 0.0;
        centreRange(_kind, box, q, qMin, qMax);
        atCentre = interest(q);
        lo = interest(qMax);
        hi = interest(qMin);
        return;
    }
    atCentre = evaluate(box.center(), view, featureInterest);
    interestRange(box, view, featureInterest, lo, hi);
}

double SaliencyMetric::ramp(double q, double nearValue, double farValue)
{
    if (std::isnan(q)) return 0.0;
    if (q <= nearValue) return 1.0;
    if (q >= farValue) return 0.0;
    return 1.0 - (q - nearValue) / (farValue - nearValue); // farValue > q > nearValue: no 0/0
}

double SaliencyMetric::interest(double q) const
{
    if (_kind == FEATURE_INTEREST) return std::isnan(q) ? 0.0 : std::min(1.0, std::max(0.0, q));
    return ramp(q, _near, _far);
}

std::string SaliencyMetric::validate() const
{
    std::ostringstream s;
    s << toString(_kind) << " metric ";
    if (!std::isfinite(_weight) || _weight < 0.0)
    {
        s << "has weight " << _weight << "; it must be finite and >= 0";
        return s.str();
    }
    if (_kind == FEATURE_INTEREST) return std::string();
    if (_scale != ABSOLUTE && _kind == VIEW_ANGLE)
        s << "cannot be scaled to the scene or view (" << toString(_scale) << "): it measures degrees";
    else if (_scale == VIEW && _kind == REGION)
        s << "cannot follow the view: the distance map of the regions is built once per binding (use scene)";
    else if (!std::isfinite(_near) || !std::isfinite(_far))
        s << "has a non-finite near or far value";
    else if (_near < 0.0)
        s << "has near " << _near << " < 0";
    else if (_near > _far)
        s << "is inverted: near " << _near << " > far " << _far;
    else if (_kind == VIEW_ANGLE && _far > 90.0)
        s << "has far " << _far << " > 90 degrees";
    else
        return std::string();
    return s.str();
}

const char* SaliencyMetric::toString(Scale scale)
{
    switch (scale)
    {
    case SCENE:
        return "scene";
    case VIEW:
        return "view";
    default:
        return "absolute";
    }
}

bool SaliencyMetric::parseScale(const std::string& name, Scale& scale)
{
    std::string n = name;
    for (char& c : n)
        c = char(std::tolower(static_cast<unsigned char>(c)));
    for (Scale s : {ABSOLUTE, SCENE, VIEW})
        if (n == toString(s))
        {
            scale = s;
            return true;
        }
    return false;
}

const char* SaliencyMetric::toString(Kind kind)
{
    switch (kind)
    {
    case VIEW_DISTANCE:
        return "view-distance";
    case VIEW_ANGLE:
        return "view-angle";
    case REGION:
        return "region";
    case FOCUS:
        return "focus";
    case FEATURE_INTEREST:
        return "feature-interest";
    }
    return "view-distance";
}

bool SaliencyMetric::parseKind(const std::string& name, Kind& kind)
{
    std::string n = name;
    std::transform(n.begin(), n.end(), n.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    std::replace(n.begin(), n.end(), '_', '-');
    for (int k = 0; k < kNumKinds; ++k)
        if (n == toString(Kind(k)))
        {
            kind = Kind(k);
            return true;
        }
    return false;
}

} // namespace osgLoA
