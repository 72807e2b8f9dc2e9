// loa-render's error paths: one clear line on stderr and the documented exit status.
// None of these reaches a GL context, so the test needs no GL.
#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace
{
struct Case
{
    const char* args;
    int status;
    const char* message;
};

std::string exe()
{
    return std::string("'") + LOA_RENDER_EXE + "'";
}
} // namespace

TEST(LoaRenderTest, BadInputGivesOneClearLineAndTheDocumentedStatus)
{
    const std::string dir = loatest::freshDirectory("LoaRenderTest");
    std::ofstream(dir + "/garbage.osgb") << "this is not an osgb file";
    std::ofstream(dir + "/model.xyz123") << "unknown format";
    std::ofstream(dir + "/group.osgt") << "#Ascii Scene\n#Version 161\n#Generator OpenSceneGraph 3.6.5\n\n"
                                          "osg::Group {\n  UniqueID 1\n}\n";
    const Case cases[] = {
        {"/nonexistent/city.osgb", 1, "cannot read '/nonexistent/city.osgb': no such file"},
        {"GARBAGE", 1, "cannot read"},
        {"XYZ", 1, "no osgDB plugin reads '.xyz123' files"},
        {"--size 12x", 2, "--size '12x' is not WIDTHxHEIGHT"},
        {"--size 0x100", 2, "is outside 1x1 .. 16384x16384"},
        {"--size 99999x10", 2, "is outside"},
        {"--size abc", 2, "is not WIDTHxHEIGHT"},
        {"--camera balloon", 2, "unknown camera 'balloon'"},
        {"--eye 1,2", 2, "--eye '1,2' is not X,Y,Z"},
        {"--eye 1,2,3", 2, "--eye and --center go together"},
        {"--frames -3", 2, "--frames '-3' is not an integer"},
        {"--out x.jpg", 2, "must name a .png file"},
        {"--bogus", 2, "unknown option '--bogus'"},
        {"--size", 2, "--size needs a value"},
        {"--size 10x10 --size 20x20", 2, "--size given more than once"},
        {"x.osgb --frob 3", 2, "unknown option '--frob'"},
        {"-O blocksX=0", 2, "blocksX must be in 1..200"},
        {"a.osgb b.osgb", 1, "cannot read 'a.osgb'"}, // several models are one scene
        {"--program toon", 2, "unknown --program 'toon'"},
        {"--style nope", 2, "unknown --style 'nope' (loa-render --list-styles lists them)"},
        {"--style kuwahara3 --scenario distance", 2, "--style excludes --scenario and --program"},
        {"--focus 0.5,0.5", 2, "need --style"},
        {"--style adaptive --focus 0.5", 2, "--focus '0.5' needs 2 comma-separated numbers"},
        {"--style adaptive --focus 0.5,x", 2, "'x' is not a number"},
        {"--style adaptive --focus-radii 0.5,0.1", 2, "focus: "},
        {"--style adaptive --focus-object -1", 2, "--focus-object '-1' is not an integer"},
        {"--style photorealistic --focus 0.5,0.5", 2, "the focus options apply to image-space"},
        {"--style /nonexistent/style.osgt", 1, "--style: no file '/nonexistent/style.osgt'"},
        {"--style NOTASTYLE", 1, "does not hold an osgLoA::AbstractionStyle"},
    };
    for (const Case& c : cases)
    {
        std::string args = c.args;
        if (args == "GARBAGE") args = "'" + dir + "/garbage.osgb'";
        if (args == "XYZ") args = "'" + dir + "/model.xyz123'";
        if (args == "--style NOTASTYLE") args = "--style '" + dir + "/group.osgt'";
        std::string out;
        const std::string outOption =
            args.find("--out ") == std::string::npos ? " --out '" + dir + "/x.png' " : " ";
        const int status = loatest::run(exe() + outOption + args, out);
        EXPECT_EQ(status, c.status) << c.args << "\n" << out;
        EXPECT_EQ(out.rfind("loa-render: error: ", 0), 0u) << c.args << " printed:\n" << out;
        EXPECT_NE(out.find(c.message), std::string::npos) << c.args << " printed:\n" << out;
        EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << c.args << " printed:\n" << out;
        EXPECT_EQ(out.find("Segmentation"), std::string::npos);
    }
}

TEST(LoaRenderTest, ListStylesPrintsEveryStyleWithItsDescription)
{
    std::string out;
    ASSERT_EQ(loatest::run(exe() + " --list-styles", out), 0) << out;
    std::vector<std::string> lines;
    std::size_t start = 0;
    for (std::size_t end; (end = out.find('\n', start)) != std::string::npos; start = end + 1)
    {
        // "NAME  description": the name, two spaces at least, a description.
        const std::string line = out.substr(start, end - start);
        const std::size_t gap = line.find("  ");
        ASSERT_NE(gap, std::string::npos) << line;
        EXPECT_GT(line.find_first_not_of(' ', gap), gap) << line;
        EXPECT_EQ(line.find("(no description)"), std::string::npos) << line;
        lines.push_back(line.substr(0, gap));
    }
    for (const char* name : {"photorealistic",
                             "abstract",
                             "cartographic",
                             "blueprint",
                             "hidden",
                             "dog",
                             "kuwahara3",
                             "kuwahara5",
                             "kuwahara-dog",
                             "adaptive",
                             "adaptive-segmented",
                             "cel",
                             "pencil",
                             "sobel",
                             "canny",
                             "hybrid-toon",
                             "hybrid-pencil",
                             "adaptive-hybrid-toon",
                             "adaptive-hybrid-pencil",
                             "palette",
                             "waterlining",
                             "relief",
                             "signatures",
                             "streets",
                             "trees",
                             "object-edges"})
        EXPECT_NE(std::find(lines.begin(), lines.end(), name), lines.end()) << name << " missing in:\n"
                                                                            << out;
    EXPECT_EQ(lines.size(), 26u) << out;
}

TEST(LoaRenderTest, HelpDocumentsEveryOption)
{
    std::string out;
    ASSERT_EQ(loatest::run(exe() + " --help", out), 0);
    for (const char* opt : {"--camera", "--eye", "--center", "--up", "--size", "--frames", "--out", "--stats",
                            "--samples", "street", "oblique", "top", "horizon", "--style", "--list-styles",
                            "--focus", "--focus-object", "--focus-world", "--focus-radii"})
        EXPECT_NE(out.find(opt), std::string::npos) << opt;
}

TEST(LoaRenderTest, NoUsableEglIsOneSentenceAndStatus3)
{
    // GLVND finds no EGL vendor library: EGL is installed but unusable.
    std::string out;
    const int status =
        loatest::run("__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json " + exe() + " --gl-info", out);
    EXPECT_EQ(status, 3) << out;
    EXPECT_NE(out.find("loa-render: error: No usable EGL display"), std::string::npos) << out;
    EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
}

// Outputs respect what their paths name (issue 22 item 4), checked through the tool: a full
// device is exit 1 with one line and stays a device, a FIFO is refused at once (no hang), a
// symbolic link is written through and stays a link.
TEST(LoaRenderTest, OutputsRespectTheFileSystem)
{
    const std::string dir = loatest::freshDirectory("LoaRenderTestFiles");
    const std::string base =
        "cd '" + dir + "' && timeout 120 " + exe() + " -O 'blocksX=2 blocksY=2 landmarks=1' --size 64x48 ";
    std::string out;
    struct stat st;
    if (::stat("/dev/full", &st) == 0)
    {
        EXPECT_EQ(loatest::run(base + "--out a.png --stats /dev/full", out), 1) << out;
        EXPECT_NE(out.find("loa-render: error: cannot write '/dev/full': No space left on device"),
                  std::string::npos)
            << out;
        ASSERT_EQ(::stat("/dev/full", &st), 0);
        EXPECT_TRUE(S_ISCHR(st.st_mode)) << "/dev/full was replaced";
    }
    ASSERT_EQ(::mkfifo((dir + "/fifo.json").c_str(), 0644), 0);
    EXPECT_EQ(loatest::run(base + "--out b.png --stats fifo.json", out), 1) << out;
    EXPECT_NE(out.find("'fifo.json' is a FIFO"), std::string::npos) << out;
    ASSERT_EQ(::lstat((dir + "/fifo.json").c_str(), &st), 0);
    EXPECT_TRUE(S_ISFIFO(st.st_mode));
    // Links: the image and the statistics land in the targets.
    ASSERT_EQ(::mkdir((dir + "/real").c_str(), 0755), 0);
    ASSERT_EQ(::symlink("real/image.png", (dir + "/link.png").c_str()), 0);
    ASSERT_EQ(::symlink("real/stats.json", (dir + "/link.json").c_str()), 0);
    EXPECT_EQ(loatest::run(base + "--out link.png --stats link.json", out), 0) << out;
    for (const char* link : {"link.png", "link.json"})
    {
        ASSERT_EQ(::lstat((dir + "/" + link).c_str(), &st), 0);
        EXPECT_TRUE(S_ISLNK(st.st_mode)) << link << " was replaced by a file";
    }
    ASSERT_EQ(::stat((dir + "/real/image.png").c_str(), &st), 0);
    EXPECT_GT(st.st_size, 100);
    ASSERT_EQ(::stat((dir + "/real/stats.json").c_str(), &st), 0);
    EXPECT_GT(st.st_size, 100);
    // The image into a device: written into it, the device stays.
    ASSERT_EQ(::symlink("/dev/null", (dir + "/null.png").c_str()), 0);
    EXPECT_EQ(loatest::run(base + "--out null.png", out), 0) << out;
    ASSERT_EQ(::stat("/dev/null", &st), 0);
    EXPECT_TRUE(S_ISCHR(st.st_mode));
}
