// loa-viewer's keys and the mouse in its authoring modes (ViewerSession), and the manipulator
// guard that leaves the camera alone while ImGui or an authoring gesture has the mouse.
#ifndef OSGLOA_APPS_AUTHORINGHANDLER_H
#define OSGLOA_APPS_AUTHORINGHANDLER_H 1

#include "ImGuiLayer.h"
#include "ViewerSession.h"

#include <osgGA/KeySwitchMatrixManipulator>
#include <osgViewer/View>

namespace loa
{

/** The stock manipulators (trackball, flight, drive, terrain, orbit: keys 1-5) that ignore the
 *  events ImGui or the authoring handler took. */
class GuardedManipulator : public osgGA::KeySwitchMatrixManipulator
{
public:
    bool handle(const osgGA::GUIEventAdapter& ea, osgGA::GUIActionAdapter& aa) override
    {
        return ea.getHandled() ? false : osgGA::KeySwitchMatrixManipulator::handle(ea, aa);
    }
    using osgGA::KeySwitchMatrixManipulator::handle;
};

class AuthoringHandler : public osgGA::GUIEventHandler
{
public:
    AuthoringHandler(ViewerSession& session, ImGuiLayer& panels) : _session(&session), _panels(&panels) {}
    bool handle(const osgGA::GUIEventAdapter& ea, osgGA::GUIActionAdapter& aa, osg::Object*,
                osg::NodeVisitor*) override;
    using osgGA::GUIEventHandler::handle;
    void getUsage(osg::ApplicationUsage& usage) const override;

    /** Moves the view's camera to viewpoint i of the session. */
    static void goTo(osgViewer::View& view, const ViewerSession::Viewpoint& v);
    /** The view's current pose. */
    static osgLoA::CameraPose currentPose(osgViewer::View& view);

private:
    ViewerSession* _session;
    ImGuiLayer* _panels;
    std::size_t _viewpoint = 0;
};

} // namespace loa

#endif
