// ScenarioEvaluator: static matching at bind time, per-frame interest and normalized weights.
#include <osgLoA/transitions/ScenarioEvaluator>

#include <algorithm>
#include <map>
#include <stdexcept>
#include <tuple>

namespace osgLoA
{

void ScenarioEvaluator::bind(const UsageScenario* scenario, const FeatureIndex& index)
{
    if (!scenario) throw std::invalid_argument("no usage scenario to bind");
    const UsageScenario::Validation v = scenario->validate();
    if (!v.ok())
    {
        std::string msg = "usage scenario '" + scenario->getName() + "' is not valid: " + v.errors.front();
        if (v.errors.size() > 1) msg += " (and " + std::to_string(v.errors.size() - 1) + " more)";
        throw std::invalid_argument(msg);
    }
    _revision = scenario->getRevision();
    _fitting.fit(*scenario, index);
    scenario = _fitting.getScenario();
    _scenario = scenario;
    _features.clear();
    _matches.clear();
    _ids.clear();
    _view = SaliencyView();
    _view.regions = &scenario->getRegions();
    _stats = Statistics();

    const auto& configs = scenario->getConfigurations();
    const auto& entries = index.entries();
    _features.reserve(entries.size());
    _ids.reserve(entries.size());

    // Group-mode matches share the centre of the union box of their group:
    // (configuration, enclosing feature, sub-type).
    typedef std::tuple<unsigned, int, std::string> GroupKey;
    std::map<GroupKey, osg::BoundingBoxd> groups;
    std::vector<std::pair<std::size_t, GroupKey>> groupMatches; // (match index, its group)

    for (unsigned i = 0; i < entries.size(); ++i)
    {
        const Feature& f = *entries[i].feature;
        FeatureState s;
        s.entry = i;
        s.staticInterest = scenario->staticInterestOf(f);
        const osg::BoundingBoxf& b = f.getBound();
        if (b.valid()) s.bound = osg::BoundingBoxd(osg::Vec3d(b._min), osg::Vec3d(b._max));
        s.firstMatch = unsigned(_matches.size());
        if (s.bound.valid())
            for (unsigned j = 0; j < configs.size(); ++j)
            {
                const TransitionConfiguration& c = *configs[j];
                if (!c.matches(f, s.staticInterest)) continue;
                Match m;
                m.configuration = j;
                m.fragment = c.getInterpolation() == TransitionConfiguration::FRAGMENT;
                m.point = s.bound.center();
                if (c.getInterpolation() == TransitionConfiguration::GROUP)
                {
                    if (c.getHasGroupFocus())
                        m.point = c.getGroupFocus();
                    else
                    {
                        const GroupKey key(j, entries[i].parent, f.getSubType());
                        groups[key].expandBy(s.bound);
                        groupMatches.emplace_back(_matches.size(), key);
                    }
                }
                _matches.push_back(m);
            }
        s.numMatches = unsigned(_matches.size()) - s.firstMatch;
        _features.push_back(s);
        _ids.push_back(f.getId());
        if (scenario->getFocusFeature() != 0 && f.getId() == scenario->getFocusFeature() && s.bound.valid())
            _view.focus.expandBy(s.bound);
    }
    for (const auto& gm : groupMatches)
        _matches[gm.first].point = groups[gm.second].center();
}

void ScenarioEvaluator::evaluate(const osg::Vec3d& eye, const unsigned char* visible)
{
    if (!_scenario.valid()) throw std::logic_error("ScenarioEvaluator::evaluate before bind");
    _viewScaleChanged = _fitting.applyEye(eye);
    _view.eye = eye;
    _stats = Statistics();
    const auto& configs = _scenario->getConfigurations();

    // Configurations with the same combination of the same metrics give the same interest at
    // the same point (the built-in scenarios repeat one metric set over all their levels):
    // same[j] is the first configuration like j. Decided per frame (a few comparisons), so
    // metrics changed since bind count as they always have; configurations past
    // kMaxConfigurations (none in a valid scenario) are their own.
    constexpr unsigned kMax = UsageScenario::kMaxConfigurations;
    unsigned same[kMax];
    const unsigned numConfigs = unsigned(std::min<std::size_t>(configs.size(), kMax));
    for (unsigned j = 0; j < numConfigs; ++j)
    {
        same[j] = j;
        for (unsigned k = 0; k < j; ++k)
            if (same[k] == k && configs[k]->hasSameInterestAs(*configs[j]))
            {
                same[j] = k;
                break;
            }
    }
    auto sameAs = [&](unsigned j) { return j < numConfigs ? same[j] : j; };

    // Per feature, what its earlier matches computed: interest at the point and, once a
    // fragment match asked for it, the interest's range over the box.
    struct Computed
    {
        double interest, lo, hi;
        bool ranged;
    };
    Computed computed[kMax];

    for (std::size_t i = 0; i < _features.size(); ++i)
    {
        FeatureState& s = _features[i];
        s.visible = !visible || visible[i] != 0;
        if (!s.visible) continue;
        ++_stats.visibleFeatures;
        Match* m = _matches.data() + s.firstMatch;
        float sum = 0.0f;
        unsigned contributing = 0;
        for (unsigned k = 0; k < s.numMatches; ++k)
        {
            const TransitionConfiguration& c = *configs[m[k].configuration];
            const BlendFunction blend = c.getBlendFunction();
            // An earlier match of this feature with the same metrics at the same point.
            const unsigned key = sameAs(m[k].configuration);
            Computed* from = nullptr;
            for (unsigned j = 0; j < k && j < kMax; ++j)
                if (sameAs(m[j].configuration) == key && m[j].point == m[k].point)
                {
                    from = &computed[j];
                    break;
                }
            Computed here;
            if (from)
            {
                // Fragment matches are evaluated at the box centre, so the earlier match's
                // interest is the centre's; only the range may be missing.
                if (m[k].fragment && !from->ranged)
                {
                    c.interestRange(s.bound, _view, s.staticInterest, from->lo, from->hi);
                    from->ranged = true;
                }
                here = *from;
            }
            else if (m[k].fragment) // point == s.bound.center()
            {
                c.interestOverBox(s.bound, _view, s.staticInterest, here.interest, here.lo, here.hi);
                here.ranged = true;
            }
            else
            {
                here.interest = c.interestAt(m[k].point, _view, s.staticInterest);
                here.lo = here.hi = 0.0;
                here.ranged = false;
            }
            if (k < kMax) computed[k] = here;
            m[k].interest = float(here.interest);
            m[k].rawWeight = blend.weight(m[k].interest);
            m[k].mayContribute =
                m[k].fragment ? blend.mayContribute(float(here.lo), float(here.hi)) : m[k].rawWeight > 0.0f;
            m[k].coversFeature = m[k].fragment ? blend.contributesThroughout(float(here.lo), float(here.hi))
                                               : m[k].rawWeight > 0.0f;
            sum += m[k].rawWeight;
            contributing += m[k].mayContribute ? 1u : 0u;
        }
        for (unsigned k = 0; k < s.numMatches; ++k)
            m[k].weight = sum > 0.0f ? m[k].rawWeight / sum : 0.0f;
        _stats.matches += s.numMatches;
        _stats.contributing += contributing;
        if (contributing == 0) ++_stats.undrawnFeatures;
    }
}

int ScenarioEvaluator::findFeature(unsigned id) const
{
    for (std::size_t i = 0; i < _ids.size(); ++i)
        if (_ids[i] == id) return int(i);
    return -1;
}

} // namespace osgLoA
