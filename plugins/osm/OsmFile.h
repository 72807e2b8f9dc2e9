// Reading an OpenStreetMap file (XML, PBF, or XML from memory) into OsmObjects with libosmium:
// tagged nodes as points, ways as lines or (closed ways with area tags) areas, multipolygon and
// boundary relations assembled into areas. The rules are those of GDAL's OSM driver with its
// default osmconf.ini, which read these files before (docs/osm.md, "What is read").
#ifndef OSGLOA_PLUGINS_OSM_OSMFILE_H
#define OSGLOA_PLUGINS_OSM_OSMFILE_H 1

#include "OsmScene.h"

#include <osgLoA/util/InputLimits>

#include <cstdint>
#include <string>
#include <vector>

namespace osmimport
{

/** What reading skipped (reported by the plugin at INFO level). */
struct ReadReport
{
    std::uint64_t nodes = 0, ways = 0, relations = 0; ///< elements read
    unsigned shortWays = 0; ///< ways with fewer than 2 nodes present in the file (cut by an extract)
    unsigned incompleteRelations = 0; ///< multipolygons with a member way missing from the file
    unsigned unassembled = 0;         ///< multipolygons whose rings do not close (no area made)
};

/** The source of an OSM file: a path (format from its name: .osm XML, .pbf PBF) or, when data is
 *  set, XML already in memory (an inflated .osm.bz2) named by name in messages. */
struct OsmSource
{
    std::string name;                        ///< the file as the user named it (messages)
    std::string path;                        ///< the file to open, when data is empty
    const std::vector<char>* data = nullptr; ///< XML in memory
};

/** Reads source into objects. Throws std::runtime_error naming the file and the problem (bad XML
 *  with its line and column, a bad coordinate, a truncated PBF block) and osgLoA::InputLimitError
 *  when more than limits.maxObjects objects or limits.maxVertices vertices are made. */
std::vector<OsmObject> readOsmFile(const OsmSource& source, const osgLoA::InputLimits& limits,
                                   ReadReport& report);

/** bzip2 data (one stream or several concatenated, as pbzip2 writes) inflated into memory: at most
 *  limits.maxInflatedBytes (a 1.7 kB file inflated to 2 GiB), more is an InputLimitError naming
 *  the file; data that is no bzip2 or is cut short is a std::runtime_error naming it. */
std::vector<char> inflateBz2(const std::vector<char>& compressed, const std::string& name,
                             const osgLoA::InputLimits& limits);

/** GDAL osmconf.ini's closed_ways_are_polygons, with area=yes/no: whether a closed way with these
 *  tags is an area. */
bool closedWayIsArea(const Tags& tags);

} // namespace osmimport

#endif
