// osgdb_osm: OpenStreetMap import through GDAL/OGR's OSM driver.
//   osgviewer map.osm
//   osgviewer map.osm.pbf
//   osgconv map.osm.bz2 map.osgb -O "storey=3.2 dem=/data/elevation.tif"
// Buildings are extruded footprints, roads and waterway lines ribbons, water and green areas flat
// polygons, natural=tree nodes simple trees, all on a ground grid (flat or from a DEM), in a local
// transverse Mercator frame centred on the data; docs/osm.md has the options and the tag table.
#include "OsmScene.h"

#include <osgLoA/util/InputLimits>

#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/Registry>

#include <bzlib.h>
#include <cpl_error.h>
#include <cpl_vsi.h>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <mutex>
#include <stdexcept>
#include <string>
#include <sys/stat.h>
#include <vector>

namespace
{
using namespace osmimport;

/** Collects GDAL's errors while it lives (the handler stack is per thread). */
class ErrorCollector
{
public:
    ErrorCollector() { CPLPushErrorHandlerEx(&ErrorCollector::handler, this); }
    ~ErrorCollector() { CPLPopErrorHandler(); }
    const std::vector<std::string>& failures() const { return _failures; }
    /** The distinct failures in order, each once with its count ("MESSAGE (x90000)"), at most
     *  three (GDAL repeats one message per element: a file gave 90,000 lines of one). */
    std::string joined() const
    {
        std::vector<std::pair<std::string, std::size_t>> distinct;
        for (const std::string& f : _failures)
        {
            auto it =
                std::find_if(distinct.begin(), distinct.end(), [&](const auto& d) { return d.first == f; });
            if (it == distinct.end())
                distinct.emplace_back(f, 1);
            else
                ++it->second;
        }
        std::string s;
        for (std::size_t i = 0; i < distinct.size() && i < 3; ++i)
            s += (s.empty() ? "" : "; ") + distinct[i].first +
                 (distinct[i].second > 1 ? " (x" + std::to_string(distinct[i].second) + ")" : "");
        if (distinct.size() > 3) s += "; and " + std::to_string(distinct.size() - 3) + " other errors";
        return s;
    }

private:
    static void CPL_STDCALL handler(CPLErr level, CPLErrorNum, const char* message)
    {
        auto* self = static_cast<ErrorCollector*>(CPLGetErrorHandlerUserData());
        if (!self) return;
        if (level == CE_Failure || level == CE_Fatal)
            self->_failures.push_back(message ? message : "unknown GDAL error");
        else if (level == CE_Warning)
            OSG_INFO << "osm: GDAL: " << (message ? message : "") << std::endl;
    }
    std::vector<std::string> _failures;
};

/** A bzip2 file decompressed into a GDAL /vsimem/ file, removed again on destruction. */
class VsiMemBz2
{
public:
    /** Inflates at most limits.maxInflatedBytes (a 1.7 kB file inflated to 2 GiB was read
     *  whole): more is an InputLimitError naming the file. */
    VsiMemBz2(const std::string& path, const osgLoA::InputLimits& limits)
    {
        FILE* f = std::fopen(path.c_str(), "rb");
        if (!f) throw std::runtime_error("cannot open '" + path + "'");
        int err = BZ_OK;
        BZFILE* bz = BZ2_bzReadOpen(&err, f, 0, 0, nullptr, 0);
        if (err != BZ_OK)
        {
            std::fclose(f);
            throw std::runtime_error("'" + path + "' is not a bzip2 file");
        }
        char buf[1 << 16];
        for (;;)
        {
            const int n = BZ2_bzRead(&err, bz, buf, sizeof buf);
            if (err != BZ_OK && err != BZ_STREAM_END) break;
            if (_data.size() + static_cast<std::size_t>(n) > limits.maxInflatedBytes)
            {
                BZ2_bzReadClose(&err, bz);
                std::fclose(f);
                throw osgLoA::InputLimitError(osgLoA::InputLimits::exceeded(
                    path,
                    "bzip2 data inflating to more than " + std::to_string(limits.maxInflatedBytes) + " bytes",
                    "max-inflated", limits.maxInflatedBytes));
            }
            _data.insert(_data.end(), buf, buf + n);
            if (err == BZ_STREAM_END)
            {
                // Concatenated streams (pbzip2): continue with the bytes left over.
                void* unused = nullptr;
                int nUnused = 0;
                BZ2_bzReadGetUnused(&err, bz, &unused, &nUnused);
                std::vector<char> rest(static_cast<char*>(unused), static_cast<char*>(unused) + nUnused);
                BZ2_bzReadClose(&err, bz);
                bz = nullptr;
                if (rest.empty() && std::feof(f)) break;
                int c = std::fgetc(f);
                if (rest.empty() && c == EOF) break;
                if (c != EOF) std::ungetc(c, f);
                bz = BZ2_bzReadOpen(&err, f, 0, 0, rest.empty() ? nullptr : rest.data(),
                                    static_cast<int>(rest.size()));
                if (err != BZ_OK) break;
            }
        }
        const bool bad = err != BZ_STREAM_END && err != BZ_OK;
        if (bz) BZ2_bzReadClose(&err, bz);
        std::fclose(f);
        if (bad || _data.empty()) throw std::runtime_error("'" + path + "' is not valid bzip2 data");
        static std::atomic<unsigned> counter{0};
        _name = "/vsimem/osgdb_osm_" + std::to_string(counter++) + ".osm";
        VSILFILE* mem = VSIFileFromMemBuffer(_name.c_str(), reinterpret_cast<GByte*>(_data.data()),
                                             static_cast<vsi_l_offset>(_data.size()), FALSE);
        if (!mem) throw std::runtime_error("cannot create " + _name);
        VSIFCloseL(mem);
    }
    ~VsiMemBz2() { VSIUnlink(_name.c_str()); }
    const std::string& name() const { return _name; }

private:
    std::vector<char> _data;
    std::string _name;
};

std::string sourceId(const std::string& layer, OGRFeature& f)
{
    auto field = [&](const char* name) -> std::string
    {
        const int i = f.GetFieldIndex(name);
        return i >= 0 && f.IsFieldSetAndNotNull(i) ? f.GetFieldAsString(i) : std::string();
    };
    if (layer == "points") return "node/" + field("osm_id");
    if (layer == "lines") return "way/" + field("osm_id");
    const std::string rel = field("osm_id");
    return rel.empty() ? "way/" + field("osm_way_id") : "relation/" + rel;
}

Ring ring(const OGRLineString& l)
{
    Ring r;
    r.reserve(static_cast<std::size_t>(l.getNumPoints()));
    for (int i = 0; i < l.getNumPoints(); ++i)
        r.push_back(osg::Vec2d(l.getX(i), l.getY(i)));
    return r;
}

Polygon polygon(const OGRPolygon& p)
{
    Polygon out;
    if (const OGRLinearRing* ext = p.getExteriorRing()) out.push_back(ring(*ext));
    for (int i = 0; i < p.getNumInteriorRings(); ++i)
        out.push_back(ring(*p.getInteriorRing(i)));
    return out;
}

class ReaderWriterOsm : public osgDB::ReaderWriter
{
public:
    ReaderWriterOsm()
    {
        supportsExtension("osm", "OpenStreetMap XML (through GDAL/OGR)");
        supportsExtension("pbf", "OpenStreetMap PBF (.osm.pbf)");
        supportsExtension("bz2", "bzip2-compressed OpenStreetMap XML (.osm.bz2 only)");
        supportsOption("storey=M", "metres per building:levels (default 3)");
        supportsOption("defaultHeight=M", "height of buildings with neither height nor levels (default 9)");
        supportsOption("dem=FILE", "GeoTIFF DEM: ground heights (default: flat ground at 0)");
        supportsOption("margin=M", "ground beyond the data's extent (default 30)");
        supportsOption("terrainCell=M", "ground grid spacing (default 25, or 5 with a DEM)");
        supportsOption("terrain=on|off", "make the ground feature (default on)");
        supportsOption("miterLimit=R", "ribbon joints bevelled beyond R half widths (default 3)");
        osgLoA::InputLimits::declareOptions(*this);
    }
    const char* className() const override { return "osgLoA OpenStreetMap importer (GDAL/OGR)"; }

    ReadResult readObject(const std::string& fileName, const Options* options) const override
    {
        return readNode(fileName, options);
    }

    ReadResult readNode(const std::string& fileName, const Options* options) const override
    {
        const std::string ext = osgDB::getLowerCaseFileExtension(fileName);
        if (!acceptsExtension(ext)) return ReadResult::FILE_NOT_HANDLED;
        const std::string lower = osgDB::convertToLowerCase(fileName);
        const bool bz2 = ext == "bz2";
        if (bz2 && (lower.size() < 8 || lower.compare(lower.size() - 8, 8, ".osm.bz2") != 0))
            return ReadResult::FILE_NOT_HANDLED;

        const std::string path = osgDB::findDataFile(fileName, options);
        if (path.empty() || osgDB::fileType(path) != osgDB::REGULAR_FILE)
        {
            ReadResult rr(ReadResult::FILE_NOT_FOUND);
            rr.message() = "osm: file not found: '" + fileName + "'";
            return rr;
        }
        try
        {
            ImportOptions opts;
            std::vector<std::string> unknown;
            if (options) opts.parse(options->getOptionString(), unknown);
            for (const std::string& u : unknown)
                OSG_INFO << "osm: ignoring option '" << u << "' (not an osm option)" << std::endl;
            if (!opts.dem.empty() && osgDB::fileType(opts.dem) != osgDB::REGULAR_FILE)
                throw std::runtime_error("dem: file not found: '" + opts.dem + "'");

            static std::once_flag registered;
            std::call_once(registered, [] { GDALAllRegister(); });

            ErrorCollector errors;
            std::unique_ptr<VsiMemBz2> mem;
            const osgLoA::InputLimits limits =
                osgLoA::InputLimits::fromOptions(options ? options->getOptionString() : std::string());
            struct stat st;
            if (::stat(path.c_str(), &st) == 0 &&
                static_cast<std::uint64_t>(st.st_size) > limits.maxFileBytes)
                throw osgLoA::InputLimitError(osgLoA::InputLimits::exceeded(
                    path, std::to_string(st.st_size) + " bytes", "max-file", limits.maxFileBytes));
            if (bz2) mem.reset(new VsiMemBz2(path, limits));
            const std::string openName = mem ? mem->name() : path;
            const char* drivers[] = {"OSM", nullptr};
            GDALDatasetUniquePtr ds(GDALDataset::Open(openName.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY,
                                                      drivers, nullptr, nullptr));
            if (!ds)
                throw std::runtime_error(
                    "'" + fileName + "' is not an OpenStreetMap file (OGR's OSM driver " + "cannot open it" +
                    (errors.failures().empty() ? "" : ": " + errors.joined()) + ")");

            std::vector<OsmObject> objects;
            unsigned badTags = 0;
            ds->ResetReading();
            for (;;)
            {
                OGRLayer* layer = nullptr;
                OGRFeatureUniquePtr f(ds->GetNextFeature(&layer, nullptr, nullptr, nullptr));
                if (!f) break;
                if (!layer) continue;
                const std::string lname = layer->GetName();
                OsmObject o;
                if (lname == "points")
                    o.geometry = OsmObject::Point;
                else if (lname == "lines")
                    o.geometry = OsmObject::Line;
                else if (lname == "multipolygons")
                    o.geometry = OsmObject::Area;
                else
                    continue; // multilinestrings, other_relations: routes and the like
                const OGRGeometry* g = f->GetGeometryRef();
                if (!g) continue;
                o.sourceId = sourceId(lname, *f);
                for (int i = 0; i < f->GetFieldCount(); ++i)
                {
                    if (!f->IsFieldSetAndNotNull(i)) continue;
                    const std::string name = f->GetFieldDefnRef(i)->GetNameRef();
                    if (name == "osm_id" || name == "osm_way_id" || name == "z_order" || name == "all_tags")
                        continue;
                    if (name == "other_tags")
                    {
                        if (!parseHstore(f->GetFieldAsString(i), o.tags)) ++badTags;
                    }
                    else
                        o.tags[name] = f->GetFieldAsString(i);
                }
                switch (wkbFlatten(g->getGeometryType()))
                {
                case wkbPoint:
                {
                    const OGRPoint* p = g->toPoint();
                    o.line.push_back(osg::Vec2d(p->getX(), p->getY()));
                    break;
                }
                case wkbLineString:
                    o.line = ring(*g->toLineString());
                    break;
                case wkbPolygon:
                    o.polygons.push_back(polygon(*g->toPolygon()));
                    break;
                case wkbMultiPolygon:
                    for (const OGRPolygon* p : *g->toMultiPolygon())
                        o.polygons.push_back(polygon(*p));
                    break;
                default:
                    continue;
                }
                objects.push_back(std::move(o));
                if (objects.size() > limits.maxObjects)
                    throw osgLoA::InputLimitError(osgLoA::InputLimits::exceeded(
                        path, "more than " + std::to_string(limits.maxObjects) + " OpenStreetMap elements",
                        "max-objects", limits.maxObjects));
            }
            if (!errors.failures().empty())
                throw std::runtime_error("'" + fileName + "' is malformed: " + errors.joined());
            if (badTags) OSG_WARN << "osm: " << badTags << " objects had unreadable other_tags" << std::endl;

            ImportReport report;
            osg::ref_ptr<osg::Group> root = buildScene(objects, opts, report);
            root->setUserValue("loa.source", fileName);
            OSG_INFO << "osm: " << fileName << ": " << report.features << " features, " << report.unsupported
                     << " objects of unsupported kinds, " << report.degenerate
                     << " degenerate objects skipped" << std::endl;
            return root.get();
        }
        catch (const std::exception& e)
        {
            return ReadResult(std::string("osm: ") + e.what());
        }
    }
};
} // namespace

REGISTER_OSGPLUGIN(osm, ReaderWriterOsm)
