#include "OsmScene.h"

#include <osgLoA/city/CityTextures>
#include <osgLoA/semantics/Feature>
#include <osgLoA/semantics/FeatureIndex>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Notify>
#include <osg/PolygonOffset>
#include <osg/TriangleIndexFunctor>
#include <osg/ValueObject>
#include <osgUtil/Tessellator>

#include <cpl_conv.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <proj.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace osmimport
{

void ImportOptions::parse(const std::string& text, std::vector<std::string>& unknown)
{
    std::istringstream in(text);
    for (std::string word; in >> word;)
    {
        const std::size_t eq = word.find('=');
        const std::string key = word.substr(0, eq),
                          value = eq == std::string::npos ? "" : word.substr(eq + 1);
        auto number = [&](double& target, double lo)
        {
            double v = 0.0;
            if (!parseNumber(value, v) || v < lo)
                throw std::invalid_argument("option " + key + "='" + value +
                                            "' is not a number >= " + std::to_string(lo));
            target = v;
        };
        if (key == "storey")
            number(storey, 0.1);
        else if (key == "defaultHeight")
            number(defaultHeight, 0.1);
        else if (key == "margin")
            number(margin, 0.0);
        else if (key == "terrainCell")
            number(terrainCell, 0.0);
        else if (key == "miterLimit")
            number(miterLimit, 1.0);
        else if (key == "terrain")
        {
            if (value != "on" && value != "off" && value != "true" && value != "false" && value != "1" &&
                value != "0")
                throw std::invalid_argument("option terrain='" + value + "' is not on/off");
            terrain = value == "on" || value == "true" || value == "1";
        }
        else if (key == "dem")
        {
            if (value.empty()) throw std::invalid_argument("option dem= needs a file name");
            dem = value;
        }
        else
            unknown.push_back(word);
    }
}

namespace
{
using osgLoA::Feature;
using osgLoA::FeatureType;

// Heights above the ground of draped layers, so that they do not z-fight (with a polygon
// offset on top): green under water under roads.
constexpr double kLiftGreen = 0.10, kLiftWater = 0.15, kLiftRoadMinor = 0.20, kLiftRoadMajor = 0.25;
constexpr double kRoofTile = 8.0, kGroundTile = 25.0, kGreenTile = 15.0, kWaterTile = 30.0;
constexpr double kFacadeStorey = 3.2; // CityTextures: one storey of a facade tile
// Plausibility bounds of tag values: the tallest building is 828 m, the widest roads and rivers
// of a street map are a few hundred metres (wider ones are mapped as areas).
constexpr double kMaxHeight = 1000.0, kMaxWidth = 1000.0;

// --- ground ---------------------------------------------------------------------------------
class Ground
{
public:
    virtual ~Ground() = default;
    virtual double height(double x, double y) const = 0;
    virtual const char* kind() const = 0;
};

class FlatGround : public Ground
{
public:
    double height(double, double) const override { return 0.0; }
    const char* kind() const override { return "ground"; }
};

/** Heights sampled bilinearly between pixel centres of a DEM's first band, in the DEM's CRS. */
class DemGround : public Ground
{
public:
    DemGround(const std::string& path, const OGRSpatialReference& local)
    {
        // The raster drivers: nothing else registers them since the OSM data is read with
        // libosmium (without this, every DEM failed with "No driver registered" outside the tests,
        // whose own GDAL calls had registered them). Idempotent and thread-safe.
        GDALAllRegister();
        GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_VERBOSE_ERROR));
        if (!ds)
            throw std::runtime_error("dem: cannot open '" + path + "' as a raster (" + CPLGetLastErrorMsg() +
                                     ")");
        if (ds->GetRasterCount() < 1) throw std::runtime_error("dem: '" + path + "' has no raster band");
        double gt[6];
        if (ds->GetGeoTransform(gt) != CE_None || !GDALInvGeoTransform(gt, _inv))
            throw std::runtime_error("dem: '" + path + "' has no usable geotransform");
        const OGRSpatialReference* srs = ds->GetSpatialRef();
        if (!srs || srs->IsEmpty())
            throw std::runtime_error("dem: '" + path + "' has no coordinate reference system");
        OGRSpatialReference demSrs(*srs);
        demSrs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        _toDem.reset(OGRCreateCoordinateTransformation(&local, &demSrs));
        if (!_toDem) throw std::runtime_error("dem: no transformation from the local frame to the DEM's CRS");
        _w = ds->GetRasterXSize();
        _h = ds->GetRasterYSize();
        if (static_cast<double>(_w) * _h > 64.0e6)
            throw std::runtime_error("dem: '" + path +
                                     "' is larger than 64 Mpixel; crop it to the area first");
        GDALRasterBand* band = ds->GetRasterBand(1);
        _data.resize(static_cast<std::size_t>(_w) * _h);
        if (band->RasterIO(GF_Read, 0, 0, _w, _h, _data.data(), _w, _h, GDT_Float64, 0, 0) != CE_None)
            throw std::runtime_error("dem: cannot read '" + path + "' (" + CPLGetLastErrorMsg() + ")");
        int hasNoData = 0;
        const double noData = band->GetNoDataValue(&hasNoData);
        double fallback = std::numeric_limits<double>::max();
        for (double& v : _data)
        {
            if (!std::isfinite(v) || (hasNoData && v == noData))
                v = std::numeric_limits<double>::quiet_NaN();
            else
                fallback = std::min(fallback, v);
        }
        if (fallback == std::numeric_limits<double>::max())
            throw std::runtime_error("dem: '" + path + "' holds no valid height");
        _fallback = fallback;
    }

    double height(double x, double y) const override
    {
        double X = x, Y = y;
        if (!_toDem->Transform(1, &X, &Y)) return _fallback;
        const double px = _inv[0] + X * _inv[1] + Y * _inv[2] - 0.5;
        const double py = _inv[3] + X * _inv[4] + Y * _inv[5] - 0.5;
        const double cx = std::clamp(px, 0.0, static_cast<double>(_w - 1));
        const double cy = std::clamp(py, 0.0, static_cast<double>(_h - 1));
        const int i0 = std::min(static_cast<int>(std::floor(cx)), std::max(0, _w - 2));
        const int j0 = std::min(static_cast<int>(std::floor(cy)), std::max(0, _h - 2));
        const int i1 = std::min(i0 + 1, _w - 1), j1 = std::min(j0 + 1, _h - 1);
        const double fx = _w > 1 ? cx - i0 : 0.0, fy = _h > 1 ? cy - j0 : 0.0;
        const double v[4] = {at(i0, j0), at(i1, j0), at(i0, j1), at(i1, j1)};
        const double wgt[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
        double sum = 0.0, wsum = 0.0;
        for (int k = 0; k < 4; ++k)
            if (!std::isnan(v[k]))
            {
                sum += v[k] * wgt[k];
                wsum += wgt[k];
            }
        return wsum > 1e-12 ? sum / wsum : _fallback;
    }
    const char* kind() const override { return "dem"; }

private:
    double at(int i, int j) const { return _data[static_cast<std::size_t>(j) * _w + i]; }

    std::unique_ptr<OGRCoordinateTransformation> _toDem;
    double _inv[6];
    int _w = 0, _h = 0;
    std::vector<double> _data;
    double _fallback = 0.0;
};

// --- plane geometry -------------------------------------------------------------------------
double signedArea(const Ring& r)
{
    double a = 0.0;
    for (std::size_t i = 0, n = r.size(); i < n; ++i)
    {
        const osg::Vec2d &p = r[i], &q = r[(i + 1) % n];
        a += p.x() * q.y() - q.x() * p.y();
    }
    return 0.5 * a;
}

/** Drops the closing node and repeated nodes; false when fewer than 3 nodes or less than 1 m^2
 *  remain (slivers of collinear nodes, as extracts cut them). */
bool cleanRing(Ring& r)
{
    Ring out;
    for (const osg::Vec2d& p : r)
        if (out.empty() || (p - out.back()).length() > 1e-4) out.push_back(p);
    while (out.size() > 1 && (out.front() - out.back()).length() <= 1e-4)
        out.pop_back();
    r.swap(out);
    return r.size() >= 3 && std::fabs(signedArea(r)) >= 1.0;
}

/** Drops repeated nodes; false when fewer than 2 nodes or no length remain. */
bool cleanLine(Ring& l)
{
    Ring out;
    for (const osg::Vec2d& p : l)
        if (out.empty() || (p - out.back()).length() > 1e-4) out.push_back(p);
    l.swap(out);
    return l.size() >= 2;
}

/** The name a map prints for an object: its `name` tag, else its `ref` (roads known by a
 *  number: "I 880"); empty when it has neither. */
std::string labelOf(const Tags& tags)
{
    const std::string& name = tag(tags, "name");
    return !name.empty() ? name : tag(tags, "ref");
}

/** Inserts nodes so that no segment is longer than step (step <= 0: unchanged). */
Ring densify(const Ring& r, double step, bool closed)
{
    if (step <= 0.0 || r.size() < 2) return r;
    Ring out;
    const std::size_t n = r.size(), segments = closed ? n : n - 1;
    for (std::size_t i = 0; i < segments; ++i)
    {
        const osg::Vec2d &a = r[i], &b = r[(i + 1) % n];
        const int k = std::max(1, static_cast<int>(std::ceil((b - a).length() / step)));
        for (int j = 0; j < k; ++j)
            out.push_back(a + (b - a) * (static_cast<double>(j) / k));
    }
    if (!closed) out.push_back(r.back());
    return out;
}

struct TriangleCollector
{
    std::vector<unsigned>* out = nullptr;
    void operator()(unsigned a, unsigned b, unsigned c) const
    {
        out->push_back(a);
        out->push_back(b);
        out->push_back(c);
    }
};

/** A plane triangulation: vertices and up-facing triangles. */
struct FlatMesh
{
    std::vector<osg::Vec2d> vertices;
    std::vector<unsigned> triangles;
};

/** Triangulates a polygon with holes (odd winding) with osgUtil::Tessellator. */
FlatMesh tessellate(const Polygon& polygon)
{
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    g->setVertexArray(v.get());
    for (const Ring& r : polygon)
    {
        const GLint first = static_cast<GLint>(v->size());
        for (const osg::Vec2d& p : r)
            v->push_back(osg::Vec3(static_cast<float>(p.x()), static_cast<float>(p.y()), 0));
        g->addPrimitiveSet(new osg::DrawArrays(GL_POLYGON, first, static_cast<GLsizei>(r.size())));
    }
    osg::ref_ptr<osgUtil::Tessellator> tess = new osgUtil::Tessellator;
    tess->setTessellationType(osgUtil::Tessellator::TESS_TYPE_GEOMETRY);
    tess->setWindingType(osgUtil::Tessellator::TESS_WINDING_ODD);
    tess->setBoundaryOnly(false);
    tess->setTessellationNormal(osg::Vec3(0, 0, 1));
    tess->retessellatePolygons(*g);

    FlatMesh mesh;
    const osg::Vec3Array* tv = dynamic_cast<const osg::Vec3Array*>(g->getVertexArray());
    if (!tv) return mesh;
    for (const osg::Vec3& p : *tv)
        mesh.vertices.push_back(osg::Vec2d(p.x(), p.y()));
    std::vector<unsigned> tris;
    osg::TriangleIndexFunctor<TriangleCollector> collect;
    collect.out = &tris;
    g->accept(collect);
    for (std::size_t t = 0; t + 2 < tris.size(); t += 3)
    {
        unsigned a = tris[t], b = tris[t + 1], c = tris[t + 2];
        if (a >= mesh.vertices.size() || b >= mesh.vertices.size() || c >= mesh.vertices.size()) continue;
        const osg::Vec2d ab = mesh.vertices[b] - mesh.vertices[a], ac = mesh.vertices[c] - mesh.vertices[a];
        const double cross = ab.x() * ac.y() - ab.y() * ac.x();
        if (std::fabs(cross) < 1e-9) continue;
        if (cross < 0) std::swap(b, c);
        mesh.triangles.insert(mesh.triangles.end(), {a, b, c});
    }
    return mesh;
}

// --- mesh assembly --------------------------------------------------------------------------
class Mesh
{
public:
    unsigned vertex(const osg::Vec3d& p, const osg::Vec3& n, const osg::Vec2& t)
    {
        _v->push_back(osg::Vec3(p));
        _n->push_back(n);
        _t->push_back(t);
        return static_cast<unsigned>(_v->size() - 1);
    }
    /** Adds the triangle so that it faces up (ground layers); drops degenerate ones. */
    void triangleUp(unsigned a, unsigned b, unsigned c)
    {
        const osg::Vec3 &pa = (*_v)[a], &pb = (*_v)[b], &pc = (*_v)[c];
        const osg::Vec3 n = (pb - pa) ^ (pc - pa);
        if (n.length2() < 1e-12f) return;
        if (n.z() < 0) std::swap(b, c);
        triangle(a, b, c);
    }
    void triangle(unsigned a, unsigned b, unsigned c)
    {
        _i->push_back(a);
        _i->push_back(b);
        _i->push_back(c);
    }
    bool empty() const { return _i->empty(); }
    unsigned size() const { return static_cast<unsigned>(_v->size()); }

    osg::ref_ptr<osg::Geometry> build(const std::string& name, const osg::Vec4* colour = nullptr)
    {
        osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
        g->setName(name);
        g->setUseVertexBufferObjects(true);
        g->setVertexArray(_v.get());
        g->setNormalArray(_n.get(), osg::Array::BIND_PER_VERTEX);
        g->setTexCoordArray(0, _t.get(), osg::Array::BIND_PER_VERTEX);
        osg::ref_ptr<osg::Vec4Array> c = new osg::Vec4Array;
        c->push_back(colour ? *colour : osg::Vec4(1, 1, 1, 1));
        g->setColorArray(c.get(), osg::Array::BIND_OVERALL);
        g->addPrimitiveSet(_i.get());
        return g;
    }

private:
    osg::ref_ptr<osg::Vec3Array> _v = new osg::Vec3Array;
    osg::ref_ptr<osg::Vec3Array> _n = new osg::Vec3Array;
    osg::ref_ptr<osg::Vec2Array> _t = new osg::Vec2Array;
    osg::ref_ptr<osg::DrawElementsUInt> _i = new osg::DrawElementsUInt(GL_TRIANGLES);
};

/** Shared state sets, one per texture. */
class StateSets
{
public:
    osg::StateSet* textured(const std::string& kind, bool draped = false)
    {
        const std::string key = draped ? kind + "#draped" : kind;
        auto it = _sets.find(key);
        if (it != _sets.end()) return it->second.get();
        osg::ref_ptr<osg::StateSet> ss = new osg::StateSet;
        ss->setName(kind);
        ss->setTextureAttributeAndModes(0, texture(kind), osg::StateAttribute::ON);
        if (draped) ss->setAttributeAndModes(new osg::PolygonOffset(-1.0f, -4.0f), osg::StateAttribute::ON);
        _sets[key] = ss;
        return ss.get();
    }

private:
    osg::Texture2D* texture(const std::string& kind)
    {
        auto it = _textures.find(kind);
        if (it != _textures.end()) return it->second.get();
        osg::ref_ptr<osg::Image> image;
        for (const osgLoA::FacadeStyle& s : osgLoA::CityTextures::facadeStyles())
            if (s.name == kind) image = osgLoA::CityTextures::facade(s);
        if (!image) image = osgLoA::CityTextures::surface(kind);
        osg::ref_ptr<osg::Texture2D> t = osgLoA::CityTextures::makeTexture(image.get());
        _textures[kind] = t;
        return t.get();
    }

    std::map<std::string, osg::ref_ptr<osg::StateSet>> _sets;
    std::map<std::string, osg::ref_ptr<osg::Texture2D>> _textures;
};

/** This thread's WGS84 (degrees, longitude first) -> transverse Mercator at (0, 0) pipeline, in
 *  this thread's own PROJ context (the default context is not for several threads at once). */
PJ* centredTransverseMercator()
{
    struct Pipeline
    {
        PJ_CONTEXT* context = proj_context_create();
        PJ* pj = context ? proj_create(context,
                                       "+proj=pipeline +step +proj=unitconvert +xy_in=deg +xy_out=rad "
                                       "+step +proj=tmerc +lat_0=0 +lon_0=0 +k=1 +x_0=0 +y_0=0 +ellps=WGS84")
                         : nullptr;
        ~Pipeline()
        {
            if (pj) proj_destroy(pj);
            if (context) proj_context_destroy(context);
        }
    };
    thread_local Pipeline pipeline;
    if (!pipeline.pj)
        throw std::runtime_error("cannot create the WGS84 -> local transverse Mercator transformation");
    return pipeline.pj;
}

std::uint32_t fnv1a(const std::string& s)
{
    std::uint32_t h = 2166136261u;
    for (unsigned char c : s)
        h = (h ^ c) * 16777619u;
    return h;
}

// --- the builder ----------------------------------------------------------------------------
struct Item
{
    OsmObject* object;
    Classification c;
};

class SceneBuilder
{
public:
    SceneBuilder(const ImportOptions& o, ImportReport& r) : _o(o), _report(r) {}

    osg::ref_ptr<osg::Group> build(std::vector<OsmObject>& objects)
    {
        std::vector<Item> items = classify(objects);
        dropInvalidCoordinates(items);
        if (items.empty())
            throw std::runtime_error(
                "no supported objects (buildings, roads, water, green areas, trees) in the "
                "file; " +
                std::to_string(_report.unsupported) + " objects of other kinds");
        project(items);

        _root = new osg::Group;
        _root->setName("OpenStreetMap");
        _root->setUserValue("loa.origin", osg::Vec3d(0, 0, 0));
        _root->setUserValue("loa.crs", _crs);
        _root->setUserValue("loa.originLonLat", osg::Vec3d(_lon0, _lat0, 0));
        const char* groups[] = {"Buildings", "Streets", "Water", "Green", "Terrain"};
        for (const char* name : groups)
        {
            osg::ref_ptr<osg::Group> g = new osg::Group;
            g->setName(name);
            _root->addChild(g.get());
            _groups[name] = g;
        }
        makeGround();

        for (Item& it : items)
        {
            osg::ref_ptr<osg::Geode> node;
            switch (it.c.kind)
            {
            case Kind::Building:
                node = building(*it.object, it.c);
                break;
            case Kind::Road:
            case Kind::WaterLine:
                node = ribbon(*it.object, it.c);
                break;
            case Kind::RoadArea:
            case Kind::WaterArea:
            case Kind::GreenArea:
                node = area(*it.object, it.c);
                break;
            case Kind::Tree:
                node = tree(*it.object, it.c);
                break;
            case Kind::None:
                break;
            }
            if (!node)
            {
                ++_report.degenerate;
                OSG_INFO << "osm: skipped degenerate " << it.object->sourceId << " (" << it.c.sourceType
                         << ")" << std::endl;
                continue;
            }
            Feature* f =
                Feature::attach(*node, new Feature(++_nextId, it.c.type, it.c.subType, Feature::MODEL_DATA));
            f->setSourceId(it.object->sourceId);
            f->setSourceType(it.c.sourceType);
            if (it.c.kind == Kind::Building) f->setLod(1.0f);
            if (it.c.kind == Kind::Road || it.c.kind == Kind::WaterLine)
            {
                // The way's nodes as the ribbon was built from them (metres, the scene frame).
                Ring line = it.object->line;
                if (cleanLine(line)) f->setCentreline(line);
            }
            for (const auto& kv : it.object->tags)
                node->setUserValue("osm." + kv.first, kv.second);
            f->setLabel(labelOf(it.object->tags));
            _groups[groupOf(it.c.type)]->addChild(node.get());
            ++_report.features;
        }
        if (_report.features == 0)
            throw std::runtime_error("no supported objects could be built: all " +
                                     std::to_string(_report.degenerate) + " candidates were degenerate");
        if (_o.terrain) terrainFeature();
        _root->setUserValue("loa.skippedDegenerate", _report.degenerate);
        osgLoA::FeatureIndex(*_root).updateBounds();
        return _root;
    }

private:
    static const char* groupOf(FeatureType t)
    {
        switch (t)
        {
        case FeatureType::Building:
            return "Buildings";
        case FeatureType::Street:
            return "Streets";
        case FeatureType::Water:
            return "Water";
        case FeatureType::Green:
            return "Green";
        default:
            return "Terrain";
        }
    }

    std::vector<Item> classify(std::vector<OsmObject>& objects)
    {
        std::vector<Item> items;
        for (OsmObject& o : objects)
        {
            Classification c;
            if (o.geometry == OsmObject::Point)
                c = classifyPoint(o.tags);
            else if (o.geometry == OsmObject::Area)
                c = classifyArea(o.tags);
            else
            {
                c = classifyLine(o.tags);
                // osmconf's closed_ways_are_polygons (OsmFile) leaves closed ways with water=* or
                // waterway=riverbank in "lines": treat them as the areas they are, unless area=no.
                const bool closed = o.line.size() >= 4 && (o.line.front() - o.line.back()).length() < 1e-12;
                if (c.kind == Kind::None && closed && tag(o.tags, "area") != "no")
                {
                    Classification a = classifyArea(o.tags);
                    if (a.kind != Kind::None && a.kind != Kind::RoadArea)
                    {
                        c = a;
                        o.geometry = OsmObject::Area;
                        o.polygons = {Polygon{o.line}};
                        o.line.clear();
                    }
                }
            }
            if (c.kind == Kind::None)
                ++_report.unsupported;
            else
                items.push_back({&o, c});
        }
        return items;
    }

    /** An object with a coordinate that is not finite, or a longitude outside [-180, 180] or a
     *  latitude outside [-90, 90], is left out with a warning naming it (OSM XML can say
     *  lat="nan"; GDAL hands it over as it is, and one such point made the projection fail for
     *  the whole file or put infinities in the scene). */
    void dropInvalidCoordinates(std::vector<Item>& items)
    {
        std::vector<Item> kept;
        for (Item& it : items)
        {
            bool valid = true;
            osg::Vec2d bad;
            std::vector<Item> one{it};
            forEachPoint(one,
                         [&](osg::Vec2d& p)
                         {
                             if (valid && !(std::isfinite(p.x()) && std::isfinite(p.y()) &&
                                            std::fabs(p.x()) <= 180.0 && std::fabs(p.y()) <= 90.0))
                                 valid = false, bad = p;
                         });
            if (valid)
                kept.push_back(it);
            else
                OSG_WARN << "osm: " << it.object->sourceId << ": coordinate (" << bad.x() << ", " << bad.y()
                         << ") is no longitude and latitude; the object is left out" << std::endl;
        }
        items.swap(kept);
    }

    void forEachPoint(std::vector<Item>& items, const std::function<void(osg::Vec2d&)>& fn)
    {
        for (Item& it : items)
        {
            for (osg::Vec2d& p : it.object->line)
                fn(p);
            for (Polygon& poly : it.object->polygons)
                for (Ring& r : poly)
                    for (osg::Vec2d& p : r)
                        fn(p);
        }
    }

    void project(std::vector<Item>& items)
    {
        double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
        forEachPoint(items,
                     [&](osg::Vec2d& p)
                     {
                         for (int k = 0; k < 2; ++k)
                         {
                             lo[k] = std::min(lo[k], p[k]);
                             hi[k] = std::max(hi[k], p[k]);
                         }
                     });
        if (lo[0] > hi[0]) throw std::runtime_error("the supported objects have no coordinates");
        _lon0 = 0.5 * (lo[0] + hi[0]);
        _lat0 = 0.5 * (lo[1] + hi[1]);
        // The local frame: a transverse Mercator on WGS84 at the data's centre, recorded as its
        // proj4 string. PROJ applies it through one pipeline per thread, centred on (0, 0) and
        // made once (proj_create is 45 us, a tenth of a small import under the fuzzer): the
        // centre's longitude is subtracted before (PROJ itself subtracts lon_0 first) and the
        // northing of the centre's latitude after (lat_0 only shifts y by that constant).
        // Longitude first, as OSM has it.
        char text[256];
        std::snprintf(
            text, sizeof text,
            "+proj=tmerc +lat_0=%.17g +lon_0=%.17g +k=1 +x_0=0 +y_0=0 +datum=WGS84 +units=m +no_defs", _lat0,
            _lon0);
        _crs = text;
        PJ* pj = centredTransverseMercator();
        const double northing0 = proj_trans(pj, PJ_FWD, proj_coord(0, _lat0, 0, 0)).xy.y;
        bool ok = std::isfinite(northing0);
        forEachPoint(items,
                     [&](osg::Vec2d& p)
                     {
                         const PJ_COORD c = proj_trans(pj, PJ_FWD, proj_coord(p.x() - _lon0, p.y(), 0, 0));
                         if (!std::isfinite(c.xy.x) || !std::isfinite(c.xy.y)) ok = false; // HUGE_VAL: failed
                         p.set(c.xy.x, c.xy.y - northing0);
                         _extent.expandBy(osg::Vec3d(p.x(), p.y(), 0));
                     });
        if (!ok) throw std::runtime_error("projection to the local frame failed for some coordinates");
    }

    void makeGround()
    {
        if (_o.dem.empty())
            _ground.reset(new FlatGround);
        else
        {
            OGRSpatialReference local; // the DEM's reprojection needs it as GDAL's object
            if (local.importFromProj4(_crs.c_str()) != OGRERR_NONE)
                throw std::runtime_error("cannot describe the local frame to GDAL: " + _crs);
            local.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
            _ground.reset(new DemGround(_o.dem, local));
        }
        _drapeStep = _o.dem.empty() ? 0.0 : cell();
    }

    double cell() const { return _o.terrainCell > 0 ? _o.terrainCell : (_o.dem.empty() ? 25.0 : 5.0); }
    double groundAt(const osg::Vec2d& p) const { return _ground->height(p.x(), p.y()); }

    osg::ref_ptr<osg::Geode> geode(osg::Geometry* g, osg::StateSet* ss)
    {
        osg::ref_ptr<osg::Geode> geode = new osg::Geode;
        g->setStateSet(ss);
        geode->addDrawable(g);
        return geode;
    }

    // Buildings: walls from every ring, a flat roof with holes.
    osg::ref_ptr<osg::Geode> building(OsmObject& o, const Classification&)
    {
        std::vector<Polygon> polys;
        for (Polygon p : o.polygons)
        {
            if (p.empty() || !cleanRing(p[0])) continue;
            if (signedArea(p[0]) < 0) std::reverse(p[0].begin(), p[0].end());
            Polygon q{p[0]};
            for (std::size_t k = 1; k < p.size(); ++k)
                if (cleanRing(p[k]))
                {
                    if (signedArea(p[k]) > 0) std::reverse(p[k].begin(), p[k].end());
                    q.push_back(p[k]);
                }
            polys.push_back(q);
        }
        if (polys.empty()) return nullptr;

        const Tags& t = o.tags;
        double height = 0.0, levels = 0.0, minHeight = 0.0, minLevel = 0.0;
        if (!parseLength(tag(t, "height"), height) || height <= 0.0)
        {
            if (parseNumber(tag(t, "building:levels"), levels) && levels > 0.0)
                height = levels * _o.storey;
            else
                height = _o.defaultHeight;
        }
        if (!parseLength(tag(t, "min_height"), minHeight))
        {
            minHeight = 0.0;
            if (parseNumber(tag(t, "building:min_level"), minLevel)) minHeight = minLevel * _o.storey;
        }
        // Absurd values (building:levels=1e308 made infinite geometry) are clamped, with a warning
        // naming the element: no building is taller than kMaxHeight.
        height = plausible(o, "height", height, kMaxHeight);
        minHeight = plausible(o, "min_height", minHeight, kMaxHeight - _o.storey);
        if (height <= minHeight + 0.1)
        {
            OSG_INFO << "osm: " << o.sourceId << ": height " << height << " m not above min_height "
                     << minHeight << " m; using one storey" << std::endl;
            height = minHeight + _o.storey;
        }

        double base = std::numeric_limits<double>::max();
        for (const Polygon& p : polys)
        {
            osg::Vec2d c;
            for (const osg::Vec2d& v : densify(p[0], _drapeStep, true))
            {
                base = std::min(base, groundAt(v));
                c += v;
            }
            base = std::min(base, groundAt(c / static_cast<double>(p[0].size())));
        }
        const double zb = base + minHeight, zt = base + height;

        const auto& styles = osgLoA::CityTextures::facadeStyles();
        const osgLoA::FacadeStyle& style = styles[fnv1a(o.sourceId) % styles.size()];
        const double tileW = style.bays * style.bayWidth, tileH = style.floors * kFacadeStorey;

        Mesh walls, roof;
        for (const Polygon& p : polys)
        {
            for (const Ring& r : p)
            {
                double s = 0.0;
                for (std::size_t i = 0, n = r.size(); i < n; ++i)
                {
                    const osg::Vec2d &a = r[i], &b = r[(i + 1) % n];
                    const osg::Vec2d d = b - a;
                    const double len = d.length();
                    const osg::Vec3 nrm(static_cast<float>(d.y() / len), static_cast<float>(-d.x() / len),
                                        0.0f);
                    const float u0 = static_cast<float>(s / tileW),
                                u1 = static_cast<float>((s + len) / tileW);
                    const float v0 = static_cast<float>((zb - base) / tileH),
                                v1 = static_cast<float>((zt - base) / tileH);
                    const unsigned k0 = walls.vertex(osg::Vec3d(a.x(), a.y(), zb), nrm, osg::Vec2(u0, v0));
                    const unsigned k1 = walls.vertex(osg::Vec3d(b.x(), b.y(), zb), nrm, osg::Vec2(u1, v0));
                    const unsigned k2 = walls.vertex(osg::Vec3d(b.x(), b.y(), zt), nrm, osg::Vec2(u1, v1));
                    const unsigned k3 = walls.vertex(osg::Vec3d(a.x(), a.y(), zt), nrm, osg::Vec2(u0, v1));
                    walls.triangle(k0, k1, k2);
                    walls.triangle(k0, k2, k3);
                    s += len;
                }
            }
            const FlatMesh m = tessellate(p);
            const unsigned first = roof.size();
            for (const osg::Vec2d& v : m.vertices)
                roof.vertex(
                    osg::Vec3d(v.x(), v.y(), zt), osg::Vec3(0, 0, 1),
                    osg::Vec2(static_cast<float>(v.x() / kRoofTile), static_cast<float>(v.y() / kRoofTile)));
            for (std::size_t k = 0; k + 2 < m.triangles.size(); k += 3)
                roof.triangle(first + m.triangles[k], first + m.triangles[k + 1], first + m.triangles[k + 2]);
        }
        if (walls.empty()) return nullptr;
        osg::ref_ptr<osg::Geode> g = geode(walls.build("WallSurface").get(), _states.textured(style.name));
        if (!roof.empty())
        {
            osg::ref_ptr<osg::Geometry> rg = roof.build("RoofSurface");
            rg->setStateSet(_states.textured("roof-gravel"));
            g->addDrawable(rg.get());
        }
        g->setUserValue("loa.height", zt - base);
        g->setUserValue("loa.baseHeight", base);
        return g;
    }

    double lift(const Classification& c) const
    {
        switch (c.kind)
        {
        case Kind::GreenArea:
            return kLiftGreen;
        case Kind::WaterArea:
        case Kind::WaterLine:
            return kLiftWater;
        default:
            return c.major ? kLiftRoadMajor : kLiftRoadMinor;
        }
    }

    std::string texture(const Classification& c) const
    {
        switch (c.kind)
        {
        case Kind::GreenArea:
            return (c.sourceType == "landuse=forest" || c.sourceType == "natural=wood") ? "forest-floor"
                                                                                        : "park-grass";
        case Kind::WaterArea:
        case Kind::WaterLine:
            return "water";
        default:
            return c.major ? "road-major" : "road-minor";
        }
    }

    static const char* surfaceName(const Classification& c)
    {
        switch (c.kind)
        {
        case Kind::WaterArea:
        case Kind::WaterLine:
            return "WaterSurface";
        case Kind::GreenArea:
            return "PlantCover";
        default:
            return "TrafficArea";
        }
    }

    /** value, or max (with a warning naming the element) when it is not finite or above max. */
    static double plausible(const OsmObject& o, const char* what, double value, double max)
    {
        if (std::isfinite(value) && value <= max) return value;
        OSG_WARN << "osm: " << o.sourceId << ": " << what << " " << value
                 << " m is not plausible; clamped to " << max << " m" << std::endl;
        return max;
    }

    // Roads and waterway lines: flat ribbons with mitered joints (bevelled past the limit).
    osg::ref_ptr<osg::Geode> ribbon(OsmObject& o, Classification c)
    {
        c.width = plausible(o, "width", c.width, kMaxWidth);
        Ring pts = o.line;
        if (!cleanLine(pts)) return nullptr;
        bool closed = pts.size() >= 4 && (pts.front() - pts.back()).length() <= 1e-4;
        if (closed) pts.pop_back();
        pts = densify(pts, _drapeStep, closed);
        const std::size_t n = pts.size();
        const double hw = 0.5 * c.width, up = lift(c), vScale = c.width * 1.5;
        auto leftNormal = [&](std::size_t i)
        {
            osg::Vec2d d = pts[(i + 1) % n] - pts[i];
            d.normalize();
            return osg::Vec2d(-d.y(), d.x());
        };
        Mesh mesh;
        std::vector<std::pair<unsigned, unsigned>> pairs;
        double s = 0.0;
        auto emit = [&](const osg::Vec2d& p, const osg::Vec2d& off)
        {
            const osg::Vec2d l = p + off, r = p - off;
            const float v = static_cast<float>(s / vScale);
            const unsigned a = mesh.vertex(osg::Vec3d(l.x(), l.y(), groundAt(l) + up), osg::Vec3(0, 0, 1),
                                           osg::Vec2(0.0f, v));
            const unsigned b = mesh.vertex(osg::Vec3d(r.x(), r.y(), groundAt(r) + up), osg::Vec3(0, 0, 1),
                                           osg::Vec2(1.0f, v));
            pairs.push_back({a, b});
        };
        const std::size_t count = closed ? n + 1 : n;
        for (std::size_t k = 0; k < count; ++k)
        {
            const std::size_t i = k % n;
            if (k > 0) s += (pts[i] - pts[(k - 1) % n]).length();
            const bool hasPrev = closed || i > 0, hasNext = closed || i + 1 < n;
            if (!hasPrev)
                emit(pts[i], leftNormal(i) * hw);
            else if (!hasNext)
                emit(pts[i], leftNormal(i - 1) * hw);
            else
            {
                const osg::Vec2d np = leftNormal((i + n - 1) % n), nn = leftNormal(i);
                osg::Vec2d m = np + nn;
                const double ml = m.length();
                const double d = ml > 1e-9 ? (m / ml) * nn : 0.0;
                if (ml > 1e-9 && d >= 1.0 / _o.miterLimit)
                    emit(pts[i], m / ml * (hw / d));
                else
                {
                    emit(pts[i], np * hw); // bevel: end of the previous segment...
                    emit(pts[i], nn * hw); // ...start of the next one
                }
            }
        }
        for (std::size_t k = 1; k < pairs.size(); ++k)
        {
            const unsigned l0 = pairs[k - 1].first, r0 = pairs[k - 1].second, l1 = pairs[k].first,
                           r1 = pairs[k].second;
            mesh.triangleUp(l0, r0, r1);
            mesh.triangleUp(l0, r1, l1);
        }
        if (mesh.empty()) return nullptr;
        return geode(mesh.build(surfaceName(c)).get(), _states.textured(texture(c), true));
    }

    // Water, green and highway areas: flat polygons draped on the ground.
    osg::ref_ptr<osg::Geode> area(OsmObject& o, const Classification& c)
    {
        Mesh mesh;
        const double up = lift(c), tile = c.kind == Kind::WaterArea ? kWaterTile : kGreenTile;
        for (Polygon p : o.polygons)
        {
            if (p.empty() || !cleanRing(p[0])) continue;
            Polygon q{densify(p[0], _drapeStep, true)};
            for (std::size_t k = 1; k < p.size(); ++k)
                if (cleanRing(p[k])) q.push_back(densify(p[k], _drapeStep, true));
            const FlatMesh m = tessellate(q);
            const unsigned first = mesh.size();
            for (const osg::Vec2d& v : m.vertices)
                mesh.vertex(osg::Vec3d(v.x(), v.y(), groundAt(v) + up), osg::Vec3(0, 0, 1),
                            osg::Vec2(static_cast<float>(v.x() / tile), static_cast<float>(v.y() / tile)));
            for (std::size_t k = 0; k + 2 < m.triangles.size(); k += 3)
                mesh.triangleUp(first + m.triangles[k], first + m.triangles[k + 1],
                                first + m.triangles[k + 2]);
        }
        if (mesh.empty()) return nullptr;
        return geode(mesh.build(surfaceName(c)).get(), _states.textured(texture(c), true));
    }

    // natural=tree: an octagonal trunk and a low-poly ellipsoid crown.
    osg::ref_ptr<osg::Geode> tree(OsmObject& o, const Classification&)
    {
        if (o.line.empty()) return nullptr;
        const osg::Vec2d p = o.line.front();
        double h = 8.0, crownD = 0.0;
        if (!parseLength(tag(o.tags, "height"), h) || h < 1.0) h = 8.0;
        if (!parseLength(tag(o.tags, "diameter_crown"), crownD) || crownD <= 0.0) crownD = 0.45 * h;
        const double z0 = groundAt(p), trunkH = 0.35 * h, trunkR = std::max(0.1, 0.025 * h);
        const int sides = 8, stacks = 5;
        Mesh trunk, crown;
        for (int k = 0; k <= sides; ++k)
        {
            const double a = 2.0 * osg::PI * k / sides;
            const osg::Vec3 n(static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0.0f);
            const osg::Vec3d q(p.x() + trunkR * std::cos(a), p.y() + trunkR * std::sin(a), z0);
            const float u = static_cast<float>(k) / sides;
            trunk.vertex(q, n, osg::Vec2(u, 0.0f));
            trunk.vertex(q + osg::Vec3d(0, 0, trunkH + 0.1 * h), n, osg::Vec2(u, 1.0f));
            if (k > 0)
            {
                const unsigned b = static_cast<unsigned>(2 * k);
                trunk.triangle(b - 2, b, b + 1);
                trunk.triangle(b - 2, b + 1, b - 1);
            }
        }
        const double rz = 0.5 * (h - trunkH), rxy = 0.5 * crownD, zc = z0 + trunkH + rz;
        for (int j = 0; j <= stacks; ++j)
        {
            const double phi = osg::PI * j / stacks; // 0 at the bottom
            for (int k = 0; k <= sides; ++k)
            {
                const double a = 2.0 * osg::PI * k / sides;
                const osg::Vec3d d(std::sin(phi) * std::cos(a), std::sin(phi) * std::sin(a), -std::cos(phi));
                osg::Vec3 n(static_cast<float>(d.x() / rxy), static_cast<float>(d.y() / rxy),
                            static_cast<float>(d.z() / rz));
                n.normalize();
                crown.vertex(osg::Vec3d(p.x() + rxy * d.x(), p.y() + rxy * d.y(), zc + rz * d.z()), n,
                             osg::Vec2(static_cast<float>(k) / sides, static_cast<float>(j) / stacks));
                if (j > 0 && k > 0)
                {
                    const unsigned c = static_cast<unsigned>(j * (sides + 1) + k), b = c - 1,
                                   a0 = c - static_cast<unsigned>(sides + 1), a1 = a0 - 1;
                    crown.triangle(a1, a0, c);
                    crown.triangle(a1, c, b);
                }
            }
        }
        const osg::Vec4 brown(0.36f, 0.26f, 0.17f, 1.0f), green(0.22f, 0.45f, 0.18f, 1.0f);
        osg::ref_ptr<osg::Geode> g = new osg::Geode;
        g->addDrawable(trunk.build("TreeTrunk", &brown).get());
        osg::ref_ptr<osg::Geometry> cg = crown.build("TreeCrown", &green);
        cg->setStateSet(_states.textured("forest-floor"));
        g->addDrawable(cg.get());
        return g;
    }

    // The ground: a grid over the extent plus the margin, heights from the ground model. Flat
    // ground with no terrainCell asked for is one quad: a grid adds nothing to the image there
    // (same normal, texture coordinates linear in x and y) but two triangles per 25 m cell, up
    // to 512 x 512 cells.
    void terrainFeature()
    {
        const double m = _o.margin, step = cell();
        const double x0 = _extent.xMin() - m, y0 = _extent.yMin() - m, x1 = _extent.xMax() + m,
                     y1 = _extent.yMax() + m;
        const bool flat = _o.dem.empty() && _o.terrainCell <= 0;
        const int nx = flat ? 1 : std::clamp(static_cast<int>(std::ceil((x1 - x0) / step)), 1, 512);
        const int ny = flat ? 1 : std::clamp(static_cast<int>(std::ceil((y1 - y0) / step)), 1, 512);
        const double dx = (x1 - x0) / nx, dy = (y1 - y0) / ny;
        std::vector<double> z(static_cast<std::size_t>((nx + 1) * (ny + 1)));
        auto Z = [&](int i, int j) -> double& { return z[static_cast<std::size_t>(j * (nx + 1) + i)]; };
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i)
                Z(i, j) = _ground->height(x0 + i * dx, y0 + j * dy);
        Mesh mesh;
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i)
            {
                const double gx = (Z(std::min(i + 1, nx), j) - Z(std::max(i - 1, 0), j)) /
                                  (dx * (std::min(i + 1, nx) - std::max(i - 1, 0)));
                const double gy = (Z(i, std::min(j + 1, ny)) - Z(i, std::max(j - 1, 0))) /
                                  (dy * (std::min(j + 1, ny) - std::max(j - 1, 0)));
                osg::Vec3 n(static_cast<float>(-gx), static_cast<float>(-gy), 1.0f);
                n.normalize();
                const double x = x0 + i * dx, y = y0 + j * dy;
                mesh.vertex(
                    osg::Vec3d(x, y, Z(i, j)), n,
                    osg::Vec2(static_cast<float>(x / kGroundTile), static_cast<float>(y / kGroundTile)));
            }
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i)
            {
                const unsigned a = static_cast<unsigned>(j * (nx + 1) + i), b = a + 1,
                               d = a + static_cast<unsigned>(nx + 1), c = d + 1;
                mesh.triangle(a, b, c);
                mesh.triangle(a, c, d);
            }
        osg::ref_ptr<osg::Geode> g = geode(mesh.build("TINRelief").get(), _states.textured("terrain"));
        Feature* f =
            Feature::attach(*g, new Feature(++_nextId, FeatureType::Terrain, "", Feature::MODEL_DATA));
        f->setSourceType(_ground->kind());
        if (!_o.dem.empty()) g->setUserValue("loa.dem", _o.dem);
        _groups["Terrain"]->addChild(g.get());
        ++_report.features;
    }

    const ImportOptions& _o;
    ImportReport& _report;
    osg::ref_ptr<osg::Group> _root;
    std::map<std::string, osg::ref_ptr<osg::Group>> _groups;
    StateSets _states;
    std::string _crs;
    double _lon0 = 0.0, _lat0 = 0.0;
    osg::BoundingBoxd _extent;
    std::unique_ptr<Ground> _ground;
    double _drapeStep = 0.0;
    unsigned _nextId = 0;
};

} // namespace

osg::ref_ptr<osg::Group> buildScene(std::vector<OsmObject>& objects, const ImportOptions& options,
                                    ImportReport& report)
{
    return SceneBuilder(options, report).build(objects);
}

} // namespace osmimport
