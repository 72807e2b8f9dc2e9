// The CityJSON reader on the shared real-world and odd sample files (shared/data/cityjson):
// every file loads, with one feature per CityObject unless it has none, and the Rotterdam subset
// keeps its 16 buildings and its textures. Skipped when the shared folder is absent.
#include "support/TestSupport.h"

#include <osgLoA/semantics/Feature>
#include <osgLoA/semantics/FeatureIndex>

#include <osg/Geometry>
#include <osg/NodeVisitor>
#include <osg/Texture2D>
#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>
#include <osgDB/Registry>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>

namespace
{

const std::string kFolder = std::string(LOA_SOURCE_DIR) + "/../shared/data/cityjson";

void findJson(const std::string& dir, std::vector<std::string>& out)
{
    for (const std::string& name : osgDB::getSortedDirectoryContents(dir))
    {
        if (name == "." || name == "..") continue;
        const std::string path = dir + "/" + name;
        if (osgDB::fileType(path) == osgDB::DIRECTORY)
            findJson(path, out);
        else if (osgDB::getLowerCaseFileExtension(path) == "json")
            out.push_back(path);
    }
}

nlohmann::json parse(const std::string& path)
{
    std::ifstream in(path);
    return nlohmann::json::parse(in);
}

class TexturedGeometries : public osg::NodeVisitor
{
public:
    TexturedGeometries() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
    void apply(osg::Drawable& d) override
    {
        const osg::Geometry* g = d.asGeometry();
        if (!g || !g->getTexCoordArray(0) || !g->getStateSet()) return;
        const auto* tex = dynamic_cast<const osg::Texture2D*>(
            g->getStateSet()->getTextureAttribute(0, osg::StateAttribute::TEXTURE));
        if (tex && tex->getImage() && g->getTexCoordArray(0)->getNumElements() > 0) ++count;
    }
    unsigned count = 0;
};

} // namespace

TEST(CityJsonSharedDataTest, EveryFileLoads)
{
    if (!osgDB::fileExists(kFolder)) GTEST_SKIP() << "shared CityJSON samples not found at " << kFolder;
    std::vector<std::string> files;
    findJson(kFolder, files);
    ASSERT_FALSE(files.empty());
    for (const std::string& path : files)
    {
        SCOPED_TRACE(path);
        const nlohmann::json doc = parse(path);
        const std::size_t objects = doc.at("CityObjects").size();
        auto rr = osgDB::Registry::instance()->readNode(path, nullptr);
        ASSERT_TRUE(rr.validNode()) << rr.message();
        osgLoA::FeatureIndex index(*rr.getNode());
        if (objects == 0)
            EXPECT_EQ(index.size(), 0u)
                << "a CityJSON file without CityObjects (minimal.json) is an empty scene";
        else
        {
            EXPECT_GT(index.size(), 0u);
            EXPECT_LE(index.size(), objects);
        }
        // Every feature's source id is a CityObject of the file.
        for (const auto& e : index.entries())
            EXPECT_TRUE(doc["CityObjects"].contains(e.feature->getSourceId())) << e.feature->getSourceId();
    }
}

TEST(CityJsonSharedDataTest, RotterdamSubsetHas16TexturedBuildings)
{
    const std::string path = kFolder + "/rotterdam/rotterdam_subset.json";
    if (!osgDB::fileExists(path)) GTEST_SKIP() << "shared CityJSON samples not found at " << path;
    // Counted independently of the reader.
    const nlohmann::json doc = parse(path);
    unsigned buildings = 0;
    for (const auto& [id, obj] : doc.at("CityObjects").items())
        if (obj.at("type") == "Building" && !obj.contains("parents")) ++buildings;
    EXPECT_EQ(buildings, 16u);

    osg::ref_ptr<osg::Node> node = osgDB::readRefNodeFile(path);
    ASSERT_TRUE(node.valid());
    osgLoA::FeatureIndex index(*node);
    EXPECT_EQ(index.counts().get(osgLoA::FeatureType::Building), buildings);
    for (const auto& e : index.entries())
    {
        EXPECT_EQ(e.feature->getSourceType(), "Building");
        EXPECT_FLOAT_EQ(e.feature->getLod(), 2.0f);
        EXPECT_TRUE(e.feature->getBound().valid());
    }
    TexturedGeometries textured;
    node->accept(textured);
    EXPECT_GT(textured.count, 0u) << "appearances/0320_4_15.jpg is present and used";
    // Re-centred: the origin is near the data (RD New, Rotterdam), the local coordinates small.
    osg::Vec3d origin;
    ASSERT_TRUE(node->getUserValue("loa.origin", origin));
    EXPECT_GT(origin.x(), 90000.0);
    EXPECT_LT(origin.x(), 92000.0);
    EXPECT_LT(node->getBound().center().length(), 500.0f);
}
