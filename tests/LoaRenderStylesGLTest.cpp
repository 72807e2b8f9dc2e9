// loa-render's texture styles on a real scene nobody on the project made (TORCS street-1:
// docs/test-scenes.md counts 43 images by hand, 2 of them GL_LUMINANCE): the palette style
// builds a palette for every image, the luminance ones included, where it used to abort the
// render with "texture format 0x1909/0x1401 is not RGB8" and exit 2; the abstract style filters
// every image once (colour and outline: 86 pyramids), with progress lines on stderr, and a
// second run reads them all from the filter cache.
#include "support/TestSupport.h"

#include <osgDB/FileUtils>

#include <gtest/gtest.h>

#include <string>

namespace
{
std::string street1()
{
    const std::string model = std::string(LOA_SOURCE_DIR) + "/data/test-scenes/torcs-street-1.osgt";
    const std::string texture = std::string(LOA_SOURCE_DIR) + "/data/cache/torcs-data/street-1/concrete.rgb";
    return osgDB::fileExists(model) && osgDB::fileExists(texture) ? model : std::string();
}

std::string render(const std::string& args, const std::string& env = std::string())
{
    return env + " '" + std::string(LOA_RENDER_EXE) + "' '" + street1() + "' --size 320x180 " + args;
}
} // namespace

TEST(LoaRenderStylesGLTest, PaletteStyleReadsLuminanceTexturesOfARealScene)
{
    if (street1().empty()) GTEST_SKIP() << "TORCS street-1 is not extracted: run scripts/fetch-test-data";
    const std::string dir = loatest::freshDirectory("LoaRenderStylesPalette");
    std::string out;
    ASSERT_EQ(loatest::run(render("--style palette --out '" + dir + "/palette.png'"), out), 0) << out;
    EXPECT_NE(out.find("palette style: 43 texture palette(s) built"), std::string::npos) << out;
    EXPECT_EQ(out.find("is not RGB8"), std::string::npos) << out;
    EXPECT_EQ(out.find("skipped"), std::string::npos) << out;
    EXPECT_TRUE(osgDB::fileExists(dir + "/palette.png"));
}

TEST(LoaRenderStylesGLTest, AbstractStyleFiltersEveryTextureOnceWithProgress)
{
    if (street1().empty()) GTEST_SKIP() << "TORCS street-1 is not extracted: run scripts/fetch-test-data";
    const std::string dir = loatest::freshDirectory("LoaRenderStylesAbstract");
    const std::string env = "OSGLOA_FILTER_CACHE='" + dir + "/cache'";
    std::string first, second;
    ASSERT_EQ(loatest::run(render("--style abstract --out '" + dir + "/a.png'", env), first), 0) << first;
    // (Images with the same pixels share a cache entry: the second of a pair is read back.)
    EXPECT_NE(first.find("abstract style: 86 filtered texture(s), "), std::string::npos) << first;
    EXPECT_EQ(first.find("86 from the cache"), std::string::npos) << first;
    EXPECT_NE(first.find("osgLoA: abstract style: filtering textures per mip level: 0/86 (grass-aa.rgb)"),
              std::string::npos)
        << first;
    EXPECT_NE(first.find("86/86 done in"), std::string::npos) << first;
    ASSERT_EQ(loatest::run(render("--style abstract --out '" + dir + "/b.png'", env), second), 0) << second;
    EXPECT_NE(second.find("abstract style: 86 filtered texture(s), 86 from the cache"), std::string::npos)
        << second;
}
