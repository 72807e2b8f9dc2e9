// GraphicStyle: a style's shader, parameters and compositor hints; the built-in styles.
#include <osgLoA/styles/GraphicStyle>

#include "../util/TriangleCollector.h"

#include <osg/Geometry>
#include <osg/NodeVisitor>
#include <osg/TriangleIndexFunctor>

#include <osgLoA/render/ShaderLibrary>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace osgLoA
{

namespace
{
float clamp01(float v)
{
    if (!std::isfinite(v)) return std::isinf(v) && v > 0.0f ? 1.0f : 0.0f;
    return std::min(1.0f, std::max(0.0f, v));
}

osg::Vec3f rgb(int r, int g, int b)
{
    return osg::Vec3f(r / 255.0f, g / 255.0f, b / 255.0f);
}

osg::ref_ptr<GraphicStyle> makeStyle(const std::string& name, const std::string& description,
                                     const std::string& fragmentShader)
{
    osg::ref_ptr<GraphicStyle> s = new GraphicStyle;
    s->setName(name);
    s->setDescription(description);
    s->setFragmentShader(fragmentShader);
    s->getParameters()->setName(name + " parameters");
    return s;
}

void addFloat(GraphicStyle& s, const std::string& name, float value)
{
    s.getParameters()->addUniform(new osg::Uniform(name.c_str(), value));
}

osg::ref_ptr<GraphicStyle> photorealistic()
{
    osg::ref_ptr<GraphicStyle> s =
        makeStyle("photorealistic",
                  "the model as OSG's fixed-function pipeline draws it: its materials, textures and light",
                  "loa_style_photorealistic.frag.glsl");
    // true: the fixed function's lighting, texture environment and texture matrix (the model as
    // a plain render shows it); false: the project's simple lighting below.
    s->getParameters()->addUniform(new osg::Uniform("loa_photorealistic_fixedFunction", true));
    addFloat(*s, "loa_photorealistic_ambient", 0.35f);
    s->getParameters()->addUniform(new osg::Uniform("loa_photorealistic_materialDiffuse", false));
    s->setOpaque(true);
    s->setUsesTexture(true);
    return s;
}

osg::ref_ptr<GraphicStyle> abstractStyle()
{
    osg::ref_ptr<GraphicStyle> s = makeStyle(
        "abstract",
        "textures abstracted per mip level (bilateral colour and DoG outlines, TextureAbstraction), "
        "blended at render time; untextured colours quantized",
        "loa_style_abstract.frag.glsl");
    s->getParameters()->addUniform(new osg::Uniform("loa_abstract_levels", 5));
    addFloat(*s, "loa_abstract_colorBlend", 1.0f);
    addFloat(*s, "loa_abstract_outlineBlend", 0.6f);
    addFloat(*s, "loa_abstract_chromaStep", 0.05f);
    addFloat(*s, "loa_abstract_ambient", 0.6f);
    s->getParameters()->addUniform(new osg::Uniform("loa_abstract_modelLighting", true));
    s->setOpaque(true);
    s->setUsesTexture(true);
    s->setEdgeColor(osg::Vec3f(0.25f, 0.25f, 0.25f));
    s->setEdgeStrength(0.35f);
    return s;
}

osg::ref_ptr<GraphicStyle> cartographic()
{
    osg::ref_ptr<GraphicStyle> s = makeStyle(
        "cartographic", "a qualitative Brewer colour per feature type, flat shading, image-space edges",
        "loa_style_cartographic.frag.glsl");
    const auto& colors = GraphicStyle::cartographicColors();
    osg::ref_ptr<osg::Uniform> u = new osg::Uniform(osg::Uniform::FLOAT_VEC3, "loa_cartographic_colors",
                                                    static_cast<int>(colors.size()));
    for (unsigned i = 0; i < colors.size(); ++i)
        u->setElement(i, colors[i]);
    s->getParameters()->addUniform(u.get());
    addFloat(*s, "loa_cartographic_ambient", 0.6f);
    s->setOpaque(true);
    s->setUsesTexture(false);
    s->setEdgeColor(osg::Vec3f(0.15f, 0.15f, 0.15f));
    s->setEdgeStrength(0.8f);
    s->setUnsharpMaskStrength(1.0f);
    s->setUnsharpMaskRadius(8.0f);
    return s;
}

osg::ref_ptr<GraphicStyle> blueprint()
{
    osg::ref_ptr<GraphicStyle> s =
        makeStyle("blueprint", "white edges on a blue ground", "loa_style_blueprint.frag.glsl");
    s->getParameters()->addUniform(new osg::Uniform("loa_blueprint_color", rgb(31, 78, 140)));
    addFloat(*s, "loa_blueprint_ambient", 0.8f);
    s->setOpaque(true);
    s->setUsesTexture(false);
    s->setEdgeColor(osg::Vec3f(1.0f, 1.0f, 1.0f));
    s->setEdgeStrength(1.0f);
    return s;
}

osg::ref_ptr<GraphicStyle> hidden()
{
    osg::ref_ptr<GraphicStyle> s = makeStyle("hidden", "draws nothing", "");
    s->setVisible(false);
    s->setOpaque(false);
    s->setUsesTexture(false);
    return s;
}
} // namespace

const std::vector<std::string>& GraphicStyle::builtinNames()
{
    static const std::vector<std::string> names = {"photorealistic", "abstract", "cartographic", "blueprint",
                                                   "hidden"};
    return names;
}

osg::ref_ptr<GraphicStyle> GraphicStyle::createBuiltin(const std::string& name)
{
    if (name == "photorealistic") return photorealistic();
    if (name == "abstract") return abstractStyle();
    if (name == "cartographic") return cartographic();
    if (name == "blueprint") return blueprint();
    if (name == "hidden") return hidden();
    throw std::invalid_argument("'" + name + "' is not a built-in graphic style");
}

const std::array<osg::Vec3f, 6>& GraphicStyle::cartographicColors()
{
    // ColorBrewer (Brewer 1994; colorbrewer2.org) qualitative schemes, chosen for map
    // semantics. Indexed by FeatureType value.
    static const std::array<osg::Vec3f, 6> colors = {
        rgb(217, 217, 217), // generic: Set3 #d9d9d9 grey
        rgb(251, 128, 114), // building: Set3 #fb8072 salmon
        rgb(255, 255, 179), // street: Set3 #ffffb3 light yellow
        rgb(128, 177, 211), // water: Set3 #80b1d3 blue
        rgb(179, 222, 105), // green: Set3 #b3de69 green
        rgb(229, 216, 189), // terrain: Pastel1 #e5d8bd tan
    };
    return colors;
}

osg::Vec3f GraphicStyle::cartographicColor(FeatureType type)
{
    const int i = static_cast<int>(type);
    return cartographicColors()[i >= 0 && i < 6 ? i : 0];
}

float GraphicStyle::lightFactor(const osg::Vec3f& viewNormal, float ambient, const osg::Vec3f& lightDirection)
{
    osg::Vec3f n = viewNormal, l = lightDirection;
    n.normalize();
    l.normalize();
    return ambient + (1.0f - ambient) * std::max(n * l, 0.0f);
}

GraphicStyle::GraphicStyle() : _parameters(new osg::StateSet) {}

GraphicStyle::GraphicStyle(const GraphicStyle& o, const osg::CopyOp& copyop)
    : osg::Object(o, copyop), _description(o._description), _fragmentShader(o._fragmentShader),
      _geometryShader(o._geometryShader),
      _parameters(o._parameters.valid() ? copyop(o._parameters.get()) : new osg::StateSet),
      _visible(o._visible), _opaque(o._opaque), _usesTexture(o._usesTexture), _edgeColor(o._edgeColor),
      _edgeStrength(o._edgeStrength), _unsharpMaskStrength(o._unsharpMaskStrength),
      _unsharpMaskRadius(o._unsharpMaskRadius)
{
}

namespace
{
/** fileName unless it is not a shader file name of this stage ("NAME.<ext>.glsl", no directories
 *  or spaces): then std::invalid_argument naming what it should be. Empty: empty. */
const std::string& checkedShaderName(const std::string& fileName, osg::Shader::Type stage, const char* what,
                                     const char* pattern)
{
    if (fileName.empty()) return fileName;
    bool ok = false;
    try
    {
        ok = ShaderLibrary::stageOf(fileName) == stage;
    }
    catch (const std::invalid_argument&)
    {
    }
    if (!ok || fileName.find_first_of("/\\ \t\r\n") != std::string::npos)
        throw std::invalid_argument(std::string("graphic style ") + what + " shader '" + fileName +
                                    "' must be a file name " + pattern + " without directories or spaces");
    return fileName;
}
} // namespace

void GraphicStyle::setFragmentShader(const std::string& fileName)
{
    _fragmentShader = checkedShaderName(fileName, osg::Shader::FRAGMENT, "fragment", "NAME.frag.glsl");
}

void GraphicStyle::setGeometryShader(const std::string& fileName)
{
    _geometryShader = checkedShaderName(fileName, osg::Shader::GEOMETRY, "geometry", "NAME.geom.glsl");
}

void GraphicStyle::setParameters(osg::StateSet* parameters)
{
    _parameters = parameters ? parameters : new osg::StateSet;
}

osg::Uniform* GraphicStyle::getParameter(const std::string& uniformName)
{
    return _parameters->getUniform(uniformName);
}

const osg::Uniform* GraphicStyle::getParameter(const std::string& uniformName) const
{
    return _parameters->getUniform(uniformName);
}

void GraphicStyle::setEdgeColor(const osg::Vec3f& c)
{
    _edgeColor.set(clamp01(c.x()), clamp01(c.y()), clamp01(c.z()));
}

void GraphicStyle::setEdgeStrength(float s)
{
    _edgeStrength = clamp01(s);
}

void GraphicStyle::setUnsharpMaskStrength(float lambda)
{
    _unsharpMaskStrength = std::isfinite(lambda) ? std::max(lambda, 0.0f) : 0.0f;
}

void GraphicStyle::setUnsharpMaskRadius(float sigmaPixels)
{
    _unsharpMaskRadius = std::isfinite(sigmaPixels) ? std::max(sigmaPixels, 0.0f) : 8.0f;
}

std::vector<std::string> GraphicStyle::shaderNames(const std::vector<std::string>& commonShaders) const
{
    std::vector<std::string> names = commonShaders;
    if (!_fragmentShader.empty())
    {
        // The fixed-function library the built-in styles call (photorealistic, abstract).
        names.push_back("loa_fixed_function.frag.glsl");
        names.push_back(_fragmentShader);
        if (!_geometryShader.empty()) names.push_back(_geometryShader);
    }
    return names;
}

osg::ref_ptr<osg::Program> GraphicStyle::createProgram(const std::vector<std::string>& commonShaders) const
{
    if (!_visible)
        throw std::logic_error("graphic style '" + getName() + "' is not visible and has no program");
    if (_fragmentShader.empty())
        throw std::logic_error("graphic style '" + getName() + "' has no fragment shader");
    if (_geometryShader.empty())
        return ShaderLibrary::createProgram("loa_style_" + getName(), shaderNames(commonShaders));
    // With a geometry stage the vertex stages hand their outputs over under loa_vs* names.
    osg::ref_ptr<osg::Program> p = new osg::Program;
    p->setName("loa_style_" + getName());
    for (const std::string& name : shaderNames(commonShaders))
        p->addShader(ShaderLibrary::stageOf(name) == osg::Shader::VERTEX
                         ? ShaderLibrary::createShader(name, {{"LOA_GEOMETRY_STAGE", ""}}).get()
                         : ShaderLibrary::createShader(name).get());
    return p;
}

void GraphicStyle::applyParameters(osg::StateSet& target) const
{
    if (_parameters.valid()) target.merge(*_parameters);
}

namespace
{
class Triangulator : public osg::NodeVisitor
{
public:
    Triangulator() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
    unsigned converted = 0, pointsOrLines = 0;
    void apply(osg::Geometry& g) override
    {
        for (unsigned i = 0; i < g.getNumPrimitiveSets(); ++i)
        {
            osg::PrimitiveSet* ps = g.getPrimitiveSet(i);
            const GLenum mode = ps->getMode();
            if (mode == GL_POINTS || mode == GL_LINES || mode == GL_LINE_STRIP || mode == GL_LINE_LOOP)
                ++pointsOrLines;
            if (mode != GL_QUADS && mode != GL_QUAD_STRIP && mode != GL_POLYGON) continue;
            std::vector<unsigned> indices;
            osg::TriangleIndexFunctor<TriangleIndexList> f;
            f.out = &indices;
            ps->accept(f);
            osg::ref_ptr<osg::DrawElementsUInt> tris =
                new osg::DrawElementsUInt(GL_TRIANGLES, indices.begin(), indices.end());
            tris->setNumInstances(ps->getNumInstances());
            g.setPrimitiveSet(i, tris.get());
            ++converted;
        }
        if (g.getUseDisplayList()) g.dirtyGLObjects();
    }
};
} // namespace

unsigned GraphicStyle::triangulate(osg::Node& model, unsigned* pointsOrLines)
{
    Triangulator t;
    model.accept(t);
    if (pointsOrLines) *pointsOrLines = t.pointsOrLines;
    return t.converted;
}

} // namespace osgLoA
