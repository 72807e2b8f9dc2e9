// TransitionConfiguration: scope, style, interpolation, metric combination, validity range.
#include <osgLoA/transitions/TransitionConfiguration>

#include <osgLoA/styles/GraphicStyleCatalog>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

namespace osgLoA
{

namespace
{
std::string lower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

bool finite2(const osg::Vec2f& v)
{
    return std::isfinite(v.x()) && std::isfinite(v.y());
}

/** Combines metric interests one at a time, the way interestAt does. */
struct Combiner
{
    double sum = 0.0, weights = 0.0, lo = 1.0, hi = 0.0;
    void add(double weight, double v)
    {
        sum += weight * v;
        weights += weight;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    double result(TransitionConfiguration::Combination c) const
    {
        switch (c)
        {
        case TransitionConfiguration::MINIMUM:
            return lo;
        case TransitionConfiguration::MAXIMUM:
            return hi;
        case TransitionConfiguration::WEIGHTED_MEAN:
            break;
        }
        return weights > 0.0 ? sum / weights : 0.0;
    }
};
} // namespace

TransitionConfiguration::TransitionConfiguration() = default;

TransitionConfiguration::TransitionConfiguration(const TransitionConfiguration& other,
                                                 const osg::CopyOp& copyop)
    : osg::Object(other, copyop), _featureTypes(other._featureTypes), _subTypes(other._subTypes),
      _lodRange(other._lodRange), _interestRange(other._interestRange), _style(other._style),
      _interpolation(other._interpolation), _groupFocus(other._groupFocus),
      _hasGroupFocus(other._hasGroupFocus), _combination(other._combination), _fadeIn(other._fadeIn),
      _fadeOut(other._fadeOut)
{
    for (const auto& m : other._metrics)
        _metrics.push_back(m.valid() ? static_cast<SaliencyMetric*>(copyop(m.get())) : nullptr);
}

void TransitionConfiguration::setFeatureTypes(const FeatureTypes& types)
{
    _featureTypes = types;
    std::sort(_featureTypes.begin(), _featureTypes.end());
    _featureTypes.erase(std::unique(_featureTypes.begin(), _featureTypes.end()), _featureTypes.end());
}

void TransitionConfiguration::addFeatureType(FeatureType type)
{
    FeatureTypes t = _featureTypes;
    t.push_back(type);
    setFeatureTypes(t);
}

bool TransitionConfiguration::hasFeatureType(FeatureType type) const
{
    return std::binary_search(_featureTypes.begin(), _featureTypes.end(), type);
}

void TransitionConfiguration::setAllFeatureTypes()
{
    setFeatureTypes(FeatureTypes(std::begin(kFeatureTypes), std::end(kFeatureTypes)));
}

bool TransitionConfiguration::matches(const Feature& feature, float staticInterest) const
{
    if (!hasFeatureType(feature.getType())) return false;
    if (!_subTypes.empty() &&
        std::find(_subTypes.begin(), _subTypes.end(), feature.getSubType()) == _subTypes.end())
        return false;
    const float lod = feature.getLod();
    if (lod >= 0.0f && (lod < _lodRange.x() || lod > _lodRange.y())) return false;
    // Half-open like the hard fades, [min, max), so that successive scopes never overlap;
    // a scope reaching 1 includes 1.
    return staticInterest >= _interestRange.x() &&
           (staticInterest < _interestRange.y() || (_interestRange.y() >= 1.0f && staticInterest <= 1.0f));
}

SaliencyMetric* TransitionConfiguration::addMetric(SaliencyMetric* metric)
{
    osg::ref_ptr<SaliencyMetric> keep = metric;
    if (!metric) return nullptr;
    for (auto& m : _metrics)
        if (m.valid() && m->getKind() == metric->getKind())
        {
            m = metric;
            return metric;
        }
    _metrics.push_back(metric);
    return metric;
}

const SaliencyMetric* TransitionConfiguration::getMetric(SaliencyMetric::Kind kind) const
{
    for (const auto& m : _metrics)
        if (m.valid() && m->getKind() == kind) return m.get();
    return nullptr;
}

double TransitionConfiguration::interestAt(const osg::Vec3d& p, const SaliencyView& view,
                                           double featureInterest) const
{
    Combiner c;
    bool any = false;
    for (const auto& m : _metrics)
    {
        if (!m.valid()) continue;
        c.add(m->getWeight(), m->evaluate(p, view, featureInterest));
        any = true;
    }
    return any ? c.result(_combination) : 0.0;
}

void TransitionConfiguration::interestRange(const osg::BoundingBoxd& box, const SaliencyView& view,
                                            double featureInterest, double& lo, double& hi) const
{
    // Every metric's interest is non-increasing in its quantity, and every combination is
    // non-decreasing in each metric's interest, so the bounds combine bound by bound.
    Combiner cLo, cHi;
    bool any = false;
    for (const auto& m : _metrics)
    {
        if (!m.valid()) continue;
        double iLo = 0.0, iHi = 0.0;
        m->interestRange(box, view, featureInterest, iLo, iHi);
        cLo.add(m->getWeight(), iLo);
        cHi.add(m->getWeight(), iHi);
        any = true;
    }
    lo = any ? cLo.result(_combination) : 0.0;
    hi = any ? cHi.result(_combination) : 0.0;
}

void TransitionConfiguration::interestOverBox(const osg::BoundingBoxd& box, const SaliencyView& view,
                                              double featureInterest, double& atCentre, double& lo,
                                              double& hi) const
{
    Combiner cAt, cLo, cHi;
    bool any = false;
    for (const auto& m : _metrics)
    {
        if (!m.valid()) continue;
        double v = 0.0, iLo = 0.0, iHi = 0.0;
        m->evaluateOverBox(box, view, featureInterest, v, iLo, iHi);
        cAt.add(m->getWeight(), v);
        cLo.add(m->getWeight(), iLo);
        cHi.add(m->getWeight(), iHi);
        any = true;
    }
    atCentre = any ? cAt.result(_combination) : 0.0;
    lo = any ? cLo.result(_combination) : 0.0;
    hi = any ? cHi.result(_combination) : 0.0;
}

bool TransitionConfiguration::hasSameInterestAs(const TransitionConfiguration& other) const
{
    if (_combination != other._combination) return false;
    auto a = _metrics.begin(), b = other._metrics.begin();
    for (;;)
    {
        while (a != _metrics.end() && !a->valid())
            ++a;
        while (b != other._metrics.end() && !b->valid())
            ++b;
        if (a == _metrics.end() || b == other._metrics.end())
            return a == _metrics.end() && b == other._metrics.end();
        if (!(*a)->sameValuesAs(**b)) return false;
        ++a;
        ++b;
    }
}

std::vector<std::string> TransitionConfiguration::validate() const
{
    std::vector<std::string> problems;
    const std::string label =
        "configuration '" + (getName().empty() ? std::string("(unnamed)") : getName()) + "': ";
    if (_featureTypes.empty()) problems.push_back(label + "empty scope: no feature type");
    if (_style.empty())
        problems.push_back(label + "no graphic style");
    else if (!GraphicStyleCatalog::instance().contains(_style))
        problems.push_back(label + "unknown graphic style '" + _style + "'");
    const std::string blend = getBlendFunction().validate();
    if (!blend.empty()) problems.push_back(label + blend);
    if (!finite2(_lodRange) || _lodRange.x() > _lodRange.y())
    {
        std::ostringstream s;
        s << label << "LoD range [" << _lodRange.x() << ", " << _lodRange.y()
          << "] is inverted or not finite";
        problems.push_back(s.str());
    }
    if (!finite2(_interestRange) || _interestRange.x() >= _interestRange.y() || _interestRange.x() < 0.0f ||
        _interestRange.y() > 1.0f)
    {
        std::ostringstream s;
        s << label << "interest scope [" << _interestRange.x() << ", " << _interestRange.y()
          << "] is empty, inverted or outside [0, 1]";
        problems.push_back(s.str());
    }
    if (_metrics.empty()) problems.push_back(label + "no saliency metric");
    bool seen[SaliencyMetric::kNumKinds] = {};
    for (const auto& m : _metrics)
    {
        if (!m.valid())
        {
            problems.push_back(label + "a null saliency metric");
            continue;
        }
        if (int(m->getKind()) < 0 || int(m->getKind()) >= SaliencyMetric::kNumKinds)
        {
            problems.push_back(label + "a saliency metric of unknown kind " +
                               std::to_string(int(m->getKind())));
            continue;
        }
        if (seen[m->getKind()])
            problems.push_back(label + "two " + SaliencyMetric::toString(m->getKind()) + " metrics");
        seen[m->getKind()] = true;
        const std::string e = m->validate();
        if (!e.empty()) problems.push_back(label + e);
    }
    if (_hasGroupFocus && _interpolation != GROUP)
        problems.push_back(label + "a group focus point is set but the interpolation is " +
                           toString(_interpolation));
    return problems;
}

const char* TransitionConfiguration::toString(Interpolation mode)
{
    switch (mode)
    {
    case FRAGMENT:
        return "fragment";
    case OBJECT:
        return "object";
    case GROUP:
        return "group";
    }
    return "object";
}

bool TransitionConfiguration::parseInterpolation(const std::string& name, Interpolation& mode)
{
    const std::string n = lower(name);
    for (Interpolation m : {FRAGMENT, OBJECT, GROUP})
        if (n == toString(m))
        {
            mode = m;
            return true;
        }
    return false;
}

const char* TransitionConfiguration::toString(Combination c)
{
    switch (c)
    {
    case WEIGHTED_MEAN:
        return "weighted-mean";
    case MINIMUM:
        return "minimum";
    case MAXIMUM:
        return "maximum";
    }
    return "weighted-mean";
}

bool TransitionConfiguration::parseCombination(const std::string& name, Combination& c)
{
    std::string n = lower(name);
    std::replace(n.begin(), n.end(), '_', '-');
    for (Combination m : {WEIGHTED_MEAN, MINIMUM, MAXIMUM})
        if (n == toString(m))
        {
            c = m;
            return true;
        }
    return false;
}

} // namespace osgLoA
