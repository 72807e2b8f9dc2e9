#include "AppSupport.h"

#include <osgLoA/Version>
#include <osgLoA/city/CityCameras>
#include <osgLoA/city/CityGenerator>
#include <osgLoA/util/BoundedObjectReader>
#include <osgLoA/util/ModelValidation>

#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>
#include <osgDB/Registry>

#include <osg/Notify>
#include <osg/ProxyNode>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <mutex>
#include <new>
#include <sstream>
#include <unistd.h>

namespace loa
{

void findPlugins()
{
    // The executable's folder (Linux: /proc/self/exe), then the lib folders beside it that hold
    // our osgPlugins-<version>/: the build tree's and the install prefix's.
    char buffer[4096];
    const ssize_t n = ::readlink("/proc/self/exe", buffer, sizeof(buffer) - 1);
    if (n <= 0) return;
    buffer[n] = '\0';
    const std::string bin = osgDB::getFilePath(buffer);
    osgDB::FilePathList& paths = osgDB::Registry::instance()->getLibraryFilePathList();
    for (const char* relative : {LOA_BUILD_BIN_TO_LIB, LOA_BIN_TO_LIB})
    {
        const std::string lib = osgDB::getRealPath(bin + "/" + relative);
        if (osgDB::fileType(lib + "/" + LOA_PLUGIN_DIR_NAME) != osgDB::DIRECTORY) continue;
        if (std::find(paths.begin(), paths.end(), lib) == paths.end()) paths.push_front(lib);
    }
}

namespace
{
/** OSG's standard handler writes NOTICE and INFO to stdout: a tool that writes data there
 *  (JSON, PPM, a scenario) would get diagnostics inside it. Every level goes to stderr, and a
 *  message repeated line after line is shown twice, then counted (OSG's text reader once wrote
 *  43,019 identical "InputIterator::checkStream()" lines before one error).
 *
 *  Warnings and errors (ours: a dropped drawable, an unreadable texture; OSG's: a file it cannot
 *  read) are always shown. Notices and info, third-party chatter for the user of a tool, are
 *  counted and shown only with --verbose (setVerbose); a tool that fails says how many it hid. */
class StderrNotifyHandler : public osg::NotifyHandler
{
public:
    void notify(osg::NotifySeverity severity, const char* message) override
    {
        std::lock_guard<std::mutex> lock(_mutex);
        if (severity > osg::WARN && !_verbose)
        {
            ++_hidden;
            return;
        }
        if (_last == message)
        {
            if (++_repeats <= 1) std::fputs(message, stderr);
            return;
        }
        flushLocked();
        _last = message;
        std::fputs(message, stderr);
    }
    void flush()
    {
        std::lock_guard<std::mutex> lock(_mutex);
        flushLocked();
    }
    void setVerbose(bool verbose)
    {
        std::lock_guard<std::mutex> lock(_mutex);
        _verbose = verbose;
    }
    unsigned long hidden()
    {
        std::lock_guard<std::mutex> lock(_mutex);
        return _hidden;
    }

private:
    void flushLocked()
    {
        if (_repeats > 1) std::fprintf(stderr, "  (the line above %lu more times)\n", _repeats - 1);
        _repeats = 0;
        _last.clear();
    }
    std::mutex _mutex;
    std::string _last;
    unsigned long _repeats = 0;
    unsigned long _hidden = 0;
    bool _verbose = false;
};

osg::ref_ptr<StderrNotifyHandler>& stderrHandler()
{
    static osg::ref_ptr<StderrNotifyHandler> handler;
    return handler;
}
} // namespace

void flushNotices()
{
    if (stderrHandler().valid()) stderrHandler()->flush();
}

void setVerbose(bool verbose)
{
    if (!stderrHandler().valid()) return;
    stderrHandler()->setVerbose(verbose);
    // OSG's own level (OSG_NOTIFY_LEVEL, NOTICE by default) decides what reaches the handler:
    // --verbose lets INFO through as well, unless the environment asked for more.
    if (verbose && osg::getNotifyLevel() < osg::INFO) osg::setNotifyLevel(osg::INFO);
}

namespace
{
/** Before a tool's error line: pending repeat counts, and how many notices --verbose would show. */
void flushBeforeError(const char* tool)
{
    flushNotices();
    if (stderrHandler().valid() && stderrHandler()->hidden() > 0)
        std::cerr << tool << ": (" << stderrHandler()->hidden()
                  << " notices from the libraries were hidden; --verbose shows them)\n";
}
} // namespace

void notifyToStderr()
{
    stderrHandler() = new StderrNotifyHandler;
    osg::setNotifyHandler(stderrHandler().get());
}

namespace
{
int runBody(const char* tool, const std::function<int()>& body);
}

int runTool(const char* tool, const std::function<int()>& body)
{
    notifyToStderr();
    findPlugins();
    const int status = runBody(tool, body);
    flushNotices();
    return status;
}

namespace
{
int runBody(const char* tool, const std::function<int()>& body)
{
    try
    {
        return body();
    }
    catch (const UsageError& e)
    {
        flushBeforeError(tool); // counted repeats before the error line
        std::cerr << tool << ": error: " << e.what() << "\n";
        return kUsage;
    }
    catch (const osgLoA::HeadlessContextError& e)
    {
        flushBeforeError(tool); // counted repeats before the error line
        std::cerr << tool << ": error: " << e.what() << "\n";
        return kNoContext;
    }
    catch (const std::invalid_argument& e)
    {
        flushBeforeError(tool); // counted repeats before the error line
        std::cerr << tool << ": error: " << e.what() << "\n";
        return kUsage;
    }
    catch (const std::bad_alloc&)
    {
        // A bare "std::bad_alloc" named nothing: say what it means and where the limits are.
        flushBeforeError(tool); // counted repeats before the error line
        std::cerr << tool
                  << ": error: out of memory: an input is larger than this machine can hold, or states sizes "
                     "it does not have (reader limits: docs/reliability.md)\n";
        return kFailure;
    }
    catch (const std::exception& e)
    {
        flushBeforeError(tool); // counted repeats before the error line
        std::cerr << tool << ": error: " << e.what() << "\n";
        return kFailure;
    }
}
} // namespace

int runTool(const char* tool, const std::function<void()>& parse, const std::function<int()>& work)
{
    return runTool(tool,
                   [&]
                   {
                       parse();
                       try
                       {
                           return work();
                       }
                       catch (const UsageError&)
                       {
                           throw;
                       }
                       catch (const osgLoA::HeadlessContextError&)
                       {
                           throw;
                       }
                       catch (const std::invalid_argument& e)
                       {
                           throw std::runtime_error(e.what());
                       }
                   });
}

void parseSize(const std::string& text, int& width, int& height)
{
    const auto x = text.find('x');
    std::size_t u1 = 0, u2 = 0;
    long w = 0, h = 0;
    try
    {
        if (x == std::string::npos) throw std::invalid_argument("no x");
        const std::string a = text.substr(0, x), b = text.substr(x + 1);
        w = std::stol(a, &u1);
        h = std::stol(b, &u2);
        if (u1 != a.size() || u2 != b.size()) throw std::invalid_argument("trailing");
    }
    catch (const std::exception&)
    {
        throw UsageError("--size '" + text + "' is not WIDTHxHEIGHT (e.g. 1280x720)");
    }
    if (w < 1 || h < 1 || w > 16384 || h > 16384)
        throw UsageError("--size '" + text + "' is outside 1x1 .. 16384x16384");
    width = static_cast<int>(w);
    height = static_cast<int>(h);
}

osg::Vec3d parseVec3(const std::string& option, const std::string& text)
{
    std::string s = text;
    for (char& c : s)
        if (c == ',') c = ' ';
    std::istringstream in(s);
    double v[3];
    std::string rest;
    if (!(in >> v[0] >> v[1] >> v[2]) || (in >> rest) || !std::isfinite(v[0]) || !std::isfinite(v[1]) ||
        !std::isfinite(v[2]))
        throw UsageError(option + " '" + text + "' is not X,Y,Z");
    return osg::Vec3d(v[0], v[1], v[2]);
}

unsigned parseCount(const std::string& option, const std::string& text, unsigned max)
{
    std::size_t used = 0;
    long long v = -1;
    try
    {
        v = std::stoll(text, &used);
    }
    catch (const std::exception&)
    {
        used = 0;
    }
    if (used != text.size() || v < 0 || v > static_cast<long long>(max))
        throw UsageError(option + " '" + text + "' is not an integer in 0.." + std::to_string(max));
    return static_cast<unsigned>(v);
}

osg::ref_ptr<osg::Node> loadModel(const std::string& path)
{
    if (!osgDB::fileExists(path))
    {
        // Pseudo-loaders (demo.loacity) read names that are not files.
        osgDB::ReaderWriter::ReadResult rr =
            osgDB::Registry::instance()->readNode(path, osgDB::Registry::instance()->getOptions());
        if (rr.validNode()) return rr.getNode();
        throw std::runtime_error("cannot read '" + path + "': no such file");
    }
    if (osgDB::fileType(path) == osgDB::DIRECTORY)
        throw std::runtime_error("cannot read '" + path + "': it is a directory");
    if (osgDB::fileType(path) != osgDB::REGULAR_FILE)
        throw std::runtime_error("cannot read '" + path + "': not a regular file (a device or FIFO)");
    const std::string ext = osgDB::getLowerCaseFileExtension(path);
    osgDB::ReaderWriter* rw = osgDB::Registry::instance()->getReaderWriterForExtension(ext);
    if (!rw)
        throw std::runtime_error("cannot read '" + path + "': no osgDB plugin reads '." + ext + "' files");
    osg::ref_ptr<osg::Node> node;
    if (osgLoA::BoundedObjectReader::handlesExtension(ext))
    {
        // OSG's own .osgt/.osgb readers loop forever on a truncated or bit-flipped file and
        // trust the sizes it states: read with the work bounded by the file's size instead.
        try
        {
            node = osgLoA::BoundedObjectReader::readNodeFile(path, osgDB::Registry::instance()->getOptions());
        }
        catch (const osgLoA::MalformedFileError& e)
        {
            throw std::runtime_error("cannot read '" + path + "': " + e.what());
        }
    }
    else
    {
        osgDB::ReaderWriter::ReadResult rr = rw->readNode(path, osgDB::Registry::instance()->getOptions());
        if (!rr.validNode())
        {
            std::string why = rr.message();
            if (why.empty())
                why = rr.status() == osgDB::ReaderWriter::ReadResult::FILE_NOT_HANDLED
                          ? "the '" + ext + "' plugin does not handle it"
                          : "the file is malformed or holds no scene";
            throw std::runtime_error("cannot read '" + path + "': " + why);
        }
        node = rr.getNode();
    }
    // Indices past their arrays, images that state more than they hold: dropped with warnings.
    osgLoA::ModelValidation::validate(*node, path);
    return node;
}

std::string CameraChoice::describe() const
{
    std::ostringstream o;
    if (!name.empty())
        o << "camera '" << name << "'";
    else if (haveEye)
        o << "eye " << eye.x() << "," << eye.y() << "," << eye.z() << " centre " << center.x() << ","
          << center.y() << "," << center.z();
    else
        o << "framing the bounding sphere";
    return o.str();
}

void applyCamera(osgLoA::OffscreenRenderer& renderer, const CameraChoice& choice)
{
    checkCameraOptions(choice);
    if (choice.name.empty() && !choice.haveEye)
    {
        renderer.frameScene();
        return;
    }
    const auto& s = renderer.getSettings();
    const osgLoA::CameraPose pose =
        cameraPose(choice, *renderer.getSceneData(), static_cast<double>(s.width) / s.height);
    if (!choice.name.empty()) renderer.setPerspective(pose.fovy);
    renderer.setViewMatrixAsLookAt(pose.eye, pose.center, pose.up);
}

osgLoA::CameraPose cameraPose(const CameraChoice& choice, osg::Node& scene, double aspect)
{
    if (!choice.name.empty()) return osgLoA::CityCameras::compute(choice.name, scene, aspect);
    osgLoA::CameraPose pose;
    if (choice.haveEye)
    {
        pose.eye = choice.eye, pose.center = choice.center, pose.up = choice.up;
        return pose;
    }
    const osg::BoundingSphere bs = scene.getBound();
    if (!bs.valid()) throw std::runtime_error("the model is empty: no camera can frame it");
    osgLoA::OffscreenRenderer::framingPose(bs, pose.fovy, aspect, pose.eye, pose.center, pose.up);
    return pose;
}

void checkCameraOptions(const CameraChoice& c)
{
    if (c.haveEye != c.haveCenter) throw UsageError("--eye and --center go together");
    if (c.haveUp && !c.haveEye) throw UsageError("--up needs --eye and --center");
    if (!c.name.empty() && c.haveEye) throw UsageError("--camera and --eye/--center exclude each other");
    if (c.haveEye && (c.center - c.eye).length2() == 0.0) throw UsageError("--eye and --center must differ");
    if (c.haveEye && ((c.center - c.eye) ^ c.up).length2() == 0.0)
        throw UsageError("--up must not be parallel to the view direction");
}

} // namespace loa

namespace loa
{
osg::ref_ptr<osg::Node> loadModel(const std::string& path, const std::string& readerOptions)
{
    if (readerOptions.find_first_not_of(' ') != std::string::npos)
    {
        osg::ref_ptr<osgDB::Options> options =
            osgDB::Registry::instance()->getOptions()
                ? static_cast<osgDB::Options*>(
                      osgDB::Registry::instance()->getOptions()->clone(osg::CopyOp()))
                : new osgDB::Options;
        options->setOptionString(readerOptions);
        osgDB::Registry::instance()->setOptions(options.get());
    }
    return loadModel(path);
}

osg::ref_ptr<osg::Node> loadModelKeepingImageNames(const std::string& path, const std::string& readerOptions)
{
    const std::string ext = osgDB::getLowerCaseFileExtension(path);
    std::string optionString = readerOptions;
    if (ext == "osgb" || ext == "osgt" || ext == "osgx")
        optionString += (optionString.empty() ? "" : " ") + std::string("ForceReadingImage");
    return loadModel(path, optionString);
}
} // namespace loa

namespace loa
{
std::string textureLabel(const osg::Texture2D& texture, std::size_t index)
{
    const osg::Image* image = texture.getImage();
    if (image && !image->getFileName().empty()) return image->getFileName();
    if (image && !image->getName().empty()) return image->getName();
    if (!texture.getName().empty()) return "texture '" + texture.getName() + "'";
    return "texture #" + std::to_string(index + 1) + " (unnamed)";
}

std::string imageSizeText(const osg::Image& image)
{
    return std::to_string(image.s()) + "x" + std::to_string(image.t());
}
} // namespace loa

namespace loa
{
osg::ref_ptr<osg::Node> loadModels(const std::vector<std::string>& paths, const std::string& readerOptions,
                                   bool keepImageNames)
{
    const auto load = [&](const std::string& path) {
        return keepImageNames ? loadModelKeepingImageNames(path, readerOptions)
                              : loadModel(path, readerOptions);
    };
    if (paths.size() == 1) return load(paths.front());
    // Several models: one scene, each model under a ProxyNode that names its file, so that the
    // classifier treats each model's top node as a file, not as a name for what is in it.
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    scene->setName("models");
    for (const std::string& path : paths)
    {
        osg::ref_ptr<osg::ProxyNode> proxy = new osg::ProxyNode;
        proxy->setName(osgDB::getSimpleFileName(path));
        proxy->setFileName(0, path);
        proxy->addChild(load(path).get());
        scene->addChild(proxy.get());
    }
    return scene;
}
std::string modelLabel(const std::vector<std::string>& models)
{
    std::string label;
    for (const std::string& m : models)
        label += (label.empty() ? "" : " + ") + m;
    return label;
}

osg::ref_ptr<osg::Node> loadModelsOrDemoCity(const std::vector<std::string>& paths,
                                             const std::string& readerOptions, std::string& what)
{
    if (!paths.empty())
    {
        what = "'" + modelLabel(paths) + "'";
        return loadModels(paths, readerOptions);
    }
    osgLoA::CityParameters params;
    try
    {
        params.parse(readerOptions);
        params.validate();
    }
    catch (const std::invalid_argument& e)
    {
        throw UsageError(std::string("-O (demo city parameters): ") + e.what());
    }
    what = "the demo city (seed " + std::to_string(params.seed) + ", " + std::to_string(params.blocksX) +
           "x" + std::to_string(params.blocksY) + " blocks)";
    return osgLoA::CityGenerator(params).generate();
}
} // namespace loa

namespace loa
{

osg::ref_ptr<osgLoA::ClassificationRuleSet> RulesChoice::assemble() const
{
    return osgLoA::ClassificationRuleSet::assemble(files, only, overrideModelData);
}

} // namespace loa
