/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/abstraction/AbstractionStyleCatalog>
#include <osgLoA/styles/GraphicStyleCatalog>

#include <stdexcept>

namespace osgLoA
{

namespace
{
void registerGraphicStyle(const AbstractionStyle& style)
{
    osg::ref_ptr<GraphicStyle> g = GraphicStyle::createBuiltin("photorealistic");
    g->setName(style.getName());
    g->setDescription(style.getDescription() + " (image-space, osgLoA::AbstractionNode)");
    GraphicStyleCatalog::instance().add(*g);
}

// Registers the built-in abstraction styles as graphic styles when the library is loaded, so
// that scenarios read before any abstraction code runs can name them.
struct Registrar
{
    Registrar() { AbstractionStyleCatalog::instance(); }
} s_registrar;
} // namespace

AbstractionStyleCatalog::AbstractionStyleCatalog()
{
    for (const std::string& name : AbstractionStyle::builtinNames())
    {
        osg::ref_ptr<AbstractionStyle> s = AbstractionStyle::createBuiltin(name);
        registerGraphicStyle(*s);
        _styles.push_back(s.get());
    }
}

AbstractionStyleCatalog& AbstractionStyleCatalog::instance()
{
    static AbstractionStyleCatalog catalog;
    return catalog;
}

void AbstractionStyleCatalog::add(const AbstractionStyle& style)
{
    const std::string& name = style.getName();
    if (name.empty() || name.find_first_of(" \t\r\n") != std::string::npos)
        throw std::invalid_argument("abstraction style name '" + name +
                                    "' must be non-empty and contain no spaces");
    style.validate();
    std::lock_guard<std::mutex> lock(_mutex);
    bool known = false;
    for (const auto& s : _styles)
        known = known || s->getName() == name;
    if (!known && GraphicStyleCatalog::instance().contains(name))
        throw std::invalid_argument("'" + name +
                                    "' is already a graphic style that is not an abstraction style");
    osg::ref_ptr<const AbstractionStyle> copy = new AbstractionStyle(style, osg::CopyOp::DEEP_COPY_ALL);
    registerGraphicStyle(*copy);
    for (auto& s : _styles)
        if (s->getName() == name)
        {
            s = copy;
            return;
        }
    _styles.push_back(copy);
}

bool AbstractionStyleCatalog::contains(const std::string& name) const
{
    std::lock_guard<std::mutex> lock(_mutex);
    for (const auto& s : _styles)
        if (s->getName() == name) return true;
    return false;
}

std::vector<std::string> AbstractionStyleCatalog::names() const
{
    std::lock_guard<std::mutex> lock(_mutex);
    std::vector<std::string> n;
    for (const auto& s : _styles)
        n.push_back(s->getName());
    return n;
}

osg::ref_ptr<AbstractionStyle> AbstractionStyleCatalog::create(const std::string& name) const
{
    std::lock_guard<std::mutex> lock(_mutex);
    std::string known;
    for (const auto& s : _styles)
    {
        if (s->getName() == name) return new AbstractionStyle(*s, osg::CopyOp::DEEP_COPY_ALL);
        known += (known.empty() ? "" : ", ") + s->getName();
    }
    throw std::invalid_argument("unknown abstraction style '" + name + "' (known: " + known + ")");
}

} // namespace osgLoA
