// ScenarioLibrary's guard against text that OSG 3.6.5's ASCII reader loops on forever
// (AsciiInputIterator::readWrappedString at the end of the stream), with the reproducers the
// fuzzer found (tests/fuzz/crashes/scenario/hang-*), and the helper program loa-scenario-parse that
// parses text files out of process.
#include "support/TestSupport.h"

#include <osgLoA/transitions/ScenarioLibrary>

#include <osgDB/FileUtils>
#include <osgDB/ObjectWrapper>
#include <osgDB/Registry>

#include <sys/stat.h>

#include <OpenThreads/ScopedLock>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <mutex>
#include <sstream>
#include <thread>
#include <vector>

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

double secondsSince(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/** Sets an environment variable for a scope, then restores it. */
class ScopedEnvironment
{
public:
    ScopedEnvironment(const char* name, const std::string& value) : _name(name)
    {
        if (const char* old = std::getenv(name)) _old = old, _had = true;
        setenv(name, value.c_str(), 1);
    }
    ~ScopedEnvironment()
    {
        if (_had)
            setenv(_name, _old.c_str(), 1);
        else
            unsetenv(_name);
    }
    ScopedEnvironment(const ScopedEnvironment&) = delete;
    ScopedEnvironment& operator=(const ScopedEnvironment&) = delete;

private:
    const char* _name;
    std::string _old;
    bool _had = false;
};

/** osgDB's ObjectWrapperManager::_wrapperMutex (protected; reached through a member pointer). */
OpenThreads::ReentrantMutex& wrapperMutex()
{
    struct Access : osgDB::ObjectWrapperManager
    {
        static OpenThreads::ReentrantMutex osgDB::ObjectWrapperManager::*member()
        {
            return &Access::_wrapperMutex;
        }
    };
    return osgDB::Registry::instance()->getObjectWrapperManager()->*Access::member();
}

/** Threads that each run a step over and over until the object goes. */
class BusyThreads
{
public:
    BusyThreads() = default;
    BusyThreads(const BusyThreads&) = delete;
    BusyThreads& operator=(const BusyThreads&) = delete;
    ~BusyThreads()
    {
        _stop = true;
        for (std::thread& t : _threads)
            t.join();
    }
    void start(std::function<void()> step)
    {
        _threads.emplace_back(
            [this, step]
            {
                while (!_stop)
                {
                    step();
                    std::this_thread::sleep_for(std::chrono::microseconds(100));
                }
            });
    }

private:
    std::atomic<bool> _stop{false};
    std::vector<std::thread> _threads;
};
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
    const std::string dir = std::string(LOA_SOURCE_DIR) + "/tests/fuzz/crashes/scenario/";
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

// Text that is structurally complete but made OSG's reader loop once a value failed to parse
// (the stream stayed failed; it used to run in a child process given 5 s): read in process by
// BoundedObjectReader's strict text iterator, it ends at the first word out of place, at once.
// So do the other reproducers whose structure is complete.
TEST(ScenarioLibraryTest, AReaderThatWouldLoopEndsWithTheData)
{
    const std::string path =
        std::string(LOA_SOURCE_DIR) + "/tests/fuzz/crashes/scenario/hang-fuzzer-found-failed-stream.osgt";
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
        // Read strictly, the mutated property name is the error (OSG's reader took any word).
        EXPECT_NE(std::string(e.what()).find("where 'UniqueID' belongs"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
    EXPECT_LT(secondsSince(t0), 1.0);
    // 4,000,000,000 list entries promised, 8 there: OSG's list reader pushed null entries for
    // minutes, then ran out of memory.
    const std::string huge =
        std::string(LOA_SOURCE_DIR) + "/tests/fuzz/crashes/scenario/oom-huge-list-count.osgt";
    const auto t1 = std::chrono::steady_clock::now();
    EXPECT_THROW(ScenarioLibrary::readFile(huge), ScenarioError);
    EXPECT_LT(secondsSince(t1), 1.0);
    // The same list count in the binary format (a bit-flipped .osgb: it reached 3.9 GB).
    const std::string dir = loatest::freshDirectory("ScenarioLibraryTest-bounded");
    ScenarioLibrary::writeFile(*ScenarioLibrary::createBuiltin("route"), dir + "/route.osgb");
    std::string binary = loatest::fileBytes(dir + "/route.osgb");
    const std::uint32_t count =
        static_cast<std::uint32_t>(ScenarioLibrary::createBuiltin("route")->getConfigurations().size());
    // Every 32-bit word that holds the number of configurations (the list's count among them)
    // made to say 4,000,000,000: each variant reads or fails, in under a second.
    unsigned variants = 0, failed = 0;
    const auto t2 = std::chrono::steady_clock::now();
    for (std::size_t k = 0; k + 4 <= binary.size(); ++k)
    {
        if (std::memcmp(binary.data() + k, &count, 4) != 0) continue;
        std::string lie = binary;
        const std::uint32_t huge32 = 4000000000u;
        std::memcpy(&lie[k], &huge32, 4);
        ++variants;
        try
        {
            ScenarioLibrary::readData(lie, "huge.osgb");
        }
        catch (const ScenarioError&)
        {
            ++failed;
        }
    }
    EXPECT_GT(variants, 0u);
    EXPECT_GT(failed, 0u) << "no variant was refused: the list count was not among them";
    EXPECT_LT(secondsSince(t2), 1.0 * variants);
}

// XML scenario files still go through the helper loa-scenario-parse, with a deadline: a helper
// that does not answer (a stand-in that sleeps) is given up after 5 s with a message.
TEST(ScenarioLibraryTest, AHelperThatHangsIsStoppedWithAMessage)
{
    const std::string dir = loatest::freshDirectory("ScenarioLibraryTest-deadline");
    ScenarioLibrary::writeFile(*ScenarioLibrary::createBuiltin("route"), dir + "/route.osgx");
    std::ofstream(dir + "/sleeper") << "#!/bin/sh\nexec sleep 60\n";
    ASSERT_EQ(::chmod((dir + "/sleeper").c_str(), 0755), 0);
    ScopedEnvironment env("OSGLOA_SCENARIO_PARSER", dir + "/sleeper");
    const auto t0 = std::chrono::steady_clock::now();
    try
    {
        ScenarioLibrary::readFile(dir + "/route.osgx");
        ADD_FAILURE() << "read";
    }
    catch (const ScenarioError& e)
    {
        EXPECT_NE(std::string(e.what()).find("did not finish within 5 s"), std::string::npos) << e.what();
    }
    const double seconds = secondsSince(t0);
    EXPECT_GT(seconds, 4.5);
    EXPECT_LT(seconds, 8.0);
}

TEST(ScenarioLibraryTest, TheReadersOwnMessageComesThrough)
{
    // A file the reader rejects reports the reader's own message.
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

// The original problem: the text parse used to run in a fork() of this process, and a fork of a
// multi-threaded process (Mesa's llvmpipe threads, OSG's pager threads) can deadlock on a lock
// another thread holds at that moment: the child is left with the lock and no thread to release
// it. Here one thread holds osgDB's wrapper lock, which every read of an osgLoA object takes
// (ObjectWrapperManager::findWrapper), nearly all the time (a forked child hung on it), and
// others keep taking the registry's plugin lock, the heap and a mutex of their own; every read
// returns, valid files with their scenario and a malformed one with a ScenarioError, in time.
TEST(ScenarioLibraryTest, TextFilesAreReadWhileOtherThreadsHoldLocks)
{
    const std::string route = std::string(LOA_SOURCE_DIR) + "/data/scenarios/route.osgt";
    const std::size_t configurations = ScenarioLibrary::createBuiltin("route")->getConfigurations().size();
    const std::string dir = loatest::freshDirectory("ScenarioLibraryTest-threads");
    std::string bad = textOf(route);
    bad.replace(bad.find("Kind REGION"), 11, "Kind LOUDNESS");
    std::ofstream(dir + "/bad-kind.osgt") << bad;
    ScenarioLibrary::writeFile(*ScenarioLibrary::createBuiltin("route"), dir + "/route.osgx");

    std::mutex held; // outlives the threads
    BusyThreads busy;
    busy.start(
        [] // osgDB's wrapper lock, held 2 ms at a time
        {
            OpenThreads::ScopedLock<OpenThreads::ReentrantMutex> lock(wrapperMutex());
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
        });
    for (const char* ext : {"osgt", "osgb"})
        busy.start(
            [&held, ext]
            {
                std::lock_guard<std::mutex> lock(held);
                osgDB::Registry::instance()->getReaderWriterForExtension(ext);
                const std::vector<std::string> garbage(64, std::string(200, 'x'));
                std::this_thread::sleep_for(std::chrono::microseconds(200));
            });
    for (int round = 0; round < 3; ++round)
    {
        for (const std::string& path : {route, dir + "/route.osgx"})
        {
            const auto t0 = std::chrono::steady_clock::now();
            osg::ref_ptr<UsageScenario> s;
            EXPECT_NO_THROW(s = ScenarioLibrary::readFile(path)) << path;
            EXPECT_TRUE(s.valid()) << path;
            if (s.valid())
            {
                EXPECT_EQ(s->getName(), "route") << path;
                EXPECT_EQ(s->getConfigurations().size(), configurations) << path;
            }
            EXPECT_LT(secondsSince(t0), 5.0) << path;
        }
        const auto t0 = std::chrono::steady_clock::now();
        try
        {
            ScenarioLibrary::readFile(dir + "/bad-kind.osgt");
            ADD_FAILURE() << "read";
        }
        catch (const ScenarioError& e)
        {
            EXPECT_NE(std::string(e.what()).find(dir + "/bad-kind.osgt"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("LOUDNESS"), std::string::npos) << e.what();
        }
        EXPECT_LT(secondsSince(t0), 5.0);
    }
}

// The text goes to the helper while its reply comes back: a file far larger than a pipe's or a
// socket's buffer (a 4 MB description) gets through whole, in both directions.
TEST(ScenarioLibraryTest, LargeTextFilesGoThroughWhole)
{
    std::string text = textOf(std::string(LOA_SOURCE_DIR) + "/data/scenarios/route.osgt");
    const std::string padding(std::size_t(4) << 20, 'x');
    text.replace(text.find("Description \"") + 13, 0, padding);
    const auto t0 = std::chrono::steady_clock::now();
    osg::ref_ptr<UsageScenario> s = ScenarioLibrary::readData(text, "large.osgt");
    EXPECT_LT(secondsSince(t0), 5.0);
    ASSERT_TRUE(s.valid());
    EXPECT_EQ(s->getDescription().compare(0, padding.size(), padding), 0);
    EXPECT_GT(s->getDescription().size(), padding.size());
}

// The helper (for XML files) is found through OSGLOA_SCENARIO_PARSER first; a wrong path there
// is a clear error (no quiet search elsewhere), and binary and ASCII files, which need no
// helper, still read.
TEST(ScenarioLibraryTest, AMissingHelperIsAClearError)
{
    const std::string dir = loatest::freshDirectory("ScenarioLibraryTest-helper");
    const std::string route = dir + "/route.osgx";
    ScenarioLibrary::writeFile(*ScenarioLibrary::createBuiltin("route"), route);
    ScenarioLibrary::writeFile(*ScenarioLibrary::createBuiltin("route"), dir + "/route.osgb");
    {
        ScopedEnvironment env("OSGLOA_SCENARIO_PARSER", dir + "/no-such-helper");
        try
        {
            ScenarioLibrary::readFile(route);
            ADD_FAILURE() << "read without a helper";
        }
        catch (const ScenarioError& e)
        {
            const std::string what = e.what();
            EXPECT_NE(what.find("'" + route + "'"), std::string::npos) << what;
            EXPECT_NE(what.find("loa-scenario-parse not found"), std::string::npos) << what;
            EXPECT_NE(what.find(dir + "/no-such-helper"), std::string::npos) << what;
            EXPECT_NE(what.find("OSGLOA_SCENARIO_PARSER"), std::string::npos) << what;
        }
        EXPECT_EQ(ScenarioLibrary::readFile(dir + "/route.osgb")->getName(), "route");
        EXPECT_EQ(
            ScenarioLibrary::readFile(std::string(LOA_SOURCE_DIR) + "/data/scenarios/route.osgt")->getName(),
            "route");
    }
    {
        ScopedEnvironment env("OSGLOA_SCENARIO_PARSER",
                              std::string(LOA_BINARY_DIR) + "/bin/loa-scenario-parse");
        EXPECT_EQ(ScenarioLibrary::readFile(route)->getName(), "route");
    }
    EXPECT_EQ(ScenarioLibrary::readFile(route)->getName(), "route"); // found next to libosgLoA
}

// The helper as a program: a file argument or stdin, one reply on stdout, exit status 0.
TEST(ScenarioLibraryTest, TheHelperRepliesWithTheScenarioOrTheError)
{
    const std::string helper = std::string(LOA_BINARY_DIR) + "/bin/loa-scenario-parse";
    const std::string route = std::string(LOA_SOURCE_DIR) + "/data/scenarios/route.osgt";
    std::string out;
    ASSERT_EQ(loatest::run("('" + helper + "' '" + route + "' 2>/dev/null)", out), 0) << out;
    ASSERT_FALSE(out.empty());
    EXPECT_EQ(out[0], 'S');
    const std::string bad =
        std::string(LOA_SOURCE_DIR) + "/tests/fuzz/crashes/scenario/ub-metric-kind-9-invalid-enum.osgt";
    ASSERT_EQ(loatest::run("('" + helper + "' --label my-label < '" + bad + "' 2>/dev/null)", out), 0) << out;
    EXPECT_EQ(out.compare(0, 36, "Ecannot read scenario file 'my-label"), 0) << out;
    EXPECT_NE(out.find("unknown Kind '9'"), std::string::npos) << out;
}
