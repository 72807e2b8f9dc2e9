#include "OsmTags.h"

#include <cctype>
#include <cmath>
#include <cstdlib>

namespace osmimport
{
namespace
{
std::string trim(const std::string& s)
{
    std::size_t a = 0, b = s.size();
    while (a < b && std::isspace(static_cast<unsigned char>(s[a])))
        ++a;
    while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1])))
        --b;
    return s.substr(a, b - a);
}

// Leading number (a decimal comma is read as a point); returns the rest.
bool leadingNumber(const std::string& text, double& value, std::string& rest)
{
    std::string t = trim(text);
    if (t.empty()) return false;
    if (t.find('.') == std::string::npos)
    {
        const std::size_t comma = t.find(',');
        if (comma != std::string::npos && comma + 1 < t.size() &&
            std::isdigit(static_cast<unsigned char>(t[comma + 1])))
            t[comma] = '.';
    }
    const char* begin = t.c_str();
    char* end = nullptr;
    const double v = std::strtod(begin, &end);
    if (end == begin || !std::isfinite(v) || v < 0.0) return false;
    // strtod accepts "inf", "nan", hex: only plain decimals count.
    for (const char* p = begin; p < end; ++p)
        if (!std::isdigit(static_cast<unsigned char>(*p)) && *p != '.' && *p != '+' && *p != 'e' &&
            *p != 'E' && *p != '-')
            return false;
    value = v;
    rest = trim(std::string(end));
    return true;
}

bool oneOf(const std::string& v, std::initializer_list<const char*> values)
{
    for (const char* x : values)
        if (v == x) return true;
    return false;
}

double widthTagOr(const Tags& tags, double fallback)
{
    double w = 0.0;
    if (parseLength(tag(tags, "width"), w) && w > 0.0) return w;
    return fallback;
}

std::string leafType(const Tags& tags, const std::string& fallback)
{
    const std::string& leaf = tag(tags, "leaf_type");
    if (leaf == "broadleaved") return "deciduous";
    if (leaf == "needleleaved") return "coniferous";
    if (leaf == "mixed") return "mixed";
    return fallback;
}
} // namespace

bool parseNumber(const std::string& text, double& value)
{
    double v = 0.0;
    std::string rest;
    if (!leadingNumber(text, v, rest) || !rest.empty()) return false;
    value = v;
    return true;
}

bool parseLength(const std::string& text, double& metres)
{
    double v = 0.0;
    std::string rest;
    if (!leadingNumber(text, v, rest)) return false;
    if (rest.empty() || rest == "m" || rest == "meter" || rest == "meters" || rest == "metre" ||
        rest == "metres")
        metres = v;
    else if (rest == "cm")
        metres = v / 100.0;
    else if (rest == "km")
        metres = v * 1000.0;
    else if (rest == "ft" || rest == "feet")
        metres = v * 0.3048;
    else if (rest[0] == '\'')
    {
        // feet and optional inches: 12'6"
        double inches = 0.0;
        std::string r = trim(rest.substr(1)), tail;
        if (!r.empty())
        {
            if (!leadingNumber(r, inches, tail) || (tail != "\"" && !tail.empty())) return false;
        }
        metres = v * 0.3048 + inches * 0.0254;
    }
    else
        return false;
    return true;
}

const std::string& tag(const Tags& tags, const std::string& key)
{
    static const std::string empty;
    auto it = tags.find(key);
    return it == tags.end() ? empty : it->second;
}

double highwayWidth(const std::string& h)
{
    if (oneOf(h, {"motorway", "motorway_link"})) return 14.0;
    if (oneOf(h, {"trunk", "trunk_link"})) return 12.0;
    if (oneOf(h, {"primary", "primary_link"})) return 10.0;
    if (oneOf(h, {"secondary", "secondary_link"})) return 8.0;
    if (oneOf(h, {"tertiary", "tertiary_link"})) return 7.0;
    if (oneOf(h, {"residential", "unclassified"})) return 6.0;
    if (h == "service") return 4.0;
    if (oneOf(h, {"footway", "path", "cycleway", "steps", "pedestrian", "bridleway"})) return 2.0;
    if (h == "track") return 3.0;
    if (oneOf(h, {"living_street", "road", "busway"})) return 5.0;
    return 0.0; // proposed, construction, platform, corridor, raceway, ...: not a road here
}

std::string roadClass(const std::string& h, bool major)
{
    if (major) return "major";
    if (oneOf(h, {"footway", "path", "cycleway", "steps", "pedestrian", "bridleway"})) return "path";
    if (h == "track") return "track";
    return "minor";
}

bool isMajorHighway(const std::string& h)
{
    return oneOf(h, {"motorway", "motorway_link", "trunk", "trunk_link", "primary", "primary_link",
                     "secondary", "secondary_link"});
}

double waterwayWidth(const std::string& w)
{
    if (w == "river") return 12.0;
    if (w == "canal") return 8.0;
    if (w == "stream") return 3.0;
    if (w == "brook") return 2.0;
    if (oneOf(w, {"ditch", "drain"})) return 1.5;
    return 0.0;
}

Classification classifyArea(const Tags& tags)
{
    Classification c;
    const std::string& building = tag(tags, "building");
    if (!building.empty() && building != "no")
    {
        c.kind = Kind::Building;
        c.type = osgLoA::FeatureType::Building;
        c.subType = building == "yes" ? std::string() : building;
        c.sourceType = "building=" + building;
        return c;
    }
    const std::string &natural = tag(tags, "natural"), &waterway = tag(tags, "waterway"),
                      &landuse = tag(tags, "landuse"), &water = tag(tags, "water"),
                      &leisure = tag(tags, "leisure");
    if (natural == "water" || waterway == "riverbank" || landuse == "reservoir" || landuse == "basin" ||
        !water.empty())
    {
        c.kind = Kind::WaterArea;
        c.type = osgLoA::FeatureType::Water;
        if (water == "river" || water == "oxbow" || water == "stream" || waterway == "riverbank")
            c.subType = water == "stream" ? "stream" : "river";
        else if (water == "canal")
            c.subType = "canal";
        else if (water == "pond")
            c.subType = "pond";
        else if (water == "reservoir" || water == "basin" || landuse == "reservoir" || landuse == "basin")
            c.subType = "reservoir";
        else
            c.subType = "lake"; // natural=water, water=lake and anything else standing
        c.sourceType = natural == "water"        ? "natural=water"
                       : waterway == "riverbank" ? "waterway=riverbank"
                       : !landuse.empty()        ? "landuse=" + landuse
                                                 : "water=" + water;
        return c;
    }
    if (oneOf(landuse, {"grass", "forest", "meadow", "recreation_ground", "cemetery", "village_green",
                        "orchard", "allotments", "vineyard"}))
    {
        c.kind = Kind::GreenArea;
        c.sourceType = "landuse=" + landuse;
        c.subType = landuse == "forest" ? leafType(tags, "forest") : landuse;
    }
    else if (oneOf(leisure, {"park", "garden", "pitch", "golf_course", "playground", "nature_reserve"}))
    {
        c.kind = Kind::GreenArea;
        c.sourceType = "leisure=" + leisure;
        c.subType = leisure;
    }
    else if (oneOf(natural, {"wood", "scrub", "grassland", "heath"}))
    {
        c.kind = Kind::GreenArea;
        c.sourceType = "natural=" + natural;
        c.subType = natural == "wood" ? leafType(tags, "wood") : natural;
    }
    if (c.kind == Kind::GreenArea)
    {
        c.type = osgLoA::FeatureType::Green;
        return c;
    }
    const std::string& highway = tag(tags, "highway");
    if (!highway.empty() && highwayWidth(highway) > 0.0)
    {
        c.kind = Kind::RoadArea;
        c.type = osgLoA::FeatureType::Street;
        c.major = isMajorHighway(highway);
        c.subType = roadClass(highway, c.major);
        c.sourceType = "highway=" + highway;
    }
    return c;
}

Classification classifyLine(const Tags& tags)
{
    Classification c;
    const std::string& highway = tag(tags, "highway");
    const double hw = highwayWidth(highway);
    if (hw > 0.0 && tag(tags, "area") != "yes")
    {
        c.kind = Kind::Road;
        c.type = osgLoA::FeatureType::Street;
        c.major = isMajorHighway(highway);
        c.subType = roadClass(highway, c.major);
        c.sourceType = "highway=" + highway;
        c.width = widthTagOr(tags, hw);
        return c;
    }
    const std::string& waterway = tag(tags, "waterway");
    const double ww = waterwayWidth(waterway);
    if (ww > 0.0)
    {
        c.kind = Kind::WaterLine;
        c.type = osgLoA::FeatureType::Water;
        c.subType = (waterway == "river" || waterway == "canal") ? waterway : "stream";
        c.sourceType = "waterway=" + waterway;
        c.width = widthTagOr(tags, ww);
    }
    return c;
}

Classification classifyPoint(const Tags& tags)
{
    Classification c;
    if (tag(tags, "natural") == "tree")
    {
        c.kind = Kind::Tree;
        c.type = osgLoA::FeatureType::Green;
        c.subType = "tree";
        c.sourceType = "natural=tree";
    }
    return c;
}

} // namespace osmimport
