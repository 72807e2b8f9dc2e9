/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/palette/PaletteStyle>
#include <osgLoA/styles/GraphicStyleCatalog>

namespace osgLoA
{

namespace
{
// Registers the style when the library is loaded, so that scenarios read before any palette
// code runs can name it.
struct Registrar
{
    Registrar() { PaletteStyle::registerStyle(); }
} s_registrar;
} // namespace

osg::ref_ptr<GraphicStyle> PaletteStyle::create()
{
    osg::ref_ptr<GraphicStyle> s = new GraphicStyle;
    s->setName(name());
    s->setDescription("textures reduced to their palette's colours, the number of colours by level, depth, "
                      "orientation or interest (paper 003)");
    s->setFragmentShader("loa_style_palette.frag.glsl");
    osg::StateSet* p = s->getParameters();
    p->setName(std::string(name()) + " parameters");
    p->addUniform(new osg::Uniform("loa_palette_strategy", 3));
    p->addUniform(new osg::Uniform("loa_palette_level", 8));
    p->addUniform(new osg::Uniform("loa_palette_levelNear", 32));
    p->addUniform(new osg::Uniform("loa_palette_levelFar", 4));
    p->addUniform(new osg::Uniform("loa_palette_near", 50.0f));
    p->addUniform(new osg::Uniform("loa_palette_far", 400.0f));
    p->addUniform(new osg::Uniform("loa_palette_levelLow", 4));
    p->addUniform(new osg::Uniform("loa_palette_levelHigh", 32));
    p->addUniform(new osg::Uniform("loa_palette_ambient", 0.35f));
    s->setOpaque(true);
    s->setUsesTexture(true);
    return s;
}

void PaletteStyle::registerStyle()
{
    GraphicStyleCatalog::instance().add(*create());
}

} // namespace osgLoA
