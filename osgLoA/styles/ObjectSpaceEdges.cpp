// ObjectSpaceEdges: creases, boundaries and silhouettes of generic features' geometry drawn as
// lines (paper 004 §3.2.3 after Döllner & Walther 2003).
#include <osgLoA/semantics/Feature>
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/styles/ObjectSpaceEdges>

#include "../util/TriangleCollector.h"

#include <osg/NodeVisitor>
#include <osg/TriangleIndexFunctor>
#include <osg/ValueObject>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>
#include <vector>

namespace osgLoA
{

namespace
{
struct EdgesRegistrar
{
    EdgesRegistrar() { ObjectSpaceEdges::registerStyle(); }
} s_edgesRegistrar;

const char* const kPreparedValue = "osgLoA.objectEdges";

template <class A>
bool copyAs(const osg::Array& src, const std::vector<unsigned>& idx, osg::ref_ptr<osg::Array>& out)
{
    const A* a = dynamic_cast<const A*>(&src);
    if (!a) return false;
    osg::ref_ptr<A> r = new A;
    r->reserve(idx.size());
    for (unsigned i : idx)
        r->push_back((*a)[i]);
    r->setBinding(src.getBinding());
    r->setNormalize(src.getNormalize());
    out = r;
    return true;
}

/** The array with its elements at idx, in that order; null for a type not handled. */
osg::ref_ptr<osg::Array> deindexed(const osg::Array& src, const std::vector<unsigned>& idx)
{
    osg::ref_ptr<osg::Array> out;
    copyAs<osg::Vec3Array>(src, idx, out) || copyAs<osg::Vec2Array>(src, idx, out) ||
        copyAs<osg::Vec4Array>(src, idx, out) || copyAs<osg::Vec4ubArray>(src, idx, out) ||
        copyAs<osg::FloatArray>(src, idx, out) || copyAs<osg::Vec3dArray>(src, idx, out) ||
        copyAs<osg::Vec2dArray>(src, idx, out) || copyAs<osg::Vec4dArray>(src, idx, out) ||
        copyAs<osg::Vec3ubArray>(src, idx, out) || copyAs<osg::Vec2ubArray>(src, idx, out) ||
        copyAs<osg::Vec3sArray>(src, idx, out);
    return out;
}

bool perVertex(const osg::Array* a)
{
    return a && a->getBinding() == osg::Array::BIND_PER_VERTEX;
}

class GenericGeometry : public osg::NodeVisitor
{
public:
    explicit GenericGeometry(ObjectSpaceEdges::Report& r) : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN), report(r)
    {
    }
    ObjectSpaceEdges::Report& report;
    void apply(osg::Node& n) override
    {
        const bool saved = _generic;
        if (const Feature* f = Feature::get(n)) _generic = f->getType() == FeatureType::Generic;
        traverse(n);
        _generic = saved;
    }
    void apply(osg::Geometry& g) override
    {
        const Feature* f = Feature::get(g);
        if (!(f ? f->getType() == FeatureType::Generic : _generic)) return;
        if (!ObjectSpaceEdges::prepareGeometry(g, report))
        {
            ++report.skipped;
            OSG_WARN << "osgLoA: object-edges: geometry '" << g.getName()
                     << "' has an array type that cannot be rewritten; it draws without object-space edges"
                     << std::endl;
        }
    }

private:
    bool _generic = false;
};
} // namespace

osg::ref_ptr<GraphicStyle> ObjectSpaceEdges::create()
{
    osg::ref_ptr<GraphicStyle> s = GraphicStyle::createBuiltin("cartographic");
    s->setName(name());
    s->setDescription("cartographic, with the creases, boundaries and silhouettes of generic features' "
                      "geometry drawn as lines (object-space edges, combined with the image-space ones)");
    s->setFragmentShader("loa_style_object_edges.frag.glsl");
    s->setGeometryShader("loa_object_edges.geom.glsl");
    osg::StateSet* ss = s->getParameters();
    ss->setName(std::string(name()) + " parameters");
    const Parameters p;
    ss->addUniform(new osg::Uniform("loa_objectEdges_width", p.width));
    ss->addUniform(new osg::Uniform("loa_objectEdges_creaseDegrees", p.creaseDegrees));
    ss->addUniform(new osg::Uniform("loa_objectEdges_color", p.color));
    return s;
}

void ObjectSpaceEdges::registerStyle()
{
    GraphicStyleCatalog::instance().add(*create());
}

osg::Vec2f ObjectSpaceEdges::octEncode(const osg::Vec3f& v)
{
    const float l1 = std::fabs(v.x()) + std::fabs(v.y()) + std::fabs(v.z());
    if (!(l1 > 0.0f)) return osg::Vec2f(0.0f, 0.0f);
    osg::Vec2f e(v.x() / l1, v.y() / l1);
    if (v.z() < 0.0f)
    {
        const float sx = e.x() >= 0.0f ? 1.0f : -1.0f, sy = e.y() >= 0.0f ? 1.0f : -1.0f;
        e = osg::Vec2f((1.0f - std::fabs(e.y())) * sx, (1.0f - std::fabs(e.x())) * sy);
    }
    return e;
}

osg::Vec3f ObjectSpaceEdges::octDecode(const osg::Vec2f& e)
{
    osg::Vec3f n(e.x(), e.y(), 1.0f - std::fabs(e.x()) - std::fabs(e.y()));
    if (n.z() < 0.0f)
    {
        const float sx = n.x() >= 0.0f ? 1.0f : -1.0f, sy = n.y() >= 0.0f ? 1.0f : -1.0f;
        n = osg::Vec3f((1.0f - std::fabs(e.y())) * sx, (1.0f - std::fabs(e.x())) * sy, n.z());
    }
    n.normalize();
    return n;
}

bool ObjectSpaceEdges::prepareGeometry(osg::Geometry& g, Report& report)
{
    bool done = false;
    if (g.getUserValue(kPreparedValue, done) && done) return true;
    const osg::Vec3Array* positions = dynamic_cast<const osg::Vec3Array*>(g.getVertexArray());
    if (!positions || positions->empty()) return true; // nothing to draw lines on
    const unsigned n = positions->getNumElements();
    std::vector<unsigned> idx;
    {
        osg::TriangleIndexFunctor<TriangleIndexList> f;
        f.out = &idx;
        g.accept(f);
    }
    for (unsigned i : idx)
        if (i >= n) return false;
    const std::size_t T = idx.size() / 3;
    if (T == 0) return true;

    // Corners welded by position (1e-6 of the geometry's size), face normals.
    osg::BoundingBoxf box;
    for (const osg::Vec3& p : *positions)
        box.expandBy(p);
    const double quantum = std::max(1e-9, 1e-6 * double(box.radius()));
    std::map<std::tuple<long long, long long, long long>, unsigned> welded;
    std::vector<unsigned> weldOf(n);
    for (unsigned i = 0; i < n; ++i)
    {
        const osg::Vec3& p = (*positions)[i];
        const auto key = std::make_tuple(std::llround(p.x() / quantum), std::llround(p.y() / quantum),
                                         std::llround(p.z() / quantum));
        weldOf[i] = welded.emplace(key, unsigned(welded.size())).first->second;
    }
    std::vector<osg::Vec3f> normal(T);
    std::vector<bool> degenerate(T);
    for (std::size_t t = 0; t < T; ++t)
    {
        const osg::Vec3 &a = (*positions)[idx[3 * t]], &b = (*positions)[idx[3 * t + 1]],
                        &c = (*positions)[idx[3 * t + 2]];
        osg::Vec3f nn = (b - a) ^ (c - a);
        degenerate[t] = !(nn.normalize() > 0.0f) || weldOf[idx[3 * t]] == weldOf[idx[3 * t + 1]] ||
                        weldOf[idx[3 * t + 1]] == weldOf[idx[3 * t + 2]] ||
                        weldOf[idx[3 * t]] == weldOf[idx[3 * t + 2]];
        normal[t] = nn;
    }
    // Each edge (welded corners, lower first) and the (triangle, opposite corner) pairs on it.
    std::map<std::pair<unsigned, unsigned>, std::vector<std::pair<std::size_t, int>>> edges;
    for (std::size_t t = 0; t < T; ++t)
    {
        if (degenerate[t]) continue;
        for (int k = 0; k < 3; ++k)
        {
            const unsigned a = weldOf[idx[3 * t + std::size_t((k + 1) % 3)]],
                           b = weldOf[idx[3 * t + std::size_t((k + 2) % 3)]];
            edges[std::make_pair(std::min(a, b), std::max(a, b))].emplace_back(t, k);
        }
    }
    report.edges += unsigned(edges.size());
    const osg::Vec2f none(9.0f, 9.0f);
    std::vector<std::array<osg::Vec2f, 3>> adjacent(T, {none, none, none});
    std::vector<int> boundaryMask(T, 0);
    for (const auto& e : edges)
    {
        const auto& sides = e.second;
        if (sides.size() != 2)
        {
            (sides.size() == 1 ? report.boundary : report.nonManifold) += 1;
            for (const auto& s : sides)
                boundaryMask[s.first] |= 1 << s.second;
            continue;
        }
        for (int i = 0; i < 2; ++i)
        {
            const auto &me = sides[std::size_t(i)], &other = sides[std::size_t(1 - i)];
            // The neighbour's normal as if its winding agreed with this face's: a consistent mesh
            // walks a shared edge in opposite directions.
            const unsigned a0 = weldOf[idx[3 * me.first + std::size_t((me.second + 1) % 3)]];
            const unsigned b0 = weldOf[idx[3 * other.first + std::size_t((other.second + 1) % 3)]];
            const bool agree = a0 != b0;
            adjacent[me.first][std::size_t(me.second)] =
                octEncode(agree ? normal[other.first] : -normal[other.first]);
        }
    }

    // Every triangle its own corners, with its edge data on units 5-7.
    std::vector<unsigned> order(idx.begin(), idx.end());
    // Per-vertex arrays are rewritten; one shorter than the vertices, or bound per primitive set
    // (its meaning tied to the primitive sets replaced here), cannot be.
    auto rewrite = [&](osg::Array* a) -> osg::ref_ptr<osg::Array>
    {
        if (!a) return a;
        if (a->getBinding() == osg::Array::BIND_PER_PRIMITIVE_SET) return nullptr;
        if (!perVertex(a)) return a;
        if (a->getNumElements() < n) return nullptr;
        return deindexed(*a, order);
    };
    osg::ref_ptr<osg::Array> v = rewrite(g.getVertexArray()), nrm = rewrite(g.getNormalArray()),
                             col = rewrite(g.getColorArray()), col2 = rewrite(g.getSecondaryColorArray()),
                             fog = rewrite(g.getFogCoordArray());
    if ((g.getVertexArray() && !v) || (g.getNormalArray() && !nrm) || (g.getColorArray() && !col) ||
        (g.getSecondaryColorArray() && !col2) || (g.getFogCoordArray() && !fog))
        return false;
    std::vector<osg::ref_ptr<osg::Array>> tex(g.getNumTexCoordArrays()), attrib(g.getNumVertexAttribArrays());
    for (unsigned u = 0; u < tex.size(); ++u)
        if (g.getTexCoordArray(u) && !(tex[u] = rewrite(g.getTexCoordArray(u)))) return false;
    for (unsigned u = 0; u < attrib.size(); ++u)
        if (g.getVertexAttribArray(u) && !(attrib[u] = rewrite(g.getVertexAttribArray(u)))) return false;
    g.setVertexArray(v.get());
    if (nrm) g.setNormalArray(nrm.get());
    if (col) g.setColorArray(col.get());
    if (col2) g.setSecondaryColorArray(col2.get());
    if (fog) g.setFogCoordArray(fog.get());
    for (unsigned u = 0; u < tex.size(); ++u)
        if (tex[u]) g.setTexCoordArray(u, tex[u].get());
    for (unsigned u = 0; u < attrib.size(); ++u)
        if (attrib[u]) g.setVertexAttribArray(u, attrib[u].get());
    osg::ref_ptr<osg::Vec4Array> d0 = new osg::Vec4Array, d1 = new osg::Vec4Array, d2 = new osg::Vec4Array;
    for (std::size_t t = 0; t < T; ++t)
        for (int k = 0; k < 3; ++k)
        {
            const float mask = degenerate[t] ? 0.0f : float(boundaryMask[t]);
            d0->push_back(osg::Vec4(k == 0 ? 1.0f : 0.0f, k == 1 ? 1.0f : 0.0f, k == 2 ? 1.0f : 0.0f, mask));
            const auto& adj = adjacent[t];
            d1->push_back(osg::Vec4(adj[0].x(), adj[0].y(), adj[1].x(), adj[1].y()));
            d2->push_back(osg::Vec4(adj[2].x(), adj[2].y(), 0.0f, 0.0f));
        }
    g.setTexCoordArray(kUnit, d0.get(), osg::Array::BIND_PER_VERTEX);
    g.setTexCoordArray(kUnit + 1, d1.get(), osg::Array::BIND_PER_VERTEX);
    g.setTexCoordArray(kUnit + 2, d2.get(), osg::Array::BIND_PER_VERTEX);
    g.removePrimitiveSet(0, g.getNumPrimitiveSets());
    g.addPrimitiveSet(new osg::DrawArrays(GL_TRIANGLES, 0, GLsizei(3 * T)));
    g.setUserValue(kPreparedValue, true);
    // The geometry stage's marker (a StateSet shared with other drawables is copied first).
    if (g.getStateSet() && g.getStateSet()->referenceCount() > 1)
        g.setStateSet(osg::clone(g.getStateSet(), osg::CopyOp::SHALLOW_COPY));
    g.getOrCreateStateSet()->addUniform(new osg::Uniform("loa_objectEdgesData", true));
    g.dirtyGLObjects();
    g.dirtyBound();
    ++report.geometries;
    report.triangles += unsigned(T);
    return true;
}

ObjectSpaceEdges::Report ObjectSpaceEdges::prepare(osg::Node& model)
{
    Report r;
    GenericGeometry v(r);
    model.accept(v);
    return r;
}

} // namespace osgLoA
