// OpenStreetMap tags: lengths with units, and the
// mapping from tags to the feature taxonomy (docs/osm.md has the table).
#ifndef OSGLOA_PLUGINS_OSM_OSMTAGS_H
#define OSGLOA_PLUGINS_OSM_OSMTAGS_H 1

#include <osgLoA/semantics/FeatureType>

#include <map>
#include <string>

namespace osmimport
{

using Tags = std::map<std::string, std::string>;

/** A length such as "12", "12.5 m", "12,5", "40 ft", "40'", "12'6\"", "350 cm"; metres.
 *  Returns false (and leaves metres alone) for text that is no non-negative length. */
bool parseLength(const std::string& text, double& metres);
/** A non-negative number ("4", "2.5"); false otherwise. */
bool parseNumber(const std::string& text, double& value);

/** The value of key, or "" when absent. */
const std::string& tag(const Tags& tags, const std::string& key);

/** What the importer makes of an object. */
enum class Kind
{
    None,      ///< not supported: skipped
    Building,  ///< area: extruded footprint
    Road,      ///< line: ribbon
    RoadArea,  ///< area with a highway tag (area=yes squares): flat polygon
    WaterArea, ///< area: flat polygon
    WaterLine, ///< line: ribbon
    GreenArea, ///< area: flat polygon
    Tree       ///< point: trunk and crown
};

struct Classification
{
    Kind kind = Kind::None;
    osgLoA::FeatureType type = osgLoA::FeatureType::Generic;
    std::string subType;
    std::string sourceType; ///< "building=yes", "highway=residential", ...
    double width = 0.0;     ///< ribbons: metres (the width tag wins over the class default)
    bool major = false;     ///< roads: motorway/trunk/primary/secondary (+_link)
};

/** Classifies an area (closed way or multipolygon relation). */
Classification classifyArea(const Tags& tags);
/** Classifies an open way (or a closed way that is not an area). */
Classification classifyLine(const Tags& tags);
/** Classifies a node. */
Classification classifyPoint(const Tags& tags);

/** Width in metres of a highway class; 0 for classes that are not imported. */
double highwayWidth(const std::string& highway);
/** motorway, trunk, primary, secondary and their _link roads. */
bool isMajorHighway(const std::string& highway);
/** The street sub-type of a highway class (the road hierarchy of the cartographic "streets"
 *  style): "major" (isMajorHighway), "path" (footway, path, cycleway, steps, pedestrian,
 *  bridleway), "track", else "minor". */
std::string roadClass(const std::string& highway, bool major);
/** Width in metres of a waterway line class; 0 for classes that are not imported. */
double waterwayWidth(const std::string& waterway);

} // namespace osmimport

#endif
