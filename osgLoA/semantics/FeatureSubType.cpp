/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/semantics/FeatureSubType>

#include <algorithm>
#include <cctype>

namespace osgLoA
{

const std::vector<std::string>& FeatureSubType::names()
{
    static const std::vector<std::string> table = []
    {
        std::vector<std::string> t = {
            "",
            // green spaces (OSM landuse / leisure / natural, leaf_type; the demo city)
            "deciduous", "coniferous", "mixed", "forest", "wood", "park", "grass", "meadow", "garden",
            "village_green", "recreation_ground", "cemetery", "orchard", "vineyard", "allotments", "scrub",
            "heath", "grassland", "pitch", "golf_course", "playground", "nature_reserve", "tree",
            // water (OSM water / waterway; CityGML Waterway)
            "river", "stream", "canal", "lake", "pond", "reservoir", "sea", "waterway",
            // streets (OSM highway classes as the reader groups them; CityGML transportation)
            "major", "minor", "path", "rail", "railway", "track", "road", "square", "bridge", "tunnel",
            // buildings (the demo city; OSM building values most used)
            "residential", "commercial", "landmark", "industrial", "house", "apartments"};
        t.resize(kCount);
        return t;
    }();
    return table;
}

int FeatureSubType::code(const std::string& subType)
{
    if (subType.empty()) return 0;
    std::string lower(subType);
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    const std::vector<std::string>& t = names();
    const auto it = std::find(t.begin() + 1, t.end(), lower);
    return it == t.end() ? 0 : int(it - t.begin());
}

} // namespace osgLoA
