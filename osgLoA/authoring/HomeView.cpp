// HomeView: an oblique home view of a city model for interactive viewers.
#include <osgLoA/authoring/HomeView>
#include <osgLoA/semantics/FeatureIndex>

#include <osg/ComputeBoundsVisitor>
#include <osgGA/KeySwitchMatrixManipulator>
#include <osgGA/StandardManipulator>

#include <algorithm>
#include <cmath>

namespace osgLoA
{

namespace
{
// The frame keeps this share of the view's half-extent free around the model.
constexpr double kHomeMargin = 0.92;

/** What the home view frames: the top-level features but the terrain (a DEM or a ground plane
 *  reaches far beyond the city), else every feature, else the scene's geometry. */
osg::BoundingBoxd framedBox(osg::Node& scene)
{
    FeatureIndex index(scene);
    index.updateBounds();
    osg::BoundingBoxd features, all;
    for (const FeatureIndex::Entry& e : index.entries())
    {
        const osg::BoundingBoxf& b = e.feature->getBound();
        if (e.parent >= 0 || !b.valid()) continue;
        const osg::BoundingBoxd box(osg::Vec3d(b._min), osg::Vec3d(b._max));
        all.expandBy(box);
        if (e.feature->getType() != FeatureType::Terrain) features.expandBy(box);
    }
    if (features.valid()) return features;
    if (all.valid()) return all;
    osg::ComputeBoundsVisitor cbv;
    scene.accept(cbv);
    const osg::BoundingBox& b = cbv.getBoundingBox();
    if (!b.valid()) throw std::invalid_argument("the scene is empty: no home view");
    return osg::BoundingBoxd(osg::Vec3d(b._min), osg::Vec3d(b._max));
}
} // namespace

CameraPose HomeView::compute(osg::Node& scene, const osg::Camera* camera)
{
    double fovy = 45.0, aspect = 4.0 / 3.0;
    if (camera)
    {
        double f = 0.0, a = 0.0, zn = 0.0, zf = 0.0;
        if (camera->getProjectionMatrixAsPerspective(f, a, zn, zf) && f > 1.0 && f < 170.0 && a > 0.0)
        {
            fovy = f;
            aspect = a;
        }
        else if (const osg::Viewport* vp = camera->getViewport())
            if (vp->width() > 0 && vp->height() > 0) aspect = vp->width() / vp->height();
    }
    // The direction of CityCameras' oblique view (from the south-west, about 35 degrees down);
    // the distance the nearest at which every corner of the framed box is in view.
    const CameraPose oblique = CityCameras::compute("oblique", scene, aspect);
    osg::Vec3d forward = oblique.center - oblique.eye;
    forward.normalize();
    osg::Vec3d right = forward ^ osg::Vec3d(0.0, 0.0, 1.0);
    right.normalize();
    const osg::Vec3d up = right ^ forward;
    const osg::BoundingBoxd box = framedBox(scene);
    const osg::Vec3d c = box.center();
    const double ty = std::tan(osg::DegreesToRadians(fovy) * 0.5) * kHomeMargin, tx = ty * aspect;
    double distance = 1e-3;
    for (unsigned i = 0; i < 8; ++i)
    {
        const osg::Vec3d d = box.corner(i) - c;
        // In view when |d.right| <= tx (D + d.forward) and |d.up| <= ty (D + d.forward).
        distance = std::max(distance, std::fabs(d * right) / tx - d * forward);
        distance = std::max(distance, std::fabs(d * up) / ty - d * forward);
    }
    CameraPose pose;
    pose.center = c;
    pose.eye = c - forward * distance;
    pose.up = up;
    pose.fovy = fovy;
    return pose;
}

void HomeView::apply(osgGA::CameraManipulator& manipulator, const CameraPose& pose)
{
    manipulator.setAutoComputeHomePosition(false);
    manipulator.setHomePosition(pose.eye, pose.center, pose.up, false);
    // The stock viewers hold their manipulators in a KeySwitchMatrixManipulator, whose
    // home(double) does nothing: each manipulator gets the home and goes there.
    if (auto* keySwitch = dynamic_cast<osgGA::KeySwitchMatrixManipulator*>(&manipulator))
    {
        for (unsigned i = 0; i < keySwitch->getNumMatrixManipulators(); ++i)
            if (osgGA::CameraManipulator* m = keySwitch->getMatrixManipulatorWithIndex(i)) apply(*m, pose);
        return;
    }
    if (auto* standard = dynamic_cast<osgGA::StandardManipulator*>(&manipulator))
        standard->setTransformation(pose.eye, pose.center, pose.up);
    else
        manipulator.setByInverseMatrix(osg::Matrixd::lookAt(pose.eye, pose.center, pose.up));
}

} // namespace osgLoA
