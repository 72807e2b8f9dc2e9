// CityJSON to scene graph (docs/cityjson.md). Two passes: the first resolves every selected
// geometry of every object into per-(semantic type, material, texture) bins of triangles, lines
// and points in world coordinates (double); the second re-centres on the bounding box of what
// was emitted and builds float osg::Geometry, object Groups and Features.
#include "CityJsonReader.h"

#include <osgLoA/semantics/CityObjectTypes>
#include <osgLoA/semantics/Feature>
#include <osgLoA/semantics/FeatureIndex>

#include <osg/BlendFunc>
#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Material>
#include <osg/Notify>
#include <osg/Texture2D>
#include <osg/TriangleIndexFunctor>
#include <osg/ValueObject>
#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>
#include <osgUtil/Tessellator>

#include <osgLoA/util/PolygonCrossings>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

namespace loacityjson
{

using json = Json;

namespace
{

std::string lower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
}

std::string inQuotes(const std::string& s)
{
    return "\"" + s + "\"";
}

/** A CityJSON LoD ("2.2" in 1.1+, a number in 1.0) as text and value; false when absent. */
bool lodOf(const json& geometry, std::string& text, float& value)
{
    auto it = geometry.find("lod");
    if (it == geometry.end()) return false;
    if (it->is_number())
    {
        std::ostringstream s;
        s << it->get<double>();
        text = s.str();
        value = it->get<float>();
        return true;
    }
    if (it->is_string())
    {
        text = it->get<std::string>();
        char* end = nullptr;
        value = std::strtof(text.c_str(), &end);
        return end != text.c_str();
    }
    return false;
}

// ---- triangulation -------------------------------------------------------------------------

osg::Vec3d newellNormal(const std::vector<osg::Vec3d>& ring)
{
    osg::Vec3d n;
    const osg::Vec3d o = ring.front();
    for (std::size_t i = 0; i < ring.size(); ++i)
    {
        const osg::Vec3d a = ring[i] - o;
        const osg::Vec3d b = ring[(i + 1) % ring.size()] - o;
        n.x() += (a.y() - b.y()) * (a.z() + b.z());
        n.y() += (a.z() - b.z()) * (a.x() + b.x());
        n.z() += (a.x() - b.x()) * (a.y() + b.y());
    }
    return n;
}

struct TriangleCollector
{
    std::vector<unsigned>* out = nullptr;
    void operator()(unsigned a, unsigned b, unsigned c)
    {
        out->push_back(a);
        out->push_back(b);
        out->push_back(c);
    }
};

/** A polygon's rings (outer first), in world coordinates, with optional texture coordinates. */
struct Polygon
{
    std::vector<std::vector<osg::Vec3d>> rings;
    std::vector<std::vector<osg::Vec2f>> uvs; ///< empty when untextured
};

/** Triangles in world coordinates with their flat normal and texture coordinates. */
struct Bin
{
    enum Kind
    {
        TRIANGLES = 0,
        LINES,
        POINTS
    };
    Kind kind = TRIANGLES;
    std::string name;
    int material = -1;
    int texture = -1;
    std::vector<osg::Vec3d> positions;
    std::vector<osg::Vec3f> normals;
    std::vector<osg::Vec2f> uvs;
    std::vector<std::pair<unsigned, unsigned>> strips; ///< LINES: (first, count) per line string
};

void emitTriangle(Bin& bin, const osg::Vec3d& normal, osg::Vec3d a, osg::Vec3d b, osg::Vec3d c, osg::Vec2f ta,
                  osg::Vec2f tb, osg::Vec2f tc, bool textured)
{
    const osg::Vec3d cr = (b - a) ^ (c - a);
    if (cr.length() <= 1e-12 * normal.length() || cr.length() == 0.0) return; // a sliver of nothing
    if (cr * normal < 0.0)
    {
        std::swap(b, c);
        std::swap(tb, tc);
    }
    osg::Vec3d nn = normal;
    nn.normalize();
    const osg::Vec3f n(nn);
    bin.positions.push_back(a);
    bin.positions.push_back(b);
    bin.positions.push_back(c);
    bin.normals.insert(bin.normals.end(), {n, n, n});
    if (textured) bin.uvs.insert(bin.uvs.end(), {ta, tb, tc});
}

/** Triangulates one polygon into the bin; false (nothing emitted) when it is degenerate. */
bool triangulate(Polygon& poly, Bin& bin)
{
    const bool textured = !poly.uvs.empty();
    // Drop consecutive repeated positions (and a closing repeat of the first) in every ring.
    for (std::size_t r = 0; r < poly.rings.size(); ++r)
    {
        std::vector<osg::Vec3d> p;
        std::vector<osg::Vec2f> t;
        for (std::size_t i = 0; i < poly.rings[r].size(); ++i)
        {
            if (!p.empty() && poly.rings[r][i] == p.back()) continue;
            p.push_back(poly.rings[r][i]);
            if (textured) t.push_back(poly.uvs[r][i]);
        }
        while (p.size() > 1 && p.front() == p.back())
        {
            p.pop_back();
            if (textured) t.pop_back();
        }
        poly.rings[r].swap(p);
        if (textured) poly.uvs[r].swap(t);
    }
    // Holes with fewer than 3 vertices enclose nothing.
    for (std::size_t r = poly.rings.size(); r-- > 1;)
        if (poly.rings[r].size() < 3)
        {
            poly.rings.erase(poly.rings.begin() + static_cast<long>(r));
            if (textured) poly.uvs.erase(poly.uvs.begin() + static_cast<long>(r));
        }
    const std::vector<osg::Vec3d>& outer = poly.rings.front();
    if (outer.size() < 3) return false;
    const osg::Vec3d normal = newellNormal(outer);
    double extent = 0.0;
    for (const osg::Vec3d& p : outer)
        extent = std::max(extent, (p - outer.front()).length());
    if (extent == 0.0 || normal.length() <= 1e-12 * extent * extent) return false;

    const std::size_t before = bin.positions.size();
    const std::vector<osg::Vec2f>* tuv = textured ? &poly.uvs.front() : nullptr;
    auto uv = [&](std::size_t i) { return tuv ? (*tuv)[i] : osg::Vec2f(); };

    if (poly.rings.size() == 1)
    {
        const std::size_t n = outer.size();
        if (n == 3)
        {
            emitTriangle(bin, normal, outer[0], outer[1], outer[2], uv(0), uv(1), uv(2), textured);
            return bin.positions.size() > before;
        }
        // Convex without holes: a fan, when every turn agrees with the normal and the fan's area
        // is the polygon's (a star polygon turns one way too but covers more).
        bool convex = true;
        for (std::size_t i = 0; i < n && convex; ++i)
        {
            const osg::Vec3d e0 = outer[(i + 1) % n] - outer[i];
            const osg::Vec3d e1 = outer[(i + 2) % n] - outer[(i + 1) % n];
            if (((e0 ^ e1) * normal) < -1e-12 * extent * extent * normal.length()) convex = false;
        }
        if (convex)
        {
            double fanArea = 0.0;
            for (std::size_t i = 1; i + 1 < n; ++i)
                fanArea += ((outer[i] - outer[0]) ^ (outer[i + 1] - outer[0])).length();
            if (std::abs(fanArea - normal.length()) <= 1e-9 * std::max(1.0, normal.length()))
            {
                for (std::size_t i = 1; i + 1 < n; ++i)
                    emitTriangle(bin, normal, outer[0], outer[i], outer[i + 1], uv(0), uv(i), uv(i + 1),
                                 textured);
                return bin.positions.size() > before;
            }
        }
    }

    // General case: GLU through osgUtil::Tessellator, every ring one contour of one polygon,
    // odd winding, the Newell normal as the projection normal. Coordinates relative to the
    // first vertex keep float precision; original vertices keep their double positions.
    const osg::Vec3d o = outer.front();
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    osg::ref_ptr<osg::Vec2Array> t = new osg::Vec2Array;
    std::vector<osg::Vec3d> original;
    std::vector<osg::Vec2f> originalUv;
    for (std::size_t r = 0; r < poly.rings.size(); ++r)
    {
        const unsigned start = static_cast<unsigned>(v->size());
        for (std::size_t i = 0; i < poly.rings[r].size(); ++i)
        {
            v->push_back(osg::Vec3(poly.rings[r][i] - o));
            original.push_back(poly.rings[r][i]);
            if (textured)
            {
                t->push_back(poly.uvs[r][i]);
                originalUv.push_back(poly.uvs[r][i]);
            }
        }
        g->addPrimitiveSet(new osg::DrawArrays(GL_POLYGON, static_cast<GLint>(start),
                                               static_cast<GLsizei>(poly.rings[r].size())));
    }
    g->setVertexArray(v.get());
    if (textured) g->setTexCoordArray(0, t.get(), osg::Array::BIND_PER_VERTEX);
    osg::Vec3d nn = normal;
    nn.normalize();
    osgUtil::Tessellator tess;
    tess.setTessellationType(osgUtil::Tessellator::TESS_TYPE_GEOMETRY);
    tess.setWindingType(osgUtil::Tessellator::TESS_WINDING_ODD);
    tess.setBoundaryOnly(false);
    tess.setTessellationNormal(osg::Vec3(nn));
    tess.retessellatePolygons(*g);

    const osg::Vec3Array* tv = dynamic_cast<const osg::Vec3Array*>(g->getVertexArray());
    const osg::Vec2Array* tt = dynamic_cast<const osg::Vec2Array*>(g->getTexCoordArray(0));
    if (!tv) return false;
    std::vector<unsigned> indices;
    osg::TriangleIndexFunctor<TriangleCollector> collect;
    collect.out = &indices;
    g->accept(collect);
    auto pos = [&](unsigned i) { return i < original.size() ? original[i] : osg::Vec3d((*tv)[i]) + o; };
    auto tex = [&](unsigned i)
    {
        if (!textured) return osg::Vec2f();
        if (i < originalUv.size()) return originalUv[i];
        return (tt && i < tt->size()) ? (*tt)[i] : osg::Vec2f();
    };
    for (std::size_t k = 0; k + 2 < indices.size(); k += 3)
    {
        const unsigned a = indices[k], b = indices[k + 1], c = indices[k + 2];
        if (a >= tv->size() || b >= tv->size() || c >= tv->size()) continue;
        emitTriangle(bin, normal, pos(a), pos(b), pos(c), tex(a), tex(b), tex(c), textured);
    }
    return bin.positions.size() > before;
}

// ---- type mapping ----------------------------------------------------------------------------

bool containsAny(const std::string& text, std::initializer_list<const char*> words,
                 std::string* which = nullptr)
{
    for (const char* w : words)
        if (text.find(w) != std::string::npos)
        {
            if (which) *which = w;
            return true;
        }
    return false;
}

/** Lower-case text of the attributes function, class and usage (strings only), space-separated. */
std::string classifyingText(const json& attributes)
{
    std::string text;
    if (!attributes.is_object()) return text;
    for (const char* key : {"function", "class", "usage"})
    {
        auto it = attributes.find(key);
        if (it == attributes.end()) continue;
        if (it->is_string())
            text += lower(it->get<std::string>()) + " ";
        else if (it->is_array())
            for (const json& e : *it)
                if (e.is_string()) text += lower(e.get<std::string>()) + " ";
    }
    return text;
}

/** The first string among class, function (lower case, trimmed); empty when none. */
std::string firstWord(const json& attributes)
{
    if (!attributes.is_object()) return std::string();
    for (const char* key : {"class", "function"})
    {
        auto it = attributes.find(key);
        if (it != attributes.end() && it->is_string() && !it->get<std::string>().empty())
            return lower(it->get<std::string>());
    }
    return std::string();
}

struct TypeMapping
{
    osgLoA::FeatureType type = osgLoA::FeatureType::Generic;
    std::string subType;
    osgLoA::Feature::Source source = osgLoA::Feature::MODEL_DATA;
};

TypeMapping mapType(const std::string& cityType, const json& attributes)
{
    using osgLoA::FeatureType;
    TypeMapping m;
    // The shared table (osgLoA::CityObjectTypes, docs/classification.md); "+Extension" and
    // unknown types stay unclassified for the rules.
    const osgLoA::CityObjectTypes::Entry* e = osgLoA::CityObjectTypes::find(cityType);
    if (!e)
    {
        m.source = osgLoA::Feature::UNCLASSIFIED;
        return m;
    }
    m.type = e->type;
    m.subType = e->subType;
    // Refinements from the object's own attributes.
    if (cityType == "WaterBody")
    {
        std::string word;
        if (containsAny(classifyingText(attributes),
                        {"river", "lake", "sea", "canal", "pond", "stream", "ocean", "reservoir", "harbour"},
                        &word))
            m.subType = word;
    }
    else if (cityType == "PlantCover" || cityType == "SolitaryVegetationObject")
    {
        const std::string word = firstWord(attributes);
        if (!word.empty()) m.subType = word;
    }
    else if (cityType == "LandUse")
    {
        const std::string text = classifyingText(attributes);
        // Street words first: "parking" contains "park".
        if (containsAny(text, {"road", "traffic", "transport", "parking"}))
            m.type = FeatureType::Street;
        else if (containsAny(text, {"grass", "park", "forest", "wood", "garden", "meadow", "agricultur"}))
            m.type = FeatureType::Green;
        else if (containsAny(text, {"water", "river", "lake"}))
            m.type = FeatureType::Water;
        if (m.type != e->type) m.subType.clear(); // "land-use" only names ground of some use
        const std::string word = firstWord(attributes);
        if (!word.empty()) m.subType = word;
    }
    return m;
}

// ---- the builder -----------------------------------------------------------------------------

/** Where a geometry's vertex indices point: the file's vertices, or a template's vertices placed
 *  by an instance (reference point + 4x4 row-major matrix). */
struct VertexSource
{
    const std::vector<osg::Vec3d>* vertices = nullptr;
    bool instance = false;
    double m[16] = {};
    osg::Vec3d reference;
    const char* what = "vertex";
};

struct ObjectData
{
    std::string id;
    const json* object = nullptr;
    std::string type;
    std::vector<Bin> bins;
    std::map<std::tuple<int, std::string, int, int>, std::size_t> binIndex;
    bool hasGeometry = false; ///< the object has geometry entries at all
    float lod = -1.0f;
    bool produced = false; ///< some selected geometry produced primitives
    int kept = -1;         ///< -1 unknown, 0 no, 1 yes
    std::vector<std::size_t> children;
    long placedUnder = -1;
    unsigned featureId = 0;
    osg::ref_ptr<osg::Group> group;
};

class Builder
{
public:
    Builder(const json& doc, const std::string& sourceName, const Settings& settings,
            const osgDB::FilePathList& textureDirs, const osgDB::Options* options)
        : _doc(doc), _source(sourceName), _settings(settings), _textureDirs(textureDirs), _options(options)
    {
    }

    osg::ref_ptr<osg::Group> build();

private:
    [[noreturn]] void fail(const std::string& message) const { throw Error(_source + ": " + message); }
    void warn(const std::string& message) const
    {
        OSG_WARN << "cityjson: " << _source << ": " << message << std::endl;
    }

    const json& requireArray(const json& j, const std::string& what) const
    {
        if (!j.is_array()) fail(what + " must be an array (found " + std::string(j.type_name()) + ")");
        return j;
    }

    void checkVersion();
    void readVertices();
    void readAppearance();
    void chooseThemes();
    void collectThemes(const json& geometry, std::vector<std::string>& materialThemes,
                       std::vector<std::string>& textureThemes) const;
    void processObject(ObjectData& od);
    void processGeometry(ObjectData& od, const json& g, const std::string& where, const VertexSource& vs);
    void addSurfaces(ObjectData& od, const json& boundaries, const json* sem, const json* semSurfaces,
                     const json* mat, int matConstant, const json* tex, int depth, const std::string& where,
                     const VertexSource& vs);
    void addSurface(ObjectData& od, const json& surface, const json* semIndex, const json* semSurfaces,
                    const json* mat, const json* tex, const std::string& where, const VertexSource& vs);
    osg::Vec3d vertex(const json& index, const std::string& where, const VertexSource& vs) const;
    std::string semanticName(const json* semIndex, const json* semSurfaces, const std::string& where) const;
    int materialIndex(const json* value, const std::string& where) const;
    Bin& binFor(ObjectData& od, Bin::Kind kind, const std::string& name, int material, int texture);
    bool computeKept(std::size_t i, std::set<std::size_t>& visiting);
    /** Throws InputLimitError for a polygon whose edges cross more than max-crossings times. */
    void checkCrossings(const Polygon& poly, const std::string& where) const;
    /** Throws InputLimitError for a chain of children longer than max-hierarchy. */
    void checkHierarchy() const;
    osg::Texture2D* texture(int index);
    osg::StateSet* stateSet(int material, int texture);
    osg::ref_ptr<osg::Geometry> makeGeometry(const Bin& bin, const osg::Vec3d& origin);
    void setAttributes(osg::Node& node, const json& attributes) const;
    void place(std::size_t i, osg::Group& parent, std::set<std::size_t>& placed);

    const json& _doc;
    std::string _source;
    Settings _settings;
    osgDB::FilePathList _textureDirs;
    const osgDB::Options* _options;

    std::string _version;
    std::vector<osg::Vec3d> _vertices;
    std::vector<osg::Vec3d> _templateVertices;
    const json* _templates = nullptr;
    std::vector<osg::Vec2f> _uvs;
    const json* _materials = nullptr;
    const json* _textures = nullptr;
    std::string _materialTheme, _textureTheme;
    float _requestedLod = -1.0f;

    std::vector<ObjectData> _objects;
    std::map<std::string, std::size_t> _byId;
    std::map<int, osg::ref_ptr<osg::Texture2D>> _textureCache; ///< null: missing file
    std::map<std::pair<int, int>, osg::ref_ptr<osg::StateSet>> _stateSets;
    unsigned _skippedPolygons = 0, _omittedObjects = 0, _skippedObjects = 0, _missingTextures = 0;
    bool _warnedUvMismatch = false;
};

void Builder::checkVersion()
{
    if (!_doc.is_object()) fail("not a CityJSON file: the top level is not a JSON object");
    auto type = _doc.find("type");
    if (type == _doc.end() || !type->is_string())
        fail("not a CityJSON file: missing top-level \"type\" (expected \"CityJSON\")");
    if (*type != "CityJSON")
        fail("not a CityJSON file: top-level \"type\" is " + type->dump() + ", expected \"CityJSON\"");
    auto version = _doc.find("version");
    if (version == _doc.end()) fail("missing \"version\"");
    if (!version->is_string())
        fail("\"version\" must be a string such as \"2.0\" (found " + version->dump() + ")");
    const std::string v = version->get<std::string>();
    for (const char* known : {"1.0", "1.1", "2.0"})
        if (v == known || v.rfind(std::string(known) + ".", 0) == 0) _version = known;
    if (_version.empty()) fail("unsupported CityJSON version \"" + v + "\" (supported: 1.0, 1.1, 2.0)");
}

void Builder::readVertices()
{
    auto vit = _doc.find("vertices");
    if (vit == _doc.end()) fail("missing \"vertices\"");
    const json& vertices = requireArray(*vit, "\"vertices\"");
    osg::Vec3d scale(1, 1, 1), translate;
    auto tit = _doc.find("transform");
    if (tit == _doc.end())
    {
        if (_version != "1.0") fail("CityJSON " + _version + " requires \"transform\", which is missing");
    }
    else
    {
        if (!tit->is_object()) fail("\"transform\" must be an object");
        auto vec3 = [&](const char* key, osg::Vec3d& out)
        {
            auto it = tit->find(key);
            if (it == tit->end()) fail(std::string("\"transform\" lacks \"") + key + "\"");
            if (!it->is_array() || it->size() != 3 || !(*it)[0].is_number() || !(*it)[1].is_number() ||
                !(*it)[2].is_number())
                fail(std::string("\"transform.") + key + "\" must be an array of 3 numbers");
            out.set((*it)[0].get<double>(), (*it)[1].get<double>(), (*it)[2].get<double>());
        };
        vec3("scale", scale);
        vec3("translate", translate);
    }
    if (vertices.size() > _settings.limits.maxVertices)
        throw osgLoA::InputLimitError(
            osgLoA::InputLimits::exceeded(_source, std::to_string(vertices.size()) + " vertices",
                                          "max-vertices", _settings.limits.maxVertices));
    _vertices.reserve(vertices.size());
    for (std::size_t i = 0; i < vertices.size(); ++i)
    {
        const json& v = vertices[i];
        if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
            fail("vertex " + std::to_string(i) + " must be an array of 3 numbers (found " + v.dump() + ")");
        const osg::Vec3d p(v[0].get<double>() * scale.x() + translate.x(),
                           v[1].get<double>() * scale.y() + translate.y(),
                           v[2].get<double>() * scale.z() + translate.z());
        if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
            fail("non-finite coordinate in vertex " + std::to_string(i) + " after \"transform\"");
        _vertices.push_back(p);
    }

    auto git = _doc.find("geometry-templates");
    if (git != _doc.end())
    {
        if (!git->is_object()) fail("\"geometry-templates\" must be an object");
        auto templates = git->find("templates");
        if (templates != git->end())
            _templates = &requireArray(*templates, "\"geometry-templates.templates\"");
        auto tv = git->find("vertices-templates");
        if (tv != git->end())
        {
            requireArray(*tv, "\"geometry-templates.vertices-templates\"");
            for (std::size_t i = 0; i < tv->size(); ++i)
            {
                const json& v = (*tv)[i];
                if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() ||
                    !v[2].is_number())
                    fail("template vertex " + std::to_string(i) + " must be an array of 3 numbers");
                const osg::Vec3d p(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
                if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
                    fail("non-finite coordinate in template vertex " + std::to_string(i));
                _templateVertices.push_back(p);
            }
        }
    }
}

void Builder::readAppearance()
{
    auto ait = _doc.find("appearance");
    if (ait == _doc.end()) return;
    if (!ait->is_object()) fail("\"appearance\" must be an object");
    auto m = ait->find("materials");
    if (m != ait->end()) _materials = &requireArray(*m, "\"appearance.materials\"");
    auto t = ait->find("textures");
    if (t != ait->end()) _textures = &requireArray(*t, "\"appearance.textures\"");
    auto vt = ait->find("vertices-texture");
    if (vt != ait->end())
    {
        requireArray(*vt, "\"appearance.vertices-texture\"");
        for (std::size_t i = 0; i < vt->size(); ++i)
        {
            const json& v = (*vt)[i];
            if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
                fail("texture vertex " + std::to_string(i) + " must be an array of 2 numbers");
            _uvs.emplace_back(v[0].get<float>(), v[1].get<float>());
        }
    }
}

void Builder::collectThemes(const json& geometry, std::vector<std::string>& materialThemes,
                            std::vector<std::string>& textureThemes) const
{
    if (!geometry.is_object()) return;
    auto add = [](const json& themes, std::vector<std::string>& out)
    {
        if (!themes.is_object()) return;
        for (auto it = themes.begin(); it != themes.end(); ++it)
            if (std::find(out.begin(), out.end(), it.key()) == out.end()) out.push_back(it.key());
    };
    if (geometry.contains("material")) add(geometry["material"], materialThemes);
    if (geometry.contains("texture")) add(geometry["texture"], textureThemes);
}

void Builder::chooseThemes()
{
    std::vector<std::string> materialThemes, textureThemes;
    const json& objects = _doc["CityObjects"];
    for (auto it = objects.begin(); it != objects.end(); ++it)
        if (it->is_object() && it->contains("geometry") && (*it)["geometry"].is_array())
            for (const json& g : (*it)["geometry"])
                collectThemes(g, materialThemes, textureThemes);
    if (_templates)
        for (const json& g : *_templates)
            collectThemes(g, materialThemes, textureThemes);
    auto choose = [&](const std::vector<std::string>& themes, const char* defaultKey) -> std::string
    {
        if (themes.empty()) return std::string();
        if (!_settings.theme.empty() &&
            std::find(themes.begin(), themes.end(), _settings.theme) != themes.end())
            return _settings.theme;
        auto ait = _doc.find("appearance");
        if (ait != _doc.end() && ait->is_object() && ait->contains(defaultKey) &&
            (*ait)[defaultKey].is_string())
        {
            const std::string d = (*ait)[defaultKey].get<std::string>();
            if (std::find(themes.begin(), themes.end(), d) != themes.end()) return d;
        }
        return themes.front();
    };
    _materialTheme = choose(materialThemes, "default-theme-material");
    _textureTheme = choose(textureThemes, "default-theme-texture");
    if (!_settings.theme.empty() && _settings.theme != _materialTheme && _settings.theme != _textureTheme)
        warn("theme \"" + _settings.theme + "\" is not in the file; using material theme \"" +
             _materialTheme + "\" and texture theme \"" + _textureTheme + "\"");
    if (!_materialTheme.empty() && !_materials)
    {
        warn("geometries name material theme \"" + _materialTheme +
             "\" but \"appearance.materials\" is absent; materials ignored");
        _materialTheme.clear();
    }
    if (!_textureTheme.empty() && !_textures)
    {
        warn("geometries name texture theme \"" + _textureTheme +
             "\" but \"appearance.textures\" is absent; textures ignored");
        _textureTheme.clear();
    }
}

osg::Vec3d Builder::vertex(const json& index, const std::string& where, const VertexSource& vs) const
{
    if (!index.is_number_integer()) fail(where + ": expected a " + vs.what + " index, found " + index.dump());
    const long long i = index.get<long long>();
    if (i < 0 || static_cast<unsigned long long>(i) >= vs.vertices->size())
        fail(where + ": " + vs.what + " index " + std::to_string(i) + " out of range (" +
             std::to_string(vs.vertices->size()) + (vs.instance ? " template vertices)" : " vertices)"));
    const osg::Vec3d& v = (*vs.vertices)[static_cast<std::size_t>(i)];
    if (!vs.instance) return v;
    const double* m = vs.m;
    const osg::Vec3d p = vs.reference + osg::Vec3d(m[0] * v.x() + m[1] * v.y() + m[2] * v.z() + m[3],
                                                   m[4] * v.x() + m[5] * v.y() + m[6] * v.z() + m[7],
                                                   m[8] * v.x() + m[9] * v.y() + m[10] * v.z() + m[11]);
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
        fail(where + ": non-finite coordinate from the template instance's transformationMatrix");
    return p;
}

std::string Builder::semanticName(const json* semIndex, const json* semSurfaces,
                                  const std::string& where) const
{
    if (!semIndex || semIndex->is_null()) return std::string();
    if (!semIndex->is_number_integer()) fail(where + ": semantics value must be an index or null");
    const long long i = semIndex->get<long long>();
    if (!semSurfaces || i < 0 || static_cast<std::size_t>(i) >= semSurfaces->size())
        fail(where + ": semantic surface index " + std::to_string(i) + " out of range");
    const json& s = (*semSurfaces)[static_cast<std::size_t>(i)];
    if (s.is_object() && s.contains("type") && s["type"].is_string()) return s["type"].get<std::string>();
    return std::string();
}

int Builder::materialIndex(const json* value, const std::string& where) const
{
    if (!value || value->is_null()) return -1;
    if (!value->is_number_integer()) fail(where + ": material value must be an index or null");
    const long long i = value->get<long long>();
    if (i < 0 || static_cast<std::size_t>(i) >= _materials->size())
        fail(where + ": material index " + std::to_string(i) + " out of range (" +
             std::to_string(_materials->size()) + " materials)");
    return static_cast<int>(i);
}

Bin& Builder::binFor(ObjectData& od, Bin::Kind kind, const std::string& name, int material, int tex)
{
    const auto key = std::make_tuple(static_cast<int>(kind), name, material, tex);
    auto it = od.binIndex.find(key);
    if (it != od.binIndex.end()) return od.bins[it->second];
    od.binIndex[key] = od.bins.size();
    od.bins.emplace_back();
    Bin& b = od.bins.back();
    b.kind = kind;
    b.name = name;
    b.material = material;
    b.texture = tex;
    return b;
}

/** Element i of an optional array (null when the array is absent, null or too short). */
const json* element(const json* array, std::size_t i)
{
    if (!array || !array->is_array() || i >= array->size()) return nullptr;
    return &(*array)[i];
}

void Builder::addSurface(ObjectData& od, const json& surface, const json* semIndex, const json* semSurfaces,
                         const json* mat, const json* tex, const std::string& where, const VertexSource& vs)
{
    requireArray(surface, where);
    if (surface.empty() || !surface[0].is_array() || surface[0].empty())
    {
        if (!surface.empty()) requireArray(surface[0], where + " ring 0");
        ++_skippedPolygons;
        return;
    }
    const std::string name = semanticName(semIndex, semSurfaces, where);
    const int material = mat ? materialIndex(mat, where) : -1;

    // Texture: [[t, uv...], [t, uv...] (holes)] or [[null]].
    int textureIndex = -1;
    if (tex && tex->is_array() && !tex->empty() && (*tex)[0].is_array() && !(*tex)[0].empty() &&
        !(*tex)[0][0].is_null())
    {
        const json& t0 = (*tex)[0][0];
        if (!t0.is_number_integer()) fail(where + ": texture value must be an index or null");
        const long long ti = t0.get<long long>();
        if (ti < 0 || static_cast<std::size_t>(ti) >= _textures->size())
            fail(where + ": texture index " + std::to_string(ti) + " out of range (" +
                 std::to_string(_textures->size()) + " textures)");
        textureIndex = static_cast<int>(ti);
        // Every ring needs one texture vertex per vertex.
        bool matches = tex->size() == surface.size();
        for (std::size_t r = 0; matches && r < surface.size(); ++r)
            matches =
                (*tex)[r].is_array() && surface[r].is_array() && (*tex)[r].size() == surface[r].size() + 1;
        if (!matches)
        {
            if (!_warnedUvMismatch)
                warn(where +
                     ": texture values do not match the rings' vertex counts; drawn untextured (further "
                     "cases not reported)");
            _warnedUvMismatch = true;
            textureIndex = -1;
        }
    }

    Polygon poly;
    for (std::size_t r = 0; r < surface.size(); ++r)
    {
        const std::string ringWhere = where + " ring " + std::to_string(r);
        const json& ring = requireArray(surface[r], ringWhere);
        if (ring.size() > _settings.limits.maxRingVertices)
            throw osgLoA::InputLimitError(osgLoA::InputLimits::exceeded(
                _source, ringWhere + " with " + std::to_string(ring.size()) + " vertices",
                "max-ring-vertices", _settings.limits.maxRingVertices));
        std::vector<osg::Vec3d> pts;
        std::vector<osg::Vec2f> uvs;
        pts.reserve(ring.size());
        for (std::size_t i = 0; i < ring.size(); ++i)
        {
            pts.push_back(vertex(ring[i], ringWhere, vs));
            if (textureIndex >= 0)
            {
                const json& u = (*tex)[r][i + 1];
                if (!u.is_number_integer()) fail(ringWhere + ": texture vertex index must be an integer");
                const long long ui = u.get<long long>();
                if (ui < 0 || static_cast<std::size_t>(ui) >= _uvs.size())
                    fail(ringWhere + ": texture vertex index " + std::to_string(ui) + " out of range (" +
                         std::to_string(_uvs.size()) + " texture vertices)");
                uvs.push_back(_uvs[static_cast<std::size_t>(ui)]);
            }
        }
        poly.rings.push_back(std::move(pts));
        if (textureIndex >= 0) poly.uvs.push_back(std::move(uvs));
    }
    if (textureIndex >= 0 && !texture(textureIndex))
    {
        textureIndex = -1; // missing image: untextured with its material (warned once per file)
        poly.uvs.clear();
    }
    checkCrossings(poly, where);
    Bin& bin = binFor(od, Bin::TRIANGLES, name.empty() ? "Surface" : name, material, textureIndex);
    if (triangulate(poly, bin))
        od.produced = true;
    else
        ++_skippedPolygons;
}

void Builder::addSurfaces(ObjectData& od, const json& boundaries, const json* sem, const json* semSurfaces,
                          const json* mat, int matConstant, const json* tex, int depth,
                          const std::string& where, const VertexSource& vs)
{
    requireArray(boundaries, where);
    for (const json* values : {sem, mat, tex})
        if (values && !values->is_null() && !values->is_array())
            fail(where + ": semantics/material/texture values must be arrays (found " + values->dump() + ")");
    for (std::size_t i = 0; i < boundaries.size(); ++i)
    {
        const std::string w = where +
                              (depth == 0   ? " surface "
                               : depth == 1 ? " shell "
                                            : " solid ") +
                              std::to_string(i);
        if (depth > 0)
            addSurfaces(od, boundaries[i], element(sem, i), semSurfaces, element(mat, i), matConstant,
                        element(tex, i), depth - 1, w, vs);
        else
        {
            json constant;
            const json* m = element(mat, i);
            if (matConstant >= 0)
            {
                constant = matConstant;
                m = &constant;
            }
            addSurface(od, boundaries[i], element(sem, i), semSurfaces, _materials ? m : nullptr,
                       element(tex, i), w, vs);
        }
    }
}

void Builder::processGeometry(ObjectData& od, const json& g, const std::string& where, const VertexSource& vs)
{
    const std::string type = g["type"].get<std::string>();
    if (type == "GeometryInstance")
    {
        if (!_templates) fail(where + ": GeometryInstance but no \"geometry-templates\"");
        auto ti = g.find("template");
        if (ti == g.end() || !ti->is_number_integer())
            fail(where + ": GeometryInstance lacks a \"template\" index");
        const long long t = ti->get<long long>();
        if (t < 0 || static_cast<std::size_t>(t) >= _templates->size())
            fail(where + ": template index " + std::to_string(t) + " out of range (" +
                 std::to_string(_templates->size()) + " templates)");
        auto b = g.find("boundaries");
        if (b == g.end()) fail(where + ": missing \"boundaries\"");
        requireArray(*b, where + ": \"boundaries\"");
        if (b->size() != 1)
            fail(where + ": GeometryInstance \"boundaries\" must hold exactly one reference vertex");
        VertexSource inst;
        inst.vertices = &_templateVertices;
        inst.instance = true;
        inst.what = "template vertex";
        inst.reference = vertex((*b)[0], where + " reference point", vs);
        auto mit = g.find("transformationMatrix");
        if (mit == g.end() || !mit->is_array() || mit->size() != 16)
            fail(where + ": \"transformationMatrix\" must be an array of 16 numbers");
        for (std::size_t k = 0; k < 16; ++k)
        {
            if (!(*mit)[k].is_number())
                fail(where + ": \"transformationMatrix\" must be an array of 16 numbers");
            inst.m[k] = (*mit)[k].get<double>();
            if (!std::isfinite(inst.m[k])) fail(where + ": non-finite value in \"transformationMatrix\"");
        }
        const json& tmpl = (*_templates)[static_cast<std::size_t>(t)];
        if (!tmpl.is_object() || !tmpl.contains("type") || !tmpl["type"].is_string() ||
            tmpl["type"] == "GeometryInstance")
            fail(where + ": template " + std::to_string(t) + " is not a geometry");
        processGeometry(od, tmpl, where + " (template " + std::to_string(t) + ")", inst);
        return;
    }

    auto b = g.find("boundaries");
    if (b == g.end()) fail(where + ": missing \"boundaries\"");
    const json& boundaries = requireArray(*b, where + ": \"boundaries\"");
    if (boundaries.empty())
    {
        warn(where + " has empty \"boundaries\"; skipped");
        return;
    }

    const json* semValues = nullptr;
    const json* semSurfaces = nullptr;
    if (g.contains("semantics") && g["semantics"].is_object())
    {
        const json& s = g["semantics"];
        if (s.contains("values")) semValues = &s["values"];
        if (s.contains("surfaces"))
            semSurfaces = &requireArray(s["surfaces"], where + ": \"semantics.surfaces\"");
    }
    const json* matValues = nullptr;
    int matConstant = -1;
    if (!_materialTheme.empty() && g.contains("material") && g["material"].is_object() &&
        g["material"].contains(_materialTheme))
    {
        const json& m = g["material"][_materialTheme];
        if (m.contains("values"))
            matValues = &m["values"];
        else if (m.contains("value") && !m["value"].is_null())
            matConstant = materialIndex(&m["value"], where);
    }
    const json* texValues = nullptr;
    if (!_textureTheme.empty() && g.contains("texture") && g["texture"].is_object() &&
        g["texture"].contains(_textureTheme) && g["texture"][_textureTheme].is_object() &&
        g["texture"][_textureTheme].contains("values"))
        texValues = &g["texture"][_textureTheme]["values"];

    if (type == "MultiSurface" || type == "CompositeSurface")
        addSurfaces(od, boundaries, semValues, semSurfaces, matValues, matConstant, texValues, 0, where, vs);
    else if (type == "Solid")
        addSurfaces(od, boundaries, semValues, semSurfaces, matValues, matConstant, texValues, 1, where, vs);
    else if (type == "MultiSolid" || type == "CompositeSolid")
        addSurfaces(od, boundaries, semValues, semSurfaces, matValues, matConstant, texValues, 2, where, vs);
    else if (type == "MultiLineString")
    {
        for (std::size_t i = 0; i < boundaries.size(); ++i)
        {
            const std::string w = where + " line string " + std::to_string(i);
            const json& line = requireArray(boundaries[i], w);
            const std::string name = semanticName(element(semValues, i), semSurfaces, w);
            std::vector<osg::Vec3d> pts;
            for (const json& idx : line)
            {
                const osg::Vec3d p = vertex(idx, w, vs);
                if (pts.empty() || pts.back() != p) pts.push_back(p);
            }
            if (pts.size() < 2)
            {
                ++_skippedPolygons;
                continue;
            }
            Bin& bin = binFor(od, Bin::LINES, name.empty() ? "MultiLineString" : name, -1, -1);
            bin.strips.emplace_back(static_cast<unsigned>(bin.positions.size()),
                                    static_cast<unsigned>(pts.size()));
            bin.positions.insert(bin.positions.end(), pts.begin(), pts.end());
            od.produced = true;
        }
    }
    else if (type == "MultiPoint")
    {
        for (std::size_t i = 0; i < boundaries.size(); ++i)
        {
            const std::string w = where + " point " + std::to_string(i);
            const std::string name = semanticName(element(semValues, i), semSurfaces, w);
            Bin& bin = binFor(od, Bin::POINTS, name.empty() ? "MultiPoint" : name, -1, -1);
            bin.positions.push_back(vertex(boundaries[i], w, vs));
            od.produced = true;
        }
    }
    else
        warn(where + ": unknown geometry type \"" + type + "\"; skipped");
}

void Builder::processObject(ObjectData& od)
{
    const json& obj = *od.object;
    auto git = obj.find("geometry");
    if (git == obj.end() || git->is_null()) return;
    const json& geoms = requireArray(*git, "\"geometry\" of object " + inQuotes(od.id));
    if (geoms.empty()) return;
    od.hasGeometry = true;

    struct Candidate
    {
        const json* g;
        bool hasLod;
        float lod;
    };
    std::vector<Candidate> candidates;
    for (std::size_t i = 0; i < geoms.size(); ++i)
    {
        const json& g = geoms[i];
        const std::string where = "object " + inQuotes(od.id) + " geometry " + std::to_string(i);
        if (!g.is_object() || !g.contains("type") || !g["type"].is_string())
            fail(where + " must be an object with a \"type\"");
        Candidate c{&g, false, -1.0f};
        std::string text;
        const json* lodSource = &g;
        if (g["type"] == "GeometryInstance" && !g.contains("lod") && _templates && g.contains("template") &&
            g["template"].is_number_integer())
        {
            const long long t = g["template"].get<long long>();
            if (t >= 0 && static_cast<std::size_t>(t) < _templates->size())
                lodSource = &(*_templates)[static_cast<std::size_t>(t)];
        }
        if (lodSource->is_object()) c.hasLod = lodOf(*lodSource, text, c.lod);
        candidates.push_back(c);
    }

    float chosen = -1.0f;
    bool any = false;
    if (!_settings.lod.empty())
    {
        chosen = _requestedLod;
        for (const Candidate& c : candidates)
            any = any || (c.hasLod && std::abs(c.lod - chosen) < 1e-4f);
    }
    else
    {
        for (const Candidate& c : candidates)
            if (c.hasLod && (!any || c.lod > chosen))
            {
                chosen = c.lod;
                any = true;
            }
    }
    for (std::size_t i = 0; i < candidates.size(); ++i)
    {
        const Candidate& c = candidates[i];
        const bool selected =
            any ? (c.hasLod && std::abs(c.lod - chosen) < 1e-4f) : (_settings.lod.empty() && !c.hasLod);
        if (!selected) continue;
        od.lod = c.hasLod ? c.lod : -1.0f;
        const std::string where = "object " + inQuotes(od.id) + " geometry " + std::to_string(i);
        VertexSource vs;
        vs.vertices = &_vertices;
        processGeometry(od, *c.g, where, vs);
    }
}

void Builder::checkCrossings(const Polygon& poly, const std::string& where) const
{
    std::size_t n = 0;
    for (const auto& ring : poly.rings)
        n += ring.size();
    if (n < 16 || poly.rings.empty() || poly.rings.front().size() < 3) return; // too small to be costly
    // Projected along the axis the outer ring's normal is closest to.
    const osg::Vec3d normal = newellNormal(poly.rings.front());
    const double ax = std::abs(normal.x()), ay = std::abs(normal.y()), az = std::abs(normal.z());
    std::vector<std::vector<osg::Vec2d>> rings;
    for (const auto& ring : poly.rings)
    {
        std::vector<osg::Vec2d> r;
        r.reserve(ring.size());
        for (const osg::Vec3d& p : ring)
            r.push_back(az >= ax && az >= ay ? osg::Vec2d(p.x(), p.y())
                        : ay >= ax           ? osg::Vec2d(p.x(), p.z())
                                             : osg::Vec2d(p.y(), p.z()));
        rings.push_back(std::move(r));
    }
    const unsigned limit = _settings.limits.maxCrossings;
    const osgLoA::PolygonCrossings c = osgLoA::PolygonCrossings::count(rings, limit + 1, 64 * n + 100000);
    if (c.tooMany || c.tooComplex)
        throw osgLoA::InputLimitError(osgLoA::InputLimits::exceeded(
            _source,
            where + ": a polygon of " + std::to_string(n) + " vertices whose edges cross " +
                (c.tooMany ? "more than " + std::to_string(limit) + " times" : "too often to count"),
            "max-crossings", limit));
}

void Builder::checkHierarchy() const
{
    // The longest chain of "children" edges (cycles cut where they close), iteratively: the later
    // recursive passes (computeKept, place) then go at most max-hierarchy deep.
    const unsigned limit = _settings.limits.maxHierarchy;
    std::vector<unsigned> height(_objects.size(), 0);
    std::vector<char> state(_objects.size(), 0);            // 0 new, 1 on the stack, 2 done
    std::vector<std::pair<std::size_t, std::size_t>> stack; // (object, next child)
    for (std::size_t root = 0; root < _objects.size(); ++root)
    {
        if (state[root]) continue;
        stack.emplace_back(root, 0);
        state[root] = 1;
        while (!stack.empty())
        {
            auto& [i, next] = stack.back();
            const std::vector<std::size_t>& children = _objects[i].children;
            if (next < children.size())
            {
                const std::size_t c = children[next++];
                if (state[c] == 0)
                {
                    state[c] = 1;
                    stack.emplace_back(c, 0);
                    if (stack.size() > limit + 1u)
                        throw osgLoA::InputLimitError(osgLoA::InputLimits::exceeded(
                            _source,
                            "a chain of more than " + std::to_string(limit) + " nested city objects (from " +
                                inQuotes(_objects[stack.front().first].id) + ")",
                            "max-hierarchy", limit));
                }
                else if (state[c] == 2)
                {
                    height[i] = std::max(height[i], height[c] + 1);
                    if (height[i] + stack.size() > limit + 1u)
                        throw osgLoA::InputLimitError(osgLoA::InputLimits::exceeded(
                            _source,
                            "a chain of more than " + std::to_string(limit) + " nested city objects (at " +
                                inQuotes(_objects[i].id) + ")",
                            "max-hierarchy", limit));
                }
                continue;
            }
            state[i] = 2;
            const std::size_t done = i;
            stack.pop_back();
            if (!stack.empty())
                height[stack.back().first] = std::max(height[stack.back().first], height[done] + 1);
        }
    }
}

bool Builder::computeKept(std::size_t i, std::set<std::size_t>& visiting)
{
    ObjectData& od = _objects[i];
    if (od.kept >= 0) return od.kept == 1;
    if (!visiting.insert(i).second) return false; // a cycle: decided by its first member
    bool childKept = false;
    for (std::size_t c : od.children)
        childKept = computeKept(c, visiting) || childKept;
    visiting.erase(i);
    const bool self = od.produced || (!od.hasGeometry && (_settings.lod.empty() || childKept));
    od.kept = (self || childKept) ? 1 : 0;
    if (!od.kept)
    {
        if (!_settings.lod.empty() && !od.produced)
            ++_omittedObjects;
        else
        {
            ++_skippedObjects;
            warn("object " + inQuotes(od.id) + " has no usable geometry; skipped");
        }
    }
    return od.kept == 1;
}

osg::Texture2D* Builder::texture(int index)
{
    auto it = _textureCache.find(index);
    if (it != _textureCache.end()) return it->second.get();
    osg::ref_ptr<osg::Texture2D> tex;
    const json& t = (*_textures)[static_cast<std::size_t>(index)];
    if (!t.is_object() || !t.contains("image") || !t["image"].is_string())
        fail("texture " + std::to_string(index) + " lacks an \"image\" file name");
    const std::string name = t["image"].get<std::string>();
    std::string path;
    if (!osgDB::isAbsolutePath(name))
    {
        for (const std::string& dir : _textureDirs)
        {
            const std::string candidate = osgDB::concatPaths(dir, name);
            if (osgDB::fileExists(candidate))
            {
                path = candidate;
                break;
            }
        }
    }
    else if (osgDB::fileExists(name))
        path = name;
    if (path.empty() && !osgDB::isAbsolutePath(name)) path = osgDB::findDataFile(name, _options);
    osg::ref_ptr<osg::Image> image = path.empty() ? nullptr : osgDB::readRefImageFile(path, _options);
    if (!image)
    {
        // The first three are named; the rest are counted in one line at the end (a model that
        // ships without its texture folder would otherwise print one line per image).
        if (++_missingTextures <= 3)
            warn(std::string("texture file \"") + name + "\" " +
                 (path.empty() ? "not found" : "could not be read") +
                 "; its surfaces are drawn untextured with their material");
    }
    else
    {
        if (image->getFileName().empty()) image->setFileName(path);
        tex = new osg::Texture2D(image.get());
        tex->setName(name);
        osg::Texture::WrapMode wrap = osg::Texture::REPEAT;
        const std::string mode = t.contains("wrapMode") && t["wrapMode"].is_string()
                                     ? t["wrapMode"].get<std::string>()
                                     : std::string("wrap");
        if (mode == "mirror")
            wrap = osg::Texture::MIRROR;
        else if (mode == "clamp")
            wrap = osg::Texture::CLAMP_TO_EDGE;
        else if (mode == "border" || mode == "none")
        {
            wrap = osg::Texture::CLAMP_TO_BORDER;
            osg::Vec4d border(0, 0, 0, 0);
            if (mode == "border" && t.contains("borderColor") && t["borderColor"].is_array() &&
                t["borderColor"].size() == 4)
                for (unsigned k = 0; k < 4; ++k)
                    if (t["borderColor"][k].is_number()) border[k] = t["borderColor"][k].get<double>();
            tex->setBorderColor(border);
        }
        tex->setWrap(osg::Texture::WRAP_S, wrap);
        tex->setWrap(osg::Texture::WRAP_T, wrap);
        tex->setFilter(osg::Texture::MIN_FILTER, osg::Texture::LINEAR_MIPMAP_LINEAR);
        tex->setFilter(osg::Texture::MAG_FILTER, osg::Texture::LINEAR);
    }
    _textureCache[index] = tex;
    return tex.get();
}

osg::StateSet* Builder::stateSet(int material, int tex)
{
    if (material < 0 && tex < 0) return nullptr;
    osg::ref_ptr<osg::StateSet>& ss = _stateSets[std::make_pair(material, tex)];
    if (ss.valid()) return ss.get();
    ss = new osg::StateSet;
    if (material >= 0)
    {
        const json& m = (*_materials)[static_cast<std::size_t>(material)];
        auto number = [&](const char* key, double fallback)
        { return m.is_object() && m.contains(key) && m[key].is_number() ? m[key].get<double>() : fallback; };
        auto colour = [&](const char* key, const osg::Vec3d& fallback)
        {
            if (!m.is_object() || !m.contains(key)) return fallback;
            const json& c = m[key];
            if (!c.is_array() || c.size() != 3 || !c[0].is_number() || !c[1].is_number() || !c[2].is_number())
                return fallback;
            return osg::Vec3d(c[0].get<double>(), c[1].get<double>(), c[2].get<double>());
        };
        // X3D defaults, as CityJSON (and CityGML) take them.
        const osg::Vec3d diffuse = colour("diffuseColor", osg::Vec3d(0.8, 0.8, 0.8));
        const double ambient = number("ambientIntensity", 0.2);
        const osg::Vec3d emissive = colour("emissiveColor", osg::Vec3d(0, 0, 0));
        const osg::Vec3d specular = colour("specularColor", osg::Vec3d(0, 0, 0));
        const double shininess = std::min(1.0, std::max(0.0, number("shininess", 0.2)));
        const double alpha = 1.0 - std::min(1.0, std::max(0.0, number("transparency", 0.0)));
        osg::ref_ptr<osg::Material> mat = new osg::Material;
        if (m.is_object() && m.contains("name") && m["name"].is_string())
            mat->setName(m["name"].get<std::string>());
        const float a = static_cast<float>(alpha);
        mat->setDiffuse(osg::Material::FRONT_AND_BACK, osg::Vec4(osg::Vec3(diffuse), a));
        mat->setAmbient(osg::Material::FRONT_AND_BACK, osg::Vec4(osg::Vec3(diffuse * ambient), a));
        mat->setEmission(osg::Material::FRONT_AND_BACK, osg::Vec4(osg::Vec3(emissive), a));
        mat->setSpecular(osg::Material::FRONT_AND_BACK, osg::Vec4(osg::Vec3(specular), a));
        mat->setShininess(osg::Material::FRONT_AND_BACK, static_cast<float>(shininess * 128.0));
        ss->setAttributeAndModes(mat.get(), osg::StateAttribute::ON);
        if (alpha < 1.0)
        {
            ss->setAttributeAndModes(new osg::BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA),
                                     osg::StateAttribute::ON);
            ss->setRenderingHint(osg::StateSet::TRANSPARENT_BIN);
        }
    }
    if (tex >= 0) ss->setTextureAttributeAndModes(0, texture(tex), osg::StateAttribute::ON);
    return ss.get();
}

osg::ref_ptr<osg::Geometry> Builder::makeGeometry(const Bin& bin, const osg::Vec3d& origin)
{
    osg::ref_ptr<osg::Geometry> geom = new osg::Geometry;
    geom->setName(bin.name);
    geom->setUseDisplayList(false);
    geom->setUseVertexBufferObjects(true);
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    v->reserve(bin.positions.size());
    for (const osg::Vec3d& p : bin.positions)
        v->push_back(osg::Vec3(p - origin));
    geom->setVertexArray(v.get());
    const GLsizei n = static_cast<GLsizei>(v->size());
    if (bin.kind == Bin::TRIANGLES)
    {
        geom->setNormalArray(new osg::Vec3Array(bin.normals.begin(), bin.normals.end()),
                             osg::Array::BIND_PER_VERTEX);
        if (!bin.uvs.empty())
            geom->setTexCoordArray(0, new osg::Vec2Array(bin.uvs.begin(), bin.uvs.end()),
                                   osg::Array::BIND_PER_VERTEX);
        geom->addPrimitiveSet(new osg::DrawArrays(GL_TRIANGLES, 0, n));
    }
    else if (bin.kind == Bin::LINES)
    {
        for (const auto& s : bin.strips)
            geom->addPrimitiveSet(new osg::DrawArrays(GL_LINE_STRIP, static_cast<GLint>(s.first),
                                                      static_cast<GLsizei>(s.second)));
    }
    else
        geom->addPrimitiveSet(new osg::DrawArrays(GL_POINTS, 0, n));
    if (osg::StateSet* ss = stateSet(bin.material, bin.texture)) geom->setStateSet(ss);
    return geom;
}

void Builder::setAttributes(osg::Node& node, const json& attributes) const
{
    if (!attributes.is_object()) return;
    for (auto it = attributes.begin(); it != attributes.end(); ++it)
    {
        const std::string key = "cityjson." + it.key();
        const json& v = it.value();
        if (v.is_number())
            node.setUserValue(key, v.get<double>());
        else if (v.is_string())
            node.setUserValue(key, v.get<std::string>());
        else if (v.is_boolean())
            node.setUserValue(key, v.get<bool>());
        else
            node.setUserValue(key, v.dump());
    }
}

void Builder::place(std::size_t i, osg::Group& parent, std::set<std::size_t>& placed)
{
    ObjectData& od = _objects[i];
    if (od.kept != 1 || !placed.insert(i).second) return;
    parent.addChild(od.group.get());
    for (std::size_t c : od.children)
        if (_objects[c].placedUnder == static_cast<long>(i)) place(c, *od.group, placed);
}

osg::ref_ptr<osg::Group> Builder::build()
{
    checkVersion();
    auto oit = _doc.find("CityObjects");
    if (oit == _doc.end()) fail("missing \"CityObjects\"");
    if (!oit->is_object())
        fail("\"CityObjects\" must be an object (found " + std::string(oit->type_name()) + ")");
    readVertices();
    readAppearance();
    if (!_settings.lod.empty()) _requestedLod = std::strtof(_settings.lod.c_str(), nullptr);
    chooseThemes();

    const json& objects = *oit;
    if (objects.size() > _settings.limits.maxObjects)
        throw osgLoA::InputLimitError(
            osgLoA::InputLimits::exceeded(_source, std::to_string(objects.size()) + " city objects",
                                          "max-objects", _settings.limits.maxObjects));
    for (auto it = objects.begin(); it != objects.end(); ++it)
    {
        if (!it->is_object()) fail("object " + inQuotes(it.key()) + " must be a JSON object");
        if (!it->contains("type") || !(*it)["type"].is_string())
            fail("object " + inQuotes(it.key()) + " lacks a \"type\"");
        ObjectData od;
        od.id = it.key();
        od.object = &*it;
        od.type = (*it)["type"].get<std::string>();
        _byId[od.id] = _objects.size();
        _objects.push_back(std::move(od));
    }
    // Parent/child edges from both sides; a child is placed under the first parent naming it.
    auto link = [&](std::size_t parent, std::size_t child)
    {
        ObjectData& p = _objects[parent];
        if (parent == child || std::find(p.children.begin(), p.children.end(), child) != p.children.end())
            return;
        p.children.push_back(child);
        if (_objects[child].placedUnder < 0) _objects[child].placedUnder = static_cast<long>(parent);
    };
    for (std::size_t i = 0; i < _objects.size(); ++i)
    {
        const json& obj = *_objects[i].object;
        for (const char* key : {"children", "parents"})
        {
            if (!obj.contains(key)) continue;
            const json& list =
                requireArray(obj[key], "\"" + std::string(key) + "\" of object " + inQuotes(_objects[i].id));
            for (const json& ref : list)
            {
                auto found = ref.is_string() ? _byId.find(ref.get<std::string>()) : _byId.end();
                if (found == _byId.end())
                {
                    warn("object " + inQuotes(_objects[i].id) + " names " + ref.dump() + " in \"" + key +
                         "\", which does not exist");
                    continue;
                }
                if (std::string(key) == "children")
                    link(i, found->second);
                else
                    link(found->second, i);
            }
        }
    }

    checkHierarchy();
    for (ObjectData& od : _objects)
        processObject(od);
    std::set<std::size_t> visiting;
    for (std::size_t i = 0; i < _objects.size(); ++i)
        computeKept(i, visiting);
    unsigned keptCount = 0;
    osg::BoundingBoxd box;
    for (const ObjectData& od : _objects)
        if (od.kept == 1)
        {
            ++keptCount;
            for (const Bin& b : od.bins)
                for (const osg::Vec3d& p : b.positions)
                    box.expandBy(p);
        }
    if (!_objects.empty() && keptCount == 0)
    {
        if (!_settings.lod.empty())
            fail("no object has LoD " + _settings.lod + " (" + std::to_string(_objects.size()) + " objects)");
        fail("no usable geometry: all " + std::to_string(_objects.size()) +
             " objects are empty or degenerate");
    }

    const osg::Vec3d origin = (_settings.recenter && box.valid()) ? box.center() : osg::Vec3d();
    unsigned nextId = 1;
    for (ObjectData& od : _objects)
    {
        if (od.kept != 1) continue;
        od.group = new osg::Group;
        od.group->setName(od.id);
        static const json none;
        const json& attributes = od.object->contains("attributes") ? (*od.object)["attributes"] : none;
        const TypeMapping m = mapType(od.type, attributes);
        osgLoA::Feature* f =
            osgLoA::Feature::attach(*od.group, new osgLoA::Feature(nextId++, m.type, m.subType, m.source));
        f->setSourceId(od.id);
        f->setSourceType(od.type);
        f->setLod(od.lod);
        // The name a map prints: CityJSON has no standard attribute for it; "name" is the one
        // the specification's examples and 3DBAG-like data use.
        if (attributes.is_object() && attributes.contains("name") && attributes["name"].is_string())
            f->setLabel(attributes["name"].get<std::string>());
        setAttributes(*od.group, attributes);
        if (!od.bins.empty())
        {
            osg::ref_ptr<osg::Geode> geode = new osg::Geode;
            for (const Bin& b : od.bins)
                if (!b.positions.empty()) geode->addDrawable(makeGeometry(b, origin));
            od.group->addChild(geode.get());
        }
    }

    osg::ref_ptr<osg::Group> root = new osg::Group;
    std::set<std::size_t> placed;
    for (std::size_t i = 0; i < _objects.size(); ++i)
        if (_objects[i].placedUnder < 0 ||
            _objects[static_cast<std::size_t>(_objects[i].placedUnder)].kept != 1)
            place(i, *root, placed);
    for (std::size_t i = 0; i < _objects.size(); ++i)
        if (_objects[i].kept == 1 && !placed.count(i))
        {
            warn("object " + inQuotes(_objects[i].id) +
                 " is part of a parent/child cycle; placed at the top level");
            place(i, *root, placed);
        }

    std::string crs;
    if (_doc.contains("metadata") && _doc["metadata"].is_object() &&
        _doc["metadata"].contains("referenceSystem") && _doc["metadata"]["referenceSystem"].is_string())
        crs = _doc["metadata"]["referenceSystem"].get<std::string>();
    root->setUserValue("loa.origin", origin);
    root->setUserValue("loa.crs", crs);
    root->setUserValue("cityjson.version", _version);
    root->setUserValue("cityjson.materialTheme", _materialTheme);
    root->setUserValue("cityjson.textureTheme", _textureTheme);
    root->setUserValue("cityjson.skippedPolygons", _skippedPolygons);
    root->setUserValue("cityjson.omittedObjects", _omittedObjects);
    root->setUserValue("cityjson.skippedObjects", _skippedObjects);
    root->setUserValue("cityjson.missingTextures", _missingTextures);
    if (_missingTextures > 3)
        warn(std::to_string(_missingTextures) +
             " texture files are missing in all (the first 3 are named above); " +
             "their surfaces are drawn untextured with their material");
    if (_skippedPolygons)
        OSG_INFO << "cityjson: " << _source << ": skipped " << _skippedPolygons << " degenerate polygons"
                 << std::endl;
    if (_omittedObjects)
        OSG_NOTICE << "cityjson: " << _source << ": " << _omittedObjects << " objects have no LoD "
                   << _settings.lod << " and were omitted" << std::endl;
    osgLoA::FeatureIndex(*root).updateBounds();
    return root;
}

} // namespace

void Settings::parse(const std::string& optionString)
{
    std::istringstream in(optionString);
    for (std::string token; in >> token;)
    {
        const std::size_t eq = token.find('=');
        if (eq == std::string::npos) continue;
        const std::string key = token.substr(0, eq), value = token.substr(eq + 1);
        if (key == "recenter")
        {
            if (value == "0" || value == "false" || value == "off")
                recenter = false;
            else if (value == "1" || value == "true" || value == "on")
                recenter = true;
            else
                throw Error("option recenter=" + value + ": expected 0 or 1");
        }
        else if (key == "lod")
        {
            char* end = nullptr;
            const float v = std::strtof(value.c_str(), &end);
            if (value.empty() || *end != '\0' || !std::isfinite(v) || v < 0.0f)
                throw Error("option lod=" + value + ": expected a LoD such as 2 or 2.2");
            lod = value;
        }
        else if (key == "theme")
            theme = value;
    }
    try
    {
        limits = osgLoA::InputLimits::fromOptions(optionString);
    }
    catch (const std::invalid_argument& e)
    {
        throw Error(e.what());
    }
}

namespace
{
/** nlohmann's DOM builder with the limits checked as it goes: containers open at most
 *  max-depth deep where a value is read, strings and keys at most max-string bytes. (The
 *  callback parser did this before, but after every object it ends it scans the object around
 *  it for discarded entries: "CityObjects" of n entries took n^2/2 steps.) */
class LimitedDomBuilder
{
public:
    LimitedDomBuilder(Json& result, const std::string& source, const osgLoA::InputLimits& limits)
        : _dom(result, true), _source(source), _limits(limits)
    {
    }
    bool null() { return value() && _dom.null(); }
    bool boolean(bool b) { return value() && _dom.boolean(b); }
    bool number_integer(Json::number_integer_t v) { return value() && _dom.number_integer(v); }
    bool number_unsigned(Json::number_unsigned_t v) { return value() && _dom.number_unsigned(v); }
    bool number_float(Json::number_float_t v, const Json::string_t& text)
    {
        return value() && _dom.number_float(v, text);
    }
    bool string(Json::string_t& v) { return value() && sized(v) && _dom.string(v); }
    bool binary(Json::binary_t& v) { return value() && _dom.binary(v); }
    bool key(Json::string_t& v) { return value() && sized(v) && _dom.key(v); }
    bool start_object(std::size_t n)
    {
        value();
        ++_open;
        return _dom.start_object(n);
    }
    bool end_object()
    {
        --_open;
        return _dom.end_object();
    }
    bool start_array(std::size_t n)
    {
        value();
        ++_open;
        return _dom.start_array(n);
    }
    bool end_array()
    {
        --_open;
        return _dom.end_array();
    }
    bool parse_error(std::size_t position, const std::string& token, const nlohmann::detail::exception& e)
    {
        return _dom.parse_error(position, token, e);
    }

private:
    nlohmann::detail::json_sax_dom_parser<Json> _dom;
    const std::string& _source;
    const osgLoA::InputLimits& _limits;
    std::size_t _open = 0; ///< containers open

    bool value() const
    {
        if (_open > _limits.maxDepth)
            throw osgLoA::InputLimitError(osgLoA::InputLimits::exceeded(
                _source, "JSON nested deeper than " + std::to_string(_limits.maxDepth) + " levels",
                "max-depth", _limits.maxDepth));
        return true;
    }
    bool sized(const Json::string_t& v) const
    {
        if (v.size() > _limits.maxStringBytes)
            throw osgLoA::InputLimitError(
                osgLoA::InputLimits::exceeded(_source, "a string of " + std::to_string(v.size()) + " bytes",
                                              "max-string", _limits.maxStringBytes));
        return true;
    }
};
} // namespace

Json parseJson(std::istream& in, const std::string& source, const osgLoA::InputLimits& limits)
{
    Json result;
    LimitedDomBuilder builder(result, source, limits);
    Json::sax_parse(in, &builder);
    return result;
}

osg::ref_ptr<osg::Group> buildScene(const Json& doc, const std::string& sourceName, const Settings& settings,
                                    const osgDB::FilePathList& textureDirs, const osgDB::Options* options)
{
    try
    {
        return Builder(doc, sourceName, settings, textureDirs, options).build();
    }
    catch (const nlohmann::json::exception& e)
    {
        throw Error(sourceName + ": malformed CityJSON: " + e.what());
    }
}

} // namespace loacityjson
