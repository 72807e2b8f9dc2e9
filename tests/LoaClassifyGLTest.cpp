// loa-classify with GL: the debug view coloured by feature type (paper 004 Figure 3B), rendered by --image,
// shows every demo-city type in its colour and nothing as generic; --best-views gives every landmark one.
#include "support/TestSupport.h"

#include <osgLoA/semantics/FeatureTypeView>
#include <osgLoA/util/ImageFile>

#include <osgDB/FileUtils>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>

#include <map>

using namespace osgLoA;

TEST(LoaClassifyGLTest, EveryDemoCityTypeShowsInItsColour)
{
    const std::string dir = loatest::freshDirectory("LoaClassifyGLTest");
    std::string out;
    ASSERT_EQ(loatest::run(std::string("'") + LOA_CITYGEN_EXE + "' --out '" + dir + "/city.osgb' --small", out), 0)
        << out;
    ASSERT_EQ(loatest::run(std::string("'") + LOA_CLASSIFY_EXE + "' '" + dir + "/city.osgb' --image '" + dir +
                               "/types.png' --size 240x180 --camera top",
                           out),
              0)
        << out;
    osg::ref_ptr<osg::Image> img = ImageFile::read(dir + "/types.png");
    ASSERT_TRUE(img.valid());
    // Lighting scales a colour; its chromaticity (r, g, b divided by their sum) stays. Each
    // pixel goes to the palette colour of nearest chromaticity, if within 0.04 (the palette's
    // closest pair, street grey and terrain sand, are 0.09 apart); the sky is excluded the same way.
    std::map<std::string, osg::Vec4> palette;
    for (FeatureType t : kFeatureTypes)
        palette[toString(t)] = FeatureTypeView::colour(t);
    palette["landmark"] = FeatureTypeView::landmarkColour();
    palette["sky"] = osg::Vec4(0.62f, 0.75f, 0.90f, 1.0f);
    auto chroma = [](const osg::Vec4& c)
    {
        const float s = c.r() + c.g() + c.b();
        return s > 0.0f ? osg::Vec3(c.r(), c.g(), c.b()) / s : osg::Vec3();
    };
    std::map<std::string, unsigned> count;
    for (int t = 0; t < img->t(); ++t)
        for (int s = 0; s < img->s(); ++s)
        {
            const osg::Vec3 c = chroma(img->getColor(s, t));
            std::string best;
            float bestD = 0.04f;
            for (const auto& kv : palette)
            {
                const float d = (chroma(kv.second) - c).length();
                if (d < bestD) bestD = d, best = kv.first;
            }
            ++count[best.empty() ? "other" : best];
        }
    const float n = static_cast<float>(img->s() * img->t());
    for (const char* t : {"building", "street", "water", "green", "terrain", "landmark"})
        EXPECT_GT(count[t] / n, 0.002f) << t << ": " << count[t] << " pixels";
    EXPECT_EQ(count["generic"], 0u);
    EXPECT_LT(count["other"] / n, 0.05f)
        << "pixels in no palette colour: textures or vertex colours show through";
}

TEST(LoaClassifyGLTest, BestViewsForEveryLandmarkAndThresholdsSelectLandmarks)
{
    const std::string dir = loatest::freshDirectory("LoaClassifyGLTestViews");
    std::string out;
    ASSERT_EQ(loatest::run(std::string("'") + LOA_CITYGEN_EXE + "' --out '" + dir + "/city.osgb' --small", out), 0)
        << out;
    const std::string classify = std::string("'") + LOA_CLASSIFY_EXE + "' '" + dir + "/city.osgb'";
    ASSERT_EQ(loatest::run(classify + " --best-views", out), 0) << out;
    std::size_t views = 0;
    for (std::size_t at = out.find("best view from direction"); at != std::string::npos;
         at = out.find("best view from direction", at + 1))
        ++views;
    EXPECT_EQ(views, 2u) << out; // the small city has two landmarks
    // The generator gives landmarks interest 1 and others 0: any threshold in (0,1] keeps two,
    // threshold 0 makes every feature a landmark.
    ASSERT_EQ(loatest::run(classify + " --landmark-threshold 0.9 --json", out), 0) << out;
    EXPECT_NE(out.find("\"landmarks\": 2}"), std::string::npos) << out;
    ASSERT_EQ(loatest::run(classify + " --landmark-threshold 0 --json", out), 0) << out;
    EXPECT_EQ(out.find("\"landmarks\": 2}"), std::string::npos) << out;
    EXPECT_EQ(loatest::run(classify + " --landmark-threshold 2", out), 2) << out;
    EXPECT_EQ(loatest::run(classify + " --interest '" + dir + "/city.osgb'", out), 1) << out;
    EXPECT_NE(out.find("not an osgLoA::FeatureInterest"), std::string::npos) << out;
}

// Issue 18: every tool classifies the same way. loa-render --stats writes the feature counts of
// what it drew; on TORCS street-1 (and the CityGML test city) they are loa-classify's.
TEST(LoaClassifyGLTest, LoaRenderCountsTheFeaturesAsLoaClassifyDoes)
{
    const std::string street1 = std::string(LOA_SOURCE_DIR) + "/data/test-scenes/torcs-street-1.osgt";
    std::vector<std::string> models = {std::string(LOA_SOURCE_DIR) + "/tests/data/citygml/small-city.gml"};
    if (osgDB::fileExists(std::string(LOA_SOURCE_DIR) + "/data/cache/torcs-data/street-1/street-1.ac"))
        models.push_back(street1);
    const std::string dir = loatest::freshDirectory("LoaClassifyGLTestStats");
    for (const std::string& model : models)
    {
        std::string classified, rendered;
        ASSERT_EQ(
            loatest::run("{ '" + std::string(LOA_CLASSIFY_EXE) + "' '" + model + "' --json 2>/dev/null; }",
                         classified),
            0)
            << classified;
        ASSERT_EQ(loatest::run("'" + std::string(LOA_RENDER_EXE) + "' '" + model +
                                   "' --style cartographic --camera oblique --size 96x54 --out '" + dir +
                                   "/x.png' --stats '" + dir + "/x.json'",
                               rendered),
                  0)
            << rendered;
        std::ifstream in(dir + "/x.json");
        const nlohmann::json stats = nlohmann::json::parse(in);
        ASSERT_TRUE(stats.contains("features")) << stats.dump();
        EXPECT_EQ(stats["features"], nlohmann::json::parse(classified)) << model;
    }
}
