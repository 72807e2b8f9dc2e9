// HomeView: an oblique home view of a city model for interactive viewers.
#include <osgLoA/authoring/HomeView>

#include <cmath>

namespace osgLoA
{

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
    CameraPose pose = CityCameras::compute("oblique", scene, aspect);
    // CityCameras frames the model for its own field of view: keep the direction, scale the
    // distance so the same extent fits this camera's.
    const double scale =
        std::tan(osg::DegreesToRadians(pose.fovy) * 0.5) / std::tan(osg::DegreesToRadians(fovy) * 0.5);
    pose.eye = pose.center + (pose.eye - pose.center) * scale;
    pose.fovy = fovy;
    return pose;
}

void HomeView::apply(osgGA::CameraManipulator& manipulator, const CameraPose& pose)
{
    manipulator.setAutoComputeHomePosition(false);
    manipulator.setHomePosition(pose.eye, pose.center, pose.up, false);
    manipulator.home(0.0);
}

} // namespace osgLoA
