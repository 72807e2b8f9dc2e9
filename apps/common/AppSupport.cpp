#include "AppSupport.h"

#include <osgLoA/Version>
#include <osgLoA/city/CityCameras>

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
 *  (JSON, PPM, a scenario) would get diagnostics inside it. Every level goes to stderr. */
class StderrNotifyHandler : public osg::NotifyHandler
{
public:
    void notify(osg::NotifySeverity, const char* message) override { std::fputs(message, stderr); }
};
} // namespace

void notifyToStderr()
{
    osg::setNotifyHandler(new StderrNotifyHandler);
}

int runTool(const char* tool, const std::function<int()>& body)
{
    notifyToStderr();
    findPlugins();
    try
    {
        return body();
    }
    catch (const UsageError& e)
    {
        std::cerr << tool << ": error: " << e.what() << "\n";
        return kUsage;
    }
    catch (const osgLoA::HeadlessContextError& e)
    {
        std::cerr << tool << ": error: " << e.what() << "\n";
        return kNoContext;
    }
    catch (const std::invalid_argument& e)
    {
        std::cerr << tool << ": error: " << e.what() << "\n";
        return kUsage;
    }
    catch (const std::exception& e)
    {
        std::cerr << tool << ": error: " << e.what() << "\n";
        return kFailure;
    }
}

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

Args::Args(int argc, char** argv)
{
    for (int i = 1; i < argc; ++i)
        _words.emplace_back(argv[i]);
}

std::string Args::next()
{
    std::string w = _words.front();
    _words.erase(_words.begin());
    return w;
}

std::string Args::value(const std::string& option)
{
    if (_words.empty()) throw UsageError(option + " needs a value");
    return next();
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
    const std::string ext = osgDB::getLowerCaseFileExtension(path);
    osgDB::ReaderWriter* rw = osgDB::Registry::instance()->getReaderWriterForExtension(ext);
    if (!rw)
        throw std::runtime_error("cannot read '" + path + "': no osgDB plugin reads '." + ext + "' files");
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
    return rr.getNode();
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

const char* const kCameraHelp =
    R"(  --camera NAME         a named view: street, oblique, top, horizon (computed from the
                        model's buildings and streets; see docs/demo-city.md)
  --eye X,Y,Z --center X,Y,Z [--up X,Y,Z]
                        an explicit look-at camera (up defaults to 0,0,1)
                        (no camera option: frame the model's bounding sphere)
)";

void exitOnHelpOrVersion(const std::string& a, const char* tool, const std::string& help)
{
    if (a == "--help" || a == "-h")
    {
        std::cout << help;
        std::exit(kOk);
    }
    if (a == "--version")
    {
        std::cout << tool << " " << osgLoAGetVersion() << "\n";
        std::exit(kOk);
    }
}

bool parseCameraOption(const std::string& a, Args& args, CameraChoice& c)
{
    if (a == "--camera")
    {
        c.name = args.value(a);
        if (!osgLoA::CityCameras::isName(c.name))
            throw UsageError("unknown camera '" + c.name + "' (known: street, oblique, top, horizon)");
    }
    else if (a == "--eye")
        c.eye = parseVec3(a, args.value(a)), c.haveEye = true;
    else if (a == "--center")
        c.center = parseVec3(a, args.value(a)), c.haveCenter = true;
    else if (a == "--up")
        c.up = parseVec3(a, args.value(a)), c.haveUp = true;
    else
        return false;
    return true;
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

bool parseReaderOption(const std::string& a, Args& args, std::string& readerOptions)
{
    if (a != "-O" && a != "--options") return false;
    readerOptions += (readerOptions.empty() ? "" : " ") + args.value(a);
    return true;
}

const char* const kReaderOptionsHelp =
    R"(  -O TEXT, --options TEXT
                        options for MODEL's reader (an osgDB option string; repeatable), e.g.
                        "lod=1 theme=summer" for CityGML, "lod=2.2" for CityJSON
)";

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
void takeModelArgument(const std::string& a, std::string& model)
{
    if (!a.empty() && a[0] == '-') throw UsageError("unknown option '" + a + "' (see --help)");
    if (!model.empty()) throw UsageError("more than one model given ('" + model + "' and '" + a + "')");
    model = a;
}

void takeModelArguments(const std::string& a, std::vector<std::string>& models, std::string& label)
{
    if (!a.empty() && a[0] == '-') throw UsageError("unknown option '" + a + "' (see --help)");
    models.push_back(a);
    label += (label.empty() ? "" : " + ") + a;
}

osg::ref_ptr<osg::Node> loadModels(const std::vector<std::string>& paths, const std::string& readerOptions)
{
    if (paths.size() == 1) return loadModel(paths.front(), readerOptions);
    // Several models: one scene, each model under a ProxyNode that names its file, so that the
    // classifier treats each model's top node as a file, not as a name for what is in it.
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    scene->setName("models");
    for (const std::string& path : paths)
    {
        osg::ref_ptr<osg::ProxyNode> proxy = new osg::ProxyNode;
        proxy->setName(osgDB::getSimpleFileName(path));
        proxy->setFileName(0, path);
        proxy->addChild(loadModel(path, readerOptions).get());
        scene->addChild(proxy.get());
    }
    return scene;
}
} // namespace loa

namespace loa
{

const char* const kRulesHelp =
    R"(  --rules FILE          classification rules (.osgt/.osgb/.osgx holding an
                        osgLoA::ClassificationRuleSet) tried before the built-in rules;
                        repeatable, the first file's rules first
  --rules-only FILE     classify with FILE's rules instead of the built-in ones (repeatable)
  --override            let the rules replace types the model data gives (never a user's)
)";

osg::ref_ptr<osgLoA::ClassificationRuleSet> RulesChoice::assemble() const
{
    return osgLoA::ClassificationRuleSet::assemble(files, only, overrideModelData);
}

bool parseRulesOption(const std::string& a, Args& args, RulesChoice& choice)
{
    if (a == "--rules" || a == "--rules-only")
    {
        const bool only = a == "--rules-only";
        if (!choice.files.empty() && choice.only != only)
            throw UsageError(
                "--rules adds to the built-in rules and --rules-only replaces them: use one of them");
        choice.only = only;
        choice.files.push_back(args.value(a));
        return true;
    }
    if (a == "--override")
    {
        choice.overrideModelData = true;
        return true;
    }
    return false;
}

} // namespace loa
