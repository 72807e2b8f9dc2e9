/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/GpuFilterEngine>
#include <osgLoA/filtering/PostProcessFiltering>

#include "../compositing/RenderTarget.h"
#include <osgLoA/render/ShaderLibrary>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Notify>
#include <osg/buffered_value>
#include <osgUtil/CullVisitor>

#include <chrono>
#include <mutex>
#include <stdexcept>

namespace osgLoA
{

namespace
{
using CopyImageSubData = void(GL_APIENTRY*)(GLuint, GLenum, GLint, GLint, GLint, GLint, GLuint, GLenum, GLint,
                                            GLint, GLint, GLint, GLsizei, GLsizei, GLsizei);

/** The scene camera's only child: traversing it traverses the PostProcessFiltering's children,
 *  so that they keep one parent (paths, bounds and intersections stay those of the group). */
class ChildrenProxy : public osg::Node
{
public:
    explicit ChildrenProxy(PostProcessFiltering* owner) : _owner(owner) { setCullingActive(false); }
    void traverse(osg::NodeVisitor& nv) override
    {
        if (_owner) _owner->osg::Group::traverse(nv);
    }
    PostProcessFiltering* _owner; // the owner holds this node; never outlives it
};

/** Runs the filter stage once the scene camera has drawn (the context is current). */
class FilterStageCallback : public osg::Camera::DrawCallback
{
public:
    explicit FilterStageCallback(PostProcessFiltering* owner) : _owner(owner) {}
    void operator()(osg::RenderInfo& renderInfo) const override
    {
        if (_owner) _owner->filterFrame(renderInfo);
    }
    PostProcessFiltering* _owner;
};

} // namespace

/** Per-context GL objects of the filter stage, and what the last stage measured. */
struct PostProcessFiltering::Internals : public osg::Referenced
{
    struct PerContext
    {
        osg::ref_ptr<GpuFilterEngine> engine;
        bool engineFailed = false;
        unsigned frameAtlas = 0, filteredAtlas = 0;
        GLuint frameName = 0, filteredName = 0;
        int width = 0, height = 0;
    };
    mutable osg::buffered_object<PerContext> contexts;
    mutable std::mutex mutex; // guards the numbers below (written by draw, read by the application)
    double lastMilliseconds = -1.0;
    unsigned filteredFrames = 0;
    std::string lastError;

    void fail(const std::string& what)
    {
        std::lock_guard<std::mutex> lock(mutex);
        if (lastError != what) OSG_WARN << "osgLoA::PostProcessFiltering: " << what << std::endl;
        lastError = what;
    }
};

PostProcessFiltering::PostProcessFiltering()
{
    build();
}

PostProcessFiltering::PostProcessFiltering(const PostProcessFiltering& other, const osg::CopyOp& copyop)
    : osg::Group(other, copyop), _filter(dynamic_cast<ImageFilter*>(copyop(other._filter.get()))),
      _enabled(other._enabled), _measureFilterTime(other._measureFilterTime)
{
    build();
}

PostProcessFiltering::~PostProcessFiltering()
{
    // The proxy and the callback point back at this node; cut them in case someone else holds
    // the cameras.
    if (_sceneCamera.valid())
    {
        _sceneCamera->setPostDrawCallback(nullptr);
        _sceneCamera->removeChildren(0, _sceneCamera->getNumChildren());
    }
}

void PostProcessFiltering::build()
{
    _internals = new Internals;
    _frameTexture = detail::createTargetTexture(GL_RGBA32F_ARB, GL_RGBA, GL_FLOAT);
    _frameTexture->setName("loa_postprocess_frame");
    _filteredTexture = detail::createTargetTexture(GL_RGBA32F_ARB, GL_RGBA, GL_FLOAT);
    _filteredTexture->setName("loa_postprocess_filtered");

    _sceneCamera = new osg::Camera;
    _sceneCamera->setName("loa_postprocess_scene");
    _sceneCamera->setRenderOrder(osg::Camera::PRE_RENDER);
    _sceneCamera->setReferenceFrame(osg::Transform::RELATIVE_RF); // the view and lights above
    _sceneCamera->setRenderTargetImplementation(osg::Camera::FRAME_BUFFER_OBJECT);
    _sceneCamera->setClearMask(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    _sceneCamera->attach(osg::Camera::COLOR_BUFFER, _frameTexture.get());
    _sceneCamera->attach(osg::Camera::DEPTH_BUFFER, GL_DEPTH_COMPONENT24);
    _sceneCamera->setCullingActive(false);
    _sceneCamera->addChild(new ChildrenProxy(this));
    _sceneCamera->setPostDrawCallback(new FilterStageCallback(this));

    // The display pass: a unit quad under an orthographic camera, nested in the camera above.
    osg::ref_ptr<osg::Geometry> quad = osg::createTexturedQuadGeometry(
        osg::Vec3(0.0f, 0.0f, 0.0f), osg::Vec3(1.0f, 0.0f, 0.0f), osg::Vec3(0.0f, 1.0f, 0.0f));
    quad->setName("loa_postprocess_quad");
    quad->setUseDisplayList(false);
    quad->setCullingActive(false);
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(quad.get());
    geode->setCullingActive(false);
    osg::StateSet* ss = geode->getOrCreateStateSet();
    ss->setDataVariance(osg::Object::DYNAMIC); // its texture changes with the viewport's size
    _displayState = ss;
    ss->setAttributeAndModes(
        ShaderLibrary::createProgram("loa_postprocess",
                                     {"loa_postprocess.vert.glsl", "loa_postprocess.frag.glsl"})
            .get(),
        osg::StateAttribute::ON | osg::StateAttribute::OVERRIDE | osg::StateAttribute::PROTECTED);
    ss->setTextureAttributeAndModes(0, _filteredTexture.get(),
                                    osg::StateAttribute::ON | osg::StateAttribute::OVERRIDE |
                                        osg::StateAttribute::PROTECTED);
    ss->addUniform(new osg::Uniform("loa_postprocess_frame", 0), osg::StateAttribute::OVERRIDE);
    const osg::StateAttribute::GLModeValue off =
        osg::StateAttribute::OFF | osg::StateAttribute::OVERRIDE | osg::StateAttribute::PROTECTED;
    ss->setMode(GL_DEPTH_TEST, off);
    ss->setMode(GL_LIGHTING, off);
    ss->setMode(GL_BLEND, off);
    ss->setMode(GL_CULL_FACE, off);

    _displayCamera = new osg::Camera;
    _displayCamera->setName("loa_postprocess_display");
    _displayCamera->setRenderOrder(osg::Camera::NESTED_RENDER);
    _displayCamera->setReferenceFrame(osg::Transform::ABSOLUTE_RF);
    _displayCamera->setProjectionMatrixAsOrtho2D(0.0, 1.0, 0.0, 1.0);
    _displayCamera->setViewMatrix(osg::Matrix::identity());
    _displayCamera->setClearMask(0);
    _displayCamera->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    _displayCamera->setCullingActive(false);
    _displayCamera->addChild(geode.get());
}

void PostProcessFiltering::setFilter(ImageFilter* filter)
{
    if (filter && !filter->hasGpuImplementation())
        throw std::invalid_argument("PostProcessFiltering: filter '" + filter->filterName() +
                                    "' has no GPU passes; post-process filtering runs the filter on "
                                    "every frame on the GPU (filter such a texture ahead of time with "
                                    "MipmapFilter instead)");
    _filter = filter;
}

double PostProcessFiltering::getLastFilterMilliseconds() const
{
    std::lock_guard<std::mutex> lock(_internals->mutex);
    return _internals->lastMilliseconds;
}

unsigned PostProcessFiltering::getFilteredFrames() const
{
    std::lock_guard<std::mutex> lock(_internals->mutex);
    return _internals->filteredFrames;
}

std::string PostProcessFiltering::getLastError() const
{
    std::lock_guard<std::mutex> lock(_internals->mutex);
    return _internals->lastError;
}

void PostProcessFiltering::resize(int width, int height)
{
    if (width == _width && height == _height) return;
    _width = width;
    _height = height;
    // New textures, and the camera's render stages dropped (setRenderingCache): OSG 3.6 sets an
    // FBO up once per render stage, so new stages attach the new textures in every context.
    _frameTexture = detail::createTargetTexture(GL_RGBA32F_ARB, GL_RGBA, GL_FLOAT);
    _frameTexture->setName("loa_postprocess_frame");
    _filteredTexture = detail::createTargetTexture(GL_RGBA32F_ARB, GL_RGBA, GL_FLOAT);
    _filteredTexture->setName("loa_postprocess_filtered");
    for (osg::Texture2D* t : {_frameTexture.get(), _filteredTexture.get()})
        t->setTextureSize(width, height);
    _sceneCamera->detach(osg::Camera::COLOR_BUFFER);
    _sceneCamera->attach(osg::Camera::COLOR_BUFFER, _frameTexture.get());
    _sceneCamera->setViewport(0, 0, width, height);
    _sceneCamera->setRenderingCache(nullptr);
    _displayState->setTextureAttributeAndModes(0, _filteredTexture.get(),
                                               osg::StateAttribute::ON | osg::StateAttribute::OVERRIDE |
                                                   osg::StateAttribute::PROTECTED);
}

void PostProcessFiltering::traverse(osg::NodeVisitor& nv)
{
    osgUtil::CullVisitor* cv = nv.asCullVisitor();
    if (!cv || !_filter.valid() || !_enabled)
    {
        osg::Group::traverse(nv);
        return;
    }
    const osg::Viewport* vp = cv->getViewport();
    if (!vp || vp->width() < 1.0 || vp->height() < 1.0) return;
    resize(int(vp->width()), int(vp->height()));
    if (osg::Camera* above = cv->getCurrentCamera())
    {
        _sceneCamera->setClearColor(above->getClearColor());
        _sceneCamera->setComputeNearFarMode(above->getComputeNearFarMode());
        _sceneCamera->setNearFarRatio(above->getNearFarRatio());
    }
    _sceneCamera->accept(nv);
    _displayCamera->accept(nv);
}

void PostProcessFiltering::filterFrame(osg::RenderInfo& renderInfo) const
{
    osg::State& state = *renderInfo.getState();
    const unsigned id = state.getContextID();
    Internals::PerContext& c = _internals->contexts[id];
    osg::ref_ptr<ImageFilter> filter = _filter;
    if (!filter.valid() || c.engineFailed) return;

    // Both textures must have GL objects: the frame texture is the FBO's attachment; the
    // filtered one is applied once (through osg::State, which keeps its bookkeeping right).
    osg::Texture::TextureObject* frameObject = _frameTexture->getTextureObject(id);
    if (!_filteredTexture->getTextureObject(id))
    {
        state.applyTextureAttribute(0, _filteredTexture.get());
        state.haveAppliedTextureAttribute(0, _filteredTexture.get());
    }
    osg::Texture::TextureObject* filteredObject = _filteredTexture->getTextureObject(id);
    if (!frameObject || !filteredObject)
    {
        _internals->fail("the frame textures have no GL objects");
        return;
    }
    try
    {
        if (!c.engine.valid()) c.engine = new GpuFilterEngine(state);
        GpuFilterEngine& e = *c.engine;
        if (c.frameName != frameObject->id() || c.filteredName != filteredObject->id() || c.width != _width ||
            c.height != _height)
        {
            if (c.frameAtlas) e.destroyAtlas(c.frameAtlas); // and its scratch atlases
            if (c.filteredAtlas) e.destroyAtlas(c.filteredAtlas);
            c.frameAtlas = c.filteredAtlas = 0;
            c.frameName = frameObject->id();
            c.filteredName = filteredObject->id();
            c.width = _width;
            c.height = _height;
            c.frameAtlas = e.adoptAtlas(c.frameName, _width, _height);
            c.filteredAtlas = e.adoptAtlas(c.filteredName, _width, _height);
        }
        GpuFilterEngine::Region region;
        region.width = _width;
        region.height = _height;
        region.border = ImageBorder(WrapMode::Clamp, WrapMode::Clamp);
        const bool measure = _measureFilterTime;
        if (measure) glFinish();
        const auto t0 = std::chrono::steady_clock::now();
        e.run(*filter, c.frameAtlas, c.filteredAtlas, {region});
        if (measure) glFinish();
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        std::lock_guard<std::mutex> lock(_internals->mutex);
        if (measure) _internals->lastMilliseconds = ms;
        ++_internals->filteredFrames;
        _internals->lastError.clear();
    }
    catch (const std::exception& ex)
    {
        if (!c.engine.valid()) c.engineFailed = true; // no compute shaders: do not retry every frame
        _internals->fail(ex.what());
        // Show the unfiltered frame rather than stale or undefined texels.
        static const CopyImageSubData copy =
            reinterpret_cast<CopyImageSubData>(osg::getGLExtensionFuncPtr("glCopyImageSubData"));
        if (copy && osg::isGLExtensionOrVersionSupported(id, "GL_ARB_copy_image", 4.3f))
            copy(frameObject->id(), GL_TEXTURE_2D, 0, 0, 0, 0, filteredObject->id(), GL_TEXTURE_2D, 0, 0, 0,
                 0, _width, _height, 1);
    }
}

void PostProcessFiltering::releaseGLObjects(osg::State* state) const
{
    osg::Group::releaseGLObjects(state);
    _sceneCamera->releaseGLObjects(state);
    _displayCamera->releaseGLObjects(state);
    _frameTexture->releaseGLObjects(state);
    _filteredTexture->releaseGLObjects(state);
    // The engines' programs, buffers and scratch atlases: freed here only when the context is
    // the current one (GL calls); otherwise dropped with the context.
    for (unsigned i = 0; i < _internals->contexts.size(); ++i)
    {
        Internals::PerContext& c = _internals->contexts[i];
        if (state && state->getContextID() == i && c.engine.valid()) c.engine->releaseGLObjects();
        if (!state || state->getContextID() == i) c = Internals::PerContext();
    }
}

void PostProcessFiltering::resizeGLObjectBuffers(unsigned int maxSize)
{
    osg::Group::resizeGLObjectBuffers(maxSize);
    _sceneCamera->resizeGLObjectBuffers(maxSize);
    _displayCamera->resizeGLObjectBuffers(maxSize);
    _internals->contexts.resize(maxSize);
}

} // namespace osgLoA
