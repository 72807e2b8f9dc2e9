// FeaturePicker: the feature and scene point under a window point.
#include <osgLoA/authoring/FeaturePicker>

#include <osg/ComputeBoundsVisitor>
#include <osgUtil/IntersectionVisitor>
#include <osgUtil/LineSegmentIntersector>

#include <cmath>

namespace osgLoA
{

const Feature* FeaturePicker::featureOn(const osg::NodePath& path)
{
    for (auto it = path.rbegin(); it != path.rend(); ++it)
        if (const Feature* f = Feature::get(**it)) return f;
    return nullptr;
}

FeaturePicker::Hit FeaturePicker::pick(const osg::Camera& camera, double windowX, double windowY,
                                       osg::Node& scene, const LoANode& node)
{
    Hit hit;
    const osg::Viewport* vp = camera.getViewport();
    if (!vp || vp->width() <= 0 || vp->height() <= 0) return hit;
    const osg::Matrixd vpw =
        camera.getViewMatrix() * camera.getProjectionMatrix() * vp->computeWindowMatrix();
    osg::Matrixd inverse;
    if (!inverse.invert(vpw)) return hit;
    const osg::Vec3d start = osg::Vec3d(windowX, windowY, 0.0) * inverse;
    const osg::Vec3d end = osg::Vec3d(windowX, windowY, 1.0) * inverse;

    // The LoA node's coordinates: its world matrix on the first path from the scene to it.
    osg::Matrixd nodeToWorld;
    {
        const osg::NodePathList paths = node.getParentalNodePaths(&scene);
        if (!paths.empty()) nodeToWorld = osg::computeLocalToWorld(paths.front());
    }
    const osg::Matrixd worldToNode = osg::Matrixd::inverse(nodeToWorld);

    osg::ref_ptr<osgUtil::LineSegmentIntersector> intersector =
        new osgUtil::LineSegmentIntersector(osgUtil::Intersector::MODEL, start, end);
    intersector->setIntersectionLimit(osgUtil::Intersector::LIMIT_NEAREST);
    osgUtil::IntersectionVisitor iv(intersector.get());
    scene.accept(iv);
    if (intersector->containsIntersections())
    {
        const osgUtil::LineSegmentIntersector::Intersection& first = intersector->getFirstIntersection();
        hit.surface = hit.ground = true;
        hit.world = first.getWorldIntersectPoint();
        hit.scene = hit.world * worldToNode;
        if (const Feature* f = featureOn(first.nodePath))
        {
            hit.feature = f;
            hit.featureId = f->getId();
        }
        return hit;
    }
    // The ground plane: the lowest point of the features (node coordinates).
    double z = 0.0;
    bool haveZ = false;
    for (const FeatureIndex::Entry& e : node.getFeatureIndex().entries())
        if (e.feature->getBound().valid())
        {
            z = haveZ ? std::min(z, double(e.feature->getBound().zMin()))
                      : double(e.feature->getBound().zMin());
            haveZ = true;
        }
    const osg::Vec3d a = start * worldToNode, b = end * worldToNode;
    const double dz = b.z() - a.z();
    if (!haveZ || std::fabs(dz) < 1e-12) return hit;
    const double t = (z - a.z()) / dz;
    if (!(t > 0.0) || !std::isfinite(t)) return hit;
    hit.ground = true;
    hit.scene = a + (b - a) * t;
    hit.world = hit.scene * nodeToWorld;
    return hit;
}

} // namespace osgLoA
