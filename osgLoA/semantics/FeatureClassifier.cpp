#include <osgLoA/semantics/Appearance>
#include <osgLoA/semantics/FeatureClassifier>
#include <osgLoA/semantics/FeatureIndex>

#include <osg/ComputeBoundsVisitor>
#include <osg/Geode>
#include <osg/Material>
#include <osg/PagedLOD>
#include <osg/ProxyNode>
#include <osg/Texture>
#include <osg/Transform>
#include <osg/UserDataContainer>
#include <osg/ValueObject>
#include <osgDB/FileNameUtils>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <map>
#include <numeric>
#include <set>
#include <sstream>
#include <tuple>

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

/** "ground_z=12.5", "height = 30": data an exporter put into a description, not a name. ANY
 *  leaves such strings out (a NODE_DESCRIPTION rule still sees them). */
bool isKeyValue(const std::string& s)
{
    std::size_t i = s.find_first_not_of(" \t");
    if (i == std::string::npos || !(std::isalpha(static_cast<unsigned char>(s[i])) || s[i] == '_'))
        return false;
    while (i < s.size() && (std::isalnum(static_cast<unsigned char>(s[i])) || std::strchr("_.:-", s[i])))
        ++i;
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t'))
        ++i;
    return i < s.size() && s[i] == '=';
}

/** Whether path[k] is the scene root, a node that stands for a file (ProxyNode, PagedLOD), or
 *  the top of a loaded file: its name says what the file is (a street circuit, a city), not
 *  what each object in it is. */
bool isFileLevel(const osg::NodePath& path, std::size_t k)
{
    if (k == 0) return true;
    if (dynamic_cast<const osg::ProxyNode*>(path[k]) || dynamic_cast<const osg::PagedLOD*>(path[k]))
        return true;
    const osg::Node* parent = path[k - 1];
    if (dynamic_cast<const osg::ProxyNode*>(parent) || dynamic_cast<const osg::PagedLOD*>(parent))
        return true;
    if (std::strcmp(parent->libraryName(), "osgLoA") == 0 && std::strcmp(parent->className(), "LoANode") == 0)
        return true;
    const std::string& name = path[k]->getName();
    if (name.find('/') != std::string::npos || name.find('\\') != std::string::npos) return true;
    static const std::set<std::string> kModelExtensions = {
        "3dc",     "3ds", "ac",  "blend", "bvh", "bz2",  "citygml", "dae",  "dxf",  "fbx",
        "flt",     "gml", "glb", "gltf",  "iv",  "ive",  "json",    "kml",  "kmz",  "loa",
        "loacity", "lwo", "lws", "md2",   "obj", "osg",  "osgb",    "osgt", "osgx", "osm",
        "pbf",     "ply", "shp", "stl",   "txp", "vrml", "wrl",     "x",    "xml",  "zip"};
    return kModelExtensions.count(osgDB::getLowerCaseFileExtension(name)) > 0;
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
            if (field == F::NODE_DESCRIPTION || !isKeyValue(d)) out.push_back(d);
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

osg::NodePath FeatureClassifier::pathOf(const Unit& u) const
{
    osg::NodePath path;
    for (long e = u.pathEnd; e >= 0; e = _pathTree[static_cast<std::size_t>(e)].second)
        path.push_back(_pathTree[static_cast<std::size_t>(e)].first);
    std::reverse(path.begin(), path.end());
    return path;
}

void FeatureClassifier::apply(osg::Node& node)
{
    const long entry = static_cast<long>(_pathTree.size());
    _pathTree.emplace_back(&node, _pathStack.empty() ? -1L : _pathStack.back());
    _pathStack.push_back(entry);
    if (Feature* f = Feature::get(node))
    {
        _units.push_back({&node, entry, f, false});
        ++_insideFeature;
        traverse(node);
        --_insideFeature;
    }
    else if (_insideFeature == 0 && node.asDrawable())
        _units.push_back({&node, entry, nullptr, false});
    else
        traverse(node);
    _pathStack.pop_back();
}

int FeatureClassifier::matchLevel(const std::vector<const osg::Node*>& nodes, bool ancestor,
                                  bool overridingOnly) const
{
    const auto& rules = _rules->getRules();
    for (std::size_t r = 0; r < rules.size(); ++r)
    {
        const ClassificationRule& rule = *rules[r];
        if (ancestor && !rule.getInheritable()) continue;
        if (overridingOnly && !rule.getOverridesModelData()) continue;
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
    _pathTree.clear();
    _pathStack.clear();
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

    // Rules, level by level (the unit and its subtree first, then each ancestor but the root
    // and file-level groups, with inheritable rules only), cached per ancestor because many
    // units share them. A type from the model data is replaced only by rules that override
    // model data (all rules when the set overrides).
    bool anyOverriding = false;
    for (const auto& r : _rules->getRules())
        anyOverriding = anyOverriding || r->getOverridesModelData();
    std::map<std::pair<const osg::Node*, bool>, int> ancestorMatch;
    for (Unit& u : _units)
    {
        Feature& f = *u.feature;
        const Feature::Source src = f.getSource();
        const bool classified = src == Feature::MODEL_DATA || src == Feature::USER;
        const bool overridingOnly = classified && !_rules->getOverrideModelData();
        if (src == Feature::USER || (overridingOnly && !anyOverriding))
        {
            ++report.keptModelData;
            continue;
        }
        // The unit's own level: its subtree, and for a drawable its Geode (which holds the
        // drawable's name and state as often as the drawable does).
        SubtreeNodes sub;
        u.node->accept(sub);
        const osg::NodePath path = pathOf(u);
        std::size_t firstAncestor = path.size() - 1;
        if (u.node->asDrawable() && firstAncestor > 0 && path[firstAncestor - 1]->asGeode())
            sub.nodes.push_back(path[--firstAncestor]);
        int match = matchLevel(sub.nodes, false, overridingOnly);
        for (std::size_t k = firstAncestor; match < 0 && k-- > 0;)
        {
            if (isFileLevel(path, k)) continue;
            const osg::Node* a = path[k];
            const auto key = std::make_pair(a, overridingOnly);
            auto it = ancestorMatch.find(key);
            if (it == ancestorMatch.end())
                it = ancestorMatch.emplace(key, matchLevel({a}, true, overridingOnly)).first;
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

    attachObjectFeatures(report);

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
    _pathTree.clear();
    _pathTree.shrink_to_fit();
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
        Appearance a = Appearance::of(*_units[i].node, pathOf(_units[i]));
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

namespace
{
/** Whether a transform holds geometry only: no transform and no model feature below it. */
class GeometryOnly : public osg::NodeVisitor
{
public:
    GeometryOnly() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) { setNodeMaskOverride(~0u); }
    bool only = true;
    void apply(osg::Node& n) override
    {
        if (!only) return;
        if (Feature::get(n))
        {
            only = false;
            return;
        }
        traverse(n);
    }
    void apply(osg::Transform&) override { only = false; }
};

osg::BoundingBoxd worldBox(osg::Node& node, const osg::NodePath& path)
{
    osg::ComputeBoundsVisitor cbv;
    cbv.setNodeMaskOverride(~0u);
    osg::Matrix toWorld = osg::computeLocalToWorld(osg::NodePath(path.begin(), path.end() - 1));
    cbv.pushMatrix(toWorld);
    node.accept(cbv);
    const osg::BoundingBox& b = cbv.getBoundingBox();
    osg::BoundingBoxd out;
    if (b.valid()) out.set(osg::Vec3d(b._min), osg::Vec3d(b._max));
    return out;
}

/** What a piece looks like, for the touching merge: the base texture's image (file name, else
 *  the image itself) of the nearest state that sets one, else the nearest material's diffuse
 *  colour, else "". */
std::string lookOf(const osg::Node& node, const osg::NodePath& path)
{
    std::vector<const osg::Node*> chain(path.begin(), path.end() - 1);
    chain.push_back(&node);
    for (auto it = chain.rbegin(); it != chain.rend(); ++it)
        if (const osg::StateSet* ss = (*it)->getStateSet())
            if (const osg::Texture* t = dynamic_cast<const osg::Texture*>(
                    ss->getTextureAttribute(0, osg::StateAttribute::TEXTURE)))
                if (const osg::Image* img = t->getImage(0))
                {
                    if (!img->getFileName().empty()) return "texture:" + img->getFileName();
                    std::ostringstream s;
                    s << "image:" << static_cast<const void*>(img);
                    return s.str();
                }
    for (auto it = chain.rbegin(); it != chain.rend(); ++it)
        if (const osg::StateSet* ss = (*it)->getStateSet())
            if (const osg::Material* m =
                    dynamic_cast<const osg::Material*>(ss->getAttribute(osg::StateAttribute::MATERIAL)))
            {
                const osg::Vec4& d = m->getDiffuse(osg::Material::FRONT);
                std::ostringstream s;
                s << "material:" << d.r() << "," << d.g() << "," << d.b() << "," << d.a();
                return s.str();
            }
    return std::string();
}

bool isCarrierNode(const osg::Node* n)
{
    return n->asGeode() || n->asTransform();
}
} // namespace

void FeatureClassifier::attachObjectFeatures(Report& report)
{
    // 1. Objects: each created unit's object node (the innermost transform below the root, when
    //    it holds geometry only and grouping is on; else the unit's Geode), and one group of
    //    units per (object, type, sub-type).
    std::map<const osg::Node*, bool> geometryOnly;
    auto transformObjectOf = [&](const Unit& u) -> osg::Node*
    {
        if (!_rules->getGroupObjects()) return nullptr;
        const osg::NodePath path = pathOf(u);
        for (std::size_t k = path.size() - 1; k-- > 0;)
        {
            osg::Transform* t = path[k]->asTransform();
            if (!t) continue;
            if (isFileLevel(path, k)) return nullptr; // the scene or a file is no object
            auto it = geometryOnly.find(t);
            if (it == geometryOnly.end())
            {
                GeometryOnly g;
                for (unsigned c = 0; c < t->getNumChildren(); ++c)
                    t->getChild(c)->accept(g);
                it = geometryOnly.emplace(t, g.only).first;
            }
            return it->second ? t : nullptr; // only the innermost transform can be the object
        }
        return nullptr;
    };
    auto geodeOf = [this](const Unit& u) -> osg::Geode*
    {
        // The parent entry of the unit's node.
        const long parent = u.pathEnd >= 0 ? _pathTree[static_cast<std::size_t>(u.pathEnd)].second : -1;
        osg::Geode* g = parent >= 0 ? _pathTree[static_cast<std::size_t>(parent)].first->asGeode() : nullptr;
        return g && !Feature::get(*g) ? g : nullptr;
    };

    typedef std::tuple<const osg::Node*, FeatureType, std::string> Key;
    std::map<Key, std::size_t> groupOf;
    std::vector<std::vector<std::size_t>> groups;
    std::vector<bool> inTransform;
    for (std::size_t i = 0; i < _units.size(); ++i)
    {
        const Unit& u = _units[i];
        if (!u.created) continue;
        const osg::Node* object = transformObjectOf(u);
        const bool transformObject = object != nullptr;
        if (!object) object = geodeOf(u) ? static_cast<const osg::Node*>(geodeOf(u)) : u.node.get();
        const Key key(object, u.feature->getType(), u.feature->getSubType());
        auto it = groupOf.find(key);
        if (it == groupOf.end())
        {
            it = groupOf.emplace(key, groups.size()).first;
            groups.emplace_back();
            inTransform.push_back(transformObject);
        }
        groups[it->second].push_back(i);
    }

    // 2. Touching pieces of a merge type outside transform objects that look alike are one
    //    object (the walls and roof of a house): single linkage over world boxes, swept along x.
    UnionFind uf(groups.size());
    const std::vector<FeatureType> mergeTypes = _rules->mergeTouchingTypeList();
    if (_rules->getGroupObjects() && !mergeTypes.empty())
    {
        const double tol = _rules->getMergeTolerance();
        struct Box
        {
            osg::BoundingBoxd box;
            std::size_t group;
        };
        // Per type and look: pieces of one object share their texture or material (the walls
        // and roof of a tower share its texture atlas; a landmark beside a row of houses does
        // not look like them).
        std::map<std::pair<FeatureType, std::string>, std::vector<Box>> byType;
        for (std::size_t g = 0; g < groups.size(); ++g)
        {
            const Unit& first = _units[groups[g].front()];
            const FeatureType type = first.feature->getType();
            if (inTransform[g] || std::find(mergeTypes.begin(), mergeTypes.end(), type) == mergeTypes.end())
                continue;
            osg::BoundingBoxd box;
            for (std::size_t i : groups[g])
                box.expandBy(worldBox(*_units[i].node, pathOf(_units[i])));
            if (box.valid())
                byType[std::make_pair(type, lookOf(*first.node, pathOf(first)))].push_back({box, g});
        }
        for (auto& kv : byType)
        {
            std::vector<Box>& boxes = kv.second;
            std::sort(boxes.begin(), boxes.end(),
                      [](const Box& a, const Box& b) { return a.box.xMin() < b.box.xMin(); });
            for (std::size_t a = 0; a < boxes.size(); ++a)
                for (std::size_t b = a + 1;
                     b < boxes.size() && boxes[b].box.xMin() <= boxes[a].box.xMax() + tol; ++b)
                {
                    const osg::BoundingBoxd& p = boxes[a].box;
                    const osg::BoundingBoxd& q = boxes[b].box;
                    if (p.yMin() <= q.yMax() + tol && q.yMin() <= p.yMax() + tol &&
                        p.zMin() <= q.zMax() + tol && q.zMin() <= p.zMax() + tol)
                        uf.unite(boxes[a].group, boxes[b].group);
                }
        }
    }
    std::map<std::size_t, std::vector<std::size_t>> objects; // representative group -> units
    for (std::size_t g = 0; g < groups.size(); ++g)
    {
        std::vector<std::size_t>& units = objects[uf.find(g)];
        units.insert(units.end(), groups[g].begin(), groups[g].end());
    }

    // 3. One Feature per object, on the fewest nodes that carry exactly its geometry: its
    //    outermost Geode or transform holding nothing else, else each whole Geode, else each
    //    drawable (one Feature then sits on several nodes; FeatureIndex counts it once).
    std::map<const osg::Node*, std::size_t> unitsBelow; // units (any) under each Geode/transform
    for (const Unit& u : _units)
    {
        const osg::NodePath path = pathOf(u);
        for (std::size_t k = 0; k + 1 < path.size(); ++k)
            if (isCarrierNode(path[k])) ++unitsBelow[path[k]];
    }
    for (const auto& kv : objects)
    {
        const std::vector<std::size_t>& members = kv.second;
        osg::ref_ptr<Feature> feature = _units[members.front()].feature;
        std::set<std::string> subTypes;
        std::map<Feature::Source, unsigned> sources;
        for (std::size_t i : members)
        {
            subTypes.insert(_units[i].feature->getSubType());
            ++sources[_units[i].feature->getSource()];
        }
        if (subTypes.size() > 1) feature->setSubType("");
        feature->setSource(std::max_element(sources.begin(), sources.end(),
                                            [](const std::pair<const Feature::Source, unsigned>& a,
                                               const std::pair<const Feature::Source, unsigned>& b)
                                            { return a.second < b.second; })
                               ->first);
        ++report.featuresCreated;
        report.featuresMerged += unsigned(members.size() - 1);

        std::map<const osg::Node*, std::size_t> count; // members under each Geode/transform
        for (std::size_t i : members)
        {
            const osg::NodePath path = pathOf(_units[i]);
            for (std::size_t k = 0; k + 1 < path.size(); ++k)
                if (isCarrierNode(path[k])) ++count[path[k]];
        }
        const osg::NodePath first = pathOf(_units[members.front()]);
        osg::Node* whole = nullptr;
        for (std::size_t k = 1; k + 1 < first.size() && !whole; ++k)
            if (isCarrierNode(first[k]) && count[first[k]] == members.size() &&
                unitsBelow[first[k]] == members.size() && !Feature::get(*first[k]))
                whole = first[k];
        if (whole)
        {
            Feature::attach(*whole, feature.get());
            continue;
        }
        std::set<osg::Node*> done;
        for (std::size_t i : members)
        {
            osg::Geode* geode = geodeOf(_units[i]);
            osg::Node* carrier = _units[i].node.get();
            if (geode && count[geode] == unitsBelow[geode] && count[geode] == geode->getNumChildren())
                carrier = geode;
            if (done.insert(carrier).second) Feature::attach(*carrier, feature.get());
        }
    }
}

std::string FeatureClassifier::Report::summary() const
{
    std::ostringstream s;
    s << units << " units: " << keptModelData << " kept from the model data, " << byRule << " by rules, "
      << byAppearance << " by appearance (" << appearanceGroups << " groups, " << appearanceConflicts
      << " left generic by conflicting groups), " << unclassified << " unclassified; " << featuresCreated
      << " features created (" << featuresMerged << " units merged into the feature of their object)";
    return s.str();
}

} // namespace osgLoA
