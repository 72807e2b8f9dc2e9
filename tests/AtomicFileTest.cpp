// Atomic writes: complete or untouched, and no temporary left behind.
#include "support/TestSupport.h"

#include <osgLoA/util/AtomicDirectory>
#include <osgLoA/util/AtomicFile>

#include <osgDB/FileUtils>

#include <gtest/gtest.h>

#include <csignal>
#include <fstream>
#include <sstream>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

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

namespace
{
/** The hidden temporaries (".NAME.tmp-PID") in dir. */
std::vector<std::string> temporaries(const std::string& dir)
{
    std::vector<std::string> t;
    for (const std::string& f : osgDB::getDirectoryContents(dir))
        if (f.find(".tmp-") != std::string::npos) t.push_back(f);
    return t;
}
} // namespace

// A symbolic link is written through to its target (atomically, in the target's folder); the
// link stays a link. A chain of links and a dangling link too.
TEST(AtomicFileTest, SymlinksAreWrittenThroughToTheirTarget)
{
    const std::string dir = loatest::freshDirectory("AtomicFileLinks");
    ::mkdir((dir + "/real").c_str(), 0755);
    AtomicFile::writeText(dir + "/real/target.json", "old");
    ASSERT_EQ(::symlink("real/target.json", (dir + "/link.json").c_str()), 0);
    ASSERT_EQ(::symlink("link.json", (dir + "/link2.json").c_str()), 0);
    AtomicFile::writeText(dir + "/link2.json", "new");
    struct stat st;
    ASSERT_EQ(::lstat((dir + "/link.json").c_str(), &st), 0);
    EXPECT_TRUE(S_ISLNK(st.st_mode));
    ASSERT_EQ(::lstat((dir + "/link2.json").c_str(), &st), 0);
    EXPECT_TRUE(S_ISLNK(st.st_mode));
    EXPECT_EQ(slurp(dir + "/real/target.json"), "new");
    EXPECT_TRUE(temporaries(dir).empty());
    EXPECT_TRUE(temporaries(dir + "/real").empty());
    // Dangling: the link's target is created.
    ASSERT_EQ(::symlink("real/created.txt", (dir + "/dangling.txt").c_str()), 0);
    AtomicFile::writeText(dir + "/dangling.txt", "made");
    EXPECT_EQ(slurp(dir + "/real/created.txt"), "made");
    // A loop is an error, not a hang.
    ASSERT_EQ(::symlink("loop-b", (dir + "/loop-a").c_str()), 0);
    ASSERT_EQ(::symlink("loop-a", (dir + "/loop-b").c_str()), 0);
    try
    {
        AtomicFile::writeText(dir + "/loop-a", "x");
        ADD_FAILURE() << "a link loop was written";
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find("too many levels of symbolic links"), std::string::npos)
            << e.what();
    }
}

// Devices are written into, never replaced; /dev/full's ENOSPC is an error; FIFOs and
// directories are refused with what they are.
TEST(AtomicFileTest, DevicesAreWrittenIntoAndFifosRefused)
{
    const std::string dir = loatest::freshDirectory("AtomicFileSpecial");
    AtomicFile::writeText("/dev/null", "discarded");
    struct stat st;
    ASSERT_EQ(::stat("/dev/null", &st), 0);
    EXPECT_TRUE(S_ISCHR(st.st_mode));
    if (osgDB::fileExists("/dev/full"))
    {
        try
        {
            AtomicFile::writeText("/dev/full", std::string(100000, 'x'));
            ADD_FAILURE() << "/dev/full took the bytes";
        }
        catch (const std::runtime_error& e)
        {
            EXPECT_NE(std::string(e.what()).find("No space left on device"), std::string::npos) << e.what();
        }
        ASSERT_EQ(::stat("/dev/full", &st), 0);
        EXPECT_TRUE(S_ISCHR(st.st_mode)) << "/dev/full was replaced";
    }
    ASSERT_EQ(::mkfifo((dir + "/fifo").c_str(), 0644), 0);
    try
    {
        AtomicFile::writeText(dir + "/fifo", "x");
        ADD_FAILURE() << "wrote a FIFO";
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find("is a FIFO"), std::string::npos) << e.what();
    }
    ASSERT_EQ(::stat((dir + "/fifo").c_str(), &st), 0);
    EXPECT_TRUE(S_ISFIFO(st.st_mode));
    EXPECT_THROW(AtomicFile::writeText(dir, "x"), std::runtime_error);
    EXPECT_TRUE(temporaries(dir).empty());
}

// An existing file keeps its permission bits; a new one gets the process's defaults.
TEST(AtomicFileTest, ExistingPermissionsAreKept)
{
    const std::string dir = loatest::freshDirectory("AtomicFileMode");
    const std::string path = dir + "/a.txt";
    AtomicFile::writeText(path, "one");
    ASSERT_EQ(::chmod(path.c_str(), 0640), 0);
    AtomicFile::writeText(path, "two");
    struct stat st;
    ASSERT_EQ(::stat(path.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 07777, 0640u);
    EXPECT_EQ(slurp(path), "two");
}

// SIGTERM during a write removes the temporary directory and ends the process as SIGTERM does;
// a temporary left by a process that no longer runs (SIGKILL) goes with the next write.
TEST(AtomicFileTest, SignalsAndDeadProcessesLeaveNoTemporaries)
{
    const std::string dir = loatest::freshDirectory("AtomicFileSignals");
    const std::string path = dir + "/out.txt";
    AtomicFile::writeText(path, "old");
    for (int sig : {SIGTERM, SIGKILL})
    {
        const pid_t child = ::fork();
        ASSERT_GE(child, 0);
        if (child == 0)
        {
            AtomicFile::write(path,
                              [sig](const std::string& temp)
                              {
                                  std::ofstream(temp) << "partial";
                                  ::raise(sig);
                                  return true;
                              });
            ::_exit(0);
        }
        int status = 0;
        ASSERT_EQ(::waitpid(child, &status, 0), child);
        EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << status;
        EXPECT_EQ(slurp(path), "old");
        if (sig == SIGTERM)
        {
            EXPECT_TRUE(temporaries(dir).empty());
        }
        else
        {
            EXPECT_EQ(temporaries(dir).size(), 1u) << "SIGKILL cannot be caught";
        }
    }
    AtomicFile::writeText(path, "new");
    EXPECT_EQ(slurp(path), "new");
    EXPECT_TRUE(temporaries(dir).empty()) << "the dead process's temporary stayed";
}

// A folder of outputs is replaced as a whole: committed, the new files only (an old file that
// the new run did not write is gone); not committed, the old folder as it was; a folder that
// holds somebody else's files is refused.
TEST(AtomicDirectoryTest, ReplacedAsAWholeOrNotAtAll)
{
    const std::string root = loatest::freshDirectory("AtomicDirectory");
    const std::string dir = root + "/out";
    {
        AtomicDirectory d(dir, "index.json");
        AtomicFile::writeText(d.staging() + "/a.png", "a1");
        AtomicFile::writeText(d.staging() + "/old-only.png", "x");
        AtomicFile::writeText(d.staging() + "/index.json", "1");
        EXPECT_FALSE(osgDB::fileExists(dir)) << "visible before commit";
        d.commit();
    }
    EXPECT_EQ(slurp(dir + "/a.png"), "a1");
    ASSERT_EQ(::chmod(dir.c_str(), 0750), 0);
    {
        AtomicDirectory d(dir, "index.json");
        AtomicFile::writeText(d.staging() + "/a.png", "a2");
        AtomicFile::writeText(d.staging() + "/index.json", "2");
        EXPECT_EQ(slurp(dir + "/a.png"), "a1") << "the old folder changed before commit";
        d.commit();
    }
    EXPECT_EQ(slurp(dir + "/a.png"), "a2");
    EXPECT_EQ(slurp(dir + "/index.json"), "2");
    EXPECT_FALSE(osgDB::fileExists(dir + "/old-only.png")) << "a mix of old and new files";
    struct stat st;
    ASSERT_EQ(::stat(dir.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 07777, 0750u) << "the folder's permissions were not kept";
    {
        AtomicDirectory d(dir, "index.json");
        AtomicFile::writeText(d.staging() + "/a.png", "a3");
        // no commit: an error in the tool
    }
    EXPECT_EQ(slurp(dir + "/a.png"), "a2");
    EXPECT_TRUE(temporaries(root).empty());
    // Somebody's folder (no index.json) is not replaced.
    AtomicFile::writeText(root + "/mine/thesis.tex", "precious");
    try
    {
        AtomicDirectory d(root + "/mine", "index.json");
        ADD_FAILURE() << "a folder of other files was accepted";
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find("holds files this tool did not write ('thesis.tex'"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_EQ(slurp(root + "/mine/thesis.tex"), "precious");
    // An empty folder is fine; a file is not a folder.
    ::mkdir((root + "/empty").c_str(), 0755);
    EXPECT_NO_THROW(AtomicDirectory(root + "/empty", "index.json"));
    EXPECT_THROW(AtomicDirectory(root + "/mine/thesis.tex", "index.json"), std::runtime_error);
}
