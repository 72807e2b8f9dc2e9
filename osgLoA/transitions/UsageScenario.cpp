// UsageScenario: interest overrides, ordered configurations, regions and focus; validation.
#include <osgLoA/transitions/UsageScenario>

#include <set>

namespace osgLoA
{

UsageScenario::UsageScenario() = default;

UsageScenario::UsageScenario(const UsageScenario& other, const osg::CopyOp& copyop)
    : osg::Object(other, copyop), _description(other._description),
      _interest(other._interest.valid() ? osg::clone(other._interest.get(), copyop) : nullptr),
      _focusFeature(other._focusFeature)
{
    for (const auto& c : other._configurations)
        _configurations.push_back(c.valid() ? osg::clone(c.get(), copyop) : nullptr);
    for (const auto& r : other._regions)
        _regions.push_back(r.valid() ? osg::clone(r.get(), copyop) : nullptr);
}

TransitionConfiguration* UsageScenario::addConfiguration(TransitionConfiguration* c)
{
    _configurations.push_back(c);
    return c;
}

TransitionConfiguration* UsageScenario::findConfiguration(const std::string& name)
{
    for (const auto& c : _configurations)
        if (c.valid() && c->getName() == name) return c.get();
    return nullptr;
}

RegionOfInterest* UsageScenario::addRegion(RegionOfInterest* r)
{
    _regions.push_back(r);
    return r;
}

float UsageScenario::staticInterestOf(const Feature& feature) const
{
    return _interest.valid() ? _interest->interestOf(feature) : feature.getInterest();
}

UsageScenario::Validation UsageScenario::validate() const
{
    Validation v;
    if (_configurations.empty()) v.errors.push_back("the scenario has no transition configuration");
    if (_configurations.size() > kMaxConfigurations)
        v.errors.push_back("the scenario has " + std::to_string(_configurations.size()) +
                           " configurations; the renderer's fragment stage holds at most " +
                           std::to_string(kMaxConfigurations));
    bool usableRegion = false;
    for (const auto& r : _regions)
    {
        if (!r.valid())
        {
            v.errors.push_back("a null region of interest");
            continue;
        }
        const std::string e = r->validate();
        if (e.empty())
            usableRegion = true;
        else
            v.errors.push_back("region: " + e);
    }
    std::set<std::string> names;
    std::set<FeatureType> drawn;
    for (const auto& c : _configurations)
    {
        if (!c.valid())
        {
            v.errors.push_back("a null transition configuration");
            continue;
        }
        for (const std::string& p : c->validate())
            v.errors.push_back(p);
        const std::string label = "configuration '" + c->getName() + "': ";
        if (c->getMetric(SaliencyMetric::REGION) && !usableRegion)
            v.errors.push_back(label + "uses the region metric but the scenario has no usable region");
        if (c->getMetric(SaliencyMetric::FOCUS) && _focusFeature == 0)
            v.errors.push_back(label + "uses the focus metric but the scenario has no focus object");
        if (!c->getName().empty() && !names.insert(c->getName()).second)
            v.warnings.push_back("two configurations are named '" + c->getName() + "'");
        if (c->getStyle() != "hidden")
            for (FeatureType t : c->getFeatureTypes())
                drawn.insert(t);
    }
    for (FeatureType t : kFeatureTypes)
        if (!_configurations.empty() && !drawn.count(t))
            v.warnings.push_back(std::string("no configuration draws ") + toString(t) +
                                 " features: they will not be drawn");
    return v;
}

} // namespace osgLoA
