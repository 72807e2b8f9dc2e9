// ScenarioLibrary's guard against text that OSG 3.6.5's ASCII reader loops on forever
// (AsciiInputIterator::readWrappedString at the end of the stream), with the reproducers the
// fuzzer found (tests/fuzz/crashes/hang-*).
#include "support/TestSupport.h"

#include <osgLoA/transitions/ScenarioLibrary>

#include <osgDB/FileUtils>

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <sstream>

using namespace osgLoA;

namespace
{
std::string textOf(const std::string& path)
{
    std::ifstream in(path.c_str(), std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}
} // namespace

TEST(ScenarioLibraryTest, AsciiStructureCheck)
{
    EXPECT_EQ(ScenarioLibrary::checkAsciiStructure("#Ascii Scene\nA {\n  Name \"x\"\n}\n"), "");
    // An escaped quote and a brace inside a string do not count.
    EXPECT_EQ(ScenarioLibrary::checkAsciiStructure("#Ascii Scene\nA { Name \"a \\\" { b\" }"), "");
    EXPECT_EQ(ScenarioLibrary::checkAsciiStructure("#Ascii Scene\nA { Name \"abc"),
              "the text ends inside a quoted string");
    EXPECT_EQ(ScenarioLibrary::checkAsciiStructure("#Ascii Scene\nA { Style "),
              "the text ends inside an object ('{' and '}' do not match)");
    EXPECT_EQ(ScenarioLibrary::checkAsciiStructure("#Ascii Scene\nA { } Style"),
              "the text does not end with its last object's '}'");
    EXPECT_EQ(ScenarioLibrary::checkAsciiStructure("#Ascii Scene\n} A {"), "a '}' closes no object");
    EXPECT_EQ(ScenarioLibrary::checkAsciiStructure("#Ascii Scene\n"), "the text holds no object");
}

TEST(ScenarioLibraryTest, EveryLibraryFilePassesTheCheck)
{
    for (const std::string& name : ScenarioLibrary::builtinNames())
    {
        const std::string path = std::string(LOA_SOURCE_DIR) + "/data/scenarios/" + name + ".osgt";
        EXPECT_EQ(ScenarioLibrary::checkAsciiStructure(textOf(path)), "") << path;
        EXPECT_EQ(ScenarioLibrary::readFile(path)->getName(), name);
    }
}

// Each of these made osgconv and our readers loop forever before the check.
TEST(ScenarioLibraryTest, TruncatedFilesFailFastWithTheReason)
{
    const std::string dir = std::string(LOA_SOURCE_DIR) + "/tests/fuzz/crashes/";
    const std::pair<const char*, const char*> cases[] = {
        {"hang-eof-inside-quoted-string.osgt", "ends inside a quoted string"},
        {"hang-eof-after-property-name.osgt", "ends inside an object"},
        {"hang-fuzzer-found-unterminated-name.osgt", "ends inside a quoted string"}};
    for (const auto& c : cases)
    {
        const auto t0 = std::chrono::steady_clock::now();
        try
        {
            ScenarioLibrary::readFile(dir + c.first);
            ADD_FAILURE() << c.first << " was read";
        }
        catch (const ScenarioError& e)
        {
            EXPECT_NE(std::string(e.what()).find(c.second), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(c.first), std::string::npos) << e.what();
        }
        EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 1.0);
    }
    // Every prefix of a library file that cuts it short is rejected (none reaches OSG's loop).
    const std::string full = textOf(std::string(LOA_SOURCE_DIR) + "/data/scenarios/route.osgt");
    const std::size_t lastBrace = full.find_last_of('}');
    for (std::size_t n = 0; n < lastBrace; n += 7)
        EXPECT_THROW(ScenarioLibrary::readData(full.substr(0, n), "prefix"), ScenarioError) << n;
}

// Text that is structurally complete but makes OSG's reader loop once a value fails to parse
// (the stream stays failed): the parse runs in a child process and gives up after 5 s.
TEST(ScenarioLibraryTest, AReaderThatLoopsIsStoppedWithAMessage)
{
    const std::string path =
        std::string(LOA_SOURCE_DIR) + "/tests/fuzz/crashes/hang-fuzzer-found-failed-stream.osgt";
    ASSERT_EQ(ScenarioLibrary::checkAsciiStructure(textOf(path)), "")
        << "the guard's first check must pass it";
    const auto t0 = std::chrono::steady_clock::now();
    try
    {
        ScenarioLibrary::readFile(path);
        ADD_FAILURE() << "read";
    }
    catch (const ScenarioError& e)
    {
        EXPECT_NE(std::string(e.what()).find("did not finish within 5 s"), std::string::npos) << e.what();
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_GT(seconds, 4.5);
    EXPECT_LT(seconds, 8.0);
    // A file the reader rejects quickly reports the reader's own message through the child.
    const std::string dir = loatest::freshDirectory("ScenarioLibraryTest");
    std::string text = textOf(std::string(LOA_SOURCE_DIR) + "/data/scenarios/route.osgt");
    text.replace(text.find("Kind REGION"), 11, "Kind LOUDNESS");
    std::ofstream(dir + "/bad-kind.osgt") << text;
    try
    {
        ScenarioLibrary::readFile(dir + "/bad-kind.osgt");
        ADD_FAILURE() << "read";
    }
    catch (const ScenarioError& e)
    {
        EXPECT_NE(std::string(e.what()).find("LOUDNESS"), std::string::npos) << e.what();
    }
}
