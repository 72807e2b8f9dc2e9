#include <osgLoA/semantics/Appearance>
#include <osgLoA/semantics/FeatureClassifier>
#include <osgLoA/semantics/FeatureIndex>

#include <osg/Geode>
#include <osg/Material>
#include <osg/Texture>
#include <osg/UserDataContainer>
#include <osg/ValueObject>
#include <osgDB/FileNameUtils>

#include <map>
#include <numeric>
#include <set>
#include <sstream>

namespace osgLoA
{

namespace
{
// Renders any user value as text ("key=value" matching).
class ValueText : public osg::ValueObject::GetValueVisitor
{
public:
    std::string text;
    void apply(bool v) override { text = v ? "true" : "false"; }
    void apply(char v) override { text = std::to_string(static_cast<int>(v)); }
    void apply(unsigned char v) override { text = std::to_string(static_cast<unsigned>(v)); }
    void apply(short v) override { text = std::to_string(v); }
    void apply(unsigned short v) override { text = std::to_string(v); }
    void apply(int v) override { text = std::to_string(v); }
    void apply(unsigned int v) override { text = std::to_string(v); }
    void apply(float v) override { text = number(v); }
    void apply(double v) override { text = number(v); }
    void apply(const std::string& v) override { text = v; }

private:
    static std::string number(double v)
    {
        std::ostringstream s;
        s << v;
        return s.str();
    }
};

void stateStrings(const osg::StateSet* ss, ClassificationRule::Field field, std::vector<std::string>& out)
{
    if (!ss) return;
    using F = ClassificationRule;
    if (field == F::MATERIAL_NAME || field == F::ANY)
    {
        if (!ss->getName().empty()) out.push_back(ss->getName());
        if (const osg::StateAttribute* m = ss->getAttribute(osg::StateAttribute::MATERIAL))
            if (!m->getName().empty()) out.push_back(m->getName());
    }
    if (field == F::TEXTURE_FILE || field == F::ANY)
        for (unsigned unit = 0; unit < ss->getTextureAttributeList().size(); ++unit)
            if (const osg::Texture* t = dynamic_cast<const osg::Texture*>(
                    ss->getTextureAttribute(unit, osg::StateAttribute::TEXTURE)))
                for (unsigned i = 0; i < t->getNumImages(); ++i)
                    if (const osg::Image* img = t->getImage(i))
                    {
                        if (!img->getFileName().empty())
                            out.push_back(osgDB::getSimpleFileName(img->getFileName()));
                        else if (!img->getName().empty())
                            out.push_back(img->getName());
                    }
}

class SubtreeNodes : public osg::NodeVisitor
{
public:
    SubtreeNodes() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) { setNodeMaskOverride(~0u); }
    void apply(osg::Node& n) override
    {
        nodes.push_back(&n);
        traverse(n);
    }
    std::vector<const osg::Node*> nodes;
};

struct UnionFind
{
    std::vector<std::size_t> p;
    explicit UnionFind(std::size_t n) : p(n) { std::iota(p.begin(), p.end(), 0); }
    std::size_t find(std::size_t x)
    {
        while (p[x] != x)
            x = p[x] = p[p[x]];
        return x;
    }
    void unite(std::size_t a, std::size_t b) { p[find(a)] = find(b); }
};
} // namespace

std::vector<std::string> FeatureClassifier::strings(const osg::Node& node, ClassificationRule::Field field,
                                                    const std::string& userValueKey)
{
    using F = ClassificationRule;
    std::vector<std::string> out;
    if ((field == F::NODE_NAME || field == F::ANY) && !node.getName().empty()) out.push_back(node.getName());
    if (field == F::NODE_DESCRIPTION || field == F::ANY)
        for (const std::string& d : node.getDescriptions())
            out.push_back(d);
    if (field == F::USER_VALUE) // not part of ANY: user values are arbitrary data
        if (const osg::UserDataContainer* udc = node.getUserDataContainer())
            for (unsigned i = 0; i < udc->getNumUserObjects(); ++i)
            {
                const osg::ValueObject* vo = dynamic_cast<const osg::ValueObject*>(udc->getUserObject(i));
                if (!vo) continue;
                ValueText vt;
                if (!vo->get(vt)) continue;
                if (field == F::USER_VALUE && !userValueKey.empty())
                {
                    if (vo->getName() == userValueKey) out.push_back(vt.text);
                }
                else
                    out.push_back(vo->getName() + "=" + vt.text);
            }
    stateStrings(node.getStateSet(), field, out);
    if (field == F::IMPORTER_SEMANTICS || field == F::ANY)
        if (const Feature* f = Feature::get(node))
            if (!f->getSourceType().empty()) out.push_back(f->getSourceType());
    return out;
}

FeatureClassifier::FeatureClassifier(ClassificationRuleSet* rules)
    : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN),
      _rules(rules ? rules : ClassificationRuleSet::createDefault().get())
{
    setNodeMaskOverride(~0u);
}

void FeatureClassifier::apply(osg::Node& node)
{
    if (Feature* f = Feature::get(node))
    {
        _units.push_back({&node, getNodePath(), f, false});
        ++_insideFeature;
        traverse(node);
        --_insideFeature;
        return;
    }
    if (_insideFeature == 0 && node.asDrawable())
    {
        _units.push_back({&node, getNodePath(), nullptr, false});
        return;
    }
    traverse(node);
}

int FeatureClassifier::matchLevel(const std::vector<const osg::Node*>& nodes) const
{
    const auto& rules = _rules->getRules();
    for (std::size_t r = 0; r < rules.size(); ++r)
    {
        const ClassificationRule& rule = *rules[r];
        for (const osg::Node* n : nodes)
        {
            for (const std::string& s : strings(*n, rule.getField(), rule.getUserValueKey()))
                if (rule.matches(s)) return static_cast<int>(r);
        }
    }
    return -1;
}

FeatureClassifier::Report FeatureClassifier::classify(osg::Node& root)
{
    _rules->validate();
    Report report;
    report.perRule.assign(_rules->getRules().size(), 0);
    _units.clear();
    _insideFeature = 0;
    root.accept(*this);
    report.units = static_cast<unsigned>(_units.size());

    // Earlier runs' rule and appearance results are recomputed with this rule set.
    for (Unit& u : _units)
        if (u.feature &&
            (u.feature->getSource() == Feature::RULE || u.feature->getSource() == Feature::APPEARANCE))
        {
            u.feature->setType(FeatureType::Generic);
            u.feature->setSubType("");
            u.feature->setSource(Feature::UNCLASSIFIED);
        }
    for (Unit& u : _units)
        if (!u.feature)
        {
            u.feature = new Feature(0, FeatureType::Generic, "", Feature::UNCLASSIFIED);
            u.created = true;
        }

    // Rules, level by level (the unit and its subtree first, then each ancestor), cached per
    // ancestor because many units share them.
    std::map<const osg::Node*, int> ancestorMatch;
    for (Unit& u : _units)
    {
        Feature& f = *u.feature;
        const Feature::Source src = f.getSource();
        const bool classified = src == Feature::MODEL_DATA || src == Feature::USER;
        if (src == Feature::USER || (classified && !_rules->getOverrideModelData()))
        {
            ++report.keptModelData;
            continue;
        }
        SubtreeNodes sub;
        u.node->accept(sub);
        int match = matchLevel(sub.nodes);
        for (std::size_t k = u.path.size() - 1; match < 0 && k-- > 0;)
        {
            const osg::Node* a = u.path[k];
            auto it = ancestorMatch.find(a);
            if (it == ancestorMatch.end()) it = ancestorMatch.emplace(a, matchLevel({a})).first;
            match = it->second;
        }
        if (match >= 0)
        {
            const ClassificationRule& rule = *_rules->getRules()[static_cast<std::size_t>(match)];
            f.setType(rule.getType());
            f.setSubType(rule.getSubType());
            f.setSource(Feature::RULE);
            ++report.byRule;
            ++report.perRule[static_cast<std::size_t>(match)];
        }
        else if (classified)
            ++report.keptModelData; // overriding found no rule: the model data stands
    }

    if (_rules->getUseAppearance()) classifyByAppearance(report);
    for (const Unit& u : _units)
        if (u.feature->getSource() == Feature::UNCLASSIFIED) ++report.unclassified;

    mergeDrawableFeatures(report);

    FeatureIndex index(root);
    index.numberUnnumbered();
    // Nodes the classifier named while ids were still 0 get their final names.
    for (const FeatureIndex::Entry& e : index.entries())
    {
        osg::ref_ptr<osg::Node> n;
        if (e.node.lock(n) && n->getName().size() > 2 &&
            n->getName().compare(n->getName().size() - 2, 2, "_0") == 0 &&
            n->getName() == osg::ref_ptr<Feature>(new Feature(0, e.feature->getType()))->defaultNodeName())
            n->setName(e.feature->defaultNodeName());
    }
    index.updateBounds();
    _units.clear();
    return report;
}

void FeatureClassifier::classifyByAppearance(Report& report)
{
    // Distinct appearances (units sharing a texture key share one), then single-linkage groups
    // of appearances closer than the threshold.
    std::vector<Appearance> looks;
    std::map<std::string, std::size_t> byKey;
    std::vector<long> unitLook(_units.size(), -1);
    bool anyUnknown = false;
    for (const Unit& u : _units)
        anyUnknown |= u.feature->getSource() == Feature::UNCLASSIFIED;
    if (!anyUnknown) return;
    for (std::size_t i = 0; i < _units.size(); ++i)
    {
        Appearance a = Appearance::of(*_units[i].node, _units[i].path);
        if (!a.valid()) continue;
        std::string key = a.textureKey;
        if (key.empty())
        {
            std::ostringstream s;
            for (const auto& c : a.dominant)
                s << static_cast<int>(c.lab.x() * 4) << ',' << static_cast<int>(c.lab.y() * 4) << ','
                  << static_cast<int>(c.lab.z() * 4) << ':' << static_cast<int>(c.weight * 64) << ';';
            key = s.str();
        }
        auto it = byKey.find(key);
        if (it == byKey.end())
        {
            it = byKey.emplace(key, looks.size()).first;
            looks.push_back(a);
        }
        unitLook[i] = static_cast<long>(it->second);
    }
    UnionFind uf(looks.size());
    const float threshold = _rules->getAppearanceThreshold();
    for (std::size_t a = 0; a < looks.size(); ++a)
        for (std::size_t b = a + 1; b < looks.size(); ++b)
            if (Appearance::distance(looks[a], looks[b]) <= threshold) uf.unite(a, b);

    struct Vote
    {
        std::set<FeatureType> types;
        std::set<std::string> subTypes;
    };
    std::map<std::size_t, Vote> votes;
    std::set<std::size_t> groups;
    for (std::size_t i = 0; i < _units.size(); ++i)
    {
        if (unitLook[i] < 0) continue;
        const std::size_t g = uf.find(static_cast<std::size_t>(unitLook[i]));
        groups.insert(g);
        const Feature& f = *_units[i].feature;
        if (f.getSource() != Feature::UNCLASSIFIED && f.getType() != FeatureType::Generic)
        {
            votes[g].types.insert(f.getType());
            votes[g].subTypes.insert(f.getSubType());
        }
    }
    report.appearanceGroups = static_cast<unsigned>(groups.size());
    for (std::size_t i = 0; i < _units.size(); ++i)
    {
        Feature& f = *_units[i].feature;
        if (unitLook[i] < 0 || f.getSource() != Feature::UNCLASSIFIED) continue;
        auto it = votes.find(uf.find(static_cast<std::size_t>(unitLook[i])));
        if (it == votes.end()) continue;
        if (it->second.types.size() != 1)
        {
            ++report.appearanceConflicts;
            continue;
        }
        f.setType(*it->second.types.begin());
        f.setSubType(it->second.subTypes.size() == 1 ? *it->second.subTypes.begin() : std::string());
        f.setSource(Feature::APPEARANCE);
        ++report.byAppearance;
    }
}

void FeatureClassifier::mergeDrawableFeatures(Report& report)
{
    // Created features of drawables, grouped by their Geode.
    std::map<osg::Geode*, std::vector<std::size_t>> byGeode;
    for (std::size_t i = 0; i < _units.size(); ++i)
    {
        const Unit& u = _units[i];
        if (!u.created) continue;
        osg::Geode* geode = u.path.size() >= 2 ? u.path[u.path.size() - 2]->asGeode() : nullptr;
        if (geode && !Feature::get(*geode))
            byGeode[geode].push_back(i);
        else
        {
            Feature::attach(*u.node, u.feature.get());
            ++report.featuresCreated;
        }
    }
    for (auto& kv : byGeode)
    {
        osg::Geode* geode = kv.first;
        const std::vector<std::size_t>& members = kv.second;
        const Feature& first = *_units[members.front()].feature;
        bool same = members.size() == geode->getNumChildren();
        for (std::size_t i : members)
        {
            const Feature& f = *_units[i].feature;
            same = same && f.getType() == first.getType() && f.getSubType() == first.getSubType() &&
                   f.getSource() == first.getSource();
        }
        if (same)
        {
            Feature::attach(*geode, _units[members.front()].feature.get());
            ++report.featuresCreated;
            report.featuresMerged += static_cast<unsigned>(members.size() - 1);
        }
        else
            for (std::size_t i : members)
            {
                Feature::attach(*_units[i].node, _units[i].feature.get());
                ++report.featuresCreated;
            }
    }
}

std::string FeatureClassifier::Report::summary() const
{
    std::ostringstream s;
    s << units << " units: " << keptModelData << " kept from the model data, " << byRule << " by rules, "
      << byAppearance << " by appearance (" << appearanceGroups << " groups, " << appearanceConflicts
      << " left generic by conflicting groups), " << unclassified << " unclassified; " << featuresCreated
      << " features created (" << featuresMerged << " drawables merged into their Geode's feature)";
    return s.str();
}

} // namespace osgLoA
