// Atomic writes: complete or untouched, and no temporary left behind.
#include "support/TestSupport.h"

#include <osgLoA/util/AtomicFile>

#include <osgDB/FileUtils>

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

using namespace osgLoA;

namespace
{
std::string slurp(const std::string& p)
{
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}
} // namespace

TEST(AtomicFileTest, WritesReplaceAndFailuresLeaveTheOldFile)
{
    const std::string dir = loatest::freshDirectory("AtomicFile");
    const std::string path = dir + "/sub/a.txt";
    AtomicFile::writeText(path, "one");
    EXPECT_EQ(slurp(path), "one");
    AtomicFile::writeText(path, "two");
    EXPECT_EQ(slurp(path), "two");
    EXPECT_THROW(AtomicFile::write(path,
                                   [](const std::string& temp)
                                   {
                                       std::ofstream(temp) << "partial";
                                       return false;
                                   }),
                 std::runtime_error);
    EXPECT_EQ(slurp(path), "two");
    EXPECT_THROW(
        AtomicFile::write(path, [](const std::string&) -> bool { throw std::runtime_error("boom"); }),
        std::runtime_error);
    EXPECT_EQ(slurp(path), "two");
    // Only a.txt is left in the directory: the temporaries are gone.
    int entries = 0;
    for (const auto& f : osgDB::getDirectoryContents(dir + "/sub"))
        entries += f != "." && f != "..";
    EXPECT_EQ(entries, 1);
}
