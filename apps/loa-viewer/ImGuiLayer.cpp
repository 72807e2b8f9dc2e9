// ImGuiLayer: osgGA events into Dear ImGui, panels drawn after the scene.
#include "ImGuiLayer.h"

#include <osgLoA/util/ImageFile>

#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <osg/Image>
#include <osg/Timer>

namespace loa
{

namespace
{
// ImGui 1.86 reads keys from io.KeysDown[512]: printable keys at their code, osgGA's special
// keys (0xFF00 and up) at 256 + their low byte.
int keyIndex(int key)
{
    if (key >= 0 && key < 256) return key;
    if (key >= 0xFF00 && key <= 0xFFFF) return 256 + (key & 0xFF);
    return -1;
}
} // namespace

struct ImGuiLayer::Draw : public osg::Camera::DrawCallback
{
    explicit Draw(ImGuiLayer* layer) : _layer(layer) {}
    void operator()(osg::RenderInfo& info) const override { _layer->draw(info); }
    ImGuiLayer* _layer;
};

ImGuiLayer::ImGuiLayer(std::function<void()> build) : _build(std::move(build))
{
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr; // no imgui.ini beside the user's files: panels open where the code says
    io.LogFilename = nullptr;
    typedef osgGA::GUIEventAdapter K;
    const std::pair<ImGuiKey, int> keys[] = {{ImGuiKey_Tab, K::KEY_Tab},
                                             {ImGuiKey_LeftArrow, K::KEY_Left},
                                             {ImGuiKey_RightArrow, K::KEY_Right},
                                             {ImGuiKey_UpArrow, K::KEY_Up},
                                             {ImGuiKey_DownArrow, K::KEY_Down},
                                             {ImGuiKey_PageUp, K::KEY_Page_Up},
                                             {ImGuiKey_PageDown, K::KEY_Page_Down},
                                             {ImGuiKey_Home, K::KEY_Home},
                                             {ImGuiKey_End, K::KEY_End},
                                             {ImGuiKey_Delete, K::KEY_Delete},
                                             {ImGuiKey_Backspace, K::KEY_BackSpace},
                                             {ImGuiKey_Enter, K::KEY_Return},
                                             {ImGuiKey_Escape, K::KEY_Escape},
                                             {ImGuiKey_KeyPadEnter, K::KEY_KP_Enter},
                                             {ImGuiKey_A, 'a'},
                                             {ImGuiKey_C, 'c'},
                                             {ImGuiKey_V, 'v'},
                                             {ImGuiKey_X, 'x'},
                                             {ImGuiKey_Y, 'y'},
                                             {ImGuiKey_Z, 'z'}};
    for (const auto& k : keys)
        io.KeyMap[k.first] = keyIndex(k.second);
}

ImGuiLayer::~ImGuiLayer()
{
    // The GL objects go with the context (the viewer closes it first); only the CPU side here.
    ImGui::DestroyContext();
}

void ImGuiLayer::install(osg::Camera& camera)
{
    camera.setFinalDrawCallback(new Draw(this));
}

bool ImGuiLayer::handle(const osgGA::GUIEventAdapter& ea, osgGA::GUIActionAdapter&, osg::Object*,
                        osg::NodeVisitor*)
{
    if (!visible || !_initialised) return false;
    ImGuiIO& io = ImGui::GetIO();
    typedef osgGA::GUIEventAdapter E;
    const int w = ea.getWindowWidth(), h = ea.getWindowHeight();
    auto pointer = [&]
    {
        _mouseX = (ea.getXnormalized() + 1.0) * 0.5 * w;
        _mouseY = (1.0 - (ea.getYnormalized() + 1.0) * 0.5) * h;
    };
    auto button = [&](unsigned mask) {
        return mask == E::LEFT_MOUSE_BUTTON ? 0 : mask == E::RIGHT_MOUSE_BUTTON ? 1 : 2;
    };
    const unsigned mods = ea.getModKeyMask();
    io.KeyCtrl = (mods & E::MODKEY_CTRL) != 0;
    io.KeyShift = (mods & E::MODKEY_SHIFT) != 0;
    io.KeyAlt = (mods & E::MODKEY_ALT) != 0;
    switch (ea.getEventType())
    {
    case E::MOVE:
        pointer();
        return false;
    case E::PUSH:
    {
        pointer();
        const int b = button(ea.getButton());
        _down[b] = _pressedThisFrame[b] = true;
        _captured = io.WantCaptureMouse;
        return _captured;
    }
    case E::DRAG:
        pointer();
        return _captured;
    case E::RELEASE:
    {
        pointer();
        _down[button(ea.getButton())] = false;
        const bool captured = _captured;
        _captured = false;
        return captured;
    }
    case E::SCROLL:
        _wheel += ea.getScrollingMotion() == E::SCROLL_UP     ? 1.0f
                  : ea.getScrollingMotion() == E::SCROLL_DOWN ? -1.0f
                                                              : 0.0f;
        return io.WantCaptureMouse;
    case E::KEYDOWN:
    case E::KEYUP:
    {
        const bool down = ea.getEventType() == E::KEYDOWN;
        const int key = ea.getKey();
        const int i = keyIndex(key);
        if (i >= 0) io.KeysDown[i] = down;
        // A control key arrives as its control character (Ctrl+Z is 26): ImGui wants 'z'.
        if (io.KeyCtrl && key >= 1 && key <= 26) io.KeysDown[keyIndex('a' + key - 1)] = down;
        if (down && key >= 32 && key < 127 && !io.KeyCtrl) io.AddInputCharacter(unsigned(key));
        return io.WantCaptureKeyboard;
    }
    default:
        return false;
    }
}

void ImGuiLayer::draw(osg::RenderInfo& info)
{
    const osg::Viewport* vp = info.getCurrentCamera() ? info.getCurrentCamera()->getViewport() : nullptr;
    if (!vp) return;
    ++_frames;
    if (visible)
    {
        if (!_initialised)
        {
            ImGui_ImplOpenGL3_Init("#version 130");
            _initialised = true;
        }
        ImGuiIO& io = ImGui::GetIO();
        const double now = osg::Timer::instance()->time_s();
        io.DeltaTime = _lastTime < 0.0 ? 1.0f / 60.0f : float(std::max(now - _lastTime, 1e-4));
        _lastTime = now;
        io.DisplaySize = ImVec2(float(vp->width()), float(vp->height()));
        io.MousePos = ImVec2(float(_mouseX), float(_mouseY));
        for (int b = 0; b < 3; ++b)
        {
            io.MouseDown[b] = _down[b] || _pressedThisFrame[b];
            _pressedThisFrame[b] = false;
        }
        io.MouseWheel = _wheel;
        _wheel = 0.0f;
        ImGui_ImplOpenGL3_NewFrame();
        ImGui::NewFrame();
        _build();
        ImGui::Render();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    }
    if (afterDraw) afterDraw(info);
    if (!_screenshot.empty())
    {
        const std::string path = _screenshot;
        _screenshot.clear();
        osg::ref_ptr<osg::Image> image = new osg::Image;
        image->readPixels(int(vp->x()), int(vp->y()), int(vp->width()), int(vp->height()), GL_RGB,
                          GL_UNSIGNED_BYTE);
        try
        {
            osgLoA::ImageFile::write(path, *image);
            screenshotError.clear();
        }
        catch (const std::exception& e)
        {
            screenshotError = e.what();
        }
    }
}

} // namespace loa
