// LinkedListABuffer: per-pixel linked lists of fragments (Yang et al. 2010) built in one geometry
// pass with atomics; storage grown to the fragments of the frame (docs/abuffer.md).
#include <osgLoA/compositing/LinkedListABuffer>

#include "ContextObjects.h"

#include <osg/ColorMask>
#include <osg/Depth>
#include <osg/GL>
#include <osg/Notify>
#include <osg/State>
#include <osg/Stencil>
#include <osgUtil/RenderBin>
#include <osgUtil/RenderStage>
#include <osgUtil/StateGraph>

#include <algorithm>
#include <map>
#include <mutex>
#include <stdexcept>

#ifndef GL_R32UI
#define GL_R32UI 0x8236
#endif
#ifndef GL_RED_INTEGER
#define GL_RED_INTEGER 0x8D94
#endif
#ifndef GL_SHADER_STORAGE_BUFFER
#define GL_SHADER_STORAGE_BUFFER 0x90D2
#endif
#ifndef GL_READ_WRITE
#define GL_READ_WRITE 0x88BA
#endif
#ifndef GL_DYNAMIC_COPY
#define GL_DYNAMIC_COPY 0x88EA
#endif
#ifndef GL_FRAMEBUFFER
#define GL_FRAMEBUFFER 0x8D40
#endif
#ifndef GL_FRAMEBUFFER_DEFAULT_WIDTH
#define GL_FRAMEBUFFER_DEFAULT_WIDTH 0x9310
#define GL_FRAMEBUFFER_DEFAULT_HEIGHT 0x9311
#endif
#ifndef GL_FRAMEBUFFER_COMPLETE
#define GL_FRAMEBUFFER_COMPLETE 0x8CD5
#endif
#ifndef GL_SHADER_STORAGE_BARRIER_BIT
#define GL_SHADER_STORAGE_BARRIER_BIT 0x00002000
#endif
#ifndef GL_SHADER_IMAGE_ACCESS_BARRIER_BIT
#define GL_SHADER_IMAGE_ACCESS_BARRIER_BIT 0x00000020
#endif
#ifndef GL_BUFFER_UPDATE_BARRIER_BIT
#define GL_BUFFER_UPDATE_BARRIER_BIT 0x00000200
#endif
#ifndef GL_MULTISAMPLE
#define GL_MULTISAMPLE 0x809D
#endif
#ifndef GL_NONE
#define GL_NONE 0
#endif

namespace osgLoA
{

namespace
{
struct GLFunctions
{
    void(GL_APIENTRY* createTextures)(GLenum, GLsizei, GLuint*) = nullptr;
    void(GL_APIENTRY* textureStorage2D)(GLuint, GLsizei, GLenum, GLsizei, GLsizei) = nullptr;
    void(GL_APIENTRY* clearTexSubImage)(GLuint, GLint, GLint, GLint, GLint, GLsizei, GLsizei, GLsizei, GLenum,
                                        GLenum, const void*) = nullptr;
    void(GL_APIENTRY* createBuffers)(GLsizei, GLuint*) = nullptr;
    void(GL_APIENTRY* namedBufferData)(GLuint, GLsizeiptr, const void*, GLenum) = nullptr;
    void(GL_APIENTRY* namedBufferSubData)(GLuint, GLintptr, GLsizeiptr, const void*) = nullptr;
    void(GL_APIENTRY* getNamedBufferSubData)(GLuint, GLintptr, GLsizeiptr, void*) = nullptr;
    void(GL_APIENTRY* deleteBuffers)(GLsizei, const GLuint*) = nullptr;
    void(GL_APIENTRY* bindBufferBase)(GLenum, GLuint, GLuint) = nullptr;
    void(GL_APIENTRY* bindImageTexture)(GLuint, GLuint, GLint, GLboolean, GLint, GLenum, GLenum) = nullptr;
    void(GL_APIENTRY* memoryBarrier)(GLbitfield) = nullptr;
    void(GL_APIENTRY* createFramebuffers)(GLsizei, GLuint*) = nullptr;
    void(GL_APIENTRY* namedFramebufferParameteri)(GLuint, GLenum, GLint) = nullptr;
    void(GL_APIENTRY* namedFramebufferDrawBuffer)(GLuint, GLenum) = nullptr;
    GLenum(GL_APIENTRY* checkNamedFramebufferStatus)(GLuint, GLenum) = nullptr;
    void(GL_APIENTRY* bindFramebuffer)(GLenum, GLuint) = nullptr;
    void(GL_APIENTRY* deleteFramebuffers)(GLsizei, const GLuint*) = nullptr;

    bool loadAll()
    {
        bool ok = true;
        ok &= detail::loadGLFunction(createTextures, "glCreateTextures");
        ok &= detail::loadGLFunction(textureStorage2D, "glTextureStorage2D");
        ok &= detail::loadGLFunction(clearTexSubImage, "glClearTexSubImage");
        ok &= detail::loadGLFunction(createBuffers, "glCreateBuffers");
        ok &= detail::loadGLFunction(namedBufferData, "glNamedBufferData");
        ok &= detail::loadGLFunction(namedBufferSubData, "glNamedBufferSubData");
        ok &= detail::loadGLFunction(getNamedBufferSubData, "glGetNamedBufferSubData");
        ok &= detail::loadGLFunction(deleteBuffers, "glDeleteBuffers");
        ok &= detail::loadGLFunction(bindBufferBase, "glBindBufferBase");
        ok &= detail::loadGLFunction(bindImageTexture, "glBindImageTexture");
        ok &= detail::loadGLFunction(memoryBarrier, "glMemoryBarrier");
        ok &= detail::loadGLFunction(createFramebuffers, "glCreateFramebuffers");
        ok &= detail::loadGLFunction(namedFramebufferParameteri, "glNamedFramebufferParameteri");
        ok &= detail::loadGLFunction(namedFramebufferDrawBuffer, "glNamedFramebufferDrawBuffer");
        ok &= detail::loadGLFunction(checkNamedFramebufferStatus, "glCheckNamedFramebufferStatus");
        ok &= detail::loadGLFunction(bindFramebuffer, "glBindFramebuffer");
        ok &= detail::loadGLFunction(deleteFramebuffers, "glDeleteFramebuffers");
        return ok;
    }
};
} // namespace

struct LinkedListABuffer::Impl
{
    struct PerContext
    {
        bool initialised = false;
        bool usable = false;
        GLFunctions gl;
        GLuint heads = 0, nodes = 0, counter = 0, fbo = 0;
        int width = 0, height = 0;
        std::uint64_t capacity = 0; // nodes
    };

    /** Binds the head image and the two buffers of the context (routing and resolve). */
    class Bindings : public osg::StateAttribute
    {
    public:
        Bindings() = default;
        explicit Bindings(Impl* impl) : _impl(impl) {}
        Bindings(const Bindings& o, const osg::CopyOp& op = osg::CopyOp::SHALLOW_COPY)
            : osg::StateAttribute(o, op), _impl(o._impl)
        {
        }
        META_StateAttribute(osgLoA, Bindings,
                            osg::StateAttribute::Type(osg::StateAttribute::CAPABILITY + 31));
        int compare(const osg::StateAttribute& sa) const override
        {
            COMPARE_StateAttribute_Types(Bindings, sa) COMPARE_StateAttribute_Parameter(_impl) return 0;
        }
        void apply(osg::State& state) const override
        {
            if (!_impl) return;
            PerContext& pc = _impl->context(state.getContextID());
            if (!pc.usable || !pc.heads) return;
            pc.gl.bindImageTexture(kHeadImageUnit, pc.heads, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
            pc.gl.bindBufferBase(GL_SHADER_STORAGE_BUFFER, kNodeBinding, pc.nodes);
            pc.gl.bindBufferBase(GL_SHADER_STORAGE_BUFFER, kCounterBinding, pc.counter);
        }

        /** The A-buffer is gone: bind nothing (StateSets may keep this attribute longer). */
        void detach() { _impl = nullptr; }

    private:
        Impl* _impl = nullptr;
    };

    explicit Impl(LinkedListABuffer* o) : owner(o) {}
    LinkedListABuffer* owner;
    std::mutex mutex;
    std::map<unsigned, PerContext> contexts;
    OITFrameStatistics last;
    bool warned = false;
    osg::ref_ptr<Bindings> bindings;
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
        pc.usable = detail::usableWithGL45("LinkedListABuffer",
                                           "image load/store, shader storage buffers, direct state access, "
                                           "framebuffers without attachments",
                                           pc.gl.loadAll(), warned);
        if (!pc.usable) return;
        pc.gl.createFramebuffers(1, &pc.fbo);
        pc.gl.namedFramebufferDrawBuffer(pc.fbo, GL_NONE);
        pc.gl.createBuffers(1, &pc.counter);
        const GLuint zero[2] = {0, 0};
        pc.gl.namedBufferData(pc.counter, sizeof(zero), zero, GL_DYNAMIC_COPY);
    }

    void allocateHeads(PerContext& pc, int w, int h)
    {
        if (pc.heads && pc.width == w && pc.height == h) return;
        if (pc.heads) glDeleteTextures(1, &pc.heads);
        pc.gl.createTextures(GL_TEXTURE_2D, 1, &pc.heads);
        pc.gl.textureStorage2D(pc.heads, 1, GL_R32UI, w, h);
        pc.width = w;
        pc.height = h;
        pc.gl.namedFramebufferParameteri(pc.fbo, GL_FRAMEBUFFER_DEFAULT_WIDTH, w);
        pc.gl.namedFramebufferParameteri(pc.fbo, GL_FRAMEBUFFER_DEFAULT_HEIGHT, h);
        const GLenum status = pc.gl.checkNamedFramebufferStatus(pc.fbo, GL_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE)
            OSG_WARN << "osgLoA::LinkedListABuffer: framebuffer without attachments incomplete (0x"
                     << std::hex << status << std::dec << ") at " << w << "x" << h << std::endl;
    }

    void allocateNodes(PerContext& pc, std::uint64_t nodes)
    {
        if (pc.nodes && pc.capacity == nodes) return;
        if (!pc.nodes) pc.gl.createBuffers(1, &pc.nodes);
        pc.gl.namedBufferData(pc.nodes, GLsizeiptr(nodes * kBytesPerNode), nullptr, GL_DYNAMIC_COPY);
        pc.capacity = nodes;
    }

    void drawPasses(osgUtil::RenderBin& bin, osg::RenderInfo& ri, osgUtil::RenderLeaf*& previous);
};

void LinkedListABuffer::Impl::drawPasses(osgUtil::RenderBin& bin, osg::RenderInfo& ri,
                                         osgUtil::RenderLeaf*& previous)
{
    osg::State& state = *ri.getState();
    PerContext& pc = context(state.getContextID());
    if (!pc.initialised) initialise(pc);
    RoutedFrame frame;
    if (!owner->beginRoutedFrame(bin, ri, previous, *passViewport, routing.get(), frame) || !pc.usable)
        return;
    const RoutedRegion& region = frame.region;
    OITFrameStatistics& st = frame.stats;
    const int w = frame.width, h = frame.height;
    const GLuint defaultFbo = frame.defaultFbo;
    if (!region.isEmpty())
    {
        allocateHeads(pc, w, h);
        const std::uint64_t limit =
            std::max<std::uint64_t>(region.countPixels(), owner->_maxBytes / kBytesPerNode);
        if (!pc.nodes) allocateNodes(pc, std::min(limit, std::max<std::uint64_t>(region.countPixels(), 1)));
        pc.gl.bindFramebuffer(GL_FRAMEBUFFER, pc.fbo);
        for (int attempt = 0;; ++attempt)
        {
            // Empty lists in the region; the counter at 0 and the capacity the shaders check.
            const GLuint end = 0xFFFFFFFFu;
            for (const RoutedRegion::Rect& r : region.rectangles())
                pc.gl.clearTexSubImage(pc.heads, 0, r.x, r.y, 0, r.width, r.height, 1, GL_RED_INTEGER,
                                       GL_UNSIGNED_INT, &end);
            const GLuint header[2] = {0, GLuint(std::min<std::uint64_t>(pc.capacity, 0xFFFFFFFEu))};
            pc.gl.namedBufferSubData(pc.counter, 0, sizeof(header), header);
            pc.gl.memoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                                GL_BUFFER_UPDATE_BARRIER_BIT);
            bindings->apply(state);
            LinkedListABuffer::drawLeaves(bin, ri, previous);
            pc.gl.memoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                                GL_BUFFER_UPDATE_BARRIER_BIT);
            GLuint count = 0;
            pc.gl.getNamedBufferSubData(pc.counter, 0, sizeof(count), &count);
            st.fragments = count;
            ++st.geometryPasses;
            if (count <= pc.capacity) break;
            if (pc.capacity >= limit || attempt > 0)
            {
                st.truncated = true;
                break;
            }
            // Grow to the frame's fragments and a quarter more, and draw the pass again.
            allocateNodes(pc, std::min(limit, std::uint64_t(count) + std::uint64_t(count) / 4));
            ++st.discardedPasses;
            --st.geometryPasses;
        }
        pc.gl.bindFramebuffer(GL_FRAMEBUFFER, defaultFbo);
    }
    else
        pc.gl.bindFramebuffer(GL_FRAMEBUFFER, defaultFbo);
    st.bytes = std::uint64_t(pc.width) * std::uint64_t(pc.height) * 4u + pc.capacity * kBytesPerNode + 8u;
    state.haveAppliedAttribute(bindings->getType(), bindings->getMember());
    std::lock_guard<std::mutex> lock(mutex);
    last = st;
}

// ------------------------------------------------------------------------------------------

LinkedListABuffer::LinkedListABuffer(int maxFragments)
    : OrderIndependentTransparency("LinkedListABuffer", kRenderBinNumber)
{
    setMaxFragments(maxFragments);
    _impl = new Impl(this);
    _impl->bindings = new Impl::Bindings(_impl);
    const auto force =
        osg::StateAttribute::ON | osg::StateAttribute::OVERRIDE | osg::StateAttribute::PROTECTED;
    const auto forceOff =
        osg::StateAttribute::OFF | osg::StateAttribute::OVERRIDE | osg::StateAttribute::PROTECTED;
    osg::ref_ptr<osg::StateSet> rs = new osg::StateSet;
    rs->setAttributeAndModes(new osg::Depth(osg::Depth::ALWAYS, 0.0, 1.0, false), forceOff);
    rs->setAttributeAndModes(new osg::ColorMask(false, false, false, false), force);
    rs->setMode(GL_STENCIL_TEST, forceOff);
    rs->setMode(GL_BLEND, forceOff);
    rs->setMode(GL_MULTISAMPLE, forceOff);
    rs->setAttribute(_impl->bindings.get(), force);
    rs->setAttribute(_impl->passViewport.get());
    _impl->routing = rs;
}

LinkedListABuffer::~LinkedListABuffer()
{
    releaseGLObjects(nullptr);
    _impl->bindings->detach();
    delete _impl;
}

void LinkedListABuffer::setMaxFragments(int n)
{
    if (n < 1 || n > 64)
        throw std::invalid_argument("linked-list A-buffer: fragments per pixel " + std::to_string(n) +
                                    " outside 1..64");
    _maxFragments = n;
    updateDefines();
}

void LinkedListABuffer::drawRouted(osgUtil::RenderBin& bin, osg::RenderInfo& ri,
                                   osgUtil::RenderLeaf*& previous)
{
    _impl->drawPasses(bin, ri, previous);
}

void LinkedListABuffer::bindTarget(osg::RenderInfo& ri)
{
    Impl::PerContext& pc = _impl->context(ri.getState()->getContextID());
    if (!pc.initialised) _impl->initialise(pc);
    if (pc.usable) pc.gl.bindFramebuffer(GL_FRAMEBUFFER, pc.fbo);
}

void LinkedListABuffer::addResolveState(osg::StateSet* ss, unsigned, unsigned)
{
    ss->setAttribute(_impl->bindings.get());
}

OITFrameStatistics LinkedListABuffer::getFrameStatistics() const
{
    std::lock_guard<std::mutex> lock(_impl->mutex);
    return _impl->last;
}

void LinkedListABuffer::releaseGLObjects(osg::State* state) const
{
    std::lock_guard<std::mutex> lock(_impl->mutex);
    for (auto& entry : _impl->contexts)
    {
        if (state && state->getContextID() != entry.first) continue;
        Impl::PerContext& pc = entry.second;
        if (!pc.usable) continue;
        if (state)
        {
            // The context is current: delete now.
            if (pc.heads) glDeleteTextures(1, &pc.heads);
            const GLuint buffers[2] = {pc.nodes, pc.counter};
            pc.gl.deleteBuffers(2, buffers);
            if (pc.fbo) pc.gl.deleteFramebuffers(1, &pc.fbo);
        }
        else
        {
            const unsigned ctx = entry.first;
            detail::scheduleDeletion(detail::GL_NAME_TEXTURE, ctx, pc.heads);
            detail::scheduleDeletion(detail::GL_NAME_BUFFER, ctx, pc.nodes);
            detail::scheduleDeletion(detail::GL_NAME_BUFFER, ctx, pc.counter);
            detail::scheduleDeletion(detail::GL_NAME_FRAMEBUFFER, ctx, pc.fbo);
        }
        pc = Impl::PerContext();
    }
}

} // namespace osgLoA
