// OrderIndependentTransparency: what the three OIT methods share (the routed camera and render
// bin, the resolve node, method names); docs/abuffer.md.
#include <osgLoA/compositing/LinkedListABuffer>
#include <osgLoA/compositing/OrderIndependentTransparency>
#include <osgLoA/compositing/StencilRoutedABuffer>
#include <osgLoA/compositing/WeightedBlendedOIT>
#include <osgLoA/render/ShaderLibrary>

#include "ContextObjects.h"
#include "RenderTarget.h"

#include <osg/BlendFunc>
#include <osg/Depth>
#include <osg/GL>
#include <osg/Scissor>
#include <osg/State>
#include <osgUtil/RenderBin>
#include <osgUtil/RenderStage>
#include <osgUtil/StateGraph>

#include <osg/GLExtensions>

#include <algorithm>
#include <atomic>
#include <map>
#include <mutex>
#include <stdexcept>

namespace osgLoA
{

namespace
{
std::atomic<unsigned> g_instances{0};

/** The render bin of the routed geometry: its draw runs the method's passes. */
class RoutingBin : public osgUtil::RenderBin
{
public:
    RoutingBin() = default;
    explicit RoutingBin(OrderIndependentTransparency* owner) : _owner(owner) {}
    RoutingBin(const RoutingBin& o, const osg::CopyOp& op = osg::CopyOp::SHALLOW_COPY)
        : osgUtil::RenderBin(o, op), _owner(o._owner)
    {
    }
    META_Object(osgLoA, RoutingBin);

    void drawImplementation(osg::RenderInfo& ri, osgUtil::RenderLeaf*& previous) override
    {
        osg::ref_ptr<OrderIndependentTransparency> owner;
        if (_owner.lock(owner))
            owner->drawRoutedTimed(*this, ri, previous);
        else
            osgUtil::RenderBin::drawImplementation(ri, previous);
    }
    void drawBase(osg::RenderInfo& ri, osgUtil::RenderLeaf*& previous)
    {
        osgUtil::RenderBin::drawImplementation(ri, previous);
    }

private:
    osg::observer_ptr<OrderIndependentTransparency> _owner;
};

/** The camera's initial draw callback: binds the method's framebuffer before the stage draws. */
class BindTarget : public osg::Camera::DrawCallback
{
public:
    explicit BindTarget(OrderIndependentTransparency* owner) : _owner(owner) {}
    void operator()(osg::RenderInfo& ri) const override
    {
        osg::ref_ptr<OrderIndependentTransparency> owner;
        if (_owner.lock(owner)) owner->bindTarget(ri);
    }

private:
    osg::observer_ptr<OrderIndependentTransparency> _owner;
};
} // namespace

#ifndef GL_TIME_ELAPSED
#define GL_TIME_ELAPSED 0x88BF
#endif
#ifndef GL_QUERY_RESULT
#define GL_QUERY_RESULT 0x8866
#endif
#ifndef GL_QUERY_RESULT_AVAILABLE
#define GL_QUERY_RESULT_AVAILABLE 0x8867
#endif

/** GL_TIME_ELAPSED queries around the routed passes, two per context (one in flight while the
 *  previous frame's is read back without waiting). */
struct OrderIndependentTransparency::Timer
{
    struct PerContext
    {
        bool initialised = false, usable = false;
        GLuint queries[2] = {0, 0};
        unsigned frames[2] = {0, 0};
        bool pending[2] = {false, false};
        int next = 0;
        void(GL_APIENTRY* genQueries)(GLsizei, GLuint*) = nullptr;
        void(GL_APIENTRY* beginQuery)(GLenum, GLuint) = nullptr;
        void(GL_APIENTRY* endQuery)(GLenum) = nullptr;
        void(GL_APIENTRY* getQueryObjectui64v)(GLuint, GLenum, GLuint64*) = nullptr;
        void(GL_APIENTRY* getQueryObjectuiv)(GLuint, GLenum, GLuint*) = nullptr;
    };
    std::mutex mutex;
    std::map<unsigned, PerContext> contexts;
    double milliseconds = -1.0;
    unsigned frame = 0;
};

void OrderIndependentTransparency::drawRoutedTimed(osgUtil::RenderBin& bin, osg::RenderInfo& ri,
                                                   osgUtil::RenderLeaf*& previous)
{
    osg::State& state = *ri.getState();
    Timer::PerContext* pc;
    {
        std::lock_guard<std::mutex> lock(_timer->mutex);
        pc = &_timer->contexts[state.getContextID()];
    }
    if (!pc->initialised)
    {
        pc->initialised = true;
        auto load = [](auto& f, const char* name)
        {
            f = reinterpret_cast<std::remove_reference_t<decltype(f)>>(osg::getGLExtensionFuncPtr(name));
            return f != nullptr;
        };
        pc->usable = load(pc->genQueries, "glGenQueries") && load(pc->beginQuery, "glBeginQuery") &&
                     load(pc->endQuery, "glEndQuery") &&
                     load(pc->getQueryObjectui64v, "glGetQueryObjectui64v") &&
                     load(pc->getQueryObjectuiv, "glGetQueryObjectuiv");
        if (pc->usable) pc->genQueries(2, pc->queries);
    }
    if (!pc->usable)
    {
        drawRouted(bin, ri, previous);
        return;
    }
    // Earlier frames' results, where they have come back.
    for (int q = 0; q < 2; ++q)
    {
        if (!pc->pending[q]) continue;
        GLuint available = 0;
        pc->getQueryObjectuiv(pc->queries[q], GL_QUERY_RESULT_AVAILABLE, &available);
        if (!available && q != pc->next) continue;
        GLuint64 ns = 0;
        pc->getQueryObjectui64v(pc->queries[q], GL_QUERY_RESULT, &ns); // waits only for the slot reused now
        pc->pending[q] = false;
        std::lock_guard<std::mutex> lock(_timer->mutex);
        if (pc->frames[q] >= _timer->frame || _timer->milliseconds < 0.0)
        {
            _timer->milliseconds = double(ns) / 1e6;
            _timer->frame = pc->frames[q];
        }
    }
    const int q = pc->next;
    pc->next = 1 - q;
    pc->frames[q] = state.getFrameStamp() ? state.getFrameStamp()->getFrameNumber() : 0;
    pc->beginQuery(GL_TIME_ELAPSED, pc->queries[q]);
    drawRouted(bin, ri, previous);
    pc->endQuery(GL_TIME_ELAPSED);
    pc->pending[q] = true;
}

double OrderIndependentTransparency::getRoutedMilliseconds(unsigned* frameNumber) const
{
    std::lock_guard<std::mutex> lock(_timer->mutex);
    if (frameNumber) *frameNumber = _timer->frame;
    return _timer->milliseconds;
}

const char* OrderIndependentTransparency::methodName(Method m)
{
    switch (m)
    {
    case STENCIL_ROUTED:
        return "stencil-routed";
    case LINKED_LIST:
        return "linked-list";
    case WEIGHTED_BLENDED:
        return "weighted-blended";
    }
    return "unknown";
}

std::vector<OrderIndependentTransparency::Method> OrderIndependentTransparency::methods()
{
    return {STENCIL_ROUTED, LINKED_LIST, WEIGHTED_BLENDED};
}

OrderIndependentTransparency::Method OrderIndependentTransparency::methodFromName(const std::string& name)
{
    std::string known;
    for (Method m : methods())
    {
        if (name == methodName(m)) return m;
        known += std::string(known.empty() ? "" : ", ") + methodName(m);
    }
    throw std::invalid_argument("unknown order-independent transparency method '" + name +
                                "' (known: " + known + ")");
}

osg::ref_ptr<OrderIndependentTransparency> OrderIndependentTransparency::create(Method m, int samples,
                                                                                int maxPasses)
{
    switch (m)
    {
    case STENCIL_ROUTED:
        return new StencilRoutedABuffer(samples, maxPasses);
    case LINKED_LIST:
        return new LinkedListABuffer(std::max(1, samples) * std::max(1, maxPasses));
    case WEIGHTED_BLENDED:
        return new WeightedBlendedOIT;
    }
    throw std::invalid_argument("unknown order-independent transparency method " + std::to_string(int(m)));
}

OrderIndependentTransparency::OrderIndependentTransparency(const std::string& name, int renderBinNumber)
    : _timer(new Timer)
{
    _binName = "loa_oit_" + std::to_string(g_instances.fetch_add(1));
    _camera = new osg::Camera;
    _camera->setName(name);
    _camera->setRenderOrder(osg::Camera::PRE_RENDER);
    _camera->setReferenceFrame(osg::Transform::RELATIVE_RF);
    _camera->setViewMatrix(osg::Matrix::identity());
    _camera->setProjectionMatrix(osg::Matrix::identity());
    _camera->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    _camera->setClearMask(0);
    _camera->setAllowEventFocus(false);
    _camera->setInitialDrawCallback(new BindTarget(this));

    _routedGroup = new osg::Group;
    _routedGroup->setName(name + " routed");
    _routedStateSet = _routedGroup->getOrCreateStateSet();
    _routedStateSet->setRenderBinDetails(renderBinNumber, _binName,
                                         osg::StateSet::OVERRIDE_RENDERBIN_DETAILS);
    _camera->addChild(_routedGroup.get());

    _regionImage = new osg::Image;
    _regionImage->allocateImage(kMaskTiles, kMaskTiles, 1, GL_RED, GL_UNSIGNED_BYTE);
    _regionImage->setInternalTextureFormat(GL_R8);
    std::fill(_regionImage->data(), _regionImage->data() + kMaskTiles * kMaskTiles, 0);
    _regionImage->setDataVariance(osg::Object::DYNAMIC);
    _regionTexture = new osg::Texture2D(_regionImage.get());
    _regionTexture->setFilter(osg::Texture::MIN_FILTER, osg::Texture::NEAREST);
    _regionTexture->setFilter(osg::Texture::MAG_FILTER, osg::Texture::NEAREST);
    _regionTexture->setResizeNonPowerOfTwoHint(false);
    _regionTexture->setUnRefImageDataAfterApply(false);
    _regionTexture->setDataVariance(osg::Object::DYNAMIC);
    _regionUniform = new osg::Uniform("loa_abufferRegion", 0, 0, 0);
    _regionUniform->setDataVariance(osg::Object::DYNAMIC);

    _binPrototype = new RoutingBin(this);
    osgUtil::RenderBin::addRenderBinPrototype(_binName, _binPrototype.get());
}

OrderIndependentTransparency::~OrderIndependentTransparency()
{
    osgUtil::RenderBin::removeRenderBinPrototype(_binPrototype.get());
    for (auto& entry : _timer->contexts)
        for (GLuint q : entry.second.queries)
            detail::scheduleDeletion(detail::GL_NAME_QUERY, entry.first, q);
    delete _timer;
}

void OrderIndependentTransparency::drawLeaves(osgUtil::RenderBin& bin, osg::RenderInfo& ri,
                                              osgUtil::RenderLeaf*& previous)
{
    static_cast<RoutingBin&>(bin).drawBase(ri, previous);
    // Back to the root of the state graph, so that the next pass starts as the first did.
    if (previous)
    {
        osgUtil::StateGraph::moveToRootStateGraph(*ri.getState(), previous->_parent->_parent);
        previous = nullptr;
    }
}

void OrderIndependentTransparency::setSize(int width, int height)
{
    if (width == _width && height == _height) return;
    _width = std::max(0, width);
    _height = std::max(0, height);
    if (_width > 0 && _height > 0)
        _camera->setViewport(0, 0, _width, _height);
    else
        _camera->setViewport(nullptr);
}

void OrderIndependentTransparency::addRegionState(osg::StateSet* ss, unsigned unit)
{
    ss->setTextureAttribute(unit, _regionTexture.get());
    ss->addUniform(new osg::Uniform("loa_abufferRegionMask", int(unit)));
    ss->addUniform(_regionUniform.get());
}

RoutedRegion OrderIndependentTransparency::updateRegion(const osgUtil::RenderBin& bin,
                                                        const osg::Viewport& vp)
{
    RoutedRegion region(int(vp.x()), int(vp.y()), int(vp.width()), int(vp.height()), kTileSize);
    if (_restrictToRegion)
        region.addRenderBin(bin);
    else
        region.addAll();
    const bool masked =
        _restrictToRegion && region.getColumns() <= kMaskTiles && region.getRows() <= kMaskTiles;
    if (masked)
    {
        // Uploaded again only when the tiles changed (a still camera keeps the same mask).
        unsigned char* d = _regionImage->data();
        const std::vector<std::uint8_t>& m = region.getMask();
        const int cols = region.getColumns();
        bool changed = false;
        for (int r = 0; r < kMaskTiles && !changed; ++r)
            for (int c = 0; c < kMaskTiles && !changed; ++c)
            {
                const std::uint8_t want = r < region.getRows() && c < cols ? m[std::size_t(r * cols + c)] : 0;
                changed = d[r * kMaskTiles + c] != want;
            }
        if (changed)
        {
            std::fill(d, d + kMaskTiles * kMaskTiles, 0);
            for (int r = 0; r < region.getRows(); ++r)
                std::copy(m.begin() + r * cols, m.begin() + (r + 1) * cols, d + r * kMaskTiles);
            _regionImage->dirty();
        }
    }
    _regionUniform->set(int(vp.x()), int(vp.y()), masked ? kTileSize : 0);
    return region;
}

bool OrderIndependentTransparency::beginRoutedFrame(osgUtil::RenderBin& bin, osg::RenderInfo& ri,
                                                    osgUtil::RenderLeaf*& previous,
                                                    osg::Viewport& passViewport, osg::StateSet* routing,
                                                    RoutedFrame& frame)
{
    osg::State& state = *ri.getState();
    if (previous)
    {
        osgUtil::StateGraph::moveToRootStateGraph(state, previous->_parent->_parent);
        previous = nullptr;
    }
    // The stage's viewport (the camera's or the one it inherits), not osg::State's current one,
    // which an earlier StateSet may have reset to osg::Viewport's default 800 x 600.
    const osgUtil::RenderStage* stage = bin.getStage();
    const osg::Viewport* vp =
        stage && stage->getViewport() ? stage->getViewport() : state.getCurrentViewport();
    if (!vp || vp->width() <= 0 || vp->height() <= 0) return false;
    frame.width = int(vp->x() + vp->width());
    frame.height = int(vp->y() + vp->height());
    passViewport.setViewport(vp->x(), vp->y(), vp->width(), vp->height());
    state.haveAppliedAttribute(osg::StateAttribute::VIEWPORT);
    if (routing) bin.setStateSet(routing);
    frame.region = updateRegion(bin, *vp);
    fillRegionStatistics(frame.stats, frame.region);
    frame.stats.frameNumber = state.getFrameStamp() ? state.getFrameStamp()->getFrameNumber() : 0;
    frame.stats.width = frame.width;
    frame.stats.height = frame.height;
    frame.defaultFbo = state.getGraphicsContext() ? state.getGraphicsContext()->getDefaultFboId() : 0;
    return true;
}

void OrderIndependentTransparency::forEachRectangle(osg::State& state, const RoutedRegion& region,
                                                    const std::function<void()>& f)
{
    glEnable(GL_SCISSOR_TEST);
    for (const RoutedRegion::Rect& r : region.rectangles())
    {
        glScissor(r.x, r.y, r.width, r.height);
        f();
    }
    glDisable(GL_SCISSOR_TEST);
    state.haveAppliedMode(GL_SCISSOR_TEST, osg::StateAttribute::OFF);
    state.haveAppliedAttribute(osg::StateAttribute::SCISSOR);
}

void OrderIndependentTransparency::fillRegionStatistics(OITFrameStatistics& st,
                                                        const RoutedRegion& region) const
{
    st.regionTiles = region.countTiles();
    st.viewportTiles = region.getColumns() * region.getRows();
    st.regionPixels = region.countPixels();
}

void OrderIndependentTransparency::setMaxFragmentsDefine(osg::StateSet* ss, int extra)
{
    _defineStateSets.emplace_back(ss, extra);
    updateDefines();
}

void OrderIndependentTransparency::updateDefines()
{
    for (auto& d : _defineStateSets)
    {
        osg::ref_ptr<osg::StateSet> ss;
        if (d.first.lock(ss))
            ss->setDefine("LOA_MAX_FRAGMENTS", std::to_string(getMaxFragments() + d.second));
    }
}

osg::ref_ptr<osg::Node> OrderIndependentTransparency::createResolveNode(float mergeEpsilon, unsigned unitA,
                                                                        unsigned unitB, unsigned regionUnit)
{
    osg::ref_ptr<osg::Geometry> quad = detail::createFullScreenTriangle();
    quad->setName(_camera->getName() + " resolve");
    osg::StateSet* ss = quad->getOrCreateStateSet();
    ss->setAttribute(
        ShaderLibrary::createProgram(std::string("resolve ") + methodName(getMethod()),
                                     {"loa_abuffer_fullscreen.vert.glsl", "loa_abuffer_resolve.frag.glsl",
                                      getFetchShaderName(), "loa_abuffer_resolve_main.frag.glsl"})
            .get());
    addResolveState(ss, unitA, unitB);
    addRegionState(ss, regionUnit);
    setMaxFragmentsDefine(ss);
    ss->addUniform(new osg::Uniform("loa_abufferMergeEpsilon", mergeEpsilon));
    ss->setAttributeAndModes(new osg::BlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA), osg::StateAttribute::ON);
    ss->setAttribute(new osg::Depth(osg::Depth::ALWAYS, 0.0, 1.0, false));
    ss->setMode(GL_DEPTH_TEST, osg::StateAttribute::OFF);
    ss->setMode(GL_CULL_FACE, osg::StateAttribute::OFF);
    ss->setRenderBinDetails(100, "RenderBin");
    return quad;
}

osg::ref_ptr<osg::Program> OrderIndependentTransparency::createVertexColorProgram(const char* writeShaderName)
{
    osg::ref_ptr<osg::Program> p = ShaderLibrary::createProgram(
        std::string("vertex colour ") + writeShaderName, {"loa_plain.vert.glsl", writeShaderName});
    p->addShader(new osg::Shader(osg::Shader::FRAGMENT, "#version 450 compatibility\n"
                                                        "in vec4 loa_color;\n"
                                                        "void loa_abufferWrite(vec4 straightAlphaColor);\n"
                                                        "void main() { loa_abufferWrite(loa_color); }\n"));
    return p;
}

osg::ref_ptr<osg::Program> OrderIndependentTransparency::createVertexColorProgramForMethod() const
{
    return createVertexColorProgram(getWriteShaderName());
}

} // namespace osgLoA
