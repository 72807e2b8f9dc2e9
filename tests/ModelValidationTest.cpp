// Models validated after load (issue 22 items 2, 3): an inline image that states more than it
// holds is emptied (it was read past its buffer), geometry indexing past its vertices or with
// non-finite vertices is dropped with a warning naming it (OSG's bound code read past the array
// of a bit-flipped .osgb), and a truncated .osgt model is refused before OSG's text reader,
// which looped forever on it; through the library and through the tools.
#include "support/TestSupport.h"

#include <osgLoA/transitions/ScenarioLibrary>
#include <osgLoA/util/BoundedObjectReader>
#include <osgLoA/util/ModelValidation>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/MatrixTransform>
#include <osg/PositionAttitudeTransform>
#include <osg/Texture2D>
#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <tuple>

using osgLoA::ModelStructureError;
using osgLoA::ModelValidation;

using loatest::triangle;

TEST(ModelValidationTest, ImagesThatStateMoreThanTheyHoldAreEmptied)
{
    const std::string dir = loatest::freshDirectory("ModelValidationImages");
    const std::string text = loatest::writeTexturedTriangle(dir + "/ok.osgt");
    osg::ref_ptr<osg::Node> ok = osgDB::readRefNodeFile(dir + "/ok.osgt");
    ASSERT_TRUE(ok.valid());
    EXPECT_TRUE(ModelValidation::validate(*ok, "ok.osgt").emptiedImages.empty());
    for (const char* size : {"Size 64 64 1", "Size 4096 4096 1"})
    {
        const std::string path = dir + "/lying.osgt";
        std::ofstream(path) << loatest::replaced(text, "Size 4 4 1", size);
        osg::ref_ptr<osg::Node> n = osgDB::readRefNodeFile(path);
        ASSERT_TRUE(n.valid());
        const ModelValidation v = ModelValidation::validate(*n, path);
        ASSERT_EQ(v.emptiedImages.size(), 1u) << size;
        EXPECT_NE(v.emptiedImages.front().find("image 'tex.png': states"), std::string::npos)
            << v.emptiedImages.front();
        // The batch tool reports the emptied image as unreadable (exit 4), no overrun, no crash.
        std::string out;
        EXPECT_EQ(loatest::run(std::string("'") + LOA_PREFILTER_EXE + "' '" + path +
                                   "' --filter gaussian --cache '" + dir + "/cache'",
                               out),
                  4)
            << out;
        EXPECT_NE(out.find("tex.png"), std::string::npos) << out;
    }
    // A pixel format without a size (0-byte rows: nothing looked too large, and the filter
    // cache's hash walked 2e9 rows; ModelFuzzer found it), and a size OSG's unsigned int
    // overflows (65536 x 65536 x RGBA = 16 GiB, 0 in 32 bits) over 64 bytes of data.
    for (const auto& c :
         {std::make_tuple(GLenum(0x20656461), GLenum(GL_UNSIGNED_BYTE), 4, 4, "has no pixel size"),
          std::make_tuple(GLenum(GL_RGBA), GLenum(GL_UNSIGNED_BYTE), 65536, 65536, "(17179869184 bytes)")})
    {
        osg::ref_ptr<osg::Geode> g = new osg::Geode;
        osg::ref_ptr<osg::Geometry> tri = triangle("t");
        osg::ref_ptr<osg::Image> image = new osg::Image;
        unsigned char* data = new unsigned char[64];
        std::memset(data, 200, 64);
        image->setImage(std::get<2>(c), std::get<3>(c), 1, GL_RGBA, std::get<0>(c), std::get<1>(c), data,
                        osg::Image::USE_NEW_DELETE);
        tri->getOrCreateStateSet()->setTextureAttributeAndModes(0, new osg::Texture2D(image.get()));
        g->addDrawable(tri.get());
        const ModelValidation v = ModelValidation::validate(*g, "pixels.osgb");
        ASSERT_EQ(v.emptiedImages.size(), 1u);
        EXPECT_NE(v.emptiedImages[0].find(std::get<4>(c)), std::string::npos) << v.emptiedImages[0];
        EXPECT_EQ(image->s(), 0);
    }
}

TEST(ModelValidationTest, GeometryPastItsArraysIsDroppedWithItsName)
{
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->setName("block");
    geode->addDrawable(triangle("good").get());
    osg::ref_ptr<osg::Geometry> pastIndices = triangle("flipped");
    osg::ref_ptr<osg::DrawElementsUShort> indices = new osg::DrawElementsUShort(GL_TRIANGLES);
    for (unsigned short i : {0, 1, 40000})
        indices->push_back(i);
    pastIndices->setPrimitiveSet(0, indices.get());
    geode->addDrawable(pastIndices.get());
    osg::ref_ptr<osg::Geometry> pastArrays = triangle("ranges");
    pastArrays->setPrimitiveSet(0, new osg::DrawArrays(GL_TRIANGLES, 1, 3));
    geode->addDrawable(pastArrays.get());
    osg::ref_ptr<osg::Geometry> shortNormals = triangle("normals");
    osg::ref_ptr<osg::Vec3Array> normals = new osg::Vec3Array(1);
    shortNormals->setNormalArray(normals.get(), osg::Array::BIND_PER_VERTEX);
    geode->addDrawable(shortNormals.get());
    osg::ref_ptr<osg::Geometry> nan = triangle("nan");
    (*static_cast<osg::Vec3Array*>(nan->getVertexArray()))[1].x() = std::nanf("");
    geode->addDrawable(nan.get());
    // Finite but beyond MAX_COORDINATE: the bounding sphere overflowed to infinity (ModelFuzzer),
    // in a double array too.
    osg::ref_ptr<osg::Geometry> huge = triangle("huge");
    osg::ref_ptr<osg::Vec3dArray> far = new osg::Vec3dArray;
    far->push_back({0, 0, 0});
    far->push_back({3e38, 0, 0});
    far->push_back({0, -3e38, 0});
    huge->setVertexArray(far.get());
    geode->addDrawable(huge.get());

    // Through a binary file, as a bit-flipped .osgb arrives.
    const std::string dir = loatest::freshDirectory("ModelValidationGeometry");
    ASSERT_TRUE(osgDB::writeNodeFile(*geode, dir + "/bad.osgb"));
    osg::ref_ptr<osg::Node> n = osgDB::readRefNodeFile(dir + "/bad.osgb");
    ASSERT_TRUE(n.valid());
    const ModelValidation v = ModelValidation::validate(*n, "bad.osgb");
    ASSERT_EQ(v.removedDrawables.size(), 5u);
    std::string all;
    for (const std::string& r : v.removedDrawables)
        all += r + "|";
    EXPECT_NE(all.find("drawable 'flipped' in Geode 'block': index 40000 past 3 vertices"), std::string::npos)
        << all;
    EXPECT_NE(all.find("drawable 'ranges' in Geode 'block': DrawArrays 1+3 past 3 vertices"),
              std::string::npos)
        << all;
    EXPECT_NE(
        all.find("drawable 'normals' in Geode 'block': a per-vertex array of 1 elements for 3 vertices"),
        std::string::npos)
        << all;
    EXPECT_NE(
        all.find("drawable 'nan' in Geode 'block': a vertex coordinate (nan) that is not finite or beyond "
                 "1e15"),
        std::string::npos)
        << all;
    EXPECT_NE(all.find("drawable 'huge' in Geode 'block': a vertex coordinate (3000000"), std::string::npos)
        << all;
    ASSERT_EQ(n->asGeode()->getNumDrawables(), 1u);
    EXPECT_EQ(n->asGeode()->getDrawable(0)->getName(), "good");
    const osg::BoundingSphere bs = n->getBound();
    EXPECT_TRUE(std::isfinite(bs.radius()));

    // The tool reads it, warns and goes on with what is valid.
    std::string out;
    EXPECT_EQ(loatest::run(std::string("'") + LOA_CLASSIFY_EXE + "' '" + dir + "/bad.osgb' --json", out), 0)
        << out;
    EXPECT_NE(out.find("index 40000 past 3 vertices; dropped"), std::string::npos) << out;
}

TEST(ModelValidationTest, TruncatedTextModelsAreRefusedAtOnce)
{
    const std::string dir = loatest::freshDirectory("ModelValidationTruncated");
    const std::string text = loatest::writeTexturedTriangle(dir + "/whole.osgt");
    EXPECT_EQ(ModelValidation::checkOsgtStructure(dir + "/whole.osgt"), "");
    std::ofstream(dir + "/half.osgt") << text.substr(0, text.size() / 2);
    EXPECT_EQ(ModelValidation::checkOsgtStructure(dir + "/half.osgt"),
              "the text ends inside an object ('{' and '}' do not match)");
    std::ofstream(dir + "/quote.osgt") << text.substr(0, text.find("tex.png") + 3);
    EXPECT_EQ(ModelValidation::checkOsgtStructure(dir + "/quote.osgt"),
              "the text ends inside a quoted string");
    std::ofstream(dir + "/extra.osgt") << text << "}\n";
    EXPECT_EQ(ModelValidation::checkOsgtStructure(dir + "/extra.osgt"), "a '}' closes no object");
    for (const char* tool : {LOA_CLASSIFY_EXE, LOA_RENDER_EXE})
    {
        std::string out;
        const auto t0 = std::chrono::steady_clock::now();
        EXPECT_EQ(
            loatest::run("timeout 60 '" + std::string(tool) + "' '" + dir + "/half.osgt' --size 64x48", out),
            1)
            << out;
        EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
        EXPECT_NE(out.find("half.osgt': the OSG text file is incomplete: the text ends inside an object"),
                  std::string::npos)
            << out;
        EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
    }
}

// OSG's text reader takes "nan" and "inf" as 0: a scenario's "Near nan" validated as 0 and
// "FadeIn inf -inf" as 0..0. The structure check refuses non-finite words outside strings.
TEST(ModelValidationTest, NonFiniteNumbersInTextAreRefused)
{
    const std::string text =
        loatest::fileBytes(std::string(LOA_SOURCE_DIR) + "/data/scenarios/distance.osgt");
    ASSERT_EQ(ModelValidation::checkOsgtText(text), "");
    const std::size_t near = text.find("Near ");
    ASSERT_NE(near, std::string::npos);
    const std::size_t end = text.find_first_of(" \n", near + 5);
    std::string bad = text;
    bad.replace(near + 5, end - (near + 5), "nan");
    EXPECT_NE(ModelValidation::checkOsgtText(bad).find("a number that is not finite ('nan' at byte"),
              std::string::npos);
    const std::string dir = loatest::freshDirectory("ModelValidationNonFinite");
    std::ofstream(dir + "/near-nan.osgt") << bad;
    try
    {
        osgLoA::ScenarioLibrary::readFile(dir + "/near-nan.osgt");
        ADD_FAILURE() << "a scenario with Near nan was read";
    }
    catch (const std::exception& e)
    {
        EXPECT_NE(std::string(e.what()).find("not finite ('nan'"), std::string::npos) << e.what();
    }
    EXPECT_NE(ModelValidation::checkOsgtText("osg::Group { FadeIn inf -inf }").find("('inf' at byte 20)"),
              std::string::npos);
    EXPECT_NE(ModelValidation::checkOsgtText("osg::Group { X -INFINITY }").find("'-INFINITY'"),
              std::string::npos);
    // Inside strings the words are names, and words that only start with them are other words.
    EXPECT_EQ(ModelValidation::checkOsgtText("osg::Group { Name \"nan inf\" Information 1 nanometre 2 }"),
              "");
}

// The scan's edges (it runs from delimiter to delimiter): escapes, control characters inside and
// outside strings, a NUL inside the text, a backslash at the very end; and a real model passes.
TEST(ModelValidationTest, TextScanEdges)
{
    EXPECT_EQ(ModelValidation::checkOsgtText("osg::Group { Name \"a\\\"b\" }"), "");
    EXPECT_EQ(ModelValidation::checkOsgtText("osg::Group { Name \"a\x01"
                                             "b\" }"),
              "the text contains the control character 0x1 at byte 20");
    EXPECT_EQ(ModelValidation::checkOsgtText("osg::Group {\x1f}"),
              "the text contains the control character 0x1f at byte 12");
    EXPECT_EQ(ModelValidation::checkOsgtText(std::string("osg::Group {\0}", 14)),
              "the text contains the control character 0x0 at byte 12");
    EXPECT_EQ(ModelValidation::checkOsgtText("osg::Group { Name \"ab\\"),
              "the text ends inside a quoted string");
    EXPECT_EQ(ModelValidation::checkOsgtText("osg::Group { Name \"a\\\x01\" }"),
              ""); // escaped: as OSG reads it
    EXPECT_EQ(ModelValidation::checkOsgtText("osg::Group {\tA 1\r\n}\n"), "");
    EXPECT_EQ(ModelValidation::checkOsgtText("osg::Group { } x"),
              "the text does not end with its last object's '}'");
    EXPECT_EQ(ModelValidation::checkOsgtText("nan"),
              "the text holds a number that is not finite ('nan' at byte 0)");
    EXPECT_EQ(ModelValidation::checkOsgtText(
                  loatest::fileBytes(std::string(LOA_SOURCE_DIR) + "/data/test-scenes/opencity-block.osgt")),
              "");
}

// Third-party chatter is collapsed (issue 22 item 3): OSG warns once per unknown object, and a
// model of 50 of them printed 50 identical lines; a tool shows a repeated line twice, then counts.
TEST(ModelValidationTest, RepeatedNoticesAreCounted)
{
    const std::string dir = loatest::freshDirectory("ModelValidationRepeats");
    std::string children;
    for (int i = 0; i < 50; ++i)
        children += "    osgFoo::Bar {\n      UniqueID " + std::to_string(i + 2) + "\n    }\n";
    std::ofstream(dir + "/unknown.osgt") << "#Ascii Scene\n#Version 161\n#Generator OpenSceneGraph 3.6.5\n\n"
                                            "osg::Group {\n  UniqueID 1\n  Children 50 {\n"
                                         << children << "  }\n}\n";
    std::string out;
    EXPECT_EQ(loatest::run("OSG_NOTIFY_LEVEL=WARN '" + std::string(LOA_CLASSIFY_EXE) + "' '" + dir +
                               "/unknown.osgt' --json",
                           out),
              0)
        << out;
    std::size_t lines = 0;
    for (std::size_t at = out.find("Unsupported wrapper class osgFoo::Bar"); at != std::string::npos;
         at = out.find("Unsupported wrapper class osgFoo::Bar", at + 1))
        ++lines;
    EXPECT_EQ(lines, 2u) << out;
    EXPECT_NE(out.find("(the line above 48 more times)"), std::string::npos) << out;
}

// The libraries' notices and info are shown only with --verbose (issue 22 item 3): without it
// they are counted, and a tool that fails says how many it hid; warnings always show.
TEST(ModelValidationTest, LibraryChatterOnlyWithVerbose)
{
    const std::string dir = loatest::freshDirectory("ModelValidationVerbose");
    std::ofstream(dir + "/short.osgt") << "#Ascii Scene\n#Version 161\n#Generator OpenSceneGraph 3.6.5\n\n"
                                          "osg::Group {\n  UniqueID 1\n  Children 3 {\n  }\n}\n";
    const std::string classify = "'" + std::string(LOA_CLASSIFY_EXE) + "' ";
    std::string quiet, verbose, failed;
    // OSG says at INFO level which plugins it opens: chatter.
    EXPECT_EQ(loatest::run("(" + classify + "demo.loacity --json >/dev/null)", quiet), 0) << quiet;
    EXPECT_EQ(quiet.find("DynamicLibrary"), std::string::npos) << quiet;
    EXPECT_EQ(loatest::run("(" + classify + "demo.loacity --json --verbose >/dev/null)", verbose), 0)
        << verbose;
    EXPECT_NE(verbose.find("DynamicLibrary"), std::string::npos) << verbose;
    // A failing read with OSG's level at INFO but no --verbose: the error line, and the count.
    EXPECT_EQ(loatest::run("OSG_NOTIFY_LEVEL=INFO " + classify + "'" + dir + "/short.osgt'", failed), 1)
        << failed;
    EXPECT_NE(failed.find("loa-classify: error: cannot read"), std::string::npos) << failed;
    EXPECT_NE(failed.find("notices from the libraries were hidden; --verbose shows them"), std::string::npos)
        << failed;
    EXPECT_EQ(failed.find("DynamicLibrary"), std::string::npos) << failed;
}

// A scene graph that is no tree (ModelFuzzer found a model whose group names an ancestor's
// UniqueID among its children: every visitor recursed until the stack overflowed): a cycle and
// a graph deeper than MAX_SCENE_DEPTH are refused naming the node; a shared subgraph (a DAG) and
// a deep but allowed chain pass. Such a file (tests/fuzz/crashes/model/) fails to load, exit 1.
TEST(ModelValidationTest, CyclesAndExcessiveDepthAreRefused)
{
    osg::ref_ptr<osg::Group> root = new osg::Group;
    osg::ref_ptr<osg::Group> a = new osg::Group;
    a->setName("block-a");
    root->addChild(a.get());
    osg::ref_ptr<osg::Group> shared = new osg::Group;
    a->addChild(shared.get());
    root->addChild(shared.get()); // shared: fine
    EXPECT_NO_THROW(ModelValidation::validate(*root, "dag.osgt"));
    shared->addChild(a.get()); // a -> shared -> a
    try
    {
        ModelValidation::validate(*root, "cycle.osgt");
        ADD_FAILURE() << "a cycle validated";
    }
    catch (const ModelStructureError& e)
    {
        EXPECT_NE(
            std::string(e.what()).find("cycle.osgt: the scene graph has a cycle: osg::Group 'block-a' is its "
                                       "own ancestor"),
            std::string::npos)
            << e.what();
    }
    shared->removeChild(a.get());
    const auto chain = [](unsigned levels)
    {
        osg::ref_ptr<osg::Group> top = new osg::Group;
        osg::Group* g = top.get();
        for (unsigned i = 1; i < levels; ++i)
        {
            osg::ref_ptr<osg::Group> c = new osg::Group;
            g->addChild(c.get());
            g = c.get();
        }
        return top;
    };
    EXPECT_NO_THROW(ModelValidation::validate(*chain(ModelValidation::MAX_SCENE_DEPTH), "deep.osgt"));
    EXPECT_THROW(ModelValidation::validate(*chain(ModelValidation::MAX_SCENE_DEPTH + 1), "deeper.osgt"),
                 ModelStructureError);
    std::string out;
    const std::string found =
        std::string(LOA_SOURCE_DIR) + "/tests/fuzz/crashes/model/cycle-group-names-its-ancestor.osgt";
    EXPECT_EQ(loatest::run("'" + std::string(LOA_CLASSIFY_EXE) + "' '" + found + "'", out), 1) << out;
    EXPECT_NE(out.find("the scene graph has a cycle: osg::Group 'block-a' is its own ancestor"),
              std::string::npos)
        << out;
}

// How OSG steps through an image's data: rows of the row length, aligned to the packing, times
// the depth. A 4x4x0 image with data and a packing of 4,521,985 stated 0 bytes and made
// getColor read megabytes past its data (ModelFuzzer, SEGV in Appearance); such images are emptied.
TEST(ModelValidationTest, ImagesWithImpossibleRowsAreEmptied)
{
    const auto imageWith = [](int r, unsigned packing, int rowLength)
    {
        osg::ref_ptr<osg::Image> image = new osg::Image;
        image->setImage(4, 4, r, GL_RGB8, GL_RGB, GL_UNSIGNED_BYTE, new unsigned char[64](),
                        osg::Image::USE_NEW_DELETE, packing, rowLength);
        return image;
    };
    struct Case
    {
        int r;
        unsigned packing;
        int rowLength;
        const char* why; // "" when the image is fine
    } cases[] = {{1, 4, 0, ""},
                 {1, 1, 4, ""},
                 {0, 4, 0, "states 4x4x0 with data"},
                 {1, 4521985, 0, "a row alignment (packing) of 4521985, not 1, 2, 4 or 8"},
                 {1, 3, 0, "a row alignment (packing) of 3"},
                 {1, 1, 2, "a row length of 2 pixels, shorter than its width 4"}};
    for (const Case& c : cases)
    {
        osg::ref_ptr<osg::Image> image = imageWith(c.r, c.packing, c.rowLength);
        osg::ref_ptr<osg::Geode> geode = new osg::Geode;
        geode->addDrawable(loatest::triangle("tri").get());
        geode->getOrCreateStateSet()->setTextureAttribute(0, new osg::Texture2D(image.get()));
        const ModelValidation v = ModelValidation::validate(*geode, "rows.osgt");
        if (!*c.why)
        {
            EXPECT_TRUE(v.emptiedImages.empty()) << c.packing;
            continue;
        }
        ASSERT_EQ(v.emptiedImages.size(), 1u) << c.why;
        EXPECT_NE(v.emptiedImages[0].find(c.why), std::string::npos) << v.emptiedImages[0];
        EXPECT_EQ(image->data(), nullptr);
    }
}

// Numbers that place a whole node: a stored initial bound at infinity (ModelFuzzer, 600 s
// campaign), a transform's matrix or position that is not finite. Each is reset with a warning
// naming the node, and the scene's bound is finite; a reproducer from the fuzzer reads likewise.
TEST(ModelValidationTest, NodesPlacedAtInfinityAreRepaired)
{
    const float inf = std::numeric_limits<float>::infinity();
    const auto triangleGeode = []
    {
        osg::ref_ptr<osg::Geode> g = new osg::Geode;
        g->addDrawable(loatest::triangle("tri").get());
        return g;
    };
    osg::ref_ptr<osg::Group> root = new osg::Group;
    osg::ref_ptr<osg::Group> far = new osg::Group;
    far->setName("far");
    far->setInitialBound(osg::BoundingSphere(osg::Vec3(inf, 0, inf), 0));
    root->addChild(far.get());
    osg::ref_ptr<osg::MatrixTransform> mt =
        new osg::MatrixTransform(osg::Matrix::translate(std::nan(""), 0, 0));
    mt->addChild(triangleGeode().get());
    root->addChild(mt.get());
    osg::ref_ptr<osg::PositionAttitudeTransform> pat = new osg::PositionAttitudeTransform;
    pat->setPosition(osg::Vec3d(0, 1e300, 0));
    pat->addChild(triangleGeode().get());
    root->addChild(pat.get());
    osg::ref_ptr<osg::Geode> box = triangleGeode();
    box->getDrawable(0)->setInitialBound(osg::BoundingBox(0, 0, 0, inf, 1, 1));
    root->addChild(box.get());
    ASSERT_FALSE(std::isfinite(root->getBound().radius()) &&
                 std::isfinite(root->getBound().center().length()));

    const ModelValidation v = ModelValidation::validate(*root, "placed.osgt");
    ASSERT_EQ(v.repairedValues.size(), 4u);
    EXPECT_NE(v.repairedValues[0].find("Group 'far': an initial bound that is not finite"), std::string::npos)
        << v.repairedValues[0];
    EXPECT_TRUE(mt->getMatrix().isIdentity());
    EXPECT_EQ(pat->getPosition(), osg::Vec3d());
    EXPECT_FALSE(box->getDrawable(0)->getInitialBound().valid());
    const osg::BoundingSphere bs = root->getBound();
    EXPECT_TRUE(std::isfinite(bs.radius()) && std::isfinite(bs.center().length()));
    EXPECT_NEAR(bs.radius(), root->getChild(1)->getBound().radius(), 1.0); // the triangles, ~1 m

    const std::string bytes = loatest::fileBytes(
        std::string(LOA_SOURCE_DIR) +
        "/tests/fuzz/crashes/model/infinite-bound-fuzzer-found-initial-bound-at-infinity.osgb");
    osg::ref_ptr<osg::Node> fuzzed = osgLoA::BoundedObjectReader::readNode(bytes, nullptr);
    ASSERT_TRUE(fuzzed.valid());
    EXPECT_EQ(ModelValidation::validate(*fuzzed, "fuzzed.osgb").repairedValues.size(), 1u);
    EXPECT_FALSE(fuzzed->getBound().valid()); // an empty group: no bound at all, and a finite one
}

// A texture's wrap or filter mode that is no GL mode: OSG stores any number a file holds in the
// enum, and loading it is undefined behaviour (UBSan; ModelFuzzer found WRAP_S 16764417). The
// modes are repaired to OSG's defaults with a warning naming the texture.
TEST(ModelValidationTest, TextureModesThatAreNoModesAreRepaired)
{
    struct Poke : osg::Texture2D
    {
        static void raw(osg::Texture2D& t, int wrapS, int magFilter)
        {
            std::memcpy(&(t.*(&Poke::_wrap_s)), &wrapS, sizeof wrapS);
            std::memcpy(&(t.*(&Poke::_mag_filter)), &magFilter, sizeof magFilter);
        }
    };
    osg::ref_ptr<osg::Geode> g = new osg::Geode;
    osg::ref_ptr<osg::Geometry> tri = triangle("t");
    osg::ref_ptr<osg::Texture2D> texture = new osg::Texture2D;
    texture->setName("bricks");
    texture->setWrap(osg::Texture::WRAP_T, osg::Texture::REPEAT);
    Poke::raw(*texture, 16764417, 7);
    tri->getOrCreateStateSet()->setTextureAttributeAndModes(0, texture.get());
    g->addDrawable(tri.get());
    struct Capture : osg::NotifyHandler
    {
        std::string text;
        void notify(osg::NotifySeverity, const char* message) override { text += message; }
    };
    osg::ref_ptr<Capture> capture = new Capture;
    osg::ref_ptr<osg::NotifyHandler> previous = osg::getNotifyHandler();
    osg::setNotifyHandler(capture.get());
    ModelValidation::validate(*g, "modes.osgb");
    osg::setNotifyHandler(previous.get());
    std::ostringstream warnings;
    warnings << capture->text;
    EXPECT_NE(warnings.str().find("texture 'bricks' WRAP_S 16764417 is no wrap mode; CLAMP used"),
              std::string::npos)
        << warnings.str();
    EXPECT_NE(warnings.str().find("texture 'bricks' MAG_FILTER 7 is no filter mode; LINEAR used"),
              std::string::npos)
        << warnings.str();
    EXPECT_EQ(texture->getWrap(osg::Texture::WRAP_S), osg::Texture::CLAMP);
    EXPECT_EQ(texture->getWrap(osg::Texture::WRAP_T), osg::Texture::REPEAT); // valid: kept
    EXPECT_EQ(texture->getFilter(osg::Texture::MAG_FILTER), osg::Texture::LINEAR);
}
