// TransitionRenderer: Algorithm 1 of paper 004 and the G-buffer, A-buffer, ping-pong and
// compositing passes around it.
#include <osgLoA/transitions/TransitionRenderer>

#include <osgLoA/compositing/StencilRoutedABuffer>
#include <osgLoA/render/GLCapabilities>
#include <osgLoA/render/ShaderLibrary>
#include <osgLoA/semantics/FeatureSubType>
#include <osgLoA/styles/ColorScheme>
#include <osgLoA/styles/FixedFunctionUniforms>
#include <osgLoA/styles/GraphicStyle>
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/transitions/LandmarkDeformation>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/TransitionUniforms>
#include <osgLoA/util/StateSetVisitor>

#include <osg/Notify>
#include <osg/Texture>
#include <osg/Transform>

#include <algorithm>
#include <bitset>
#include <cmath>
#include <functional>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace osgLoA
{

namespace
{
constexpr unsigned kN = UsageScenario::kMaxConfigurations;
constexpr unsigned kFrontDepthUnit = 14;
constexpr int kFirstRenderOrder = 1000;
constexpr unsigned kABufferColorUnit = 12, kABufferDepthUnit = 13, kABufferRegionUnit = 15;

const char* const kVertexShaders[] = {"loa_style.vert.glsl", "loa_landmark.vert.glsl"};

enum ProxyKind
{
    PROXY_GBUFFER = 0,
    PROXY_ABUFFER,
    PROXY_PING0,
    PROXY_PING1
};

/** The child of a pass camera: traversing it draws the features in that camera's passes. */
class PassProxy : public osg::Node
{
public:
    PassProxy(TransitionRenderer* renderer, ProxyKind kind,
              std::function<void(osgUtil::CullVisitor&, ProxyKind)> fn)
        : _renderer(renderer), _kind(kind), _fn(std::move(fn))
    {
        setCullingActive(false);
    }
    void traverse(osg::NodeVisitor& nv) override
    {
        osg::ref_ptr<TransitionRenderer> r;
        osgUtil::CullVisitor* cv = nv.asCullVisitor();
        if (cv && _renderer.lock(r)) _fn(*cv, _kind);
    }

private:
    osg::observer_ptr<TransitionRenderer> _renderer;
    ProxyKind _kind;
    std::function<void(osgUtil::CullVisitor&, ProxyKind)> _fn;
};

/** On a feature's node (Group, Geode, ...): lets the renderer decide whether it draws. */
class FeatureNodeCallback : public osg::NodeCallback
{
public:
    FeatureNodeCallback(TransitionRenderer* r, unsigned entry) : _renderer(r), _entry(entry) {}
    void operator()(osg::Node* node, osg::NodeVisitor* nv) override
    {
        osg::ref_ptr<TransitionRenderer> r;
        osgUtil::CullVisitor* cv = nv->asCullVisitor();
        if (!cv || !_renderer.lock(r) || !r->isDrawing())
        {
            traverse(node, nv);
            return;
        }
        r->drawFeature(_entry, *node, *cv, this);
    }

private:
    osg::observer_ptr<TransitionRenderer> _renderer;
    unsigned _entry;
};

/** On a feature that is a Drawable: the same, drawing the drawable under the feature's state. */
class FeatureDrawableCallback : public osg::DrawableCullCallback
{
public:
    FeatureDrawableCallback(TransitionRenderer* r, unsigned entry) : _renderer(r), _entry(entry) {}
    bool cull(osg::NodeVisitor* nv, osg::Drawable* drawable, osg::RenderInfo*) const override
    {
        if (_inside) return false; // the renderer's own apply of the drawable
        osg::ref_ptr<TransitionRenderer> r;
        osgUtil::CullVisitor* cv = nv->asCullVisitor();
        if (!cv || !_renderer.lock(r) || !r->isDrawing()) return false;
        _inside = true;
        r->drawFeature(_entry, *drawable, *cv, nullptr);
        _inside = false;
        return true;
    }

private:
    osg::observer_ptr<TransitionRenderer> _renderer;
    unsigned _entry;
    mutable bool _inside = false;
};

/** Whether a feature's material is opaque: none of its StateSets blends or uses the transparent
 *  bin (FixedFunctionUniforms::isOpaque; without blending, alpha is ignored, as by OSG). */
bool inspectMaterial(osg::Node& node)
{
    bool opaque = true;
    StateSetVisitor v([&](osg::StateSet& ss) { opaque = opaque && FixedFunctionUniforms::isOpaque(ss); });
    node.accept(v);
    return opaque;
}

osg::Uniform* uniform(osg::StateSet& ss, const char* name, osg::Uniform::Type type, unsigned n = 1)
{
    osg::Uniform* u = ss.getOrCreateUniform(name, type, n);
    u->setDataVariance(osg::Object::DYNAMIC);
    return u;
}

/** The projection with near and far planes fitted to a sphere given in view coordinates. */
osg::Matrixd fitDepthRange(const osg::Matrixd& p, const osg::BoundingSphere& viewSphere, double& zNear,
                           double& zFar, bool& orthographic)
{
    orthographic = p(3, 3) == 1.0 && p(2, 3) == 0.0;
    const double zc = -viewSphere.center().z();
    zFar = zc + viewSphere.radius();
    zNear = zc - viewSphere.radius();
    double l, r, b, t, n0, f0;
    if (orthographic)
    {
        if (!(zFar > zNear)) zFar = zNear + 1.0;
        p.getOrtho(l, r, b, t, n0, f0);
        return osg::Matrixd::ortho(l, r, b, t, zNear, zFar);
    }
    if (!(zFar > 0.0)) zFar = 1.0;
    zNear = std::max(zNear, zFar * 1.0e-4);
    if (!p.getFrustum(l, r, b, t, n0, f0) || !(n0 > 0.0)) return p;
    const double s = zNear / n0;
    return osg::Matrixd::frustum(l * s, r * s, b * s, t * s, zNear, zFar);
}

/** The shaders every feature draw links: the vertex stage, the blend weights, the material's
 *  alpha test, and (for passes that draw a style) the fixed-function equations styles call. */
void addFeatureShaders(osg::Program& p, bool styled, const std::string& geometryShader = std::string())
{
    // A style's geometry stage takes the vertex stage's outputs under their loa_vs* names.
    for (const char* v : kVertexShaders)
        p.addShader(geometryShader.empty()
                        ? ShaderLibrary::createShader(v).get()
                        : ShaderLibrary::createShader(v, {{"LOA_GEOMETRY_STAGE", ""}}).get());
    if (!geometryShader.empty()) p.addShader(ShaderLibrary::createShader(geometryShader).get());
    p.addShader(ShaderLibrary::createShader("loa_transition.frag.glsl").get());
    p.addShader(ShaderLibrary::createShader("loa_material_alpha.frag.glsl").get());
    if (styled) p.addShader(ShaderLibrary::createShader("loa_fixed_function.frag.glsl").get());
}

/** The pass's main (loa_pass.frag.glsl) with the pass's defines ("A B": A and B defined as 1). */
osg::ref_ptr<osg::Shader> passMain(const std::string& passDefines)
{
    ShaderLibrary::Defines defines;
    std::istringstream words(passDefines);
    for (std::string d; words >> d;)
        defines.emplace_back(d, "");
    return ShaderLibrary::createShader("loa_pass.frag.glsl", defines);
}

/** The functions a GLSL source defines (with a body; not those it only declares), main aside:
 *  in a fused program each style's are renamed with the style's suffix, so that two styles
 *  (or two copies of one included helper file) may define a function of one name. */
std::vector<std::string> definedFunctions(const std::string& text)
{
    static const std::regex definition(
        R"((?:^|[;}\s])(?:void|bool|int|uint|float|double|[biud]?vec[234]|mat[234](?:x[234])?)\s+([A-Za-z_]\w*)\s*\([^;{)]*\)\s*\{)");
    std::vector<std::string> names;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), definition); it != std::sregex_iterator();
         ++it)
    {
        const std::string name = (*it)[1].str();
        if (name != "main" && std::find(names.begin(), names.end(), name) == names.end())
            names.push_back(name);
    }
    return names;
}

/** Whether two styles' parameter StateSets set something differently (a uniform of one name
 *  with other values, a mode, an attribute or a texture of one unit, a define): such styles
 *  cannot share one fused program, where each name has one value. */
bool conflicting(const osg::StateSet& a, const osg::StateSet& b)
{
    for (const auto& u : a.getUniformList())
    {
        const osg::Uniform* other = b.getUniform(u.first);
        if (other && u.second.first.valid() && other->compare(*u.second.first) != 0) return true;
    }
    for (const auto& m : a.getModeList())
    {
        auto it = b.getModeList().find(m.first);
        if (it != b.getModeList().end() && it->second != m.second) return true;
    }
    auto attributesDiffer = [](const osg::StateSet::AttributeList& x, const osg::StateSet::AttributeList& y)
    {
        for (const auto& at : x)
        {
            auto it = y.find(at.first);
            if (it != y.end() &&
                (it->second.first->compare(*at.second.first) != 0 || it->second.second != at.second.second))
                return true;
        }
        return false;
    };
    if (attributesDiffer(a.getAttributeList(), b.getAttributeList())) return true;
    const auto& ta = a.getTextureAttributeList();
    const auto& tb = b.getTextureAttributeList();
    for (std::size_t unit = 0; unit < std::min(ta.size(), tb.size()); ++unit)
        if (attributesDiffer(ta[unit], tb[unit])) return true;
    const auto& ma = a.getTextureModeList();
    const auto& mb = b.getTextureModeList();
    for (std::size_t unit = 0; unit < std::min(ma.size(), mb.size()); ++unit)
        for (const auto& m : ma[unit])
        {
            auto it = mb[unit].find(m.first);
            if (it != mb[unit].end() && it->second != m.second) return true;
        }
    for (const auto& d : a.getDefineList())
    {
        auto it = b.getDefineList().find(d.first);
        if (it != b.getDefineList().end() && it->second != d.second) return true;
    }
    return false;
}

} // namespace

TransitionRenderer::TransitionRenderer(LoANode& node) : _node(node)
{
    // Render orders after every other pre-render camera of the scene (the distance field's
    // jump-flooding passes count from 0).
    _gbuffer = new GeometryBuffer(kFirstRenderOrder);
    _pingPong = new PingPongBuffer(kFirstRenderOrder + 2);
    _unsharp = new DepthUnsharpMask(kFirstRenderOrder + 4);
    _unsharp->setInput(_gbuffer->getTexture(GeometryBuffer::DEPTH), _gbuffer->getTexture(GeometryBuffer::ID));
    _compositing = new ImageCompositing;
    _compositing->setGeometryBuffer(_gbuffer.get());
    _compositing->setPingPongBuffer(_pingPong.get());
    _compositing->setDepthUnsharpMask(_unsharp.get());
    setSettings(_settings);

    auto fn = [this](osgUtil::CullVisitor& cv, ProxyKind kind)
    {
        if (kind == PROXY_GBUFFER)
        {
            for (unsigned j = 0; j < _styles.size(); ++j)
                if (_sharedAny[j])
                    traversePass(cv, Pass::SHARED, int(j), _styles[j].parameters.get(),
                                 _styles[j].shared.get());
            for (unsigned mask : _fusedMasks)
                traversePass(cv, Pass::FUSED, -1, nullptr, fusedState(mask), mask);
            if (_depthAny) traversePass(cv, Pass::DEPTH_ONLY, -1, nullptr, _depthOnly.get());
            if (_hasUnfeatured) traversePass(cv, Pass::UNFEATURED, -1, nullptr, _unfeatured.get());
        }
        else if (kind == PROXY_ABUFFER)
        {
            for (unsigned j = 0; j < _styles.size(); ++j)
                if (_aAny[j])
                    traversePass(cv, Pass::A_BUFFER, int(j), _styles[j].parameters.get(),
                                 _styles[j].aBuffer.get());
        }
        else
        {
            const unsigned target = kind == PROXY_PING0 ? 0u : 1u;
            for (unsigned j = 0; j < _styles.size(); ++j)
                if (_pingAny[j] && _styles[j].pingTarget == target)
                    traversePass(cv, Pass::PING_PONG, int(j), _styles[j].parameters.get(),
                                 _styles[j].pingPong.get());
        }
    };
    _proxy[PROXY_GBUFFER] = new PassProxy(this, PROXY_GBUFFER, fn);
    _proxy[PROXY_ABUFFER] = new PassProxy(this, PROXY_ABUFFER, fn);
    _proxy[PROXY_PING0] = new PassProxy(this, PROXY_PING0, fn);
    _proxy[PROXY_PING1] = new PassProxy(this, PROXY_PING1, fn);
    _gbuffer->getCamera()->addChild(_proxy[PROXY_GBUFFER].get());
    _aBuffer->getRoutedGroup()->addChild(_proxy[PROXY_ABUFFER].get());
    _pingPong->getCamera(0)->addChild(_proxy[PROXY_PING0].get());
    _pingPong->getCamera(1)->addChild(_proxy[PROXY_PING1].get());

    _internal = new osg::Group;
    _passStates = new osg::Group;
    _internal->addChild(_gbuffer->getCamera());
    _internal->addChild(_pingPong->getCamera(0));
    _internal->addChild(_pingPong->getCamera(1));
    for (unsigned p = 0; p < DepthUnsharpMask::NUM_PASSES; ++p)
        _internal->addChild(_unsharp->getCamera(p));
    _internal->addChild(_compositing->getNode());
    _internal->addChild(_passStates.get());
    _internal->addChild(_aBuffer->getCamera());

    _common = new osg::StateSet;
    _common->setDataVariance(osg::Object::DYNAMIC);
    _viewToScene = uniform(*_common, "loa_viewToScene", osg::Uniform::FLOAT_MAT4);
    _sceneToView = uniform(*_common, "loa_sceneToView", osg::Uniform::FLOAT_MAT4);
    // The viewport, for geometry stages (leaf sprites' minimum size, object edges' widths).
    _viewportHeight = uniform(*_common, "loa_viewportHeight", osg::Uniform::FLOAT);
    _viewportWidth = uniform(*_common, "loa_viewportWidth", osg::Uniform::FLOAT);
    // Not a crown unless a drawable says so (TreeSilhouettes::markCrowns): set here, since a
    // program keeps a uniform's last value for drawables that do not set it.
    uniform(*_common, "loa_treeCrown", osg::Uniform::BOOL)->set(false);
    uniform(*_common, "loa_objectEdgesData", osg::Uniform::BOOL)->set(false);
    uniform(*_common, "loa_baseTexture", osg::Uniform::SAMPLER_2D)->set(0);
    // The fixed-function state the styles reproduce starts from OSG's defaults (with the
    // samplers of texture units 1 and 2); the model's
    // StateSets carry their own (bind()). The alpha test is the shaders' (loa_alphaFunc): GL's
    // would test the blend-weighted alpha of the A-buffer pass.
    FixedFunctionUniforms::setDefaults(*_common);
    _common->setMode(GL_ALPHA_TEST, osg::StateAttribute::OFF | osg::StateAttribute::OVERRIDE |
                                        osg::StateAttribute::PROTECTED);
    uniform(*_common, "loa_frontDepth", osg::Uniform::SAMPLER_2D)->set(int(kFrontDepthUnit));
}

TransitionRenderer::~TransitionRenderer()
{
    removeCallbacks();
}

OrderIndependentTransparency::Method TransitionRenderer::methodInUse(const Settings& s)
{
    // (With one sample the raster coverage is the pixel centre's: exact.)
    if (s.oit == OrderIndependentTransparency::STENCIL_ROUTED && !s.approximateStencilRouting &&
        s.samples > 1 && StencilRoutedABuffer::rasterCoverageByDefault(GLCapabilities::lastQueriedRenderer()))
        return OrderIndependentTransparency::LINKED_LIST;
    return s.oit;
}

void TransitionRenderer::setSettings(const Settings& settings)
{
    Settings s = settings;
    if (s.oitAuto && !_settings.oitAuto)
    {
        Settings stencil = s;
        stencil.oit = OrderIndependentTransparency::STENCIL_ROUTED;
        if (methodInUse(stencil) == OrderIndependentTransparency::STENCIL_ROUTED)
            _oitSelection = OITAutoSelection();
        else
            _oitSelection = OITAutoSelection({OrderIndependentTransparency::LINKED_LIST});
    }
    if (s.oitAuto) s.oit = _oitSelection.current();
    if (s.samples == 0)
        throw std::invalid_argument("TransitionRenderer: the A-buffer needs at least 1 sample");
    if (s.maxPasses == 0)
        throw std::invalid_argument("TransitionRenderer: at least 1 routing pass is needed");
    if (!(s.depthEpsilon >= 0.0f) || s.depthEpsilon > 0.01f)
        throw std::invalid_argument("TransitionRenderer: depth epsilon must be in [0, 0.01]");
    const OrderIndependentTransparency::Method inUse = methodInUse(s);
    _oitRendererKnown = !GLCapabilities::lastQueriedRenderer().empty();
    const bool rebuild = !_aBuffer.valid() || s.samples != _settings.samples ||
                         s.maxPasses != _settings.maxPasses || inUse != _oitInUse;
    _settings = s;
    if (rebuild)
    {
        if (_aBuffer.valid() && _proxy[PROXY_ABUFFER].valid())
            _aBuffer->getRoutedGroup()->removeChild(_proxy[PROXY_ABUFFER].get());
        if (_aBuffer.valid() && _internal.valid()) _internal->removeChild(_aBuffer->getCamera());
        _aBuffer = OrderIndependentTransparency::create(inUse, int(s.samples), int(s.maxPasses));
        _oitInUse = inUse;
        // Same matrices as the G-buffer (the front-depth test compares their depths).
        _aBuffer->getCamera()->setReferenceFrame(osg::Transform::ABSOLUTE_RF);
        _aBuffer->getCamera()->setRenderOrder(osg::Camera::PRE_RENDER, kFirstRenderOrder + 1);
        if (_proxy[PROXY_ABUFFER].valid()) _aBuffer->getRoutedGroup()->addChild(_proxy[PROXY_ABUFFER].get());
        _aBuffer->addResolveState(_compositing->getStateSet(), kABufferColorUnit, kABufferDepthUnit);
        _aBuffer->addRegionState(_compositing->getStateSet(), kABufferRegionUnit);
        _compositing->setFetchShader(_aBuffer->getFetchShaderName());
        // Local arrays sized to the fragments that can occur: the A-buffer's N x passes plus the
        // G-buffer's opaque colour and the ping-pong fragment.
        _aBuffer->setMaxFragmentsDefine(_compositing->getStateSet(), 2);
        if (_internal.valid()) _internal->addChild(_aBuffer->getCamera());
        // The A-buffer draws link the method's write shader.
        for (auto& st : _styles)
            if (st.aBuffer.valid() && st.style.valid())
                st.aBuffer->setAttributeAndModes(
                    program(st.style->getFragmentShader(), "LOA_PASS_ABUFFER", st.style->getGeometryShader())
                        .get());
    }
    _compositing->setMergeEpsilon(s.mergeSurfaces ? s.depthEpsilon : -1.0f);
    for (auto& st : _styles)
        for (osg::StateSet* ss : {st.aBuffer.get(), st.pingPong.get()})
            if (ss) ss->getOrCreateUniform("loa_depthEpsilon", osg::Uniform::FLOAT)->set(s.depthEpsilon);
}

osg::ref_ptr<osg::Program> TransitionRenderer::program(const std::string& styleShader, const char* passDefine,
                                                       const std::string& geometryShader)
{
    const bool routed = std::string(passDefine).find("LOA_PASS_ABUFFER") != std::string::npos;
    const std::string key = styleShader + "|" + geometryShader + "|" + passDefine +
                            (routed ? std::string("|") + _aBuffer->getWriteShaderName() : "");
    auto it = _programs.find(key);
    if (it != _programs.end()) return it->second;
    osg::ref_ptr<osg::Program> p = new osg::Program;
    p->setName("loa-" + (styleShader.empty() ? std::string("depth") : styleShader) + "-" + passDefine);
    addFeatureShaders(*p, !styleShader.empty(), geometryShader);
    if (!styleShader.empty())
    {
        // The style sees the pass's defines too, so that it can tell its own draw (the shared
        // G-buffer pass, LOA_PASS_GBUFFER_COLOR) from blends with other styles.
        ShaderLibrary::Defines defines;
        std::istringstream words(passDefine);
        for (std::string w; words >> w;)
            defines.emplace_back(w, "");
        p->addShader(ShaderLibrary::createShader(styleShader, defines).get());
    }
    if (routed) p->addShader(ShaderLibrary::createShader(_aBuffer->getWriteShaderName()).get());
    p->addShader(passMain(passDefine).get());
    _programs[key] = p;
    return p;
}

osg::StateSet* TransitionRenderer::fusedState(unsigned mask)
{
    auto found = _fused.find(mask);
    if (found != _fused.end()) return found->second.get();
    // The configurations, and the distinct style shaders among them: configurations of one
    // shader (compatible parameters, so the same values) share one evaluation of it.
    std::vector<unsigned> configurations;
    std::vector<std::string> shaders;
    std::vector<std::vector<unsigned>> slotsOfShader; // shader -> slots (index into configurations)
    for (unsigned j = 0; j < _styles.size(); ++j)
    {
        if (!(mask & (1u << j))) continue;
        const std::string frag = _styles[j].style->getFragmentShader();
        auto it = std::find(shaders.begin(), shaders.end(), frag);
        if (it == shaders.end())
        {
            shaders.push_back(frag);
            slotsOfShader.emplace_back();
            it = shaders.end() - 1;
        }
        slotsOfShader[std::size_t(it - shaders.begin())].push_back(unsigned(configurations.size()));
        configurations.push_back(j);
    }
    osg::ref_ptr<osg::Program> p = new osg::Program;
    std::string label;
    for (unsigned j : configurations)
        label += (label.empty() ? "" : "+") + _styles[j].style->getName() + "#" + std::to_string(j);
    p->setName(ShaderLibrary::objectLabel("loa-fused-" + label));
    addFeatureShaders(*p, true);
    // Each style's functions (loa_styleColor and its helpers, included ones too) under names of
    // its own: ShaderLibrary::createShader with `#define NAME NAME_s`.
    for (std::size_t s = 0; s < shaders.size(); ++s)
    {
        ShaderLibrary::Defines renames;
        for (const std::string& f : definedFunctions(ShaderLibrary::getSource(shaders[s]).text))
            renames.emplace_back(f, f + "_" + std::to_string(s));
        p->addShader(ShaderLibrary::createShader(shaders[s], renames).get());
    }
    // loa_fusedColor: the weights of the (at most four) configurations in one evaluation, every
    // style evaluated (no branch: the styles take screen-space derivatives and implicit-LOD
    // texture samples, undefined in non-uniform control flow), blended by weight.
    const char* lanes = "xyzw";
    std::string src = "#version 450 compatibility\n// Fused styles of configurations " + label +
                      " (osgLoA::TransitionRenderer::fusedState)\n"
                      "uniform vec4 loa_styleEdge[16];\nuniform float loa_styleUnsharp[16];\n"
                      "vec4 loa_blendWeights4(ivec4 js, vec3 p);\n";
    for (std::size_t s = 0; s < shaders.size(); ++s)
        src += "vec4 loa_styleColor_" + std::to_string(s) +
               "(vec3 scenePosition, vec3 viewPosition, vec3 viewNormal, vec2 texCoord, vec4 color);\n";
    std::string js;
    for (std::size_t k = 0; k < 4; ++k)
        js += (k ? ", " : "") +
              (k < configurations.size() ? std::to_string(configurations[k]) : std::string("-1"));
    src += "vec4 loa_fusedColor(vec3 scenePosition, vec3 viewPosition, vec3 viewNormal, vec2 texCoord, vec4 "
           "color,\n"
           "                    out vec4 edge, out float unsharp)\n{\n"
           "    vec4 w = loa_blendWeights4(ivec4(" +
           js +
           "), scenePosition);\n"
           "    edge = vec4(0.0);\n    unsharp = 0.0;\n    vec3 c = vec3(0.0);\n";
    for (std::size_t k = 0; k < configurations.size(); ++k)
    {
        const std::string j = std::to_string(configurations[k]), wk = std::string("w.") + lanes[k];
        src += "    edge += " + wk + " * vec4(loa_styleEdge[" + j + "].rgb * loa_styleEdge[" + j +
               "].a, loa_styleEdge[" + j + "].a);\n    unsharp += " + wk + " * loa_styleUnsharp[" + j +
               "];\n";
    }
    for (std::size_t s = 0; s < shaders.size(); ++s)
    {
        std::string ws;
        for (unsigned slot : slotsOfShader[s])
            ws += (ws.empty() ? "" : " + ") + std::string("w.") + lanes[slot];
        src += "    c += (" + ws + ") * loa_styleColor_" + std::to_string(s) +
               "(scenePosition, viewPosition, viewNormal, texCoord, color).rgb;\n";
    }
    src += "    return vec4(c, dot(w, vec4(1.0)));\n}\n";
    osg::ref_ptr<osg::Shader> fused = new osg::Shader(osg::Shader::FRAGMENT, src);
    fused->setName(ShaderLibrary::objectLabel("loa_fused[" + label + "]"));
    p->addShader(fused.get());
    p->addShader(passMain("LOA_PASS_GBUFFER_FUSED").get());
    _programs["fused|" + std::to_string(mask)] = p;

    osg::ref_ptr<osg::StateSet> ss = new osg::StateSet;
    for (unsigned j : configurations)
        if (_styles[j].parameters.valid()) ss->merge(*_styles[j].parameters);
    ss->setAttributeAndModes(p.get());
    osg::ref_ptr<osg::Node> holder = new osg::Node;
    holder->setStateSet(ss.get());
    _passStates->addChild(holder.get());
    _fused[mask] = ss;
    return ss.get();
}

void TransitionRenderer::bind(const ScenarioEvaluator& evaluator, const FeatureIndex& index)
{
    unbind();
    const UsageScenario* scenario = evaluator.getScenario();
    if (!scenario) return;
    const auto& configs = scenario->getConfigurations();
    const unsigned n = unsigned(std::min<std::size_t>(configs.size(), kN));
    // Textures, lighting, materials, texture environments and alpha tests wherever they sit in
    // the model (a feature's own node, a Geode, a drawable): uniforms the styles read.
    for (unsigned c = 0; c < _node.getNumChildren(); ++c)
        FixedFunctionUniforms::annotate(*_node.getChild(c));
    _styles.assign(n, StyleState());
    _geometryStageMask = 0;
    int visibleMask = 0;
    osg::Uniform* edge = uniform(*_common, "loa_styleEdge", osg::Uniform::FLOAT_VEC4, kN);
    osg::Uniform* unsharp = uniform(*_common, "loa_styleUnsharp", osg::Uniform::FLOAT, kN);
    _maxUnsharpSigma = 0.0f;
    osg::Texture2D* frontDepth = _gbuffer->getTexture(GeometryBuffer::DEPTH);
    for (unsigned j = 0; j < n; ++j)
    {
        StyleState& st = _styles[j];
        osg::ref_ptr<GraphicStyle> style;
        try
        {
            style = GraphicStyleCatalog::instance().create(configs[j]->getStyle());
        }
        catch (const std::invalid_argument& e)
        {
            throw std::invalid_argument("configuration '" + configs[j]->getName() + "': " + e.what());
        }
        st.style = style;
        st.visible = style->getVisible();
        st.opaque = style->getOpaque();
        st.parameters = style->getParameters();
        edge->setElement(j, _settings.edges ? style->getEdge() : osg::Vec4f());
        const float lambda = _settings.unsharpMasking ? style->getUnsharpMaskStrength() : 0.0f;
        unsharp->setElement(j, lambda);
        if (lambda > 0.0f) _maxUnsharpSigma = std::max(_maxUnsharpSigma, style->getUnsharpMaskRadius());
        if (!style->getGeometryShader().empty()) _geometryStageMask |= 1u << j;
        st.fusable = st.visible && st.opaque && !style->getFragmentShader().empty() &&
                     style->getGeometryShader().empty(); // another stage: not in a fused program
        for (unsigned k = 0; k < j; ++k)
            if (_styles[k].parameters.valid() && st.parameters.valid() &&
                conflicting(*_styles[k].parameters, *st.parameters))
            {
                st.conflicts |= 1u << k;
                _styles[k].conflicts |= 1u << j;
            }
        if (!st.visible) continue;
        visibleMask |= 1 << j;
        const std::string frag = st.style->getFragmentShader();
        auto passState = [&](const char* define, bool frontDepthNeeded)
        {
            osg::ref_ptr<osg::StateSet> ss = new osg::StateSet;
            ss->setAttributeAndModes(program(frag, define, style->getGeometryShader()).get());
            ss->addUniform(new osg::Uniform("loa_configuration", int(j)));
            ss->addUniform(new osg::Uniform("loa_styleUsesTexture", style->getUsesTexture()));
            if (frontDepthNeeded)
            {
                ss->setTextureAttribute(kFrontDepthUnit, frontDepth);
                ss->addUniform(new osg::Uniform("loa_depthEpsilon", _settings.depthEpsilon));
            }
            return ss;
        };
        st.shared = passState("LOA_PASS_GBUFFER_COLOR", false);
        st.sharedCovered = passState("LOA_PASS_GBUFFER_COLOR LOA_COVERED", false);
        st.aBuffer = passState("LOA_PASS_ABUFFER", true);
        st.pingPong = passState("LOA_PASS_PINGPONG", true);
        for (osg::StateSet* ss :
             {st.shared.get(), st.sharedCovered.get(), st.aBuffer.get(), st.pingPong.get()})
        {
            osg::ref_ptr<osg::Node> holder = new osg::Node;
            holder->setStateSet(ss);
            _passStates->addChild(holder.get());
        }
    }
    uniform(*_common, "loa_visibleStyles", osg::Uniform::INT)->set(visibleMask);
    _depthOnly = new osg::StateSet;
    _depthOnly->setAttributeAndModes(program("", "LOA_PASS_GBUFFER_DEPTH").get());
    _unfeatured = new osg::StateSet;
    {
        osg::ref_ptr<const GraphicStyle> photo = GraphicStyleCatalog::instance().prototype("photorealistic");
        _unfeatured->setAttributeAndModes(program(photo.valid()
                                                      ? photo->getFragmentShader()
                                                      : std::string("loa_style_photorealistic.frag.glsl"),
                                                  "LOA_PASS_GBUFFER_COLOR LOA_UNFEATURED")
                                              .get());
        _unfeatured->addUniform(new osg::Uniform("loa_configuration", 0));
        _unfeatured->addUniform(new osg::Uniform("loa_featureId", 0u));
    }
    for (osg::StateSet* ss : {_depthOnly.get(), _unfeatured.get()})
    {
        osg::ref_ptr<osg::Node> holder = new osg::Node;
        holder->setStateSet(ss);
        _passStates->addChild(holder.get());
    }
    LandmarkDeformation::applyScenario(*_common, scenario->getLandmarkDeformation());
    // The scenario's colour scheme for every cartographic style (none: all sub-types unset).
    {
        const ColorScheme::Scheme* scheme = ColorScheme::find(scenario->getColorScheme());
        _common->addUniform(ColorScheme::uniform(scheme ? *scheme : ColorScheme::schemes().front()).get());
    }

    // Features: per-feature state, the ping-pong routing, opaque materials, callbacks.
    const auto& features = evaluator.features();
    _featureState.assign(features.size(), nullptr);
    _featureOfEntry.assign(index.size(), -1);
    _opaqueMaterial.assign(features.size(), 1);
    _routedToPingPong.assign(features.size(), 0);
    _decisions.assign(features.size(), Decision());
    for (std::size_t i = 0; i < features.size(); ++i)
    {
        const FeatureIndex::Entry& e = index.entries()[features[i].entry];
        _featureOfEntry[features[i].entry] = int(i);
        osg::ref_ptr<osg::StateSet> ss = new osg::StateSet;
        ss->setDataVariance(osg::Object::DYNAMIC);
        uniform(*ss, "loa_featureType", osg::Uniform::INT)->set(int(e.feature->getType()));
        uniform(*ss, "loa_featureSubType", osg::Uniform::INT)
            ->set(FeatureSubType::code(e.feature->getSubType()));
        uniform(*ss, "loa_featureId", osg::Uniform::UNSIGNED_INT)->set(e.feature->getId());
        _featureState[i] = ss;
        if (osg::Node* node = e.node.get()) _opaqueMaterial[i] = inspectMaterial(*node) ? 1 : 0;
        const auto& subs = _settings.pingPongSubTypes;
        // The ping-pong buffer keeps one opaque fragment per pixel: it serves forests of opaque
        // materials only (paper 004 §4.4: it "only resolves this issue if features are rendered
        // opaquely"). Alpha-blended tree cards go to the order-independent transparency with their
        // alpha, else the ping-pong pass's alpha test cuts their fringes.
        _routedToPingPong[i] = _settings.pingPong && _opaqueMaterial[i] &&
                               e.feature->getType() == FeatureType::Green &&
                               std::find(subs.begin(), subs.end(), e.feature->getSubType()) != subs.end();
    }
    // Ping-pong targets alternate over the configurations that forests match.
    unsigned rank = 0;
    for (unsigned j = 0; j < n; ++j)
    {
        bool used = false;
        for (std::size_t i = 0; i < features.size() && !used; ++i)
        {
            if (!_routedToPingPong[i]) continue;
            const ScenarioEvaluator::Match* m = evaluator.matchesOf(features[i]);
            for (unsigned k = 0; k < features[i].numMatches; ++k)
                used = used || m[k].configuration == j;
        }
        _styles[j].pingTarget = used ? (rank++ & 1u) : 0u;
    }
    _sharedAny.assign(n, 0);
    _aAny.assign(n, 0);
    _pingAny.assign(n, 0);
    bindLabels(index);
    installCallbacks(index);
    _bound = true;
}

void TransitionRenderer::bindLabels(const FeatureIndex& index)
{
    // Street labels: the configurations whose style has a label layer (StreetLabels), the
    // parameters of the first of them, and the model's labelled streets.
    _labelMask = 0;
    _labels = nullptr;
    _labelStreetFeature.clear();
    bool first = true;
    for (unsigned j = 0; j < _styles.size(); ++j)
    {
        StreetLabels::Parameters p;
        if (!_styles[j].style.valid() || !_styles[j].visible ||
            !StreetLabels::parametersOf(*_styles[j].style, p))
            continue;
        _labelMask |= 1u << j;
        if (first) _labelParameters = p;
        first = false;
    }
    if (_labelMask == 0) return;
    std::vector<StreetLabels::Street> streets = StreetLabels::collect(index);
    if (streets.empty()) return;
    try
    {
        _labels = new StreetLabels(streets);
    }
    catch (const std::exception& e)
    {
        // Documented fallback (docs/cartographic.md): the frame without labels, said once.
        static bool warned = false;
        if (!warned) OSG_WARN << "osgLoA: no street labels: " << e.what() << std::endl;
        warned = true;
        return;
    }
    for (const StreetLabels::Street& s : _labels->getStreets())
        _labelStreetFeature.push_back(s.featureId);
}

float TransitionRenderer::labelOpacity(const ScenarioEvaluator& evaluator, std::size_t street,
                                       const osg::Vec3d& point) const
{
    // The labelling configurations' share of the street's blend weights at the point: fragment
    // matches evaluated there (as the shader does per fragment), the others as the evaluator
    // weighed them for the feature.
    const int fi = evaluator.findFeature(_labelStreetFeature[street]);
    if (fi < 0) return 0.0f;
    const ScenarioEvaluator::FeatureState& fs = evaluator.features()[std::size_t(fi)];
    if (!fs.visible) return 0.0f;
    const auto& configs = evaluator.getScenario()->getConfigurations();
    const ScenarioEvaluator::Match* m = evaluator.matchesOf(fs);
    double labelled = 0.0, total = 0.0;
    for (unsigned k = 0; k < fs.numMatches; ++k)
    {
        double raw = m[k].rawWeight;
        if (m[k].fragment && m[k].configuration < configs.size())
        {
            const TransitionConfiguration& c = *configs[m[k].configuration];
            raw = c.getBlendFunction().weight(
                float(c.interestAt(point, evaluator.getView(), fs.staticInterest)));
        }
        total += raw;
        if (m[k].configuration < 32 && (_labelMask & (1u << m[k].configuration))) labelled += raw;
    }
    return total > 0.0 ? float(labelled / total) : 0.0f;
}

void TransitionRenderer::installCallbacks(const FeatureIndex& index)
{
    _nested.assign(index.size(), {});
    _between.assign(index.size(), {});
    _hasUnfeatured = false;
    for (unsigned e = 0; e < index.size(); ++e)
    {
        const FeatureIndex::Entry& entry = index.entries()[e];
        if (entry.parent >= 0)
        {
            _nested[unsigned(entry.parent)].push_back(e);
            // Only the nodes between the enclosing feature's node and this one (a whole path
            // per entry took memory quadratic in the scene's depth).
            const osg::NodePath outer = index.pathOf(index.entries()[unsigned(entry.parent)]);
            const osg::NodePath inner = index.pathOf(entry);
            if (inner.size() > outer.size())
                _between[e].assign(inner.begin() + static_cast<long>(outer.size()), inner.end());
        }
        osg::Node* node = entry.node.get();
        if (!node) continue;
        osg::ref_ptr<osg::Callback> cb;
        if (osg::Drawable* d = node->asDrawable())
        {
            if (d->getCullCallback())
            {
                OSG_WARN << "osgLoA::TransitionRenderer: feature " << entry.feature->getId()
                         << " is a drawable with its own cull callback; it is drawn unstyled" << std::endl;
                continue;
            }
            cb = new FeatureDrawableCallback(this, e);
            d->setCullCallback(cb.get());
        }
        else
        {
            cb = new FeatureNodeCallback(this, e);
            node->addCullCallback(cb.get());
        }
        _callbacks.emplace_back(node, cb);
    }
    // Geometry outside every feature is drawn once, photorealistic, in the G-buffer pass.
    struct Unfeatured : public osg::NodeVisitor
    {
        Unfeatured() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
        bool found = false;
        void apply(osg::Node& n) override
        {
            if (Feature::get(n)) return;
            traverse(n);
        }
        void apply(osg::Drawable& d) override
        {
            if (!Feature::get(d)) found = true;
        }
    } v;
    for (unsigned c = 0; c < _node.getNumChildren(); ++c)
        _node.getChild(c)->accept(v);
    _hasUnfeatured = v.found;
}

void TransitionRenderer::removeCallbacks()
{
    for (auto& c : _callbacks)
    {
        osg::ref_ptr<osg::Node> node;
        if (!c.first.lock(node)) continue;
        if (osg::Drawable* d = node->asDrawable())
        {
            if (d->getCullCallback() == c.second.get()) d->setCullCallback(nullptr);
        }
        else
            node->removeCullCallback(c.second.get());
    }
    _callbacks.clear();
}

void TransitionRenderer::rebindValues(const ScenarioEvaluator& evaluator)
{
    if (!_bound || !evaluator.getScenario()) return;
    LandmarkDeformation::applyScenario(*_common, evaluator.getScenario()->getLandmarkDeformation());
}

std::vector<osg::Program*> TransitionRenderer::getPrograms() const
{
    std::vector<osg::Program*> out;
    for (const auto& p : _programs)
        out.push_back(p.second.get());
    return out;
}

void TransitionRenderer::unbind()
{
    removeCallbacks();
    _passStates->removeChildren(0, _passStates->getNumChildren());
    _bound = false;
    _styles.clear();
    _fused.clear();
    _fusedMasks.clear();
    _featureState.clear();
    _decisions.clear();
    _labels = nullptr;
    _labelMask = 0;
}

void TransitionRenderer::decide(const ScenarioEvaluator& evaluator)
{
    std::fill(_sharedAny.begin(), _sharedAny.end(), 0);
    std::fill(_aAny.begin(), _aAny.end(), 0);
    std::fill(_pingAny.begin(), _pingAny.end(), 0);
    _fusedMasks.clear();
    _depthAny = false;
    const auto& features = evaluator.features();
    const LandmarkDeformation* deformation = evaluator.getScenario()->getLandmarkDeformation();
    // Deformed landmarks leave their drawables' bounds: the A-buffer's routed region (those
    // bounds projected) would clip them.
    _aBuffer->setRestrictToRoutedRegion(deformation == nullptr);
    const FeatureIndex& index = _node.getFeatureIndex();
    const LandmarkDeformation::View view = LandmarkDeformation::View::fromViewToScene(_viewToSceneMatrix);
    // Configurations whose style is map-like (the deformation's sinking may follow their weight).
    unsigned mapConfigurations = 0;
    if (deformation && deformation->getSinkFollowsMapStyles())
    {
        const UsageScenario::Configurations& configurations = evaluator.getScenario()->getConfigurations();
        for (std::size_t j = 0; j < configurations.size() && j < 32; ++j)
            if (configurations[j].valid() && deformation->isMapStyle(configurations[j]->getStyle()))
                mapConfigurations |= 1u << j;
    }
    for (std::size_t i = 0; i < features.size(); ++i)
    {
        Decision& d = _decisions[i];
        d = Decision();
        const ScenarioEvaluator::FeatureState& fs = features[i];
        if (!fs.visible) continue;
        const ScenarioEvaluator::Match* m = evaluator.matchesOf(fs);
        unsigned contributing = 0, visibleMask = 0, contributingMask = 0;
        int last = -1;
        bool covers = false;
        for (unsigned k = 0; k < fs.numMatches; ++k)
        {
            if (!m[k].mayContribute || m[k].configuration >= _styles.size()) continue;
            ++contributing;
            contributingMask |= 1u << m[k].configuration;
            last = int(m[k].configuration);
            covers = m[k].coversFeature;
            if (_styles[m[k].configuration].visible) visibleMask |= 1u << m[k].configuration;
        }
        if (visibleMask == 0) continue;
        const StyleState* only = contributing == 1 ? &_styles[unsigned(last)] : nullptr;
        if (only && only->opaque && _opaqueMaterial[i])
        {
            d.shared = last;
            d.covered = covers;
            _sharedAny[unsigned(last)] = 1;
            ++_stats.sharedDraws;
        }
        else if (fusable(contributingMask) && _opaqueMaterial[i])
        {
            d.fusedMask = contributingMask;
            if (std::find(_fusedMasks.begin(), _fusedMasks.end(), contributingMask) == _fusedMasks.end())
                _fusedMasks.push_back(contributingMask);
            ++_stats.fusedDraws;
        }
        else
        {
            // A style with a geometry stage (leaf sprites) draws other surfaces than the feature's
            // mesh: the mesh's depth must not hide them.
            d.depthOnly = _opaqueMaterial[i] != 0 && (visibleMask & _geometryStageMask) == 0;
            _depthAny = _depthAny || d.depthOnly;
            if (d.depthOnly) ++_stats.depthOnlyDraws;
            (_routedToPingPong[i] ? d.pingMask : d.aMask) = visibleMask;
            for (unsigned j = 0; j < _styles.size(); ++j)
                if (visibleMask & (1u << j))
                {
                    if (_routedToPingPong[i])
                    {
                        _pingAny[j] = 1;
                        ++_stats.pingPongDraws;
                    }
                    else
                    {
                        _aAny[j] = 1;
                        ++_stats.aBufferDraws;
                    }
                }
        }
        ++_stats.drawnFeatures;
        osg::StateSet& ss = *_featureState[i];
        TransitionUniforms::applyFeature(ss, evaluator, fs);
        const Feature& feature = *index.entries()[fs.entry].feature;
        if (deformation)
        {
            LandmarkDeformation::FeatureInput input(feature, fs.bound, fs.staticInterest);
            if (deformation->getSinkFollowsMapStyles())
            {
                input.mapWeight = 0.0;
                for (unsigned k = 0; k < fs.numMatches; ++k)
                    if (m[k].configuration < 32 && (mapConfigurations & (1u << m[k].configuration)))
                        input.mapWeight += m[k].weight;
            }
            deformation->applyFeature(ss, input, view);
        }
    }
}

bool TransitionRenderer::fusable(unsigned mask) const
{
    if (!_settings.fuseStyles || mask == 0 || std::bitset<32>(mask).count() > 4) return false;
    for (unsigned j = 0; j < _styles.size(); ++j)
        if ((mask & (1u << j)) && (!_styles[j].fusable || (_styles[j].conflicts & mask) != 0)) return false;
    return true;
}

void TransitionRenderer::traversePass(osgUtil::CullVisitor& cv, Pass::Kind kind, int configuration,
                                      osg::StateSet* style, osg::StateSet* pass, unsigned mask)
{
    cv.pushStateSet(_common.get());
    if (style) cv.pushStateSet(style);
    cv.pushStateSet(pass);
    _pass.kind = kind;
    _pass.configuration = configuration;
    _pass.mask = mask;
    ++_stats.configurationPasses;
    _node.traverseChildren(cv);
    _pass = Pass();
    cv.popStateSet();
    if (style) cv.popStateSet();
    cv.popStateSet();
}

void TransitionRenderer::drawFeature(unsigned entry, osg::Node& node, osgUtil::CullVisitor& cv,
                                     osg::Callback* callback)
{
    if (_pass.kind == Pass::UNFEATURED || entry >= _featureOfEntry.size() || _featureOfEntry[entry] < 0)
        return;
    const unsigned i = unsigned(_featureOfEntry[entry]);
    const Decision& d = _decisions[i];
    bool draw = false;
    Draw::Kind kind = Draw::SHARED;
    const unsigned bit = _pass.configuration >= 0 ? 1u << unsigned(_pass.configuration) : 0u;
    switch (_pass.kind)
    {
    case Pass::SHARED:
        draw = d.shared == _pass.configuration;
        break;
    case Pass::DEPTH_ONLY:
        draw = d.depthOnly;
        kind = Draw::DEPTH_ONLY;
        break;
    case Pass::A_BUFFER:
        draw = (d.aMask & bit) != 0;
        kind = Draw::A_BUFFER;
        break;
    case Pass::PING_PONG:
        draw = (d.pingMask & bit) != 0;
        kind = Draw::PING_PONG;
        break;
    case Pass::FUSED:
        draw = d.fusedMask != 0 && d.fusedMask == _pass.mask;
        kind = Draw::FUSED;
        break;
    default:
        break;
    }
    if (!draw)
    {
        visitNested(entry, cv);
        return;
    }
    if (_recordDraws)
    {
        Draw rec;
        rec.featureId = _node.getFeatureIndex().entries()[entry].feature->getId();
        rec.configuration = kind == Draw::DEPTH_ONLY || kind == Draw::FUSED ? -1 : _pass.configuration;
        rec.kind = kind;
        rec.configurations = kind == Draw::FUSED ? d.fusedMask : 0u;
        _draws.push_back(rec);
    }
    cv.pushStateSet(_featureState[i].get());
    // A feature its one configuration covers entirely skips the per-fragment weight test; the
    // pass state is pushed again per feature so that nested features do not inherit the variant.
    osg::StateSet* variant = nullptr;
    if (kind == Draw::SHARED)
    {
        const StyleState& st = _styles[unsigned(d.shared)];
        variant = d.covered ? st.sharedCovered.get() : st.shared.get();
    }
    if (variant) cv.pushStateSet(variant);
    if (callback)
        callback->traverse(&node, &cv);
    else if (osg::Drawable* drawable = node.asDrawable())
        cv.apply(*drawable);
    if (variant) cv.popStateSet();
    cv.popStateSet();
}

void TransitionRenderer::visitNested(unsigned entry, osgUtil::CullVisitor& cv)
{
    for (unsigned child : _nested[entry])
    {
        // Walk the path from this feature's node to the nested one, applying the transforms and
        // state sets between them as the cull traversal would.
        const osg::NodePath& between = _between[child];
        if (between.empty()) continue;
        unsigned pushedMatrices = 0, pushedStates = 0;
        for (std::size_t k = 0; k + 1 < between.size(); ++k)
        {
            osg::Node* n = between[k];
            if (osg::Transform* t = n->asTransform())
            {
                osg::ref_ptr<osg::RefMatrix> m = new osg::RefMatrix(*cv.getModelViewMatrix());
                t->computeLocalToWorldMatrix(*m, &cv);
                cv.pushModelViewMatrix(m.get(), t->getReferenceFrame());
                ++pushedMatrices;
            }
            if (osg::StateSet* ss = n->getStateSet())
            {
                cv.pushStateSet(ss);
                ++pushedStates;
            }
        }
        between.back()->accept(cv);
        for (unsigned k = 0; k < pushedStates; ++k)
            cv.popStateSet();
        for (unsigned k = 0; k < pushedMatrices; ++k)
            cv.popModelViewMatrix();
    }
}

void TransitionRenderer::cull(osgUtil::CullVisitor& cv, const ScenarioEvaluator& evaluator)
{
    _stats = Statistics();
    _draws.clear();
    const osg::Viewport* vp = cv.getViewport();
    const int w = vp ? std::max(1, int(vp->width())) : 1, h = vp ? std::max(1, int(vp->height())) : 1;
    // The renderer became known since the A-buffer was made (a viewer's first frame queried it):
    // checked only until then, not every frame.
    if (!_oitRendererKnown && methodInUse(_settings) != _oitInUse) setSettings(_settings);
    if (_settings.oitAuto)
    {
        // The routed passes' GPU time of an earlier frame, once per frame measured: the method
        // for this frame (switching rebuilds the A-buffer and relinks the routed programs).
        unsigned measured = 0;
        const double ms = _aBuffer->getRoutedMilliseconds(&measured);
        if (ms >= 0.0 && measured != _oitMeasuredFrame)
        {
            _oitMeasuredFrame = measured;
            const OrderIndependentTransparency::Method m = _oitSelection.record(ms, w, h);
            if (m != _settings.oit)
            {
                Settings next = _settings;
                next.oit = m;
                setSettings(next);
                _oitMeasuredFrame = ~0u;
            }
        }
    }
    const osg::Matrixd mv = *cv.getModelViewMatrix();
    _viewToSceneMatrix = osg::Matrixd::inverse(mv);
    decide(evaluator);
    _stats.fusedPrograms = unsigned(_fusedMasks.size());

    osg::BoundingSphere bs = _node.getBound();
    osg::BoundingSphere viewSphere(bs.center() * mv,
                                   bs.radius() * float(mv.getScale().length() / std::sqrt(3.0)));
    double zNear = 1.0, zFar = 1000.0;
    bool ortho = false;
    const osg::Matrixd projection = fitDepthRange(*cv.getProjectionMatrix(), viewSphere, zNear, zFar, ortho);
    _sceneToView->set(osg::Matrixf(mv));
    _viewportHeight->set(float(h));
    _viewportWidth->set(float(w));
    _viewToScene->set(osg::Matrixf(_viewToSceneMatrix));

    auto setUp = [&](osg::Camera* c)
    {
        c->setViewMatrix(mv);
        c->setProjectionMatrix(projection);
        c->accept(cv);
    };
    _gbuffer->setSize(w, h);
    setUp(_gbuffer->getCamera());
    _stats.aBuffer = std::find(_aAny.begin(), _aAny.end(), 1) != _aAny.end();
    if (_stats.aBuffer)
    {
        _aBuffer->setSize(w, h);
        setUp(_aBuffer->getCamera());
    }
    _stats.pingPongBuffer = std::find(_pingAny.begin(), _pingAny.end(), 1) != _pingAny.end();
    if (_stats.pingPongBuffer)
    {
        _pingPong->setSize(w, h);
        setUp(_pingPong->getCamera(0));
        setUp(_pingPong->getCamera(1));
    }
    _stats.unsharp = _settings.unsharpMasking && _maxUnsharpSigma > 0.0f;
    if (_stats.unsharp)
    {
        _unsharp->setSize(w, h);
        _unsharp->setSigma(_maxUnsharpSigma);
        _unsharp->setDepthRange(float(zNear), float(zFar), ortho);
        for (unsigned p = 0; p < DepthUnsharpMask::NUM_PASSES; ++p)
            _unsharp->getCamera(p)->accept(cv);
    }
    _compositing->setInputs(_stats.aBuffer, _stats.pingPongBuffer, _settings.edges, _stats.unsharp);
    _compositing->setDepthRange(float(zNear), float(zFar), ortho);
    _compositing->setViewportOrigin(vp ? int(vp->x()) : 0, vp ? int(vp->y()) : 0);
    _compositing->getNode()->accept(cv);
    // 5. Street labels over the composited frame.
    _labelStats = StreetLabels::Statistics();
    if (_labels.valid())
    {
        StreetLabels::View view;
        view.sceneToClip = mv * projection;
        view.width = w;
        view.height = h;
        const std::vector<StreetLabels::Label> labels = StreetLabels::layout(
            _labels->getStreets(), view, _labels->getFont(), _labelParameters,
            [&](std::size_t street, const osg::Vec3d& p) { return labelOpacity(evaluator, street, p); },
            &_labelStats);
        _labels->draw(cv, labels, _labelParameters, view, _gbuffer->getTexture(GeometryBuffer::DEPTH),
                      float(zNear), float(zFar), ortho);
    }
}

TransitionRenderer::Memory TransitionRenderer::memory(int width, int height, unsigned samples,
                                                      unsigned passes, bool pingPong, bool unsharp,
                                                      float unsharpSigma)
{
    Memory m;
    m.aBufferBytes = double(ABufferMemory::of(width, height, int(samples), int(passes)).bytes());
    m.pingPongBytes = pingPong ? PingPongBuffer::memoryBytes(width, height) : 0.0;
    m.geometryBufferBytes = GeometryBuffer::memoryBytes(width, height);
    m.unsharpBytes = unsharp ? DepthUnsharpMask::memoryBytes(width, height, unsharpSigma) : 0.0;
    m.paperBytes = double(width) * height * (2.0 * samples + 7.0) * 4.0;
    return m;
}

void TransitionRenderer::releaseGLObjects(osg::State* state) const
{
    _gbuffer->getCamera()->releaseGLObjects(state);
    _aBuffer->getCamera()->releaseGLObjects(state);
    _aBuffer->releaseGLObjects(state);
    _pingPong->getCamera(0)->releaseGLObjects(state);
    _pingPong->getCamera(1)->releaseGLObjects(state);
    for (unsigned p = 0; p < DepthUnsharpMask::NUM_PASSES; ++p)
        _unsharp->getCamera(p)->releaseGLObjects(state);
    const_cast<ImageCompositing*>(_compositing.get())->getNode()->releaseGLObjects(state);
    for (const auto& p : _programs)
        p.second->releaseGLObjects(state);
}

void TransitionRenderer::resizeGLObjectBuffers(unsigned maxSize)
{
    _gbuffer->getCamera()->resizeGLObjectBuffers(maxSize);
    _aBuffer->getCamera()->resizeGLObjectBuffers(maxSize);
    _pingPong->getCamera(0)->resizeGLObjectBuffers(maxSize);
    _pingPong->getCamera(1)->resizeGLObjectBuffers(maxSize);
    for (unsigned p = 0; p < DepthUnsharpMask::NUM_PASSES; ++p)
        _unsharp->getCamera(p)->resizeGLObjectBuffers(maxSize);
    _compositing->getNode()->resizeGLObjectBuffers(maxSize);
    for (const auto& p : _programs)
        p.second->resizeGLObjectBuffers(maxSize);
}

} // namespace osgLoA
