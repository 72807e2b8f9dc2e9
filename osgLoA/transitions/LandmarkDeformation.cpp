// LandmarkDeformation: scaling, rotation to the best view, flattening and cylindrical billboard
// of landmarks, sinking of non-landmarks (paper 004 §3.2.2); the CPU twin of
// shaders/loa_landmark.vert.glsl and its uniforms.
#include <osgLoA/transitions/LandmarkDeformation>

#include <osg/Uniform>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace osgLoA
{

namespace
{
constexpr double kPi = 3.14159265358979323846;
/** A horizontal part shorter than this fraction of its vector counts as none. */
constexpr double kHorizontalEpsilon = 1e-9;

const std::string kEnabledName = "loa_deformEnabled";
const std::string kMatrixName = "loa_deformMatrix";
const std::string kNormalName = "loa_deformNormalMatrix";

bool finite(double v)
{
    return std::isfinite(v);
}

bool finite(const osg::Vec3d& v)
{
    return finite(v.x()) && finite(v.y()) && finite(v.z());
}

bool finite(const osg::Matrixd& m)
{
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
            if (!finite(m(r, c))) return false;
    return true;
}

/** The unit horizontal part of v, or false when it has none (relative to |v|). */
bool horizontalUnit(const osg::Vec3d& v, osg::Vec3d& out)
{
    if (!finite(v)) return false;
    const double h = std::sqrt(v.x() * v.x() + v.y() * v.y());
    const double len = v.length();
    if (!(h > 0.0) || h <= kHorizontalEpsilon * len) return false;
    out.set(v.x() / h, v.y() / h, 0.0);
    return true;
}

double clampd(double v, double lo, double hi)
{
    return std::max(lo, std::min(hi, v));
}

/** The affine matrix of an affine point function f, evaluated around origin o (which keeps the
 *  differences small): rows 0-2 the images of the unit vectors, row 3 the translation. */
template <class F> osg::Matrixd affineOf(const F& f, const osg::Vec3d& o)
{
    const osg::Vec3d f0 = f(o);
    const osg::Vec3d x = f(o + osg::Vec3d(1, 0, 0)) - f0;
    const osg::Vec3d y = f(o + osg::Vec3d(0, 1, 0)) - f0;
    const osg::Vec3d z = f(o + osg::Vec3d(0, 0, 1)) - f0;
    // p' = f0 + L (p - o) = L p + (f0 - L o); in rows: p' = p * M.
    const osg::Vec3d t = f0 - (x * o.x() + y * o.y() + z * o.z());
    return osg::Matrixd(x.x(), x.y(), x.z(), 0.0, y.x(), y.y(), y.z(), 0.0, z.x(), z.y(), z.z(), 0.0, t.x(),
                        t.y(), t.z(), 1.0);
}

/** The cofactor matrix of m's linear part (rows r0, r1, r2 -> r1 x r2, r2 x r0, r0 x r1). */
osg::Matrixd cofactorOf(const osg::Matrixd& m)
{
    const osg::Vec3d r0(m(0, 0), m(0, 1), m(0, 2)), r1(m(1, 0), m(1, 1), m(1, 2)),
        r2(m(2, 0), m(2, 1), m(2, 2));
    const osg::Vec3d a = r1 ^ r2, b = r2 ^ r0, c = r0 ^ r1;
    return osg::Matrixd(a.x(), a.y(), a.z(), 0.0, b.x(), b.y(), b.z(), 0.0, c.x(), c.y(), c.z(), 0.0, 0.0,
                        0.0, 0.0, 1.0);
}
} // namespace

// ---- inputs ----------------------------------------------------------------------------------

LandmarkDeformation::FeatureInput::FeatureInput(const Feature& feature, const osg::BoundingBoxd& sceneBound,
                                                double interest)
    : bound(sceneBound), landmark(feature.getLandmark()), bestView(feature.getBestViewDirection()),
      staticInterest(interest), type(feature.getType())
{
}

LandmarkDeformation::View LandmarkDeformation::View::lookAt(const osg::Vec3d& eye, const osg::Vec3d& center,
                                                            const osg::Vec3d& up)
{
    osg::Vec3d f = center - eye;
    f.normalize();
    // The true up vector: up without its part along f.
    osg::Vec3d u = up - f * (up * f);
    u.normalize();
    return View(eye, f, u);
}

LandmarkDeformation::View LandmarkDeformation::View::fromViewToScene(const osg::Matrixd& viewToScene)
{
    const osg::Vec3d eye = osg::Vec3d(0, 0, 0) * viewToScene;
    osg::Vec3d f = osg::Matrixd::transform3x3(osg::Vec3d(0, 0, -1), viewToScene);
    osg::Vec3d u = osg::Matrixd::transform3x3(osg::Vec3d(0, 1, 0), viewToScene);
    f.normalize();
    u.normalize();
    return View(eye, f, u);
}

// ---- object ----------------------------------------------------------------------------------

LandmarkDeformation::LandmarkDeformation()
    : _driver(new SaliencyMetric(SaliencyMetric::VIEW_ANGLE, 25.0, 60.0)), _sinkTypes{FeatureType::Building}
{
}

LandmarkDeformation::LandmarkDeformation(const LandmarkDeformation& other, const osg::CopyOp& copyop)
    : osg::Object(other, copyop), _scalingEnabled(other._scalingEnabled),
      _rotationEnabled(other._rotationEnabled), _flatteningEnabled(other._flatteningEnabled),
      _billboardEnabled(other._billboardEnabled), _sinkingEnabled(other._sinkingEnabled),
      _scaleNear(other._scaleNear), _scaleFar(other._scaleFar), _maxScale(other._maxScale),
      _interestFadeBegin(other._interestFadeBegin), _interestFadeEnd(other._interestFadeEnd),
      // The driver is part of this object's value: always its own copy.
      _driver(new SaliencyMetric(*other._driver, osg::CopyOp::DEEP_COPY_ALL)),
      _maxTiltDegrees(other._maxTiltDegrees), _sinkTypes(other._sinkTypes),
      _shrinkFactor(other._shrinkFactor), _sinkFactor(other._sinkFactor),
      _sinkFollowsMapStyles(other._sinkFollowsMapStyles), _mapStyles(other._mapStyles)
{
}

LandmarkDeformation::StyleNames LandmarkDeformation::defaultMapStyles()
{
    return {"cartographic", "waterlining", "relief", "signatures", "streets"};
}

bool LandmarkDeformation::isMapStyle(const std::string& style) const
{
    return std::find(_mapStyles.begin(), _mapStyles.end(), style) != _mapStyles.end();
}

bool LandmarkDeformation::sinks(FeatureType t) const
{
    return std::find(_sinkTypes.begin(), _sinkTypes.end(), t) != _sinkTypes.end();
}

std::string LandmarkDeformation::validate() const
{
    std::ostringstream s;
    if (!finite(_scaleNear) || !finite(_scaleFar) || _scaleNear < 0.0 || _scaleNear > _scaleFar)
        s << "scale distances " << _scaleNear << ".." << _scaleFar << " must be finite with 0 <= near <= far";
    else if (!finite(_maxScale) || !(_maxScale > 0.0))
        s << "maximum scale " << _maxScale << " must be finite and > 0";
    else if (!(_interestFadeBegin >= 0.0 && _interestFadeEnd <= 1.0 &&
               _interestFadeBegin <= _interestFadeEnd))
        s << "interest fade " << _interestFadeBegin << ".." << _interestFadeEnd
          << " must lie in [0,1] with begin <= end";
    else if (_driver->getKind() == SaliencyMetric::REGION || _driver->getKind() == SaliencyMetric::FOCUS)
        s << "the driver must be view-distance, view-angle or feature-interest, not "
          << SaliencyMetric::toString(_driver->getKind());
    else if (!_driver->validate().empty())
        s << "driver: " << _driver->validate();
    else if (!(_maxTiltDegrees >= 0.0 && _maxTiltDegrees <= 90.0))
        s << "maximum tilt " << _maxTiltDegrees << " must lie in [0,90] degrees";
    else if (!(_shrinkFactor >= 0.0 && _shrinkFactor <= 1.0))
        s << "shrink factor " << _shrinkFactor << " must lie in [0,1]";
    else if (!finite(_sinkFactor) || _sinkFactor < 0.0)
        s << "sink factor " << _sinkFactor << " must be finite and >= 0";
    return s.str();
}

// ---- amounts ---------------------------------------------------------------------------------

double LandmarkDeformation::smoothstep(double e0, double e1, double x)
{
    if (std::isnan(x)) return 0.0;
    if (!(e0 < e1)) return x < e1 ? 0.0 : 1.0;
    const double t = clampd((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

double LandmarkDeformation::interestFade(double staticInterest) const
{
    return smoothstep(_interestFadeBegin, _interestFadeEnd, staticInterest);
}

double LandmarkDeformation::scaleFactor(double distance, double fade) const
{
    const double s = 1.0 + (_maxScale - 1.0) * smoothstep(_scaleNear, _scaleFar, distance) * fade;
    return finite(s) && s > 0.0 ? s : 1.0;
}

double LandmarkDeformation::mapLikeness(const osg::Vec3d& centre, const osg::Vec3d& eye,
                                        double staticInterest) const
{
    SaliencyView view;
    view.eye = eye;
    return clampd(1.0 - _driver->evaluate(centre, view, staticInterest), 0.0, 1.0);
}

osg::Vec3d LandmarkDeformation::facingDirection(const View& view, const osg::Vec3d& centre,
                                                const osg::Vec3d& bestView, bool* fromBestView)
{
    if (fromBestView) *fromBestView = false;
    const osg::Vec3d forward = view.forward.length2() > 0.0 ? view.forward : centre - view.eye;
    osg::Vec3d h;
    if (horizontalUnit(forward, h) || horizontalUnit(view.up, h)) return -h;
    if (fromBestView) *fromBestView = true;
    if (horizontalUnit(bestView, h)) return h;
    return osg::Vec3d(0.0, -1.0, 0.0);
}

double LandmarkDeformation::elevation(const View& view, const osg::Vec3d& centre)
{
    const osg::Vec3d f = view.forward.length2() > 0.0 ? view.forward : centre - view.eye;
    if (!finite(f)) return 0.0;
    const double h = std::sqrt(f.x() * f.x() + f.y() * f.y());
    if (h == 0.0 && f.z() == 0.0) return 0.0;
    return std::atan2(-f.z(), h);
}

// ---- steps -----------------------------------------------------------------------------------

osg::Vec3d LandmarkDeformation::scaleStep(const osg::Vec3d& p, const osg::Vec3d& base, double scale)
{
    return base + (p - base) * scale;
}

osg::Vec3d LandmarkDeformation::rotateStep(const osg::Vec3d& p, const osg::Vec3d& centre, double angle)
{
    const double c = std::cos(angle), s = std::sin(angle);
    const double x = p.x() - centre.x(), y = p.y() - centre.y();
    return osg::Vec3d(centre.x() + c * x - s * y, centre.y() + s * x + c * y, p.z());
}

osg::Vec3d LandmarkDeformation::flattenStep(const osg::Vec3d& p, const osg::Vec3d& centre,
                                            const osg::Vec3d& facing)
{
    return p - facing * ((p - centre) * facing);
}

osg::Vec3d LandmarkDeformation::billboardStep(const osg::Vec3d& p, const osg::Vec3d& base,
                                              const osg::Vec3d& facing, double tilt)
{
    // In the frame (n, axis, Z) at the base, a rotation in the (n, Z) plane that takes n to
    // cos(t) n + sin(t) Z and Z to cos(t) Z - sin(t) n; the axis component stays.
    const osg::Vec3d d = p - base;
    const double u = d * facing, w = d.z();
    const double c = std::cos(tilt), s = std::sin(tilt);
    const osg::Vec3d z(0.0, 0.0, 1.0);
    return base + d - facing * u - z * w + (facing * c + z * s) * u + (z * c - facing * s) * w;
}

osg::Vec3d LandmarkDeformation::sinkStep(const osg::Vec3d& p, const osg::Vec3d& base, double height,
                                         double amount, double shrinkFactor, double sinkFactor)
{
    return base + (p - base) * (1.0 - amount * shrinkFactor) -
           osg::Vec3d(0.0, 0.0, amount * sinkFactor * height);
}

osg::Vec3d LandmarkDeformation::deform(const osg::Vec3d& p, const FeatureFrame& f)
{
    if (!f.landmark)
        return f.sink > 0.0 ? sinkStep(p, f.base, f.height, f.sink, f.shrinkFactor, f.sinkFactor) : p;
    const osg::Vec3d scaled = scaleStep(p, f.base, f.scale);
    if (!(f.morph > 0.0)) return scaled;
    osg::Vec3d q = rotateStep(scaled, f.centre, f.rotation);
    if (f.flatten) q = flattenStep(q, f.centre, f.facing);
    q = billboardStep(q, f.base, f.facing, f.tilt);
    return scaled + (q - scaled) * f.morph;
}

osg::Vec3d LandmarkDeformation::deformNormal(const osg::Vec3d& n, const FeatureFrame& frame)
{
    const osg::Matrixd& m = frame.normalMatrix;
    double frobenius = 0.0;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            frobenius += m(r, c) * m(r, c);
    osg::Vec3d d = osg::Matrixd::transform3x3(n, m);
    if (!(d.length2() > 1e-8 * frobenius * n.length2())) d = n;
    const double len = d.length();
    return len > 0.0 ? d / len : d;
}

// ---- per feature -----------------------------------------------------------------------------

LandmarkDeformation::FeatureFrame LandmarkDeformation::computeFrame(const FeatureInput& in,
                                                                    const View& view) const
{
    FeatureFrame f;
    f.landmark = in.landmark;
    if (!in.bound.valid() || !finite(in.bound._min) || !finite(in.bound._max)) return f;
    f.centre = in.bound.center();
    f.base.set(f.centre.x(), f.centre.y(), in.bound.zMin());
    f.height = in.bound.zMax() - in.bound.zMin();
    f.interestFade = interestFade(in.staticInterest);
    f.mapLikeness = mapLikeness(f.centre, view.eye, in.staticInterest);
    if (in.landmark)
    {
        if (_scalingEnabled) f.scale = scaleFactor((f.centre - view.eye).length(), f.interestFade);
        if (_rotationEnabled || _flatteningEnabled || _billboardEnabled)
            f.morph = f.mapLikeness * f.interestFade;
        bool fromBestView = false;
        f.facing = facingDirection(view, f.centre, in.bestView, &fromBestView);
        osg::Vec3d best;
        if (_rotationEnabled && !fromBestView && horizontalUnit(in.bestView, best))
            f.rotation = std::atan2(best.x() * f.facing.y() - best.y() * f.facing.x(), best * f.facing);
        f.flatten = _flatteningEnabled;
        if (_billboardEnabled)
            f.tilt = clampd(elevation(view, f.centre), 0.0, clampd(_maxTiltDegrees, 0.0, 90.0) * kPi / 180.0);
    }
    else if (_sinkingEnabled && sinks(in.type))
    {
        f.sink =
            _sinkFollowsMapStyles && in.mapWeight >= 0.0 ? clampd(in.mapWeight, 0.0, 1.0) : f.mapLikeness;
        f.shrinkFactor = clampd(_shrinkFactor, 0.0, 1.0);
        f.sinkFactor = finite(_sinkFactor) ? std::max(0.0, _sinkFactor) : 0.0;
    }
    const bool identity = in.landmark ? (f.scale == 1.0 && !(f.morph > 0.0)) : !(f.sink > 0.0);
    if (!identity)
    {
        f.matrix = affineOf([&f](const osg::Vec3d& p) { return deform(p, f); }, f.base);
        f.normalMatrix = cofactorOf(f.matrix);
        if (!finite(f.matrix) || !finite(f.normalMatrix))
        {
            f.matrix.makeIdentity();
            f.normalMatrix.makeIdentity();
        }
    }
    return f;
}

// ---- uniforms --------------------------------------------------------------------------------

void LandmarkDeformation::applyScenario(osg::StateSet& ss, const LandmarkDeformation* deformation)
{
    ss.getOrCreateUniform(kEnabledName, osg::Uniform::BOOL)->set(deformation != nullptr);
    applyFrame(ss, FeatureFrame());
}

void LandmarkDeformation::applyFeature(osg::StateSet& ss, const FeatureInput& feature, const View& view) const
{
    applyFrame(ss, computeFrame(feature, view));
}

void LandmarkDeformation::applyFrame(osg::StateSet& ss, const FeatureFrame& frame)
{
    ss.getOrCreateUniform(kMatrixName, osg::Uniform::FLOAT_MAT4)->set(osg::Matrixf(frame.matrix));
    const osg::Matrixd& n = frame.normalMatrix;
    ss.getOrCreateUniform(kNormalName, osg::Uniform::FLOAT_MAT3)
        ->set(osg::Matrix3(float(n(0, 0)), float(n(0, 1)), float(n(0, 2)), float(n(1, 0)), float(n(1, 1)),
                           float(n(1, 2)), float(n(2, 0)), float(n(2, 1)), float(n(2, 2))));
}

} // namespace osgLoA
