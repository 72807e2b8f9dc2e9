#include <osgLoA/semantics/Feature>
#include <osgLoA/util/SceneStatistics>

#include <osg/Geometry>
#include <osg/NodeVisitor>
#include <osg/Texture>
#include <osg/TriangleFunctor>

#include <set>
#include <sstream>
#include <vector>

namespace osgLoA
{
namespace
{
struct TriangleCounter
{
    unsigned long long count = 0;
    void operator()(const osg::Vec3&, const osg::Vec3&, const osg::Vec3&) { ++count; }
};

class StatisticsVisitor : public osg::NodeVisitor
{
public:
    explicit StatisticsVisitor(SceneStatistics& s) : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN), _s(s) {}

    void apply(osg::Node& node) override
    {
        addStateSet(node.getStateSet());
        const Feature* f = Feature::get(node);
        const bool tagged = f != nullptr;
        if (tagged)
        {
            ++_s.features;
            ++_s.featuresByType[f->getType()];
            if (f->getLandmark()) ++_s.landmarks;
            _typeStack.push_back(f->getType());
        }
        traverse(node);
        if (tagged) _typeStack.pop_back();
    }

    void apply(osg::Drawable& drawable) override
    {
        addStateSet(drawable.getStateSet());
        osg::TriangleFunctor<TriangleCounter> tf;
        drawable.accept(tf);
        ++_s.drawables;
        _s.triangles += tf.count;
        if (!_typeStack.empty()) _s.trianglesByType[_typeStack.back()] += tf.count;
        if (auto* g = drawable.asGeometry())
            if (g->getVertexArray()) _s.vertices += g->getVertexArray()->getNumElements();
    }

    void addStateSet(osg::StateSet* ss)
    {
        if (!ss) return;
        for (unsigned u = 0; u < ss->getTextureAttributeList().size(); ++u)
            if (auto* t = ss->getTextureAttribute(u, osg::StateAttribute::TEXTURE)) _textures.insert(t);
    }

    std::set<const osg::StateAttribute*> _textures;

private:
    SceneStatistics& _s;
    std::vector<FeatureType> _typeStack;
};
} // namespace

SceneStatistics SceneStatistics::collect(osg::Node& scene)
{
    SceneStatistics s;
    StatisticsVisitor v(s);
    scene.accept(v);
    s.textures = static_cast<unsigned>(v._textures.size());
    return s;
}

std::string SceneStatistics::summary() const
{
    std::ostringstream o;
    o << triangles << " triangles in " << drawables << " drawables, " << textures << " textures; " << features
      << " features";
    const char* sep = ": ";
    for (const auto& kv : featuresByType)
    {
        o << sep << kv.second << " " << toString(kv.first);
        sep = ", ";
    }
    if (landmarks) o << " (" << landmarks << " landmarks)";
    return o.str();
}

std::string SceneStatistics::toJson() const
{
    std::ostringstream o;
    o << "{\"triangles\": " << triangles << ", \"vertices\": " << vertices << ", \"drawables\": " << drawables
      << ", \"textures\": " << textures << ", \"features\": " << features << ", \"landmarks\": " << landmarks
      << ", \"features_by_type\": {";
    const char* sep = "";
    for (const auto& kv : featuresByType)
    {
        o << sep << "\"" << toString(kv.first) << "\": " << kv.second;
        sep = ", ";
    }
    o << "}}";
    return o.str();
}

} // namespace osgLoA
