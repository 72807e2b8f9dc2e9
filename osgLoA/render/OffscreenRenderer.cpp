#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/render/ShaderLibrary>
#include <osgLoA/util/StateSetVisitor>

#include <osg/ComputeBoundsVisitor>
#include <osg/GLExtensions>
#include <osg/NodeVisitor>
#include <osg/Program>

#include <algorithm>
#include <chrono>
#include <numeric>
#include <set>
#include <stdexcept>

namespace osgLoA
{

double FrameTimes::median() const
{
    if (milliseconds.empty()) return 0.0;
    std::vector<double> s = milliseconds;
    std::sort(s.begin(), s.end());
    const size_t n = s.size();
    return n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
}
double FrameTimes::min() const
{
    return milliseconds.empty() ? 0.0 : *std::min_element(milliseconds.begin(), milliseconds.end());
}
double FrameTimes::max() const
{
    return milliseconds.empty() ? 0.0 : *std::max_element(milliseconds.begin(), milliseconds.end());
}
double FrameTimes::mean() const
{
    return milliseconds.empty() ? 0.0
                                : std::accumulate(milliseconds.begin(), milliseconds.end(), 0.0) /
                                      static_cast<double>(milliseconds.size());
}

namespace
{
/** Ends each frame with glFinish and, on request, reads the colour texture back. */
class FinishAndCapture : public osg::Camera::DrawCallback
{
public:
    explicit FinishAndCapture(osg::Texture2D* texture) : _texture(texture) {}

    void operator()(osg::RenderInfo& renderInfo) const override
    {
        glFinish();
        if (!_capture) return;
        osg::State& state = *renderInfo.getState();
        state.setActiveTextureUnit(0);
        state.applyTextureAttribute(0, _texture.get());
        const int w = _texture->getTextureWidth(), h = _texture->getTextureHeight();
        _image = new osg::Image;
        _image->allocateImage(w, h, 1, GL_RGBA, GL_UNSIGNED_BYTE);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, _image->data());
        _capture = false;
    }

    mutable bool _capture = false;
    mutable osg::ref_ptr<osg::Image> _image;
    osg::ref_ptr<osg::Texture2D> _texture;
};

} // namespace

OffscreenRenderer::OffscreenRenderer(const Settings& settings) : _settings(settings)
{
    if (settings.width < 1 || settings.height < 1 || settings.width > 16384 || settings.height > 16384)
        throw std::invalid_argument("image size " + std::to_string(settings.width) + "x" +
                                    std::to_string(settings.height) + " is outside 1x1 .. 16384x16384");
    if (settings.samples < 0) throw std::invalid_argument("sample count must be 0 or positive");

    _context = new HeadlessContext(); // throws HeadlessContextError
    if (!_context->realize()) throw HeadlessContextError("the EGL context could not be made current.");
    const GLCapabilities& caps = _context->getCapabilities();
    if (settings.samples > caps.maxSamples)
        throw std::invalid_argument("--samples " + std::to_string(settings.samples) +
                                    " exceeds GL_MAX_SAMPLES = " + std::to_string(caps.maxSamples) + " of " +
                                    caps.renderer);
    if (std::max(settings.width, settings.height) > caps.maxTextureSize)
        throw std::invalid_argument("image size exceeds GL_MAX_TEXTURE_SIZE = " +
                                    std::to_string(caps.maxTextureSize));

    _viewer = new osgViewer::Viewer;
    _viewer->setThreadingModel(osgViewer::ViewerBase::SingleThreaded);
    _viewer->setKeyEventSetsDone(0);
    _viewer->setQuitEventSetsDone(false);
    _viewer->setReleaseContextAtEndOfFrameHint(false);

    _colorTexture = new osg::Texture2D;
    _colorTexture->setTextureSize(settings.width, settings.height);
    _colorTexture->setInternalFormat(GL_RGBA8);
    _colorTexture->setSourceFormat(GL_RGBA);
    _colorTexture->setSourceType(GL_UNSIGNED_BYTE);
    _colorTexture->setFilter(osg::Texture::MIN_FILTER, osg::Texture::NEAREST);
    _colorTexture->setFilter(osg::Texture::MAG_FILTER, osg::Texture::NEAREST);
    _colorTexture->setResizeNonPowerOfTwoHint(false);

    osg::Camera* camera = _viewer->getCamera();
    camera->setGraphicsContext(_context.get());
    camera->setViewport(0, 0, settings.width, settings.height);
    camera->setRenderTargetImplementation(osg::Camera::FRAME_BUFFER_OBJECT);
    camera->attach(osg::Camera::COLOR_BUFFER, _colorTexture.get(), 0, 0, false,
                   static_cast<unsigned>(settings.samples), 0u);
    // OSG gives every renderbuffer of a multisampled FBO the colour attachment's sample count.
    camera->attach(osg::Camera::PACKED_DEPTH_STENCIL_BUFFER, static_cast<GLenum>(GL_DEPTH24_STENCIL8_EXT));
    camera->setClearColor(settings.clearColor);
    camera->setClearMask(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    _finishCallback = new FinishAndCapture(_colorTexture.get());
    camera->setFinalDrawCallback(_finishCallback.get());
    _context->getState()->setUseModelViewAndProjectionUniforms(true);

    setUpSun(*_viewer);
    setPerspective(45.0);
}

void OffscreenRenderer::setUpSun(osg::View& view)
{
    // A sun from the south-west, fixed in the world: the same shading from every camera.
    view.setLightingMode(osg::View::SKY_LIGHT);
    osg::Light* sun = view.getLight();
    sun->setPosition(osg::Vec4(-0.45f, -0.55f, 0.70f, 0.0f));
    sun->setAmbient(osg::Vec4(0.42f, 0.42f, 0.45f, 1.0f));
    sun->setDiffuse(osg::Vec4(0.70f, 0.68f, 0.62f, 1.0f));
    sun->setSpecular(osg::Vec4(0.0f, 0.0f, 0.0f, 1.0f));
}

OffscreenRenderer::~OffscreenRenderer()
{
    if (_viewer.valid())
    {
        _viewer->setDone(true);
        _viewer->stopThreading();
    }
}

void OffscreenRenderer::setSceneData(osg::Node* node)
{
    _viewer->setSceneData(node);
    _programsChecked = false;
}

void OffscreenRenderer::setPerspective(double fovyDegrees)
{
    _fovy = fovyDegrees;
    _viewer->getCamera()->setProjectionMatrixAsPerspective(
        fovyDegrees, static_cast<double>(_settings.width) / _settings.height, 1.0, 10000.0);
}

void OffscreenRenderer::setViewMatrixAsLookAt(const osg::Vec3d& eye, const osg::Vec3d& center,
                                              const osg::Vec3d& up)
{
    _viewer->getCamera()->setViewMatrixAsLookAt(eye, center, up);
}

void OffscreenRenderer::framingPose(const osg::BoundingSphere& bs, double fovyDegrees, double aspect,
                                    osg::Vec3d& eye, osg::Vec3d& center, osg::Vec3d& up)
{
    const double fovyRad = osg::DegreesToRadians(fovyDegrees);
    const double halfFov = std::min(fovyRad, 2.0 * std::atan(std::tan(fovyRad / 2.0) * aspect)) / 2.0;
    const double distance = bs.radius() / std::sin(halfFov);
    osg::Vec3d dir(-0.5, -0.7, 0.55);
    dir.normalize();
    center = bs.center();
    eye = center + dir * distance;
    up.set(0, 0, 1);
}

void OffscreenRenderer::frameScene()
{
    osg::Node* scene = _viewer->getSceneData();
    if (!scene) return;
    const osg::BoundingSphere bs = scene->getBound();
    if (!bs.valid()) return;
    osg::Vec3d eye, center, up;
    framingPose(bs, _fovy, static_cast<double>(_settings.width) / _settings.height, eye, center, up);
    _viewer->getCamera()->setViewMatrixAsLookAt(eye, center, up);
}

void OffscreenRenderer::realizeOnce()
{
    if (_realized) return;
    _viewer->realize();
    _realized = true;
}

void OffscreenRenderer::checkScenePrograms()
{
    if (_programsChecked) return;
    const std::set<osg::Program*> programs = _viewer->getSceneData()
                                                 ? StateSetVisitor::programs(*_viewer->getSceneData())
                                                 : std::set<osg::Program*>();
    std::vector<ShaderDiagnostic> all;
    if (!programs.empty())
    {
        // Left current afterwards: osgViewer assumes the context it made current in the last
        // frame still is, so releasing it here would make the next frame render without one.
        _context->makeCurrent();
        for (osg::Program* p : programs)
        {
            auto d = ShaderLibrary::check(*p, *_context->getState());
            all.insert(all.end(), d.begin(), d.end());
        }
    }
    if (!all.empty()) throw ShaderError(all);
    _programsChecked = true;
}

double OffscreenRenderer::frameMilliseconds()
{
    const auto t0 = std::chrono::steady_clock::now();
    _viewer->frame(); // the final draw callback ends with glFinish
    const auto t1 = std::chrono::steady_clock::now();
    return std::chrono::duration<double, std::milli>(t1 - t0).count();
}

osg::ref_ptr<osg::Image> OffscreenRenderer::renderImage()
{
    realizeOnce();
    checkScenePrograms();
    auto* cb = static_cast<FinishAndCapture*>(_finishCallback.get());
    cb->_capture = true;
    cb->_image = nullptr;
    _viewer->frame();
    if (!cb->_image.valid()) throw std::runtime_error("the frame was not drawn: no image could be read back");
    return cb->_image;
}

double OffscreenRenderer::renderTimedFrame()
{
    realizeOnce();
    checkScenePrograms();
    return frameMilliseconds();
}

FrameTimes OffscreenRenderer::timeFrames(unsigned frames)
{
    realizeOnce();
    checkScenePrograms();
    FrameTimes times;
    frameMilliseconds(); // warm-up: shader JIT, texture upload, display lists
    times.milliseconds.reserve(frames);
    for (unsigned i = 0; i < frames; ++i)
        times.milliseconds.push_back(frameMilliseconds());
    return times;
}

} // namespace osgLoA
