// The .loacity pseudo-loader, as osgviewer and osgconv use it.
#include <osgLoA/semantics/Feature>
#include <osgLoA/util/SceneStatistics>

#include <osgDB/ReadFile>
#include <osgDB/Registry>

#include <gtest/gtest.h>

TEST(LoaCityPluginTest, ReadsTheDemoCityWithOptions)
{
    osg::ref_ptr<osgDB::Options> opts = new osgDB::Options("seed=5 blocksX=2 blocksY=2 terrainResolution=16");
    osg::ref_ptr<osg::Node> n = osgDB::readRefNodeFile("demo.loacity", opts.get());
    ASSERT_TRUE(n.valid()) << "osgdb_loacity not found on OSG_LIBRARY_PATH";
    const auto s = osgLoA::SceneStatistics::collect(*n);
    EXPECT_EQ(s.featuresByType.at(osgLoA::FeatureType::Street), 6u); // 3 + 3 road lines
    EXPECT_EQ(s.featuresByType.at(osgLoA::FeatureType::Terrain), 1u);
}

TEST(LoaCityPluginTest, BadOptionsGiveAnErrorNotACity)
{
    osg::ref_ptr<osgDB::Options> opts = new osgDB::Options("blocksX=0");
    auto rr = osgDB::Registry::instance()->readNode("demo.loacity", opts.get());
    EXPECT_FALSE(rr.validNode());
    EXPECT_NE(rr.message().find("blocksX"), std::string::npos) << rr.message();
}
