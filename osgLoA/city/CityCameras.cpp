#include <osgLoA/city/CityCameras>
#include <osgLoA/semantics/Feature>

#include <osg/ComputeBoundsVisitor>
#include <osgUtil/IntersectionVisitor>
#include <osgUtil/LineSegmentIntersector>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace osgLoA
{
namespace
{
/** Bounding boxes of buildings and streets, and of the first major street. */
class FocusBounds : public osg::NodeVisitor
{
public:
    FocusBounds() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
    void apply(osg::Node& node) override
    {
        if (const Feature* f = Feature::get(node))
        {
            if (f->getType() == FeatureType::Building || f->getType() == FeatureType::Street)
            {
                // In the scene's coordinates: the transforms above the feature apply.
                osg::ComputeBoundsVisitor cbv;
                const osg::NodePath& path = getNodePath();
                osg::Matrix toScene = osg::computeLocalToWorld(osg::NodePath(path.begin(), path.end() - 1));
                cbv.pushMatrix(toScene);
                node.accept(cbv);
                focus.expandBy(cbv.getBoundingBox());
                if (f->getType() == FeatureType::Street && f->getSubType() == "major")
                    majorStreets.push_back(cbv.getBoundingBox());
            }
            return; // features do not nest
        }
        traverse(node);
    }
    osg::BoundingBox focus;
    std::vector<osg::BoundingBox> majorStreets;
};
} // namespace

std::vector<std::string> CityCameras::names()
{
    return {"street", "oblique", "top", "horizon"};
}

bool CityCameras::isName(const std::string& name)
{
    for (const auto& n : names())
        if (n == name) return true;
    return false;
}

double CityCameras::groundHeight(osg::Node& scene, double x, double y, double fallback)
{
    const osg::BoundingSphere bs = scene.getBound();
    const double top = bs.center().z() + bs.radius() + 1.0, bottom = bs.center().z() - bs.radius() - 1.0;
    osg::ref_ptr<osgUtil::LineSegmentIntersector> li =
        new osgUtil::LineSegmentIntersector(osg::Vec3d(x, y, top), osg::Vec3d(x, y, bottom));
    li->setIntersectionLimit(osgUtil::Intersector::LIMIT_NEAREST);
    osgUtil::IntersectionVisitor iv(li.get());
    scene.accept(iv);
    return li->containsIntersections() ? li->getFirstIntersection().getWorldIntersectPoint().z() : fallback;
}

CameraPose CityCameras::compute(const std::string& name, osg::Node& scene, double aspect)
{
    if (!isName(name))
        throw std::invalid_argument("unknown camera '" + name + "' (known: street, oblique, top, horizon)");
    FocusBounds fb;
    scene.accept(fb);
    osg::BoundingBox box = fb.focus;
    if (!box.valid())
    {
        osg::ComputeBoundsVisitor cbv;
        scene.accept(cbv);
        box = cbv.getBoundingBox();
    }
    if (!box.valid()) throw std::invalid_argument("camera '" + name + "' needs a scene with geometry");

    CameraPose pose;
    pose.up.set(0, 0, 1);
    const osg::Vec3d c = box.center();
    const double ex = box.xMax() - box.xMin(), ey = box.yMax() - box.yMin();
    const double tanHalf = std::tan(osg::DegreesToRadians(pose.fovy) / 2.0);
    if (name == "top")
    {
        const double need = std::max(ey, ex / aspect) * 0.5 / tanHalf;
        pose.eye.set(c.x(), c.y(), box.zMax() + need * 1.05);
        pose.center.set(c.x(), c.y(), box.zMin());
        pose.up.set(0, 1, 0);
    }
    else if (name == "oblique")
    {
        osg::Vec3d dir(-0.45, -0.75, 0.62);
        dir.normalize();
        const double radius = 0.5 * std::sqrt(ex * ex + ey * ey);
        const double dist = radius / std::sin(std::atan(tanHalf * std::min(1.0, aspect))) * 0.9;
        pose.center.set(c.x(), c.y(), box.zMin());
        pose.eye = pose.center + dir * dist;
    }
    else if (name == "horizon")
    {
        const double gx = c.x(), gy = box.yMin() - 0.05 * ey;
        const double gz = groundHeight(scene, gx, gy, box.zMin());
        pose.eye.set(gx, gy, gz + 25.0);
        pose.center = pose.eye + osg::Vec3d(0.0, 100.0, -4.0);
    }
    else // street
    {
        pose.fovy = 60.0;
        // The major street whose centre is nearest the city's centre.
        osg::BoundingBox s;
        double best = 1e300;
        for (const osg::BoundingBox& m : fb.majorStreets)
        {
            const osg::Vec3d d = osg::Vec3d(m.center()) - c;
            const double d2 = d.x() * d.x() + d.y() * d.y();
            if (d2 < best) best = d2, s = m;
        }
        if (s.valid())
        {
            const bool alongX = (s.xMax() - s.xMin()) >= (s.yMax() - s.yMin());
            const double width = alongX ? s.yMax() - s.yMin() : s.xMax() - s.xMin();
            // Stand a quarter of the way along, in the right-hand lane, look along the street.
            double x = alongX ? s.xMin() + 0.25 * (s.xMax() - s.xMin()) : s.center().x() + width / 4;
            double y = alongX ? s.center().y() - width / 4 : s.yMin() + 0.25 * (s.yMax() - s.yMin());
            const double z = groundHeight(scene, x, y, s.zMax()) + 1.7;
            pose.eye.set(x, y, z);
            pose.center = pose.eye + (alongX ? osg::Vec3d(100.0, 0.0, 0.0) : osg::Vec3d(0.0, 100.0, 0.0));
        }
        else
        {
            const double x = c.x(), y = box.yMin();
            pose.eye.set(x, y, groundHeight(scene, x, y, box.zMin()) + 1.7);
            pose.center = pose.eye + osg::Vec3d(0.0, 100.0, 0.0);
        }
    }
    return pose;
}

} // namespace osgLoA
