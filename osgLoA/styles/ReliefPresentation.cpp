/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/styles/ReliefPresentation>

#include <algorithm>
#include <cmath>

namespace osgLoA
{

namespace
{
struct ReliefRegistrar
{
    ReliefRegistrar() { ReliefPresentation::registerStyle(); }
} s_reliefRegistrar;

osg::Vec3d upward(const osg::Vec3d& normal)
{
    osg::Vec3d n = normal;
    const double len = n.length();
    if (!(len > 0.0) || !std::isfinite(len)) return osg::Vec3d(0, 0, 1);
    n /= len;
    return n.z() < 0.0 ? -n : n;
}
} // namespace

osg::ref_ptr<GraphicStyle> ReliefPresentation::create()
{
    osg::ref_ptr<GraphicStyle> s = GraphicStyle::createBuiltin("cartographic");
    s->setName(name());
    s->setDescription("cartographic, with terrain as relief: slope lines, shadowed hachures lit from the "
                      "north-west and loose form lines (paper 004 Figure 8D)");
    s->setFragmentShader("loa_style_relief.frag.glsl");
    osg::StateSet* ss = s->getParameters();
    ss->setName(std::string(name()) + " parameters");
    const Parameters p;
    ss->addUniform(new osg::Uniform("loa_relief_strokeColor", osg::Vec3f(140, 81, 10) / 255.0f));
    ss->addUniform(new osg::Uniform("loa_relief_cellPixels", p.cellPixels));
    ss->addUniform(new osg::Uniform("loa_relief_length", p.length));
    ss->addUniform(new osg::Uniform("loa_relief_width", p.width));
    ss->addUniform(new osg::Uniform("loa_relief_shadowWidth", p.shadowWidth));
    ss->addUniform(new osg::Uniform("loa_relief_minSlope", p.minSlope));
    ss->addUniform(new osg::Uniform("loa_relief_maxSlope", p.maxSlope));
    ss->addUniform(new osg::Uniform("loa_relief_lightDirection", osg::Vec3f(p.lightDirection)));
    ss->addUniform(new osg::Uniform("loa_relief_contourInterval", p.contourInterval));
    ss->addUniform(new osg::Uniform("loa_relief_contourPixels", p.contourPixels));
    ss->addUniform(new osg::Uniform("loa_relief_contourStrength", p.contourStrength));
    return s;
}

void ReliefPresentation::registerStyle()
{
    GraphicStyleCatalog::instance().add(*create());
}

osg::Vec2d ReliefPresentation::downhill(const osg::Vec3d& normal)
{
    const osg::Vec3d n = upward(normal);
    const double h = std::hypot(n.x(), n.y());
    // The upward normal leans downhill: its ground part is the direction of steepest descent.
    return h > 1e-6 ? osg::Vec2d(n.x() / h, n.y() / h) : osg::Vec2d(0.0, -1.0);
}

double ReliefPresentation::slope(const osg::Vec3d& normal)
{
    const osg::Vec3d n = upward(normal);
    return std::hypot(n.x(), n.y()) / std::max(n.z(), 1e-3);
}

double ReliefPresentation::shade(const osg::Vec3d& normal, const Parameters& p)
{
    osg::Vec3d l = p.lightDirection;
    l.normalize();
    return 1.0 - std::max(upward(normal) * l, 0.0);
}

double ReliefPresentation::density(double s, const Parameters& p)
{
    const double e0 = p.minSlope, e1 = p.maxSlope;
    if (!(e1 > e0)) return s >= e1 ? 1.0 : 0.0;
    const double t = std::clamp((s - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

osg::Vec3d ReliefPresentation::cellSizes(double pixelWorld, const Parameters& p)
{
    const double level = std::log2(std::max(double(p.cellPixels) * pixelWorld, 1e-6));
    const double l0 = std::floor(level);
    return osg::Vec3d(std::exp2(l0), std::exp2(l0 + 1.0), level - l0);
}

} // namespace osgLoA
