/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/DeferredTexturing>

#include "../compositing/RenderTarget.h"
#include "../render/GLProgramBuild.h"
#include <osgLoA/render/ShaderLibrary>
#include <osgLoA/styles/GraphicStyle>
#include <osgLoA/util/StateSetVisitor>

#include <osg/BufferIndexBinding>
#include <osg/BufferObject>
#include <osg/Depth>
#include <osg/GLExtensions>
#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Notify>
#include <osg/Program>
#include <osgUtil/CullVisitor>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <stdexcept>

#ifndef GL_COMPUTE_SHADER
#define GL_COMPUTE_SHADER 0x91B9
#endif
#ifndef GL_SHADER_STORAGE_BUFFER
#define GL_SHADER_STORAGE_BUFFER 0x90D2
#endif
#ifndef GL_SHADER_STORAGE_BARRIER_BIT
#define GL_SHADER_STORAGE_BARRIER_BIT 0x00002000
#endif
#ifndef GL_BUFFER_UPDATE_BARRIER_BIT
#define GL_BUFFER_UPDATE_BARRIER_BIT 0x00000200
#endif
#ifndef GL_READ_ONLY
#define GL_READ_ONLY 0x88B8
#endif
#ifndef GL_CURRENT_PROGRAM
#define GL_CURRENT_PROGRAM 0x8B8D
#endif
#ifndef GL_DYNAMIC_READ
#define GL_DYNAMIC_READ 0x88E9
#endif
#ifndef GL_DYNAMIC_DRAW
#define GL_DYNAMIC_DRAW 0x88E8
#endif
#ifndef GL_STATIC_DRAW
#define GL_STATIC_DRAW 0x88E4
#endif

namespace osgLoA
{

namespace
{
/** Render order of the G-buffer camera among pre-render cameras (after the distance field's
 *  jump-flooding passes, which count from 0). */
constexpr int kGBufferRenderOrder = 100;
/** Texture units of the shading pass. */
constexpr int kSourceAtlasUnit = 4, kFilteredAtlasUnit = 5;
/** SSBO bindings of the shading pass (the filtering stage uses 0-2). */
constexpr unsigned kPageBinding = 4, kRegionBinding = 5, kTileStateBinding = 6;

/** The projection with near and far planes fitted to a view-space sphere (depth precision of
 *  the G-buffer), keeping the frustum's x/y extent. */
osg::Matrixd fitDepthRange(const osg::Matrixd& p, const osg::BoundingSphere& viewSphere)
{
    const bool orthographic = p(3, 3) == 1.0 && p(2, 3) == 0.0;
    const double zc = -viewSphere.center().z();
    double zFar = zc + viewSphere.radius(), zNear = zc - viewSphere.radius();
    double l, r, b, t, n0, f0;
    if (orthographic)
    {
        if (!(zFar > zNear)) zFar = zNear + 1.0;
        if (!p.getOrtho(l, r, b, t, n0, f0)) return p;
        return osg::Matrixd::ortho(l, r, b, t, zNear, zFar);
    }
    if (!(zFar > 0.0)) zFar = 1.0;
    zNear = std::max(zNear, zFar * 1.0e-4);
    if (!p.getFrustum(l, r, b, t, n0, f0) || !(n0 > 0.0)) return p;
    const double s = zNear / n0;
    return osg::Matrixd::frustum(l * s, r * s, b * s, t * s, zNear, zFar);
}

osg::ref_ptr<osg::ShaderStorageBufferBinding> storageBinding(unsigned index, osg::Array* array)
{
    osg::ref_ptr<osg::ShaderStorageBufferObject> sbo = new osg::ShaderStorageBufferObject;
    sbo->setUsage(GL_DYNAMIC_DRAW);
    array->setBufferObject(sbo.get());
    return new osg::ShaderStorageBufferBinding(index, array, 0, GLsizeiptr(array->getTotalDataSize()));
}

/** The child of the G-buffer camera: traversing it traverses the node's children. */
class ChildrenProxy : public osg::Node
{
public:
    explicit ChildrenProxy(DeferredTexturing* node) : _node(node) { setCullingActive(false); }
    void traverse(osg::NodeVisitor& nv) override
    {
        osg::ref_ptr<DeferredTexturing> node;
        if (_node.lock(node)) node->osg::Group::traverse(nv);
    }
    osg::BoundingSphere computeBound() const override
    {
        osg::ref_ptr<DeferredTexturing> node;
        return _node.lock(node) ? node->getBound() : osg::BoundingSphere();
    }

private:
    osg::observer_ptr<DeferredTexturing> _node;
};
} // namespace

/** Everything the node renders with: settings, the page table, the cameras and textures of the
 *  three stages, and the GL objects of the filtering stage (draw thread). */
class DeferredTexturing::Pipeline : public osg::Referenced
{
public:
    explicit Pipeline(DeferredTexturing* node);

    // Settings.
    osg::ref_ptr<ImageFilter> filter;
    Mode mode = PER_FRAGMENT_CACHED;
    unsigned budgetTexels = 0;
    unsigned fadeFrames = 4;
    bool timeFiltering = false;
    float ambient = 0.35f;
    osg::Vec3f lightDirection = GraphicStyle::defaultLightDirection();

    // Scene textures.
    std::mutex tableMutex;
    osg::ref_ptr<TexturePageTable> table = new TexturePageTable;
    bool texturesDirty = true;
    unsigned tableRevision = 0; ///< counts prepare() runs that built a table

    // Geometry stage.
    osg::ref_ptr<osg::Camera> camera;
    osg::ref_ptr<osg::Texture2D> targets[NUM_GBUFFER_TARGETS];
    int width = 0, height = 0;

    // Shading stage.
    osg::ref_ptr<osg::Geode> shade;
    osg::ref_ptr<osg::Texture2D> sourceAtlas, filteredAtlas;
    osg::ref_ptr<osg::UIntArray> tileState;
    osg::ref_ptr<osg::Uniform> uFrame, uFade, uTextureCount, uOrigin, uProjectionInverse, uAmbient, uLight;

    // Filtering stage (draw thread).
    struct GLResources
    {
        unsigned contextID = ~0u;
        osg::ref_ptr<GpuFilterEngine> engine;
        std::string engineError;
        unsigned uploadedRevision = 0; ///< the table the source atlas holds (0: none)
        GLuint uploadedName = 0;       ///< ... in this GL texture
        unsigned adoptedRevision = 0;  ///< the table the engine's atlases and buffers hold
        unsigned srcAtlas = 0, dstAtlas = 0;
        GLuint srcName = 0, dstName = 0;
        GLuint prefetch = 0;
        GLuint pageBuffer = 0, regionBuffer = 0, flagBuffer = 0;
        GpuFilterEngine::TileCache cache;
        std::string cacheKey;
        unsigned frame = 0;
    } gl;
    Statistics stats;
    std::vector<GpuFilterEngine::Tile> needed;

    void prepare(DeferredTexturing& node);
    void cull(DeferredTexturing& node, osgUtil::CullVisitor& cv);
    void filterStage(osg::RenderInfo& renderInfo);
    void releaseGL(osg::State* state);

private:
    bool runFilterStage(osg::State& state, TexturePageTable& t, unsigned revision, Statistics& st);
    void uploadSource(osg::State& state, TexturePageTable& t, unsigned revision);
    void adoptAtlases(osg::State& state, TexturePageTable& t, unsigned revision);
    std::vector<GLuint> prefetchTiles(osg::State& state, TexturePageTable& t, bool markCoarser);
    void resetTileState();
};

namespace
{
/** The camera's draw callback running the filtering stage. */
class FilterStage : public osg::Camera::DrawCallback
{
public:
    explicit FilterStage(DeferredTexturing::Pipeline* p) : _pipeline(p) {}
    void operator()(osg::RenderInfo& renderInfo) const override
    {
        osg::ref_ptr<DeferredTexturing::Pipeline> p;
        if (_pipeline.lock(p)) p->filterStage(renderInfo);
    }

private:
    osg::observer_ptr<DeferredTexturing::Pipeline> _pipeline;
};

GLuint compileCompute(osg::GLExtensions* ext, const std::string& name)
{
    std::string log;
    const GLuint sh =
        detail::compileShaderStage(ext, GL_COMPUTE_SHADER, ShaderLibrary::getSource(name).text, log);
    if (!sh)
        throw GpuFilterError("DeferredTexturing: shader '" + name +
                             "' (compute stage) failed to compile: " + log);
    const GLuint p = detail::linkProgram(ext, {sh}, log);
    if (!p) throw GpuFilterError("DeferredTexturing: program '" + name + "' failed to link: " + log);
    return p;
}

void uploadBuffer(osg::GLExtensions* ext, GLuint& buffer, const std::vector<int>& data)
{
    if (!buffer) ext->glGenBuffers(1, &buffer);
    ext->glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
    std::vector<int> d = data;
    if (d.empty()) d.assign(8, 0);
    ext->glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(d.size() * sizeof(int)), d.data(), GL_STATIC_DRAW);
}

int tileTexels(const GpuFilterEngine::Region& r, int x, int y)
{
    const int T = GpuFilterEngine::TILE;
    return std::min(T, r.width - x * T) * std::min(T, r.height - y * T);
}
} // namespace

DeferredTexturing::Pipeline::Pipeline(DeferredTexturing* node)
{
    // Geometry stage: the G-buffer camera and its targets.
    camera = new osg::Camera;
    camera->setName("osgLoA.DeferredTexturing.GBuffer");
    camera->setRenderOrder(osg::Camera::PRE_RENDER, kGBufferRenderOrder);
    camera->setRenderTargetImplementation(osg::Camera::FRAME_BUFFER_OBJECT);
    camera->setReferenceFrame(osg::Transform::ABSOLUTE_RF);
    camera->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    camera->setClearColor(osg::Vec4(0.0f, 0.0f, 0.0f, -1.0f)); // TID -1 where nothing is drawn
    camera->setClearMask(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    camera->setViewport(0, 0, 1, 1);
    camera->setAllowEventFocus(false);
    camera->setImplicitBufferAttachmentMask(0, 0);
    targets[TEXCOORD] = detail::createTargetTexture(GL_RGBA32F_ARB, GL_RGBA, GL_FLOAT);
    targets[NORMAL] = detail::createTargetTexture(GL_RGBA32F_ARB, GL_RGBA, GL_FLOAT);
    targets[BASE_COLOR] = detail::createTargetTexture(GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE);
    targets[DEPTH] = detail::createTargetTexture(GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT);
    for (int t = TEXCOORD; t < DEPTH; ++t)
        camera->attach(osg::Camera::BufferComponent(osg::Camera::COLOR_BUFFER0 + t), targets[t].get());
    camera->attach(osg::Camera::DEPTH_BUFFER, targets[DEPTH].get());
    camera->addChild(new ChildrenProxy(node));
    camera->setPostDrawCallback(new FilterStage(this));
    osg::StateSet* gs = camera->getOrCreateStateSet();
    gs->setDataVariance(osg::Object::DYNAMIC);
    const auto overrideOn =
        osg::StateAttribute::ON | osg::StateAttribute::OVERRIDE | osg::StateAttribute::PROTECTED;
    gs->setAttributeAndModes(
        ShaderLibrary::createProgram("osgLoA.DeferredTexturing.gbuffer",
                                     {"loa_deferred_gbuffer.vert.glsl", "loa_deferred_gbuffer.frag.glsl"})
            .get(),
        overrideOn);
    gs->setMode(GL_BLEND,
                osg::StateAttribute::OFF | osg::StateAttribute::OVERRIDE | osg::StateAttribute::PROTECTED);
    gs->addUniform(new osg::Uniform("loa_deferredTid", -1));
    gs->addUniform(new osg::Uniform("loa_deferredTextureSize", osg::Vec2f(1.0f, 1.0f)));
    gs->addUniform(new osg::Uniform("loa_featureId", 0u));

    // Shading stage: a full-screen triangle in the culling camera.
    shade = new osg::Geode;
    shade->setName("osgLoA.DeferredTexturing.Shade");
    shade->setCullingActive(false);
    shade->addDrawable(detail::createFullScreenTriangle().get());
    osg::StateSet* ss = shade->getOrCreateStateSet();
    ss->setDataVariance(osg::Object::DYNAMIC);
    ss->setAttributeAndModes(
        ShaderLibrary::createProgram("osgLoA.DeferredTexturing.shade",
                                     {"loa_deferred_shade.vert.glsl", "loa_deferred_shade.frag.glsl"})
            .get(),
        osg::StateAttribute::ON | osg::StateAttribute::PROTECTED);
    ss->setAttributeAndModes(new osg::Depth(osg::Depth::LESS, 0.0, 1.0, true));
    ss->setMode(GL_BLEND, osg::StateAttribute::OFF);
    ss->setMode(GL_CULL_FACE, osg::StateAttribute::OFF);
    const char* samplers[] = {"loa_gTexCoord", "loa_gNormal", "loa_gBaseColor", "loa_gDepth"};
    for (int t = 0; t < NUM_GBUFFER_TARGETS; ++t)
    {
        ss->setTextureAttribute(unsigned(t), targets[t].get());
        ss->addUniform(new osg::Uniform(samplers[t], t));
    }
    ss->addUniform(new osg::Uniform("loa_sourceAtlas", kSourceAtlasUnit));
    ss->addUniform(new osg::Uniform("loa_filteredAtlas", kFilteredAtlasUnit));
    uFrame = new osg::Uniform("loa_frame", 1u);
    uFade = new osg::Uniform("loa_fadeFrames", 0u);
    uTextureCount = new osg::Uniform("loa_textureCount", 0);
    uOrigin = new osg::Uniform(osg::Uniform::INT_VEC2, "loa_viewportOrigin");
    uOrigin->set(0, 0);
    uProjectionInverse = new osg::Uniform("loa_gbufferProjectionInverse", osg::Matrixf());
    uAmbient = new osg::Uniform("loa_ambient", ambient);
    uLight = new osg::Uniform("loa_lightDirection", lightDirection);
    for (osg::Uniform* u : {uFrame.get(), uFade.get(), uTextureCount.get(), uOrigin.get(),
                            uProjectionInverse.get(), uAmbient.get(), uLight.get()})
    {
        u->setDataVariance(osg::Object::DYNAMIC);
        ss->addUniform(u);
    }
}

void DeferredTexturing::Pipeline::resetTileState()
{
    if (!tileState.valid()) return;
    std::fill(tileState->begin(), tileState->end(), 0u);
    tileState->dirty();
}

void DeferredTexturing::Pipeline::prepare(DeferredTexturing& node)
{
    std::lock_guard<std::mutex> lock(tableMutex);
    if (!texturesDirty && table->isPacked()) return;
    texturesDirty = false;
    osg::ref_ptr<TexturePageTable> t = new TexturePageTable;
    StateSetVisitor visitor(
        [&](osg::StateSet& ss)
        {
            osg::StateAttribute* attribute = ss.getTextureAttribute(0, osg::StateAttribute::TEXTURE);
            if (!attribute) return;
            auto* texture = dynamic_cast<osg::Texture2D*>(attribute);
            int tid = -1; // other texture types are drawn untextured (not inheriting a parent's TID)
            osg::Vec2f size(1.0f, 1.0f);
            try
            {
                if (!texture)
                    throw std::invalid_argument(std::string("a ") + attribute->className() +
                                                " on unit 0 is not an osg::Texture2D");
                tid = t->registerTexture(*texture, 0);
                const TexturePageTable::Entry& e = t->entries()[std::size_t(tid)];
                size.set(float(e.width), float(e.height));
            }
            catch (const std::invalid_argument& e)
            {
                OSG_WARN << "osgLoA::DeferredTexturing: " << e.what() << "; drawn untextured" << std::endl;
            }
            ss.getOrCreateUniform("loa_deferredTid", osg::Uniform::INT)->set(tid);
            ss.getOrCreateUniform("loa_deferredTextureSize", osg::Uniform::FLOAT_VEC2)->set(size);
        });
    for (unsigned i = 0; i < node.getNumChildren(); ++i)
        node.getChild(i)->accept(visitor);
    try
    {
        t->pack();
    }
    catch (const std::invalid_argument& e)
    {
        OSG_WARN << "osgLoA::DeferredTexturing: " << e.what() << "; textures are not mapped" << std::endl;
        t = new TexturePageTable;
        t->pack();
    }
    table = t;
    ++tableRevision;

    // Atlases and tables of the shading stage, sized to the new layout.
    auto atlas = [&](const char* name)
    {
        osg::ref_ptr<osg::Texture2D> a = detail::createTargetTexture(GL_RGBA32F_ARB, GL_RGBA, GL_FLOAT);
        a->setName(name);
        a->setTextureSize(t->atlasWidth(), t->atlasHeight());
        return a;
    };
    sourceAtlas = atlas("osgLoA.DeferredTexturing.sourceAtlas");
    filteredAtlas = atlas("osgLoA.DeferredTexturing.filteredAtlas");
    osg::StateSet* ss = shade->getStateSet();
    ss->setTextureAttribute(kSourceAtlasUnit, sourceAtlas.get());
    ss->setTextureAttribute(kFilteredAtlasUnit, filteredAtlas.get());
    std::vector<int> pages = t->pageTableData(), regions = t->regionTableData();
    if (pages.empty()) pages.assign(8, 0);
    if (regions.empty()) regions.assign(8, 0);
    osg::ref_ptr<osg::IntArray> pageArray = new osg::IntArray(pages.begin(), pages.end());
    osg::ref_ptr<osg::IntArray> regionArray = new osg::IntArray(regions.begin(), regions.end());
    tileState = new osg::UIntArray(unsigned(std::max<std::size_t>(t->tileCount(), 1)));
    ss->setAttribute(storageBinding(kPageBinding, pageArray.get()).get());
    ss->setAttribute(storageBinding(kRegionBinding, regionArray.get()).get());
    ss->setAttribute(storageBinding(kTileStateBinding, tileState.get()).get());
    uTextureCount->set(int(t->size()));
}

void DeferredTexturing::Pipeline::cull(DeferredTexturing& node, osgUtil::CullVisitor& cv)
{
    prepare(node);
    const osg::Viewport* vp = cv.getViewport();
    const int w = vp ? std::max(1, int(vp->width())) : 1, h = vp ? std::max(1, int(vp->height())) : 1;
    if (w != width || h != height)
    {
        for (auto& t : targets)
        {
            t->setTextureSize(w, h);
            t->dirtyTextureObject();
        }
        camera->setViewport(0, 0, w, h);
        camera->dirtyAttachmentMap();
        width = w;
        height = h;
    }
    const osg::BoundingSphere bs = node.getBound();
    if (!bs.valid()) return;
    const osg::Matrixd mv = *cv.getModelViewMatrix();
    const osg::BoundingSphere viewSphere(bs.center() * mv,
                                         bs.radius() * float(mv.getScale().length() / std::sqrt(3.0)));
    const osg::Matrixd projection = fitDepthRange(*cv.getProjectionMatrix(), viewSphere);
    camera->setViewMatrix(mv);
    camera->setProjectionMatrix(projection);
    uProjectionInverse->set(osg::Matrixf(osg::Matrixd::inverse(projection)));
    uOrigin->set(vp ? int(vp->x()) : 0, vp ? int(vp->y()) : 0);
    uAmbient->set(ambient);
    uLight->set(lightDirection);
    // The shading variant: the filtered atlas where the filtering stage works (its last frame
    // had no error), with the progressive fallback when a budget leaves tiles for later.
    const bool filtered = filter.valid() && table->size() > 0 && stats.error.empty();
    osg::StateSet* ss = shade->getStateSet();
    ss->setDefine("LOA_DEFERRED_FILTERED", filtered ? osg::StateAttribute::ON : osg::StateAttribute::OFF);
    ss->setDefine("LOA_DEFERRED_PROGRESSIVE",
                  filtered && budgetTexels > 0 ? osg::StateAttribute::ON : osg::StateAttribute::OFF);
    camera->accept(cv);
    // The children are drawn by the pass camera only; the culling camera's near and far planes
    // must still cover them (the shading pass writes their depth).
    osg::BoundingBox box;
    box.expandBy(bs);
    cv.updateCalculatedNearFar(mv, box);
    shade->accept(cv);
}

void DeferredTexturing::Pipeline::uploadSource(osg::State& state, TexturePageTable& t, unsigned revision)
{
    // Plain GL (no compute needed): the unfiltered levels are what the node maps when it cannot
    // filter.
    state.applyTextureAttribute(kSourceAtlasUnit, sourceAtlas.get());
    osg::Texture::TextureObject* so = sourceAtlas->getTextureObject(state.getContextID());
    if (!so) throw GpuFilterError("DeferredTexturing: the source atlas could not be created");
    if (gl.uploadedRevision == revision && gl.uploadedName == so->id()) return;
    GLint unpackRow = 0, unpackAlign = 4;
    glGetIntegerv(GL_UNPACK_ROW_LENGTH, &unpackRow);
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &unpackAlign);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    for (std::size_t r = 0; r < t.regions().size(); ++r) // the texture is bound on the active unit
    {
        const GpuFilterEngine::Region& reg = t.regions()[r];
        glTexSubImage2D(GL_TEXTURE_2D, 0, reg.x, reg.y, reg.width, reg.height, GL_RGBA, GL_FLOAT,
                        t.levelImage(t.textureOf(int(r)), t.levelOf(int(r))).data().data());
    }
    glPixelStorei(GL_UNPACK_ROW_LENGTH, unpackRow);
    glPixelStorei(GL_UNPACK_ALIGNMENT, unpackAlign);
    gl.uploadedRevision = revision;
    gl.uploadedName = so->id();
}

void DeferredTexturing::Pipeline::adoptAtlases(osg::State& state, TexturePageTable& t, unsigned revision)
{
    const unsigned ctx = state.getContextID();
    state.applyTextureAttribute(kFilteredAtlasUnit, filteredAtlas.get());
    osg::Texture::TextureObject* so = sourceAtlas->getTextureObject(ctx);
    osg::Texture::TextureObject* fo = filteredAtlas->getTextureObject(ctx);
    if (!so || !fo) throw GpuFilterError("DeferredTexturing: the atlas textures could not be created");
    if (gl.adoptedRevision == revision && so->id() == gl.srcName && fo->id() == gl.dstName) return;
    if (gl.srcAtlas) gl.engine->destroyAtlas(gl.srcAtlas);
    if (gl.dstAtlas) gl.engine->destroyAtlas(gl.dstAtlas);
    gl.srcAtlas = gl.engine->adoptAtlas(so->id(), t.atlasWidth(), t.atlasHeight());
    gl.dstAtlas = gl.engine->adoptAtlas(fo->id(), t.atlasWidth(), t.atlasHeight());
    gl.srcName = so->id();
    gl.dstName = fo->id();
    gl.adoptedRevision = revision;
    osg::GLExtensions* ext = state.get<osg::GLExtensions>();
    uploadBuffer(ext, gl.pageBuffer, t.pageTableData());
    uploadBuffer(ext, gl.regionBuffer, t.regionTableData());
    ext->glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    gl.cache.clear();
    gl.cacheKey.clear();
    resetTileState();
}

std::vector<GLuint> DeferredTexturing::Pipeline::prefetchTiles(osg::State& state, TexturePageTable& t,
                                                               bool markCoarser)
{
    osg::GLExtensions* ext = state.get<osg::GLExtensions>();
    osg::Texture::TextureObject* go = targets[TEXCOORD]->getTextureObject(state.getContextID());
    if (!go) throw GpuFilterError("DeferredTexturing: the G-buffer was not drawn");
    if (!gl.prefetch) gl.prefetch = compileCompute(ext, "loa_deferred_prefetch.comp.glsl");
    GLint previous = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &previous);

    const std::size_t words = (t.tileCount() + 31) / 32;
    std::vector<GLuint> flags(std::max<std::size_t>(words, 1), 0u);
    if (!gl.flagBuffer) ext->glGenBuffers(1, &gl.flagBuffer);
    ext->glBindBuffer(GL_SHADER_STORAGE_BUFFER, gl.flagBuffer);
    ext->glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(flags.size() * sizeof(GLuint)), flags.data(),
                      GL_DYNAMIC_READ);
    ext->glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, gl.pageBuffer);
    ext->glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, gl.regionBuffer);
    ext->glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, gl.flagBuffer);
    ext->glBindImageTexture(0, go->id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F_ARB);
    ext->glUseProgram(gl.prefetch);
    ext->glUniform2i(ext->glGetUniformLocation(gl.prefetch, "loa_gbufferSize"), width, height);
    ext->glUniform1i(ext->glGetUniformLocation(gl.prefetch, "loa_textureCount"), GLint(t.size()));
    ext->glUniform1i(ext->glGetUniformLocation(gl.prefetch, "loa_markCoarser"), markCoarser ? 1 : 0);
    ext->glDispatchCompute(GLuint((width + 7) / 8), GLuint((height + 7) / 8), 1);
    ext->glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    // The sync point: the CPU waits for the G-buffer and the prefetch before it can list tiles.
    ext->glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(flags.size() * sizeof(GLuint)),
                            flags.data());
    ext->glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    ext->glUseProgram(GLuint(previous));
    return flags;
}

bool DeferredTexturing::Pipeline::runFilterStage(osg::State& state, TexturePageTable& t, unsigned revision,
                                                 Statistics& st)
{
    if (!t.isPacked() || t.size() == 0) return false;
    uploadSource(state, t, revision);
    osg::ref_ptr<ImageFilter> f = filter;
    if (!f.valid()) return false;
    if (!gl.engine.valid())
    {
        if (!gl.engineError.empty()) throw GpuFilterError(gl.engineError);
        try
        {
            gl.engine = new GpuFilterEngine(state);
            gl.contextID = state.getContextID();
        }
        catch (const GpuFilterError& e)
        {
            gl.engineError = e.what();
            throw;
        }
    }
    if (state.getContextID() != gl.contextID)
        throw GpuFilterError(
            "DeferredTexturing: one node serves one graphics context (the first that drew it)");
    adoptAtlases(state, t, revision);
    const std::vector<GpuFilterPass> passes = f->gpuPasses();
    if (passes.empty())
        throw GpuFilterError("DeferredTexturing: filter '" + f->filterName() +
                             "' has no GPU implementation; apply it ahead of time (MipmapFilter)");
    const std::size_t P = passes.size();
    st.atlasBytes = t.atlasBytes() * (2 + (P - 1));
    const std::string key =
        std::to_string(reinterpret_cast<std::uintptr_t>(f.get())) + "|" + f->getParameterString();
    if (key != gl.cacheKey)
    {
        gl.cache.clear();
        resetTileState();
        gl.cacheKey = key;
    }
    if (mode == PER_FRAGMENT) gl.cache.clear();

    // Prefetch: the tiles visible fragments need.
    const bool progressive = budgetTexels > 0;
    const std::vector<GLuint> flags = prefetchTiles(state, t, progressive);
    const std::vector<GpuFilterEngine::Region>& regions = t.regions();
    needed.clear();
    std::vector<unsigned char> regionNeeded(regions.size(), 0);
    for (std::size_t r = 0; r < regions.size(); ++r)
    {
        const GpuFilterEngine::Region& reg = regions[r];
        const std::size_t base = t.tileBase(int(r));
        for (int y = 0; y < reg.tilesY(); ++y)
            for (int x = 0; x < reg.tilesX(); ++x)
            {
                const std::size_t i = base + std::size_t(y * reg.tilesX() + x);
                if (flags[i >> 5] & (1u << (i & 31u)))
                {
                    needed.push_back({GLuint(r), GLuint(x), GLuint(y)});
                    regionNeeded[r] = 1;
                }
            }
    }
    st.neededTiles = needed.size();

    // Candidates: every tile of each needed level (setup 1, and filters that need whole levels)
    // or the needed tiles; grouped into units of work: a tile, or a whole level for filters whose
    // output depends on whole lines or the whole image (the engine filters all of such a level).
    const bool wholeLevelUnits = f->dependencyRadius() < 0;
    const bool allTilesOfLevels = mode == PER_LEVEL_CACHED || wholeLevelUnits;
    struct Unit
    {
        int level = 0;
        std::size_t region = 0;
        bool fresh = false; ///< holds a tile never shown filtered
        std::size_t texels = 0;
        std::vector<GpuFilterEngine::Tile> tiles;
    };
    std::vector<Unit> units;
    auto candidate = [&](std::size_t r, int x, int y, Unit& u)
    {
        const GpuFilterEngine::Region& reg = regions[r];
        const int index = y * reg.tilesX() + x;
        if (mode != PER_FRAGMENT && gl.cache.isDone(P - 1, r, index)) return;
        u.level = t.levelOf(int(r));
        u.region = r;
        u.tiles.push_back({GLuint(r), GLuint(x), GLuint(y)});
        u.texels += std::size_t(tileTexels(reg, x, y));
        if ((*tileState)[t.tileBase(int(r)) + std::size_t(index)] == 0u) u.fresh = true;
    };
    if (allTilesOfLevels)
    {
        for (std::size_t r = 0; r < regions.size(); ++r)
        {
            if (!regionNeeded[r]) continue;
            Unit level;
            for (int y = 0; y < regions[r].tilesY(); ++y)
                for (int x = 0; x < regions[r].tilesX(); ++x)
                {
                    if (wholeLevelUnits)
                        candidate(r, x, y, level);
                    else
                    {
                        Unit u;
                        candidate(r, x, y, u);
                        if (!u.tiles.empty()) units.push_back(std::move(u));
                    }
                }
            if (!level.tiles.empty()) units.push_back(std::move(level));
        }
    }
    else
        for (const GpuFilterEngine::Tile& tile : needed)
        {
            Unit u;
            candidate(tile.region, int(tile.x), int(tile.y), u);
            if (!u.tiles.empty()) units.push_back(std::move(u));
        }
    // Tiles never shown filtered first (matters without a cache), then coarse levels first.
    std::stable_sort(units.begin(), units.end(),
                     [](const Unit& a, const Unit& b)
                     {
                         if (a.fresh != b.fresh) return a.fresh;
                         if (a.level != b.level) return a.level > b.level;
                         return a.region < b.region;
                     });
    // Progressive filtering: whole units while they fit the budget (and always the first), in
    // order; once one waits, every later one waits too (coarse levels stay first).
    std::vector<GpuFilterEngine::Tile> tiles;
    std::size_t taken = 0, waiting = 0;
    for (const Unit& u : units)
    {
        const bool take =
            budgetTexels == 0 || taken == 0 || (waiting == 0 && taken + u.texels <= budgetTexels);
        if (take)
        {
            tiles.insert(tiles.end(), u.tiles.begin(), u.tiles.end());
            taken += u.texels;
        }
        else
            waiting += u.tiles.size();
    }
    st.requestedTiles = tiles.size();
    st.deferredTiles = waiting;

    if (!tiles.empty())
    {
        st.run = gl.engine->run(*f, gl.srcAtlas, gl.dstAtlas, regions, &tiles,
                                mode == PER_FRAGMENT ? nullptr : &gl.cache);
        bool changed = false;
        for (const GpuFilterEngine::Tile& tile : tiles)
        {
            const GpuFilterEngine::Region& reg = regions[tile.region];
            unsigned& s = (*tileState)[t.tileBase(int(tile.region)) +
                                       std::size_t(tile.y) * std::size_t(reg.tilesX()) + tile.x];
            if (s == 0u)
            {
                s = gl.frame;
                changed = true;
            }
        }
        if (changed) tileState->dirty();
    }
    if (mode != PER_FRAGMENT)
        for (std::size_t r = 0; r < regions.size(); ++r)
            st.cachedTiles += gl.cache.doneCount(P - 1, r);
    return true;
}

void DeferredTexturing::Pipeline::filterStage(osg::RenderInfo& renderInfo)
{
    osg::State& state = *renderInfo.getState();
    if (timeFiltering) glFinish();
    const auto t0 = std::chrono::steady_clock::now();
    Statistics st;
    st.frame = ++gl.frame;
    osg::ref_ptr<TexturePageTable> t;
    unsigned revision = 0;
    {
        std::lock_guard<std::mutex> lock(tableMutex);
        t = table;
        revision = tableRevision;
    }
    st.textures = t->size();
    st.atlasTiles = t->tileCount();
    st.atlasBytes = t->size() ? t->atlasBytes() * 2 : 0;
    st.gbufferBytes = gbufferBytes(width, height);
    uFrame->set(gl.frame);
    uFade->set(budgetTexels > 0 ? fadeFrames : 0u);
    try
    {
        runFilterStage(state, *t, revision, st);
    }
    catch (const std::exception& e)
    {
        if (stats.error != e.what())
            OSG_WARN << "osgLoA::DeferredTexturing: " << e.what() << "; textures are mapped unfiltered"
                     << std::endl;
        st.error = e.what();
    }
    if (timeFiltering) glFinish();
    st.filterMilliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    stats = st;
}

void DeferredTexturing::Pipeline::releaseGL(osg::State* state)
{
    camera->releaseGLObjects(state);
    shade->releaseGLObjects(state);
    if (sourceAtlas.valid()) sourceAtlas->releaseGLObjects(state);
    if (filteredAtlas.valid()) filteredAtlas->releaseGLObjects(state);
    if (state && state->getContextID() == gl.contextID && gl.engine.valid())
    {
        // OSG releases GL objects with the context current.
        osg::GLExtensions* ext = state->get<osg::GLExtensions>();
        gl.engine->releaseGLObjects();
        if (gl.prefetch) ext->glDeleteProgram(gl.prefetch);
        for (GLuint* b : {&gl.pageBuffer, &gl.regionBuffer, &gl.flagBuffer})
            if (*b) ext->glDeleteBuffers(1, b);
    }
    const unsigned frame = gl.frame;
    gl = GLResources();
    gl.frame = frame;
    resetTileState();
}

// ---------------------------------------------------------------------------------------------

DeferredTexturing::DeferredTexturing()
{
    init();
}

DeferredTexturing::DeferredTexturing(const DeferredTexturing& o, const osg::CopyOp& copyop)
    : osg::Group(o, copyop)
{
    init();
    const Pipeline& p = *o._pipeline;
    if (p.filter.valid()) _pipeline->filter = dynamic_cast<ImageFilter*>(copyop(p.filter.get()));
    _pipeline->mode = p.mode;
    _pipeline->budgetTexels = p.budgetTexels;
    _pipeline->fadeFrames = p.fadeFrames;
    _pipeline->timeFiltering = p.timeFiltering;
    _pipeline->ambient = p.ambient;
    _pipeline->lightDirection = p.lightDirection;
}

DeferredTexturing::~DeferredTexturing() = default;

void DeferredTexturing::init()
{
    _pipeline = new Pipeline(this);
    // The update traversal registers the textures (outside of cull and draw).
    setNumChildrenRequiringUpdateTraversal(getNumChildrenRequiringUpdateTraversal() + 1);
}

void DeferredTexturing::setFilter(ImageFilter* filter)
{
    if (filter && !filter->hasGpuImplementation())
        throw std::invalid_argument("DeferredTexturing: filter '" + filter->filterName() +
                                    "' has no GPU implementation and cannot filter per frame; apply it ahead "
                                    "of time (MipmapFilter)");
    _pipeline->filter = filter;
}
ImageFilter* DeferredTexturing::getFilter()
{
    return _pipeline->filter.get();
}
const ImageFilter* DeferredTexturing::getFilter() const
{
    return _pipeline->filter.get();
}

void DeferredTexturing::setMode(Mode mode)
{
    if (mode != PER_LEVEL_CACHED && mode != PER_FRAGMENT && mode != PER_FRAGMENT_CACHED)
        throw std::invalid_argument(
            "DeferredTexturing: mode " + std::to_string(int(mode)) +
            " is not 1 (per level, cached), 2 (per fragment) or 3 (per fragment, cached)");
    _pipeline->mode = mode;
}
DeferredTexturing::Mode DeferredTexturing::getMode() const
{
    return _pipeline->mode;
}

void DeferredTexturing::setBudgetTexels(unsigned texels)
{
    _pipeline->budgetTexels = texels;
}
unsigned DeferredTexturing::getBudgetTexels() const
{
    return _pipeline->budgetTexels;
}

void DeferredTexturing::setFadeFrames(unsigned frames)
{
    _pipeline->fadeFrames = frames;
}
unsigned DeferredTexturing::getFadeFrames() const
{
    return _pipeline->fadeFrames;
}

void DeferredTexturing::setTimeFiltering(bool on)
{
    _pipeline->timeFiltering = on;
}
bool DeferredTexturing::getTimeFiltering() const
{
    return _pipeline->timeFiltering;
}

void DeferredTexturing::setAmbient(float ambient)
{
    _pipeline->ambient = ambient;
}
float DeferredTexturing::getAmbient() const
{
    return _pipeline->ambient;
}

void DeferredTexturing::setLightDirection(const osg::Vec3f& direction)
{
    _pipeline->lightDirection = direction;
}
const osg::Vec3f& DeferredTexturing::getLightDirection() const
{
    return _pipeline->lightDirection;
}

void DeferredTexturing::dirtyTextures()
{
    std::lock_guard<std::mutex> lock(_pipeline->tableMutex);
    _pipeline->texturesDirty = true;
}

bool DeferredTexturing::addChild(osg::Node* child)
{
    const bool ok = osg::Group::addChild(child);
    if (ok && _pipeline.valid()) dirtyTextures();
    return ok;
}
bool DeferredTexturing::insertChild(unsigned int index, osg::Node* child)
{
    const bool ok = osg::Group::insertChild(index, child);
    if (ok && _pipeline.valid()) dirtyTextures();
    return ok;
}
bool DeferredTexturing::removeChildren(unsigned int pos, unsigned int numChildrenToRemove)
{
    const bool ok = osg::Group::removeChildren(pos, numChildrenToRemove);
    if (ok && _pipeline.valid()) dirtyTextures();
    return ok;
}
bool DeferredTexturing::replaceChild(osg::Node* origChild, osg::Node* newChild)
{
    const bool ok = osg::Group::replaceChild(origChild, newChild);
    if (ok && _pipeline.valid()) dirtyTextures();
    return ok;
}
bool DeferredTexturing::setChild(unsigned int i, osg::Node* node)
{
    const bool ok = osg::Group::setChild(i, node);
    if (ok && _pipeline.valid()) dirtyTextures();
    return ok;
}

void DeferredTexturing::prepare()
{
    _pipeline->prepare(*this);
}

void DeferredTexturing::traverse(osg::NodeVisitor& nv)
{
    if (nv.getVisitorType() == osg::NodeVisitor::UPDATE_VISITOR)
    {
        _pipeline->prepare(*this);
        osg::Group::traverse(nv);
        return;
    }
    osgUtil::CullVisitor* cv = nv.asCullVisitor();
    if (!cv)
    {
        osg::Group::traverse(nv);
        return;
    }
    _pipeline->cull(*this, *cv);
}

const DeferredTexturing::Statistics& DeferredTexturing::getStatistics() const
{
    return _pipeline->stats;
}
const std::vector<GpuFilterEngine::Tile>& DeferredTexturing::getNeededTiles() const
{
    return _pipeline->needed;
}
TexturePageTable* DeferredTexturing::getPageTable()
{
    return _pipeline->table.get();
}
osg::Texture2D* DeferredTexturing::getGBufferTexture(GBufferTarget target)
{
    return target >= 0 && target < NUM_GBUFFER_TARGETS ? _pipeline->targets[target].get() : nullptr;
}
osg::Camera* DeferredTexturing::getGBufferCamera()
{
    return _pipeline->camera.get();
}
osg::Texture2D* DeferredTexturing::getSourceAtlas()
{
    return _pipeline->sourceAtlas.get();
}
osg::Texture2D* DeferredTexturing::getFilteredAtlas()
{
    return _pipeline->filteredAtlas.get();
}

std::size_t DeferredTexturing::gbufferBytes(int width, int height)
{
    // RGBA32F texture coordinates + RGBA32F normal + RGBA8 colour + 32-bit depth.
    return std::size_t(std::max(width, 0)) * std::size_t(std::max(height, 0)) * (16u + 16u + 4u + 4u);
}

void DeferredTexturing::releaseGLObjects(osg::State* state) const
{
    osg::Group::releaseGLObjects(state);
    _pipeline->releaseGL(state);
}

void DeferredTexturing::resizeGLObjectBuffers(unsigned int maxSize)
{
    osg::Group::resizeGLObjectBuffers(maxSize);
    _pipeline->camera->resizeGLObjectBuffers(maxSize);
    _pipeline->shade->resizeGLObjectBuffers(maxSize);
}

} // namespace osgLoA
