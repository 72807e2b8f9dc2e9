// FeatureInspector: a feature's classification and blend weights at a point.
#include <osgLoA/authoring/FeatureInspector>

#include <iomanip>
#include <sstream>

namespace osgLoA
{

std::string FeatureInspector::Report::text() const
{
    std::ostringstream out;
    out << std::fixed << std::setprecision(3);
    out << "feature " << id << ": " << type << (subType.empty() ? "" : "/" + subType) << " (" << source
        << ")";
    if (!label.empty()) out << " '" << label << "'";
    out << "\n";
    if (!sourceType.empty()) out << "model class: " << sourceType << "\n";
    out << "interest " << staticInterest << (landmark ? ", landmark" : "") << (focus ? ", focus object" : "")
        << "\n";
    for (const Weight& w : weights)
        out << "  " << w.name << " [" << w.style << ", " << w.interpolation << "]: interest " << w.interest
            << ", weight " << w.weight << " (raw " << w.rawWeight << ")\n";
    return out.str();
}

FeatureInspector::Report FeatureInspector::inspect(const LoANode& node, unsigned featureId,
                                                   const osg::Vec3d& point)
{
    Report r;
    r.id = featureId;
    const FeatureIndex::Entry* entry = node.getFeatureIndex().find(featureId);
    if (!entry) return r;
    const Feature& f = *entry->feature;
    r.type = toString(f.getType());
    r.subType = f.getSubType();
    r.source = Feature::toString(f.getSource());
    r.label = f.getLabel();
    r.sourceType = f.getSourceType();
    const ScenarioEvaluator* evaluator = node.getEvaluator();
    if (!evaluator || !evaluator->isBound()) return r;
    const int i = evaluator->findFeature(featureId);
    if (i < 0) return r;
    r.found = true;
    const ScenarioEvaluator::FeatureState& s = evaluator->features()[std::size_t(i)];
    r.staticInterest = s.staticInterest;
    r.landmark = s.staticInterest >= 0.8f;
    r.focus = evaluator->getScenario()->getFocusFeature() == featureId;
    const auto& configs = evaluator->getScenario()->getConfigurations();
    const ScenarioEvaluator::Match* m = evaluator->matchesOf(s);
    float sum = 0.0f;
    for (unsigned k = 0; k < s.numMatches; ++k)
    {
        if (m[k].configuration >= configs.size() || !configs[m[k].configuration].valid()) continue;
        const TransitionConfiguration& c = *configs[m[k].configuration];
        Weight w;
        w.configuration = m[k].configuration;
        w.name = c.getName();
        w.style = c.getStyle();
        w.interpolation = TransitionConfiguration::toString(c.getInterpolation());
        if (m[k].fragment)
        {
            w.interest = float(c.interestAt(point, evaluator->getView(), s.staticInterest));
            w.rawWeight = c.getBlendFunction().weight(w.interest);
        }
        else
        {
            w.interest = m[k].interest;
            w.rawWeight = m[k].rawWeight;
        }
        sum += w.rawWeight;
        r.weights.push_back(w);
    }
    for (Weight& w : r.weights)
        w.weight = sum > 0.0f ? w.rawWeight / sum : 0.0f;
    return r;
}

} // namespace osgLoA
