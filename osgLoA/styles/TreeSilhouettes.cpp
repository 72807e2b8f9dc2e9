// TreeSilhouettes: tree crowns as leaf sprites whose depth steps the compositor outlines
// (Deussen & Strothotte 2000, paper 004 Figure 8C).
#include <osgLoA/semantics/Feature>
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/styles/TreeSilhouettes>

#include "../util/TriangleCollector.h"

#include <osg/Geode>
#include <osg/Image>
#include <osg/NodeVisitor>
#include <osg/Texture>
#include <osg/TriangleIndexFunctor>

#include <algorithm>
#include <cmath>

namespace osgLoA
{

namespace
{
struct TreesRegistrar
{
    TreesRegistrar() { TreeSilhouettes::registerStyle(); }
} s_treesRegistrar;

const char* const kCrownUniform = "loa_treeCrown";

/** Marks crowns: TreeCrown drawables anywhere, textured drawables with alpha inside green
 *  features (the innermost feature decides). */
class CrownMarker : public osg::NodeVisitor
{
public:
    CrownMarker() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
    unsigned marked = 0;

    void apply(osg::Node& n) override
    {
        const Feature* f = Feature::get(n);
        const bool saved = _green;
        if (f) _green = f->getType() == FeatureType::Green;
        pushState(n.getStateSet());
        traverse(n);
        popState(n.getStateSet());
        _green = saved;
    }
    void apply(osg::Drawable& d) override
    {
        const Feature* f = Feature::get(d);
        const bool green = f ? f->getType() == FeatureType::Green : _green;
        pushState(d.getStateSet());
        bool crown = d.getName() == "TreeCrown";
        if (!crown && green && !_textures.empty())
        {
            // The nearest texture on unit 0 decides: a card shows its foliage cut out, so a good
            // share of the texels its triangles cover are translucent.
            const osg::Texture* t = _textures.back();
            const osg::Image* img = t->getNumImages() > 0 ? t->getImage(0) : nullptr;
            const osg::Geometry* g = d.asGeometry();
            crown = img && g && osg::Image::computeNumComponents(img->getPixelFormat()) % 2 == 0 &&
                    translucentShare(*g, *img) >= 0.15;
        }
        // Cards stand: most of their area faces sideways (a park's ground in the same atlas lies
        // flat and is not a crown).
        if (crown && d.getName() != "TreeCrown")
        {
            TriangleCollector triangles(osg::computeLocalToWorld(getNodePath()));
            d.accept(triangles);
            const std::vector<osg::Vec3d>& c = triangles.corners();
            double area = 0.0, up = 0.0;
            osg::BoundingBoxd box;
            for (std::size_t i = 0; i + 2 < c.size(); i += 3)
            {
                const osg::Vec3d n = (c[i + 1] - c[i]) ^ (c[i + 2] - c[i]);
                const double a = n.length();
                area += a;
                up += std::fabs(n.z());
                for (int k = 0; k < 3; ++k)
                    box.expandBy(c[i + std::size_t(k)]);
            }
            // ... and as a tree does, at least half as high as wide (a park's low border or hedge
            // in the same atlas stands too, but is long and low).
            const double wide = std::max(box.xMax() - box.xMin(), box.yMax() - box.yMin());
            crown = area > 0.0 && up < 0.5 * area && box.zMax() - box.zMin() >= 0.5 * wide;
        }
        popState(d.getStateSet());
        if (!crown) return;
        // A StateSet shared with other drawables is copied first: only crowns are marked.
        osg::StateSet* own = d.getStateSet();
        if (own && own->referenceCount() > 1) d.setStateSet(osg::clone(own, osg::CopyOp::SHALLOW_COPY));
        d.getOrCreateStateSet()->addUniform(new osg::Uniform(kCrownUniform, true));
        ++marked;
    }

private:
    /** The share of translucent texels (alpha < 250/255) at 10 points of every triangle (its
     *  corners' texture coordinates, unit 0, wrapped). */
    static double translucentShare(const osg::Geometry& g, const osg::Image& img)
    {
        const osg::Vec2Array* tc = dynamic_cast<const osg::Vec2Array*>(g.getTexCoordArray(0));
        if (!tc || tc->empty() || img.s() < 1 || img.t() < 1 || !img.data()) return 0.0;
        std::vector<unsigned> idx;
        osg::TriangleIndexFunctor<TriangleIndexList> f;
        f.out = &idx;
        const_cast<osg::Geometry&>(g).accept(f);
        long samples = 0, translucent = 0;
        const double w[10][3] = {{1, 0, 0},      {0, 1, 0},     {0, 0, 1},   {1 / 3., 1 / 3., 1 / 3.},
                                 {.5, .5, 0},    {0, .5, .5},   {.5, 0, .5}, {.7, .15, .15},
                                 {.15, .7, .15}, {.15, .15, .7}};
        for (std::size_t i = 0; i + 2 < idx.size(); i += 3)
        {
            if (idx[i] >= tc->size() || idx[i + 1] >= tc->size() || idx[i + 2] >= tc->size()) continue;
            for (const auto& b : w)
            {
                osg::Vec2 uv = (*tc)[idx[i]] * float(b[0]) + (*tc)[idx[i + 1]] * float(b[1]) +
                               (*tc)[idx[i + 2]] * float(b[2]);
                uv = osg::Vec2(uv.x() - std::floor(uv.x()), uv.y() - std::floor(uv.y()));
                const int x = std::min(img.s() - 1, int(uv.x() * float(img.s())));
                const int y = std::min(img.t() - 1, int(uv.y() * float(img.t())));
                ++samples;
                translucent += img.getColor(unsigned(x), unsigned(y)).a() < 250.0f / 255.0f;
            }
        }
        return samples ? double(translucent) / double(samples) : 0.0;
    }

    void pushState(const osg::StateSet* ss)
    {
        const osg::Texture* t =
            ss ? dynamic_cast<const osg::Texture*>(ss->getTextureAttribute(0, osg::StateAttribute::TEXTURE))
               : nullptr;
        if (t) _textures.push_back(t);
        _pushed.push_back(t != nullptr);
    }
    void popState(const osg::StateSet*)
    {
        if (_pushed.back()) _textures.pop_back();
        _pushed.pop_back();
    }
    bool _green = false;
    std::vector<const osg::Texture*> _textures;
    std::vector<bool> _pushed;
};
} // namespace

osg::ref_ptr<GraphicStyle> TreeSilhouettes::create()
{
    osg::ref_ptr<GraphicStyle> s = GraphicStyle::createBuiltin("cartographic");
    s->setName(name());
    s->setDescription("cartographic, with tree crowns drawn as round leaf sprites whose depth steps the "
                      "edges outline: near crowns show inner outlines, far ones their silhouette "
                      "(Deussen & Strothotte 2000)");
    s->setFragmentShader("loa_style_trees.frag.glsl");
    s->setGeometryShader("loa_tree_sprites.geom.glsl");
    osg::StateSet* ss = s->getParameters();
    ss->setName(std::string(name()) + " parameters");
    const Parameters p;
    ss->addUniform(new osg::Uniform("loa_trees_leafRadius", p.leafRadius));
    ss->addUniform(new osg::Uniform("loa_trees_density", p.density));
    ss->addUniform(new osg::Uniform("loa_trees_minPixels", p.minPixels));
    // The edges are the cartographic style's (so that everything but the crowns is drawn as it
    // draws them): they outline the leaves.
    return s;
}

void TreeSilhouettes::registerStyle()
{
    GraphicStyleCatalog::instance().add(*create());
}

unsigned TreeSilhouettes::markCrowns(osg::Node& model)
{
    CrownMarker m;
    model.accept(m);
    return m.marked;
}

bool TreeSilhouettes::isCrown(const osg::Drawable& d)
{
    const osg::StateSet* ss = d.getStateSet();
    const osg::Uniform* u = ss ? ss->getUniform(kCrownUniform) : nullptr;
    bool v = false;
    return u && u->get(v) && v;
}

std::uint32_t TreeSilhouettes::pcg(std::uint32_t x)
{
    x = x * 747796405u + 2891336453u;
    const std::uint32_t w = ((x >> ((x >> 28u) + 4u)) ^ x) * 277803737u;
    return (w >> 22u) ^ w;
}

std::uint32_t TreeSilhouettes::triangleHash(const osg::Vec3d& a, const osg::Vec3d& b, const osg::Vec3d& c)
{
    std::uint32_t h = 0u;
    for (const osg::Vec3d* p : {&a, &b, &c})
    {
        // As GLSL's uint(int): two's complement.
        const auto cm = [](double v) { return std::uint32_t(std::int32_t(std::lround(float(v) * 100.0f))); };
        h += pcg(cm(p->x()) * 73856093u ^ pcg(cm(p->y()) * 19349663u ^ pcg(cm(p->z()) * 83492791u)));
    }
    return pcg(h);
}

double TreeSilhouettes::unit(std::uint32_t h)
{
    return double(h >> 8u) / 16777216.0;
}

int TreeSilhouettes::spriteCount(double area, double density, std::uint32_t hash)
{
    const int n = int(std::floor(area * density + unit(hash)));
    return std::max(0, std::min(n, kMaxSprites));
}

osg::Vec3d TreeSilhouettes::spriteBarycentric(std::uint32_t hash, int k)
{
    const double u0 = unit(pcg(hash ^ 0x9e3779b9u)), v0 = unit(pcg(hash ^ 0x7f4a7c15u));
    double u = u0 + 0.7548776662 * double(k + 1), v = v0 + 0.5698402910 * double(k + 1);
    u -= std::floor(u);
    v -= std::floor(v);
    if (u + v > 1.0)
    {
        u = 1.0 - u;
        v = 1.0 - v;
    }
    return osg::Vec3d(1.0 - u - v, u, v);
}

} // namespace osgLoA
