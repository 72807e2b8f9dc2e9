/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/abstraction/AbstractionLevelsFilter>
#include <osgLoA/abstraction/AbstractionNode>
#include <osgLoA/abstraction/AbstractionStyleCatalog>
#include <osgLoA/abstraction/PencilTextures>
#include <osgLoA/filtering/DoGFilter>
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/GpuFilterEngine>
#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/ScenarioEvaluator>
#include <osgLoA/transitions/UsageScenario>

#include "../compositing/RenderTarget.h"
#include <osgLoA/render/ShaderLibrary>
#include <osgLoA/styles/FixedFunctionUniforms>

#include <osg/BlendFunc>
#include <osg/ComputeBoundsVisitor>
#include <osg/Geode>
#include <osg/Notify>
#include <osg/buffered_value>
#include <osgUtil/CullVisitor>
#include <osgUtil/IntersectionVisitor>
#include <osgUtil/LineSegmentIntersector>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>

namespace osgLoA
{

namespace
{
enum Unit
{
    UNIT_NORMAL = 0,
    UNIT_PAINTERLY,
    UNIT_EDGES,
    UNIT_IDS,
    UNIT_OBJECT_DATA,
    UNIT_SHADING,
    UNIT_BASE,
    UNIT_PENCIL,
    UNIT_SURFACE
};

const osg::StateAttribute::OverrideValue kForce =
    osg::StateAttribute::ON | osg::StateAttribute::OVERRIDE | osg::StateAttribute::PROTECTED;

/** A camera child that draws the abstraction node's children as they are. */
class ChildrenProxy : public osg::Node
{
public:
    explicit ChildrenProxy(AbstractionNode* owner) : _owner(owner) { setCullingActive(false); }
    void traverse(osg::NodeVisitor& nv) override
    {
        if (_owner) _owner->osg::Group::traverse(nv);
    }
    AbstractionNode* _owner; // the owner holds this node; never outlives it
};

/** A camera child that draws the content plainly (object passes). */
class ContentProxy : public osg::Node
{
public:
    explicit ContentProxy(AbstractionNode* owner) : _owner(owner) { setCullingActive(false); }
    void traverse(osg::NodeVisitor& nv) override
    {
        if (_owner) _owner->traverseContent(nv);
    }
    AbstractionNode* _owner;
};

class ImageStageCallback : public osg::Camera::DrawCallback
{
public:
    explicit ImageStageCallback(AbstractionNode* owner) : _owner(owner) {}
    void operator()(osg::RenderInfo& renderInfo) const override
    {
        if (_owner) _owner->runImageStages(renderInfo);
    }
    AbstractionNode* _owner;
};

/** Object number (1-based) as an exact RGBA8 colour. */
osg::Vec4f idColor(unsigned number)
{
    return osg::Vec4f(float(number & 0xffu) / 255.0f, float((number >> 8) & 0xffu) / 255.0f,
                      float((number >> 16) & 0xffu) / 255.0f, 1.0f);
}

/** The StateSet of a node or drawable that only it uses (a shared one is replaced by a copy). */
template <class T> osg::StateSet* ownStateSet(T& holder)
{
    osg::StateSet* ss = holder.getStateSet();
    if (!ss) return holder.getOrCreateStateSet();
    if (ss->getNumParents() > 1)
    {
        osg::ref_ptr<osg::StateSet> copy = new osg::StateSet(*ss, osg::CopyOp::SHALLOW_COPY);
        holder.setStateSet(copy.get());
        return copy.get();
    }
    return ss;
}

class DrawableCollector : public osg::NodeVisitor
{
public:
    DrawableCollector() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
    void apply(osg::Drawable& d) override { found.push_back({&d, getNodePath()}); }
    std::vector<std::pair<osg::Drawable*, osg::NodePath>> found;
};

osg::Matrixd parentMatrix(const osg::NodePath& path)
{
    if (path.size() < 2) return osg::Matrixd::identity();
    return osg::computeLocalToWorld(osg::NodePath(path.begin(), path.end() - 1));
}

void setComponent(osg::Uniform& u, int slot, float value)
{
    osg::Vec4f v;
    u.get(v);
    v[slot] = value;
    u.set(v);
}

/** Abstraction nodes nested below `node` along its children (through LoA nodes). */
int nestedAbstractionNodes(osg::Group& node)
{
    int most = 0;
    for (unsigned i = 0; i < node.getNumChildren(); ++i)
    {
        osg::Group* child = node.getChild(i)->asGroup();
        if (!child) continue;
        if (dynamic_cast<AbstractionNode*>(child))
            most = std::max(most, 1 + nestedAbstractionNodes(*child));
        else if (dynamic_cast<LoANode*>(child))
            most = std::max(most, nestedAbstractionNodes(*child));
    }
    return most;
}

void setDefine(osg::StateSet& ss, const char* name, int value, bool enabled = true)
{
    if (enabled)
        ss.setDefine(name, std::to_string(value), osg::StateAttribute::ON);
    else
        ss.removeDefine(name);
}

} // namespace

/** Per-context GL objects of the image stages, and what the last frame did. */
struct AbstractionNode::Internals : public osg::Referenced
{
    struct PerContext
    {
        osg::ref_ptr<GpuFilterEngine> engine;
        bool engineFailed = false;
        unsigned normalAtlas = 0, painterlyAtlas = 0, edgesAtlas = 0;
        GLuint normalName = 0, painterlyName = 0, edgesName = 0;
        int width = 0, height = 0;
    };
    mutable osg::buffered_object<PerContext> contexts;
    mutable std::mutex mutex;
    FrameStatistics stats;
    std::string lastError;  ///< of the image stages (draw)
    std::string focusError; ///< of the style and focus (cull)
    osg::ref_ptr<ImageFilter> levels, edges;
    osg::ref_ptr<osg::Uniform> stagesOk; ///< the display pass shows N when the stages failed

    void setFocusError(const std::string& what)
    {
        std::lock_guard<std::mutex> lock(mutex);
        if (!what.empty() && focusError != what) OSG_WARN << "osgLoA::AbstractionNode: " << what << std::endl;
        focusError = what;
    }

    void fail(const std::string& what)
    {
        std::lock_guard<std::mutex> lock(mutex);
        if (lastError != what) OSG_WARN << "osgLoA::AbstractionNode: " << what << std::endl;
        lastError = what;
    }
};

AbstractionNode::AbstractionNode()
{
    build();
}

AbstractionNode::AbstractionNode(const AbstractionNode& other, const osg::CopyOp& copyop)
    : osg::Group(other, copyop), _style(dynamic_cast<AbstractionStyle*>(copyop(other._style.get()))),
      _enabled(other._enabled), _scenarioNode(other._scenarioNode), _scenarioStyle(other._scenarioStyle)
{
    build();
}

AbstractionNode::~AbstractionNode()
{
    for (osg::Camera* c :
         {_baseCamera.get(), _normalCamera.get(), _idCamera.get(), _shadingCamera.get(), _focusCamera.get()})
        if (c)
        {
            c->setPostDrawCallback(nullptr);
            c->removeChildren(0, c->getNumChildren());
        }
}

void AbstractionNode::build()
{
    _internals = new Internals;
    auto sceneCamera = [&](const char* name, int order, bool plain)
    {
        osg::ref_ptr<osg::Camera> c = new osg::Camera;
        c->setName(name);
        c->setRenderOrder(osg::Camera::PRE_RENDER, order);
        c->setReferenceFrame(osg::Transform::RELATIVE_RF); // the view and lights above
        c->setRenderTargetImplementation(osg::Camera::FRAME_BUFFER_OBJECT);
        c->setClearMask(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        c->setCullingActive(false);
        if (plain)
            c->addChild(new ContentProxy(this));
        else
            c->addChild(new ChildrenProxy(this));
        return c;
    };
    _idCamera = sceneCamera("loa_abstraction_ids", 0, true);
    _idCamera->setClearColor(osg::Vec4(0, 0, 0, 0));
    _shadingCamera = sceneCamera("loa_abstraction_shading", 1, true);
    // White, alpha 0: the compositing tells the background (no surface) from lit white faces.
    _shadingCamera->setClearColor(osg::Vec4(1, 1, 1, 0));
    _baseCamera = sceneCamera("loa_abstraction_base", 2, false);
    _normalCamera = sceneCamera("loa_abstraction_normal", 3, false); // children reset in configure()

    _idState = _idCamera->getOrCreateStateSet();
    _idState->setAttributeAndModes(
        ShaderLibrary::createProgram("loa_abstraction_id",
                                     {"loa_abstraction_object.vert.glsl", "loa_material_alpha.frag.glsl",
                                      "loa_abstraction_id.frag.glsl"})
            .get(),
        kForce);
    _idState->addUniform(new osg::Uniform("loa_objectId", osg::Vec4f(0, 0, 0, 0)));
    _idState->addUniform(new osg::Uniform("loa_baseTexture", 0)); // alpha-tested cards keep their shape
    _idState->addUniform(new osg::Uniform("loa_objectImportance", osg::Vec4f()));
    _idState->addUniform(new osg::Uniform("loa_objectWeight", osg::Vec4f()));
    _idState->setMode(GL_BLEND, osg::StateAttribute::OFF | osg::StateAttribute::OVERRIDE);

    _shadingState = _shadingCamera->getOrCreateStateSet();
    _shadingProgram = ShaderLibrary::createProgram(
        "loa_abstraction_shading", {"loa_abstraction_object.vert.glsl", "loa_material_alpha.frag.glsl",
                                    "loa_abstraction_shading.frag.glsl"});
    _shadingState->setAttributeAndModes(_shadingProgram.get(), kForce);
    _shadingState->addUniform(new osg::Uniform("loa_objectImportance", osg::Vec4f()));
    _shadingState->addUniform(new osg::Uniform("loa_abstraction_pencil", int(UNIT_PENCIL)));
    _shadingState->addUniform(new osg::Uniform("loa_baseTexture", 0));
    _shadingState->setMode(GL_BLEND, osg::StateAttribute::OFF | osg::StateAttribute::OVERRIDE);

    _unshadedState = new osg::StateSet;
    _unshadedState->setAttributeAndModes(
        ShaderLibrary::createProgram("loa_abstraction_unshaded",
                                     {"loa_abstraction_object.vert.glsl", "loa_material_alpha.frag.glsl",
                                      "loa_abstraction_unshaded.frag.glsl"})
            .get(),
        kForce);
    _unshadedState->addUniform(new osg::Uniform("loa_baseTexture", 0));
    _unshadedState->addUniform(new osg::Uniform("loa_hasTexture", false));

    // The focus pass: alpha only, into the normal frame, then the image stages.
    _focusCamera = new osg::Camera;
    _focusCamera->setName("loa_abstraction_focus");
    _focusCamera->setRenderOrder(osg::Camera::PRE_RENDER, 4);
    _focusCamera->setReferenceFrame(osg::Transform::ABSOLUTE_RF);
    _focusCamera->setRenderTargetImplementation(osg::Camera::FRAME_BUFFER_OBJECT);
    _focusCamera->setClearMask(0);
    _focusCamera->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    _focusCamera->setCullingActive(false);
    _focusCamera->setPostDrawCallback(new ImageStageCallback(this));
    {
        osg::ref_ptr<osg::Geode> geode = new osg::Geode;
        geode->addDrawable(detail::createFullScreenTriangle().get());
        geode->setCullingActive(false);
        _focusCamera->addChild(geode.get());
        _focusState = geode->getOrCreateStateSet();
        _focusProgram = ShaderLibrary::createProgram(
            "loa_abstraction_focus", {"loa_compose.vert.glsl", "loa_abstraction_focus.frag.glsl"});
        _focusState->setAttributeAndModes(_focusProgram.get(), kForce);
        // Alpha only, by blending (RGB: 0 * src + 1 * dst; alpha: src) rather than a colour mask:
        // OSG restores a colour mask lazily, so a mask left set would make the next camera's
        // clear skip RGB.
        _focusState->setAttributeAndModes(new osg::BlendFunc(GL_ZERO, GL_ONE, GL_ONE, GL_ZERO), kForce);
        _focusState->addUniform(new osg::Uniform("loa_abstraction_ids", int(UNIT_IDS)));
        _focusState->addUniform(new osg::Uniform("loa_abstraction_objectData", int(UNIT_OBJECT_DATA)));
        for (GLenum m : {GLenum(GL_DEPTH_TEST), GLenum(GL_CULL_FACE), GLenum(GL_LIGHTING)})
            _focusState->setMode(m, osg::StateAttribute::OFF | osg::StateAttribute::OVERRIDE |
                                        osg::StateAttribute::PROTECTED);
    }

    _displayCamera = new osg::Camera;
    _displayCamera->setName("loa_abstraction_display");
    _displayCamera->setRenderOrder(osg::Camera::NESTED_RENDER);
    _displayCamera->setReferenceFrame(osg::Transform::ABSOLUTE_RF);
    _displayCamera->setClearMask(0);
    _displayCamera->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    _displayCamera->setCullingActive(false);
    {
        osg::ref_ptr<osg::Geode> geode = new osg::Geode;
        geode->addDrawable(detail::createFullScreenTriangle().get());
        geode->setCullingActive(false);
        _displayCamera->addChild(geode.get());
        _displayState = geode->getOrCreateStateSet();
        _displayState->setDataVariance(osg::Object::DYNAMIC);
        _composeProgram = ShaderLibrary::createProgram(
            "loa_abstraction_compose", {"loa_compose.vert.glsl", "loa_abstraction_compose.frag.glsl"});
        _displayState->setAttributeAndModes(_composeProgram.get(), kForce);
        const char* samplers[] = {"loa_abstraction_normal",     "loa_abstraction_painterly",
                                  "loa_abstraction_edges",      "loa_abstraction_ids",
                                  "loa_abstraction_objectData", "loa_abstraction_shading",
                                  "loa_abstraction_base"};
        for (int i = 0; i < 7; ++i)
            _displayState->addUniform(new osg::Uniform(samplers[i], i), osg::StateAttribute::OVERRIDE);
        _displayState->addUniform(new osg::Uniform("loa_abstraction_surface", int(UNIT_SURFACE)),
                                  osg::StateAttribute::OVERRIDE);
        _internals->stagesOk = new osg::Uniform("loa_abstraction_stagesOk", true);
        _internals->stagesOk->setDataVariance(osg::Object::DYNAMIC);
        _displayState->addUniform(_internals->stagesOk.get(), osg::StateAttribute::OVERRIDE);
        // Drawn before the rest of the camera above (the node is meant to hold the scene): the
        // composite writes no depth, so what is drawn after it appears in front of it.
        _displayState->setRenderBinDetails(-10, "RenderBin");
        for (GLenum m : {GLenum(GL_DEPTH_TEST), GLenum(GL_BLEND), GLenum(GL_CULL_FACE), GLenum(GL_LIGHTING)})
            _displayState->setMode(m, osg::StateAttribute::OFF | osg::StateAttribute::OVERRIDE |
                                          osg::StateAttribute::PROTECTED);
    }
    _configuredKey.clear();
    _width = _height = 0;
}

void AbstractionNode::setStyle(AbstractionStyle* style)
{
    if (style) style->validate();
    _style = style;
    _configuredKey.clear();
}

void AbstractionNode::setScenarioWeighting(LoANode* loa, const std::string& styleName)
{
    _scenarioNode = loa;
    _scenarioStyle = loa ? styleName : std::string();
    _configuredKey.clear();
    _objectsDirty = true;
}

osg::ref_ptr<osg::Node> AbstractionNode::wrapScenario(LoANode* loa)
{
    if (!loa) return nullptr;
    loa->bind();
    osg::ref_ptr<osg::Node> top = loa;
    const UsageScenario* scenario = loa->getScenario();
    if (!scenario) return top;
    std::set<std::string> done;
    for (const osg::ref_ptr<TransitionConfiguration>& configuration : scenario->getConfigurations())
    {
        const std::string style = configuration->getStyle();
        if (done.count(style) || !AbstractionStyleCatalog::instance().contains(style)) continue;
        done.insert(style);
        osg::ref_ptr<AbstractionNode> node = new AbstractionNode;
        node->setName("loa_abstraction_" + style);
        node->setStyle(AbstractionStyleCatalog::instance().create(style).get());
        node->addChild(top.get());
        node->setScenarioWeighting(loa, style);
        top = node;
    }
    return top;
}

int AbstractionNode::findObject(unsigned id) const
{
    const auto it = _objectOfId.find(id);
    return it == _objectOfId.end() ? -1 : int(it->second);
}

AbstractionNode::FrameStatistics AbstractionNode::getLastFrameStatistics() const
{
    std::lock_guard<std::mutex> lock(_internals->mutex);
    return _internals->stats;
}

std::string AbstractionNode::getLastError() const
{
    std::lock_guard<std::mutex> lock(_internals->mutex);
    if (_internals->focusError.empty()) return _internals->lastError;
    if (_internals->lastError.empty()) return _internals->focusError;
    return _internals->focusError + "; " + _internals->lastError;
}

namespace
{
struct Needs
{
    bool ids = false, shading = false, painterly = false, edges = false, base = false, unshaded = false,
         weighted = false;
};

Needs needsOf(const AbstractionStyle& s, bool weighted)
{
    Needs n;
    n.weighted = weighted;
    n.ids = s.needsIdPass() || weighted;
    n.shading = s.needsShadingPass();
    n.painterly = s.needsPainterly();
    n.edges = s.getEdgeDetector() != AbstractionStyle::NO_EDGES;
    n.unshaded = s.getNormalPass() == AbstractionStyle::UNSHADED;
    n.base = weighted && n.unshaded; // a LIT normal pass is the base frame itself
    return n;
}
} // namespace

double AbstractionNode::memoryBytes(int width, int height) const
{
    if (!_style.valid()) return 0.0;
    const Needs n = needsOf(*_style, _scenarioNode.valid());
    const double px = double(width) * double(height);
    double bytes = px * (16.0 + 4.0); // normal RGBA32F + its depth
    if (n.base) bytes += px * (16.0 + 4.0);
    if (n.ids) bytes += px * (4.0 + 4.0 + 8.0 + 4.0); // ids, object data, surface RGBA16F, depth
    if (n.shading) bytes += px * (4.0 + 4.0);
    if (n.painterly) bytes += px * 16.0;
    if (n.edges) bytes += px * 16.0;
    return bytes;
}

void AbstractionNode::configure()
{
    const AbstractionStyle& s = *_style;
    const bool weighted = _scenarioNode.valid();
    const Needs n = needsOf(s, weighted);
    std::ostringstream key;
    key << n.ids << n.shading << n.painterly << n.edges << n.base << n.unshaded << n.weighted << ' '
        << int(s.getShading()) << ' ' << int(s.getEdgeDetector()) << ' ' << int(s.getCombination()) << ' '
        << int(s.getAdaptivity()) << ' ' << s.getSegmentation() << s.getSilhouettes() << ' '
        << s.getPencilLevels() << ' ' << s.getPencilAnisotropy() << ' ' << s.getKuwaharaRadius() << ' '
        << s.getKuwaharaIterations() << ' ' << s.getKuwaharaIterationsFocus() << ' ' << int(s.getEdgeSource())
        << ' ' << s.getDogSigma() << ' ' << s.getDogRatio() << ' ' << s.getDogTau() << ' '
        << s.getDogEpsilon() << ' ' << s.getCannyLow() << ' ' << s.getCannyHigh();
    if (key.str() == _configuredKey) return;
    _configuredKey = key.str();

    // The normal pass: the children as they are (LIT) or plainly without shading.
    _normalCamera->removeChildren(0, _normalCamera->getNumChildren());
    if (n.unshaded)
    {
        _normalCamera->addChild(new ContentProxy(this));
        _normalCamera->setStateSet(_unshadedState.get());
    }
    else
    {
        _normalCamera->addChild(new ChildrenProxy(this));
        _normalCamera->setStateSet(nullptr);
    }

    setDefine(*_shadingState, "LOA_SHADING", int(s.getShading()), n.shading);
    if (s.getAdaptivity() == AbstractionStyle::OBJECT_FOCUS && s.getShading() == AbstractionStyle::CEL)
        _shadingState->setDefine("LOA_ADAPTIVE"); // adaptive cel levels; pencil levels are fixed
    else
        _shadingState->removeDefine("LOA_ADAPTIVE");
    if (s.getShading() == AbstractionStyle::PENCIL)
    {
        osg::ref_ptr<osg::Image> layers = PencilTextures::create(s.getPencilLevels(), 256);
        _pencil = new osg::Texture2DArray;
        _pencil->setTextureSize(layers->s(), layers->t(), layers->r());
        for (int k = 0; k < layers->r(); ++k)
        {
            osg::ref_ptr<osg::Image> layer = new osg::Image;
            layer->allocateImage(layers->s(), layers->t(), 1, layers->getPixelFormat(),
                                 layers->getDataType());
            std::copy(layers->data(0, 0, k), layers->data(0, 0, k) + layer->getTotalSizeInBytes(),
                      layer->data());
            _pencil->setImage(unsigned(k), layer.get());
        }
        _pencil->setWrap(osg::Texture::WRAP_S, osg::Texture::REPEAT);
        _pencil->setWrap(osg::Texture::WRAP_T, osg::Texture::REPEAT);
        _pencil->setFilter(osg::Texture::MIN_FILTER, osg::Texture::LINEAR_MIPMAP_LINEAR);
        _pencil->setFilter(osg::Texture::MAG_FILTER, osg::Texture::LINEAR);
        _pencil->setMaxAnisotropy(s.getPencilAnisotropy()); // AbstractionStyle: quality against cost
        _shadingState->setTextureAttributeAndModes(UNIT_PENCIL, _pencil.get(), kForce);
    }
    else
    {
        _pencil = nullptr;
        _shadingState->removeTextureAttribute(UNIT_PENCIL, osg::StateAttribute::TEXTURE);
    }

    setDefine(*_focusState, "LOA_ADAPTIVITY", int(s.getAdaptivity()));
    if (s.getSegmentation())
        _focusState->setDefine("LOA_SEGMENTATION");
    else
        _focusState->removeDefine("LOA_SEGMENTATION");

    setDefine(*_displayState, "LOA_COMBINATION", int(s.getCombination()));
    setDefine(*_displayState, "LOA_EDGES", int(s.getEdgeDetector()));
    setDefine(*_displayState, "LOA_SHADING", int(s.getShading()));
    setDefine(*_displayState, "LOA_ADAPTIVITY", int(s.getAdaptivity()));
    auto flag = [&](const char* name, bool on)
    {
        if (on)
            _displayState->setDefine(name);
        else
            _displayState->removeDefine(name);
    };
    flag("LOA_SILHOUETTES", s.getSilhouettes());
    flag("LOA_PAINTERLY", n.painterly);
    flag("LOA_WEIGHTED", n.weighted);

    // The image filters.
    if (n.painterly)
    {
        osg::ref_ptr<AbstractionLevelsFilter> f = new AbstractionLevelsFilter;
        f->setRadius(s.getKuwaharaRadius());
        f->setIterations(s.getKuwaharaIterations());
        f->setIterationsFocus(s.getAdaptivity() == AbstractionStyle::UNIFORM
                                  ? s.getKuwaharaIterations()
                                  : s.getKuwaharaIterationsFocus());
        _internals->levels = f;
    }
    else
        _internals->levels = nullptr;
    _internals->edges = nullptr;
    if (n.edges)
    {
        switch (s.getEdgeDetector())
        {
        case AbstractionStyle::DOG:
        {
            osg::ref_ptr<DoGFilter> dog = new DoGFilter;
            dog->setFlow(false);
            dog->setSigmaE(s.getDogSigma());
            dog->setK(s.getDogRatio());
            dog->setTau(s.getDogTau());
            dog->setEpsilon(s.getDogEpsilon());
            dog->setMode(DoGFilter::EDGES);
            _internals->edges = dog;
            break;
        }
        case AbstractionStyle::SOBEL:
            _internals->edges = FilterRegistry::create("sobel:threshold=0");
            break;
        case AbstractionStyle::CANNY:
        {
            osg::ref_ptr<ImageFilter> canny = FilterRegistry::create("canny");
            canny->setParameter("low", double(s.getCannyLow()));
            canny->setParameter("high", double(s.getCannyHigh()));
            _internals->edges = canny;
            break;
        }
        default:
            break;
        }
    }
    _width = _height = 0; // targets for the new configuration
}

void AbstractionNode::resize(int width, int height)
{
    if (width == _width && height == _height) return;
    _width = width;
    _height = height;
    const Needs n = needsOf(*_style, _scenarioNode.valid());
    auto make = [&](const char* name, GLint internalFormat, GLenum type)
    {
        osg::ref_ptr<osg::Texture2D> t = detail::createTargetTexture(internalFormat, GL_RGBA, type);
        t->setName(name);
        t->setTextureSize(width, height);
        return t;
    };
    auto attach = [&](osg::Camera* c, osg::Camera::BufferComponent b, osg::Texture2D* t)
    {
        c->detach(b);
        if (t) c->attach(b, t);
    };
    auto finish = [&](osg::Camera* c, bool depth)
    {
        c->detach(osg::Camera::DEPTH_BUFFER);
        if (depth) c->attach(osg::Camera::DEPTH_BUFFER, GL_DEPTH_COMPONENT24);
        c->setViewport(0, 0, width, height);
        c->setRenderingCache(nullptr);
    };
    _normal = make("loa_abstraction_normal", GL_RGBA32F_ARB, GL_FLOAT);
    attach(_normalCamera.get(), osg::Camera::COLOR_BUFFER, _normal.get());
    finish(_normalCamera.get(), true);
    attach(_focusCamera.get(), osg::Camera::COLOR_BUFFER, _normal.get());
    finish(_focusCamera.get(), false);
    _base = n.base ? make("loa_abstraction_base", GL_RGBA32F_ARB, GL_FLOAT) : nullptr;
    if (n.base)
    {
        attach(_baseCamera.get(), osg::Camera::COLOR_BUFFER, _base.get());
        finish(_baseCamera.get(), true);
    }
    _ids = n.ids ? make("loa_abstraction_ids", GL_RGBA8, GL_UNSIGNED_BYTE) : nullptr;
    _objectData = n.ids ? make("loa_abstraction_object_data", GL_RGBA8, GL_UNSIGNED_BYTE) : nullptr;
    // View-space normal and depth of the front surface: silhouettes only where the surface is
    // not continuous (objects tiling one surface meet without a line).
    _surface = n.ids ? make("loa_abstraction_surface", GL_RGBA16F_ARB, GL_FLOAT) : nullptr;
    if (n.ids)
    {
        attach(_idCamera.get(), osg::Camera::COLOR_BUFFER0, _ids.get());
        attach(_idCamera.get(), osg::Camera::COLOR_BUFFER1, _objectData.get());
        attach(_idCamera.get(), osg::Camera::COLOR_BUFFER2, _surface.get());
        finish(_idCamera.get(), true);
    }
    _shading = n.shading ? make("loa_abstraction_shading", GL_RGBA8, GL_UNSIGNED_BYTE) : nullptr;
    if (n.shading)
    {
        attach(_shadingCamera.get(), osg::Camera::COLOR_BUFFER, _shading.get());
        finish(_shadingCamera.get(), true);
    }
    _painterly = n.painterly ? make("loa_abstraction_painterly", GL_RGBA32F_ARB, GL_FLOAT) : nullptr;
    _edges = n.edges ? make("loa_abstraction_edges", GL_RGBA32F_ARB, GL_FLOAT) : nullptr;

    auto bind = [&](osg::StateSet& ss, unsigned unit, osg::Texture2D* t)
    {
        if (t)
            ss.setTextureAttribute(unit, t, osg::StateAttribute::OVERRIDE | osg::StateAttribute::PROTECTED);
        else
            ss.removeTextureAttribute(unit, osg::StateAttribute::TEXTURE);
    };
    bind(*_displayState, UNIT_NORMAL, _normal.get());
    bind(*_displayState, UNIT_PAINTERLY, _painterly.get());
    bind(*_displayState, UNIT_EDGES, _edges.get());
    bind(*_displayState, UNIT_IDS, _ids.get());
    bind(*_displayState, UNIT_OBJECT_DATA, _objectData.get());
    bind(*_displayState, UNIT_SURFACE, _surface.get());
    bind(*_displayState, UNIT_SHADING, _shading.get());
    bind(*_displayState, UNIT_BASE, n.base ? _base.get() : _normal.get());
    bind(*_focusState, UNIT_IDS, _ids.get());
    bind(*_focusState, UNIT_OBJECT_DATA, _objectData.get());
    _displayState->getOrCreateUniform("loa_abstraction_base", osg::Uniform::INT)
        ->set(int(n.base ? UNIT_BASE : UNIT_NORMAL));
}

void AbstractionNode::traverseContent(osg::NodeVisitor& nv)
{
    for (unsigned i = 0; i < getNumChildren(); ++i)
    {
        osg::Node* child = getChild(i);
        if (LoANode* loa = dynamic_cast<LoANode*>(child))
        {
            nv.pushOntoNodePath(loa);
            loa->traverseChildren(nv);
            nv.popFromNodePath();
        }
        else if (AbstractionNode* nested = dynamic_cast<AbstractionNode*>(child))
        {
            nv.pushOntoNodePath(nested);
            nested->traverseContent(nv);
            nv.popFromNodePath();
        }
        else
            child->accept(nv);
    }
}

void AbstractionNode::collectObjects()
{
    _objectsDirty = false;
    _objects.clear();
    _objectOfId.clear();
    for (osg::StateSet* ss : {_idState.get(), _shadingState.get()})
        ss->getOrCreateUniform("loa_abstraction_slot", osg::Uniform::INT)->set(_slot);
    // Which StateSets carry a base texture (the unshaded pass samples exactly those): the same
    // mirror of the fixed-function state the LoA node's styles read.
    for (unsigned c = 0; c < getNumChildren(); ++c)
        FixedFunctionUniforms::annotate(*getChild(c));

    auto add =
        [&](unsigned id, const osg::Vec3d& centre, osg::StateSet* ss, osg::Node* node, osg::Drawable* d)
    {
        Object o;
        o.id = id;
        o.centre = centre;
        o.node = node;
        o.drawable = d;
        const unsigned number = unsigned(_objects.size()) + 1;
        // Nested abstraction nodes share the objects' uniforms (the same objects in the same
        // order give the same numbers); each writes its own component of the vec4s.
        auto shared = [&](const char* name, const osg::Vec4f& value, bool keep)
        {
            osg::ref_ptr<osg::Uniform> u = ss->getUniform(name);
            if (!u.valid() || u->getType() != osg::Uniform::FLOAT_VEC4)
            {
                u = new osg::Uniform(name, value);
                u->setDataVariance(osg::Object::DYNAMIC);
                ss->addUniform(u.get());
            }
            else if (!keep)
                u->set(value);
            return u;
        };
        shared("loa_objectId", idColor(number), false);
        o.importance = shared("loa_objectImportance", osg::Vec4f(), true);
        o.weight = shared("loa_objectWeight", osg::Vec4f(), true);
        _objectOfId.emplace(id, unsigned(_objects.size())); // the first object of an id wins
        _objects.push_back(o);
    };
    FeatureIndex index;
    index.build(*this);
    if (!index.empty())
    {
        for (const FeatureIndex::Entry& e : index.entries())
        {
            osg::ref_ptr<osg::Node> node;
            if (!e.node.lock(node)) continue;
            const osg::Vec3d centre = osg::Vec3d(node->getBound().center()) * parentMatrix(index.pathOf(e));
            osg::StateSet* ss = nullptr;
            if (osg::Drawable* d = node->asDrawable())
                ss = ownStateSet(*d);
            else
                ss = ownStateSet(*node);
            add(e.feature->getId(), centre, ss, node.get(), nullptr);
        }
        return;
    }
    DrawableCollector drawables;
    osg::Group::traverse(drawables);
    for (auto& [d, path] : drawables.found)
    {
        osg::NodePath full = path;
        full.push_back(d);
        const osg::Vec3d centre = osg::Vec3d(d->getBound().center()) * parentMatrix(full);
        add(unsigned(_objects.size()) + 1, centre, ownStateSet(*d), nullptr, d);
    }
}

void AbstractionNode::updateFocus(osgUtil::CullVisitor& cv)
{
    const AbstractionStyle& s = *_style;
    const AbstractionFocus& f = *s.getFocus();
    const osg::Viewport* vp = cv.getViewport();
    const osg::Matrixd mvpw = osg::Matrixd(*cv.getModelViewMatrix()) *
                              osg::Matrixd(*cv.getProjectionMatrix()) * vp->computeWindowMatrix();
    const osg::Vec2f windowOrigin(float(vp->x()), float(vp->y()));
    _focusObject = -1;
    bool haveCentre = false;
    osg::Vec3d centre;
    const osg::Matrixd mvp = osg::Matrixd(*cv.getModelViewMatrix()) * osg::Matrixd(*cv.getProjectionMatrix());
    auto project = [&](const osg::Vec3d& p)
    {
        const osg::Vec4d clip = osg::Vec4d(p, 1.0) * mvp;
        if (clip.w() <= 0.0) return osg::Vec2f(-1e6f, -1e6f); // behind the eye: off screen
        const osg::Vec3d w = p * mvpw;
        return osg::Vec2f(float(w.x()) - windowOrigin.x(), float(w.y()) - windowOrigin.y());
    };
    bool wantObject = s.getSegmentation() || s.getAdaptivity() == AbstractionStyle::OBJECT_FOCUS;
    AbstractionFocus::Mode mode = f.getMode();
    if (mode == AbstractionFocus::OBJECT && f.getObjectId() == 0)
    {
        // No object named: the object under the focus point.
        mode = AbstractionFocus::SCREEN_POINT;
        wantObject = true;
    }
    switch (mode)
    {
    case AbstractionFocus::SCREEN_POINT:
    {
        _focusPixel =
            osg::Vec2f(f.getScreenPoint().x() * float(_width), f.getScreenPoint().y() * float(_height));
        if (!wantObject) break;
        // The object under the focus point: a ray through the pixel centre.
        const osg::Matrixd inverse = osg::Matrixd::inverse(mvpw);
        const osg::Vec3d wx(_focusPixel.x() + windowOrigin.x(), _focusPixel.y() + windowOrigin.y(), 0.0);
        osg::ref_ptr<osgUtil::LineSegmentIntersector> hit =
            new osgUtil::LineSegmentIntersector(wx * inverse, osg::Vec3d(wx.x(), wx.y(), 1.0) * inverse);
        osgUtil::IntersectionVisitor iv(hit.get());
        osg::Group::traverse(iv);
        if (!hit->containsIntersections()) break;
        const osgUtil::LineSegmentIntersector::Intersection& first = hit->getFirstIntersection();
        centre = first.getWorldIntersectPoint();
        haveCentre = true;
        for (std::size_t i = 0; i < _objects.size(); ++i)
        {
            osg::ref_ptr<osg::Drawable> d;
            if (_objects[i].drawable.lock(d) && d.get() == first.drawable.get()) _focusObject = int(i);
            osg::ref_ptr<osg::Node> node;
            if (_objects[i].node.lock(node) && (std::find(first.nodePath.begin(), first.nodePath.end(),
                                                          node.get()) != first.nodePath.end() ||
                                                node.get() == first.drawable.get()))
                _focusObject = int(i); // the deepest feature on the path wins (index order)
        }
        break;
    }
    case AbstractionFocus::WORLD_POINT:
        centre = f.getWorldPoint();
        haveCentre = true;
        _focusPixel = project(centre);
        if (wantObject)
        {
            double best = 0.0;
            for (std::size_t i = 0; i < _objects.size(); ++i)
            {
                const double d2 = (_objects[i].centre - centre).length2();
                if (_focusObject < 0 || d2 < best) best = d2, _focusObject = int(i);
            }
        }
        break;
    case AbstractionFocus::OBJECT:
        _focusObject = findObject(f.getObjectId());
        if (_focusObject >= 0)
        {
            centre = _objects[std::size_t(_focusObject)].centre;
            haveCentre = true;
            _focusPixel = project(centre);
        }
        else
        {
            _internals->setFocusError("the focus object id " + std::to_string(f.getObjectId()) +
                                      " is not among the node's objects; no focus (strongest abstraction "
                                      "everywhere)");
            _focusPixel = osg::Vec2f(-1e6f, -1e6f);
        }
        break;
    }
    const double diameter = 2.0 * double(getBound().radius());
    for (Object& o : _objects)
        setComponent(*o.importance, _slot,
                     haveCentre ? f.objectImportance(o.centre, centre, diameter) : 0.0f);

    // Uniforms of the passes.
    _focusState->getOrCreateUniform("loa_abstraction_focusPixel", osg::Uniform::FLOAT_VEC2)->set(_focusPixel);
    _focusState->getOrCreateUniform("loa_abstraction_size", osg::Uniform::FLOAT_VEC2)
        ->set(osg::Vec2f(float(_width), float(_height)));
    _focusState->getOrCreateUniform("loa_abstraction_innerRadius", osg::Uniform::FLOAT)
        ->set(f.getInnerRadius());
    _focusState->getOrCreateUniform("loa_abstraction_outerRadius", osg::Uniform::FLOAT)
        ->set(f.getOuterRadius());
    osg::Vec3f focusId(-1.0f, -1.0f, -1.0f);
    if (_focusObject >= 0)
        focusId = osg::Vec3f(idColor(unsigned(_focusObject) + 1).x() * 255.0f,
                             idColor(unsigned(_focusObject) + 1).y() * 255.0f,
                             idColor(unsigned(_focusObject) + 1).z() * 255.0f);
    _focusState->getOrCreateUniform("loa_abstraction_focusId", osg::Uniform::FLOAT_VEC3)->set(focusId);

    _shadingState->getOrCreateUniform("loa_abstraction_levels", osg::Uniform::INT)
        ->set(s.getShading() == AbstractionStyle::PENCIL ? s.getPencilLevels() : s.getCelLevels());
    _shadingState->getOrCreateUniform("loa_abstraction_levelsFar", osg::Uniform::INT)
        ->set(s.getCelLevelsFar());
    _shadingState->getOrCreateUniform("loa_abstraction_ambient", osg::Uniform::FLOAT)->set(s.getAmbient());
    _shadingState->getOrCreateUniform("loa_abstraction_pencilScale", osg::Uniform::FLOAT)
        ->set(s.getPencilScale());

    osg::StateSet& d = *_displayState;
    d.getOrCreateUniform("loa_abstraction_origin", osg::Uniform::INT_VEC2)
        ->set(int(windowOrigin.x()), int(windowOrigin.y()));
    d.getOrCreateUniform("loa_abstraction_edgeOpacity", osg::Uniform::FLOAT)->set(s.getEdgeOpacity());
    d.getOrCreateUniform("loa_abstraction_edgeOpacityFar", osg::Uniform::FLOAT)->set(s.getEdgeOpacityFar());
    d.getOrCreateUniform("loa_abstraction_bleaching", osg::Uniform::FLOAT)->set(s.getBleaching());
    d.getOrCreateUniform("loa_abstraction_sobelThreshold", osg::Uniform::FLOAT)->set(s.getSobelThreshold());
    d.getOrCreateUniform("loa_abstraction_sobelThresholdFar", osg::Uniform::FLOAT)
        ->set(s.getSobelThresholdFar());
    d.getOrCreateUniform("loa_abstraction_brightening", osg::Uniform::FLOAT)->set(s.getBrightening());
    d.getOrCreateUniform("loa_abstraction_pencilGamma", osg::Uniform::FLOAT)->set(s.getPencilGamma());
    d.getOrCreateUniform("loa_abstraction_shadingAtFocus", osg::Uniform::FLOAT)->set(s.getShadingAtFocus());
}

void AbstractionNode::updateWeights()
{
    osg::ref_ptr<LoANode> loa;
    if (!_scenarioNode.lock(loa))
    {
        for (Object& o : _objects)
            setComponent(*o.weight, _slot, 1.0f);
        return;
    }
    for (Object& o : _objects)
        setComponent(*o.weight, _slot, 0.0f);
    const ScenarioEvaluator* ev = loa->getEvaluator();
    const UsageScenario* scenario = loa->getScenario();
    if (!ev || !ev->isBound() || !scenario) return;
    const FeatureIndex& index = loa->getFeatureIndex();
    // Which configurations draw in this node's style (at most UsageScenario::kMaxConfigurations).
    std::vector<char> ours;
    for (const auto& c : scenario->getConfigurations())
        ours.push_back(c->getStyle() == _scenarioStyle);
    for (const ScenarioEvaluator::FeatureState& fs : ev->features())
    {
        if (fs.entry >= index.size()) continue;
        float w = 0.0f;
        const ScenarioEvaluator::Match* m = ev->matchesOf(fs);
        for (unsigned k = 0; k < fs.numMatches; ++k)
            if (m[k].configuration < ours.size() && ours[m[k].configuration]) w += m[k].weight;
        const int i = findObject(index.entries()[fs.entry].feature->getId());
        if (i >= 0) setComponent(*_objects[std::size_t(i)].weight, _slot, std::min(w, 1.0f));
    }
}

void AbstractionNode::traverse(osg::NodeVisitor& nv)
{
    osgUtil::CullVisitor* cv = nv.asCullVisitor();
    if (!cv || !_style.valid() || !_enabled)
    {
        osg::Group::traverse(nv);
        return;
    }
    const osg::Viewport* vp = cv->getViewport();
    if (!vp || vp->width() < 1.0 || vp->height() < 1.0) return;
    try
    {
        // The style may have been edited in place since setStyle.
        _style->validate();
        configure();
        if (_objectsDirty) _slot = nestedAbstractionNodes(*this);
        if (_slot > 3)
            throw std::invalid_argument("more than 4 abstraction nodes nested in one another (their objects "
                                        "share 4 uniform components)");
    }
    catch (const std::exception& e)
    {
        _internals->setFocusError(std::string("style '") + _style->getName() + "': " + e.what() +
                                  "; drawing the children unabstracted");
        osg::Group::traverse(nv);
        return;
    }
    _internals->setFocusError("");
    resize(int(vp->width()), int(vp->height()));
    const Needs n = needsOf(*_style, _scenarioNode.valid());
    const bool objectFocus = _style->getFocus()->getMode() == AbstractionFocus::OBJECT;
    if (_objectsDirty && (n.ids || n.shading || n.unshaded || objectFocus)) collectObjects();
    if (osg::Camera* above = cv->getCurrentCamera())
        for (osg::Camera* c : {_baseCamera.get(), _normalCamera.get()})
        {
            c->setClearColor(above->getClearColor());
            c->setComputeNearFarMode(above->getComputeNearFarMode());
            c->setNearFarRatio(above->getNearFarRatio());
        }
    for (osg::Camera* c : {_idCamera.get(), _shadingCamera.get()})
        if (osg::Camera* above = cv->getCurrentCamera())
        {
            c->setComputeNearFarMode(above->getComputeNearFarMode());
            c->setNearFarRatio(above->getNearFarRatio());
        }
    updateFocus(*cv);
    unsigned passes = 1;
    if (n.base)
    {
        _baseCamera->accept(nv);
        ++passes;
    }
    _normalCamera->accept(nv);
    updateWeights(); // a LoA node below was evaluated in the pass above
    if (n.ids)
    {
        _idCamera->accept(nv);
        ++passes;
    }
    if (n.shading)
    {
        _shadingCamera->accept(nv);
        ++passes;
    }
    _focusCamera->accept(nv);
    _displayCamera->accept(nv);
    std::lock_guard<std::mutex> lock(_internals->mutex);
    _internals->stats.passes = passes;
    _internals->stats.focusObject = _focusObject;
    _internals->stats.focusPixel = _focusPixel;
}

void AbstractionNode::runImageStages(osg::RenderInfo& renderInfo) const
{
    osg::State& state = *renderInfo.getState();

    const unsigned id = state.getContextID();
    Internals::PerContext& c = _internals->contexts[id];
    osg::ref_ptr<ImageFilter> levels = _internals->levels, edges = _internals->edges;
    unsigned runs = 0;
    std::size_t texels = 0;
    if (!levels.valid() && !edges.valid())
    {
        std::lock_guard<std::mutex> lock(_internals->mutex);
        _internals->stats.filterRuns = 0;
        _internals->stats.filterTexels = 0;
        _internals->lastError.clear();
        _internals->stagesOk->set(true);
        return;
    }
    _internals->stagesOk->set(false); // until the stages ran: a failure shows the normal frame
    if (c.engineFailed) return;
    auto object = [&](osg::Texture2D* t) -> osg::Texture::TextureObject*
    {
        if (!t) return nullptr;
        if (!t->getTextureObject(id))
        {
            state.applyTextureAttribute(0, t);
            state.haveAppliedTextureAttribute(0, t);
        }
        return t->getTextureObject(id);
    };
    osg::Texture::TextureObject* normal = object(_normal.get());
    osg::Texture::TextureObject* painterly = object(_painterly.get());
    osg::Texture::TextureObject* edgeImage = object(_edges.get());
    if (!normal || (levels.valid() && !painterly) || (edges.valid() && !edgeImage))
    {
        _internals->fail("the frame textures have no GL objects");
        return;
    }
    try
    {
        if (!c.engine.valid()) c.engine = new GpuFilterEngine(state);
        GpuFilterEngine& e = *c.engine;
        const GLuint pn = painterly ? painterly->id() : 0, en = edgeImage ? edgeImage->id() : 0;
        if (c.normalName != normal->id() || c.painterlyName != pn || c.edgesName != en || c.width != _width ||
            c.height != _height)
        {
            for (unsigned a : {c.normalAtlas, c.painterlyAtlas, c.edgesAtlas})
                if (a) e.destroyAtlas(a);
            c = Internals::PerContext{c.engine, false};
            c.normalName = normal->id();
            c.painterlyName = pn;
            c.edgesName = en;
            c.width = _width;
            c.height = _height;
            c.normalAtlas = e.adoptAtlas(c.normalName, _width, _height);
            if (pn) c.painterlyAtlas = e.adoptAtlas(pn, _width, _height);
            if (en) c.edgesAtlas = e.adoptAtlas(en, _width, _height);
        }
        GpuFilterEngine::Region region;
        region.width = _width;
        region.height = _height;
        region.border = ImageBorder(WrapMode::Clamp, WrapMode::Clamp);
        if (levels.valid())
        {
            texels += e.run(*levels, c.normalAtlas, c.painterlyAtlas, {region}).texels;
            ++runs;
        }
        if (edges.valid())
        {
            const bool abstracted =
                _style->getEdgeSource() == AbstractionStyle::ABSTRACTED_IMAGE && levels.valid();
            texels +=
                e.run(*edges, abstracted ? c.painterlyAtlas : c.normalAtlas, c.edgesAtlas, {region}).texels;
            ++runs;
        }
        std::lock_guard<std::mutex> lock(_internals->mutex);
        _internals->stats.filterRuns = runs;
        _internals->stats.filterTexels = texels;
        _internals->lastError.clear();
        _internals->stagesOk->set(true);
    }
    catch (const std::exception& ex)
    {
        if (!c.engine.valid()) c.engineFailed = true;
        _internals->fail(ex.what());
    }
}

void AbstractionNode::releaseGLObjects(osg::State* state) const
{
    osg::Group::releaseGLObjects(state);
    for (const osg::Camera* c : {_baseCamera.get(), _normalCamera.get(), _idCamera.get(),
                                 _shadingCamera.get(), _focusCamera.get(), _displayCamera.get()})
        c->releaseGLObjects(state);
    for (const osg::Texture2D* t : {_base.get(), _normal.get(), _ids.get(), _objectData.get(), _surface.get(),
                                    _shading.get(), _painterly.get(), _edges.get()})
        if (t) t->releaseGLObjects(state);
    if (_pencil.valid()) _pencil->releaseGLObjects(state);
    for (unsigned i = 0; i < _internals->contexts.size(); ++i)
    {
        Internals::PerContext& c = _internals->contexts[i];
        if (state && state->getContextID() == i && c.engine.valid()) c.engine->releaseGLObjects();
        if (!state || state->getContextID() == i) c = Internals::PerContext();
    }
}

void AbstractionNode::resizeGLObjectBuffers(unsigned int maxSize)
{
    osg::Group::resizeGLObjectBuffers(maxSize);
    for (osg::Camera* c : {_baseCamera.get(), _normalCamera.get(), _idCamera.get(), _shadingCamera.get(),
                           _focusCamera.get(), _displayCamera.get()})
        c->resizeGLObjectBuffers(maxSize);
    _internals->contexts.resize(maxSize);
}

bool AbstractionNode::addChild(osg::Node* child)
{
    _objectsDirty = true;
    return osg::Group::addChild(child);
}

bool AbstractionNode::insertChild(unsigned int index, osg::Node* child)
{
    _objectsDirty = true;
    return osg::Group::insertChild(index, child);
}

bool AbstractionNode::removeChildren(unsigned int pos, unsigned int numChildrenToRemove)
{
    _objectsDirty = true;
    return osg::Group::removeChildren(pos, numChildrenToRemove);
}

bool AbstractionNode::replaceChild(osg::Node* origChild, osg::Node* newChild)
{
    _objectsDirty = true;
    return osg::Group::replaceChild(origChild, newChild);
}

bool AbstractionNode::setChild(unsigned int i, osg::Node* node)
{
    _objectsDirty = true;
    return osg::Group::setChild(i, node);
}

} // namespace osgLoA
