/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/FlowBilateralFilter>
#include <osgLoA/palette/WeightedColor>

#include <cmath>

namespace osgLoA
{

osg::Vec3f WeightedColor::toLab(const osg::Vec3f& rgb)
{
    return FlowBilateralFilter::rgbToLab(rgb);
}

osg::Vec3f WeightedColor::fromLab(const osg::Vec3f& lab)
{
    return FlowBilateralFilter::labToRgb(lab);
}

double WeightedColor::deltaE(const osg::Vec3f& lab1, const osg::Vec3f& lab2)
{
    return deltaE(osg::Vec3d(lab1), osg::Vec3d(lab2));
}

double WeightedColor::deltaE(const osg::Vec3d& lab1, const osg::Vec3d& lab2)
{
    const osg::Vec3d d = lab1 - lab2;
    return std::sqrt(d * d);
}

} // namespace osgLoA
