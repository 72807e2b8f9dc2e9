// The stock osgviewer opens LoA scenes through osgdb_loa: demo.loacity.loa with the default
// scenario and with every library scenario, and the example data/demo.loa. It runs under
// xvfb-run (an X server in memory; Mesa renders with llvmpipe), three frames each.
#include "support/TestSupport.h"

#include <osgLoA/city/CityCameras>
#include <osgLoA/city/CityGenerator>
#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/transitions/ScenarioLibrary>
#include <osgLoA/util/ImageCompare>
#include <osgLoA/util/ImageFile>

#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <fstream>

#include <gtest/gtest.h>

#include <sstream>

#include <unistd.h>

namespace
{
// City options in the same -O string as scenario=: seed, blocksX and blocksY are keys that
// osgdb_loacity declares, so osgdb_loa passes them on without a warning.
const std::string kCity = "seed=2 blocksX=4 blocksY=4";

bool have(const std::string& tool)
{
    std::string out;
    return loatest::run("command -v " + tool, out) == 0;
}

/** Lines of osgviewer's output that say something went wrong in loading or drawing a LoA scene:
 *  anything from our plugins and nodes ("loa:", "loacity:", "osgLoA::"), any "Error" or
 *  "Warning", and a viewer that got no window (osgviewer still exits with 0 then). */
std::string problemLines(const std::string& output)
{
    const char* const markers[] = {"loa:",
                                   "loacity:",
                                   "osgLoA::",
                                   "Error",
                                   "Warning",
                                   "failed to set up any windows",
                                   "X11ErrorHandling"};
    std::istringstream in(output);
    std::string problems;
    for (std::string line; std::getline(in, line);)
        for (const char* m : markers)
            if (line.find(m) != std::string::npos)
            {
                problems += line + "\n";
                break;
            }
    return problems;
}

/** Runs `inner` (a command line) under xvfb-run with a screen of width x height, from the folder
 *  dir ("" for the current one). xvfb-run -n N -a searches for a free display from N on (-a must
 *  follow -n): parallel tests start apart. A run that got no display is tried once more; the
 *  program's other problems never are. */
int runUnderXvfb(const std::string& dir, const std::string& inner, int width, int height,
                 std::string& command, std::string& output)
{
    static unsigned runs = 0;
    int rc = 0;
    for (int attempt = 0; attempt < 2; ++attempt)
    {
        const unsigned display = 100 + (static_cast<unsigned>(::getpid()) * 37u + runs++ * 11u) % 800u;
        command = (dir.empty() ? std::string() : "cd '" + dir + "' && ") + "xvfb-run -n " +
                  std::to_string(display) + " -a -s '-screen 0 " + std::to_string(width) + "x" +
                  std::to_string(height) + "x24' " + inner;
        rc = loatest::run(command, output);
        if (output.find("Unable to open display") == std::string::npos) break;
    }
    return rc;
}

void view(const std::string& what, const std::string& optionString, const std::string& file)
{
    // osgviewer's default full-screen window fails on Xvfb in about one run in four ("Unable to
    // open display", X errors, sometimes an abort; measured 5 of 20 runs of plain demo.loacity,
    // without osgdb_loa), so the window is 320x240 (0 failures in 50 runs).
    std::string command, output;
    const int rc = runUnderXvfb(
        "",
        "env " + loatest::stockToolEnvironment() + "OSG_LIBRARY_PATH='" + std::string(LOA_BINARY_DIR) +
            "/lib' OSG_RUN_FRAME_COUNT=3 OSG_NOTIFY_LEVEL=WARN osgviewer --window 0 0 320 240" +
            (optionString.empty() ? std::string() : " -O '" + optionString + "'") + " '" + file + "'",
        640, 480, command, output);
    EXPECT_EQ(rc, 0) << what << ": " << command << "\n" << output;
    EXPECT_EQ(problemLines(output), "") << what << ": " << command << "\n" << output;
}

void skipWithoutViewer()
{
    if (!have("xvfb-run")) GTEST_SKIP() << "xvfb-run not installed (Debian packages xvfb, xauth)";
    if (!have("osgviewer")) GTEST_SKIP() << "osgviewer not installed (Debian package openscenegraph)";
}
} // namespace

TEST(LoaViewerGLTest, DefaultScenario)
{
    skipWithoutViewer();
    view("default scenario", kCity, "demo.loacity.loa");
}

TEST(LoaViewerGLTest, ScenarioAndCityOptionsInOneString)
{
    skipWithoutViewer();
    view("route, small city", "scenario=route " + kCity, "demo.loacity.loa");
}

TEST(LoaViewerGLTest, EveryLibraryScenario)
{
    skipWithoutViewer();
    // The default city (about 1.5 s a run here): it holds the blueprint scenario's focus object,
    // which a small city lacks (osgLoA::LoANode warns about that when it binds).
    for (const std::string& name : osgLoA::ScenarioLibrary::builtinNames())
        view("scenario " + name, "scenario=" + name, "demo.loacity.loa");
}

TEST(LoaViewerGLTest, DemoLoaFile)
{
    skipWithoutViewer();
    view("data/demo.loa", "", std::string(LOA_SOURCE_DIR) + "/data/demo.loa");
}

// loa-viewer under Xvfb (issue 20): a script of osgGA events authors the circle-of-interest
// scenario by mouse, saves it, and the viewer's frame equals loa-render's frame of the saved file.
namespace
{
struct ViewerRun
{
    int rc = 0;
    std::string output, command;
};

/** Runs loa-viewer with a script in an Xvfb screen of the window's size. */
ViewerRun runViewer(const std::string& script, const std::string& arguments, int width, int height,
                    const std::string& environment = std::string())
{
    const std::string dir =
        loatest::freshDirectory("loa-viewer-" + std::to_string(width) + "x" + std::to_string(height));
    {
        std::ofstream out(dir + "/script.txt");
        out << script;
    }
    ViewerRun r;
    const std::string size = std::to_string(width) + "x" + std::to_string(height);
    r.rc = runUnderXvfb(dir,
                        "env " + environment + " OSG_LIBRARY_PATH='" + std::string(LOA_BINARY_DIR) +
                            "/lib' OSG_NOTIFY_LEVEL=WARN '" + LOA_VIEWER_EXE + "' --size " + size +
                            " --script script.txt " + arguments,
                        width, height, r.command, r.output);
    return r;
}

osg::ref_ptr<osg::Image> renderSaved(const std::string& dir, const std::string& arguments, int width,
                                     int height)
{
    std::string out;
    const std::string png = dir + "/loa-render.png";
    const std::string command = "'" + std::string(LOA_RENDER_TOOL) + "' --size " + std::to_string(width) +
                                "x" + std::to_string(height) + " --out '" + png + "' " + arguments + " 2>&1";
    EXPECT_EQ(loatest::run(command, out), 0) << command << "\n" << out;
    return osgDB::fileExists(png) ? osgLoA::ImageFile::read(png) : nullptr;
}

/** The pixel shows the tools' sky colour (the clear colour; within 2/255 a channel). */
bool isSky(const osg::Image& image, int x, int y)
{
    const osg::Vec4 c = image.getColor(x, y) * 255.0f;
    const osg::Vec4 sky = osgLoA::OffscreenRenderer::skyColor() * 255.0f;
    return std::fabs(c.r() - sky.r()) < 3 && std::fabs(c.g() - sky.g()) < 3 && std::fabs(c.b() - sky.b()) < 3;
}

void skipWithoutXvfb()
{
    if (!have("xvfb-run")) GTEST_SKIP() << "xvfb-run not installed (Debian packages xvfb, xauth)";
}

/** The viewer's frame against loa-render's of the same scenario, camera and size. */
void expectSameFrame(const std::string& dir, const std::string& viewerShot,
                     const std::string& renderArguments, int width, int height)
{
    osg::ref_ptr<osg::Image> viewer = osgLoA::ImageFile::read(dir + "/" + viewerShot);
    osg::ref_ptr<osg::Image> reference = renderSaved(dir, renderArguments, width, height);
    ASSERT_TRUE(viewer.valid() && reference.valid());
    // The same pipeline, light, field of view and sky: equal up to llvmpipe's rounding.
    const osgLoA::ImageComparison cmp = osgLoA::ImageComparison::compare(*viewer, *reference, 16);
    EXPECT_TRUE(cmp.sizesMatch);
    EXPECT_LE(cmp.meanDifference, 0.5) << cmp.summary();
    EXPECT_LE(cmp.failingFraction, 0.001) << cmp.summary();
}
} // namespace

TEST(LoaViewerGLTest, CircleOfInterestAuthoredByMouseAt1920x1080)
{
    skipWithoutXvfb();
    // Region mode (r), a circle dragged from the window's centre 180 px to the right, the circle
    // scenario (R: detail inside, abstract outside), its fade dragged with the right button,
    // panels hidden (Tab), a screenshot, Ctrl+S.
    const std::string script = "key r\ndrag 960 540 1140 540 steps 2\nkey R\n"
                               "drag 960 540 1260 540 right steps 2\nkey tab\nscreenshot viewer.png\n"
                               "key s ctrl\nquit\n";
    const std::string city = "-O 'seed=2 blocksX=4 blocksY=4' --camera top";
    const ViewerRun run = runViewer(script, city + " --save circle.osgt", 1920, 1080);
    ASSERT_EQ(run.rc, 0) << run.command << "\n" << run.output;
    EXPECT_NE(run.output.find("edit 1: place circle 'circle-1'"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("edit 3: region fade"), std::string::npos) << run.output;
    const std::string dir = std::string(LOA_BINARY_DIR) + "/test-output/loa-viewer-1920x1080";
    osg::ref_ptr<osgLoA::UsageScenario> saved = osgLoA::ScenarioLibrary::readFile(dir + "/circle.osgt");
    ASSERT_EQ(saved->getRegions().size(), 1u);
    ASSERT_EQ(saved->getConfigurations().size(), 4u);
    // The top view looks straight down at the city's centre: the window's centre pixel is the
    // point under the eye, and 180 px at 1080 px over 45 degrees spans 2 (180/1080) tan(22.5)
    // times the eye's height above the picked surface.
    osgLoA::CityParameters p;
    p.seed = 2;
    p.blocksX = 4;
    p.blocksY = 4;
    osg::ref_ptr<osg::Group> model = osgLoA::CityGenerator(p).generate();
    const osgLoA::CameraPose top = osgLoA::CityCameras::compute("top", *model, 1920.0 / 1080.0);
    const osg::Vec2d centre = saved->getRegions()[0]->getVertices()[0];
    // The script's pixel (960, 540) has its centre half a pixel right of and below the
    // window's centre: within one pixel's ground size there.
    const double pixel = 2.0 * std::tan(osg::DegreesToRadians(22.5)) * top.eye.z() / 1080.0;
    EXPECT_NEAR(centre.x(), top.eye.x(), pixel);
    EXPECT_NEAR(centre.y(), top.eye.y(), pixel);
    const double radius = saved->getRegions()[0]->getRadius();
    const double perMetre = 2.0 * 180.0 / 1080.0 * std::tan(osg::DegreesToRadians(22.5));
    EXPECT_GT(radius, perMetre * (top.eye.z() - 40.0)); // the surface lies below 40 m there
    EXPECT_LT(radius, perMetre * (top.eye.z() + 1.0));
    for (const auto& c : saved->getConfigurations())
    {
        ASSERT_TRUE(c->getMetric(osgLoA::SaliencyMetric::REGION));
        // The right drag ended 300 px from the centre, the circle's edge is at 180 px: the fade
        // is 120/180 of the radius (the same height there, within 10 %).
        EXPECT_NEAR(c->getMetric(osgLoA::SaliencyMetric::REGION)->getFar(), radius * 2.0 / 3.0, radius * 0.1);
    }
    expectSameFrame(dir, "viewer.png", city + " --scenario '" + dir + "/circle.osgt'", 1920, 1080);
}

TEST(LoaViewerGLTest, PanelsAndAuthoringOnARealSceneAtAnOddSize)
{
    skipWithoutXvfb();
    const std::string scene = std::string(LOA_SOURCE_DIR) + "/data/test-scenes/opencity-block.osgt";
    if (!osgDB::fileExists(std::string(LOA_SOURCE_DIR) + "/data/cache/opencity-data/pine2/pine2.ac"))
        GTEST_SKIP() << "the OpenCity models are absent: run scripts/fetch-test-data";
    // The OpenCity block from its home view at 961x541: a circle dragged by mouse, the circle
    // scenario, a screenshot with the panels (against a golden), one without (against
    // loa-render's frame of the saved scenario from the same viewpoint).
    const std::string script =
        "key r\ndrag 480 330 560 330 steps 2\nkey R\nscreenshot panels.png\n"
        "key tab\nscreenshot viewer.png\nkey i\nscreenshot interest.png\nkey s ctrl\nquit\n";
    const ViewerRun run = runViewer(script, "'" + scene + "' --camera oblique --save circle.osgb", 961, 541);
    ASSERT_EQ(run.rc, 0) << run.command << "\n" << run.output;
    const std::string dir = std::string(LOA_BINARY_DIR) + "/test-output/loa-viewer-961x541";
    osg::ref_ptr<osgLoA::UsageScenario> saved = osgLoA::ScenarioLibrary::readFile(dir + "/circle.osgb");
    ASSERT_EQ(saved->getRegions().size(), 1u);
    EXPECT_GT(saved->getRegions()[0]->getRadius(), 1.0);
    expectSameFrame(dir, "viewer.png",
                    "'" + scene + "' --camera oblique --scenario '" + dir + "/circle.osgb'", 961, 541);
    // The interest debug view (i): grey by interest (black in the circle, white far from it),
    // red where no configuration matches; the sky stays.
    osg::ref_ptr<osg::Image> interest = osgLoA::ImageFile::read(dir + "/interest.png");
    ASSERT_TRUE(interest.valid());
    unsigned drawn = 0, grey = 0, dark = 0, light = 0;
    for (int y = 0; y < interest->t(); ++y)
        for (int x = 0; x < interest->s(); ++x)
        {
            if (isSky(*interest, x, y)) continue;
            const osg::Vec4 c = interest->getColor(x, y) * 255.0f;
            ++drawn;
            const bool isGrey = std::fabs(c.r() - c.g()) <= 6 && std::fabs(c.g() - c.b()) <= 6;
            const bool isRed = c.r() > 200 && c.g() < 40 && c.b() < 40;
            grey += isGrey || isRed ? 1 : 0;
            dark += isGrey && c.r() < 64 ? 1 : 0;
            light += isGrey && c.r() > 192 ? 1 : 0;
        }
    EXPECT_GT(drawn, 961u * 541u / 8);
    EXPECT_GE(grey, drawn * 99 / 100) << grey << " of " << drawn;
    EXPECT_GT(dark, drawn / 100);
    EXPECT_GT(light, drawn / 100);
    osg::ref_ptr<osg::Image> panels = osgLoA::ImageFile::read(dir + "/panels.png");
    ASSERT_TRUE(panels.valid());
    osg::ref_ptr<osg::Image> golden = loatest::goldenOrUpdate("viewer-panels-opencity-961x541.png", *panels);
    if (!golden) GTEST_SKIP() << "golden updated";
    const osgLoA::ImageComparison cmp = osgLoA::ImageComparison::compare(*panels, *golden, 16);
    EXPECT_TRUE(cmp.sizesMatch);
    EXPECT_LE(cmp.failingFraction, 0.005) << cmp.summary();
    if (cmp.failingFraction > 0.005)
        loatest::saveFailure("viewer-panels-opencity-961x541", *panels, cmp.difference.get());
}

TEST(LoaViewerGLTest, TheHomeViewShowsTheCityFromAbove)
{
    skipWithoutXvfb();
    // OSG's own home looks at a city edge-on (a thin line under the sky); loa-viewer's shows it
    // from the south-west, the whole of it in the frame.
    const ViewerRun run = runViewer("wait 1\nkey tab\nscreenshot home.png\nquit\n",
                                    "-O 'seed=2 blocksX=4 blocksY=4'", 641, 359);
    ASSERT_EQ(run.rc, 0) << run.command << "\n" << run.output;
    osg::ref_ptr<osg::Image> home =
        osgLoA::ImageFile::read(std::string(LOA_BINARY_DIR) + "/test-output/loa-viewer-641x359/home.png");
    ASSERT_TRUE(home.valid());
    // Rows of the frame that show some of the model: edge-on, a thin band (OSG's home: about a
    // tenth of the height); from above, most of the height.
    unsigned rows = 0;
    for (int y = 0; y < home->t(); ++y)
    {
        bool model = false;
        for (int x = 0; x < home->s() && !model; ++x)
            model = !isSky(*home, x, y);
        rows += model ? 1 : 0;
    }
    EXPECT_GT(rows, 359u / 2) << "the city is seen edge-on";
}

TEST(LoaViewerGLTest, AShaderReloadShowsTheCompileLog)
{
    skipWithoutXvfb();
    // A style's fragment stage overridden through OSG_FILE_PATH with a syntax error: F5 rebuilds
    // the style programs from the files and the log names the shader, its stage and the error.
    const std::string dir = loatest::freshDirectory("loa-viewer-shaders");
    {
        std::ofstream out(dir + "/loa_style_photorealistic.frag.glsl");
        out << "#version 450 compatibility\nvec4 loa_styleColor(vec3 a, vec3 b, vec3 c, vec2 d, vec4 e) "
               "{ return this is not glsl; }\n";
    }
    const ViewerRun run =
        runViewer("key f5\nwait 2\nquit\n", "-O 'seed=2 blocksX=2 blocksY=2' --no-panels 2>&1", 320, 240,
                  "OSG_FILE_PATH='" + dir + "'");
    const std::string& output = run.output;
    EXPECT_NE(output.find("shader log:"), std::string::npos) << output;
    EXPECT_NE(output.find("loa_style_photorealistic.frag.glsl"), std::string::npos) << output;
    EXPECT_NE(output.find("fragment"), std::string::npos) << output;
}
