// Dear ImGui over an osgViewer view (Debian's libimgui-dev, its OpenGL 3 backend), as osgEarth's
// ImGui integration does it: osgGA events feed ImGui's input, and the panels are built and drawn
// in the camera's final draw callback, after the scene. Events ImGui uses (a click on a panel,
// typing in a field) are marked handled, so the authoring handler and the manipulator skip them.
#ifndef OSGLOA_APPS_IMGUILAYER_H
#define OSGLOA_APPS_IMGUILAYER_H 1

#include <osg/Camera>
#include <osgGA/GUIEventHandler>

#include <functional>
#include <string>

namespace loa
{

class ImGuiLayer : public osgGA::GUIEventHandler
{
public:
    /** build: the panels (ImGui calls), run once a frame between NewFrame and Render. */
    explicit ImGuiLayer(std::function<void()> build);
    /** Draws over camera (its final draw callback). */
    void install(osg::Camera& camera);

    bool handle(const osgGA::GUIEventAdapter& ea, osgGA::GUIActionAdapter& aa, osg::Object*,
                osg::NodeVisitor*) override;
    using osgGA::GUIEventHandler::handle;

    /** Panels shown (Tab). Hidden, nothing of ImGui is drawn and no event is taken. */
    bool visible = true;
    /** Writes the next frame, panels included, to path (after drawing; ImageFile, atomic). */
    void requestScreenshot(const std::string& path) { _screenshot = path; }
    /** Called in the draw callback with the context current, after the panels (shader checks). */
    std::function<void(osg::RenderInfo&)> afterDraw;
    /** The last screenshot's error ("" when written). */
    std::string screenshotError;
    unsigned framesDrawn() const { return _frames; }

protected:
    ~ImGuiLayer() override;
    struct Draw;
    void draw(osg::RenderInfo& info);

    std::function<void()> _build;
    bool _initialised = false;
    bool _down[3] = {false, false, false};
    bool _pressedThisFrame[3] = {false, false, false};
    bool _captured = false; ///< the press that began the current drag went to ImGui
    double _mouseX = -1.0, _mouseY = -1.0;
    float _wheel = 0.0f;
    double _lastTime = -1.0;
    std::string _screenshot;
    unsigned _frames = 0;
};

} // namespace loa

#endif
