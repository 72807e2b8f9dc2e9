/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/abstraction/AbstractionFocus>

#include <cmath>
#include <stdexcept>
#include <string>

namespace osgLoA
{

AbstractionFocus::AbstractionFocus(const AbstractionFocus& o, const osg::CopyOp& copyop)
    : osg::Object(o, copyop), _mode(o._mode), _screenPoint(o._screenPoint), _worldPoint(o._worldPoint),
      _objectId(o._objectId), _innerRadius(o._innerRadius), _outerRadius(o._outerRadius)
{
}

void AbstractionFocus::validate() const
{
    if (_mode != SCREEN_POINT && _mode != WORLD_POINT && _mode != OBJECT)
        throw std::invalid_argument("AbstractionFocus: mode " + std::to_string(int(_mode)) +
                                    " is not a mode");
    if (!std::isfinite(_screenPoint.x()) || !std::isfinite(_screenPoint.y()))
        throw std::invalid_argument("AbstractionFocus: screenPoint must be finite");
    if (!std::isfinite(_worldPoint.x()) || !std::isfinite(_worldPoint.y()) || !std::isfinite(_worldPoint.z()))
        throw std::invalid_argument("AbstractionFocus: worldPoint must be finite");
    if (!std::isfinite(_innerRadius) || _innerRadius < 0.0f)
        throw std::invalid_argument("AbstractionFocus: innerRadius " + std::to_string(_innerRadius) +
                                    " must be finite and >= 0");
    if (!std::isfinite(_outerRadius) || _outerRadius < 0.0f)
        throw std::invalid_argument("AbstractionFocus: outerRadius " + std::to_string(_outerRadius) +
                                    " must be finite and >= 0");
    if (_innerRadius > _outerRadius)
        throw std::invalid_argument("AbstractionFocus: innerRadius " + std::to_string(_innerRadius) +
                                    " is above outerRadius " + std::to_string(_outerRadius));
}

float AbstractionFocus::smoothstep(float e0, float e1, float x)
{
    if (e0 == e1) return x < e0 ? 0.0f : 1.0f;
    float t = (x - e0) / (e1 - e0);
    t = t < 0.0f ? 0.0f : (t > 1.0f ? 1.0f : t);
    return t * t * (3.0f - 2.0f * t);
}

float AbstractionFocus::focusWeight(float distance) const
{
    if (std::isnan(distance)) return 0.0f;
    if (_innerRadius == _outerRadius) return distance < _innerRadius ? 1.0f : 0.0f;
    return 1.0f - smoothstep(_innerRadius, _outerRadius, distance);
}

float AbstractionFocus::screenDistance(const osg::Vec2f& pixelCentre, const osg::Vec2f& focusPixel, int width,
                                       int height)
{
    if (width <= 0) throw std::invalid_argument("AbstractionFocus::screenDistance: width must be positive");
    if (height <= 0) throw std::invalid_argument("AbstractionFocus::screenDistance: height must be positive");
    const float diagonal = std::sqrt(float(width) * float(width) + float(height) * float(height));
    return (pixelCentre - focusPixel).length() / diagonal;
}

osg::Vec2f AbstractionFocus::focusPixel(int width, int height) const
{
    return osg::Vec2f(_screenPoint.x() * float(width), _screenPoint.y() * float(height));
}

float AbstractionFocus::objectImportance(const osg::Vec3d& objectCentre, const osg::Vec3d& focusCentre,
                                         double sceneDiameter) const
{
    if (!(sceneDiameter > 0.0)) return objectCentre == focusCentre ? 1.0f : 0.0f;
    return focusWeight(float((objectCentre - focusCentre).length() / sceneDiameter));
}

} // namespace osgLoA
