// loa-citygen writes complete files in several formats and reports bad arguments.
#include "support/TestSupport.h"

#include <osgLoA/util/SceneStatistics>

#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <gtest/gtest.h>

namespace
{
std::string exe()
{
    return std::string("'") + LOA_CITYGEN_EXE + "'";
}
} // namespace

TEST(LoaCitygenTest, WritesOsgtOsgbAndObjThatReadBack)
{
    const std::string dir = loatest::freshDirectory("LoaCitygenTest");
    for (const char* name : {"c.osgt", "c.osgb", "obj/c.obj"})
    {
        std::string out;
        ASSERT_EQ(loatest::run(exe() + " --out '" + dir + "/" + name + "' --small --seed 3", out), 0) << out;
        osg::ref_ptr<osg::Node> n = osgDB::readRefNodeFile(dir + "/" + name);
        ASSERT_TRUE(n.valid()) << name;
        EXPECT_GT(osgLoA::SceneStatistics::collect(*n).triangles, 5000u) << name;
    }
    EXPECT_TRUE(osgDB::fileExists(dir + "/obj/c.mtl"));
    EXPECT_TRUE(osgDB::fileExists(dir + "/obj/loa_facade-brick.png"));
    // Native formats keep the feature tags; the text and binary files describe the same city.
    osg::ref_ptr<osg::Node> t = osgDB::readRefNodeFile(dir + "/c.osgt"),
                            b = osgDB::readRefNodeFile(dir + "/c.osgb");
    EXPECT_EQ(loatest::toOsgt(*t), loatest::toOsgt(*b));
    EXPECT_GT(osgLoA::SceneStatistics::collect(*t).features, 10u);
}

TEST(LoaCitygenTest, BadArguments)
{
    std::string out;
    EXPECT_EQ(loatest::run(exe(), out), 2);
    EXPECT_NE(out.find("no --out FILE given"), std::string::npos) << out;
    EXPECT_EQ(loatest::run(exe() + " --out /tmp/x.nosuchformat", out), 2);
    EXPECT_NE(out.find("no osgDB plugin writes '.nosuchformat'"), std::string::npos) << out;
    // The old positional OUTPUT is an unexpected argument now (one spelling: --out).
    EXPECT_EQ(loatest::run(exe() + " /tmp/x.osgt", out), 2);
    EXPECT_NE(out.find("unexpected argument '/tmp/x.osgt'"), std::string::npos) << out;
    EXPECT_EQ(loatest::run(exe() + " --out /tmp/x.nosuchformat", out), 2);
    EXPECT_NE(out.find("no osgDB plugin writes '.nosuchformat'"), std::string::npos) << out;
    EXPECT_EQ(loatest::run(exe() + " --out /tmp/x.osgt -O riverWidth=1", out), 2);
    EXPECT_NE(out.find("riverWidth"), std::string::npos) << out;
    // A parent "directory" that is a regular file cannot be created, even by root.
    const std::string dir = loatest::freshDirectory("LoaCitygenBad");
    loatest::run("touch '" + dir + "/afile'", out);
    EXPECT_EQ(loatest::run(exe() + " --out '" + dir + "/afile/x.osgt' --small", out), 1);
    EXPECT_NE(out.find("loa-citygen: error:"), std::string::npos) << out;
}
