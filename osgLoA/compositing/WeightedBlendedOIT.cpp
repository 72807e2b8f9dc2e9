// WeightedBlendedOIT: McGuire & Bavoil 2013, one additive pass into two float targets
// (docs/abuffer.md).
#include <osgLoA/compositing/WeightedBlendedOIT>

#include "ContextObjects.h"

#include <osg/BlendEquation>
#include <osg/BlendFunc>
#include <osg/ColorMask>
#include <osg/Depth>
#include <osg/Notify>
#include <osgUtil/RenderBin>
#include <osgUtil/RenderStage>
#include <osgUtil/StateGraph>

#include <map>
#include <mutex>

#ifndef GL_RGBA32F
#define GL_RGBA32F 0x8814
#endif
#ifndef GL_RG32F
#define GL_RG32F 0x8230
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
#ifndef GL_COLOR
#define GL_COLOR 0x1800
#endif
#ifndef GL_MULTISAMPLE
#define GL_MULTISAMPLE 0x809D
#endif

namespace osgLoA
{

namespace
{
struct GLFunctions
{
    void(GL_APIENTRY* createTextures)(GLenum, GLsizei, GLuint*) = nullptr;
    void(GL_APIENTRY* textureStorage2D)(GLuint, GLsizei, GLenum, GLsizei, GLsizei) = nullptr;
    void(GL_APIENTRY* createFramebuffers)(GLsizei, GLuint*) = nullptr;
    void(GL_APIENTRY* namedFramebufferTexture)(GLuint, GLenum, GLuint, GLint) = nullptr;
    void(GL_APIENTRY* namedFramebufferDrawBuffers)(GLuint, GLsizei, const GLenum*) = nullptr;
    GLenum(GL_APIENTRY* checkNamedFramebufferStatus)(GLuint, GLenum) = nullptr;
    void(GL_APIENTRY* bindFramebuffer)(GLenum, GLuint) = nullptr;
    void(GL_APIENTRY* clearBufferfv)(GLenum, GLint, const GLfloat*) = nullptr;
    void(GL_APIENTRY* deleteFramebuffers)(GLsizei, const GLuint*) = nullptr;

    bool loadAll()
    {
        bool ok = true;
        ok &= detail::loadGLFunction(createTextures, "glCreateTextures");
        ok &= detail::loadGLFunction(textureStorage2D, "glTextureStorage2D");
        ok &= detail::loadGLFunction(createFramebuffers, "glCreateFramebuffers");
        ok &= detail::loadGLFunction(namedFramebufferTexture, "glNamedFramebufferTexture");
        ok &= detail::loadGLFunction(namedFramebufferDrawBuffers, "glNamedFramebufferDrawBuffers");
        ok &= detail::loadGLFunction(checkNamedFramebufferStatus, "glCheckNamedFramebufferStatus");
        ok &= detail::loadGLFunction(bindFramebuffer, "glBindFramebuffer");
        ok &= detail::loadGLFunction(clearBufferfv, "glClearBufferfv");
        ok &= detail::loadGLFunction(deleteFramebuffers, "glDeleteFramebuffers");
        return ok;
    }
};
} // namespace

struct WeightedBlendedOIT::Impl
{
    struct PerContext
    {
        bool initialised = false;
        bool usable = false;
        GLFunctions gl;
        GLuint accum = 0, reveal = 0, fbo = 0;
        int width = 0, height = 0;
    };
    explicit Impl(WeightedBlendedOIT* o) : owner(o) {}
    WeightedBlendedOIT* owner;
    std::mutex mutex;
    std::map<unsigned, PerContext> contexts;
    OITFrameStatistics last;
    bool warned = false;
    osg::ref_ptr<osg::StateSet> routing;
    osg::ref_ptr<osg::Viewport> passViewport = new osg::Viewport(0, 0, 1, 1);

    PerContext& context(unsigned ctx)
    {
        std::lock_guard<std::mutex> lock(mutex);
        return contexts[ctx];
    }
    void initialise(PerContext& pc)
    {
        pc.initialised = true;
        pc.usable =
            detail::usableWithGL45("WeightedBlendedOIT", "direct state access", pc.gl.loadAll(), warned);
        if (!pc.usable) return;
        pc.gl.createFramebuffers(1, &pc.fbo);
        const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT0 + 1};
        pc.gl.namedFramebufferDrawBuffers(pc.fbo, 2, buffers);
    }
    void allocate(unsigned ctx, PerContext& pc, int w, int h)
    {
        if (pc.accum && pc.width == w && pc.height == h) return;
        if (pc.accum) glDeleteTextures(1, &pc.accum);
        if (pc.reveal) glDeleteTextures(1, &pc.reveal);
        pc.gl.createTextures(GL_TEXTURE_2D, 1, &pc.accum);
        pc.gl.textureStorage2D(pc.accum, 1, GL_RGBA32F, w, h);
        pc.gl.createTextures(GL_TEXTURE_2D, 1, &pc.reveal);
        pc.gl.textureStorage2D(pc.reveal, 1, GL_RG32F, w, h);
        pc.gl.namedFramebufferTexture(pc.fbo, GL_COLOR_ATTACHMENT0, pc.accum, 0);
        pc.gl.namedFramebufferTexture(pc.fbo, GL_COLOR_ATTACHMENT0 + 1, pc.reveal, 0);
        const GLenum status = pc.gl.checkNamedFramebufferStatus(pc.fbo, GL_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE)
            OSG_WARN << "osgLoA::WeightedBlendedOIT: framebuffer incomplete (0x" << std::hex << status
                     << std::dec << ") at " << w << "x" << h << std::endl;
        pc.width = w;
        pc.height = h;
        static_cast<detail::ContextTexture*>(owner->_accum.get())->setTextureName(ctx, pc.accum);
        static_cast<detail::ContextTexture*>(owner->_reveal.get())->setTextureName(ctx, pc.reveal);
    }
};

WeightedBlendedOIT::WeightedBlendedOIT()
    : OrderIndependentTransparency("WeightedBlendedOIT", kRenderBinNumber)
{
    _impl = new Impl(this);
    _accum = new detail::ContextTexture(GL_TEXTURE_2D);
    _accum->setName("loa_wboitAccum");
    _reveal = new detail::ContextTexture(GL_TEXTURE_2D);
    _reveal->setName("loa_wboitReveal");
    const auto force =
        osg::StateAttribute::ON | osg::StateAttribute::OVERRIDE | osg::StateAttribute::PROTECTED;
    const auto forceOff =
        osg::StateAttribute::OFF | osg::StateAttribute::OVERRIDE | osg::StateAttribute::PROTECTED;
    osg::ref_ptr<osg::StateSet> rs = new osg::StateSet;
    rs->setAttributeAndModes(new osg::Depth(osg::Depth::ALWAYS, 0.0, 1.0, false), forceOff);
    rs->setAttributeAndModes(new osg::ColorMask(true, true, true, true), force);
    rs->setAttributeAndModes(new osg::BlendFunc(GL_ONE, GL_ONE), force);
    rs->setAttributeAndModes(new osg::BlendEquation(osg::BlendEquation::FUNC_ADD), force);
    rs->setMode(GL_STENCIL_TEST, forceOff);
    rs->setMode(GL_MULTISAMPLE, forceOff);
    rs->setAttribute(_impl->passViewport.get());
    _impl->routing = rs;
}

WeightedBlendedOIT::~WeightedBlendedOIT()
{
    releaseGLObjects(nullptr);
    delete _impl;
}

void WeightedBlendedOIT::bindTarget(osg::RenderInfo& ri)
{
    Impl::PerContext& pc = _impl->context(ri.getState()->getContextID());
    if (!pc.initialised) _impl->initialise(pc);
    if (pc.usable) pc.gl.bindFramebuffer(GL_FRAMEBUFFER, pc.fbo);
}

void WeightedBlendedOIT::drawRouted(osgUtil::RenderBin& bin, osg::RenderInfo& ri,
                                    osgUtil::RenderLeaf*& previous)
{
    osg::State& state = *ri.getState();
    const unsigned ctx = state.getContextID();
    Impl::PerContext& pc = _impl->context(ctx);
    if (!pc.initialised) _impl->initialise(pc);
    RoutedFrame frame;
    if (!beginRoutedFrame(bin, ri, previous, *_impl->passViewport, _impl->routing.get(), frame) || !pc.usable)
        return;
    const RoutedRegion& region = frame.region;
    OITFrameStatistics& st = frame.stats;
    const int w = frame.width, h = frame.height;
    const GLuint defaultFbo = frame.defaultFbo;
    if (!region.isEmpty())
    {
        const bool changed = pc.width != w || pc.height != h || !pc.accum;
        _impl->allocate(ctx, pc, w, h);
        pc.gl.bindFramebuffer(GL_FRAMEBUFFER, pc.fbo);
        state.applyAttribute(_impl->passViewport.get());
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        state.haveAppliedAttribute(osg::StateAttribute::COLORMASK);
        const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        forEachRectangle(state, region,
                         [&]
                         {
                             pc.gl.clearBufferfv(GL_COLOR, 0, zero);
                             pc.gl.clearBufferfv(GL_COLOR, 1, zero);
                         });
        WeightedBlendedOIT::drawLeaves(bin, ri, previous);
        st.geometryPasses = 1;
        if (changed) state.dirtyAllAttributes();
    }
    pc.gl.bindFramebuffer(GL_FRAMEBUFFER, defaultFbo);
    st.bytes = std::uint64_t(pc.width) * std::uint64_t(pc.height) * 24u;
    std::lock_guard<std::mutex> lock(_impl->mutex);
    _impl->last = st;
}

void WeightedBlendedOIT::addResolveState(osg::StateSet* ss, unsigned unitA, unsigned unitB)
{
    ss->setTextureAttribute(unitA, _accum.get());
    ss->setTextureAttribute(unitB, _reveal.get());
    ss->addUniform(new osg::Uniform("loa_wboitAccum", int(unitA)));
    ss->addUniform(new osg::Uniform("loa_wboitReveal", int(unitB)));
}

OITFrameStatistics WeightedBlendedOIT::getFrameStatistics() const
{
    std::lock_guard<std::mutex> lock(_impl->mutex);
    return _impl->last;
}

void WeightedBlendedOIT::releaseGLObjects(osg::State* state) const
{
    std::lock_guard<std::mutex> lock(_impl->mutex);
    for (auto& entry : _impl->contexts)
    {
        const unsigned ctx = entry.first;
        if (state && state->getContextID() != ctx) continue;
        Impl::PerContext& pc = entry.second;
        if (!pc.usable) continue;
        if (state)
        {
            if (pc.accum) glDeleteTextures(1, &pc.accum);
            if (pc.reveal) glDeleteTextures(1, &pc.reveal);
            if (pc.fbo) pc.gl.deleteFramebuffers(1, &pc.fbo);
        }
        else
        {
            detail::scheduleDeletion(detail::GL_NAME_TEXTURE, ctx, pc.accum);
            detail::scheduleDeletion(detail::GL_NAME_TEXTURE, ctx, pc.reveal);
            detail::scheduleDeletion(detail::GL_NAME_FRAMEBUFFER, ctx, pc.fbo);
        }
        static_cast<detail::ContextTexture*>(_accum.get())->setTextureName(ctx, 0);
        static_cast<detail::ContextTexture*>(_reveal.get())->setTextureName(ctx, 0);
        pc = Impl::PerContext();
    }
}

} // namespace osgLoA
