#include <osgLoA/semantics/Appearance>

#include <osg/Array>
#include <osg/Geometry>
#include <osg/Material>
#include <osg/NodeVisitor>
#include <osg/Texture>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <set>

namespace osgLoA
{

namespace
{
float linearize(float c)
{
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

float labF(float t)
{
    const float d = 6.0f / 29.0f;
    return t > d * d * d ? std::cbrt(t) : t / (3.0f * d * d) + 4.0f / 29.0f;
}

// State that decides what geometry looks like: the unit-0 texture image and the material.
struct LookState
{
    const osg::Image* image = nullptr;
    bool hasMaterial = false;
    osg::Vec4 diffuse;

    void merge(const osg::StateSet* ss)
    {
        if (!ss) return;
        if (const osg::Texture* t =
                dynamic_cast<const osg::Texture*>(ss->getTextureAttribute(0, osg::StateAttribute::TEXTURE)))
            if (t->getNumImages() > 0 && t->getImage(0)) image = t->getImage(0);
        if (const osg::Material* m =
                dynamic_cast<const osg::Material*>(ss->getAttribute(osg::StateAttribute::MATERIAL)))
        {
            hasMaterial = true;
            diffuse = m->getDiffuse(osg::Material::FRONT);
        }
    }
};

std::string imageKey(const osg::Image* image)
{
    if (!image->getFileName().empty()) return image->getFileName();
    if (!image->getName().empty()) return "name:" + image->getName();
    return "image@" + std::to_string(reinterpret_cast<std::uintptr_t>(image));
}

// Merges colours closer than 5 Delta E, keeps the three heaviest, normalizes the weights.
std::vector<Appearance::Colour> reduce(std::vector<Appearance::Colour> c)
{
    std::sort(c.begin(), c.end(), [](const auto& a, const auto& b) { return a.weight > b.weight; });
    std::vector<Appearance::Colour> out;
    for (const auto& x : c)
    {
        bool merged = false;
        for (auto& o : out)
            if ((o.lab - x.lab).length() < 5.0f)
            {
                o.lab = (o.lab * o.weight + x.lab * x.weight) / (o.weight + x.weight);
                o.rgb = (o.rgb * o.weight + x.rgb * x.weight) / (o.weight + x.weight);
                o.weight += x.weight;
                merged = true;
                break;
            }
        if (!merged) out.push_back(x);
    }
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.weight > b.weight; });
    if (out.size() > 3) out.resize(3);
    float sum = 0.0f;
    for (const auto& o : out)
        sum += o.weight;
    if (sum <= 0.0f) return {};
    for (auto& o : out)
        o.weight /= sum;
    return out;
}

class Gather : public osg::NodeVisitor
{
public:
    Gather(const LookState& inherited) : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN)
    {
        _stack.push_back(inherited);
    }

    void apply(osg::Node& node) override
    {
        LookState s = _stack.back();
        s.merge(node.getStateSet());
        _stack.push_back(s);
        if (osg::Geometry* g = node.asGeometry()) add(*g, s);
        traverse(node);
        _stack.pop_back();
    }

    void add(const osg::Geometry& g, const LookState& s)
    {
        const osg::Array* v = g.getVertexArray();
        const float w = v ? static_cast<float>(v->getNumElements()) : 0.0f;
        if (w <= 0.0f) return;
        std::vector<Appearance::Colour> colours;
        if (s.image)
        {
            colours = dominantOf(*s.image);
            if (!colours.empty()) images.insert(imageKey(s.image));
            if (s.hasMaterial)
                for (auto& c : colours)
                {
                    // Texels are modulated by the diffuse colour (as OSG's MODULATE texture
                    // environment does with lit geometry).
                    c.rgb = osg::Vec3(c.rgb.x() * s.diffuse.r(), c.rgb.y() * s.diffuse.g(),
                                      c.rgb.z() * s.diffuse.b());
                    c.lab = Appearance::srgbToLab(c.rgb);
                }
        }
        else if (s.hasMaterial)
        {
            const osg::Vec3 rgb(s.diffuse.r(), s.diffuse.g(), s.diffuse.b());
            colours.push_back({Appearance::srgbToLab(rgb), 1.0f, rgb});
            untextured = true;
        }
        else if (const osg::Vec4Array* ca = dynamic_cast<const osg::Vec4Array*>(g.getColorArray()))
        {
            if (!ca->empty())
            {
                osg::Vec3 m;
                for (const auto& c : *ca)
                    m += osg::Vec3(c.r(), c.g(), c.b());
                m /= static_cast<float>(ca->size());
                colours.push_back({Appearance::srgbToLab(m), 1.0f, m});
                untextured = true;
            }
        }
        for (auto& c : colours)
        {
            c.weight *= w;
            all.push_back(c);
        }
    }

    static std::vector<Appearance::Colour> dominantOf(const osg::Image& image)
    {
        static std::mutex m;
        static std::map<std::pair<const osg::Image*, unsigned>, std::vector<Appearance::Colour>> cache;
        std::lock_guard<std::mutex> lock(m);
        const auto key = std::make_pair(&image, image.getModifiedCount());
        auto it = cache.find(key);
        if (it != cache.end()) return it->second;
        auto d = Appearance::dominantColours(image);
        cache[key] = d;
        return d;
    }

    std::vector<LookState> _stack;
    std::vector<Appearance::Colour> all;
    std::set<std::string> images;
    bool untextured = false;
};
} // namespace

osg::Vec3 Appearance::srgbToLab(const osg::Vec3& rgb)
{
    const float r = linearize(std::clamp(rgb.x(), 0.0f, 1.0f)),
                g = linearize(std::clamp(rgb.y(), 0.0f, 1.0f)),
                b = linearize(std::clamp(rgb.z(), 0.0f, 1.0f));
    const float x = (0.4124f * r + 0.3576f * g + 0.1805f * b) / 0.95047f;
    const float y = 0.2126f * r + 0.7152f * g + 0.0722f * b;
    const float z = (0.0193f * r + 0.1192f * g + 0.9505f * b) / 1.08883f;
    const float fx = labF(x), fy = labF(y), fz = labF(z);
    return osg::Vec3(116.0f * fy - 16.0f, 500.0f * (fx - fy), 200.0f * (fy - fz));
}

std::vector<Appearance::Colour> Appearance::dominantColours(const osg::Image& image)
{
    const int w = image.s(), h = image.t();
    if (!image.data() || w <= 0 || h <= 0 || image.isCompressed()) return {};
    const int stepS = std::max(1, w / 64), stepT = std::max(1, h / 64);
    struct Bin
    {
        osg::Vec3 sum;
        unsigned n = 0;
    };
    std::map<int, Bin> bins;
    unsigned total = 0;
    for (int t = 0; t < h; t += stepT)
        for (int s = 0; s < w; s += stepS)
        {
            const osg::Vec4 c = image.getColor(s, t);
            if (c.a() < 0.5f && image.isImageTranslucent()) continue; // cut-out texels do not show
            auto q = [](float v) { return std::clamp(static_cast<int>(v * 16.0f), 0, 15); };
            Bin& b = bins[(q(c.r()) << 8) | (q(c.g()) << 4) | q(c.b())];
            b.sum += osg::Vec3(c.r(), c.g(), c.b());
            ++b.n;
            ++total;
        }
    if (total == 0) return {};
    std::vector<Colour> colours;
    for (const auto& kv : bins)
    {
        const osg::Vec3 rgb = kv.second.sum / static_cast<float>(kv.second.n);
        colours.push_back({srgbToLab(rgb), static_cast<float>(kv.second.n) / static_cast<float>(total), rgb});
    }
    return reduce(colours);
}

Appearance Appearance::of(osg::Node& node, const osg::NodePath& path)
{
    LookState inherited;
    for (osg::Node* n : path)
        if (n != &node) inherited.merge(n->getStateSet());
    Gather g(inherited);
    node.accept(g);
    Appearance a;
    a.dominant = reduce(g.all);
    if (g.images.size() == 1 && !g.untextured) a.textureKey = *g.images.begin();
    return a;
}

float Appearance::distance(const Appearance& a, const Appearance& b)
{
    if (!a.valid() || !b.valid()) return std::numeric_limits<float>::infinity();
    if (!a.textureKey.empty() && a.textureKey == b.textureKey) return 0.0f;
    auto directed = [](const Appearance& x, const Appearance& y)
    {
        float d = 0.0f;
        for (const Colour& c : x.dominant)
        {
            float best = std::numeric_limits<float>::max();
            for (const Colour& o : y.dominant)
                best = std::min(best, (c.lab - o.lab).length());
            d += c.weight * best;
        }
        return d;
    };
    return std::max(directed(a, b), directed(b, a));
}

} // namespace osgLoA
