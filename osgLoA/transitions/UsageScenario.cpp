// UsageScenario: interest overrides, ordered configurations, regions and focus; validation.
#include <osgLoA/styles/ColorScheme>
#include <osgLoA/transitions/UsageScenario>

#include <algorithm>
#include <map>
#include <set>
#include <sstream>
#include <vector>

namespace osgLoA
{

UsageScenario::UsageScenario() = default;

UsageScenario::UsageScenario(const UsageScenario& other, const osg::CopyOp& copyop)
    : osg::Object(other, copyop), _description(other._description),
      _interest(other._interest.valid() ? static_cast<FeatureInterest*>(copyop(other._interest.get()))
                                        : nullptr),
      _focusFeature(other._focusFeature), _focusTallestLandmark(other._focusTallestLandmark),
      _landmarkDeformation(other._landmarkDeformation.valid()
                               ? static_cast<LandmarkDeformation*>(copyop(other._landmarkDeformation.get()))
                               : nullptr),
      _colorScheme(other._colorScheme)
{
    for (const auto& c : other._configurations)
        _configurations.push_back(c.valid() ? static_cast<TransitionConfiguration*>(copyop(c.get()))
                                            : nullptr);
    for (const auto& r : other._regions)
        _regions.push_back(r.valid() ? static_cast<RegionOfInterest*>(copyop(r.get())) : nullptr);
}

void UsageScenario::assign(const UsageScenario& other)
{
    if (&other == this) return;
    osg::ref_ptr<UsageScenario> copy = new UsageScenario(other, osg::CopyOp::DEEP_COPY_ALL);
    setName(copy->getName());
    _description = copy->_description;
    _interest = copy->_interest;
    _configurations = copy->_configurations;
    _regions = copy->_regions;
    _focusFeature = copy->_focusFeature;
    _focusTallestLandmark = copy->_focusTallestLandmark;
    _landmarkDeformation = copy->_landmarkDeformation;
    _colorScheme = copy->_colorScheme;
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
    if (_landmarkDeformation.valid())
    {
        const std::string e = _landmarkDeformation->validate();
        if (!e.empty()) v.errors.push_back("landmark deformation: " + e);
    }
    if (!_colorScheme.empty() && !ColorScheme::find(_colorScheme))
        v.errors.push_back("colour scheme '" + _colorScheme + "' is not one of " + ColorScheme::names());
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
        if (c->getMetric(SaliencyMetric::FOCUS) && _focusFeature == 0 && !_focusTallestLandmark)
            v.errors.push_back(label + "uses the focus metric but the scenario has no focus object");
        if (!c->getName().empty() && !names.insert(c->getName()).second)
            v.warnings.push_back("two configurations are named '" + c->getName() + "'");
        if (c->getStyle() != "hidden")
            for (FeatureType t : c->getFeatureTypes())
                drawn.insert(t);
    }
    // Gaps: for each type and static interest, the configurations in scope; when they all use
    // the same metrics (so one interest axis is shared), interest values where every weight is
    // 0 leave those features undrawn. A configuration's weights at the 1,001 interest samples are
    // computed once, not once per type and static interest (55 times: most of a validation).
    std::map<const TransitionConfiguration*, std::vector<float>> sampled;
    const auto weights = [&sampled](const TransitionConfiguration* c) -> const std::vector<float>&
    {
        auto it = sampled.find(c);
        if (it == sampled.end())
        {
            std::vector<float> w(1001);
            for (int k = 0; k <= 1000; ++k)
                w[k] = c->getBlendFunction().weight(k / 1000.0f);
            it = sampled.emplace(c, std::move(w)).first;
        }
        return it->second;
    };
    for (FeatureType t : kFeatureTypes)
        for (int si = 0; si <= 10 && drawn.count(t); ++si)
        {
            const float staticInterest = si / 10.0f;
            std::vector<const TransitionConfiguration*> inScope;
            for (const auto& c : _configurations)
                if (c.valid() && c->hasFeatureType(t) && c->getSubTypes().empty() &&
                    staticInterest >= c->getInterestRange().x() &&
                    staticInterest <= c->getInterestRange().y())
                    inScope.push_back(c.get());
            if (inScope.empty())
            {
                v.warnings.push_back(std::string(toString(t)) + " features of static interest " +
                                     std::to_string(si / 10) + "." + std::to_string(si % 10) +
                                     " are in no configuration's scope: they will not be drawn");
                break;
            }
            if (!std::all_of(inScope.begin(), inScope.end(),
                             [&](const TransitionConfiguration* c)
                             { return c->hasSameInterestAs(*inScope.front()); }))
                continue;
            std::vector<const std::vector<float>*> drawing;
            for (const TransitionConfiguration* c : inScope)
                if (c->getStyle() != "hidden") drawing.push_back(&weights(c));
            int gapBegin = -1;
            for (int k = 0; k <= 1000; ++k)
            {
                float sum = 0.0f;
                for (const std::vector<float>* w : drawing)
                    sum += (*w)[k];
                if (sum <= 0.0f && gapBegin < 0) gapBegin = k;
                if ((sum > 0.0f || k == 1000) && gapBegin >= 0)
                {
                    std::ostringstream w;
                    w << toString(t) << " features get no style at interest " << gapBegin / 1000.0f << " to "
                      << (sum > 0.0f ? (k - 1) : k) / 1000.0f << ": no fade range covers it";
                    v.warnings.push_back(w.str());
                    gapBegin = -1;
                    k = 1001;
                }
            }
        }
    for (FeatureType t : kFeatureTypes)
        if (!_configurations.empty() && !drawn.count(t))
            v.warnings.push_back(std::string("no configuration draws ") + toString(t) +
                                 " features: they will not be drawn");
    return v;
}

} // namespace osgLoA
