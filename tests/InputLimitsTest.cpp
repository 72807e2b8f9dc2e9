// Limits on hostile input (issue 22 item 1): the option syntax, PolygonCrossings against hand
// counts, and the CityJSON reproducers of the issue (nesting 10^5 deep in boundaries and in an
// attribute, a 20,000-object parent chain, star polygons, an over-long string, a FIFO and
// /dev/zero as the model) each refused in under a second with one message naming the file and
// the limit, and readable again once the limit is raised.
#include "support/Slowdown.h"
#include "support/TestSupport.h"

#include <osgLoA/util/InputLimits>
#include <osgLoA/util/PolygonCrossings>

#include <osgDB/ReadFile>
#include <osgDB/Registry>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <sys/stat.h>

using osgLoA::InputLimits;
using osgLoA::PolygonCrossings;

TEST(InputLimitsTest, OptionsSetLimitsAndBadValuesAreNamed)
{
    const InputLimits d;
    EXPECT_EQ(d.maxDepth, 64u);
    EXPECT_EQ(d.maxHierarchy, 32u);
    const InputLimits l =
        InputLimits::fromOptions("lod=2 max-depth=10 max-objects=5 max-inflated=1000 theme=x");
    EXPECT_EQ(l.maxDepth, 10u);
    EXPECT_EQ(l.maxObjects, 5u);
    EXPECT_EQ(l.maxInflatedBytes, 1000u);
    EXPECT_EQ(l.maxVertices, d.maxVertices);
    for (const char* bad : {"max-depth=x", "max-depth=0", "max-depth=-1", "max-depth=99999999999"})
        EXPECT_THROW(InputLimits::fromOptions(bad), std::invalid_argument) << bad;
    EXPECT_EQ(InputLimits::exceeded("a.json", "9 things", "max-objects", 5),
              "a.json: 9 things exceeds the limit max-objects=5 (raise it with -O max-objects=N)");
}

namespace
{
std::vector<osg::Vec2d> star(unsigned n, unsigned k)
{
    std::vector<osg::Vec2d> r;
    for (unsigned i = 0; i < n; ++i)
    {
        const double a = 2.0 * M_PI * double((i * k) % n) / double(n);
        r.emplace_back(100.0 * std::cos(a), 100.0 * std::sin(a));
    }
    return r;
}
} // namespace

// Hand counts: a square has no crossing, a bow-tie one, the pentagram {5/2} five, the star
// {7/3} n(k-1) = 14, a hole poking out of its square two; the count stops at its bounds.
TEST(InputLimitsTest, PolygonCrossingsMatchHandCounts)
{
    const std::vector<osg::Vec2d> square = {{0, 0}, {4, 0}, {4, 4}, {0, 4}};
    EXPECT_EQ(PolygonCrossings::count({square}, 100, 100000).crossings, 0u);
    EXPECT_EQ(PolygonCrossings::count({{{0, 0}, {2, 2}, {2, 0}, {0, 2}}}, 100, 100000).crossings, 1u);
    EXPECT_EQ(PolygonCrossings::count({star(5, 2)}, 100, 100000).crossings, 5u);
    EXPECT_EQ(PolygonCrossings::count({star(7, 3)}, 100, 100000).crossings, 14u);
    EXPECT_EQ(PolygonCrossings::count({star(41, 10)}, 1000, 1000000).crossings, 41u * 9u);
    EXPECT_EQ(PolygonCrossings::count({square, {{1, 1}, {3, 1}, {3, 3}, {1, 3}}}, 100, 100000).crossings, 0u);
    EXPECT_EQ(PolygonCrossings::count({square, {{3, 1}, {5, 1}, {5, 3}, {3, 3}}}, 100, 100000).crossings, 2u);
    // A circle of 10,000 vertices: none, in about one test per edge.
    std::vector<osg::Vec2d> circle;
    for (int i = 0; i < 10000; ++i)
        circle.emplace_back(std::cos(2 * M_PI * i / 10000.0), std::sin(2 * M_PI * i / 10000.0));
    const PolygonCrossings c = PolygonCrossings::count({circle}, 100, 1000000);
    EXPECT_EQ(c.crossings, 0u);
    EXPECT_FALSE(c.tooMany || c.tooComplex);
    EXPECT_LT(c.tests, 20u * 10000u);
    // Bounds: {41/10} has 369 crossings.
    EXPECT_TRUE(PolygonCrossings::count({star(41, 10)}, 50, 1000000).tooMany);
    EXPECT_TRUE(PolygonCrossings::count({star(2001, 1000)}, 1000000, 50000).tooComplex);
}

namespace
{
std::string kHeader =
    R"({"type":"CityJSON","version":"2.0","transform":{"scale":[1,1,1],"translate":[0,0,0]},)";

/** Reads path through osgDB with options; the message of a failed read ("" on success). */
std::string readMessage(const std::string& path, const std::string& options, double& seconds)
{
    osg::ref_ptr<osgDB::Options> o = new osgDB::Options(options);
    const auto t0 = std::chrono::steady_clock::now();
    osgDB::ReaderWriter::ReadResult r = osgDB::Registry::instance()->readNode(path, o.get());
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r.validNode() ? std::string() : r.message();
}

void write(const std::string& path, const std::string& text)
{
    std::ofstream(path, std::ios::binary) << text;
}
} // namespace

TEST(InputLimitsTest, CityJsonReproducersAreRefusedQuicklyWithTheLimitNamed)
{
    const std::string dir = loatest::freshDirectory("InputLimitsCityJson");
    const std::size_t n = 100000;
    write(
        dir + "/deep-boundaries.city.json",
        kHeader +
            R"("CityObjects":{"a":{"type":"Building","geometry":[{"type":"MultiSurface","lod":"1","boundaries":)" +
            std::string(n, '[') + "0" + std::string(n, ']') + R"(}]}},"vertices":[[0,0,0]]})");
    std::string attribute;
    for (std::size_t i = 0; i < n; ++i)
        attribute += R"({"a":)";
    attribute += "1" + std::string(n, '}');
    write(dir + "/deep-attribute.city.json",
          kHeader + R"("CityObjects":{"a":{"type":"Building","attributes":{"x":)" + attribute +
              R"(},"geometry":[]}},"vertices":[]})");
    const auto chain = [&](const std::string& file, int length)
    {
        std::string text = kHeader + R"("CityObjects":{)";
        for (int i = 0; i < length; ++i)
            text +=
                (i ? "," : "") + std::string("\"b") + std::to_string(i) +
                R"(":{"type":"Building","geometry":[{"type":"MultiSurface","lod":"1","boundaries":[[[0,1,2]]]}])" +
                (i + 1 < length ? ",\"children\":[\"b" + std::to_string(i + 1) + "\"]" : std::string()) + "}";
        write(dir + "/" + file, text + R"(},"vertices":[[0,0,0],[1,0,0],[1,1,0]]})");
    };
    chain("chain.city.json", 20000);
    chain("chain40.city.json", 40);
    std::string vertices, ring;
    const std::vector<osg::Vec2d> s = star(2001, 1000);
    for (std::size_t i = 0; i < s.size(); ++i)
    {
        vertices += (i ? "," : "") + std::string("[") + std::to_string(int(std::lround(s[i].x() * 10))) +
                    "," + std::to_string(int(std::lround(s[i].y() * 10))) + ",0]";
        ring += (i ? "," : "") + std::to_string(i);
    }
    write(
        dir + "/star.city.json",
        kHeader +
            R"("CityObjects":{"s":{"type":"Building","geometry":[{"type":"MultiSurface","lod":"1","boundaries":[[[)" +
            ring + R"(]]]}]}},"vertices":[)" + vertices + "]}");
    write(dir + "/long-string.city.json",
          kHeader + R"("CityObjects":{"a":{"type":"Building","attributes":{"x":")" +
              std::string(2u << 20, 'x') + R"("},"geometry":[]}},"vertices":[]})");

    struct Case
    {
        const char* file;
        const char* limit;
        const char* raised; ///< options under which the file reads (or fails later, for another reason)
    };
    for (const Case& c : {Case{"deep-boundaries.city.json", "max-depth=64", nullptr},
                          Case{"deep-attribute.city.json", "max-depth=64", nullptr},
                          Case{"chain.city.json", "max-hierarchy=32", nullptr},
                          Case{"chain40.city.json", "max-hierarchy=32", "max-hierarchy=64"},
                          Case{"star.city.json", "max-crossings=1000", nullptr},
                          Case{"long-string.city.json", "max-string=1048576", "max-string=4000000"}})
    {
        double seconds = 0.0;
        const std::string message = readMessage(dir + "/" + c.file, "", seconds);
        EXPECT_NE(message.find(c.file), std::string::npos) << message;
        EXPECT_NE(message.find(std::string("exceeds the limit ") + c.limit), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        EXPECT_LT(seconds, 2.0 * loatest::kSlowdown) << c.file;
        if (c.raised)
        {
            const std::string again = readMessage(dir + "/" + c.file, c.raised, seconds);
            EXPECT_EQ(again.find("exceeds the limit"), std::string::npos) << c.file << ": " << again;
        }
    }

    // Not regular files: a FIFO and /dev/zero would be read forever.
    ASSERT_EQ(::mkfifo((dir + "/fifo.city.json").c_str(), 0644), 0);
    double seconds = 0.0;
    EXPECT_NE(readMessage(dir + "/fifo.city.json", "", seconds).find("not a regular file"),
              std::string::npos);
    ASSERT_EQ(::symlink("/dev/zero", (dir + "/zero.city.json").c_str()), 0);
    EXPECT_NE(readMessage(dir + "/zero.city.json", "", seconds).find("not a regular file"),
              std::string::npos);
    EXPECT_LT(seconds, 2.0);
}

// The .loa reproducers: a file naming itself, two naming each other, a pseudo-loader chain
// 4,000 long, .loa files nested 100 deep, /dev/zero as a model: one message each, at once.
TEST(InputLimitsTest, LoaCyclesDepthAndDevicesAreRefused)
{
    const std::string dir = loatest::freshDirectory("InputLimitsLoa");
    write(dir + "/self.loa", R"({"models": ["self.loa"]})");
    write(dir + "/a.loa", R"({"models": ["b.loa"]})");
    write(dir + "/b.loa", R"({"models": ["a.loa"]})");
    for (int i = 0; i < 100; ++i)
        write(dir + "/n" + std::to_string(i) + ".loa",
              "{\"models\": [\"n" + std::to_string(i + 1) + ".loa\"]}");
    ASSERT_EQ(::symlink("/dev/zero", (dir + "/zero.osgt").c_str()), 0);
    write(dir + "/zero.loa", R"({"models": ["zero.osgt"]})");
    std::string chain = dir + "/x.osgt";
    for (int i = 0; i < 4000; ++i)
        chain += ".loa";
    struct Case
    {
        std::string path, message;
    };
    for (const Case& c :
         {Case{dir + "/self.loa",
               "is already being read: the .loa files name each other (self.loa -> self.loa)"},
          Case{dir + "/a.loa", "(a.loa -> b.loa -> a.loa)"},
          Case{dir + "/n0.loa", "nested more than 64 deep exceeds the limit max-depth=64"},
          Case{chain, "exceeds the limit max-depth=64"},
          Case{dir + "/zero.loa", "zero.osgt' is not a regular file (a device or FIFO)"}})
    {
        double seconds = 0.0;
        const std::string message = readMessage(c.path, "", seconds);
        EXPECT_NE(message.find(c.message), std::string::npos) << message.substr(0, 400);
        EXPECT_LT(seconds, 2.0) << c.message;
    }
}
