// Turns OpenStreetMap objects (already read by OsmFile, in WGS84 lon/lat) into an osgLoA scene:
// a local transverse Mercator frame, a ground (flat or a GeoTIFF DEM), and one feature per
// object (docs/osm.md).
#ifndef OSGLOA_PLUGINS_OSM_OSMSCENE_H
#define OSGLOA_PLUGINS_OSM_OSMSCENE_H 1

#include "OsmTags.h"

#include <osg/Group>
#include <osg/Vec2d>

#include <string>
#include <vector>

namespace osmimport
{

/** The reader's options (osgDB option string "key=value ..."; docs/osm.md). */
struct ImportOptions
{
    double storey = 3.0;        ///< metres per building:levels
    double defaultHeight = 9.0; ///< metres, for buildings with neither height nor levels
    double margin = 30.0;       ///< metres of ground around the data's extent
    double terrainCell = 0.0;   ///< ground grid spacing in metres; 0: 25 flat, 5 with a DEM
    double miterLimit = 3.0;    ///< ribbon joints: miter length / half width above which to bevel
    bool terrain = true;        ///< make the ground feature
    std::string dem;            ///< GeoTIFF (any GDAL raster) with heights in metres

    /** Parses "key=value" words; throws std::invalid_argument for a bad value. Unknown keys
     *  are returned in unknown (they may belong to another plugin). */
    void parse(const std::string& text, std::vector<std::string>& unknown);
};

using Ring = std::vector<osg::Vec2d>;
using Polygon = std::vector<Ring>; ///< [0] outer ring, then holes

/** One OSM object as OsmFile delivers it. */
struct OsmObject
{
    enum Geometry
    {
        Point,
        Line,
        Area
    } geometry = Point;
    std::string sourceId; ///< "node/5", "way/123", "relation/7"
    Tags tags;
    Ring line;                     ///< Point: one position; Line: the polyline (lon, lat)
    std::vector<Polygon> polygons; ///< Area (lon, lat)
};

struct ImportReport
{
    unsigned features = 0;
    unsigned unsupported = 0; ///< objects with no tag the importer maps
    unsigned degenerate = 0;  ///< skipped: too few distinct nodes, zero length or zero area
};

/** Builds the scene; throws std::runtime_error with a message for the user (no supported
 *  objects, unusable DEM, projection failure). */
osg::ref_ptr<osg::Group> buildScene(std::vector<OsmObject>& objects, const ImportOptions& options,
                                    ImportReport& report);

} // namespace osmimport

#endif
