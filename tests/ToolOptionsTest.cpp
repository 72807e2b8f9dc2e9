// Help and tools agree (issue 18 item 6): every option a tool's --help names is one the tool
// accepts. Each option is given with dummy arguments after it that make the parse fail on
// purpose (a second model, a bad value), so no tool does any work; what must not appear is the
// tool's "unknown option" error naming that option.
#include "support/TestSupport.h"

#include <osgDB/FileNameUtils>

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <regex>
#include <set>
#include <sstream>

namespace
{
std::string binDir()
{
    return osgDB::getFilePath(LOA_RENDER_EXE);
}

/** The shell words that run `tool` ("loa-render", or "loa-scenario explain": a tool's command). */
std::string command(const std::string& tool)
{
    const std::size_t space = tool.find(' ');
    const std::string exe = tool.substr(0, space);
    return "'" + binDir() + "/" + exe + "'" + (space == std::string::npos ? "" : tool.substr(space));
}

std::string helpText(const std::string& tool)
{
    std::string help;
    EXPECT_EQ(loatest::run(command(tool) + " --help", help), 0) << tool;
    return help;
}

std::set<std::string> helpOptions(const std::string& tool)
{
    const std::string help = helpText(tool);
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
    EXPECT_GE(options.size(), 1u) << tool; // at least --help
    std::string name = tool;
    std::replace(name.begin(), name.end(), ' ', '-');
    const std::string dir = loatest::freshDirectory("ToolOptionsTest/" + name); // nothing lands elsewhere
    for (const std::string& option : options)
    {
        bool accepted = false;
        std::string last;
        for (const std::string& prefix : prefixes)
        {
            std::string out;
            loatest::run("cd '" + dir + "' && timeout 60 " + command(tool) + " " + prefix + " " + option +
                             " zz-dummy-1 zz-dummy-2.png zz-dummy-3 2>&1",
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
// loa-scenario's options belong to its commands: each command's --help names its own, and that
// command accepts every one of them.
TEST(ToolOptionsTest, LoaScenario)
{
    for (const char* name : {"list", "show", "validate", "create", "set", "explain"})
        expectEveryHelpOptionAccepted(std::string("loa-scenario ") + name);
}

/** The help entry of `option` in a tool's help: its line and the indented lines after it. */
std::string helpEntry(const std::string& help, const std::string& option)
{
    std::istringstream in(help);
    std::string line, entry;
    bool inEntry = false;
    while (std::getline(in, line))
    {
        const bool starts = line.compare(0, 2, "  ") == 0 && line.size() > 2 && line[2] == '-';
        if (starts)
        {
            if (inEntry) break;
            const std::regex names("^  (-[A-Za-z], )?(--[a-z][a-z0-9-]*)");
            std::smatch m;
            inEntry = std::regex_search(line, m, names) && m[2].str() == option;
        }
        else if (inEntry && (line.empty() || line.find_first_not_of(' ') < 24))
            break;
        if (inEntry) entry += line + "\n";
    }
    return entry;
}

// One command line (issue 18 item 6): an option of the shared groups reads the same, value name
// and description, in every tool that takes it, and the rendering tools share one default size.
TEST(ToolOptionsTest, SharedOptionsAreSpelledTheSameEverywhere)
{
    const std::vector<std::string> tools = {"loa-render",          "loa-classify",       "loa-prefilter",
                                            "loa-palette",         "loa-filter-compare", "loa-citygen",
                                            "loa-scenario explain"};
    std::map<std::string, std::string> helps;
    for (const std::string& t : tools)
        helps[t] = helpText(t);
    for (const char* option : {"--options", "--camera", "--eye", "--center", "--up", "--rules",
                               "--rules-only", "--override", "--help", "--version"})
    {
        std::string first, firstTool;
        int found = 0;
        for (const std::string& t : tools)
        {
            const std::string entry = helpEntry(helps[t], option);
            if (entry.empty()) continue;
            ++found;
            if (first.empty())
                first = entry, firstTool = t;
            else
                EXPECT_EQ(entry, first) << option << " in " << t << " differs from " << firstTool;
        }
        EXPECT_GE(found, 2) << option;
    }
    // --size: one default everywhere an image is rendered.
    for (const char* t : {"loa-render", "loa-classify", "loa-filter-compare", "loa-scenario explain"})
    {
        // Words, not line breaks: the entry's whitespace runs as single spaces.
        const std::string entry = std::regex_replace(helpEntry(helps[t], "--size"), std::regex("\\s+"), " ");
        EXPECT_NE(entry.find("(default 1280x720)"), std::string::npos) << t << ": " << entry;
    }
    // The models are positional (MODEL...) in every tool that reads models.
    for (const char* t : {"loa-render", "loa-classify", "loa-prefilter", "loa-palette", "loa-filter-compare"})
        EXPECT_NE(helps[t].find("\n  MODEL...  "), std::string::npos) << t;
    EXPECT_NE(helps["loa-scenario explain"].find("\n  SCENARIO MODEL...  "), std::string::npos);
    // --out is a file and --out-dir a folder: no help describes --out as a directory.
    for (const auto& h : helps)
    {
        const std::string out = helpEntry(h.second, "--out");
        EXPECT_EQ(out.find("DIR"), std::string::npos) << h.first << ": " << out;
        EXPECT_EQ(out.find("directory"), std::string::npos) << h.first << ": " << out;
    }
}
