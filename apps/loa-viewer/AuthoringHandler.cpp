// AuthoringHandler: LoA keys and authoring gestures.
#include "AuthoringHandler.h"

#include <osg/ApplicationUsage>
#include <osgGA/StandardManipulator>

namespace loa
{

namespace
{
osgGA::StandardManipulator* standardManipulator(osgViewer::View& view)
{
    osgGA::CameraManipulator* m = view.getCameraManipulator();
    if (auto* ks = dynamic_cast<osgGA::KeySwitchMatrixManipulator*>(m)) m = ks->getCurrentMatrixManipulator();
    return dynamic_cast<osgGA::StandardManipulator*>(m);
}

/** The event's pointer in window coordinates of the view's camera (origin bottom left). */
void windowPoint(const osgGA::GUIEventAdapter& ea, const osg::Camera& camera, double& x, double& y)
{
    const osg::Viewport* vp = camera.getViewport();
    x = vp->x() + (ea.getXnormalized() + 1.0) * 0.5 * vp->width();
    y = vp->y() + (ea.getYnormalized() + 1.0) * 0.5 * vp->height();
}

int buttonNumber(unsigned button)
{
    typedef osgGA::GUIEventAdapter E;
    return button == E::LEFT_MOUSE_BUTTON ? 1 : button == E::MIDDLE_MOUSE_BUTTON ? 2 : 3;
}
} // namespace

void AuthoringHandler::goTo(osgViewer::View& view, const ViewerSession::Viewpoint& v)
{
    if (osgGA::StandardManipulator* m = standardManipulator(view))
        m->setTransformation(v.pose.eye, v.pose.center, v.pose.up);
}

osgLoA::CameraPose AuthoringHandler::currentPose(osgViewer::View& view)
{
    osgLoA::CameraPose pose;
    if (osgGA::StandardManipulator* m = standardManipulator(view))
        m->getTransformation(pose.eye, pose.center, pose.up);
    else
        view.getCamera()->getViewMatrixAsLookAt(pose.eye, pose.center, pose.up);
    return pose;
}

bool AuthoringHandler::handle(const osgGA::GUIEventAdapter& ea, osgGA::GUIActionAdapter& aa, osg::Object*,
                              osg::NodeVisitor*)
{
    if (ea.getHandled()) return false;
    osgViewer::View* view = dynamic_cast<osgViewer::View*>(&aa);
    if (!view) return false;
    const osg::Camera& camera = *view->getCamera();
    typedef osgGA::GUIEventAdapter E;
    ViewerSession& s = *_session;
    double x = 0.0, y = 0.0;
    switch (ea.getEventType())
    {
    case E::PUSH:
        windowPoint(ea, camera, x, y);
        return s.press(camera, x, y, buttonNumber(ea.getButton()));
    case E::DRAG:
        windowPoint(ea, camera, x, y);
        return s.drag(camera, x, y);
    case E::RELEASE:
        windowPoint(ea, camera, x, y);
        return s.release(camera, x, y);
    case E::KEYDOWN:
    {
        const int key = ea.getKey();
        const bool ctrl = (ea.getModKeyMask() & E::MODKEY_CTRL) != 0;
        const bool shift = (ea.getModKeyMask() & E::MODKEY_SHIFT) != 0;
        // With Ctrl, X11 delivers control characters (Ctrl+Z = 26); scripts send the letter.
        const int letter = ctrl && key >= 1 && key <= 26 ? 'a' + key - 1 : key;
        if (ctrl && (letter == 'z' || letter == 'Z')) return shift ? s.redo() || true : s.undo() || true;
        if (ctrl && (letter == 'y' || letter == 'Y')) return s.redo() || true;
        if (ctrl && (letter == 's' || letter == 'S'))
        {
            s.attempt([&] { s.saveScenario(s.savePath); });
            return true;
        }
        if (ctrl) return false;
        switch (key)
        {
        case E::KEY_Tab:
            _panels->visible = !_panels->visible;
            return true;
        case 'n':
            s.mode = ViewerSession::NAVIGATE;
            break;
        case 'e':
            s.mode = ViewerSession::INSPECT;
            break;
        case 'r':
            s.mode = ViewerSession::REGION;
            break;
        case 't':
            s.mode = ViewerSession::ROUTE;
            break;
        case 'o':
            s.mode = ViewerSession::FOCUS;
            break;
        case 'R':
            s.useRegionDetail();
            return true;
        case 'i':
            s.setInterestView(!s.getInterestView());
            return true;
        case E::KEY_F5:
            s.reloadShaders();
            return true;
        case 'v':
            if (!s.viewpoints.empty())
            {
                _viewpoint = (_viewpoint + 1) % s.viewpoints.size();
                goTo(*view, s.viewpoints[_viewpoint]);
                s.say("viewpoint '" + s.viewpoints[_viewpoint].name + "'");
            }
            return true;
        case 'V':
            s.addViewpoint("view " + std::to_string(s.viewpoints.size() + 1), currentPose(*view));
            s.say("saved viewpoint '" + s.viewpoints.back().name + "'");
            return true;
        default:
            return false;
        }
        s.say(std::string("mode: ") + ViewerSession::modeName(s.mode));
        return true;
    }
    default:
        return false;
    }
}

void AuthoringHandler::getUsage(osg::ApplicationUsage& usage) const
{
    usage.addKeyboardMouseBinding("Tab", "LoA: show or hide the panels");
    usage.addKeyboardMouseBinding("n", "LoA: navigate mode (the mouse moves the camera)");
    usage.addKeyboardMouseBinding("e", "LoA: inspect mode (click a feature)");
    usage.addKeyboardMouseBinding(
        "r", "LoA: region mode (drag a circle; drag inside one to move it; right-drag sets the fade)");
    usage.addKeyboardMouseBinding("R", "LoA: detail inside the circles, abstract outside");
    usage.addKeyboardMouseBinding(
        "t", "LoA: route mode (click adds a point, drag moves one, right-click removes one)");
    usage.addKeyboardMouseBinding("o", "LoA: focus mode (click the focus object)");
    usage.addKeyboardMouseBinding("i", "LoA: interest debug view on/off (black: detail, white: abstract)");
    usage.addKeyboardMouseBinding("v", "LoA: next viewpoint");
    usage.addKeyboardMouseBinding("V", "LoA: save the current view as a viewpoint");
    usage.addKeyboardMouseBinding("F5", "LoA: reload the style shaders from OSG_FILE_PATH");
    usage.addKeyboardMouseBinding("Ctrl+z", "LoA: undo");
    usage.addKeyboardMouseBinding("Ctrl+y", "LoA: redo (also Ctrl+Shift+z)");
    usage.addKeyboardMouseBinding("Ctrl+s", "LoA: save the scenario");
}

} // namespace loa
