// RegionFile: a user's routes and regions from GeoJSON through GDAL, in scene coordinates and
// transformed from longitude/latitude into a geo-referenced model's frame (checked against the
// UTM projection's known values and against the OSM importer's own origin), and its errors.
#include "support/TestSupport.h"

#include <osgLoA/interest/RegionFile>

#include <osg/Group>
#include <osg/ValueObject>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <gtest/gtest.h>

#include <fstream>

using namespace osgLoA;

namespace
{
std::string write(const std::string& path, const std::string& text)
{
    std::ofstream(path) << text;
    return path;
}
} // namespace

TEST(RegionFileTest, SceneCoordinatesBecomeCirclesPolylinesAndPolygons)
{
    const std::string dir = loatest::freshDirectory("RegionFileTest");
    const std::string path = write(dir + "/mine.geojson", R"({"type": "FeatureCollection", "features": [
      {"type": "Feature", "properties": {"name": "meeting point"}, "geometry": {"type": "Point", "coordinates": [10, 20]}},
      {"type": "Feature", "properties": {"name": "my route"}, "geometry": {"type": "LineString", "coordinates": [[0, 0], [100, 0], [100, 50]]}},
      {"type": "Feature", "properties": {}, "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [10, 0], [10, 10], [0, 0]]]}},
      {"type": "Feature", "properties": {"name": "two"}, "geometry": {"type": "MultiLineString", "coordinates": [[[0, 1], [1, 1]], [[5, 5], [6, 6]]]}}
    ]})");
    const auto regions = RegionFile::read(path, nullptr, 4.0);
    ASSERT_EQ(regions.size(), 5u);
    EXPECT_EQ(regions[0]->getName(), "meeting point");
    EXPECT_EQ(regions[0]->getShape(), RegionOfInterest::CIRCLES);
    EXPECT_EQ(regions[0]->getVertices()[0], osg::Vec2d(10, 20));
    EXPECT_DOUBLE_EQ(regions[0]->getRadius(), 4.0);
    EXPECT_EQ(regions[1]->getShape(), RegionOfInterest::POLYLINE);
    ASSERT_EQ(regions[1]->getVertices().size(), 3u);
    EXPECT_EQ(regions[1]->getVertices()[2], osg::Vec2d(100, 50));
    EXPECT_EQ(regions[2]->getShape(), RegionOfInterest::POLYGON);
    EXPECT_EQ(regions[2]->getVertices().size(), 3u); // the closing vertex dropped
    EXPECT_EQ(regions[2]->getName(), "mine-3");
    EXPECT_EQ(regions[3]->getName(), "two");
    EXPECT_EQ(regions[4]->getVertices()[1], osg::Vec2d(6, 6));
    // A model without a reference system: scene coordinates, as they are.
    osg::ref_ptr<osg::Group> plain = new osg::Group;
    EXPECT_EQ(RegionFile::read(path, plain.get())[0]->getVertices()[0], osg::Vec2d(10, 20));
}

// UTM zone 32N (EPSG:32632) puts longitude 9 E (its central meridian) at easting 500000 and the
// equator at northing 0; 1 degree north on the central meridian is 0.9996 x 110574.4 m (the
// WGS84 meridian arc) = 110530.2 m.
TEST(RegionFileTest, LongitudeLatitudeGoIntoTheModelsFrame)
{
    const std::string dir = loatest::freshDirectory("RegionFileTestGeo");
    const std::string path = write(dir + "/geo.geojson", R"({"type": "FeatureCollection", "features": [
      {"type": "Feature", "properties": {}, "geometry": {"type": "LineString", "coordinates": [[9, 0], [9, 1]]}}]})");
    osg::ref_ptr<osg::Group> model = new osg::Group;
    model->setUserValue("loa.crs", std::string("EPSG:32632"));
    model->setUserValue("loa.origin", osg::Vec3d(500000, 100000, 0));
    const auto regions = RegionFile::read(path, model.get());
    ASSERT_EQ(regions.size(), 1u);
    const auto& v = regions[0]->getVertices();
    EXPECT_NEAR(v[0].x(), 0.0, 0.01);
    EXPECT_NEAR(v[0].y(), -100000.0, 0.01);
    EXPECT_NEAR(v[1].x(), 0.0, 0.01);
    EXPECT_NEAR(v[1].y(), 110530.2 - 100000.0, 1.0);
    // Forced scene coordinates ignore the reference system.
    EXPECT_EQ(RegionFile::read(path, model.get(), 0.0, RegionFile::SCENE)[0]->getVertices()[1],
              osg::Vec2d(9, 1));
}

// A real OpenStreetMap extract (Kirchberg an der Iller): the importer's own origin, given in
// longitude/latitude (loa.originLonLat), lands on the scene's (0, 0).
TEST(RegionFileTest, TheOriginOfARealOsmImportIsTheSceneOrigin)
{
    const std::string osm = std::string(LOA_SOURCE_DIR) + "/../shared/data/osm/kirchberg.osm";
    if (!osgDB::fileExists(osm)) GTEST_SKIP() << "../shared/data is absent";
    osg::ref_ptr<osg::Node> model = osgDB::readRefNodeFile(osm);
    ASSERT_TRUE(model.valid());
    osg::Vec3d lonLat;
    ASSERT_TRUE(model->getUserValue("loa.originLonLat", lonLat));
    const std::string dir = loatest::freshDirectory("RegionFileTestOsm");
    char text[512];
    std::snprintf(
        text, sizeof text,
        R"({"type": "Feature", "properties": {"name": "centre"}, "geometry": {"type": "Point", "coordinates": [%.9f, %.9f]}})",
        lonLat.x(), lonLat.y());
    const auto regions = RegionFile::read(write(dir + "/centre.geojson", text), model.get(), 50.0);
    ASSERT_EQ(regions.size(), 1u);
    EXPECT_NEAR(regions[0]->getVertices()[0].x(), 0.0, 0.01);
    EXPECT_NEAR(regions[0]->getVertices()[0].y(), 0.0, 0.01);
}

TEST(RegionFileTest, ErrorsNameTheFileAndTheProblem)
{
    const std::string dir = loatest::freshDirectory("RegionFileTestErrors");
    auto message = [](const std::function<void()>& f)
    {
        try
        {
            f();
        }
        catch (const std::exception& e)
        {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message([&] { RegionFile::read(dir + "/missing.geojson", nullptr); }).find("missing.geojson"),
              std::string::npos);
    const std::string empty =
        write(dir + "/empty.geojson", R"({"type": "FeatureCollection", "features": []})");
    EXPECT_NE(message([&] { RegionFile::read(empty, nullptr); }).find("no point, line or polygon"),
              std::string::npos);
    const std::string flat = write(dir + "/flat.geojson", R"({"type": "Feature", "properties": {}, "geometry":
        {"type": "Polygon", "coordinates": [[[0, 0], [1, 1], [2, 2], [0, 0]]]}})");
    EXPECT_NE(message([&] { RegionFile::read(flat, nullptr); }).find("zero area"), std::string::npos);
    const std::string point = write(
        dir + "/p.geojson",
        R"({"type": "Feature", "properties": {}, "geometry": {"type": "Point", "coordinates": [1, 2]}})");
    EXPECT_NE(message([&] { RegionFile::read(point, nullptr, 0.0, RegionFile::GEOGRAPHIC); })
                  .find("geo-referenced"),
              std::string::npos);
    EXPECT_NE(message([&] { RegionFile::read(point, nullptr, -1.0); }).find("radius"), std::string::npos);
    osg::ref_ptr<osg::Group> bad = new osg::Group;
    bad->setUserValue("loa.crs", std::string("not a reference system"));
    EXPECT_NE(message([&] { RegionFile::read(point, bad.get()); }).find("not one GDAL knows"),
              std::string::npos);
}
