// GraphicStyleCatalog: the style names configurations may use.
#include <osgLoA/styles/GraphicStyleCatalog>

#include <stdexcept>

namespace osgLoA
{

GraphicStyleCatalog::GraphicStyleCatalog()
{
    _entries = {
        {"photorealistic", "the model's own materials and textures, lit"},
        {"abstract", "colour-quantized textures (filtered mipmaps once texture filtering lands)"},
        {"cartographic", "a qualitative Brewer colour per feature type, flat shading, image-space edges"},
        {"blueprint", "white edges on a blue ground"},
        {"hidden", "draws nothing"}};
}

GraphicStyleCatalog& GraphicStyleCatalog::instance()
{
    static GraphicStyleCatalog catalog;
    return catalog;
}

void GraphicStyleCatalog::add(const std::string& name, const std::string& description)
{
    if (name.empty() || name.find_first_of(" \t\r\n") != std::string::npos)
        throw std::invalid_argument("style name '" + name + "' must be non-empty and contain no spaces");
    std::lock_guard<std::mutex> lock(_mutex);
    for (Entry& e : _entries)
        if (e.name == name)
        {
            e.description = description;
            return;
        }
    _entries.push_back({name, description});
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

} // namespace osgLoA
