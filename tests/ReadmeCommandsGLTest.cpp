// Every command the README shows runs (issue 18 items 5, 6): the tool lines of its code blocks and
// its tool table (build/bin/..., the stock osgconv), from a scratch folder whose build/ and
// data/ are the real ones, without OSG_LIBRARY_PATH. The stock osgconv finds our plugins once
// osgLoA is installed (scripts/install, into /usr/local, which OSG searches by itself): the test
// installs the build into a scratch prefix and points OSG there instead, so the installed
// layout (plugin RPATHs, data files) is what the osgconv lines use. Lines run in README order;
// one that fails is tried again after the others (an example may read what a later one
// writes). The interactive osgviewer lines are LoaViewerGLTest's (under xvfb); loa-viewer lines
// run here under xvfb-run for three frames.
#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

namespace
{
std::vector<std::string> readmeCommands()
{
    std::ifstream in(std::string(LOA_SOURCE_DIR) + "/README.md");
    std::vector<std::string> commands;
    bool code = false;
    const std::regex cell("`(build/bin/[^`]+)`");
    for (std::string line; std::getline(in, line);)
    {
        if (line.compare(0, 3, "```") == 0)
        {
            code = !code;
            continue;
        }
        if (code)
        {
            std::string c = line.substr(0, line.find(" # "));
            while (!c.empty() && c.back() == ' ')
                c.pop_back();
            if (c.compare(0, 10, "build/bin/") == 0 || c.compare(0, 8, "osgconv ") == 0)
                commands.push_back(c);
        }
        else
            for (auto it = std::sregex_iterator(line.begin(), line.end(), cell); it != std::sregex_iterator();
                 ++it)
                commands.push_back((*it)[1].str());
    }
    return commands;
}
} // namespace

TEST(ReadmeCommandsGLTest, EveryToolCommandOfTheReadmeRuns)
{
    const std::vector<std::string> commands = readmeCommands();
    ASSERT_GE(commands.size(), 15u) << "the README's tool examples were not found";
    const std::string dir = loatest::freshDirectory("ReadmeCommandsGLTest");
    std::string out;
    ASSERT_EQ(loatest::run("cd '" + dir + "' && ln -s '" + std::string(LOA_BINARY_DIR) +
                               "' build && ln -s '" + LOA_SOURCE_DIR + "/data' data && mkdir -p out",
                           out),
              0)
        << out;
    // The stand-in for /usr/local: the build installed as scripts/install installs it.
    ASSERT_EQ(loatest::run(
                  "cmake --install '" + std::string(LOA_BINARY_DIR) + "' --prefix '" + dir + "/prefix'", out),
              0)
        << out;
    std::string pluginDir;
    ASSERT_EQ(loatest::run("cd '" + dir + "/prefix' && ls -d lib*/osgPlugins-*", pluginDir), 0) << pluginDir;
    const std::string stockEnv =
        loatest::stockToolEnvironment() + "OSG_LIBRARY_PATH='" + dir + "/prefix/" + pluginDir.substr(0, pluginDir.find("/osgPlugins-")) + "' ";
    std::vector<std::pair<std::string, std::string>> failed;
    for (int pass = 0; pass < 2; ++pass)
    {
        std::vector<std::string> todo;
        if (pass == 0)
            todo = commands;
        else
            for (const auto& f : failed)
                todo.push_back(f.first);
        failed.clear();
        for (const std::string& c : todo)
        {
            const bool stock = c.compare(0, 8, "osgconv ") == 0;
            // loa-viewer opens a window: under xvfb-run, for three frames.
            const bool window = c.compare(0, 20, "build/bin/loa-viewer") == 0;
            const std::string run = window ? "xvfb-run -a -s \"-screen 0 1280x720x24\" " + c + " --frames 3" : c;
            const int status =
                loatest::run("cd '" + dir + "' && env -u OSG_LIBRARY_PATH " +
                                 (stock ? stockEnv : std::string()) + "timeout 600 sh -c '" + run + "'",
                             out);
            if (status != 0) failed.emplace_back(c, "exit " + std::to_string(status) + ": " + out);
        }
    }
    for (const auto& f : failed)
        ADD_FAILURE() << f.first << "\n" << f.second;
}
