// loa-classify: counts per type (text and JSON) on files written by loa-citygen, the classifier
// recovering types from names after an .obj round trip, saved output, and its error paths.
#include "support/TestSupport.h"

#include <osgLoA/city/CityGenerator>
#include <osgLoA/semantics/ClassificationRuleSet>
#include <osgLoA/semantics/FeatureIndex>

#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <gtest/gtest.h>

namespace
{
std::string classify()
{
    return std::string("'") + LOA_CLASSIFY_EXE + "'";
}

std::string smallCity(const std::string& dir, const std::string& name)
{
    std::string out;
    const std::string path = dir + "/" + name;
    if (!osgDB::fileExists(path))
    {
        EXPECT_EQ(loatest::run(std::string("'") + LOA_CITYGEN_EXE + "' '" + path + "' --small", out), 0)
            << out;
    }
    return path;
}
} // namespace

// The JSON counts equal the generator's own feature counts (top-level features).
TEST(LoaClassifyTest, JsonCountsMatchTheGenerator)
{
    const std::string dir = loatest::freshDirectory("LoaClassifyTest");
    const std::string city = smallCity(dir, "city.osgb");
    std::string out;
    ASSERT_EQ(loatest::run(classify() + " '" + city + "' --json", out), 0) << out;
    osg::ref_ptr<osg::Group> truth = osgLoA::CityGenerator(osgLoA::CityParameters::small()).generate();
    const std::string expected = osgLoA::FeatureIndex(*truth).counts().toJson();
    EXPECT_EQ(out, expected + "\n");
    EXPECT_NE(expected.find("\"landmarks\": 2"), std::string::npos) << expected;

    ASSERT_EQ(loatest::run(classify() + " '" + city + "'", out), 0) << out;
    EXPECT_NE(out.find("features:"), std::string::npos) << out;
    EXPECT_NE(out.find("kept from the model data"), std::string::npos) << out;
}

// .obj keeps no Feature objects, only names: the default rules give every drawable back the
// type the generator meant, with nothing left generic.
TEST(LoaClassifyTest, ObjExportIsReclassifiedFromNames)
{
    const std::string dir = loatest::freshDirectory("LoaClassifyTestObj");
    const std::string obj = smallCity(dir, "city.obj");
    const std::string saved = dir + "/classified.osgb";
    std::string out;
    ASSERT_EQ(loatest::run(classify() + " '" + obj + "' --save '" + saved + "'", out), 0) << out;
    EXPECT_NE(out.find(" 0 generic"), std::string::npos) << out;
    osg::ref_ptr<osg::Node> back = osgDB::readRefNodeFile(saved);
    ASSERT_TRUE(back.valid());
    osgLoA::FeatureIndex index(*back);
    const auto c = index.counts();
    EXPECT_EQ(c.get(osgLoA::FeatureType::Generic), 0u);
    EXPECT_EQ(c.get(osgLoA::FeatureType::Water), 1u);
    EXPECT_EQ(c.get(osgLoA::FeatureType::Terrain), 1u);
    EXPECT_GE(c.get(osgLoA::FeatureType::Street), 9u);
    EXPECT_GE(c.get(osgLoA::FeatureType::Building), 12u); // 10 blocks of houses + 2 landmarks, at least
    for (const auto& e : index.entries())
        EXPECT_EQ(e.feature->getSource(), osgLoA::Feature::RULE);
}

TEST(LoaClassifyTest, WritesTheDefaultRulesAndReadsThemBack)
{
    const std::string dir = loatest::freshDirectory("LoaClassifyTestRules");
    std::string out;
    ASSERT_EQ(loatest::run(classify() + " --write-default-rules '" + dir + "/rules.osgt'", out), 0) << out;
    osg::ref_ptr<osgLoA::ClassificationRuleSet> rules =
        osgLoA::ClassificationRuleSet::read(dir + "/rules.osgt");
    EXPECT_EQ(rules->getRules().size(), osgLoA::ClassificationRuleSet::createDefault()->getRules().size());
    const std::string city = smallCity(dir, "city.osgb");
    ASSERT_EQ(
        loatest::run(classify() + " '" + city + "' --rules '" + dir + "/rules.osgt' --override --json", out),
        0)
        << out;
    // Overriding the model data with the default rules gives the same counts on the demo city
    // (landmarks are flagged by the model, not by rules).
    osg::ref_ptr<osg::Group> truth = osgLoA::CityGenerator(osgLoA::CityParameters::small()).generate();
    EXPECT_EQ(out, osgLoA::FeatureIndex(*truth).counts().toJson() + "\n");
}

TEST(LoaClassifyTest, ErrorsAreClearWithTheirExitStatus)
{
    const std::string dir = loatest::freshDirectory("LoaClassifyTestErrors");
    std::string out;
    EXPECT_EQ(loatest::run(classify(), out), 2) << out;
    EXPECT_NE(out.find("no MODEL"), std::string::npos) << out;
    EXPECT_EQ(loatest::run(classify() + " x.osgb --frobnicate", out), 2) << out;
    EXPECT_EQ(loatest::run(classify() + " x.osgb --image x.jpg", out), 2) << out;
    EXPECT_EQ(loatest::run(classify() + " '" + dir + "/missing.osgb'", out), 1) << out;
    EXPECT_NE(out.find("missing.osgb"), std::string::npos) << out;
    const std::string city = smallCity(dir, "city.osgb");
    EXPECT_EQ(loatest::run(classify() + " '" + city + "' --rules '" + dir + "/nope.osgt'", out), 1) << out;
    EXPECT_NE(out.find("nope.osgt"), std::string::npos) << out;
    // A rule file that holds something else.
    EXPECT_EQ(loatest::run(classify() + " '" + city + "' --rules '" + city + "'", out), 1) << out;
    EXPECT_NE(out.find("not an osgLoA::ClassificationRuleSet"), std::string::npos) << out;
}

// The tools find the project's osgDB plugins beside their executable (loa::findPlugins): without
// OSG_LIBRARY_PATH, reading the demo city's pseudo file needs osgdb_loacity and typing its
// features needs the serializers. Before, this printed "cannot read 'demo.loacity': no such file".
TEST(LoaClassifyTest, FindsItsPluginsWithoutOsgLibraryPath)
{
    std::string out;
    const int status =
        loatest::run("env -u OSG_LIBRARY_PATH '" + std::string(LOA_CLASSIFY_EXE) + "' demo.loacity", out);
    EXPECT_EQ(status, 0) << out;
    EXPECT_NE(out.find("401 units: 401 kept from the model data"), std::string::npos) << out;
    EXPECT_EQ(out.find("no such file"), std::string::npos) << out;
    EXPECT_EQ(out.find("Unsupported wrapper"), std::string::npos) << out;
}
