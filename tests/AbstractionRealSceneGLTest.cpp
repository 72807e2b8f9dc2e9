// Every image-space and hybrid abstraction style on a real scene nobody on the project made
// (TORCS street-1, scripts/fetch-test-data; docs/test-scenes.md) at 480x270 against a golden
// each, and the failures real scenes showed (issue: "image styles on real scenes"), measured:
//  - DoG does not dot flat terrain: isolated dark pixels on the textured ground stay below a bar,
//    and the paper's threshold epsilon = 0 (the documented failure) makes many more;
//  - pencil keeps lit faces visible against the sky: the sky stays the sky, geometry does not
//    take the sky's colour;
//  - silhouettes are not drawn between the hundreds of coplanar terrain pieces: with silhouettes
//    the hybrid-toon frame has few more line pixels than without.
// The scene's tree cards are alpha-textured (blended by OSG's ac reader):
// AbstractionNodeGLTest.SilhouettesFollowTheAlphaOfCards has the hand-checked case.
#include <osgLoA/abstraction/AbstractionNode>
#include <osgLoA/abstraction/AbstractionStyleCatalog>
#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/render/ShaderLibrary>
#include <osgLoA/util/ImageCompare>
#include <osgLoA/util/ImageFile>

#include "support/TestSupport.h"

#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>

using namespace osgLoA;

namespace
{
const int W = 480, H = 270;
const osg::Vec4 kSky(0.62f, 0.75f, 0.90f, 1.0f);

/** TORCS street-1 as the loader reads it (null when scripts/fetch-test-data has not run). */
osg::ref_ptr<osg::Node> street1()
{
    static osg::ref_ptr<osg::Node> model;
    static bool tried = false;
    if (!tried)
    {
        tried = true;
        const std::string path = std::string(LOA_SOURCE_DIR) + "/data/test-scenes/torcs-street-1.osgt";
        const std::string texture =
            std::string(LOA_SOURCE_DIR) + "/data/cache/torcs-data/street-1/grass-aa.rgb";
        if (osgDB::fileExists(path) && osgDB::fileExists(texture)) model = osgDB::readRefNodeFile(path);
    }
    return model;
}

/** A view over the track (terrain pieces, road, trees (cards), buildings and the sky), or with
 *  `ground` a view from 20 m above the grass near the track's centre, the near ground filling the
 *  lower third of the frame. */
osg::ref_ptr<osg::Image> render(osg::Node* scene, bool ground = false, int width = W, int height = H)
{
    OffscreenRenderer::Settings s;
    s.width = width;
    s.height = height;
    s.clearColor = kSky;
    osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(s);
    r->setSceneData(scene);
    const osg::BoundingSphere bs = street1()->getBound();
    r->setPerspective(45.0);
    if (ground)
        r->setViewMatrixAsLookAt(osg::Vec3d(701, 206, 35), osg::Vec3d(701, 290, 12), osg::Vec3d(0, 0, 1));
    else
        r->setViewMatrixAsLookAt(bs.center() + osg::Vec3d(0.18, -0.3, 0.16) * bs.radius(), bs.center(),
                                 osg::Vec3d(0, 0, 1));
    return r->renderImage();
}

osg::ref_ptr<osg::Image> styled(AbstractionStyle* style, bool ground = false, int width = W, int height = H)
{
    osg::ref_ptr<AbstractionNode> node = new AbstractionNode;
    node->setStyle(style);
    node->addChild(street1().get());
    osg::ref_ptr<osg::Image> img = render(node.get(), ground, width, height);
    EXPECT_EQ(node->getLastError(), "");
    return img;
}

double luma(const osg::Image& img, int x, int y)
{
    const unsigned char* p = img.data(x, y);
    return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
}

bool isSky(const osg::Image& img, int x, int y)
{
    const unsigned char* p = img.data(x, y);
    for (int c = 0; c < 3; ++c)
        if (std::abs(int(p[c]) - int(std::lround(kSky[c] * 255.0f))) > 8) return false;
    return true;
}

/** Fraction of the lower third of the frame (the near grass in the ground view) that img draws
 *  dark: luma below half the plain frame's at that pixel (DoG lines and dots). */
double darkened(const osg::Image& img, const osg::Image& plain)
{
    long long n = 0, all = 0;
    for (int y = 0; y < H / 3; ++y) // osg::Image row 0 is the bottom of the frame
        for (int x = 0; x < W; ++x, ++all)
            if (luma(img, x, y) < 0.5 * luma(plain, x, y)) ++n;
    return double(n) / double(all);
}

/** Fraction of pixels that are black lines (luma below 24). */
double linePixels(const osg::Image& img)
{
    long long n = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            if (luma(img, x, y) < 24.0) ++n;
    return double(n) / (double(W) * H);
}

class AbstractionRealSceneGLTest : public ::testing::TestWithParam<std::string>
{
};
} // namespace

TEST_P(AbstractionRealSceneGLTest, MatchesGolden)
{
    if (!street1()) GTEST_SKIP() << "TORCS street-1 is not extracted: run scripts/fetch-test-data";
    const std::string style = GetParam();
    osg::ref_ptr<osg::Image> actual = styled(AbstractionStyleCatalog::instance().create(style).get());
    const std::string name = "abstraction-street-1-" + style + "-480x270";
    osgDB::makeDirectory(std::string(LOA_TEST_OUTPUT_DIR) + "/real-scene");
    ImageFile::write(std::string(LOA_TEST_OUTPUT_DIR) + "/real-scene/" + name + ".png", *actual);
    std::string summary;
    bool skipped = false;
    const bool ok = loatest::matchesAbstractionGolden(name, *actual, summary, skipped);
    if (skipped) GTEST_SKIP() << "LOA_UPDATE_GOLDENS=1: wrote tests/data/golden/" << name << ".png";
    EXPECT_TRUE(ok) << name << ": " << summary;
    osg::ref_ptr<osg::Image> plain = render(street1().get());
    EXPECT_GT(ImageComparison::compare(*actual, *plain, 16).failingFraction, 0.02) << style;
}

INSTANTIATE_TEST_SUITE_P(Styles, AbstractionRealSceneGLTest,
                         ::testing::ValuesIn(AbstractionStyle::builtinNames()),
                         [](const ::testing::TestParamInfo<std::string>& p)
                         { return loatest::paramName(p.param); });

// DoG on the rendered frame, close over textured grass: the default threshold (epsilon -1 L*)
// darkens at most 0.5 % of the near ground; the paper's epsilon 0, which draws a line wherever
// the response is negative at all, dots the grass (the documented failure, at least 3x as much).
TEST(AbstractionRealSceneGLTest, DogDoesNotDotTheTerrain)
{
    if (!street1()) GTEST_SKIP() << "TORCS street-1 is not extracted: run scripts/fetch-test-data";
    osg::ref_ptr<osg::Image> plain = render(street1().get(), true);
    osg::ref_ptr<AbstractionStyle> dog = AbstractionStyleCatalog::instance().create("dog");
    osg::ref_ptr<osg::Image> ours = styled(dog.get(), true);
    dog->setDogEpsilon(0.0f);
    osg::ref_ptr<osg::Image> theirs = styled(dog.get(), true);
    osgDB::makeDirectory(std::string(LOA_TEST_OUTPUT_DIR) + "/real-scene");
    ImageFile::write(std::string(LOA_TEST_OUTPUT_DIR) + "/real-scene/dog-ground-epsilon-0.png", *theirs);
    ImageFile::write(std::string(LOA_TEST_OUTPUT_DIR) + "/real-scene/dog-ground.png", *ours);
    const double dots = darkened(*ours, *plain), paper = darkened(*theirs, *plain);
    std::cout << "dog on the near grass: " << 100.0 * dots << " % darkened (epsilon 0: " << 100.0 * paper
              << " %)\n";
    EXPECT_LE(dots, 0.005);
    EXPECT_GE(paper, 3.0 * dots);
}

// Pencil on white paper with a sky: the sky stays the sky (at least 99 % of the plain frame's sky
// pixels) and lit faces, drawn white, do not take the sky's colour (at most 1 % of the covered
// pixels look like sky).
TEST(AbstractionRealSceneGLTest, PencilKeepsLitFacesVisibleAgainstTheSky)
{
    if (!street1()) GTEST_SKIP() << "TORCS street-1 is not extracted: run scripts/fetch-test-data";
    osg::ref_ptr<osg::Image> plain = render(street1().get());
    osg::ref_ptr<osg::Image> pencil = styled(AbstractionStyleCatalog::instance().create("pencil").get());
    long long sky = 0, skyKept = 0, covered = 0, coveredAsSky = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            if (isSky(*plain, x, y))
            {
                ++sky;
                skyKept += isSky(*pencil, x, y) ? 1 : 0;
            }
            else
            {
                ++covered;
                coveredAsSky += isSky(*pencil, x, y) ? 1 : 0;
            }
    ASSERT_GT(sky, 1000);
    ASSERT_GT(covered, 1000);
    EXPECT_GE(double(skyKept), 0.99 * double(sky));
    EXPECT_LE(double(coveredAsSky), 0.01 * double(covered));
}

// hybrid-toon with object-ID silhouettes: street-1's ground is hundreds of coplanar pieces. The
// silhouettes are drawn only where the surface is discontinuous; drawn at every change of object
// (the paper's rule, the documented failure: every terrain piece outlined, restored here by
// overriding the compositing shader through OSG_FILE_PATH) they add far more line pixels. Bar:
// our silhouettes add at most half the lines the paper's rule adds.
TEST(AbstractionRealSceneGLTest, SilhouettesDoNotOutlineTerrainPieces)
{
    if (!street1()) GTEST_SKIP() << "TORCS street-1 is not extracted: run scripts/fetch-test-data";
    osg::ref_ptr<AbstractionStyle> toon = AbstractionStyleCatalog::instance().create("hybrid-toon");
    ASSERT_TRUE(toon->getSilhouettes());
    osg::ref_ptr<osg::Image> withImage = styled(toon.get());
    // The paper's rule: a silhouette wherever the object id changes.
    std::string text = ShaderLibrary::getSource("loa_abstraction_compose.frag.glsl").text;
    const std::string rule =
        "    return 1.0 - dot(a.xyz, b.xyz) > 0.05 || abs(a.w - b.w) > 0.02 * max(a.w, b.w);";
    const std::size_t at = text.find(rule);
    ASSERT_NE(at, std::string::npos) << "the silhouette rule changed: update this test";
    text.replace(at, rule.size(), "    return true;");
    const std::string dir = loatest::freshDirectory("AbstractionRealSceneSilhouettes");
    std::ofstream(dir + "/loa_abstraction_compose.frag.glsl") << text;
    loatest::setFilePath(dir);
    osg::ref_ptr<osg::Image> paperImage = styled(toon.get());
    loatest::setFilePath("");
    toon->setSilhouettes(false);
    osg::ref_ptr<osg::Image> withoutImage = styled(toon.get());
    osgDB::makeDirectory(std::string(LOA_TEST_OUTPUT_DIR) + "/real-scene");
    ImageFile::write(std::string(LOA_TEST_OUTPUT_DIR) + "/real-scene/hybrid-toon-silhouettes.png",
                     *withImage);
    ImageFile::write(std::string(LOA_TEST_OUTPUT_DIR) +
                         "/real-scene/hybrid-toon-silhouettes-every-object.png",
                     *paperImage);
    const double with = linePixels(*withImage), paper = linePixels(*paperImage),
                 without = linePixels(*withoutImage);
    std::cout << "hybrid-toon line pixels: " << 100.0 * with << " % with silhouettes, " << 100.0 * paper
              << " % with a silhouette at every object change, " << 100.0 * without << " % without\n";
    EXPECT_GT(with, without);
    EXPECT_LE(with - without, 0.5 * (paper - without));
}

// Every style on the real scene at 1920x1080 (the goldens are 480x270): the image stages run
// without error at full HD, change the picture (at least 2 % of the pixels by more than 16/255),
// and leave no 16x16 block black where plain rendering has content (the black blocks that
// viewport bugs leave). The frames are written to build/test-output/real-scene/ to look at.
TEST(AbstractionRealSceneGLTest, EveryStyleAt1920x1080)
{
    if (!street1()) GTEST_SKIP() << "TORCS street-1 is not extracted: run scripts/fetch-test-data";
    const int w = 1920, h = 1080;
    osg::ref_ptr<osg::Image> plain = render(street1().get(), false, w, h);
    osgDB::makeDirectory(std::string(LOA_TEST_OUTPUT_DIR) + "/real-scene");
    auto black = [](const osg::Image& img, int x, int y)
    {
        const unsigned char* p = img.data(x, y);
        return p[0] < 4 && p[1] < 4 && p[2] < 4;
    };
    for (const std::string& name : AbstractionStyle::builtinNames())
    {
        osg::ref_ptr<osg::Image> img = styled(AbstractionStyleCatalog::instance().create(name).get(), false, w, h);
        ImageFile::write(std::string(LOA_TEST_OUTPUT_DIR) + "/real-scene/street-1-" + name + "-1920x1080.png", *img);
        EXPECT_GT(ImageComparison::compare(*img, *plain, 16).failingFraction, 0.02) << name;
        int blocks = 0;
        for (int ty = 0; ty + 16 <= h; ty += 16)
            for (int tx = 0; tx + 16 <= w; tx += 16)
            {
                bool styledBlack = true, plainBlack = true;
                for (int y = ty; y < ty + 16; ++y)
                    for (int x = tx; x < tx + 16; ++x)
                    {
                        styledBlack = styledBlack && black(*img, x, y);
                        plainBlack = plainBlack && black(*plain, x, y);
                    }
                if (styledBlack && !plainBlack) ++blocks;
            }
        EXPECT_EQ(blocks, 0) << name << ": black 16x16 blocks where plain rendering has content";
    }
}
