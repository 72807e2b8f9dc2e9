#include <osgLoA/render/HeadlessContext>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <osg/GLExtensions>
#include <osg/State>

#include <cstring>
#include <sstream>
#include <vector>

namespace osgLoA
{
namespace
{
bool hasToken(const char* list, const char* token)
{
    if (!list) return false;
    std::istringstream in(list);
    std::string t;
    while (in >> t)
        if (t == token) return true;
    return false;
}

const char* eglErrorName(EGLint e)
{
    switch (e)
    {
    case EGL_SUCCESS:
        return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
        return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
        return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
        return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
        return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
        return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
        return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
        return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
        return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
        return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE:
        return "EGL_BAD_SURFACE";
    default:
        return "an unknown EGL error";
    }
}

// Tries to initialize a display; returns EGL_NO_DISPLAY (terminated) on failure.
EGLDisplay tryInitialize(EGLDisplay dpy)
{
    if (dpy == EGL_NO_DISPLAY) return EGL_NO_DISPLAY;
    EGLint major = 0, minor = 0;
    if (!eglInitialize(dpy, &major, &minor)) return EGL_NO_DISPLAY;
    if (!eglBindAPI(EGL_OPENGL_API))
    {
        eglTerminate(dpy);
        return EGL_NO_DISPLAY;
    }
    return dpy;
}
} // namespace

HeadlessContext::HeadlessContext(osg::GraphicsContext::Traits* traits)
{
    if (!traits)
    {
        traits = new osg::GraphicsContext::Traits;
        traits->width = 1;
        traits->height = 1;
        traits->windowDecoration = false;
        traits->doubleBuffer = false;
        traits->pbuffer = true;
    }
    _traits = traits;
    createDisplayAndContext(); // throws HeadlessContextError

    setState(new osg::State);
    getState()->setGraphicsContext(this);
    getState()->setContextID(osg::GraphicsContext::createNewContextID());
}

HeadlessContext::~HeadlessContext()
{
    close(true);
    destroy();
}

void HeadlessContext::createDisplayAndContext()
{
    const char* clientExts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    auto getPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    EGLDisplay dpy = EGL_NO_DISPLAY;
    std::string tried;

    // 1. Mesa's surfaceless platform: no window system, no device node needed.
    if (getPlatformDisplay && hasToken(clientExts, "EGL_MESA_platform_surfaceless"))
    {
        dpy = tryInitialize(getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr));
        if (dpy != EGL_NO_DISPLAY) _platform = "surfaceless";
        tried += "surfaceless ";
    }
    // 2. The EGL device platform: each enumerated device in turn (a GPU vendor's EGL).
    if (dpy == EGL_NO_DISPLAY && getPlatformDisplay && hasToken(clientExts, "EGL_EXT_platform_device"))
    {
        auto queryDevices =
            reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
        if (queryDevices)
        {
            EGLDeviceEXT devices[16];
            EGLint n = 0;
            if (queryDevices(16, devices, &n))
                for (EGLint i = 0; i < n && dpy == EGL_NO_DISPLAY; ++i)
                    dpy = tryInitialize(getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr));
            if (dpy != EGL_NO_DISPLAY) _platform = "device";
        }
        tried += "device ";
    }
    // 3. Whatever the default display is (honours EGL_PLATFORM).
    if (dpy == EGL_NO_DISPLAY)
    {
        dpy = tryInitialize(eglGetDisplay(EGL_DEFAULT_DISPLAY));
        if (dpy != EGL_NO_DISPLAY) _platform = "default";
        tried += "default";
    }
    if (dpy == EGL_NO_DISPLAY)
        throw HeadlessContextError("No usable EGL display for headless OpenGL (tried platforms: " + tried +
                                   "; last error " + eglErrorName(eglGetError()) +
                                   "): install libegl1 and libegl-mesa0, or a GPU driver with EGL.");
    _display = dpy;

    const char* dpyExts = eglQueryString(dpy, EGL_EXTENSIONS);
    _eglDescription = std::string(eglQueryString(dpy, EGL_VERSION) ? eglQueryString(dpy, EGL_VERSION) : "?") +
                      " " + (eglQueryString(dpy, EGL_VENDOR) ? eglQueryString(dpy, EGL_VENDOR) : "?");
    const bool surfaceless = hasToken(dpyExts, "EGL_KHR_surfaceless_context");

    const EGLint configAttribs[] = {EGL_SURFACE_TYPE,
                                    surfaceless ? 0 : EGL_PBUFFER_BIT,
                                    EGL_RENDERABLE_TYPE,
                                    EGL_OPENGL_BIT,
                                    EGL_RED_SIZE,
                                    8,
                                    EGL_GREEN_SIZE,
                                    8,
                                    EGL_BLUE_SIZE,
                                    8,
                                    EGL_ALPHA_SIZE,
                                    8,
                                    EGL_DEPTH_SIZE,
                                    24,
                                    EGL_STENCIL_SIZE,
                                    8,
                                    EGL_NONE};
    EGLConfig config = nullptr;
    EGLint numConfigs = 0;
    if (!eglChooseConfig(dpy, configAttribs, &config, 1, &numConfigs) || numConfigs < 1)
    {
        destroy();
        throw HeadlessContextError(std::string("EGL display (") + _platform +
                                   ") offers no RGBA8/depth24/stencil8 config for desktop OpenGL.");
    }
    _config = config;

    // Desktop GL, compatibility profile (OSG 3.6 uses fixed-function state for its defaults).
    const bool createContextExt = hasToken(dpyExts, "EGL_KHR_create_context");
    std::vector<EGLint> ctxAttribs;
    if (createContextExt)
    {
        ctxAttribs = {EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT};
        if (_traits.valid() && _traits->glContextVersion != "1.0" && !_traits->glContextVersion.empty())
        {
            unsigned major = 1, minor = 0;
            _traits->getContextVersion(major, minor);
            if (major >= 3)
                ctxAttribs.insert(ctxAttribs.end(), {EGL_CONTEXT_MAJOR_VERSION, static_cast<EGLint>(major),
                                                     EGL_CONTEXT_MINOR_VERSION, static_cast<EGLint>(minor)});
        }
    }
    ctxAttribs.push_back(EGL_NONE);
    EGLContext share = EGL_NO_CONTEXT;
    if (_traits.valid() && _traits->sharedContext.valid())
        if (auto* other = dynamic_cast<HeadlessContext*>(_traits->sharedContext.get()))
            share = other->_context;
    EGLContext ctx = eglCreateContext(dpy, config, share, ctxAttribs.data());
    if (ctx == EGL_NO_CONTEXT)
    {
        const EGLint err = eglGetError();
        destroy();
        throw HeadlessContextError(
            std::string("EGL could not create a desktop OpenGL compatibility context (") + eglErrorName(err) +
            ") on the " + _platform + " platform.");
    }
    _context = ctx;

    if (!surfaceless)
    {
        const EGLint pbAttribs[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
        _surface = eglCreatePbufferSurface(dpy, config, pbAttribs);
        if (_surface == EGL_NO_SURFACE)
        {
            destroy();
            throw HeadlessContextError(
                "EGL has neither EGL_KHR_surfaceless_context nor a usable pbuffer surface.");
        }
    }
}

bool HeadlessContext::realizeImplementation()
{
    if (_realized) return true;
    if (!makeCurrentImplementation()) return false;
    _realized = true;

    _capabilities.query();
    const unsigned contextID = getState()->getContextID();
    osg::GLExtensions* ext = osg::GLExtensions::Get(contextID, true);
    // The OSG 3.6.5 multisample-FBO fix (ARCHITECTURE.md §4): trust the extension string only.
    if (ext && ext->glRenderbufferStorageMultisampleCoverageNV &&
        !_capabilities.hasExtension("GL_NV_framebuffer_multisample_coverage"))
    {
        ext->glRenderbufferStorageMultisampleCoverageNV = nullptr;
        _coverageFixApplied = true;
    }
    releaseContextImplementation();
    return true;
}

void HeadlessContext::closeImplementation()
{
    _realized = false;
}

bool HeadlessContext::makeCurrentImplementation()
{
    if (!_display || !_context) return false;
    return eglMakeCurrent(_display, _surface ? _surface : EGL_NO_SURFACE,
                          _surface ? _surface : EGL_NO_SURFACE, _context) == EGL_TRUE;
}

bool HeadlessContext::makeContextCurrentImplementation(osg::GraphicsContext*)
{
    return makeCurrentImplementation();
}

bool HeadlessContext::releaseContextImplementation()
{
    if (!_display) return false;
    return eglMakeCurrent(_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT) == EGL_TRUE;
}

void HeadlessContext::swapBuffersImplementation()
{
    // Nothing to present: every camera renders into an FBO.
}

void HeadlessContext::destroy()
{
    if (!_display) return;
    eglMakeCurrent(_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (_surface) eglDestroySurface(_display, _surface);
    if (_context) eglDestroyContext(_display, _context);
    // The display is shared per platform by EGL (eglTerminate would also kill other contexts
    // of this process on the same display), so it is left initialized.
    _surface = nullptr;
    _context = nullptr;
    _display = nullptr;
}

} // namespace osgLoA
