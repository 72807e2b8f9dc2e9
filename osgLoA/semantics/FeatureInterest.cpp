#include <osgLoA/semantics/FeatureInterest>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace osgLoA
{

namespace
{
void checkUnit(float value, const std::string& what)
{
    if (std::isnan(value) || value < 0.0f || value > 1.0f)
    {
        std::ostringstream s;
        s << "FeatureInterest: " << what << " " << value << " is outside [0,1]";
        throw std::invalid_argument(s.str());
    }
}
} // namespace

FeatureInterest::FeatureInterest() {}

FeatureInterest::FeatureInterest(const FeatureInterest& o, const osg::CopyOp& copyop)
    : osg::Object(o, copyop), _typeInterests(o._typeInterests), _featureInterests(o._featureInterests),
      _defaultInterest(o._defaultInterest), _keepExistingInterest(o._keepExistingInterest),
      _landmarkThreshold(o._landmarkThreshold)
{
}

void FeatureInterest::setTypeInterest(FeatureType type, float interest)
{
    checkUnit(interest, std::string("interest of type ") + toString(type));
    _typeInterests[type] = interest;
}

void FeatureInterest::removeTypeInterest(FeatureType type)
{
    _typeInterests.erase(type);
}

bool FeatureInterest::hasTypeInterest(FeatureType type) const
{
    return _typeInterests.count(type) != 0;
}

float FeatureInterest::getTypeInterest(FeatureType type) const
{
    auto it = _typeInterests.find(type);
    return it == _typeInterests.end() ? _defaultInterest : it->second;
}

void FeatureInterest::setTypeInterests(const TypeInterests& interests)
{
    for (const auto& kv : interests)
        checkUnit(kv.second, std::string("interest of type ") + toString(kv.first));
    _typeInterests = interests;
}

void FeatureInterest::setFeatureInterest(unsigned featureId, float interest)
{
    checkUnit(interest, "interest of feature " + std::to_string(featureId));
    _featureInterests[featureId] = interest;
}

void FeatureInterest::removeFeatureInterest(unsigned featureId)
{
    _featureInterests.erase(featureId);
}

bool FeatureInterest::hasFeatureInterest(unsigned featureId) const
{
    return _featureInterests.count(featureId) != 0;
}

void FeatureInterest::setFeatureInterests(const FeatureInterests& interests)
{
    for (const auto& kv : interests)
        checkUnit(kv.second, "interest of feature " + std::to_string(kv.first));
    _featureInterests = interests;
}

void FeatureInterest::setDefaultInterest(float interest)
{
    checkUnit(interest, "default interest");
    _defaultInterest = interest;
}

void FeatureInterest::setLandmarkThreshold(float threshold)
{
    checkUnit(threshold, "landmark threshold");
    _landmarkThreshold = threshold;
}

float FeatureInterest::interestOf(const Feature& feature) const
{
    auto byId = _featureInterests.find(feature.getId());
    if (byId != _featureInterests.end()) return byId->second;
    auto byType = _typeInterests.find(feature.getType());
    if (byType != _typeInterests.end()) return byType->second;
    if (_keepExistingInterest) return feature.getInterest();
    return _defaultInterest;
}

unsigned FeatureInterest::apply(FeatureIndex& index) const
{
    unsigned landmarks = 0;
    for (const FeatureIndex::Entry& e : index.entries())
    {
        Feature& f = *e.feature;
        f.setInterest(interestOf(f));
        const bool landmark = f.getInterest() >= _landmarkThreshold;
        f.setLandmark(landmark);
        if (landmark) ++landmarks;
    }
    return landmarks;
}

} // namespace osgLoA
