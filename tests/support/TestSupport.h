// Helpers shared by the tests.
#ifndef OSGLOA_TESTS_TESTSUPPORT_H
#define OSGLOA_TESTS_TESTSUPPORT_H 1

#include "BoxGeode.h"

#include <osgLoA/filtering/GpuFilterEngine>
#include <osgLoA/render/HeadlessContext>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Image>
#include <osg/Node>

#include <string>

namespace loatest
{

/** The bytes of a file ("" when it cannot be read). */
std::string fileBytes(const std::string& path);
/** A Geometry named `name`: one triangle (0,0,0) (1,0,0) (0,1,0), drawn by DrawArrays. */
osg::ref_ptr<osg::Geometry> triangle(const std::string& name);
/** Writes a Geode holding one textured triangle ("tri", a 4x4 RGBA image of 200s named tex.png,
 *  inline) to path with osgDB; returns the file's bytes. */
std::string writeTexturedTriangle(const std::string& path);
/** text with the first `from` replaced by `to` (a test failure when `from` is missing). */
std::string replaced(std::string text, const std::string& from, const std::string& to);

/** A w x h crop at (x0, y0) of a skimage photograph (data/cache/python3-skimage, extracted by
 *  scripts/fetch-test-data, or ../shared/data/images), or an empty image when it is missing. */
osgLoA::FilterImage photoCrop(const std::string& name, int x0, int y0, int w, int h);

/** A fresh empty directory under the build's test-output folder. */
std::string freshDirectory(const std::string& name);

/** Sets OSG_FILE_PATH and makes osgDB re-read it. */
void setFilePath(const std::string& value);

/** Runs a shell command; returns its exit status and fills stdout+stderr. */
int run(const std::string& command, std::string& output);

/** Environment assignments to put before a stock OSG program (osgconv, osgviewer) that loads
 *  our plugins: empty in a normal build; in a sanitized one (OSGLOA_SANITIZE) the ASan runtime
 *  preloaded, which an uninstrumented program needs to load instrumented plugins, and leak
 *  detection off (the leaks would be OSG's own). Ends with a space when not empty. */
std::string stockToolEnvironment();

/** The node written to .osgt text (the whole graph, user values included). */
std::string toOsgt(const osg::Node& node);

/** Reads the golden PNG tests/data/golden/NAME; when LOA_UPDATE_GOLDENS=1 writes actual
 *  there instead (scripts/update-goldens) and returns null. */
osg::ref_ptr<osg::Image> goldenOrUpdate(const std::string& name, const osg::Image& actual);

/** A one-colour quad over x in [x0, x1], y in [-halfHeight, halfHeight] at z = -distance, normal
 *  +z (the A-buffer tests' layers under an orthographic view). */
osg::ref_ptr<osg::Geometry> depthQuad(float x0, float x1, float halfHeight, float distance,
                                      const osg::Vec4& color);

/** A gtest parameter as a test name: '-' becomes '_' (style names such as "hybrid-toon"). */
std::string paramName(const std::string& param);

/** Compares an abstraction frame with the golden NAME.png at the bars of the abstraction goldens
 *  (a channel may differ by 16/255, the mean by 1/255, 1 % of the pixels fail: llvmpipe builds
 *  round filtering differently and the image stages turn a flipped edge pixel into a changed
 *  Kuwahara sector or edge decision over a few pixels). Saves the failure; with
 *  LOA_UPDATE_GOLDENS=1 writes the golden and returns false with `skipped` set. */
bool matchesAbstractionGolden(const std::string& name, const osg::Image& actual, std::string& summary,
                              bool& skipped);

/** Writes NAME-actual.png and NAME-diff.png beside the build for a failed comparison. */
void saveFailure(const std::string& name, const osg::Image& actual, const osg::Image* difference);

// boxGeode(minimum, maximum): BoxGeode.h.

/** A headless context made current and a GpuFilterEngine on it, for the filter GL tests; the
 *  destructor frees the engine's GL objects and releases the context. Throws std::runtime_error
 *  when no EGL context can be made. */
struct GpuFilterFixture
{
    osg::ref_ptr<osgLoA::HeadlessContext> context;
    osg::ref_ptr<osgLoA::GpuFilterEngine> engine;
    GpuFilterFixture();
    ~GpuFilterFixture();
    GpuFilterFixture(const GpuFilterFixture&) = delete;
    GpuFilterFixture& operator=(const GpuFilterFixture&) = delete;
};

} // namespace loatest

#endif
