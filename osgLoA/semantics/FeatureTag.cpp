#include <osgLoA/semantics/FeatureTag>

#include <osg/ValueObject>

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
    for (FeatureType t : {FeatureType::Generic, FeatureType::Building, FeatureType::Street,
                          FeatureType::Water, FeatureType::Green, FeatureType::Terrain})
        if (n == toString(t))
        {
            type = t;
            return true;
        }
    return false;
}

std::string FeatureTag::nodeName() const
{
    std::string t = toString(type);
    t[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(t[0])));
    return t + "_" + std::to_string(id);
}

void FeatureTag::apply(osg::Node& node) const
{
    node.setUserValue(kId, id);
    node.setUserValue(kType, std::string(toString(type)));
    node.setUserValue(kSubtype, subtype);
    if (landmark) node.setUserValue(kLandmark, true);
    node.setName(nodeName());
}

bool FeatureTag::read(const osg::Node& node, FeatureTag& tag)
{
    unsigned id = 0;
    std::string type;
    if (!node.getUserValue(kId, id) || !node.getUserValue(kType, type)) return false;
    FeatureTag t;
    t.id = id;
    if (!parseFeatureType(type, t.type)) t.type = FeatureType::Generic;
    node.getUserValue(kSubtype, t.subtype);
    bool lm = false;
    t.landmark = node.getUserValue(kLandmark, lm) && lm;
    tag = t;
    return true;
}

} // namespace osgLoA
