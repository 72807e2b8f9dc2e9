// GraphicStyleCatalog: the style names configurations may use, and their styles.
#include <osgLoA/styles/GraphicStyleCatalog>

#include <stdexcept>

namespace osgLoA
{

namespace
{
osg::ref_ptr<const GraphicStyle> deepCopy(const GraphicStyle& style)
{
    return osg::ref_ptr<const GraphicStyle>(new GraphicStyle(style, osg::CopyOp::DEEP_COPY_ALL));
}
} // namespace

GraphicStyleCatalog::GraphicStyleCatalog()
{
    for (const std::string& name : GraphicStyle::builtinNames())
    {
        osg::ref_ptr<GraphicStyle> style = GraphicStyle::createBuiltin(name);
        _entries.push_back({name, style->getDescription(), style.get()});
    }
}

GraphicStyleCatalog& GraphicStyleCatalog::instance()
{
    static GraphicStyleCatalog catalog;
    return catalog;
}

void GraphicStyleCatalog::checkName(const std::string& name)
{
    if (name.empty() || name.find_first_of(" \t\r\n") != std::string::npos)
        throw std::invalid_argument("style name '" + name + "' must be non-empty and contain no spaces");
}

void GraphicStyleCatalog::add(const std::string& name, const std::string& description)
{
    checkName(name);
    std::lock_guard<std::mutex> lock(_mutex);
    for (Entry& e : _entries)
        if (e.name == name)
        {
            // Prototypes are immutable: re-describe a copy.
            osg::ref_ptr<GraphicStyle> copy = new GraphicStyle(*e.style, osg::CopyOp::DEEP_COPY_ALL);
            copy->setDescription(description);
            e.description = description;
            e.style = copy.get();
            return;
        }
    osg::ref_ptr<GraphicStyle> style = new GraphicStyle;
    style->setName(name);
    style->setDescription(description);
    style->setFragmentShader("loa_style_" + name + ".frag.glsl");
    _entries.push_back({name, description, style.get()});
}

void GraphicStyleCatalog::add(const GraphicStyle& style)
{
    checkName(style.getName());
    osg::ref_ptr<const GraphicStyle> copy = deepCopy(style);
    std::lock_guard<std::mutex> lock(_mutex);
    for (Entry& e : _entries)
        if (e.name == style.getName())
        {
            e.description = style.getDescription();
            e.style = copy;
            return;
        }
    _entries.push_back({style.getName(), style.getDescription(), copy});
}

bool GraphicStyleCatalog::contains(const std::string& name) const
{
    std::lock_guard<std::mutex> lock(_mutex);
    for (const Entry& e : _entries)
        if (e.name == name) return true;
    return false;
}

std::vector<GraphicStyleCatalog::Entry> GraphicStyleCatalog::entries() const
{
    std::lock_guard<std::mutex> lock(_mutex);
    return _entries;
}

std::vector<std::string> GraphicStyleCatalog::names() const
{
    std::lock_guard<std::mutex> lock(_mutex);
    std::vector<std::string> out;
    for (const Entry& e : _entries)
        out.push_back(e.name);
    return out;
}

osg::ref_ptr<const GraphicStyle> GraphicStyleCatalog::prototype(const std::string& name) const
{
    std::lock_guard<std::mutex> lock(_mutex);
    for (const Entry& e : _entries)
        if (e.name == name) return e.style;
    return nullptr;
}

osg::ref_ptr<GraphicStyle> GraphicStyleCatalog::create(const std::string& name) const
{
    osg::ref_ptr<const GraphicStyle> p = prototype(name);
    if (!p) throw std::invalid_argument("unknown graphic style '" + name + "'");
    // Copying outside the lock: prototypes are never modified, only replaced.
    return new GraphicStyle(*p, osg::CopyOp::DEEP_COPY_ALL);
}

} // namespace osgLoA
