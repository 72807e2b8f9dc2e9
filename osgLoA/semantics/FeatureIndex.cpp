#include <osgLoA/semantics/FeatureIndex>

#include <osg/ComputeBoundsVisitor>
#include <osg/NodeVisitor>
#include <osg/Transform>

#include <algorithm>
#include <set>
#include <sstream>

namespace osgLoA
{

namespace
{
class CollectFeatures : public osg::NodeVisitor
{
public:
    CollectFeatures(std::vector<FeatureIndex::Entry>& out, std::vector<std::pair<osg::Node*, long>>& tree)
        : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN), _out(out), _tree(tree)
    {
        setNodeMaskOverride(~0u);
    }

    void apply(osg::Node& node) override
    {
        const long place = static_cast<long>(_tree.size());
        _tree.emplace_back(&node, _places.empty() ? -1L : _places.back());
        _places.push_back(place);
        Feature* f = Feature::get(node);
        if (f)
        {
            FeatureIndex::Entry e;
            e.feature = f;
            e.node = &node;
            e.pathEnd = place;
            e.parent = _stack.empty() ? -1 : _stack.back();
            _stack.push_back(static_cast<int>(_out.size()));
            _out.push_back(e);
        }
        traverse(node);
        if (f) _stack.pop_back();
        _places.pop_back();
    }

private:
    std::vector<FeatureIndex::Entry>& _out;
    std::vector<std::pair<osg::Node*, long>>& _tree;
    std::vector<int> _stack;
    std::vector<long> _places;
};
} // namespace

void FeatureIndex::build(osg::Node& root)
{
    _entries.clear();
    _pathTree.clear();
    CollectFeatures c(_entries, _pathTree);
    root.accept(c);
}

osg::NodePath FeatureIndex::pathOf(const Entry& entry) const
{
    osg::NodePath path;
    for (long p = entry.pathEnd; p >= 0 && static_cast<std::size_t>(p) < _pathTree.size();
         p = _pathTree[static_cast<std::size_t>(p)].second)
        path.push_back(_pathTree[static_cast<std::size_t>(p)].first);
    std::reverse(path.begin(), path.end());
    return path;
}

const FeatureIndex::Entry* FeatureIndex::find(unsigned id) const
{
    for (const Entry& e : _entries)
        if (e.feature->getId() == id) return &e;
    return nullptr;
}

unsigned FeatureIndex::numberUnnumbered()
{
    unsigned maxId = 0;
    for (const Entry& e : _entries)
        maxId = std::max(maxId, e.feature->getId());
    unsigned n = 0;
    for (Entry& e : _entries)
        if (e.feature->getId() == 0)
        {
            e.feature->setId(++maxId);
            ++n;
        }
    return n;
}

std::vector<unsigned> FeatureIndex::duplicateIds() const
{
    std::map<unsigned, const Feature*> seen; // one Feature on several nodes is no duplicate
    std::set<unsigned> dup;
    for (const Entry& e : _entries)
    {
        auto it = seen.emplace(e.feature->getId(), e.feature.get()).first;
        if (it->second != e.feature.get()) dup.insert(e.feature->getId());
    }
    return std::vector<unsigned>(dup.begin(), dup.end());
}

void FeatureIndex::updateBounds()
{
    // A Feature on several nodes (one object of several pieces) gets the union of their boxes.
    std::map<const Feature*, osg::BoundingBox> boxes;
    for (Entry& e : _entries)
    {
        osg::ref_ptr<osg::Node> node;
        if (!e.node.lock(node)) continue;
        osg::NodePath parentPath = pathOf(e);
        if (!parentPath.empty()) parentPath.pop_back();
        osg::ComputeBoundsVisitor cbv;
        cbv.setNodeMaskOverride(~0u);
        osg::Matrix toWorld = osg::computeLocalToWorld(parentPath);
        cbv.pushMatrix(toWorld);
        node->accept(cbv);
        boxes[e.feature.get()].expandBy(cbv.getBoundingBox());
    }
    for (Entry& e : _entries)
    {
        auto it = boxes.find(e.feature.get());
        if (it != boxes.end()) e.feature->setBound(osg::BoundingBoxf(it->second._min, it->second._max));
    }
}

unsigned FeatureIndex::Counts::get(FeatureType t) const
{
    auto it = byType.find(t);
    return it == byType.end() ? 0u : it->second;
}

std::string FeatureIndex::Counts::toJson() const
{
    std::ostringstream s;
    s << "{";
    for (FeatureType t : kFeatureTypes)
        s << "\"" << toString(t) << "\": " << get(t) << ", ";
    s << "\"landmarks\": " << landmarks << "}";
    return s.str();
}

FeatureIndex::Counts FeatureIndex::counts(bool topLevelOnly) const
{
    Counts c;
    for (FeatureType t : kFeatureTypes)
        c.byType[t] = 0;
    std::set<const Feature*> counted; // one Feature on several nodes counts once
    for (const Entry& e : _entries)
    {
        if (topLevelOnly && e.parent >= 0) continue;
        if (!counted.insert(e.feature.get()).second) continue;
        ++c.byType[e.feature->getType()];
        ++c.total;
        if (e.feature->getLandmark()) ++c.landmarks;
    }
    return c;
}

} // namespace osgLoA
