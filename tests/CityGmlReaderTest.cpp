// osgdb_citygml / osgdb_gml (libcitygml): a CityGML 2.0 city written for the tests
// (tests/data/citygml/small-city.gml, counted by hand: 2 buildings, one with a BuildingPart, a
// road, a bridge, a land use area, a plant cover): features and their types through
// CityObjectTypes, LoD choice, thematic surfaces as named drawables, X3D materials, the origin
// and reference system, and the errors.
#include "support/TestSupport.h"

#include <osgLoA/semantics/FeatureIndex>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Material>
#include <osg/ValueObject>
#include <osgDB/ReadFile>
#include <osgDB/Registry>

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <chrono>
#include <fstream>
#include <map>

using namespace osgLoA;

namespace
{
const std::string kCity = std::string(LOA_SOURCE_DIR) + "/tests/data/citygml/small-city.gml";

osg::ref_ptr<osg::Node> read(const std::string& options = std::string())
{
    osg::ref_ptr<osgDB::Options> o = new osgDB::Options(options);
    return osgDB::readRefNodeFile(kCity, o.get());
}

const FeatureIndex::Entry* byName(const FeatureIndex& index, const std::string& name)
{
    for (const auto& e : index.entries())
        if (e.node.valid() && e.node->getName() == name) return &e;
    return nullptr;
}

/** Triangles per drawable name under node. */
std::map<std::string, unsigned> triangles(osg::Node& node)
{
    struct V : osg::NodeVisitor
    {
        V() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
        std::map<std::string, unsigned> n;
        void apply(osg::Geometry& g) override
        {
            for (unsigned i = 0; i < g.getNumPrimitiveSets(); ++i)
                n[g.getName()] += g.getPrimitiveSet(i)->getNumIndices() / 3;
        }
    } v;
    node.accept(v);
    return v.n;
}
} // namespace

TEST(CityGmlReaderTest, ObjectsBecomeTypedFeatures)
{
    osg::ref_ptr<osg::Node> city = read();
    ASSERT_TRUE(city.valid());
    FeatureIndex index(*city);
    const FeatureIndex::Counts top = index.counts();
    EXPECT_EQ(top.get(FeatureType::Building), 2u);
    EXPECT_EQ(top.get(FeatureType::Street), 2u); // the road and the bridge
    EXPECT_EQ(top.get(FeatureType::Terrain), 1u);
    EXPECT_EQ(top.get(FeatureType::Green), 1u);
    EXPECT_EQ(top.total, 6u);
    EXPECT_EQ(index.counts(false).total, 7u); // + the BuildingPart, nested in its building
    const FeatureIndex::Entry* bridge = byName(index, "bridge");
    ASSERT_NE(bridge, nullptr);
    EXPECT_EQ(bridge->feature->getSubType(), "bridge");
    EXPECT_EQ(bridge->feature->getSourceType(), "Bridge");
    EXPECT_EQ(bridge->feature->getSource(), Feature::MODEL_DATA);
    const FeatureIndex::Entry* part = byName(index, "hall-tower");
    ASSERT_NE(part, nullptr);
    EXPECT_EQ(part->feature->getSubType(), "part");
    ASSERT_GE(part->parent, 0);
    EXPECT_EQ(index.entries()[unsigned(part->parent)].node->getName(), "hall");
    EXPECT_EQ(byName(index, "field")->feature->getType(), FeatureType::Terrain);
    EXPECT_EQ(byName(index, "meadow")->feature->getType(), FeatureType::Green);
    EXPECT_TRUE(index.duplicateIds().empty());
    // Re-centred on the envelope's centre (500050, 5400050) at its floor; the reference system kept.
    osg::Vec3d origin;
    ASSERT_TRUE(city->getUserValue("loa.origin", origin));
    EXPECT_EQ(origin, osg::Vec3d(500050, 5400050, 0));
    std::string crs;
    ASSERT_TRUE(city->getUserValue("loa.crs", crs));
    EXPECT_EQ(crs, "EPSG:25832");
    const osg::BoundingBoxf& house = byName(index, "house")->feature->getBound();
    EXPECT_NEAR(house.xMin(), -40.0f, 1e-3f);
    EXPECT_NEAR(house.xMax(), -30.0f, 1e-3f);
    EXPECT_NEAR(house.zMax(), 6.0f, 1e-3f);
}

// The house has LoD1 (a solid: 6 faces, 12 triangles) and LoD2 (4 wall surfaces and a roof
// surface: 10 triangles); by default each object shows its highest LoD, lod=N picks one.
TEST(CityGmlReaderTest, LodChoiceAndThematicSurfaces)
{
    osg::ref_ptr<osg::Node> city = read();
    FeatureIndex index(*city);
    osg::ref_ptr<osg::Node> house = byName(index, "house")->node.get();
    const auto lod2 = triangles(*house);
    EXPECT_EQ(lod2.at("WallSurface"), 8u);
    EXPECT_EQ(lod2.at("RoofSurface"), 2u);
    EXPECT_EQ(lod2.count("Building"), 0u);
    EXPECT_FLOAT_EQ(byName(index, "house")->feature->getLod(), 2.0f);

    osg::ref_ptr<osg::Node> lod1City = read("lod=1");
    FeatureIndex lod1Index(*lod1City);
    osg::ref_ptr<osg::Node> lod1House = byName(lod1Index, "house")->node.get();
    const auto lod1 = triangles(*lod1House);
    EXPECT_EQ(lod1.at("Building"), 12u);
    EXPECT_EQ(lod1.count("WallSurface"), 0u);
    EXPECT_FLOAT_EQ(byName(lod1Index, "house")->feature->getLod(), 1.0f);
}

// The roof's X3D material (theme "colours", diffuse 0.8 0.1 0.1) reaches its drawable.
TEST(CityGmlReaderTest, MaterialsOfTheTheme)
{
    osg::ref_ptr<osg::Node> city = read();
    FeatureIndex index(*city);
    struct Find : osg::NodeVisitor
    {
        Find() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
        const osg::Material* roof = nullptr;
        void apply(osg::Geometry& g) override
        {
            if (g.getName() == "RoofSurface" && g.getStateSet())
                roof = dynamic_cast<const osg::Material*>(
                    g.getStateSet()->getAttribute(osg::StateAttribute::MATERIAL));
        }
    } f;
    byName(index, "house")->node->accept(f);
    ASSERT_NE(f.roof, nullptr);
    const osg::Vec4 d = f.roof->getDiffuse(osg::Material::FRONT);
    EXPECT_NEAR(d.r(), 0.8f, 1e-5f);
    EXPECT_NEAR(d.g(), 0.1f, 1e-5f);
    EXPECT_NEAR(d.a(), 1.0f, 1e-5f);
}

TEST(CityGmlReaderTest, ErrorsNameTheFileAndTheProblem)
{
    const std::string dir = loatest::freshDirectory("CityGmlReaderTest");
    osgDB::ReaderWriter* rw = osgDB::Registry::instance()->getReaderWriterForExtension("gml");
    ASSERT_NE(rw, nullptr);
    EXPECT_EQ(rw->readNode(dir + "/missing.gml").status(), osgDB::ReaderWriter::ReadResult::FILE_NOT_FOUND);
    osg::ref_ptr<osgDB::Options> bad = new osgDB::Options("lod=7");
    auto lod = rw->readNode(kCity, bad.get());
    EXPECT_FALSE(lod.validNode());
    EXPECT_NE(lod.message().find("lod=7"), std::string::npos) << lod.message();
    std::ofstream(dir + "/empty.gml")
        << R"(<?xml version="1.0"?><core:CityModel xmlns:core="http://www.opengis.net/citygml/2.0" xmlns:gml="http://www.opengis.net/gml"></core:CityModel>)";
    auto empty = rw->readNode(dir + "/empty.gml");
    EXPECT_FALSE(empty.validNode());
    EXPECT_NE(empty.message().find("empty.gml"), std::string::npos) << empty.message();
    std::ofstream(dir + "/broken.gml") << "<?xml version=\"1.0\"?><core:CityModel "
                                          "xmlns:core=\"http://www.opengis.net/citygml/2.0\"><unclosed>";
    auto broken = rw->readNode(dir + "/broken.gml");
    EXPECT_FALSE(broken.validNode());
    EXPECT_NE(broken.message().find("broken.gml"), std::string::npos) << broken.message();
}

// The limits checked before libcitygml parses (issue 22 item 1, CityGmlPrescan): 20,000 nested
// BuildingParts did not finish in a minute; a gml:posList of 100,001 vertices; a FIFO. Each is
// refused in under a second naming the file, the limit and the option, and reads past it with
// the limit raised. The real file still reads under the defaults (its elements nest 12 deep).
TEST(CityGmlReaderTest, LimitsAreCheckedBeforeParsing)
{
    const std::string dir = loatest::freshDirectory("CityGmlReaderTest-limits");
    osgDB::ReaderWriter* rw = osgDB::Registry::instance()->getReaderWriterForExtension("gml");
    ASSERT_NE(rw, nullptr);
    const std::string head =
        "<?xml version=\"1.0\"?><core:CityModel xmlns:core=\"http://www.opengis.net/citygml/2.0\" "
        "xmlns:bldg=\"http://www.opengis.net/citygml/building/2.0\" "
        "xmlns:gml=\"http://www.opengis.net/gml\"><core:cityObjectMember>"
        "<bldg:Building gml:id=\"b\">";
    const std::string foot = "</bldg:Building></core:cityObjectMember></core:CityModel>";
    {
        std::ofstream out(dir + "/deep.gml");
        out << head;
        for (int i = 0; i < 20000; ++i)
            out << "<!-- a comment > with > brackets --><bldg:consistsOfBuildingPart><bldg:BuildingPart "
                   "gml:id=\"p"
                << i << "\" class=\"a > b\">";
        for (int i = 0; i < 20000; ++i)
            out << "</bldg:BuildingPart></bldg:consistsOfBuildingPart>";
        out << foot;
    }
    {
        std::ofstream out(dir + "/long-ring.gml");
        out << head
            << "<bldg:lod1MultiSurface><gml:MultiSurface><gml:surfaceMember><gml:Polygon><gml:exterior>"
            << "<gml:LinearRing><gml:posList srsDimension=\"3\">";
        for (int i = 0; i < 100001; ++i)
            out << i << " 0 0 ";
        out << "</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>"
            << "</gml:MultiSurface></bldg:lod1MultiSurface>" << foot;
    }
    const struct
    {
        const char* file;
        const char* limit;
        const char* raised;
    } cases[] = {{"deep.gml", "max-depth=64", "max-depth=100000"},
                 {"long-ring.gml", "max-ring-vertices=100000", "max-ring-vertices=200000"}};
    for (const auto& c : cases)
    {
        const auto t0 = std::chrono::steady_clock::now();
        auto rr = rw->readNode(dir + "/" + c.file);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        EXPECT_FALSE(rr.validNode()) << c.file;
        EXPECT_NE(rr.message().find(std::string(c.file) + ": "), std::string::npos) << rr.message();
        EXPECT_NE(rr.message().find(std::string("exceeds the limit ") + c.limit), std::string::npos)
            << rr.message();
        EXPECT_LT(seconds, 1.0) << c.file;
        if (std::string(c.file) == "long-ring.gml")
        {
            // Raised, the prescan lets it through to libcitygml.
            osg::ref_ptr<osgDB::Options> raised = new osgDB::Options(c.raised);
            auto again = rw->readNode(dir + "/" + c.file, raised.get());
            EXPECT_EQ(again.message().find("exceeds the limit"), std::string::npos) << again.message();
        }
    }
    ASSERT_EQ(::mkfifo((dir + "/fifo.gml").c_str(), 0600), 0);
    auto fifo = rw->readNode(dir + "/fifo.gml");
    EXPECT_FALSE(fifo.validNode());
    EXPECT_NE(fifo.message().find("not a regular file"), std::string::npos) << fifo.message();
    EXPECT_TRUE(read().valid()) << "the real file no longer reads under the default limits";
}
