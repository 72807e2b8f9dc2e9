// Shared by the command-line tools: strict argument parsing and scene loading.
#ifndef OSGLOA_APPS_APPSUPPORT_H
#define OSGLOA_APPS_APPSUPPORT_H 1

#include <osgLoA/city/CityCameras>
#include <osgLoA/city/CityParameters>
#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/semantics/ClassificationRuleSet>

#include <osg/Node>
#include <osg/Texture2D>
#include <osg/Vec3d>

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace loa
{

/** A usage error: printed as "<tool>: error: <what>" with exit status 2. */
struct UsageError : std::runtime_error
{
    using std::runtime_error::runtime_error;
};

/** Exit codes shared by every tool. */
enum ExitCode
{
    kOk = 0,
    kFailure = 1,   ///< the work itself failed (unreadable model, write error, shader error)
    kUsage = 2,     ///< bad arguments
    kNoContext = 3, ///< no usable EGL / OpenGL
};

/** Puts the folder holding our osgDB plugins (osgPlugins-<version>/) beside the executable on
 *  osgDB's library path: the build tree's lib/ and the install prefix's libdir, where they
 *  exist. runTool calls it first, so no tool needs OSG_LIBRARY_PATH. */
void findPlugins();
/** Sends every OSG notification to stderr (stdout carries the tools' data), a message repeated
 *  line after line shown twice and then counted; runTool calls it. */
void notifyToStderr();
/** Prints the count of a repeated notification still pending (runTool does at the end). */
void flushNotices();
/** --verbose: OSG's and other libraries' notices and info shown too (collapsed as warnings
 *  are); without it they are counted, and a tool that fails says how many it hid. */
void setVerbose(bool verbose);

/** Runs a tool's body and maps exceptions to one line "<tool>: error: <what>" on stderr and
 *  the exit codes above: UsageError and std::invalid_argument 2, HeadlessContextError 3,
 *  anything else 1. */
int runTool(const char* tool, const std::function<int()>& body);
/** As runTool, in two phases: std::invalid_argument is a bad argument (2) only while parse
 *  runs; from work it is a problem of the data the tool was given (a model, a texture, a
 *  scenario file), exit 1. UsageError is 2 in either phase. */
int runTool(const char* tool, const std::function<void()>& parse, const std::function<int()>& work);

/** "WxH" with 1 <= W, H <= 16384. */
void parseSize(const std::string& text, int& width, int& height);
/** "X,Y,Z" of finite numbers. */
osg::Vec3d parseVec3(const std::string& option, const std::string& text);
/** A non-negative integer up to max. */
unsigned parseCount(const std::string& option, const std::string& text, unsigned max);

/** Loads a model file with osgDB, or throws std::runtime_error with one clear sentence. */
osg::ref_ptr<osg::Node> loadModel(const std::string& path);
/** loadModel with an osgDB option string for the model's reader ("" for none). */
osg::ref_ptr<osg::Node> loadModel(const std::string& path, const std::string& readerOptions);

/** Loads the models (reader options for each) into one scene: a single model as it is, several
 *  under one group, each in a ProxyNode naming its file. keepImageNames: each through
 *  loadModelKeepingImageNames (the batch tools). */
osg::ref_ptr<osg::Node> loadModels(const std::vector<std::string>& paths, const std::string& readerOptions,
                                   bool keepImageNames = false);

/** The models as one label: "a.osgb + b.osgb" ("" for none). */
std::string modelLabel(const std::vector<std::string>& models);

/** loadModels, or without models the demo city generated from readerOptions (CityParameters
 *  syntax; a bad parameter is a UsageError). what: "'a.osgb + b.osgb'" or "the demo city (seed
 *  S, WxH blocks)", for messages. */
osg::ref_ptr<osg::Node> loadModelsOrDemoCity(const std::vector<std::string>& paths,
                                             const std::string& readerOptions, std::string& what);

/** How the batch tools name a texture in messages: its image's file name, else the image's name,
 *  else "texture 'NAME'", else "texture #index+1 (unnamed)". */
std::string textureLabel(const osg::Texture2D& texture, std::size_t index);

/** "WIDTHxHEIGHT" of an image. */
std::string imageSizeText(const osg::Image& image);

/** loadModel with the reader options `readerOptions` (osgDB option string) and, for OSG's own
 *  formats (.osgb/.osgt/.osgx), ForceReadingImage: an image file that cannot be read then leaves
 *  an empty image carrying its file name instead of vanishing (the batch tools report it). */
osg::ref_ptr<osg::Node> loadModelKeepingImageNames(const std::string& path, const std::string& readerOptions);

/** Applies --camera NAME or --eye/--center/--up, or frames the scene. */
struct CameraChoice
{
    std::string name;
    bool haveEye = false, haveCenter = false, haveUp = false;
    osg::Vec3d eye, center, up = osg::Vec3d(0, 0, 1);
    std::string describe() const;
};
void applyCamera(osgLoA::OffscreenRenderer& renderer, const CameraChoice& choice);
/** The pose applyCamera gives a renderer of this aspect ratio showing scene (for tools that
 *  evaluate from the camera without rendering). Throws std::runtime_error for an empty scene
 *  when no camera is named or given. */
osgLoA::CameraPose cameraPose(const CameraChoice& choice, osg::Node& scene, double aspect);
/** Throws UsageError for contradictory camera options, an --eye equal to --center, and an --up
 *  parallel to the view direction. */
void checkCameraOptions(const CameraChoice& choice);

/** The classification every tool shares (--rules, --rules-only, --override;
 *  ClassificationRuleSet::assemble). */
struct RulesChoice
{
    std::vector<std::string> files;
    bool only = false;
    bool overrideModelData = false;
    /** The rule set; throws std::runtime_error naming an unreadable file. */
    osg::ref_ptr<osgLoA::ClassificationRuleSet> assemble() const;
};

} // namespace loa

#endif
