// osgdb_osm: OpenStreetMap import, read with libosmium (OsmFile).
//   osgviewer map.osm
//   osgviewer map.osm.pbf
//   osgconv map.osm.bz2 map.osgb -O "storey=3.2 dem=/data/elevation.tif"
// Buildings are extruded footprints, roads and waterway lines ribbons, water and green areas flat
// polygons, natural=tree nodes simple trees, all on a ground grid (flat or from a DEM), in a local
// transverse Mercator frame centred on the data; docs/osm.md has the options and the tag table.
#include "OsmFile.h"
#include "OsmScene.h"

#include <osgLoA/util/InputLimits>

#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/Registry>

#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <sys/stat.h>
#include <vector>

namespace
{
using namespace osmimport;

std::vector<char> readWhole(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot open '" + path + "'");
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw std::runtime_error("cannot read '" + path + "'");
    return bytes;
}

class ReaderWriterOsm : public osgDB::ReaderWriter
{
public:
    ReaderWriterOsm()
    {
        supportsExtension("osm", "OpenStreetMap XML");
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
    const char* className() const override { return "osgLoA OpenStreetMap importer (libosmium)"; }

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

            const osgLoA::InputLimits limits =
                osgLoA::InputLimits::fromOptions(options ? options->getOptionString() : std::string());
            struct stat st;
            if (::stat(path.c_str(), &st) == 0 &&
                static_cast<std::uint64_t>(st.st_size) > limits.maxFileBytes)
                throw osgLoA::InputLimitError(osgLoA::InputLimits::exceeded(
                    path, std::to_string(st.st_size) + " bytes", "max-file", limits.maxFileBytes));
            std::vector<char> inflated;
            if (bz2) inflated = inflateBz2(readWhole(path), fileName, limits);
            OsmSource source;
            source.name = fileName;
            source.path = path;
            if (bz2) source.data = &inflated;
            ReadReport read;
            std::vector<OsmObject> objects = readOsmFile(source, limits, read);
            OSG_INFO << "osm: " << fileName << ": " << read.nodes << " nodes, " << read.ways << " ways, "
                     << read.relations << " relations; " << read.shortWays
                     << " ways with fewer than 2 nodes in the file, " << read.incompleteRelations
                     << " multipolygons with members missing, " << read.unassembled
                     << " multipolygons whose rings do not close" << std::endl;

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
