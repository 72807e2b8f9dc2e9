// Help and tools agree (issue 18 item 6): every option a tool's --help names is one the tool
// accepts. Each option is given with dummy arguments after it that make the parse fail on
// purpose (a second model, a bad value), so no tool does any work; what must not appear is the
// tool's "unknown option" error naming that option.
#include "support/TestSupport.h"

#include <osgDB/FileNameUtils>

#include <gtest/gtest.h>

#include <regex>
#include <set>

namespace
{
std::string binDir()
{
    return osgDB::getFilePath(LOA_RENDER_EXE);
}

std::set<std::string> helpOptions(const std::string& tool)
{
    std::string help;
    EXPECT_EQ(loatest::run("'" + binDir() + "/" + tool + "' --help", help), 0) << tool;
    std::set<std::string> options;
    const std::regex option("(^|[\\s,\\[(|])(--[a-z][a-z0-9-]*)");
    for (auto it = std::sregex_iterator(help.begin(), help.end(), option); it != std::sregex_iterator(); ++it)
        options.insert((*it)[2].str());
    return options;
}

/** Whether the tool's output calls `option` unknown. */
bool rejected(const std::string& output, const std::string& option)
{
    for (const char* what : {"unknown option '", "unknown argument '", "unexpected argument '"})
        if (output.find(what + option + "'") != std::string::npos) return true;
    return false;
}

void expectEveryHelpOptionAccepted(const std::string& tool, const std::vector<std::string>& prefixes = {""})
{
    const std::set<std::string> options = helpOptions(tool);
    EXPECT_GE(options.size(), 3u) << tool;
    const std::string dir = loatest::freshDirectory("ToolOptionsTest/" + tool); // nothing lands elsewhere
    for (const std::string& option : options)
    {
        bool accepted = false;
        std::string last;
        for (const std::string& prefix : prefixes)
        {
            std::string out;
            loatest::run("cd '" + dir + "' && timeout 60 '" + binDir() + "/" + tool + "' " + prefix + " " +
                             option + " zz-dummy-1 zz-dummy-2.png zz-dummy-3 2>&1",
                         out);
            if (!rejected(out, option))
            {
                accepted = true;
                break;
            }
            last = out;
        }
        EXPECT_TRUE(accepted) << tool << " --help names " << option << ", which the tool rejects: " << last;
    }
}
} // namespace

TEST(ToolOptionsTest, LoaRender)
{
    expectEveryHelpOptionAccepted("loa-render");
}
TEST(ToolOptionsTest, LoaClassify)
{
    expectEveryHelpOptionAccepted("loa-classify");
}
TEST(ToolOptionsTest, LoaCitygen)
{
    expectEveryHelpOptionAccepted("loa-citygen");
}
TEST(ToolOptionsTest, LoaPrefilter)
{
    expectEveryHelpOptionAccepted("loa-prefilter");
}
TEST(ToolOptionsTest, LoaPalette)
{
    expectEveryHelpOptionAccepted("loa-palette");
}
TEST(ToolOptionsTest, LoaFilterCompare)
{
    expectEveryHelpOptionAccepted("loa-filter-compare");
}
TEST(ToolOptionsTest, LoaBench)
{
    expectEveryHelpOptionAccepted("loa-bench");
}
TEST(ToolOptionsTest, LoaSheet)
{
    expectEveryHelpOptionAccepted("loa-sheet");
}
// loa-scenario's options belong to its commands: each must be accepted by one of them.
TEST(ToolOptionsTest, LoaScenario)
{
    expectEveryHelpOptionAccepted("loa-scenario",
                                  {"explain", "set zz.osgt", "show", "create zz.osgt", "validate"});
}
