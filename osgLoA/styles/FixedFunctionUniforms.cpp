// FixedFunctionUniforms: the fixed-function state of a model as uniforms for the graphic styles.
#include <osgLoA/styles/FixedFunctionUniforms>

#include <osgLoA/util/StateSetVisitor>

#include <osg/AlphaFunc>
#include <osg/Material>
#include <osg/TexEnv>

#include <string>

namespace osgLoA
{

namespace
{
/** The uniform's override flags: those of the state it mirrors. */
osg::StateAttribute::OverrideValue flagsOf(osg::StateAttribute::GLModeValue value)
{
    return value & (osg::StateAttribute::OVERRIDE | osg::StateAttribute::PROTECTED);
}

template <typename T>
void put(osg::StateSet& ss, const char* name, T value, osg::StateAttribute::OverrideValue flags)
{
    if (ss.getUniform(name)) return; // a user's (or an earlier annotation's) value stays
    ss.addUniform(new osg::Uniform(name, value), flags);
}

int colorMaterialMode(const osg::Material& m)
{
    switch (m.getColorMode())
    {
    case osg::Material::AMBIENT_AND_DIFFUSE:
        return 1;
    case osg::Material::AMBIENT:
        return 2;
    case osg::Material::DIFFUSE:
        return 3;
    case osg::Material::EMISSION:
        return 4;
    case osg::Material::SPECULAR:
        return 5;
    default:
        return 0;
    }
}

int texEnvMode(const osg::TexEnv& e)
{
    switch (e.getMode())
    {
    case osg::TexEnv::REPLACE:
        return 1;
    case osg::TexEnv::DECAL:
        return 2;
    case osg::TexEnv::ADD:
        return 3;
    case osg::TexEnv::BLEND:
        return 4;
    default:
        return 0;
    }
}
} // namespace

bool FixedFunctionUniforms::annotate(osg::StateSet& ss)
{
    bool any = false;
    for (unsigned unit = 0; unit < kUnits; ++unit)
    {
        const std::string suffix = unit ? std::to_string(unit) : std::string();
        const std::string has = "loa_hasTexture" + suffix, env = "loa_texEnvMode" + suffix;
        // A texture on the unit: the attribute, or the GL_TEXTURE_2D mode alone.
        const osg::StateSet::RefAttributePair* tex = ss.getTextureAttributePair(unit, osg::StateAttribute::TEXTURE);
        const osg::StateAttribute::GLModeValue texMode = ss.getTextureMode(unit, GL_TEXTURE_2D);
        if (tex && tex->first.valid())
        {
            const bool off = (texMode != osg::StateAttribute::INHERIT) && !(texMode & osg::StateAttribute::ON);
            put(ss, has.c_str(), !off, flagsOf(tex->second | texMode));
            any = true;
        }
        else if (texMode != osg::StateAttribute::INHERIT)
        {
            put(ss, has.c_str(), (texMode & osg::StateAttribute::ON) != 0, flagsOf(texMode));
            any = true;
        }
        if (const osg::StateSet::RefAttributePair* ep = ss.getTextureAttributePair(unit, osg::StateAttribute::TEXENV))
        {
            if (const auto* e = dynamic_cast<const osg::TexEnv*>(ep->first.get()))
            {
                put(ss, env.c_str(), texEnvMode(*e), flagsOf(ep->second));
                any = true;
            }
        }
    }
    const osg::StateAttribute::GLModeValue lighting = ss.getMode(GL_LIGHTING);
    if (lighting != osg::StateAttribute::INHERIT)
    {
        put(ss, "loa_lighting", (lighting & osg::StateAttribute::ON) != 0, flagsOf(lighting));
        any = true;
    }
    if (const osg::StateSet::RefAttributePair* mp = ss.getAttributePair(osg::StateAttribute::MATERIAL))
    {
        if (const auto* m = dynamic_cast<const osg::Material*>(mp->first.get()))
        {
            put(ss, "loa_colorMaterial", colorMaterialMode(*m), flagsOf(mp->second));
            any = true;
        }
    }
    const osg::StateAttribute::GLModeValue blend = ss.getMode(GL_BLEND);
    if (blend != osg::StateAttribute::INHERIT)
    {
        put(ss, "loa_blending", (blend & osg::StateAttribute::ON) != 0, flagsOf(blend));
        any = true;
    }
    const osg::StateAttribute::GLModeValue alphaTest = ss.getMode(GL_ALPHA_TEST);
    const osg::StateSet::RefAttributePair* ap = ss.getAttributePair(osg::StateAttribute::ALPHAFUNC);
    const auto* alphaFunc = ap ? dynamic_cast<const osg::AlphaFunc*>(ap->first.get()) : nullptr;
    if (alphaTest != osg::StateAttribute::INHERIT || alphaFunc)
    {
        const bool on = alphaTest == osg::StateAttribute::INHERIT
                            ? alphaFunc != nullptr
                            : (alphaTest & osg::StateAttribute::ON) != 0;
        const int func = on && alphaFunc ? int(alphaFunc->getFunction()) : int(GL_ALWAYS);
        const float ref = alphaFunc ? alphaFunc->getReferenceValue() : 0.0f;
        const auto flags = flagsOf(alphaTest | (ap ? ap->second : 0u));
        put(ss, "loa_alphaFunc", func, flags);
        put(ss, "loa_alphaRef", ref, flags);
        any = true;
    }
    return any;
}

void FixedFunctionUniforms::annotate(osg::Node& scene)
{
    StateSetVisitor v([](osg::StateSet& ss) { annotate(ss); });
    scene.accept(v);
}

void FixedFunctionUniforms::setDefaults(osg::StateSet& ss)
{
    ss.addUniform(new osg::Uniform("loa_hasTexture", false));
    for (unsigned unit = 1; unit < kUnits; ++unit)
    {
        ss.addUniform(new osg::Uniform(("loa_hasTexture" + std::to_string(unit)).c_str(), false));
        ss.addUniform(new osg::Uniform(("loa_texEnvMode" + std::to_string(unit)).c_str(), 0));
        ss.addUniform(new osg::Uniform(("loa_texture" + std::to_string(unit)).c_str(), int(unit)));
    }
    ss.addUniform(new osg::Uniform("loa_lighting", true));
    ss.addUniform(new osg::Uniform("loa_colorMaterial", 1));
    ss.addUniform(new osg::Uniform("loa_texEnvMode", 0));
    ss.addUniform(new osg::Uniform("loa_alphaFunc", int(GL_ALWAYS)));
    ss.addUniform(new osg::Uniform("loa_alphaRef", 0.0f));
    ss.addUniform(new osg::Uniform("loa_blending", false));
}

bool FixedFunctionUniforms::isOpaque(const osg::StateSet& ss)
{
    // As the fixed-function pipeline: without blending, a texture's or colour's alpha does not
    // make a surface translucent (an alpha test may still drop fragments: loa_alphaFunc).
    return !(ss.getRenderingHint() == osg::StateSet::TRANSPARENT_BIN ||
             (ss.getMode(GL_BLEND) & osg::StateAttribute::ON));
}

} // namespace osgLoA
