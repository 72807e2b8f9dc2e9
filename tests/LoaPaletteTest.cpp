// loa-palette: the tool that writes paper 003's segmented textures per level and the histogram
// chart for every texture of a model (runs the built executable; no GL).
#include <osgLoA/palette/WeightedColor>
#include <osgLoA/util/ImageFile>

#include "support/TestSupport.h"

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Group>
#include <osg/Texture2D>
#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <set>

using osgLoA::WeightedColor;

namespace
{

const std::string kExe = LOA_PALETTE_EXE;

int runTool(const std::string& args, std::string& out)
{
    return loatest::run("'" + kExe + "' " + args, out);
}

bool contains(const std::string& text, const std::string& what)
{
    return text.find(what) != std::string::npos;
}

unsigned rgbKey(const osg::Image& image, int x, int y)
{
    const unsigned char* p = image.data(x, y);
    return (unsigned(p[0]) << 16) | (unsigned(p[1]) << 8) | p[2];
}

std::set<unsigned> distinctColors(const osg::Image& image)
{
    std::set<unsigned> colors;
    for (int y = 0; y < image.t(); ++y)
        for (int x = 0; x < image.s(); ++x)
            colors.insert(rgbKey(image, x, y));
    return colors;
}

using Rgb = std::array<unsigned char, 3>;

/** The five colours of the synthetic texture and how many of its 16 texels show each (6, 4, 3,
 *  2, 1: distinct counts, so the histogram bars have known heights). */
const Rgb kFive[5] = {{200, 40, 30}, {30, 90, 200}, {240, 230, 60}, {20, 140, 40}, {250, 250, 250}};
const int kCounts[5] = {6, 4, 3, 2, 1};

osg::ref_ptr<osg::Image> fiveColorImage()
{
    osg::ref_ptr<osg::Image> img = new osg::Image;
    img->allocateImage(4, 4, 1, GL_RGB, GL_UNSIGNED_BYTE);
    img->setPacking(1);
    int color = 0, left = kCounts[0];
    for (int i = 0; i < 16; ++i)
    {
        // texels in a scattered order, so that colours are not one block each
        const int t = (i * 7) % 16;
        unsigned char* p = img->data(t % 4, t / 4);
        p[0] = kFive[color][0], p[1] = kFive[color][1], p[2] = kFive[color][2];
        if (--left == 0 && color < 4) left = kCounts[++color];
    }
    return img;
}

/** 4x4: columns 0-1 red (255,0,0) and blue (0,0,255) alternating by row; columns 2-3 hold
 *  near-red (250,20,20) on the red rows and near-blue (20,20,240) on the blue rows. */
osg::ref_ptr<osg::Image> halfImage()
{
    osg::ref_ptr<osg::Image> img = new osg::Image;
    img->allocateImage(4, 4, 1, GL_RGB, GL_UNSIGNED_BYTE);
    img->setPacking(1);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
        {
            const bool red = y % 2 == 0;
            const Rgb c =
                x < 2 ? (red ? Rgb{255, 0, 0} : Rgb{0, 0, 255}) : (red ? Rgb{250, 20, 20} : Rgb{20, 20, 240});
            unsigned char* p = img->data(x, y);
            p[0] = c[0], p[1] = c[1], p[2] = c[2];
        }
    return img;
}

osg::ref_ptr<osg::Geode> quad(osg::Image* image, float offset, float uMax)
{
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(osg::createTexturedQuadGeometry(osg::Vec3(offset, 0, 0), osg::X_AXIS, osg::Y_AXIS,
                                                       0.0f, 0.0f, uMax, 1.0f));
    if (image) geode->getOrCreateStateSet()->setTextureAttributeAndModes(0, new osg::Texture2D(image));
    return geode;
}

/** A model of two unit quads with inline 4x4 textures: "five colours.png" (the whole texture
 *  mapped, every texel of weight 1/4) and "half.png" (only u in [0, 0.5] mapped: columns 2-3
 *  have weight 0). */
std::string makeModel(const std::string& dir)
{
    osg::ref_ptr<osg::Image> five = fiveColorImage(), half = halfImage();
    five->setFileName("textures/five colours.png");
    half->setFileName("half.png");
    for (osg::Image* i : {five.get(), half.get()})
        i->setWriteHint(osg::Image::STORE_INLINE);
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(quad(five.get(), 0, 1.0f));
    root->addChild(quad(half.get(), 2, 0.5f));
    const std::string path = dir + "/model.osgt";
    EXPECT_TRUE(osgDB::writeNodeFile(
        *root, path, osg::ref_ptr<osgDB::Options>(new osgDB::Options("WriteImageHint=IncludeData")).get()));
    return path;
}

osg::ref_ptr<osg::Image> readPng(const std::string& path)
{
    try
    {
        return osgLoA::ImageFile::read(path);
    }
    catch (const std::exception& e)
    {
        ADD_FAILURE() << e.what();
        return nullptr;
    }
}

class LoaPalette : public ::testing::Test
{
protected:
    void SetUp() override
    {
        if (!osgDB::fileExists(kExe)) GTEST_SKIP() << "loa-palette not built: " << kExe;
        dir = loatest::freshDirectory(std::string("LoaPalette.") +
                                      ::testing::UnitTest::GetInstance()->current_test_info()->name());
        model = makeModel(dir);
    }
    std::string dir, model;
};

} // namespace

// Level 1 is the Lab weighted mean, level 5 (and the clamped 8) the texture itself; texels of
// weight 0 get the nearest level colour in Lab; the chart's bars have the hand-computed heights.
TEST_F(LoaPalette, SyntheticModelLevelsAndChart)
{
    std::string out;
    const std::string o = dir + "/out";
    const int rc = runTool("'" + model + "' --levels 5,1,8 --out-dir '" + o + "'", out);
    ASSERT_EQ(rc, 0) << out;
    EXPECT_TRUE(contains(out, "five colours.png has 5 colours: level 8 gives all 5")) << out;

    const osg::ref_ptr<osg::Image> texture = fiveColorImage();
    const osg::ref_ptr<osg::Image> l1 = readPng(o + "/five_colours-1.png"),
                                   l5 = readPng(o + "/five_colours-5.png"),
                                   l8 = readPng(o + "/five_colours-8.png");
    ASSERT_TRUE(l1 && l5 && l8);
    for (const osg::Image* i : {l1.get(), l5.get(), l8.get()})
        ASSERT_TRUE(i->s() == 4 && i->t() == 4) << i->s() << "x" << i->t();
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
        {
            EXPECT_EQ(rgbKey(*l5, x, y), rgbKey(*texture, x, y)) << x << "," << y;
            EXPECT_EQ(rgbKey(*l8, x, y), rgbKey(*texture, x, y)) << x << "," << y;
        }

    // Level 1: one colour, the count-weighted mean of the five in CIELab (every texel weighs 1/4).
    ASSERT_EQ(distinctColors(*l1).size(), 1u);
    osg::Vec3f mean;
    for (int i = 0; i < 5; ++i)
        mean += WeightedColor::toLab(osg::Vec3f(kFive[i][0], kFive[i][1], kFive[i][2]) / 255.0f) *
                (float(kCounts[i]) / 16.0f);
    const osg::Vec3f expected = WeightedColor::fromLab(mean) * 255.0f;
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(l1->data(0, 0)[c], expected[c], 0.51) << "channel " << c;

    // half.png: level 2 = red, blue (the only weighted colours); the unused columns take the
    // nearest of them in Lab: near-red -> red, near-blue -> blue.
    std::string out2;
    ASSERT_EQ(runTool("'" + model + "' --levels 2 --out-dir '" + o + "2'", out2), 0) << out2;
    // A second run into the same folder replaces it as a whole: level 2 only, no level 5 file of
    // an earlier run beside the new palettes.json.
    ASSERT_EQ(runTool("'" + model + "' --levels 5 --out-dir '" + o + "2'", out2), 0) << out2;
    EXPECT_TRUE(osgDB::fileExists(o + "2/half-5.png"));
    ASSERT_EQ(runTool("'" + model + "' --levels 2 --out-dir '" + o + "2'", out2), 0) << out2;
    EXPECT_FALSE(osgDB::fileExists(o + "2/half-5.png")) << "old and new outputs mixed";
    const osg::ref_ptr<osg::Image> h2 = readPng(o + "2/half-2.png");
    ASSERT_TRUE(h2);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
            EXPECT_EQ(rgbKey(*h2, x, y), y % 2 == 0 ? 0xff0000u : 0x0000ffu) << x << "," << y;

    // The chart: 1024 wide, 8 + 200 + 1 + 3 x (8 + 28) + 8 high. Bars of 960 / 5 = 192 columns from
    // x = 56, sorted by weight (counts 6, 4, 3, 2, 1): heights round(200 w / 6).
    const osg::ref_ptr<osg::Image> chart = readPng(o + "/five_colours-histogram.png");
    ASSERT_TRUE(chart);
    ASSERT_EQ(chart->s(), 1024);
    ASSERT_EQ(chart->t(), 8 + 200 + 1 + 3 * 36 + 8);
    auto at = [&](int x, int yTop) { return rgbKey(*chart, x, chart->t() - 1 - yTop); };
    const int heights[5] = {200, 133, 100, 67, 33};
    for (int i = 0; i < 5; ++i)
    {
        const unsigned color = (unsigned(kFive[i][0]) << 16) | (unsigned(kFive[i][1]) << 8) | kFive[i][2];
        int h = 0;
        for (int y = 0; y < 208; ++y)
            h += at(56 + 192 * i + 96, y) == color ? 1 : 0;
        EXPECT_EQ(h, heights[i]) << "bar " << i;
        EXPECT_EQ(at(56 + 192 * i + 96, 207), color) << "bar " << i << " stands on the baseline";
    }
    // Strips in level order 1, 5, 8: level 1 is one colour across; level 5 shows the five with
    // widths 960 * count / 16 = 360, 240, 180, 120, 60.
    const int strip1 = 209 + 8 + 14, strip5 = strip1 + 36;
    for (int x = 56; x < 56 + 960; x += 7)
        EXPECT_EQ(at(x, strip1), rgbKey(*l1, 0, 0)) << x;
    int x0 = 56;
    for (int i = 0; i < 5; ++i)
    {
        const unsigned color = (unsigned(kFive[i][0]) << 16) | (unsigned(kFive[i][1]) << 8) | kFive[i][2];
        const int w = 960 * kCounts[i] / 16;
        EXPECT_EQ(at(x0, strip5), color) << "strip 5 colour " << i;
        EXPECT_EQ(at(x0 + w - 1, strip5), color) << "strip 5 colour " << i;
        x0 += w;
    }

    // palettes.json: balanced, and the keys and values above.
    std::ifstream in(o + "/palettes.json");
    const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    int depth = 0;
    bool inString = false, balanced = true;
    for (std::size_t i = 0; i < json.size(); ++i)
    {
        const char c = json[i];
        if (inString)
        {
            if (c == '\\')
                ++i;
            else if (c == '"')
                inString = false;
        }
        else if (c == '"')
            inString = true;
        else if (c == '{' || c == '[')
            ++depth;
        else if (c == '}' || c == ']')
            balanced = balanced && --depth >= 0;
    }
    EXPECT_TRUE(balanced && depth == 0 && !inString) << json;
    for (const char* key :
         {"\"levels\": [1, 5, 8]", "\"name\": \"five_colours\"", "\"name\": \"half\"", "\"tableSize\": 5",
          "\"tableSize\": 2", "\"width\": 4", "\"level\": 8, \"colors\": 5", "\"level\": 1, \"colors\": 1",
          "\"color\": \"#c8281e\"", "\"linkage\": \"ward\"", "\"weights\": \"cpu\"", "\"skipped\": []"})
        EXPECT_TRUE(contains(json, key)) << key << "\n" << json;
}

// The demo city through the loacity pseudo-loader, levels 2 and 4: every unit-0 texture image
// gets its two segmented PNGs of its own size with at most k colours, and a chart.
TEST_F(LoaPalette, DemoCity)
{
    const std::string options = "seed=2 blocksX=2 blocksY=2", o = dir + "/city";
    std::string out;
    const int rc = runTool("demo.loacity -O '" + options + "' --levels 2,4 --out-dir '" + o + "'", out);
    ASSERT_EQ(rc, 0) << out;
    EXPECT_TRUE(contains(out, " 0 skipped")) << out;

    // The textures, read here independently of the tool.
    osg::ref_ptr<osg::Node> city =
        osgDB::readNodeFile("demo.loacity", osg::ref_ptr<osgDB::Options>(new osgDB::Options(options)).get());
    ASSERT_TRUE(city);
    std::map<std::string, osg::ref_ptr<osg::Image>> images;
    struct Collect : osg::NodeVisitor
    {
        std::map<std::string, osg::ref_ptr<osg::Image>>* images;
        Collect() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
        void check(osg::StateSet* ss)
        {
            if (!ss) return;
            if (auto* t =
                    dynamic_cast<osg::Texture2D*>(ss->getTextureAttribute(0, osg::StateAttribute::TEXTURE)))
                if (t->getImage())
                    (*images)[osgDB::getStrippedName(t->getImage()->getFileName())] = t->getImage();
        }
        void apply(osg::Node& n) override
        {
            check(n.getStateSet());
            traverse(n);
        }
        void apply(osg::Drawable& d) override { check(d.getStateSet()); }
    } collect;
    collect.images = &images;
    city->accept(collect);
    ASSERT_FALSE(images.empty());

    std::ifstream in(o + "/palettes.json");
    const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_TRUE(contains(json, "\"levels\": [2, 4]")) << json;
    for (const auto& kv : images)
    {
        EXPECT_TRUE(contains(json, "\"name\": \"" + kv.first + "\"")) << kv.first;
        for (unsigned k : {2u, 4u})
        {
            const osg::ref_ptr<osg::Image> seg =
                readPng(o + "/" + kv.first + "-" + std::to_string(k) + ".png");
            ASSERT_TRUE(seg) << kv.first;
            EXPECT_EQ(seg->s(), kv.second->s()) << kv.first;
            EXPECT_EQ(seg->t(), kv.second->t()) << kv.first;
            const std::size_t n = distinctColors(*seg).size();
            EXPECT_LE(n, k) << kv.first << " level " << k;
            EXPECT_GE(n, 2u) << kv.first << " level " << k;
        }
        EXPECT_TRUE(osgDB::fileExists(o + "/" + kv.first + "-histogram.png")) << kv.first;
    }
}

TEST_F(LoaPalette, UsageAndFailureExitCodes)
{
    // A model with geometry but no texture.
    osg::ref_ptr<osg::Group> bare = new osg::Group;
    bare->addChild(quad(nullptr, 0, 1.0f));
    ASSERT_TRUE(osgDB::writeNodeFile(*bare, dir + "/bare.osgt"));
    std::ofstream(dir + "/file") << "x";

    struct Case
    {
        std::string args;
        int rc;
        std::string message;
    };
    const std::string m = "'" + model + "'", o = " --out-dir '" + dir + "/out'";
    const std::vector<Case> cases = {
        {"", 2, "no MODEL given"},
        {m, 2, "--out-dir DIR is required"},
        {m + o + " --levels 0", 2, "--levels '0': 0 is outside 1..65536"},
        {m + o + " --levels 4,,8", 2, "'' is not a level"},
        {m + o + " --levels four", 2, "'four' is not a level"},
        {m + o + " --levels 70000", 2, "outside 1..65536"},
        {m + o + " --levels", 2, "--levels needs a value"},
        {m + o + " --linkage single", 2, "--linkage 'single' is not ward or centroid"},
        {m + o + " --max-colors 0", 2, "--max-colors must be at least 1"},
        {m + o + " --frobnicate", 2, "unknown option '--frobnicate'"},
        {m + " '" + dir + "/nothere.osgb'" + o, 1, "nothere.osgb"}, // several models: each must read
        {"'" + dir + "/nothere.osgt'" + o, 1, "cannot read"},
        {"'" + dir + "/bare.osgt'" + o, 1, "no textured geometry"},
        {m + " --out-dir '" + dir + "/file/sub'", 1, "cannot create the output directory"},
        {m + " --out-dir '" + dir + "/file'", 1, "exists and is not a directory"},
        // A folder of other files is never replaced (the output folder is written as a whole).
        {m + " --out-dir '" + dir + "'", 1, "holds files this tool did not write"},
    };
    for (const Case& k : cases)
    {
        std::string out;
        EXPECT_EQ(runTool(k.args, out), k.rc) << k.args << "\n" << out;
        EXPECT_EQ(out.rfind("loa-palette: error: ", 0), 0u) << k.args << "\n" << out;
        EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << k.args << "\n" << out;
        EXPECT_TRUE(contains(out, k.message)) << k.args << "\n" << out;
    }

    // A table above --max-colors: five colours.png (5) is skipped with exit 4, half.png (2) done.
    std::string out;
    EXPECT_EQ(runTool(m + o + " --max-colors 3 --quiet", out), 4) << out;
    EXPECT_TRUE(contains(out, "five colours.png: its colour table holds 5 colours, above --max-colors 3"))
        << out;
    // --quiet: only the skip and the note on half.png's 2 colours
    EXPECT_TRUE(contains(out, "half.png has 2 colours: levels 4, 8, 16, 32 give all 2")) << out;
    EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 2) << out;
    EXPECT_FALSE(osgDB::fileExists(dir + "/out/five_colours-4.png"));
    EXPECT_TRUE(osgDB::fileExists(dir + "/out/half-4.png"));

    EXPECT_EQ(runTool("--help", out), 0);
    EXPECT_TRUE(contains(out, "exit status")) << out;
    EXPECT_TRUE(contains(out, "nearest level-k colour in CIELab")) << out;
}
