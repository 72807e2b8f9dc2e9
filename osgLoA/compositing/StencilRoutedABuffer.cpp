// StencilRoutedABuffer: stencil routing (Myers & Bavoil 2007) into 2D multisample array textures,
// one layer per routing pass, with adaptive passes driven by an occlusion query (docs/abuffer.md).
#include <osgLoA/compositing/StencilRoutedABuffer>
#include <osgLoA/render/ShaderLibrary>

#include <osg/BlendFunc>
#include <osg/ColorMask>
#include <osg/ContextData>
#include <osg/Depth>
#include <osg/GL>
#include <osg/GLExtensions>
#include <osg/GLObjects>
#include <osg/Geometry>
#include <osg/Notify>
#include <osg/Stencil>
#include <osg/Viewport>
#include <osgUtil/RenderBin>
#include <osgUtil/RenderStage>
#include <osgUtil/StateGraph>

#include <algorithm>
#include <atomic>
#include <map>
#include <stdexcept>

#ifndef GL_TEXTURE_2D_MULTISAMPLE_ARRAY
#define GL_TEXTURE_2D_MULTISAMPLE_ARRAY 0x9102
#endif
#ifndef GL_MULTISAMPLE
#define GL_MULTISAMPLE 0x809D
#endif
#ifndef GL_SAMPLE_MASK
#define GL_SAMPLE_MASK 0x8E51
#endif
#ifndef GL_SAMPLE_ALPHA_TO_COVERAGE
#define GL_SAMPLE_ALPHA_TO_COVERAGE 0x809E
#endif
#ifndef GL_SAMPLES_PASSED
#define GL_SAMPLES_PASSED 0x8914
#endif
#ifndef GL_QUERY_RESULT
#define GL_QUERY_RESULT 0x8866
#endif
#ifndef GL_TEXTURE_SAMPLES
#define GL_TEXTURE_SAMPLES 0x9106
#endif
#ifndef GL_DEPTH_STENCIL_TEXTURE_MODE
#define GL_DEPTH_STENCIL_TEXTURE_MODE 0x90EA
#endif
#ifndef GL_DEPTH24_STENCIL8
#define GL_DEPTH24_STENCIL8 0x88F0
#endif
#ifndef GL_DEPTH_STENCIL_ATTACHMENT
#define GL_DEPTH_STENCIL_ATTACHMENT 0x821A
#endif
#ifndef GL_FRAMEBUFFER
#define GL_FRAMEBUFFER 0x8D40
#endif
#ifndef GL_FRAMEBUFFER_COMPLETE
#define GL_FRAMEBUFFER_COMPLETE 0x8CD5
#endif
#ifndef GL_COLOR_ATTACHMENT0
#define GL_COLOR_ATTACHMENT0 0x8CE0
#endif

namespace osgLoA
{

namespace
{

// GL 4.5 entry points (direct state access keeps OSG's texture and framebuffer bindings intact).
struct GLFunctions
{
    void(GL_APIENTRY* createTextures)(GLenum, GLsizei, GLuint*) = nullptr;
    void(GL_APIENTRY* textureStorage3DMultisample)(GLuint, GLsizei, GLenum, GLsizei, GLsizei, GLsizei,
                                                   GLboolean) = nullptr;
    void(GL_APIENTRY* textureParameteri)(GLuint, GLenum, GLint) = nullptr;
    void(GL_APIENTRY* getTextureLevelParameteriv)(GLuint, GLint, GLenum, GLint*) = nullptr;
    void(GL_APIENTRY* createFramebuffers)(GLsizei, GLuint*) = nullptr;
    void(GL_APIENTRY* namedFramebufferTextureLayer)(GLuint, GLenum, GLuint, GLint, GLint) = nullptr;
    void(GL_APIENTRY* namedFramebufferDrawBuffer)(GLuint, GLenum) = nullptr;
    GLenum(GL_APIENTRY* checkNamedFramebufferStatus)(GLuint, GLenum) = nullptr;
    void(GL_APIENTRY* bindFramebuffer)(GLenum, GLuint) = nullptr;
    void(GL_APIENTRY* deleteFramebuffers)(GLsizei, const GLuint*) = nullptr;
    void(GL_APIENTRY* createQueries)(GLenum, GLsizei, GLuint*) = nullptr;
    void(GL_APIENTRY* deleteQueries)(GLsizei, const GLuint*) = nullptr;
    void(GL_APIENTRY* beginQuery)(GLenum, GLuint) = nullptr;
    void(GL_APIENTRY* endQuery)(GLenum) = nullptr;
    void(GL_APIENTRY* getQueryObjectuiv)(GLuint, GLenum, GLuint*) = nullptr;
    void(GL_APIENTRY* sampleMaski)(GLuint, GLbitfield) = nullptr;

    template <typename F> static bool load(F& f, const char* name)
    {
        f = reinterpret_cast<F>(osg::getGLExtensionFuncPtr(name));
        return f != nullptr;
    }

    /** Loads every entry point; false when one is missing. Call with the context current. */
    bool loadAll()
    {
        bool ok = true;
        ok &= load(createTextures, "glCreateTextures");
        ok &= load(textureStorage3DMultisample, "glTextureStorage3DMultisample");
        ok &= load(textureParameteri, "glTextureParameteri");
        ok &= load(getTextureLevelParameteriv, "glGetTextureLevelParameteriv");
        ok &= load(createFramebuffers, "glCreateFramebuffers");
        ok &= load(namedFramebufferTextureLayer, "glNamedFramebufferTextureLayer");
        ok &= load(namedFramebufferDrawBuffer, "glNamedFramebufferDrawBuffer");
        ok &= load(checkNamedFramebufferStatus, "glCheckNamedFramebufferStatus");
        ok &= load(bindFramebuffer, "glBindFramebuffer");
        ok &= load(deleteFramebuffers, "glDeleteFramebuffers");
        ok &= load(createQueries, "glCreateQueries");
        ok &= load(deleteQueries, "glDeleteQueries");
        ok &= load(beginQuery, "glBeginQuery");
        ok &= load(endQuery, "glEndQuery");
        ok &= load(getQueryObjectuiv, "glGetQueryObjectuiv");
        ok &= load(sampleMaski, "glSampleMaski");
        return ok;
    }
};

/** Deferred deletion of the A-buffer's GL names in their context (osg::flushDeletedGLObjects). */
template <int Kind> class ABufferObjectManager : public osg::GLObjectManager
{
public:
    explicit ABufferObjectManager(unsigned int contextID)
        : osg::GLObjectManager("ABufferObjectManager", contextID)
    {
    }
    void deleteGLObject(GLuint name) override
    {
        if (Kind == 0)
        {
            glDeleteTextures(1, &name);
            return;
        }
        GLFunctions f;
        if (Kind == 1 && GLFunctions::load(f.deleteFramebuffers, "glDeleteFramebuffers"))
            f.deleteFramebuffers(1, &name);
        if (Kind == 2 && GLFunctions::load(f.deleteQueries, "glDeleteQueries")) f.deleteQueries(1, &name);
    }
};
using TextureDeleter = ABufferObjectManager<0>;
using FramebufferDeleter = ABufferObjectManager<1>;
using QueryDeleter = ABufferObjectManager<2>;

/** A sampler binding a per-context GL_TEXTURE_2D_MULTISAMPLE_ARRAY name owned by the A-buffer. */
class ABufferTexture : public osg::Texture
{
public:
    ABufferTexture() = default;
    ABufferTexture(const ABufferTexture& o, const osg::CopyOp& op = osg::CopyOp::SHALLOW_COPY)
        : osg::Texture(o, op), _names(o._names)
    {
    }
    META_StateAttribute(osgLoA, ABufferTexture, TEXTURE);

    int compare(const osg::StateAttribute& sa) const override
    {
        if (this == &sa) return 0;
        const int t = compareTexture(static_cast<const osg::Texture&>(sa));
        if (t != 0) return t;
        return this < &sa ? -1 : 1;
    }
    GLenum getTextureTarget() const override { return GL_TEXTURE_2D_MULTISAMPLE_ARRAY; }
    bool getModeUsage(osg::StateAttribute::ModeUsage&) const override { return false; }
    void setImage(unsigned int, osg::Image*) override {}
    osg::Image* getImage(unsigned int) override { return nullptr; }
    const osg::Image* getImage(unsigned int) const override { return nullptr; }
    unsigned int getNumImages() const override { return 0; }
    void allocateMipmap(osg::State&) const override {}
    void computeInternalFormat() const override {}
    void releaseGLObjects(osg::State* = nullptr) const override {} // the A-buffer owns the names

    void apply(osg::State& state) const override
    {
        const unsigned ctx = state.getContextID();
        glBindTexture(GL_TEXTURE_2D_MULTISAMPLE_ARRAY, ctx < _names.size() ? _names[ctx] : 0);
    }

    void setTextureName(unsigned ctx, GLuint name)
    {
        if (_names.size() <= ctx) _names.resize(ctx + 1, 0);
        _names[ctx] = name;
    }

private:
    std::vector<GLuint> _names;
};

osg::ref_ptr<osg::Geometry> fullScreenQuad()
{
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    v->push_back(osg::Vec3(-1.0f, -1.0f, 0.0f));
    v->push_back(osg::Vec3(1.0f, -1.0f, 0.0f));
    v->push_back(osg::Vec3(1.0f, 1.0f, 0.0f));
    v->push_back(osg::Vec3(-1.0f, 1.0f, 0.0f));
    g->setVertexArray(v.get());
    g->addPrimitiveSet(new osg::DrawArrays(GL_TRIANGLE_FAN, 0, 4));
    g->setUseDisplayList(false);
    g->setUseVertexBufferObjects(true);
    g->setCullingActive(false);
    // Clip-space vertices: an empty bound keeps the quad out of near/far computation.
    struct EmptyBound : public osg::Drawable::ComputeBoundingBoxCallback
    {
        osg::BoundingBox computeBound(const osg::Drawable&) const override { return osg::BoundingBox(); }
    };
    g->setComputeBoundingBoxCallback(new EmptyBound);
    return g;
}

std::atomic<unsigned> g_instances{0};

} // namespace

// ------------------------------------------------------------------------------------------

struct StencilRoutedABuffer::Impl
{
    struct PerContext
    {
        bool initialised = false;
        bool usable = false;
        GLFunctions gl;
        GLCapabilities caps;
        GLuint color = 0, depth = 0, fbo = 0, query = 0;
        int width = 0, height = 0, samples = 0, allocatedSamples = 0, layers = 0;
    };

    class RoutingBin;
    class BindFramebuffer;

    explicit Impl(StencilRoutedABuffer* o) : owner(o) {}

    StencilRoutedABuffer* owner;
    std::mutex mutex;                        // contexts, statistics
    std::map<unsigned, PerContext> contexts; // stable references
    ABufferFrameStatistics last;
    bool warnedClamp = false;
    bool warnedUnusable = false;
    osg::ref_ptr<RoutingBin> prototype;
    osg::ref_ptr<osg::StateSet> routingFull, routingRaster, clearState, initState, countState;
    osg::ref_ptr<osg::Geometry> quad;
    /** The viewport of the frame's passes, in every state set the passes apply. Without it,
     *  osg::State falls back to the global default viewport (osg::Viewport's 800 x 600) once the
     *  stage's viewport is popped: the clear, stencil initialisation and overflow count then
     *  covered only x < 800, y < 600 of larger frames. */
    osg::ref_ptr<osg::Viewport> passViewport = new osg::Viewport(0, 0, 1, 1);

    PerContext& context(unsigned ctx)
    {
        std::lock_guard<std::mutex> lock(mutex);
        return contexts[ctx];
    }

    void initialise(PerContext& pc)
    {
        pc.initialised = true;
        pc.caps.query();
        const bool version =
            pc.caps.versionAtLeast(4, 5) || pc.caps.hasExtension("GL_ARB_direct_state_access");
        pc.usable = version && pc.gl.loadAll() && pc.caps.maxSamples >= 1;
        if (!pc.usable && !warnedUnusable)
        {
            warnedUnusable = true;
            OSG_WARN << "osgLoA::StencilRoutedABuffer: the context (" << pc.caps.summary()
                     << ") lacks GL 4.5 direct state access or multisample textures; nothing is routed"
                     << std::endl;
        }
        if (pc.usable)
        {
            pc.gl.createFramebuffers(1, &pc.fbo);
            pc.gl.namedFramebufferDrawBuffer(pc.fbo, GL_COLOR_ATTACHMENT0);
            pc.gl.createQueries(GL_SAMPLES_PASSED, 1, &pc.query);
        }
    }

    void deleteTextures(PerContext& pc)
    {
        if (pc.color) glDeleteTextures(1, &pc.color);
        if (pc.depth) glDeleteTextures(1, &pc.depth);
        pc.color = pc.depth = 0;
        pc.layers = 0;
    }

    /** (Re)allocates the storage; true when the GL names changed. */
    bool allocate(unsigned ctx, PerContext& pc, int w, int h, int n, int layers)
    {
        if (pc.color && pc.width == w && pc.height == h && pc.samples == n && pc.layers == layers)
            return false;
        deleteTextures(pc);
        pc.gl.createTextures(GL_TEXTURE_2D_MULTISAMPLE_ARRAY, 1, &pc.color);
        pc.gl.textureStorage3DMultisample(pc.color, n, GL_RGBA8, w, h, layers, GL_TRUE);
        pc.gl.createTextures(GL_TEXTURE_2D_MULTISAMPLE_ARRAY, 1, &pc.depth);
        pc.gl.textureStorage3DMultisample(pc.depth, n, GL_DEPTH24_STENCIL8, w, h, layers, GL_TRUE);
        pc.gl.textureParameteri(pc.depth, GL_DEPTH_STENCIL_TEXTURE_MODE, GL_DEPTH_COMPONENT);
        GLint colorSamples = 0, depthSamples = 0;
        pc.gl.getTextureLevelParameteriv(pc.color, 0, GL_TEXTURE_SAMPLES, &colorSamples);
        pc.gl.getTextureLevelParameteriv(pc.depth, 0, GL_TEXTURE_SAMPLES, &depthSamples);
        pc.allocatedSamples = std::max(n, int(std::max(colorSamples, depthSamples)));
        pc.width = w;
        pc.height = h;
        pc.samples = n;
        pc.layers = layers;
        static_cast<ABufferTexture*>(owner->_colorTexture.get())->setTextureName(ctx, pc.color);
        static_cast<ABufferTexture*>(owner->_depthTexture.get())->setTextureName(ctx, pc.depth);
        pc.gl.namedFramebufferTextureLayer(pc.fbo, GL_COLOR_ATTACHMENT0, pc.color, 0, 0);
        pc.gl.namedFramebufferTextureLayer(pc.fbo, GL_DEPTH_STENCIL_ATTACHMENT, pc.depth, 0, 0);
        const GLenum status = pc.gl.checkNamedFramebufferStatus(pc.fbo, GL_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE)
            OSG_WARN << "osgLoA::StencilRoutedABuffer: framebuffer incomplete (0x" << std::hex << status
                     << std::dec << ") for " << w << "x" << h << " with " << n << " samples and " << layers
                     << " layers" << std::endl;
        return true;
    }

    void drawPasses(osgUtil::RenderBin& bin, osg::RenderInfo& ri, osgUtil::RenderLeaf*& previous);
    void drawLeaves(osgUtil::RenderBin& bin, osg::RenderInfo& ri, osgUtil::RenderLeaf*& previous);
};

/** The render bin of the routed geometry: its draw runs the routing passes. */
class StencilRoutedABuffer::Impl::RoutingBin : public osgUtil::RenderBin
{
public:
    RoutingBin() = default;
    explicit RoutingBin(StencilRoutedABuffer* owner) : _owner(owner) {}
    RoutingBin(const RoutingBin& o, const osg::CopyOp& op = osg::CopyOp::SHALLOW_COPY)
        : osgUtil::RenderBin(o, op), _owner(o._owner)
    {
    }
    META_Object(osgLoA, RoutingBin);

    void drawImplementation(osg::RenderInfo& ri, osgUtil::RenderLeaf*& previous) override
    {
        osg::ref_ptr<StencilRoutedABuffer> owner;
        if (_owner.lock(owner))
            owner->_impl->drawPasses(*this, ri, previous);
        else
            osgUtil::RenderBin::drawImplementation(ri, previous);
    }
    void drawBase(osg::RenderInfo& ri, osgUtil::RenderLeaf*& previous)
    {
        osgUtil::RenderBin::drawImplementation(ri, previous);
    }

private:
    osg::observer_ptr<StencilRoutedABuffer> _owner;
};

/** The camera's initial draw callback: binds the A-buffer's framebuffer, so that what the stage
 *  does before the routing bin (draw buffer, viewport) goes to it and not to another target. */
class StencilRoutedABuffer::Impl::BindFramebuffer : public osg::Camera::DrawCallback
{
public:
    explicit BindFramebuffer(StencilRoutedABuffer* owner) : _owner(owner) {}
    void operator()(osg::RenderInfo& ri) const override
    {
        osg::ref_ptr<StencilRoutedABuffer> owner;
        if (!_owner.lock(owner)) return;
        Impl& impl = *owner->_impl;
        PerContext& pc = impl.context(ri.getState()->getContextID());
        if (!pc.initialised) impl.initialise(pc);
        if (pc.usable) pc.gl.bindFramebuffer(GL_FRAMEBUFFER, pc.fbo);
    }

private:
    osg::observer_ptr<StencilRoutedABuffer> _owner;
};

void StencilRoutedABuffer::Impl::drawLeaves(osgUtil::RenderBin& bin, osg::RenderInfo& ri,
                                            osgUtil::RenderLeaf*& previous)
{
    osg::State& state = *ri.getState();
    static_cast<RoutingBin&>(bin).drawBase(ri, previous);
    // Back to the root of the state graph, so that the next pass starts as the first did.
    if (previous)
    {
        osgUtil::StateGraph::moveToRootStateGraph(state, previous->_parent->_parent);
        previous = nullptr;
    }
}

void StencilRoutedABuffer::Impl::drawPasses(osgUtil::RenderBin& bin, osg::RenderInfo& ri,
                                            osgUtil::RenderLeaf*& previous)
{
    osg::State& state = *ri.getState();
    const unsigned ctx = state.getContextID();
    PerContext& pc = context(ctx);
    if (!pc.initialised) initialise(pc);
    if (previous)
    {
        osgUtil::StateGraph::moveToRootStateGraph(state, previous->_parent->_parent);
        previous = nullptr;
    }
    if (!pc.usable) return;

    const int requested = owner->_samples;
    const int n = clampSamples(requested, pc.caps);
    if (n != requested && !warnedClamp)
    {
        warnedClamp = true;
        OSG_WARN << "osgLoA::StencilRoutedABuffer: " << requested
                 << " samples exceed this context's limit; using " << n << " (GL_MAX_SAMPLES "
                 << pc.caps.maxSamples << ", GL_MAX_COLOR_TEXTURE_SAMPLES " << pc.caps.maxColorTextureSamples
                 << ", GL_MAX_DEPTH_TEXTURE_SAMPLES " << pc.caps.maxDepthTextureSamples << ")" << std::endl;
    }
    const int maxPasses = std::max(1, std::min(owner->_maxPasses, stencilPassLimit(n)));
    const bool fullCoverage = owner->_coverage == FULL_COVERAGE ||
                              (owner->_coverage == AUTO_COVERAGE && !rasterCoverageByDefault(pc.caps));
    bin.setStateSet(fullCoverage ? routingFull.get() : routingRaster.get());

    // The stage's viewport: the camera's, or the one it inherits from the camera above it (set
    // by the cull traversal on the render stage). osg::State's current viewport is not used: a
    // state set applied earlier in the frame may have reset it to osg::Viewport's default
    // 800 x 600. Every pass below draws with this one (passViewport), whatever its size and origin.
    const osgUtil::RenderStage* stage = bin.getStage();
    const osg::Viewport* vp =
        stage && stage->getViewport() ? stage->getViewport() : state.getCurrentViewport();
    const int w = vp ? int(vp->x() + vp->width()) : 0;
    const int h = vp ? int(vp->y() + vp->height()) : 0;
    if (w <= 0 || h <= 0 || vp->width() <= 0 || vp->height() <= 0) return;
    passViewport->setViewport(vp->x(), vp->y(), vp->width(), vp->height());
    // Same object, new values: make osg::State apply it again.
    state.haveAppliedAttribute(osg::StateAttribute::VIEWPORT);

    bool namesChanged = allocate(ctx, pc, w, h, n, std::max(1, pc.layers));
    ABufferFrameStatistics stats;
    stats.frameNumber = state.getFrameStamp() ? state.getFrameStamp()->getFrameNumber() : 0;
    stats.requestedSamples = requested;
    stats.samples = n;
    stats.samplesClamped = n != requested;
    stats.maxPasses = maxPasses;
    stats.fullCoverage = fullCoverage;
    stats.width = w;
    stats.height = h;

    const unsigned lastSample = 1u << unsigned(n - 1);
    const osg::Drawable* quadDrawable = quad.get();
    int p = 0;
    for (;;)
    {
        pc.gl.namedFramebufferTextureLayer(pc.fbo, GL_COLOR_ATTACHMENT0, pc.color, 0, p);
        pc.gl.namedFramebufferTextureLayer(pc.fbo, GL_DEPTH_STENCIL_ATTACHMENT, pc.depth, 0, p);
        pc.gl.bindFramebuffer(GL_FRAMEBUFFER, pc.fbo);

        // Empty layer: colour 0, depth 1 (Algorithm 2's "empty"), stencil 0 (never routed).
        state.apply(clearState.get());
        glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
        glClearDepth(1.0);
        glClearStencil(0);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);

        // Sample i of pass p starts at i + 2 + pN: the (pN + i + 1)-th fragment finds it at 2.
        state.apply(initState.get());
        for (int i = 0; i < n; ++i)
        {
            pc.gl.sampleMaski(0, 1u << unsigned(i));
            glStencilFunc(GL_ALWAYS, i + 2 + p * n, 0xFF);
            quadDrawable->draw(ri);
        }
        state.haveAppliedAttribute(osg::StateAttribute::STENCIL);

        drawLeaves(bin, ri, previous);

        // Overflow: the last routed sample's stencil reached 0 (saturating DECR).
        state.apply(countState.get());
        pc.gl.sampleMaski(0, lastSample);
        pc.gl.beginQuery(GL_SAMPLES_PASSED, pc.query);
        quadDrawable->draw(ri);
        pc.gl.endQuery(GL_SAMPLES_PASSED);
        GLuint overflow = 0;
        pc.gl.getQueryObjectuiv(pc.query, GL_QUERY_RESULT, &overflow);
        stats.overflowPixels.push_back(overflow);

        if (overflow == 0) break;
        if (p + 1 >= maxPasses)
        {
            stats.truncated = true;
            break;
        }
        if (p + 1 >= pc.layers)
        {
            // Grow to the passes needed so far plus one and draw the frame's passes again
            // (the old layers go with the old storage).
            stats.discardedPasses += p + 1;
            namesChanged |= allocate(ctx, pc, w, h, n, p + 2);
            stats.overflowPixels.clear();
            p = 0;
            continue;
        }
        ++p;
    }
    stats.passes = p + 1;
    stats.allocatedSamples = pc.allocatedSamples;
    stats.memory = ABufferMemory::of(pc.width, pc.height, pc.allocatedSamples, pc.layers);

    pc.gl.sampleMaski(0, ~0u);
    state.haveAppliedAttribute(osg::StateAttribute::SAMPLEMASKI);
    state.apply();
    const GLuint defaultFbo = state.getGraphicsContext() ? state.getGraphicsContext()->getDefaultFboId() : 0;
    pc.gl.bindFramebuffer(GL_FRAMEBUFFER, defaultFbo);
    // Samplers bound before with the old names must be bound again.
    if (namesChanged) state.dirtyAllAttributes();

    owner->_layersUniform->set(stats.passes);
    owner->_samplesUniform->set(n);
    std::lock_guard<std::mutex> lock(mutex);
    last = stats;
}

// ------------------------------------------------------------------------------------------

StencilRoutedABuffer::StencilRoutedABuffer(int samples, int maxPasses) : _samples(1), _maxPasses(1)
{
    setSamples(samples);
    setMaxPasses(maxPasses);
    _impl = new Impl(this);
    _binName = "loa_abuffer_" + std::to_string(g_instances.fetch_add(1));

    _camera = new osg::Camera;
    _camera->setName("StencilRoutedABuffer");
    _camera->setRenderOrder(osg::Camera::PRE_RENDER);
    _camera->setReferenceFrame(osg::Transform::RELATIVE_RF);
    _camera->setViewMatrix(osg::Matrix::identity());
    _camera->setProjectionMatrix(osg::Matrix::identity());
    _camera->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    _camera->setClearMask(0);
    _camera->setAllowEventFocus(false);
    _camera->setInitialDrawCallback(new Impl::BindFramebuffer(this));

    _routedGroup = new osg::Group;
    _routedGroup->setName("StencilRoutedABuffer routed");
    _routedStateSet = _routedGroup->getOrCreateStateSet();
    _routedStateSet->setRenderBinDetails(kRenderBinNumber, _binName,
                                         osg::StateSet::OVERRIDE_RENDERBIN_DETAILS);
    _camera->addChild(_routedGroup.get());

    _colorTexture = new ABufferTexture;
    _colorTexture->setName("loa_abufferColor");
    _depthTexture = new ABufferTexture;
    _depthTexture->setName("loa_abufferDepth");
    _layersUniform = new osg::Uniform("loa_abufferLayers", 0);
    _layersUniform->setDataVariance(osg::Object::DYNAMIC);
    _samplesUniform = new osg::Uniform("loa_abufferSamples", _samples);
    _samplesUniform->setDataVariance(osg::Object::DYNAMIC);

    const auto force =
        osg::StateAttribute::ON | osg::StateAttribute::OVERRIDE | osg::StateAttribute::PROTECTED;
    const auto forceOff =
        osg::StateAttribute::OFF | osg::StateAttribute::OVERRIDE | osg::StateAttribute::PROTECTED;

    // Routing: full coverage (multisample rasterization off), per-sample stencil EQUAL 2 with
    // DECR on every outcome, depth ALWAYS with writes (the routed sample keeps the depth).
    Impl& impl = *_impl;
    for (int full = 0; full < 2; ++full)
    {
        osg::ref_ptr<osg::StateSet> rs = new osg::StateSet;
        osg::ref_ptr<osg::Stencil> st = new osg::Stencil;
        st->setFunction(osg::Stencil::EQUAL, 2, 0xFF);
        st->setOperation(osg::Stencil::DECR, osg::Stencil::DECR, osg::Stencil::DECR);
        st->setWriteMask(0xFF);
        rs->setAttributeAndModes(st.get(), force);
        rs->setAttributeAndModes(new osg::Depth(osg::Depth::ALWAYS, 0.0, 1.0, true), force);
        rs->setAttributeAndModes(new osg::ColorMask(true, true, true, true), force);
        rs->setMode(GL_MULTISAMPLE, full ? forceOff : force);
        rs->setMode(GL_SAMPLE_MASK, forceOff);
        rs->setMode(GL_SAMPLE_ALPHA_TO_COVERAGE, forceOff);
        rs->setMode(GL_BLEND, forceOff);
        rs->setAttribute(impl.passViewport.get());
        (full ? impl.routingFull : impl.routingRaster) = rs;
    }
    impl.clearState = new osg::StateSet;
    {
        osg::ref_ptr<osg::Stencil> st = new osg::Stencil;
        st->setWriteMask(0xFF);
        impl.clearState->setAttribute(st.get());
        impl.clearState->setAttribute(new osg::Depth(osg::Depth::ALWAYS, 0.0, 1.0, true));
        impl.clearState->setAttribute(new osg::ColorMask(true, true, true, true));
        impl.clearState->setAttribute(impl.passViewport.get());
    }
    osg::ref_ptr<osg::Program> quadProgram = ShaderLibrary::createProgram(
        "abuffer routing init", {"loa_abuffer_fullscreen.vert.glsl", "loa_abuffer_route_init.frag.glsl"});
    auto passState = [&](osg::Stencil::Function f)
    {
        osg::ref_ptr<osg::StateSet> ss = new osg::StateSet;
        osg::ref_ptr<osg::Stencil> st = new osg::Stencil;
        st->setFunction(f, 0, 0xFF);
        const auto op = f == osg::Stencil::ALWAYS ? osg::Stencil::REPLACE : osg::Stencil::KEEP;
        st->setOperation(op, op, op);
        st->setWriteMask(0xFF);
        ss->setAttributeAndModes(st.get(), osg::StateAttribute::ON);
        ss->setAttribute(new osg::Depth(osg::Depth::ALWAYS, 0.0, 1.0, false));
        ss->setMode(GL_DEPTH_TEST, osg::StateAttribute::OFF);
        ss->setAttribute(new osg::ColorMask(false, false, false, false));
        ss->setAttribute(quadProgram.get());
        ss->setMode(GL_MULTISAMPLE, osg::StateAttribute::ON);
        ss->setMode(GL_SAMPLE_MASK, osg::StateAttribute::ON);
        ss->setMode(GL_BLEND, osg::StateAttribute::OFF);
        ss->setMode(GL_CULL_FACE, osg::StateAttribute::OFF);
        ss->setAttribute(impl.passViewport.get());
        return ss;
    };
    impl.initState = passState(osg::Stencil::ALWAYS);
    impl.countState = passState(osg::Stencil::EQUAL);
    impl.quad = fullScreenQuad();

    impl.prototype = new Impl::RoutingBin(this);
    impl.prototype->setStateSet(impl.routingFull.get());
    osgUtil::RenderBin::addRenderBinPrototype(_binName, impl.prototype.get());
}

StencilRoutedABuffer::~StencilRoutedABuffer()
{
    osgUtil::RenderBin::removeRenderBinPrototype(_impl->prototype.get());
    releaseGLObjects(nullptr);
    delete _impl;
}

void StencilRoutedABuffer::setSamples(int samples)
{
    if (samples < 1)
        throw std::invalid_argument("A-buffer sample count " + std::to_string(samples) +
                                    " must be at least 1");
    _samples = samples;
    updateDefines();
}

void StencilRoutedABuffer::setMaxPasses(int passes)
{
    if (passes < 1)
        throw std::invalid_argument("A-buffer routing passes " + std::to_string(passes) +
                                    " must be at least 1");
    _maxPasses = passes;
    updateDefines();
}

int StencilRoutedABuffer::getMaxFragments() const
{
    return int(std::min<long long>(64, (long long)(_samples) * (long long)(_maxPasses)));
}

void StencilRoutedABuffer::setMaxFragmentsDefine(osg::StateSet* ss, int extra)
{
    _defineStateSets.emplace_back(ss, extra);
    updateDefines();
}

void StencilRoutedABuffer::updateDefines()
{
    for (auto& d : _defineStateSets)
    {
        osg::ref_ptr<osg::StateSet> ss;
        if (d.first.lock(ss))
            ss->setDefine("LOA_MAX_FRAGMENTS", std::to_string(getMaxFragments() + d.second));
    }
}

bool StencilRoutedABuffer::rasterCoverageByDefault(const GLCapabilities& caps)
{
    // Measured (docs/abuffer.md): Mesa's llvmpipe writes colour and depth of a fragment drawn
    // with GL_MULTISAMPLE disabled into sample 0 only, so full-coverage routing keeps one fragment
    // per layer there. softpipe shares the gallium rasterizer state handling.
    return caps.renderer.find("llvmpipe") != std::string::npos ||
           caps.renderer.find("softpipe") != std::string::npos;
}

void StencilRoutedABuffer::setRoutingCoverage(RoutingCoverage coverage)
{
    _coverage = coverage;
}

int StencilRoutedABuffer::stencilPassLimit(int samples)
{
    if (samples < 1) return 0;
    // The largest value written is (p + 1) N + 1 for pass p: (p + 1) N + 1 <= 255.
    return std::max(0, (255 - 1) / samples);
}

int StencilRoutedABuffer::clampSamples(int samples, const GLCapabilities& caps)
{
    int limit = caps.maxSamples;
    if (caps.maxColorTextureSamples > 0) limit = std::min(limit, caps.maxColorTextureSamples);
    if (caps.maxDepthTextureSamples > 0) limit = std::min(limit, caps.maxDepthTextureSamples);
    // Sample masks of one word: 32 samples at most.
    limit = std::min(limit, 32);
    return std::max(1, std::min(samples, limit));
}

void StencilRoutedABuffer::checkSamples(int samples, const GLCapabilities& caps)
{
    const int limit = clampSamples(1 << 30, caps);
    if (samples < 1 || samples > limit)
        throw std::invalid_argument("A-buffer sample count " + std::to_string(samples) + " is outside 1.." +
                                    std::to_string(limit) + " (GL_MAX_SAMPLES " +
                                    std::to_string(caps.maxSamples) + " of " + caps.renderer + ")");
}

void StencilRoutedABuffer::setSize(int width, int height)
{
    if (width == _width && height == _height) return;
    _width = std::max(0, width);
    _height = std::max(0, height);
    if (_width > 0 && _height > 0)
        _camera->setViewport(0, 0, _width, _height);
    else
        _camera->setViewport(nullptr);
}

void StencilRoutedABuffer::addResolveState(osg::StateSet* ss, unsigned colorUnit, unsigned depthUnit)
{
    ss->setTextureAttribute(colorUnit, _colorTexture.get());
    ss->setTextureAttribute(depthUnit, _depthTexture.get());
    ss->addUniform(new osg::Uniform("loa_abufferColor", int(colorUnit)));
    ss->addUniform(new osg::Uniform("loa_abufferDepth", int(depthUnit)));
    ss->addUniform(_layersUniform.get());
    ss->addUniform(_samplesUniform.get());
}

osg::ref_ptr<osg::Node> StencilRoutedABuffer::createResolveNode(float mergeEpsilon, unsigned colorUnit,
                                                                unsigned depthUnit)
{
    osg::ref_ptr<osg::Geometry> quad = fullScreenQuad();
    quad->setName("StencilRoutedABuffer resolve");
    osg::StateSet* ss = quad->getOrCreateStateSet();
    ss->setAttribute(ShaderLibrary::createProgram("abuffer resolve", {"loa_abuffer_fullscreen.vert.glsl",
                                                                      "loa_abuffer_resolve.frag.glsl",
                                                                      "loa_abuffer_resolve_main.frag.glsl"})
                         .get());
    addResolveState(ss, colorUnit, depthUnit);
    setMaxFragmentsDefine(ss);
    ss->addUniform(new osg::Uniform("loa_abufferMergeEpsilon", mergeEpsilon));
    ss->setAttributeAndModes(new osg::BlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA), osg::StateAttribute::ON);
    ss->setAttribute(new osg::Depth(osg::Depth::ALWAYS, 0.0, 1.0, false));
    ss->setMode(GL_DEPTH_TEST, osg::StateAttribute::OFF);
    ss->setMode(GL_CULL_FACE, osg::StateAttribute::OFF);
    ss->setRenderBinDetails(100, "RenderBin");
    return quad;
}

osg::ref_ptr<osg::Program> StencilRoutedABuffer::createVertexColorProgram()
{
    osg::ref_ptr<osg::Program> p = ShaderLibrary::createProgram(
        "abuffer vertex colour", {"loa_plain.vert.glsl", "loa_abuffer_write.frag.glsl"});
    p->addShader(new osg::Shader(osg::Shader::FRAGMENT, "#version 450 compatibility\n"
                                                        "in vec4 loa_color;\n"
                                                        "void loa_abufferWrite(vec4 straightAlphaColor);\n"
                                                        "void main() { loa_abufferWrite(loa_color); }\n"));
    return p;
}

ABufferFrameStatistics StencilRoutedABuffer::getLastFrameStatistics() const
{
    std::lock_guard<std::mutex> lock(_impl->mutex);
    return _impl->last;
}

ABufferMemory StencilRoutedABuffer::getAllocatedMemory() const
{
    std::lock_guard<std::mutex> lock(_impl->mutex);
    ABufferMemory best;
    for (const auto& entry : _impl->contexts)
    {
        const Impl::PerContext& pc = entry.second;
        const ABufferMemory m = ABufferMemory::of(pc.width, pc.height, pc.allocatedSamples, pc.layers);
        if (pc.color && m.bytes() > best.bytes()) best = m;
    }
    return best;
}

void StencilRoutedABuffer::releaseGLObjects(osg::State* state) const
{
    std::lock_guard<std::mutex> lock(_impl->mutex);
    for (auto& entry : _impl->contexts)
    {
        const unsigned ctx = entry.first;
        if (state && state->getContextID() != ctx) continue;
        Impl::PerContext& pc = entry.second;
        if (!pc.initialised) continue;
        if (state)
        {
            if (pc.color) glDeleteTextures(1, &pc.color);
            if (pc.depth) glDeleteTextures(1, &pc.depth);
            if (pc.fbo) pc.gl.deleteFramebuffers(1, &pc.fbo);
            if (pc.query) pc.gl.deleteQueries(1, &pc.query);
        }
        else
        {
            if (pc.color) osg::get<TextureDeleter>(ctx)->scheduleGLObjectForDeletion(pc.color);
            if (pc.depth) osg::get<TextureDeleter>(ctx)->scheduleGLObjectForDeletion(pc.depth);
            if (pc.fbo) osg::get<FramebufferDeleter>(ctx)->scheduleGLObjectForDeletion(pc.fbo);
            if (pc.query) osg::get<QueryDeleter>(ctx)->scheduleGLObjectForDeletion(pc.query);
        }
        static_cast<ABufferTexture*>(_colorTexture.get())->setTextureName(ctx, 0);
        static_cast<ABufferTexture*>(_depthTexture.get())->setTextureName(ctx, 0);
        pc = Impl::PerContext();
    }
}

} // namespace osgLoA
