// The OpenStreetMap importer (plugins/osm) without GL: counts on real data checked against an
// independent scan of the XML, geometry checked against hand calculations on fixtures that the
// test writes itself, a DEM made with GDAL's GTiff driver, errors, and the .osgt round trip.
#include "support/TestSupport.h"

#include <osgLoA/semantics/Feature>
#include <osgLoA/semantics/FeatureIndex>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/TriangleFunctor>
#include <osg/ValueObject>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>
#include <osgDB/Registry>

#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <osmium/io/pbf_output.hpp>
#include <osmium/io/reader.hpp>
#include <osmium/io/writer.hpp>
#include <osmium/io/xml_input.hpp>

#include <bzlib.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using osgLoA::Feature;
using osgLoA::FeatureIndex;
using osgLoA::FeatureType;

namespace
{
const std::string kDataDir = std::string(LOA_SOURCE_DIR) + "/data/cache/python-osmnx-doc";

std::string dataFile(const std::string& name)
{
    return kDataDir + "/" + name;
}

bool haveData()
{
    return osgDB::fileExists(dataFile("kirchberg.osm")) && osgDB::fileExists(dataFile("West-Oakland.osm")) &&
           osgDB::fileExists(dataFile("West-Oakland.osm.bz2"));
}
#define REQUIRE_DATA()                                                                                       \
    if (!haveData())                                                                                         \
    FAIL() << "the OSM test data is missing from " << kDataDir << ": run scripts/fetch-test-data"

// Metres per degree on the WGS84 ellipsoid (series expansions), independent of PROJ.
double metresPerDegreeLat(double lat)
{
    const double p = osg::DegreesToRadians(lat);
    return 111132.92 - 559.82 * std::cos(2 * p) + 1.175 * std::cos(4 * p);
}
double metresPerDegreeLon(double lat)
{
    const double p = osg::DegreesToRadians(lat);
    return 111412.84 * std::cos(p) - 93.5 * std::cos(3 * p);
}

// --- an independent scan of OSM XML --------------------------------------------------------
// Hand-written on purpose (no GDAL): elements, attributes and the five XML entities.
struct XmlElement
{
    std::string name;
    std::map<std::string, std::string> attrs;
    bool closing = false, selfClosing = false;
};

std::string decode(const std::string& s)
{
    std::string out;
    for (std::size_t i = 0; i < s.size(); ++i)
    {
        if (s[i] != '&')
        {
            out += s[i];
            continue;
        }
        const std::size_t semi = s.find(';', i);
        const std::string e = s.substr(i + 1, semi - i - 1);
        out += e == "quot"   ? '"'
               : e == "amp"  ? '&'
               : e == "lt"   ? '<'
               : e == "gt"   ? '>'
               : e == "apos" ? '\''
                             : '?';
        i = semi;
    }
    return out;
}

std::vector<XmlElement> scanXml(const std::string& text)
{
    std::vector<XmlElement> out;
    std::size_t i = 0;
    while ((i = text.find('<', i)) != std::string::npos)
    {
        if (text.compare(i, 2, "<?") == 0 || text.compare(i, 2, "<!") == 0)
        {
            i = text.find('>', i);
            continue;
        }
        XmlElement e;
        std::size_t j = i + 1;
        if (text[j] == '/') e.closing = true, ++j;
        while (j < text.size() && !std::isspace(static_cast<unsigned char>(text[j])) && text[j] != '>' &&
               text[j] != '/')
            e.name += text[j++];
        for (;;)
        {
            while (j < text.size() && std::isspace(static_cast<unsigned char>(text[j])))
                ++j;
            if (j >= text.size()) break;
            if (text[j] == '>') break;
            if (text[j] == '/')
            {
                e.selfClosing = true;
                ++j;
                continue;
            }
            std::string key;
            while (j < text.size() && text[j] != '=')
                key += text[j++];
            const char quote = text[j + 1];
            const std::size_t end = text.find(quote, j + 2);
            e.attrs[key] = decode(text.substr(j + 2, end - j - 2));
            j = end + 1;
        }
        out.push_back(e);
        i = j;
    }
    return out;
}

struct OsmObj
{
    std::string type, id;
    std::map<std::string, std::string> tags;
    std::vector<std::string> refs;                               // way: node refs
    std::vector<std::pair<std::string, std::string>> wayMembers; // relation: (ref, role)
};

// The importer's definitions, restated here (docs/osm.md, "What counts"):
//  - building: a closed way (>= 4 refs, first == last, all nodes in the file, >= 3 distinct
//    nodes, an area of at least 1 m^2) or a multipolygon relation whose member ways are all in the file and
//    form closed rings, with building=* other than "no";
//  - road: a way with >= 2 distinct nodes in the file, highway=<one of kRoadClasses>, no area=yes;
//  - green: a closed way / multipolygon as above with one of the green tags.
const std::set<std::string> kRoadClasses = {
    "motorway",  "motorway_link",  "trunk",         "trunk_link",    "primary",     "primary_link",
    "secondary", "secondary_link", "tertiary",      "tertiary_link", "residential", "unclassified",
    "service",   "footway",        "path",          "cycleway",      "steps",       "pedestrian",
    "bridleway", "track",          "living_street", "road",          "busway"};

bool isGreen(const std::map<std::string, std::string>& t)
{
    static const std::set<std::string> landuse = {"grass",    "forest",        "meadow",  "recreation_ground",
                                                  "cemetery", "village_green", "orchard", "allotments",
                                                  "vineyard"},
                                       leisure = {"park",        "garden",     "pitch",
                                                  "golf_course", "playground", "nature_reserve"},
                                       natural = {"wood", "scrub", "grassland", "heath"};
    auto has = [&](const char* k, const std::set<std::string>& vals)
    { return t.count(k) && vals.count(t.at(k)) > 0; };
    return has("landuse", landuse) || has("leisure", leisure) || has("natural", natural);
}

struct XmlCounts
{
    unsigned buildingsTagged = 0, buildingsWithLevels = 0, buildings = 0, buildingsWithLevelsImported = 0,
             roads = 0, green = 0, water = 0;
};

XmlCounts countXml(const std::string& path)
{
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    std::map<std::string, std::pair<double, double>> nodes; // id -> lon, lat
    std::vector<OsmObj> objs;
    OsmObj* cur = nullptr;
    for (const XmlElement& e : scanXml(ss.str()))
    {
        if (e.closing) continue;
        if (e.name == "node" || e.name == "way" || e.name == "relation")
        {
            objs.push_back({e.name, e.attrs.at("id"), {}, {}, {}});
            cur = &objs.back();
            if (e.name == "node")
                nodes[e.attrs.at("id")] = {std::stod(e.attrs.at("lon")), std::stod(e.attrs.at("lat"))};
        }
        else if (cur && e.name == "tag")
            cur->tags[e.attrs.at("k")] = e.attrs.at("v");
        else if (cur && e.name == "nd")
            cur->refs.push_back(e.attrs.at("ref"));
        else if (cur && e.name == "member" && e.attrs.at("type") == "way")
            cur->wayMembers.push_back({e.attrs.at("ref"), e.attrs.at("role")});
    }
    std::map<std::string, const OsmObj*> ways;
    for (const OsmObj& o : objs)
        if (o.type == "way") ways[o.id] = &o;
    auto allPresent = [&](const OsmObj& w)
    {
        for (const std::string& r : w.refs)
            if (!nodes.count(r)) return false;
        return true;
    };
    auto closedWithArea = [&](const OsmObj& w)
    {
        if (w.refs.size() < 4 || w.refs.front() != w.refs.back() || !allPresent(w)) return false;
        double a = 0.0;
        for (std::size_t i = 0; i + 1 < w.refs.size(); ++i)
        {
            const auto &p = nodes[w.refs[i]], &q = nodes[w.refs[i + 1]];
            a += p.first * q.second - q.first * p.second;
        }
        const double lat = nodes[w.refs[0]].second;
        return 0.5 * std::fabs(a) * metresPerDegreeLat(lat) * metresPerDegreeLon(lat) >= 1.0; // m^2
    };
    auto relationComplete = [&](const OsmObj& r)
    {
        if (r.tags.count("type") == 0 || r.tags.at("type") != "multipolygon" || r.wayMembers.empty())
            return false;
        std::map<std::string, int> ends; // every ring end must meet another
        for (const auto& m : r.wayMembers)
        {
            auto it = ways.find(m.first);
            if (it == ways.end() || !allPresent(*it->second) || it->second->refs.size() < 2) return false;
            if (it->second->refs.front() == it->second->refs.back()) continue;
            ++ends[it->second->refs.front()];
            ++ends[it->second->refs.back()];
        }
        for (const auto& e : ends)
            if (e.second % 2) return false;
        return true;
    };
    XmlCounts c;
    for (const OsmObj& o : objs)
    {
        if (o.type == "node") continue;
        const bool area = o.type == "way" ? closedWithArea(o) : relationComplete(o);
        if (o.tags.count("building") && o.tags.at("building") != "no")
        {
            ++c.buildingsTagged;
            if (o.tags.count("building:levels")) ++c.buildingsWithLevels;
            if (area) ++c.buildings;
            if (area && o.tags.count("building:levels")) ++c.buildingsWithLevelsImported;
            continue;
        }
        if (o.type == "way" && o.tags.count("highway") && kRoadClasses.count(o.tags.at("highway")) &&
            !(o.tags.count("area") && o.tags.at("area") == "yes"))
        {
            std::set<std::string> distinct(o.refs.begin(), o.refs.end());
            if (distinct.size() >= 2 && allPresent(o)) ++c.roads;
        }
        if (area && isGreen(o.tags)) ++c.green;
        if (area && (o.tags.count("water") || (o.tags.count("natural") && o.tags.at("natural") == "water")))
            ++c.water;
    }
    return c;
}

// --- helpers ---------------------------------------------------------------------------------
osg::ref_ptr<osg::Node> load(const std::string& path, const std::string& options = "")
{
    osg::ref_ptr<osgDB::Options> opts = new osgDB::Options(options);
    return osgDB::readRefNodeFile(path, opts.get());
}

osgDB::ReaderWriter::ReadResult loadResult(const std::string& path, const std::string& options = "")
{
    osg::ref_ptr<osgDB::Options> opts = new osgDB::Options(options);
    return osgDB::Registry::instance()->readNode(path, opts.get());
}

const FeatureIndex::Entry* bySource(const FeatureIndex& index, const std::string& sourceId)
{
    for (const FeatureIndex::Entry& e : index.entries())
        if (e.feature->getSourceId() == sourceId) return &e;
    return nullptr;
}

struct AreaSum
{
    double area = 0.0;
    void operator()(const osg::Vec3& a, const osg::Vec3& b, const osg::Vec3& c, bool = false)
    {
        area += 0.5 * ((b - a) ^ (c - a)).length();
    }
};

double drawableArea(const osg::Node* node, const std::string& drawableName)
{
    const osg::Geode* g = node ? node->asGeode() : nullptr;
    double sum = 0.0;
    if (!g) return -1.0;
    for (unsigned i = 0; i < g->getNumDrawables(); ++i)
        if (g->getDrawable(i)->getName() == drawableName)
        {
            osg::TriangleFunctor<AreaSum> f;
            g->getDrawable(i)->accept(f);
            sum += f.area;
        }
    return sum;
}

/** GDAL's transformation from a recorded local CRS (a PROJ string) to WGS84 lon/lat; null if
 *  GDAL cannot make it. */
std::unique_ptr<OGRCoordinateTransformation> toWgs84(const std::string& crs)
{
    OGRSpatialReference local, wgs84;
    if (local.importFromProj4(crs.c_str()) != OGRERR_NONE) return nullptr;
    wgs84.SetWellKnownGeogCS("WGS84");
    local.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    return std::unique_ptr<OGRCoordinateTransformation>(OGRCreateCoordinateTransformation(&local, &wgs84));
}

// A tiny OSM document builder for fixtures.
class OsmWriter
{
public:
    std::string node(double lat, double lon, const std::map<std::string, std::string>& tags = {})
    {
        const std::string id = std::to_string(++_nextNode);
        std::ostringstream s;
        s.precision(10);
        s << "  <node id=\"" << id << "\" lat=\"" << lat << "\" lon=\"" << lon << "\"";
        if (tags.empty())
            s << "/>\n";
        else
            s << ">\n" << tagText(tags) << "  </node>\n";
        _nodes += s.str();
        return id;
    }
    /** A closed way round a rectangle of w x h metres centred at (lat, lon). */
    std::string box(double lat, double lon, double w, double h,
                    const std::map<std::string, std::string>& tags)
    {
        const double dx = 0.5 * w / metresPerDegreeLon(lat), dy = 0.5 * h / metresPerDegreeLat(lat);
        const std::string a = node(lat - dy, lon - dx), b = node(lat - dy, lon + dx),
                          c = node(lat + dy, lon + dx), d = node(lat + dy, lon - dx);
        return way({a, b, c, d, a}, tags);
    }
    std::string way(const std::vector<std::string>& refs, const std::map<std::string, std::string>& tags)
    {
        const std::string id = std::to_string(++_nextWay);
        _ways += "  <way id=\"" + id + "\">\n";
        for (const std::string& r : refs)
            _ways += "    <nd ref=\"" + r + "\"/>\n";
        _ways += tagText(tags) + "  </way>\n";
        return id;
    }
    std::string relation(const std::vector<std::pair<std::string, std::string>>& members,
                         const std::map<std::string, std::string>& tags)
    {
        const std::string id = std::to_string(++_nextRel);
        _rels += "  <relation id=\"" + id + "\">\n";
        for (const auto& m : members)
            _rels += "    <member type=\"way\" ref=\"" + m.first + "\" role=\"" + m.second + "\"/>\n";
        _rels += tagText(tags) + "  </relation>\n";
        return id;
    }
    std::string write(const std::string& name) const
    {
        const std::string path = loatest::freshDirectory("OsmImportTest-" + name) + "/" + name + ".osm";
        std::ofstream out(path);
        out << "<?xml version='1.0' encoding='UTF-8'?>\n<osm version=\"0.6\" generator=\"OsmImportTest\">\n"
            << _nodes << _ways << _rels << "</osm>\n";
        return path;
    }

private:
    static std::string escape(const std::string& s)
    {
        std::string o;
        for (char c : s)
            o += c == '"'   ? std::string("&quot;")
                 : c == '&' ? std::string("&amp;")
                 : c == '<' ? "&lt;"
                            : std::string(1, c);
        return o;
    }
    static std::string tagText(const std::map<std::string, std::string>& tags)
    {
        std::string s;
        for (const auto& kv : tags)
            s += "    <tag k=\"" + escape(kv.first) + "\" v=\"" + escape(kv.second) + "\"/>\n";
        return s;
    }
    long _nextNode = 100, _nextWay = 1000, _nextRel = 5000;
    std::string _nodes, _ways, _rels;
};

std::string writeText(const std::string& name, const std::string& text)
{
    const std::string path = loatest::freshDirectory("OsmImportTest-" + name) + "/" + name;
    std::ofstream(path) << text;
    return path;
}
} // namespace

// --- real data -------------------------------------------------------------------------------
TEST(OsmImportTest, KirchbergCountsMatchAnIndependentScan)
{
    REQUIRE_DATA();
    const XmlCounts xml = countXml(dataFile("kirchberg.osm"));
    // Facts of the file (shared/data/README.md): 33 building ways, 10 with building:levels. Two
    // of them are cut by the extract (one node; three collinear nodes): 31 importable.
    EXPECT_EQ(xml.buildingsTagged, 33u);
    EXPECT_EQ(xml.buildingsWithLevels, 10u);
    EXPECT_EQ(xml.buildings, 31u);
    EXPECT_EQ(xml.roads, 14u); // 19 highway ways, 5 of them cut to one node by the extract

    osg::ref_ptr<osg::Node> n = load(dataFile("kirchberg.osm"));
    ASSERT_TRUE(n.valid()) << "osgdb_osm not found on OSG_LIBRARY_PATH, or the import failed";
    const FeatureIndex::Counts c = FeatureIndex(*n).counts();
    EXPECT_EQ(c.get(FeatureType::Building), xml.buildings);
    EXPECT_EQ(c.get(FeatureType::Street), xml.roads);
    EXPECT_EQ(c.get(FeatureType::Green), xml.green);
    EXPECT_EQ(c.get(FeatureType::Water), xml.water);
    EXPECT_EQ(c.get(FeatureType::Terrain), 1u);
    unsigned skipped = 0;
    ASSERT_TRUE(n->getUserValue("loa.skippedDegenerate", skipped));
    EXPECT_EQ(skipped, 1u); // the zero-area building; OGR itself drops the one-node ways

    // Buildings with building:levels are 3 m a storey (plus flat ground at 0).
    const FeatureIndex index(*n);
    unsigned withLevels = 0;
    for (const FeatureIndex::Entry& e : index.entries())
    {
        if (e.feature->getType() != FeatureType::Building) continue;
        EXPECT_EQ(e.feature->getLod(), 1.0f);
        std::string levels;
        if (!e.node->getUserValue("osm.building:levels", levels)) continue;
        ++withLevels;
        EXPECT_NEAR(e.feature->getBound().zMax(), 3.0 * std::stod(levels), 1e-3) << e.feature->getSourceId();
    }
    EXPECT_EQ(withLevels, xml.buildingsWithLevelsImported);
    EXPECT_EQ(withLevels, 9u); // the one-node building has building:levels=2
}

TEST(OsmImportTest, WestOaklandBz2CountsMatchAnIndependentScan)
{
    REQUIRE_DATA();
    const XmlCounts xml = countXml(dataFile("West-Oakland.osm"));
    EXPECT_EQ(xml.buildingsTagged, 23u); // shared/data/README.md
    EXPECT_EQ(xml.buildings, 23u);
    EXPECT_EQ(xml.roads, 31u);
    EXPECT_EQ(xml.green, 2u); // a park and a playground

    osg::ref_ptr<osg::Node> bz = load(dataFile("West-Oakland.osm.bz2"));
    ASSERT_TRUE(bz.valid()) << "osgdb_bz2 (a link to osgdb_osm) not found, or the import failed";
    const FeatureIndex::Counts c = FeatureIndex(*bz).counts();
    EXPECT_EQ(c.get(FeatureType::Building), xml.buildings);
    EXPECT_EQ(c.get(FeatureType::Street), xml.roads);
    EXPECT_EQ(c.get(FeatureType::Green), xml.green);
    EXPECT_EQ(c.get(FeatureType::Water), xml.water);

    // The decompressed file gives the same scene.
    osg::ref_ptr<osg::Node> plain = load(dataFile("West-Oakland.osm"));
    ASSERT_TRUE(plain.valid());
    EXPECT_EQ(FeatureIndex(*plain).counts().toJson(), c.toJson());
    std::string crsA, crsB;
    bz->getUserValue("loa.crs", crsA);
    plain->getUserValue("loa.crs", crsB);
    EXPECT_EQ(crsA, crsB);

    // Sub-types: secondary roads are major, the rest minor.
    unsigned major = 0;
    const FeatureIndex bzIndex(*bz);
    for (const FeatureIndex::Entry& e : bzIndex.entries())
        if (e.feature->getType() == FeatureType::Street && e.feature->getSubType() == "major") ++major;
    EXPECT_EQ(major, 5u);
}

/** The osgt text of a scene without its loa.source value (the file name). */
std::string sceneText(osg::Node& n)
{
    n.setUserValue("loa.source", std::string());
    return loatest::toOsgt(n);
}

// The formats: XML, PBF (written here from the real XML by libosmium's writer, so its reading is
// checked against the XML's) and bzip2 in several streams as pbzip2 writes it give one scene.
TEST(OsmImportTest, PbfAndMultiStreamBz2GiveTheXmlScene)
{
    REQUIRE_DATA();
    const std::string dir = loatest::freshDirectory("OsmImportTest-formats");
    const std::string pbf = dir + "/kirchberg.osm.pbf";
    {
        osmium::io::Reader reader(dataFile("kirchberg.osm"));
        osmium::io::Writer writer(pbf);
        while (osmium::memory::Buffer buffer = reader.read())
            writer(std::move(buffer));
        writer.close();
        reader.close();
    }
    osg::ref_ptr<osg::Node> xml = load(dataFile("kirchberg.osm"));
    osg::ref_ptr<osg::Node> fromPbf = load(pbf);
    ASSERT_TRUE(xml.valid());
    ASSERT_TRUE(fromPbf.valid());
    EXPECT_EQ(FeatureIndex(*fromPbf).counts().toJson(), FeatureIndex(*xml).counts().toJson());
    EXPECT_EQ(sceneText(*fromPbf), sceneText(*xml));

    // Three bzip2 streams, each a third of the XML, one after the other.
    std::ifstream in(dataFile("kirchberg.osm"), std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::string packed;
    for (std::size_t part = 0; part < 3; ++part)
    {
        const std::size_t from = text.size() * part / 3, to = text.size() * (part + 1) / 3;
        std::vector<char> out(to - from + (to - from) / 100 + 700);
        unsigned outSize = static_cast<unsigned>(out.size());
        ASSERT_EQ(BZ2_bzBuffToBuffCompress(out.data(), &outSize, const_cast<char*>(text.data() + from),
                                           static_cast<unsigned>(to - from), 9, 0, 0),
                  BZ_OK);
        packed.append(out.data(), outSize);
    }
    const std::string bz2 = dir + "/kirchberg.osm.bz2";
    std::ofstream(bz2, std::ios::binary) << packed;
    osg::ref_ptr<osg::Node> fromBz2 = load(bz2);
    ASSERT_TRUE(fromBz2.valid());
    EXPECT_EQ(sceneText(*fromBz2), sceneText(*xml));
}

// GDAL's OSM driver read these files before libosmium; its default osmconf.ini rules stay: a closed
// way is an area with an area key (building, landuse, ...) or area=yes, never with area=no; the
// ignore list (note, source, fixme, ...) is dropped; a node tagged only with "unsignificant" keys
// is no point; multipolygon relations are assembled only when every member way is in the file.
TEST(OsmImportTest, ClosedWaysRelationsAndTagsFollowOsmconf)
{
    OsmWriter w;
    const double lat = 47.5, lon = 9.5;
    const std::string roundabout = w.box(lat, lon, 40, 40, {{"highway", "residential"}});
    const std::string square = w.box(lat + 0.001, lon, 30, 30, {{"highway", "pedestrian"}, {"area", "yes"}});
    const std::string notArea = w.box(lat + 0.002, lon, 30, 30, {{"building", "yes"}, {"area", "no"}});
    const std::string house =
        w.box(lat + 0.003, lon, 10, 10, {{"building", "house"}, {"note", "checked"}, {"source", "survey"}});
    const std::string tree = w.node(lat + 0.004, lon, {{"natural", "tree"}, {"fixme", "species?"}});
    w.node(lat + 0.004, lon + 0.001, {{"source", "survey"}, {"created_by", "JOSM"}});
    const std::string park = w.box(lat + 0.005, lon, 50, 50, {});
    const std::string parkRel =
        w.relation({{park, "outer"}}, {{"type", "multipolygon"}, {"leisure", "park"}});
    const std::string missing =
        w.relation({{park, "outer"}, {"999999", "outer"}}, {{"type", "multipolygon"}, {"landuse", "grass"}});
    osg::ref_ptr<osg::Node> n = load(w.write("osmconf"));
    ASSERT_TRUE(n.valid());
    const FeatureIndex index(*n);
    const FeatureIndex::Entry* e = bySource(index, "way/" + roundabout);
    ASSERT_NE(e, nullptr);
    EXPECT_EQ(e->feature->getSourceType(), "highway=residential"); // a road ribbon, not an area
    EXPECT_GT(drawableArea(e->node.get(), "TrafficArea"), 0.0);
    e = bySource(index, "way/" + square);
    ASSERT_NE(e, nullptr);
    EXPECT_NEAR(drawableArea(e->node.get(), "TrafficArea"), 900.0, 9.0); // the square, flat
    EXPECT_EQ(bySource(index, "way/" + notArea), nullptr);               // a building line: nothing
    e = bySource(index, "way/" + house);
    ASSERT_NE(e, nullptr);
    std::string value;
    EXPECT_TRUE(e->node->getUserValue("osm.building", value));
    EXPECT_FALSE(e->node->getUserValue("osm.note", value));
    EXPECT_FALSE(e->node->getUserValue("osm.source", value));
    e = bySource(index, "node/" + tree);
    ASSERT_NE(e, nullptr);
    EXPECT_FALSE(e->node->getUserValue("osm.fixme", value));
    ASSERT_NE(bySource(index, "relation/" + parkRel), nullptr);
    EXPECT_EQ(bySource(index, "relation/" + missing), nullptr);
    EXPECT_EQ(index.counts().get(FeatureType::Green), 2u); // the tree and the park
    EXPECT_EQ(index.counts().get(FeatureType::Building), 1u);
    EXPECT_EQ(index.counts().get(FeatureType::Street), 2u);
}

// JOSM saves new objects with negative ids; an OSM file lists nodes, then ways, then relations, and
// one that does not is refused with a message that says so (the ways' nodes would be unknown).
TEST(OsmImportTest, NegativeIdsReadAndOrderIsChecked)
{
    const std::string josm = writeText(
        "josm.osm",
        "<?xml version='1.0'?>\n<osm version=\"0.6\" generator=\"JOSM\">\n"
        " <node id=\"-3\" lat=\"48.0\" lon=\"11.0\"/><node id=\"-2\" lat=\"48.0\" lon=\"11.0002\"/>\n"
        " <node id=\"-1\" lat=\"48.0002\" lon=\"11.0002\"/><node id=\"7\" lat=\"48.0002\" lon=\"11.0\"/>\n"
        " <way id=\"-5\"><nd ref=\"-3\"/><nd ref=\"-2\"/><nd ref=\"-1\"/><nd ref=\"7\"/><nd ref=\"-3\"/>"
        "<tag k=\"building\" v=\"yes\"/></way>\n</osm>\n");
    osg::ref_ptr<osg::Node> n = load(josm);
    ASSERT_TRUE(n.valid());
    const FeatureIndex index(*n);
    const FeatureIndex::Entry* e = bySource(index, "way/-5");
    ASSERT_NE(e, nullptr);
    const double side = 0.0002 * metresPerDegreeLat(48.0), across = 0.0002 * metresPerDegreeLon(48.0);
    EXPECT_NEAR(drawableArea(e->node.get(), "RoofSurface"), side * across, 0.01 * side * across);

    const std::string late = writeText(
        "late.osm", "<osm version=\"0.6\"><way id=\"5\"><nd ref=\"1\"/><nd ref=\"2\"/>"
                    "<tag k=\"highway\" v=\"residential\"/></way><node id=\"1\" lat=\"48\" lon=\"11\"/>"
                    "<node id=\"2\" lat=\"48\" lon=\"11.001\"/></osm>\n");
    auto rr = loadResult(late);
    EXPECT_FALSE(rr.validNode());
    EXPECT_NE(rr.message().find("node 1 comes after ways or relations"), std::string::npos) << rr.message();

    // libosmium 2.19 overflows on a coordinate's large exponent (undefined behaviour; OsmFuzzer's
    // campaign): coordinates with an exponent or a character reference are refused first, in a
    // plain file and inflated from bzip2 alike; plain decimals with spaces around '=' read.
    const std::string node = "<osm version=\"0.6\"><node id=\"1\" lat=\"48\" lon=\"11\"><tag k=\"natural\" "
                             "v=\"tree\"/></node>\n<node id=\"2\" lat = '48.0001'\n lon=";
    rr = loadResult(writeText("exponent.osm", node + "\"4.8e20\"/></osm>\n"));
    EXPECT_NE(rr.message().find("has the coordinate lon=\"4.8e20\" (byte 120), written with an exponent"),
              std::string::npos)
        << rr.message();
    rr = loadResult(writeText("reference.osm", node + "\"11&#46;0\"/></osm>\n"));
    EXPECT_NE(rr.message().find("has the coordinate lon=\"11&#46;0\""), std::string::npos) << rr.message();
    EXPECT_TRUE(load(writeText("spaced.osm", node + "'11.0001'/></osm>\n")).valid());
    {
        const std::string xml = node + "\"-1E+9\"/></osm>\n";
        std::vector<char> out(xml.size() + 700);
        unsigned outSize = static_cast<unsigned>(out.size());
        ASSERT_EQ(BZ2_bzBuffToBuffCompress(out.data(), &outSize, const_cast<char*>(xml.data()),
                                           static_cast<unsigned>(xml.size()), 9, 0, 0),
                  BZ_OK);
        const std::string path = loatest::freshDirectory("OsmImportTest-exponent") + "/exponent.osm.bz2";
        std::ofstream(path, std::ios::binary).write(out.data(), outSize);
        rr = loadResult(path);
        EXPECT_NE(rr.message().find("has the coordinate lon=\"-1E+9\""), std::string::npos) << rr.message();
    }

    rr = loadResult(writeText("truncated.osm.bz2", std::string("BZh91AY&SY", 10)));
    EXPECT_FALSE(rr.validNode());
    EXPECT_NE(rr.message().find("not valid bzip2 data"), std::string::npos) << rr.message();
}

// --- fixtures --------------------------------------------------------------------------------
TEST(OsmImportTest, ExtrusionHeightsFromHeightLevelsAndDefault)
{
    OsmWriter w;
    const std::string a = w.box(48.0, 11.0, 10, 10, {{"building", "yes"}, {"height", "12"}});
    const std::string b = w.box(48.0, 11.001, 10, 10, {{"building", "yes"}, {"building:levels", "4"}});
    const std::string c = w.box(48.0, 11.002, 10, 10, {{"building", "house"}});
    const std::string d = w.box(48.0, 11.003, 10, 10, {{"building", "yes"}, {"height", "12.5 m"}});
    const std::string e = w.box(48.0, 11.004, 10, 10, {{"building", "yes"}, {"height", "40 ft"}});
    const std::string f =
        w.box(48.0, 11.005, 10, 10, {{"building", "yes"}, {"height", "10"}, {"min_height", "3"}});
    const std::string g = w.box(48.0, 11.006, 10, 10,
                                {{"building", "yes"}, {"building:levels", "5"}, {"building:min_level", "2"}});
    const std::string path = w.write("heights");

    osg::ref_ptr<osg::Node> n = load(path, "storey=3.0 defaultHeight=9");
    ASSERT_TRUE(n.valid());
    const FeatureIndex index(*n);
    auto zRange = [&](const std::string& id)
    {
        const FeatureIndex::Entry* en = bySource(index, "way/" + id);
        EXPECT_NE(en, nullptr) << id;
        return en ? std::make_pair(en->feature->getBound().zMin(), en->feature->getBound().zMax())
                  : std::make_pair(-1.0f, -1.0f);
    };
    EXPECT_NEAR(zRange(a).second, 12.0, 1e-4);
    EXPECT_NEAR(zRange(b).second, 12.0, 1e-4); // 4 levels x 3 m
    EXPECT_NEAR(zRange(c).second, 9.0, 1e-4);  // default
    EXPECT_NEAR(zRange(d).second, 12.5, 1e-4);
    EXPECT_NEAR(zRange(e).second, 40 * 0.3048, 1e-4);
    EXPECT_NEAR(zRange(f).first, 3.0, 1e-4);
    EXPECT_NEAR(zRange(f).second, 10.0, 1e-4);
    EXPECT_NEAR(zRange(g).first, 6.0, 1e-4);
    EXPECT_NEAR(zRange(g).second, 15.0, 1e-4);

    // Options change the storey and the default.
    osg::ref_ptr<osg::Node> m = load(path, "storey=2.5 defaultHeight=7");
    ASSERT_TRUE(m.valid());
    const FeatureIndex index2(*m);
    EXPECT_NEAR(bySource(index2, "way/" + b)->feature->getBound().zMax(), 10.0, 1e-4);
    EXPECT_NEAR(bySource(index2, "way/" + c)->feature->getBound().zMax(), 7.0, 1e-4);

    // Features: ids from 1, sources, names.
    const FeatureIndex::Entry* ea = bySource(index, "way/" + a);
    ASSERT_NE(ea, nullptr);
    EXPECT_EQ(ea->feature->getId(), 1u);
    EXPECT_EQ(ea->feature->getSourceType(), "building=yes");
    EXPECT_EQ(ea->feature->getSource(), Feature::MODEL_DATA);
    EXPECT_EQ(bySource(index, "way/" + c)->feature->getSourceType(), "building=house");
    bool walls = false, roof = false;
    const osg::Geode* geode = ea->node->asGeode();
    ASSERT_NE(geode, nullptr);
    for (unsigned i = 0; i < geode->getNumDrawables(); ++i)
    {
        walls |= geode->getDrawable(i)->getName() == "WallSurface";
        roof |= geode->getDrawable(i)->getName() == "RoofSurface";
    }
    EXPECT_TRUE(walls && roof);
    // The roof of a 10 m x 10 m box.
    EXPECT_NEAR(drawableArea(ea->node.get(), "RoofSurface"), 100.0, 1.0);
}

TEST(OsmImportTest, BuildingWithAHoleHasARoofOfOuterMinusInner)
{
    OsmWriter w;
    const double lat = 47.5, lon = 9.5;
    const std::string outer = w.box(lat, lon, 40, 30, {});
    const std::string inner = w.box(lat, lon + 0.00005, 12, 8, {});
    const std::string rel =
        w.relation({{outer, "outer"}, {inner, "inner"}}, {{"type", "multipolygon"}, {"building", "yes"}});
    const std::string path = w.write("hole");
    osg::ref_ptr<osg::Node> n = load(path);
    ASSERT_TRUE(n.valid());
    const FeatureIndex index(*n);
    const FeatureIndex::Entry* e = bySource(index, "relation/" + rel);
    ASSERT_NE(e, nullptr);
    // Expected from the ellipsoid's metres per degree, not from the importer's projection.
    const double expected = 40.0 * 30.0 - 12.0 * 8.0;
    EXPECT_NEAR(drawableArea(e->node.get(), "RoofSurface"), expected, 0.01 * expected);
    EXPECT_EQ(index.counts().get(FeatureType::Building), 1u);
}

TEST(OsmImportTest, RoadRibbonAreaIsLengthTimesWidth)
{
    OsmWriter w;
    const double lat = 48.1, lon = 10.0, len = 100.0;
    const double dLon = len / metresPerDegreeLon(lat);
    const std::string r1 = w.way({w.node(lat, lon), w.node(lat, lon + dLon)}, {{"highway", "residential"}});
    const std::string r2 = w.way({w.node(lat + 0.001, lon), w.node(lat + 0.001, lon + dLon)},
                                 {{"highway", "primary"}, {"width", "4.5"}});
    const std::string r3 =
        w.way({w.node(lat + 0.002, lon), w.node(lat + 0.002, lon + dLon)}, {{"highway", "motorway"}});
    // A right-angle bend: mitered, so the area is (a + b) x width exactly at the outer corner.
    const double dLat = 50.0 / metresPerDegreeLat(lat);
    const std::string r4 = w.way(
        {w.node(lat + 0.003, lon), w.node(lat + 0.003, lon + dLon), w.node(lat + 0.003 + dLat, lon + dLon)},
        {{"highway", "footway"}});
    const std::string ignored =
        w.way({w.node(lat + 0.004, lon), w.node(lat + 0.004, lon + dLon)}, {{"highway", "proposed"}});
    const std::string path = w.write("roads");
    osg::ref_ptr<osg::Node> n = load(path);
    ASSERT_TRUE(n.valid());
    const FeatureIndex index(*n);
    EXPECT_EQ(index.counts().get(FeatureType::Street), 4u);
    EXPECT_EQ(bySource(index, "way/" + ignored), nullptr);
    const FeatureIndex::Entry *e1 = bySource(index, "way/" + r1), *e2 = bySource(index, "way/" + r2),
                              *e3 = bySource(index, "way/" + r3), *e4 = bySource(index, "way/" + r4);
    ASSERT_TRUE(e1 && e2 && e3 && e4);
    EXPECT_NEAR(drawableArea(e1->node.get(), "TrafficArea"), len * 6.0, 0.01 * len * 6.0);
    EXPECT_NEAR(drawableArea(e2->node.get(), "TrafficArea"), len * 4.5, 0.01 * len * 4.5); // width tag wins
    EXPECT_NEAR(drawableArea(e3->node.get(), "TrafficArea"), len * 14.0, 0.01 * len * 14.0);
    // Mitered right angle of a 2 m path: centre line length x width.
    EXPECT_NEAR(drawableArea(e4->node.get(), "TrafficArea"), (len + 50.0) * 2.0, 0.01 * 300.0);
    EXPECT_EQ(e1->feature->getSubType(), "minor");
    EXPECT_EQ(e4->feature->getSubType(), "path"); // highway=footway
    EXPECT_EQ(e2->feature->getSubType(), "major");
    EXPECT_EQ(e2->feature->getSourceType(), "highway=primary");
    // Roads lie above the ground (flat at 0), by the draping offset.
    EXPECT_GT(e1->feature->getBound().zMin(), 0.05f);
    EXPECT_LT(e1->feature->getBound().zMax(), 1.0f);
}

TEST(OsmImportTest, ProjectionIsMetricAndRecordedOnTheRoot)
{
    OsmWriter w;
    const std::string t1 = w.node(48.0, 11.0, {{"natural", "tree"}, {"name", "Linde"}});
    // other_tags round trip: quotes, a backslash and an hstore-looking value.
    const std::string t2 = w.node(
        48.001, 11.0,
        {{"natural", "tree"}, {"description", "He said \"hi\", \\ok =>\"x\""}, {"leaf_type", "broadleaved"}});
    const std::string path = w.write("projection");
    osg::ref_ptr<osg::Node> n = load(path);
    ASSERT_TRUE(n.valid());
    const FeatureIndex index(*n);
    const FeatureIndex::Entry *a = bySource(index, "node/" + t1), *b = bySource(index, "node/" + t2);
    ASSERT_TRUE(a && b);
    const osg::Vec3 ca = a->feature->getBound().center(), cb = b->feature->getBound().center();
    const double d = std::hypot(ca.x() - cb.x(), ca.y() - cb.y());
    EXPECT_NEAR(d, 0.001 * metresPerDegreeLat(48.0005), 0.5); // ~111.2 m
    EXPECT_NEAR(d, 111.2, 0.5);
    EXPECT_NEAR(cb.y() - ca.y(), d, 1e-3); // north is +y
    EXPECT_NEAR(ca.x(), 0.0, 1e-3);        // centred on the data

    osg::Vec3d origin(1, 1, 1), lonLat;
    std::string crs;
    ASSERT_TRUE(n->getUserValue("loa.origin", origin));
    ASSERT_TRUE(n->getUserValue("loa.crs", crs));
    ASSERT_TRUE(n->getUserValue("loa.originLonLat", lonLat));
    EXPECT_EQ(origin, osg::Vec3d(0, 0, 0));
    EXPECT_NE(crs.find("+proj=tmerc"), std::string::npos) << crs;
    EXPECT_NEAR(lonLat.x(), 11.0, 1e-9);
    EXPECT_NEAR(lonLat.y(), 48.0005, 1e-9);

    // Map a point back with the recorded CRS.
    std::unique_ptr<OGRCoordinateTransformation> ct = toWgs84(crs);
    ASSERT_TRUE(ct) << crs;
    double x = cb.x(), y = cb.y();
    ASSERT_TRUE(ct->Transform(1, &x, &y));
    EXPECT_NEAR(x, 11.0, 1e-8);
    EXPECT_NEAR(y, 48.001, 1e-8);

    // Trees: green features with trunk and crown; tags kept as user values.
    EXPECT_EQ(a->feature->getType(), FeatureType::Green);
    EXPECT_EQ(a->feature->getSubType(), "tree");
    EXPECT_GT(drawableArea(a->node.get(), "TreeTrunk"), 0.0);
    EXPECT_GT(drawableArea(a->node.get(), "TreeCrown"), 0.0);
    std::string name, description;
    EXPECT_TRUE(a->node->getUserValue("osm.name", name));
    EXPECT_EQ(name, "Linde");
    EXPECT_TRUE(b->node->getUserValue("osm.description", description));
    EXPECT_EQ(description, "He said \"hi\", \\ok =>\"x\"");
}

TEST(OsmImportTest, FarPointsMapBackThroughTheRecordedCrs)
{
    // Trees up to ~100 km from the data's centre (60.0 N, 10.0 E): each lands where the recorded
    // CRS, applied by GDAL/PROJ as a whole, maps it back (the importer projects through one
    // pipeline centred on (0, 0) and shifts). Geometry is float: ~1 cm at 100 km, so 3e-7 deg.
    OsmWriter w;
    const double points[][2] = {{59.5, 8.5}, {60.5, 11.5}, {60.0, 10.0}, {59.9, 11.2}, {60.3, 8.9}};
    std::vector<std::string> ids;
    for (const auto& p : points)
        ids.push_back(w.node(p[0], p[1], {{"natural", "tree"}}));
    osg::ref_ptr<osg::Node> n = load(w.write("far-points"));
    ASSERT_TRUE(n.valid());
    std::string crs;
    ASSERT_TRUE(n->getUserValue("loa.crs", crs));
    std::unique_ptr<OGRCoordinateTransformation> ct = toWgs84(crs);
    ASSERT_TRUE(ct) << crs;
    const FeatureIndex index(*n);
    for (std::size_t i = 0; i < ids.size(); ++i)
    {
        const FeatureIndex::Entry* e = bySource(index, "node/" + ids[i]);
        ASSERT_TRUE(e) << ids[i];
        const osg::Vec3 c = e->feature->getBound().center();
        double x = c.x(), y = c.y();
        ASSERT_TRUE(ct->Transform(1, &x, &y));
        EXPECT_NEAR(x, points[i][1], 3e-7) << "tree " << i;
        EXPECT_NEAR(y, points[i][0], 3e-7) << "tree " << i;
    }
}

TEST(OsmImportTest, FlatGroundIsOneQuadAndAGridWhenACellIsAsked)
{
    // Two trees 0.001 deg of latitude apart (111.2 m), margin 30 m: the ground spans 60 x 171.2 m.
    OsmWriter w;
    w.node(48.0, 11.0, {{"natural", "tree"}});
    w.node(48.001, 11.0, {{"natural", "tree"}});
    const std::string path = w.write("flat-ground");
    const double width = 60.0, height = 0.001 * metresPerDegreeLat(48.0005) + 60.0;
    struct Case
    {
        const char* options;
        unsigned vertices, triangles;
    };
    // One quad by default; terrainCell=50: ceil(60/50) x ceil(171.2/50) = 2 x 4 cells.
    for (const Case& c : {Case{"", 4, 2}, Case{"terrainCell=50", 3 * 5, 2 * 2 * 4}})
    {
        osg::ref_ptr<osg::Node> n = load(path, c.options);
        ASSERT_TRUE(n.valid()) << c.options;
        const FeatureIndex index(*n);
        const FeatureIndex::Entry* terrain = nullptr;
        for (const FeatureIndex::Entry& e : index.entries())
            if (e.feature->getType() == FeatureType::Terrain) terrain = &e;
        ASSERT_TRUE(terrain) << c.options;
        const osg::Geode* g = terrain->node->asGeode();
        ASSERT_TRUE(g && g->getNumDrawables() == 1) << c.options;
        const osg::Geometry* geometry = g->getDrawable(0)->asGeometry();
        ASSERT_TRUE(geometry && geometry->getName() == "TINRelief") << c.options;
        EXPECT_EQ(geometry->getVertexArray()->getNumElements(), c.vertices) << c.options;
        ASSERT_EQ(geometry->getNumPrimitiveSets(), 1u);
        EXPECT_EQ(geometry->getPrimitiveSet(0)->getNumIndices(), 3 * c.triangles) << c.options;
        EXPECT_NEAR(drawableArea(g, "TINRelief"), width * height, 1.0) << c.options;
    }
}

TEST(OsmImportTest, WaterAndGreenSubTypes)
{
    OsmWriter w;
    const std::string pond = w.box(48.0, 11.0, 30, 20, {{"natural", "water"}, {"water", "pond"}});
    const std::string lake = w.box(48.0, 11.001, 30, 20, {{"natural", "water"}});
    const std::string bank = w.box(48.0, 11.002, 30, 20, {{"waterway", "riverbank"}});
    const std::string res = w.box(48.0, 11.003, 30, 20, {{"landuse", "reservoir"}});
    const std::string forest =
        w.box(48.001, 11.0, 30, 20, {{"landuse", "forest"}, {"leaf_type", "needleleaved"}});
    const std::string wood = w.box(48.001, 11.001, 30, 20, {{"natural", "wood"}});
    const std::string park = w.box(48.001, 11.002, 30, 20, {{"leisure", "park"}});
    const std::string river =
        w.way({w.node(48.002, 11.0), w.node(48.002, 11.001)}, {{"waterway", "river"}, {"name", "Iller"}});
    const std::string ditch =
        w.way({w.node(48.0025, 11.0), w.node(48.0025, 11.001)}, {{"waterway", "ditch"}});
    const std::string farmland = w.box(48.003, 11.0, 30, 20, {{"landuse", "farmland"}});
    // Degenerate: three collinear nodes (zero area), and a two-node closed way.
    const std::string a = w.node(48.004, 11.0), b = w.node(48.004, 11.0001), c = w.node(48.004, 11.0002);
    const std::string flat = w.way({a, b, c, a}, {{"building", "yes"}});
    const std::string path = w.write("water");
    osg::ref_ptr<osg::Node> n = load(path);
    ASSERT_TRUE(n.valid());
    const FeatureIndex index(*n);
    auto sub = [&](const std::string& id)
    {
        const FeatureIndex::Entry* e = bySource(index, id);
        return e ? toString(e->feature->getType()) + std::string("/") + e->feature->getSubType()
                 : std::string("none");
    };
    EXPECT_EQ(sub("way/" + pond), "water/pond");
    EXPECT_EQ(sub("way/" + lake), "water/lake");
    EXPECT_EQ(sub("way/" + bank), "water/river");
    EXPECT_EQ(sub("way/" + res), "water/reservoir");
    EXPECT_EQ(sub("way/" + forest), "green/coniferous");
    EXPECT_EQ(sub("way/" + wood), "green/wood");
    EXPECT_EQ(sub("way/" + park), "green/park");
    EXPECT_EQ(sub("way/" + river), "water/river");
    EXPECT_EQ(sub("way/" + ditch), "water/stream");
    EXPECT_EQ(sub("way/" + farmland), "none");
    EXPECT_EQ(sub("way/" + flat), "none");
    unsigned skipped = 0;
    EXPECT_TRUE(n->getUserValue("loa.skippedDegenerate", skipped));
    EXPECT_EQ(skipped, 1u);
    // Flat polygons: the pond's area; layered above the ground, water above green.
    const FeatureIndex::Entry* ep = bySource(index, "way/" + pond);
    ASSERT_NE(ep, nullptr);
    EXPECT_NEAR(drawableArea(ep->node.get(), "WaterSurface"), 600.0, 6.0);
    EXPECT_NEAR(drawableArea(bySource(index, "way/" + river)->node.get(), "WaterSurface"),
                12.0 * 0.001 * metresPerDegreeLon(48.002), 0.01 * 12.0 * 75.0);
    EXPECT_GT(ep->feature->getBound().zMin(), bySource(index, "way/" + park)->feature->getBound().zMin());
    EXPECT_GT(bySource(index, "way/" + park)->feature->getBound().zMin(), 0.0f);
}

// --- DEM -------------------------------------------------------------------------------------
namespace
{
// Heights linear in longitude: 100 m at lon0, +1 m per 0.001 degree (bilinear interpolation
// between pixel centres reproduces it exactly).
constexpr double kDemLon0 = 10.99, kDemLat1 = 48.01, kDemPixel = 0.001;
constexpr int kDemSize = 20;
double demHeight(double lon)
{
    return 100.0 + (lon - kDemLon0) / kDemPixel;
}

std::string writeDem()
{
    GDALAllRegister();
    const std::string path = loatest::freshDirectory("OsmImportTest-demfile") + "/dem.tif";
    GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GTiff");
    if (!drv) return std::string();
    GDALDatasetUniquePtr ds(drv->Create(path.c_str(), kDemSize, kDemSize, 1, GDT_Float32, nullptr));
    if (!ds) return std::string();
    double gt[6] = {kDemLon0, kDemPixel, 0, kDemLat1, 0, -kDemPixel};
    ds->SetGeoTransform(gt);
    OGRSpatialReference srs;
    srs.SetWellKnownGeogCS("WGS84");
    ds->SetSpatialRef(&srs);
    std::vector<float> h(kDemSize * kDemSize);
    for (int j = 0; j < kDemSize; ++j)
        for (int i = 0; i < kDemSize; ++i)
            h[static_cast<std::size_t>(j * kDemSize + i)] =
                static_cast<float>(demHeight(kDemLon0 + (i + 0.5) * kDemPixel));
    if (ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, kDemSize, kDemSize, h.data(), kDemSize, kDemSize,
                                       GDT_Float32, 0, 0) != CE_None)
        return std::string();
    return path;
}
} // namespace

TEST(OsmImportTest, DemGivesBuildingBasesAndTerrainHeights)
{
    const std::string dem = writeDem();
    ASSERT_FALSE(dem.empty()) << "GDAL could not write a GeoTIFF";
    OsmWriter w;
    const double lat = 48.0, lon = 11.0, width = 20.0;
    const std::string b = w.box(lat, lon, width, 10, {{"building", "yes"}, {"height", "10"}});
    const std::string r = w.way({w.node(lat + 0.002, lon - 0.002), w.node(lat + 0.002, lon + 0.002)},
                                {{"highway", "residential"}});
    const std::string path = w.write("dem");

    osg::ref_ptr<osg::Node> n = load(path, "dem=" + dem + " margin=20");
    ASSERT_TRUE(n.valid());
    const FeatureIndex index(*n);
    const FeatureIndex::Entry* e = bySource(index, "way/" + b);
    ASSERT_NE(e, nullptr);
    // The lowest ground under the footprint is at its western edge.
    const double west = lon - 0.5 * width / metresPerDegreeLon(lat);
    EXPECT_NEAR(e->feature->getBound().zMin(), demHeight(west), 0.01);
    EXPECT_NEAR(e->feature->getBound().zMax(), demHeight(west) + 10.0, 0.01);
    // The road follows the slope: 4 m lower at its western end than at its eastern end.
    const FeatureIndex::Entry* er = bySource(index, "way/" + r);
    ASSERT_NE(er, nullptr);
    EXPECT_NEAR(er->feature->getBound().zMin(), demHeight(lon - 0.002) + 0.2, 0.1);
    EXPECT_NEAR(er->feature->getBound().zMax(), demHeight(lon + 0.002) + 0.2, 0.1);
    // The terrain spans the heights of the extent plus margin.
    for (const FeatureIndex::Entry& t : index.entries())
        if (t.feature->getType() == FeatureType::Terrain)
        {
            EXPECT_EQ(t.feature->getSourceType(), "dem");
            EXPECT_LT(t.feature->getBound().zMin(), demHeight(lon - 0.002));
            EXPECT_GT(t.feature->getBound().zMax(), demHeight(lon + 0.002));
        }

    auto rr = loadResult(path, "dem=/nonexistent/dem.tif");
    EXPECT_FALSE(rr.validNode());
    EXPECT_NE(rr.message().find("dem"), std::string::npos) << rr.message();
    const std::string notRaster = writeText("notraster.tif", "not a raster");
    rr = loadResult(path, "dem=" + notRaster);
    EXPECT_FALSE(rr.validNode());
    EXPECT_NE(rr.message().find("dem"), std::string::npos) << rr.message();
}

// --- errors ----------------------------------------------------------------------------------
TEST(OsmImportTest, ErrorsAreClearNotCrashes)
{
    auto rr = loadResult("/nonexistent/map.osm");
    EXPECT_FALSE(rr.validNode());
    EXPECT_EQ(rr.status(), osgDB::ReaderWriter::ReadResult::FILE_NOT_FOUND);

    const std::string malformed =
        writeText("malformed.osm",
                  "<?xml version='1.0'?>\n<osm version=\"0.6\">\n <node id=\"1\" lat=\"48\" lon=\"11\">\n"
                  "  <tag k=\"natural\" v=\"tree\"/>\n <way id=\"2\"><nd ref=\"1\"></node>\n");
    rr = loadResult(malformed);
    EXPECT_FALSE(rr.validNode());
    EXPECT_TRUE(rr.error()) << rr.message();
    EXPECT_NE(rr.message().find("osm:"), std::string::npos) << rr.message();

    const std::string notOsm = writeText("notosm.osm", "hello, this is not OpenStreetMap\n");
    rr = loadResult(notOsm);
    EXPECT_FALSE(rr.validNode());
    EXPECT_NE(rr.message().find("not an OpenStreetMap file"), std::string::npos) << rr.message();
    rr = loadResult(writeText("html.osm", "<html><body>a web page</body></html>\n"));
    EXPECT_NE(rr.message().find("not an OpenStreetMap file"), std::string::npos) << rr.message();
    // Malformed XML names the line and column where expat does, libosmium's element checks say what.
    rr = loadResult(malformed);
    EXPECT_NE(rr.message().find("malformed: XML error: Unknown element in <node>: way"), std::string::npos)
        << rr.message();
    rr = loadResult(
        writeText("mismatch.osm", "<osm version=\"0.6\">\n <node id=\"1\" lat=\"48\" lon=\"11\">\n</way>\n"));
    EXPECT_NE(rr.message().find("malformed: XML error at line 3, column 2: mismatched tag"),
              std::string::npos)
        << rr.message();

    OsmWriter w;
    w.node(48.0, 11.0, {{"highway", "stop"}});
    w.way({w.node(48.0, 11.0), w.node(48.001, 11.0)}, {{"power", "line"}});
    rr = loadResult(w.write("nothing"));
    EXPECT_FALSE(rr.validNode());
    EXPECT_NE(rr.message().find("no supported objects"), std::string::npos) << rr.message();

    const std::string badBz2 = writeText("broken.osm.bz2", "BZh9 this is not bzip2");
    rr = loadResult(badBz2);
    EXPECT_FALSE(rr.validNode());
    EXPECT_NE(rr.message().find("bzip2"), std::string::npos) << rr.message();

    rr = loadResult(writeText("x.osm", "<osm/>"), "storey=abc");
    EXPECT_FALSE(rr.validNode());
    EXPECT_NE(rr.message().find("storey"), std::string::npos) << rr.message();

    // A .bz2 that is not .osm.bz2 is not the importer's.
    osgDB::ReaderWriter* rw = osgDB::Registry::instance()->getReaderWriterForExtension("osm");
    ASSERT_NE(rw, nullptr);
    EXPECT_EQ(rw->readNode(writeText("archive.tar.bz2", "BZh9")).status(),
              osgDB::ReaderWriter::ReadResult::FILE_NOT_HANDLED);
    EXPECT_TRUE(rw->acceptsExtension("pbf"));
}

// Hostile input (issue 22 items 1, 3): a bzip2 bomb stops at max-inflated with the limit named,
// in well under a second; absurd tag values are clamped with a warning naming the element and
// the scene stays finite.
TEST(OsmImportTest, BombsStopAtTheLimitAndAbsurdValuesAreClamped)
{
    const std::string dir = loatest::freshDirectory("OsmImportTest-hostile");
    std::string out;
    ASSERT_EQ(loatest::run("head -c 50000000 /dev/zero | bzip2 -9 > '" + dir + "/bomb.osm.bz2'", out), 0)
        << out;
    const auto t0 = std::chrono::steady_clock::now();
    auto rr = loadResult(dir + "/bomb.osm.bz2", "max-inflated=1000000");
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_FALSE(rr.validNode());
    EXPECT_NE(
        rr.message().find("bomb.osm.bz2: bzip2 data inflating to more than 1000000 bytes exceeds the limit "
                          "max-inflated=1000000"),
        std::string::npos)
        << rr.message();
    EXPECT_LT(seconds, 1.0);
    // The object and vertex limits, on a real file (46 objects and 1,000s of vertices).
    if (haveData())
    {
        rr = loadResult(dataFile("kirchberg.osm"), "max-objects=20");
        EXPECT_NE(rr.message().find("more than 20 OpenStreetMap elements exceeds the limit max-objects=20"),
                  std::string::npos)
            << rr.message();
        rr = loadResult(dataFile("kirchberg.osm"), "max-vertices=100");
        EXPECT_NE(rr.message().find("more than 100 vertices exceeds the limit max-vertices=100"),
                  std::string::npos)
            << rr.message();
    }
    rr = loadResult(dir + "/bomb.osm.bz2", "max-inflated=x");
    EXPECT_NE(rr.message().find("max-inflated=x"), std::string::npos) << rr.message();

    OsmWriter w;
    const std::string tall = w.box(
        48.0, 11.0, 10, 10, {{"building", "yes"}, {"building:levels", "1e308"}, {"min_height", "1e300"}});
    const std::string wide = w.way({w.node(48.001, 11.0), w.node(48.001, 11.001)},
                                   {{"highway", "residential"}, {"width", "1e300"}});
    osg::ref_ptr<osg::Node> n = load(w.write("absurd"));
    ASSERT_TRUE(n.valid());
    const osg::BoundingSphere bs = n->getBound();
    EXPECT_TRUE(bs.valid() && std::isfinite(bs.radius()) && std::isfinite(bs.center().x())) << bs.radius();
    const FeatureIndex index(*n);
    const FeatureIndex::Entry* t = bySource(index, "way/" + tall);
    ASSERT_NE(t, nullptr);
    EXPECT_NEAR(t->feature->getBound().zMax(), 1000.0, 1e-3); // clamped to the plausible maximum
    const FeatureIndex::Entry* r = bySource(index, "way/" + wide);
    ASSERT_NE(r, nullptr);
    EXPECT_LE(r->feature->getBound().xMax() - r->feature->getBound().xMin(), 1100.0);
}

// --- round trip ------------------------------------------------------------------------------
TEST(OsmImportTest, OsgtWriteReadWriteIsIdentical)
{
    OsmWriter w;
    w.box(48.0, 11.0, 10, 10, {{"building", "yes"}, {"name", "Rathaus"}, {"height", "15"}});
    w.way({w.node(48.0005, 10.999), w.node(48.0005, 11.001)}, {{"highway", "secondary"}});
    w.node(47.9995, 11.0, {{"natural", "tree"}});
    osg::ref_ptr<osg::Node> n = load(w.write("roundtrip"), "terrainCell=50");
    ASSERT_TRUE(n.valid());
    const std::string a = loatest::toOsgt(*n);
    ASSERT_GT(a.size(), 1000u);
    EXPECT_NE(a.find("osgLoA::Feature"), std::string::npos);
    EXPECT_NE(a.find("Rathaus"), std::string::npos);
    const std::string path = writeText("roundtrip.osgt", a);
    osg::ref_ptr<osg::Node> back = osgDB::readRefNodeFile(path);
    ASSERT_TRUE(back.valid());
    EXPECT_EQ(loatest::toOsgt(*back), a);
    EXPECT_EQ(FeatureIndex(*back).counts().toJson(), FeatureIndex(*n).counts().toJson());
}
