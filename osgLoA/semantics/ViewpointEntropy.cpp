#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/render/ShaderLibrary>
#include <osgLoA/semantics/ViewpointEntropy>

#include "../util/TriangleCollector.h"

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Notify>
#include <osg/Transform>
#include <osg/TriangleFunctor>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

namespace osgLoA
{

namespace
{
// ---------------------------------------------------------------- triangle collection

// ---------------------------------------------------------------- face merging

struct CellKey
{
    std::int64_t x, y, z;
    bool operator==(const CellKey& o) const { return x == o.x && y == o.y && z == o.z; }
};

struct CellHash
{
    std::size_t operator()(const CellKey& k) const
    {
        std::uint64_t h = static_cast<std::uint64_t>(k.x) * 0x9E3779B97F4A7C15ull;
        h ^= static_cast<std::uint64_t>(k.y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
        h ^= static_cast<std::uint64_t>(k.z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
        return static_cast<std::size_t>(h);
    }
};

/** Welds positions closer than epsilon (first come, first served) on a hash grid of cell epsilon. */
class Welder
{
public:
    explicit Welder(double epsilon) : _eps(epsilon) {}

    unsigned id(const osg::Vec3& p)
    {
        const CellKey c = key(p);
        const double eps2 = _eps * _eps;
        for (std::int64_t dx = -1; dx <= 1; ++dx)
            for (std::int64_t dy = -1; dy <= 1; ++dy)
                for (std::int64_t dz = -1; dz <= 1; ++dz)
                {
                    auto it = _cells.find(CellKey{c.x + dx, c.y + dy, c.z + dz});
                    if (it == _cells.end()) continue;
                    for (unsigned v : it->second)
                        if ((osg::Vec3d(_points[v]) - osg::Vec3d(p)).length2() <= eps2) return v;
                }
        const unsigned v = static_cast<unsigned>(_points.size());
        _points.push_back(p);
        _cells[c].push_back(v);
        return v;
    }

private:
    CellKey key(const osg::Vec3& p) const
    {
        return CellKey{static_cast<std::int64_t>(std::floor(p.x() / _eps)),
                       static_cast<std::int64_t>(std::floor(p.y() / _eps)),
                       static_cast<std::int64_t>(std::floor(p.z() / _eps))};
    }

    double _eps;
    std::vector<osg::Vec3> _points;
    std::unordered_map<CellKey, std::vector<unsigned>, CellHash> _cells;
};

unsigned findRoot(std::vector<unsigned>& parent, unsigned i)
{
    while (parent[i] != i)
    {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}

// ---------------------------------------------------------------- ID encoding

constexpr unsigned kMaxFaces = 0xFFFFFFu; // 24 bits of rgb; alpha 255 marks a face pixel

osg::Vec4ub encodeId(unsigned id)
{
    return osg::Vec4ub(static_cast<unsigned char>(id & 0xFF), static_cast<unsigned char>((id >> 8) & 0xFF),
                       static_cast<unsigned char>((id >> 16) & 0xFF), 255);
}

std::string str(double v)
{
    std::ostringstream s;
    s << v;
    return s.str();
}
} // namespace

ViewpointEntropy::ViewpointEntropy() {}

ViewpointEntropy::ViewpointEntropy(const Settings& settings)
{
    setSettings(settings);
}

ViewpointEntropy::~ViewpointEntropy() {}

void ViewpointEntropy::setSettings(const Settings& s)
{
    auto bad = [](const std::string& what) { throw std::invalid_argument("ViewpointEntropy: " + what); };
    if (s.directions < 1) bad("directions must be at least 1");
    if (!(s.elevationDegrees > -90.0 && s.elevationDegrees < 90.0))
        bad("elevation " + str(s.elevationDegrees) + " degrees is outside (-90, 90)");
    if (!(s.fovyDegrees > 0.0 && s.fovyDegrees < 180.0))
        bad("field of view " + str(s.fovyDegrees) + " degrees is outside (0, 180)");
    if (s.width < 1 || s.height < 1 || s.width > 16384 || s.height > 16384)
        bad("ID buffer size " + std::to_string(s.width) + "x" + std::to_string(s.height) +
            " is outside 1x1 .. 16384x16384");
    if (!(s.positionEpsilon > 0.0) || !std::isfinite(s.positionEpsilon))
        bad("position epsilon " + str(s.positionEpsilon) + " must be positive");
    if (!(s.faceAngleDegrees >= 0.0 && s.faceAngleDegrees < 90.0))
        bad("face angle " + str(s.faceAngleDegrees) + " degrees is outside [0, 90)");
    if (_renderer.valid() &&
        (s.width != _renderer->getSettings().width || s.height != _renderer->getSettings().height))
    {
        _renderer = nullptr;
        _sceneRoot = nullptr;
    }
    _settings = s;
}

double ViewpointEntropy::entropy(const std::vector<double>& areas, double background)
{
    if (!std::isfinite(background) || background < 0.0)
        throw std::invalid_argument("ViewpointEntropy::entropy: background area " + str(background) +
                                    " is negative or not finite");
    double total = background;
    for (double a : areas)
    {
        if (!std::isfinite(a) || a < 0.0)
            throw std::invalid_argument("ViewpointEntropy::entropy: area " + str(a) +
                                        " is negative or not finite");
        total += a;
    }
    if (total <= 0.0) return 0.0;
    auto term = [total](double a) { return a > 0.0 ? -(a / total) * std::log2(a / total) : 0.0; };
    double h = term(background);
    for (double a : areas)
        h += term(a);
    return h;
}

std::vector<osg::Vec3> ViewpointEntropy::collectTriangles(osg::Node& node, const osg::Matrixd& toWorld)
{
    TriangleCollector c(toWorld);
    node.accept(c);
    std::vector<osg::Vec3> out;
    out.reserve(c.corners().size());
    for (const osg::Vec3d& v : c.corners())
        out.push_back(osg::Vec3(v));
    return out;
}

ViewpointEntropy::Faces ViewpointEntropy::mergeFaces(const std::vector<osg::Vec3>& tv, double positionEpsilon,
                                                     double faceAngleDegrees)
{
    if (!(positionEpsilon > 0.0))
        throw std::invalid_argument("ViewpointEntropy::mergeFaces: position epsilon " + str(positionEpsilon) +
                                    " must be positive");
    const double cosLimit = std::cos(osg::DegreesToRadians(faceAngleDegrees));
    Welder welder(positionEpsilon);
    Faces faces;
    std::vector<unsigned> ids;       // welded vertex ids, 3 per kept triangle
    std::vector<osg::Vec3d> normals; // unit, per kept triangle
    const std::size_t n = tv.size() / 3;
    for (std::size_t t = 0; t < n; ++t)
    {
        const osg::Vec3d a = tv[3 * t], b = tv[3 * t + 1], c = tv[3 * t + 2];
        osg::Vec3d nrm = (b - a) ^ (c - a);
        const double len = nrm.length();
        const double longest2 = std::max({(b - a).length2(), (c - b).length2(), (a - c).length2()});
        // Degenerate: zero area, or an area negligible against its longest edge (a sliver of
        // collinear points, whose normal would be noise).
        if (!(len > 1e-9 * longest2) || !std::isfinite(len)) continue;
        const unsigned ia = welder.id(tv[3 * t]), ib = welder.id(tv[3 * t + 1]),
                       ic = welder.id(tv[3 * t + 2]);
        if (ia == ib || ib == ic || ia == ic) continue; // two corners within epsilon
        ids.insert(ids.end(), {ia, ib, ic});
        normals.push_back(nrm / len);
        faces.vertices.insert(faces.vertices.end(), {tv[3 * t], tv[3 * t + 1], tv[3 * t + 2]});
    }
    const unsigned kept = static_cast<unsigned>(normals.size());
    std::vector<unsigned> parent(kept);
    std::iota(parent.begin(), parent.end(), 0u);
    // Triangles sharing an (undirected) edge, keyed by the edge's two welded vertex ids.
    std::unordered_map<std::uint64_t, std::vector<unsigned>> edges;
    edges.reserve(kept * 3);
    for (unsigned t = 0; t < kept; ++t)
        for (int e = 0; e < 3; ++e)
        {
            const std::uint64_t u = ids[3 * t + e], v = ids[3 * t + (e + 1) % 3];
            const std::uint64_t key = std::min(u, v) << 32 | std::max(u, v);
            std::vector<unsigned>& list = edges[key];
            for (unsigned other : list)
                if (normals[t] * normals[other] >= cosLimit)
                    parent[findRoot(parent, t)] = findRoot(parent, other);
            list.push_back(t);
        }
    // Face ids 1..count in the order of each face's first triangle.
    std::unordered_map<unsigned, unsigned> faceOfRoot;
    faces.faceOfTriangle.resize(kept);
    for (unsigned t = 0; t < kept; ++t)
    {
        const unsigned r = findRoot(parent, t);
        auto it = faceOfRoot.find(r);
        if (it == faceOfRoot.end()) it = faceOfRoot.emplace(r, ++faces.count).first;
        faces.faceOfTriangle[t] = it->second;
    }
    return faces;
}

void ViewpointEntropy::ensureRenderer()
{
    if (_renderer.valid()) return;
    OffscreenRenderer::Settings rs;
    rs.width = _settings.width;
    rs.height = _settings.height;
    rs.samples = 0;
    rs.clearColor = osg::Vec4(0.0f, 0.0f, 0.0f, 0.0f); // id 0: background
    _renderer = new OffscreenRenderer(rs);

    _sceneRoot = new osg::Group;
    osg::StateSet* ss = _sceneRoot->getOrCreateStateSet();
    const auto on = osg::StateAttribute::ON | osg::StateAttribute::OVERRIDE | osg::StateAttribute::PROTECTED;
    const auto off =
        osg::StateAttribute::OFF | osg::StateAttribute::OVERRIDE | osg::StateAttribute::PROTECTED;
    ss->setAttributeAndModes(
        ShaderLibrary::createProgram("loa_face_id", {"loa_face_id.vert.glsl", "loa_face_id.frag.glsl"}).get(),
        on);
    ss->setMode(GL_BLEND, off);
    ss->setMode(GL_DITHER, off);
    ss->setMode(GL_MULTISAMPLE, off);
    ss->setMode(GL_CULL_FACE, off);
    ss->setMode(GL_LIGHTING, off);
    ss->setMode(GL_DEPTH_TEST, on);
    _renderer->setSceneData(_sceneRoot.get());

    osg::Camera* cam = _renderer->getCamera();
    cam->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    cam->setCullingMode(osg::CullSettings::NO_CULLING);
}

ViewpointEntropy::Result ViewpointEntropy::evaluate(osg::Node& featureRoot, const osg::NodePath& pathToIt)
{
    const auto t0 = std::chrono::steady_clock::now();
    Result r;
    const unsigned N = _settings.directions;
    for (unsigned k = 0; k < N; ++k)
    {
        const double a = 2.0 * osg::PI * k / N;
        r.directions.push_back(
            osg::Vec3(static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0.0f));
    }

    // World matrix of featureRoot's parent: the path without featureRoot itself.
    osg::NodePath parentPath = pathToIt;
    if (!parentPath.empty() && parentPath.back() == &featureRoot) parentPath.pop_back();
    const osg::Matrixd toWorld = osg::computeLocalToWorld(parentPath);
    const Faces faces = mergeFaces(collectTriangles(featureRoot, toWorld), _settings.positionEpsilon,
                                   _settings.faceAngleDegrees);
    r.triangles = faces.triangles();
    r.faces = faces.count;
    auto finish = [&]()
    {
        r.milliseconds =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        return r;
    };
    if (faces.count == 0)
    {
        r.message = "no triangles: nothing to view";
        return finish();
    }
    if (faces.count > kMaxFaces)
        throw std::runtime_error("ViewpointEntropy: " + std::to_string(faces.count) +
                                 " faces exceed the 24-bit ID range");

    // Bounding sphere: the box centre and the farthest vertex.
    osg::BoundingBoxd box;
    for (const osg::Vec3& v : faces.vertices)
        box.expandBy(osg::Vec3d(v));
    r.center = box.center();
    for (const osg::Vec3& v : faces.vertices)
        r.radius = std::max(r.radius, (osg::Vec3d(v) - r.center).length());

    // The ID geometry: de-indexed, one colour per vertex, the same for all three of a triangle.
    osg::ref_ptr<osg::Geometry> geom = new osg::Geometry;
    geom->setUseDisplayList(false);
    geom->setUseVertexBufferObjects(true);
    osg::ref_ptr<osg::Vec3Array> verts = new osg::Vec3Array(faces.vertices.begin(), faces.vertices.end());
    osg::ref_ptr<osg::Vec4ubArray> colors = new osg::Vec4ubArray;
    colors->reserve(faces.vertices.size());
    for (unsigned f : faces.faceOfTriangle)
        for (int i = 0; i < 3; ++i)
            colors->push_back(encodeId(f));
    colors->setNormalize(true);
    geom->setVertexArray(verts.get());
    geom->setColorArray(colors.get(), osg::Array::BIND_PER_VERTEX);
    geom->addPrimitiveSet(new osg::DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(verts->size())));
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(geom.get());

    ensureRenderer();
    _sceneRoot->removeChildren(0, _sceneRoot->getNumChildren());
    _sceneRoot->addChild(geode.get());

    // Camera: the bounding sphere fits the narrower of the two fields of view.
    const double fovy = osg::DegreesToRadians(_settings.fovyDegrees);
    const double aspect = static_cast<double>(_settings.width) / _settings.height;
    const double fovx = 2.0 * std::atan(std::tan(fovy / 2.0) * aspect);
    const double halfFov = std::min(fovy, fovx) / 2.0;
    r.distance = r.radius / std::sin(halfFov);
    osg::Camera* cam = _renderer->getCamera();
    cam->setProjectionMatrixAsPerspective(_settings.fovyDegrees, aspect, (r.distance - r.radius) * 0.99,
                                          (r.distance + r.radius) * 1.01);
    const double elev = osg::DegreesToRadians(_settings.elevationDegrees);

    std::vector<double> areas(faces.count);
    for (unsigned k = 0; k < N; ++k)
    {
        const osg::Vec3d d(r.directions[k]);
        const osg::Vec3d eye =
            r.center + (d * std::cos(elev) + osg::Vec3d(0, 0, 1) * std::sin(elev)) * r.distance;
        cam->setViewMatrixAsLookAt(eye, r.center, osg::Vec3d(0, 0, 1));
        osg::ref_ptr<osg::Image> img = _renderer->renderImage();

        std::fill(areas.begin(), areas.end(), 0.0);
        double background = 0.0;
        unsigned long long invalid = 0;
        const unsigned char* p = img->data();
        const std::size_t pixels = static_cast<std::size_t>(img->s()) * img->t();
        for (std::size_t i = 0; i < pixels; ++i, p += 4)
        {
            const unsigned id = unsigned(p[0]) | unsigned(p[1]) << 8 | unsigned(p[2]) << 16;
            if (p[3] == 0 && id == 0)
                background += 1.0;
            else if (p[3] == 255 && id >= 1 && id <= faces.count)
                areas[id - 1] += 1.0;
            else
                ++invalid;
        }
        r.invalidPixels += invalid;
        r.entropies.push_back(entropy(areas, background));
        r.visibleFaces.push_back(static_cast<unsigned>(
            std::count_if(areas.begin(), areas.end(), [](double a) { return a > 0.0; })));
    }
    _sceneRoot->removeChildren(0, _sceneRoot->getNumChildren());

    if (r.invalidPixels > 0 && _settings.failOnInvalidPixels)
        throw std::runtime_error("ViewpointEntropy: " + std::to_string(r.invalidPixels) +
                                 " ID-buffer pixels hold no valid face id (of " +
                                 std::to_string(faces.count) +
                                 " faces): the ID rendering is not exact on this driver");

    // The first maximum in ring order.
    r.bestIndex =
        static_cast<unsigned>(std::max_element(r.entropies.begin(), r.entropies.end()) - r.entropies.begin());
    r.bestDirection = r.directions[r.bestIndex];
    r.valid = true;
    return finish();
}

unsigned ViewpointEntropy::computeBestViews(FeatureIndex& index, std::vector<Result>* results)
{
    unsigned set = 0;
    for (const FeatureIndex::Entry& e : index.entries())
    {
        Feature& f = *e.feature;
        if (!f.getLandmark()) continue;
        osg::ref_ptr<osg::Node> node;
        Result r;
        if (e.node.lock(node))
            r = evaluate(*node, index.pathOf(e));
        else
            r.message = "the feature's node no longer exists";
        r.featureId = f.getId();
        if (r.valid)
        {
            f.setBestViewDirection(r.bestDirection);
            ++set;
        }
        else
        {
            f.setBestViewDirection(osg::Vec3());
            OSG_NOTICE << "osgLoA::ViewpointEntropy: landmark " << f.getId()
                       << " has no best view: " << r.message << std::endl;
        }
        if (results) results->push_back(r);
    }
    return set;
}

} // namespace osgLoA
