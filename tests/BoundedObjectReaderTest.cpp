// BoundedObjectReader against what ModelFuzzer found in OSG's own readers (issue 22 items 3, 5):
// nesting deep enough to overflow the stack, a UniqueID of a geometry where an image belongs
// (OSG casts it), array counts with nothing behind them, an inline image's AllocationMode, and
// the strict text reading that closes OSG's "any word is a number" gaps; and, on a real model,
// that the bounded reader reads what OSG's reader reads.
#include "support/TestSupport.h"

#include <osgLoA/util/BoundedObjectReader>
#include <osgLoA/util/ModelValidation>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Texture2D>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <regex>
#include <string>
#include <thread>
#include <vector>

using osgLoA::BoundedObjectReader;
using osgLoA::MalformedFileError;

namespace
{
const char* const kHeader = "#Ascii Scene\n#Version 161\n#Generator OpenSceneGraph 3.6.5\n\n";

/** A text scene of `levels` groups, each the only child of the one before. */
std::string chainText(int levels)
{
    std::string t = kHeader;
    for (int i = 0; i < levels - 1; ++i)
        t += "osg::Group {\n UniqueID " + std::to_string(i + 1) + "\n Children 1 {\n";
    t += "osg::Group {\n UniqueID " + std::to_string(levels) + "\n}\n";
    for (int i = 0; i < levels - 1; ++i)
        t += "}\n}\n";
    return t;
}

/** The message of the MalformedFileError reading `data` throws, or "" (and a failure). */
std::string errorOf(const std::string& data, double* seconds = nullptr)
{
    const auto t0 = std::chrono::steady_clock::now();
    std::string what;
    try
    {
        BoundedObjectReader::readNode(data, nullptr);
        ADD_FAILURE() << "read without an error";
    }
    catch (const MalformedFileError& e)
    {
        what = e.what();
    }
    if (seconds) *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return what;
}

struct Counts
{
    unsigned geodes = 0, drawables = 0, vertices = 0, textures = 0;
};

Counts countsOf(osg::Node& node)
{
    struct Counter : osg::NodeVisitor
    {
        Counts c;
        Counter() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
        void apply(osg::Geode& geode) override
        {
            ++c.geodes;
            for (unsigned i = 0; i < geode.getNumDrawables(); ++i)
            {
                ++c.drawables;
                if (const osg::Geometry* g = geode.getDrawable(i)->asGeometry())
                    if (g->getVertexArray()) c.vertices += g->getVertexArray()->getNumElements();
                if (const osg::StateSet* s = geode.getDrawable(i)->getStateSet())
                    c.textures += s->getTextureAttributeList().size();
            }
            traverse(geode);
        }
    } counter;
    node.accept(counter);
    return counter.c;
}
} // namespace

// OSG reads nested objects by recursion: a text of 20,000 nested groups overflowed an 8 MB stack
// in osgconv and in our tools. The reader runs OSG on a thread with a 256 MB stack and refuses
// nesting past MAX_NESTING ('{' within '{', two per scene level) before it gets there; the
// deepest scene ModelValidation accepts (MAX_SCENE_DEPTH, 4,096 levels) still reads.
TEST(BoundedObjectReaderTest, NestingPastTheLimitIsRefusedAndTheDeepestSceneReads)
{
    double seconds = 0;
    const std::string deep = errorOf(chainText(20000), &seconds);
    EXPECT_NE(deep.find("objects nested deeper than 8448 levels"), std::string::npos) << deep;
    EXPECT_LT(seconds, 2.0);

    osg::ref_ptr<osg::Node> chain =
        BoundedObjectReader::readNode(chainText(int(osgLoA::ModelValidation::MAX_SCENE_DEPTH)), nullptr);
    ASSERT_TRUE(chain.valid());
    EXPECT_NO_THROW(osgLoA::ModelValidation::validate(*chain, "chain.osgt"));

    // The same limit in binary: OSG writes a 5,000-level chain, the reader refuses it.
    osg::ref_ptr<osg::Group> root = new osg::Group;
    osg::Group* at = root.get();
    for (int i = 0; i < 5000; ++i)
    {
        osg::ref_ptr<osg::Group> next = new osg::Group;
        at->addChild(next.get());
        at = next.get();
    }
    const std::string dir = loatest::freshDirectory("BoundedObjectReaderTest/nesting");
    ASSERT_TRUE(osgDB::writeNodeFile(*root, dir + "/chain.osgb"));
    const std::string binary = errorOf(loatest::fileBytes(dir + "/chain.osgb"), &seconds);
    EXPECT_NE(binary.find("objects nested deeper than 8448 levels"), std::string::npos) << binary;
    EXPECT_LT(seconds, 2.0);
}

// Each calling thread has one reading thread of its own, made on its first read and kept: reads
// from several threads at once, and deep reads one after another on one thread, all succeed (the
// fork() of a process that has one is ScenarioSerializationTest's readInChild).
TEST(BoundedObjectReaderTest, ReadsFromSeveralThreadsAndOneAfterAnother)
{
    const std::string text = chainText(200);
    std::atomic<int> read{0};
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back(
            [&]
            {
                for (int i = 0; i < 5; ++i)
                    if (BoundedObjectReader::readNode(text, nullptr).valid()) ++read;
            });
    for (std::thread& t : threads)
        t.join();
    EXPECT_EQ(read.load(), 20);
    const std::string deepest = chainText(int(osgLoA::ModelValidation::MAX_SCENE_DEPTH));
    for (int i = 0; i < 3; ++i)
        EXPECT_TRUE(BoundedObjectReader::readNode(deepest, nullptr).valid()) << "read " << i;
}

// OSG's InputStream::readImage returns the object a UniqueID names, cast to osg::Image without a
// check: a text naming its geometry's ID where its image belongs made OSG call image methods on
// the geometry (UBSan; ModelFuzzer found it). Refused, naming the ID and the class.
TEST(BoundedObjectReaderTest, AnObjectsIdWhereAnImageBelongsIsRefused)
{
    const std::string text = loatest::writeTexturedTriangle(
        loatest::freshDirectory("BoundedObjectReaderTest/ids") + "/textured.osgt");
    std::smatch geometry, image;
    ASSERT_TRUE(std::regex_search(text, geometry, std::regex("osg::Geometry \\{\\s+UniqueID (\\d+)")));
    ASSERT_TRUE(std::regex_search(text, image, std::regex("ClassName osg::Image\\s+UniqueID (\\d+)")));
    ASSERT_NO_THROW(BoundedObjectReader::readNode(text, nullptr)); // as written, it reads
    const std::string bad =
        loatest::replaced(text, image[0].str(), "ClassName osg::Image\n UniqueID " + geometry[1].str());
    const std::string what = errorOf(bad);
    EXPECT_NE(what.find("UniqueID " + geometry[1].str() +
                        " names the osg::Geometry read before, where an "
                        "image belongs"),
              std::string::npos)
        << what;
    // The fuzzer's own input (mutated elsewhere too: read strictly, it fails at its first
    // mutation, a byte in a property name, before it gets to the ID).
    const std::string found = errorOf(
        loatest::fileBytes(std::string(LOA_SOURCE_DIR) +
                           "/tests/fuzz/crashes/model/memory-fuzzer-found-geometry-id-as-image.osgt"));
    EXPECT_NE(found.find("where '"), std::string::npos) << found;
}

// A count with nothing behind it: OSG reserves room for it before it reads an entry (11.7 GB for
// a 1.4 kB binary without block sizes, found by ModelFuzzer). Refused at once, in binary and in
// text.
TEST(BoundedObjectReaderTest, CountsBeyondTheDataAreRefusedAtOnce)
{
    double seconds = 0;
    const std::string binary = errorOf(
        loatest::fileBytes(std::string(LOA_SOURCE_DIR) +
                           "/tests/fuzz/crashes/model/oom-fuzzer-found-array-count-without-blocks.osgb"),
        &seconds);
    EXPECT_NE(binary.find("entries of 4 bytes stated for 'vector'"), std::string::npos) << binary;
    EXPECT_LT(seconds, 1.0);

    // An image without data whose mipmap level count OSG made a vector of (13 GB, 21 s).
    const std::string levels =
        errorOf(loatest::fileBytes(
                    std::string(LOA_SOURCE_DIR) +
                    "/tests/fuzz/crashes/model/oom-fuzzer-found-level-count-of-image-without-data.osgb"),
                &seconds);
    EXPECT_NE(levels.find("3369876500 mipmap levels stated for an image without data"), std::string::npos)
        << levels;
    EXPECT_LT(seconds, 1.0);

    // An image's data size, allocated by OSG before it reads a byte (4 GB: seconds under ASan).
    const std::string image =
        errorOf(loatest::fileBytes(std::string(LOA_SOURCE_DIR) +
                                   "/tests/fuzz/crashes/model/slow-fuzzer-found-image-of-4-gb-stated.osgb"),
                &seconds);
    EXPECT_NE(image.find("an image of 4294967295 bytes stated"), std::string::npos) << image;
    EXPECT_LT(seconds, 1.0);

    const std::string text = loatest::writeTexturedTriangle(
        loatest::freshDirectory("BoundedObjectReaderTest/counts") + "/textured.osgt");
    const std::string vector = errorOf(loatest::replaced(text, "vector 3 {", "vector 300000000 {"), &seconds);
    EXPECT_NE(vector.find("300000000 entries of 1 bytes stated for 'vector'"), std::string::npos) << vector;
    EXPECT_LT(seconds, 1.0);
}

// OSG's text reader takes any word for any value ("four" reads as 0, a misspelt property name
// passes with a warning), so a mutated file read as another structure; ours names the word.
TEST(BoundedObjectReaderTest, TextIsReadStrictly)
{
    const std::string text = loatest::writeTexturedTriangle(
        loatest::freshDirectory("BoundedObjectReaderTest/strict") + "/textured.osgt");
    std::string what = errorOf(loatest::replaced(text, "UniqueID", "UniqueIX"));
    EXPECT_NE(what.find("'UniqueIX' where 'UniqueID' belongs"), std::string::npos) << what;
    what = errorOf(loatest::replaced(text, "Size 4 4 1", "Size 4 four 1"));
    EXPECT_NE(what.find("'four' where an integer belongs"), std::string::npos) << what;
}

// OSG decodes an inline text image into new[] memory and hands it over with the file's
// AllocationMode: 2 (malloc/free) made it free new[] memory with free() (ASan:
// alloc-dealloc-mismatch; ModelFuzzer found it), 0 would leak it. The reader reads it as 1.
TEST(BoundedObjectReaderTest, InlineImagesAreOwnedAsOSGAllocatedThem)
{
    const std::string text = loatest::writeTexturedTriangle(
        loatest::freshDirectory("BoundedObjectReaderTest/allocation") + "/textured.osgt");
    ASSERT_NE(text.find("AllocationMode 1"), std::string::npos);
    for (const char* mode : {"0", "2"})
    {
        SCOPED_TRACE(mode);
        osg::ref_ptr<osg::Node> node = BoundedObjectReader::readNode(
            loatest::replaced(text, "AllocationMode 1", std::string("AllocationMode ") + mode), nullptr);
        ASSERT_TRUE(node.valid());
        const osg::Geometry* g = node->asGeode()->getDrawable(0)->asGeometry();
        const auto* texture = dynamic_cast<const osg::Texture2D*>(
            g->getStateSet()->getTextureAttribute(0, osg::StateAttribute::TEXTURE));
        ASSERT_TRUE(texture && texture->getImage());
        EXPECT_EQ(texture->getImage()->getAllocationMode(), osg::Image::USE_NEW_DELETE);
    }
}

// A real model nobody on the project made (TORCS street-1 from Debian's torcs-data, 1,436
// geometries; docs/test-scenes.md), written by OSG as .osgt and .osgb: the bounded reader reads
// what OSG's own reader reads from the same files.
TEST(BoundedObjectReaderTest, ARealModelReadsAsOSGReadsIt)
{
    const std::string source = std::string(LOA_SOURCE_DIR) + "/data/cache/torcs-data/street-1/street-1.ac";
    if (!osgDB::fileExists(source)) GTEST_SKIP() << source << " is absent: run scripts/fetch-test-data";
    osg::ref_ptr<osg::Node> scene = osgDB::readNodeFile(source);
    ASSERT_TRUE(scene.valid());
    const std::string dir = loatest::freshDirectory("BoundedObjectReaderTest/real");
    for (const char* extension : {"osgt", "osgb"})
    {
        SCOPED_TRACE(extension);
        const std::string path = dir + "/street-1." + extension;
        ASSERT_TRUE(osgDB::writeNodeFile(*scene, path));
        osg::ref_ptr<osg::Node> stock = osgDB::readNodeFile(path);
        ASSERT_TRUE(stock.valid());
        osg::ref_ptr<osg::Node> ours = BoundedObjectReader::readNodeFile(path, nullptr);
        ASSERT_TRUE(ours.valid());
        const Counts a = countsOf(*stock), b = countsOf(*ours);
        EXPECT_EQ(a.drawables, 1436u); // docs/test-scenes.md
        EXPECT_EQ(a.geodes, b.geodes);
        EXPECT_EQ(a.drawables, b.drawables);
        EXPECT_EQ(a.vertices, b.vertices);
        EXPECT_EQ(a.textures, b.textures);
    }
}
