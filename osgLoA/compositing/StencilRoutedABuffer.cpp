// StencilRoutedABuffer: stencil routing (Myers & Bavoil 2007) into 2D multisample array textures,
// one layer per routing pass, with adaptive passes driven by an occlusion query (docs/abuffer.md).
#include <osgLoA/compositing/StencilRoutedABuffer>
#include <osgLoA/render/ShaderLibrary>

#include "ContextObjects.h"
#include "RenderTarget.h"

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
#include <functional>
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

    /** Loads every entry point; false when one is missing. Call with the context current. */
    bool loadAll()
    {
        bool ok = true;
        ok &= detail::loadGLFunction(createTextures, "glCreateTextures");
        ok &= detail::loadGLFunction(textureStorage3DMultisample, "glTextureStorage3DMultisample");
        ok &= detail::loadGLFunction(textureParameteri, "glTextureParameteri");
        ok &= detail::loadGLFunction(getTextureLevelParameteriv, "glGetTextureLevelParameteriv");
        ok &= detail::loadGLFunction(createFramebuffers, "glCreateFramebuffers");
        ok &= detail::loadGLFunction(namedFramebufferTextureLayer, "glNamedFramebufferTextureLayer");
        ok &= detail::loadGLFunction(namedFramebufferDrawBuffer, "glNamedFramebufferDrawBuffer");
        ok &= detail::loadGLFunction(checkNamedFramebufferStatus, "glCheckNamedFramebufferStatus");
        ok &= detail::loadGLFunction(bindFramebuffer, "glBindFramebuffer");
        ok &= detail::loadGLFunction(deleteFramebuffers, "glDeleteFramebuffers");
        ok &= detail::loadGLFunction(createQueries, "glCreateQueries");
        ok &= detail::loadGLFunction(deleteQueries, "glDeleteQueries");
        ok &= detail::loadGLFunction(beginQuery, "glBeginQuery");
        ok &= detail::loadGLFunction(endQuery, "glEndQuery");
        ok &= detail::loadGLFunction(getQueryObjectuiv, "glGetQueryObjectuiv");
        ok &= detail::loadGLFunction(sampleMaski, "glSampleMaski");
        return ok;
    }
};

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

    explicit Impl(StencilRoutedABuffer* o) : owner(o) {}

    StencilRoutedABuffer* owner;
    std::mutex mutex;                        // contexts, statistics
    std::map<unsigned, PerContext> contexts; // stable references
    ABufferFrameStatistics last;
    OITFrameStatistics lastOit;
    bool warnedClamp = false;
    bool warnedUnusable = false;
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
        static_cast<detail::ContextTexture*>(owner->_colorTexture.get())->setTextureName(ctx, pc.color);
        static_cast<detail::ContextTexture*>(owner->_depthTexture.get())->setTextureName(ctx, pc.depth);
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
};

void StencilRoutedABuffer::drawRouted(osgUtil::RenderBin& bin, osg::RenderInfo& ri,
                                      osgUtil::RenderLeaf*& previous)
{
    _impl->drawPasses(bin, ri, previous);
}

void StencilRoutedABuffer::bindTarget(osg::RenderInfo& ri)
{
    Impl::PerContext& pc = _impl->context(ri.getState()->getContextID());
    if (!pc.initialised) _impl->initialise(pc);
    if (pc.usable) pc.gl.bindFramebuffer(GL_FRAMEBUFFER, pc.fbo);
}

void StencilRoutedABuffer::Impl::drawPasses(osgUtil::RenderBin& bin, osg::RenderInfo& ri,
                                            osgUtil::RenderLeaf*& previous)
{
    osg::State& state = *ri.getState();
    const unsigned ctx = state.getContextID();
    PerContext& pc = context(ctx);
    if (!pc.initialised) initialise(pc);
    if (!pc.usable)
    {
        RoutedFrame none;
        owner->beginRoutedFrame(bin, ri, previous, *passViewport, nullptr, none);
        return;
    }

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
    // Every pass below draws with the stage's viewport (passViewport), whatever its size and
    // origin, scissored to the tiles the routed draws touch.
    RoutedFrame frame;
    if (!owner->beginRoutedFrame(bin, ri, previous, *passViewport,
                                 fullCoverage ? routingFull.get() : routingRaster.get(), frame))
        return;
    const RoutedRegion& region = frame.region;
    OITFrameStatistics& oit = frame.stats;
    const int w = frame.width, h = frame.height;
    if (region.isEmpty())
    {
        // Nothing routed in view: no pass at all (the resolve's mask is empty too).
        pc.gl.bindFramebuffer(GL_FRAMEBUFFER, frame.defaultFbo);
        owner->_layersUniform->set(0);
        oit.bytes = ABufferMemory::of(pc.width, pc.height, pc.allocatedSamples, pc.layers).bytes();
        std::lock_guard<std::mutex> lock(mutex);
        last = ABufferFrameStatistics();
        last.frameNumber = oit.frameNumber;
        last.width = w;
        last.height = h;
        lastOit = oit;
        return;
    }

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
    auto inRegion = [&](const std::function<void()>& f) { forEachRectangle(state, region, f); };
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
        inRegion([] { glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT); });

        // Sample i of pass p starts at i + 2 + pN: the (pN + i + 1)-th fragment finds it at 2.
        state.apply(initState.get());
        for (int i = 0; i < n; ++i)
        {
            pc.gl.sampleMaski(0, 1u << unsigned(i));
            glStencilFunc(GL_ALWAYS, i + 2 + p * n, 0xFF);
            inRegion([&] { quadDrawable->draw(ri); });
        }
        state.haveAppliedAttribute(osg::StateAttribute::STENCIL);

        StencilRoutedABuffer::drawLeaves(bin, ri, previous);

        // Overflow: the last routed sample's stencil reached 0 (saturating DECR).
        state.apply(countState.get());
        pc.gl.sampleMaski(0, lastSample);
        pc.gl.beginQuery(GL_SAMPLES_PASSED, pc.query);
        inRegion([&] { quadDrawable->draw(ri); });
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
    pc.gl.bindFramebuffer(GL_FRAMEBUFFER, frame.defaultFbo);
    // Samplers bound before with the old names must be bound again.
    if (namesChanged) state.dirtyAllAttributes();

    owner->_layersUniform->set(stats.passes);
    owner->_samplesUniform->set(n);
    oit.geometryPasses = stats.passes;
    oit.discardedPasses = stats.discardedPasses;
    oit.truncated = stats.truncated;
    oit.bytes = stats.memory.bytes();
    std::lock_guard<std::mutex> lock(mutex);
    last = stats;
    lastOit = oit;
}

// ------------------------------------------------------------------------------------------

StencilRoutedABuffer::StencilRoutedABuffer(int samples, int maxPasses)
    : OrderIndependentTransparency("StencilRoutedABuffer", kRenderBinNumber), _samples(1), _maxPasses(1)
{
    setSamples(samples);
    setMaxPasses(maxPasses);
    _impl = new Impl(this);

    _colorTexture = new detail::ContextTexture(GL_TEXTURE_2D_MULTISAMPLE_ARRAY);
    _colorTexture->setName("loa_abufferColor");
    _depthTexture = new detail::ContextTexture(GL_TEXTURE_2D_MULTISAMPLE_ARRAY);
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
    impl.quad = detail::createFullScreenTriangle();
}

StencilRoutedABuffer::~StencilRoutedABuffer()
{
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

bool StencilRoutedABuffer::rasterCoverageByDefault(const GLCapabilities& caps)
{
    return rasterCoverageByDefault(caps.renderer);
}

bool StencilRoutedABuffer::rasterCoverageByDefault(const std::string& renderer)
{
    // Measured (docs/abuffer.md): Mesa's llvmpipe writes colour and depth of a fragment drawn
    // with GL_MULTISAMPLE disabled into sample 0 only, so full-coverage routing keeps one fragment
    // per layer there. softpipe shares the gallium rasterizer state handling.
    return renderer.find("llvmpipe") != std::string::npos || renderer.find("softpipe") != std::string::npos;
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

void StencilRoutedABuffer::addResolveState(osg::StateSet* ss, unsigned colorUnit, unsigned depthUnit)
{
    ss->setTextureAttribute(colorUnit, _colorTexture.get());
    ss->setTextureAttribute(depthUnit, _depthTexture.get());
    ss->addUniform(new osg::Uniform("loa_abufferColor", int(colorUnit)));
    ss->addUniform(new osg::Uniform("loa_abufferDepth", int(depthUnit)));
    ss->addUniform(_layersUniform.get());
    ss->addUniform(_samplesUniform.get());
}

ABufferFrameStatistics StencilRoutedABuffer::getLastFrameStatistics() const
{
    std::lock_guard<std::mutex> lock(_impl->mutex);
    return _impl->last;
}

OITFrameStatistics StencilRoutedABuffer::getFrameStatistics() const
{
    std::lock_guard<std::mutex> lock(_impl->mutex);
    return _impl->lastOit;
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
            if (pc.color) detail::scheduleDeletion(detail::GL_NAME_TEXTURE, ctx, pc.color);
            if (pc.depth) detail::scheduleDeletion(detail::GL_NAME_TEXTURE, ctx, pc.depth);
            if (pc.fbo) detail::scheduleDeletion(detail::GL_NAME_FRAMEBUFFER, ctx, pc.fbo);
            if (pc.query) detail::scheduleDeletion(detail::GL_NAME_QUERY, ctx, pc.query);
        }
        static_cast<detail::ContextTexture*>(_colorTexture.get())->setTextureName(ctx, 0);
        static_cast<detail::ContextTexture*>(_depthTexture.get())->setTextureName(ctx, 0);
        pc = Impl::PerContext();
    }
}

} // namespace osgLoA
