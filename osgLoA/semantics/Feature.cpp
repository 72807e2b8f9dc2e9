#include <osgLoA/semantics/Feature>

#include <osg/UserDataContainer>

#include <cctype>
#include <cmath>

namespace osgLoA
{

Feature::Feature()
{
    setName(kUserObjectName);
}

Feature::Feature(unsigned id, FeatureType type, const std::string& subType, Source source)
    : _id(id), _type(type), _subType(subType), _source(source)
{
    setName(kUserObjectName);
}

Feature::Feature(const Feature& o, const osg::CopyOp& copyop)
    : osg::Object(o, copyop), _id(o._id), _type(o._type), _subType(o._subType), _source(o._source),
      _interest(o._interest), _landmark(o._landmark), _bestViewDirection(o._bestViewDirection),
      _bound(o._bound), _lod(o._lod), _sourceId(o._sourceId), _sourceType(o._sourceType),
      _centreline(o._centreline), _label(o._label)
{
}

void Feature::setInterest(float interest)
{
    if (!std::isfinite(interest)) interest = std::isinf(interest) && interest > 0 ? 1.0f : 0.0f;
    _interest = interest < 0.0f ? 0.0f : (interest > 1.0f ? 1.0f : interest);
}

std::string Feature::defaultNodeName(FeatureType type, unsigned id)
{
    std::string t = osgLoA::toString(type);
    t[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(t[0])));
    return t + "_" + std::to_string(id);
}

Feature* Feature::attach(osg::Node& node, Feature* feature)
{
    if (!feature) return nullptr;
    feature->setName(kUserObjectName);
    osg::UserDataContainer* udc = node.getOrCreateUserDataContainer();
    const unsigned i = udc->getUserObjectIndex(kUserObjectName);
    if (i < udc->getNumUserObjects())
        udc->setUserObject(i, feature);
    else
        udc->addUserObject(feature);
    if (node.getName().empty()) node.setName(feature->defaultNodeName());
    return feature;
}

const Feature* Feature::get(const osg::Node& node)
{
    const osg::UserDataContainer* udc = node.getUserDataContainer();
    if (!udc) return nullptr;
    const unsigned i = udc->getUserObjectIndex(kUserObjectName);
    if (i >= udc->getNumUserObjects()) return nullptr;
    return dynamic_cast<const Feature*>(udc->getUserObject(i));
}

Feature* Feature::get(osg::Node& node)
{
    return const_cast<Feature*>(get(static_cast<const osg::Node&>(node)));
}

bool Feature::detach(osg::Node& node)
{
    osg::UserDataContainer* udc = node.getUserDataContainer();
    if (!udc) return false;
    const unsigned i = udc->getUserObjectIndex(kUserObjectName);
    if (i >= udc->getNumUserObjects()) return false;
    udc->removeUserObject(i);
    return true;
}

const char* Feature::toString(Source s)
{
    switch (s)
    {
    case MODEL_DATA:
        return "model-data";
    case RULE:
        return "rule";
    case APPEARANCE:
        return "appearance";
    case USER:
        return "user";
    case UNCLASSIFIED:
        break;
    }
    return "unclassified";
}

} // namespace osgLoA
