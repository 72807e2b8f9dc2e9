#include <osgLoA/semantics/FeatureType>

#include <algorithm>
#include <cctype>

namespace osgLoA
{

const char* toString(FeatureType type)
{
    switch (type)
    {
    case FeatureType::Building:
        return "building";
    case FeatureType::Street:
        return "street";
    case FeatureType::Water:
        return "water";
    case FeatureType::Green:
        return "green";
    case FeatureType::Terrain:
        return "terrain";
    case FeatureType::Generic:
        break;
    }
    return "generic";
}

bool parseFeatureType(const std::string& name, FeatureType& type)
{
    std::string n = name;
    std::transform(n.begin(), n.end(), n.begin(), [](unsigned char c) { return std::tolower(c); });
    for (FeatureType t : kFeatureTypes)
        if (n == toString(t))
        {
            type = t;
            return true;
        }
    return false;
}

} // namespace osgLoA
