// loa-render: renders a model (or the built-in demo city) headless through EGL to a PNG.
#include "../common/AppSupport.h"

#include <osgLoA/Version>
#include <osgLoA/city/CityCameras>
#include <osgLoA/city/CityGenerator>
#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/render/ShaderLibrary>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/ScenarioLibrary>
#include <osgLoA/util/AtomicFile>
#include <osgLoA/util/ImageFile>
#include <osgLoA/util/JsonString>
#include <osgLoA/util/MachineInfo>
#include <osgLoA/util/SceneStatistics>

#include <osg/Uniform>
#include <osgDB/FileNameUtils>

#include <chrono>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace
{
const char* kHelp = R"(usage: loa-render [MODEL] [options]

Renders MODEL (any file osgDB reads: .osgb, .osgt, .obj, ...) headless through EGL into a PNG.
Without MODEL it renders the built-in demo city.

options:
)";
const char* kHelpOptions = R"(  --size WxH            image size in pixels (default 1280x720)
  --samples N           multisample anti-aliasing with N samples (default 0; at most
                        GL_MAX_SAMPLES, which is 4 on llvmpipe)
  --frames N            render N timed frames after one warm-up frame and report the
                        median and minimum frame time (each frame ends with glFinish)
  --out FILE.png        where to write the image (default out/render.png)
  --stats FILE.json     write frame times, scene statistics, GL renderer and machine as JSON
  --city "K=V ..."      demo city parameters, e.g. "seed=7 blocksX=6 blocksY=4"
                        (keys: see docs/demo-city.md); ignored with MODEL
  --scenario NAME|FILE  draw with LoA transitions: wrap the scene in a LoA node carrying the
                        usage scenario NAME of the library (loa-scenario list) or FILE
                        (.osgt/.osgb/.osgx); the features are drawn in their configurations'
                        graphic styles and composed by the stencil-routed A-buffer
  --abuffer-samples N   A-buffer samples per pixel (default 4; at most GL_MAX_SAMPLES)
  --abuffer-passes N    A-buffer routing passes at most (default 4)
  --program plain       draw with the project's loa_plain GLSL program instead of OSG's
                        fixed-function pipeline
  --gl-info             print the GL context's capabilities and exit
  --version             print the version and exit
  --help                this text

exit status: 0 done, 1 the model or an output could not be read or written or a shader
failed, 2 bad arguments, 3 no usable EGL/OpenGL context.
)";

struct Options
{
    std::string model, out = "out/render.png", stats, city, program, scenario;
    unsigned samplesABuffer = 4, passesABuffer = 4;
    loa::CameraChoice camera;
    int width = 1280, height = 720, samples = 0;
    unsigned frames = 0;
    bool glInfo = false;
};

Options parse(int argc, char** argv)
{
    Options o;
    loa::Args args(argc, argv);
    while (!args.empty())
    {
        const std::string a = args.next();
        loa::exitOnHelpOrVersion(a, "loa-render", std::string(kHelp) + loa::kCameraHelp + kHelpOptions);
        if (loa::parseCameraOption(a, args, o.camera))
            continue;
        else if (a == "--size")
            loa::parseSize(args.value(a), o.width, o.height);
        else if (a == "--samples")
            o.samples = static_cast<int>(loa::parseCount(a, args.value(a), 64));
        else if (a == "--frames")
            o.frames = loa::parseCount(a, args.value(a), 100000);
        else if (a == "--out")
            o.out = args.value(a);
        else if (a == "--stats")
            o.stats = args.value(a);
        else if (a == "--city")
            o.city = args.value(a);
        else if (a == "--scenario")
            o.scenario = args.value(a);
        else if (a == "--abuffer-samples")
            o.samplesABuffer = loa::parseCount(a, args.value(a), 64);
        else if (a == "--abuffer-passes")
            o.passesABuffer = loa::parseCount(a, args.value(a), 63);
        else if (a == "--program")
        {
            o.program = args.value(a);
            if (o.program != "plain")
                throw loa::UsageError("unknown --program '" + o.program + "' (known: plain)");
        }
        else if (a == "--gl-info")
            o.glInfo = true;
        else if (!a.empty() && a[0] == '-')
            throw loa::UsageError("unknown option '" + a + "' (see --help)");
        else if (o.model.empty())
            o.model = a;
        else
            throw loa::UsageError("more than one model given ('" + o.model + "' and '" + a + "')");
    }
    loa::checkCameraOptions(o.camera);
    if (!o.scenario.empty() && !o.program.empty())
        throw loa::UsageError(
            "--scenario and --program exclude each other (a scenario's styles bring their programs)");
    if (o.samplesABuffer == 0 || o.passesABuffer == 0)
        throw loa::UsageError("--abuffer-samples and --abuffer-passes must be at least 1");
    if (osgDB::getLowerCaseFileExtension(o.out) != "png")
        throw loa::UsageError("--out '" + o.out + "' must name a .png file");
    return o;
}

int run(const Options& o)
{
    // The scene first: a missing or malformed model is reported as such, with or without GL.
    const bool glInfoOnly = o.glInfo;
    osg::ref_ptr<osg::Node> scene;
    std::string what;
    double loadMs = 0.0;
    if (!glInfoOnly)
    {
        const auto g0 = std::chrono::steady_clock::now();
        if (!o.model.empty())
        {
            scene = loa::loadModel(o.model);
            what = "'" + o.model + "'";
        }
        else
        {
            osgLoA::CityParameters params;
            try
            {
                params.parse(o.city);
                params.validate();
            }
            catch (const std::invalid_argument& e)
            {
                throw loa::UsageError(std::string("--city: ") + e.what());
            }
            scene = osgLoA::CityGenerator(params).generate();
            what = "the demo city (seed " + std::to_string(params.seed) + ", " +
                   std::to_string(params.blocksX) + "x" + std::to_string(params.blocksY) + " blocks)";
        }
        loadMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - g0).count();
    }
    osgLoA::OffscreenRenderer::Settings settings;
    settings.width = o.width;
    settings.height = o.height;
    settings.samples = o.samples;
    osg::ref_ptr<osgLoA::OffscreenRenderer> renderer = new osgLoA::OffscreenRenderer(settings);
    const osgLoA::GLCapabilities& caps = renderer->getCapabilities();
    if (glInfoOnly)
    {
        std::cout << "EGL:             " << renderer->getContext()->getEGLDescription() << " ("
                  << renderer->getContext()->getPlatform() << " platform)\n"
                  << caps.report() << "multisample-FBO fix applied: "
                  << (renderer->getContext()->appliedMultisampleCoverageFix() ? "yes" : "no") << "\n";
        return loa::kOk;
    }

    if (o.program == "plain")
    {
        osg::StateSet* ss = scene->getOrCreateStateSet();
        ss->setAttributeAndModes(
            osgLoA::ShaderLibrary::createProgram("plain", {"loa_plain.vert.glsl", "loa_plain.frag.glsl"})
                .get());
        ss->addUniform(new osg::Uniform("loa_baseTexture", 0));
    }
    osg::ref_ptr<osgLoA::LoANode> loaNode;
    if (!o.scenario.empty())
    {
        std::string origin;
        osg::ref_ptr<osgLoA::UsageScenario> scenario;
        try
        {
            scenario = osgLoA::ScenarioLibrary::load(o.scenario, &origin);
        }
        catch (const std::exception& e)
        {
            throw std::runtime_error(std::string("--scenario: ") + e.what());
        }
        if (o.samplesABuffer > unsigned(caps.maxSamples))
            throw loa::UsageError("--abuffer-samples " + std::to_string(o.samplesABuffer) +
                                  " exceeds this context's GL_MAX_SAMPLES (" +
                                  std::to_string(caps.maxSamples) + ")");
        loaNode = new osgLoA::LoANode;
        loaNode->setScenario(scenario.get());
        loaNode->addChild(scene.get());
        osgLoA::TransitionRenderer::Settings rs = loaNode->getRenderer()->getSettings();
        rs.samples = o.samplesABuffer;
        rs.maxPasses = o.passesABuffer;
        loaNode->getRenderer()->setSettings(rs);
        try
        {
            loaNode->bind();
        }
        catch (const std::exception& e)
        {
            throw std::runtime_error("scenario '" + o.scenario +
                                     "' cannot be used with this model: " + e.what());
        }
        scene = loaNode;
    }
    renderer->setSceneData(scene.get());
    loa::applyCamera(*renderer, o.camera);

    const osgLoA::SceneStatistics stats = osgLoA::SceneStatistics::collect(*scene);
    osgLoA::FrameTimes times;
    if (o.frames > 0) times = renderer->timeFrames(o.frames);
    osg::ref_ptr<osg::Image> image = renderer->renderImage();
    osgLoA::ImageFile::write(o.out, *image);

    const osgLoA::MachineInfo machine = osgLoA::MachineInfo::query();
    std::cout << "rendered " << what << ": " << stats.summary() << "\n"
              << "view: " << o.camera.describe() << ", " << o.width << "x" << o.height
              << (o.samples ? ", " + std::to_string(o.samples) + "x MSAA" : std::string())
              << (!o.scenario.empty() ? ", scenario " + o.scenario
                  : o.program.empty() ? ", fixed-function pipeline"
                                      : ", program " + o.program)
              << "\n"
              << "GL: " << caps.summary() << " via EGL " << renderer->getContext()->getPlatform() << "\n"
              << "scene built/loaded in " << std::fixed << std::setprecision(1) << loadMs << " ms\n";
    if (o.frames > 0)
        std::cout << "frame time over " << o.frames << " frames (after 1 warm-up, glFinish each): median "
                  << std::setprecision(2) << times.median() << " ms, min " << times.min() << " ms, max "
                  << times.max() << " ms\n";
    if (loaNode)
    {
        const osgLoA::TransitionRenderer::Statistics& st = loaNode->getRenderer()->getStatistics();
        std::cout << "LoA: " << st.drawnFeatures << " features drawn: " << st.sharedDraws
                  << " in one style (shared pass), " << st.depthOnlyDraws << " in transition; "
                  << st.aBufferDraws << " A-buffer draws, " << st.pingPongDraws
                  << " ping-pong draws; A-buffer " << (st.aBuffer ? "used" : "not needed")
                  << ", unsharp masking " << (st.unsharp ? "on" : "off") << "\n";
        const osgLoA::ABufferFrameStatistics ab =
            loaNode->getRenderer()->getABuffer()->getLastFrameStatistics();
        const auto mem = osgLoA::TransitionRenderer::memory(
            o.width, o.height, unsigned(std::max(ab.samples, 1)), unsigned(std::max(ab.memory.layers, 1)),
            st.pingPongBuffer, st.unsharp, loaNode->getRenderer()->getUnsharpSigma());
        std::cout << std::setprecision(1) << "GPU memory of the LoA passes: " << mem.totalBytes() / 1048576.0
                  << " MiB (A-buffer " << mem.aBufferBytes / 1048576.0
                  << " with N=" << std::max(ab.samples, 1) << " x " << std::max(ab.memory.layers, 1)
                  << " layer(s), G-buffer " << mem.geometryBufferBytes / 1048576.0 << ", ping-pong "
                  << mem.pingPongBytes / 1048576.0 << ", unsharp mask " << mem.unsharpBytes / 1048576.0
                  << "); paper 004 formula W H (2N+7)/262144: " << mem.paperBytes / 1048576.0 << " MB\n";
    }
    std::cout << "wrote " << o.out << "\n";

    if (!o.stats.empty())
    {
        std::ostringstream j;
        j << std::setprecision(6) << "{\n  \"tool\": \"loa-render\", \"version\": \"" << osgLoAGetVersion()
          << "\",\n"
          << "  \"model\": \"" << osgLoA::jsonEscape(o.model.empty() ? "demo-city" : o.model) << "\",\n"
          << "  \"camera\": \"" << osgLoA::jsonEscape(o.camera.describe()) << "\",\n"
          << "  \"width\": " << o.width << ", \"height\": " << o.height << ", \"samples\": " << o.samples
          << ",\n"
          << "  \"frames\": " << o.frames << ", \"median_ms\": " << times.median()
          << ", \"min_ms\": " << times.min() << ", \"max_ms\": " << times.max() << ",\n  \"frame_ms\": [";
        for (size_t i = 0; i < times.milliseconds.size(); ++i)
            j << (i ? ", " : "") << times.milliseconds[i];
        j << "],\n  \"scene\": " << stats.toJson() << ",\n  \"gl\": " << caps.toJson() << ",\n"
          << "  \"machine\": {\"cpu\": \"" << osgLoA::jsonEscape(machine.cpuModel)
          << "\", \"cores\": " << machine.cores << ", \"memory_gib\": " << machine.memoryGiB << ", \"os\": \""
          << osgLoA::jsonEscape(machine.os) << "\"}\n}\n";
        osgLoA::AtomicFile::writeText(o.stats, j.str());
        std::cout << "wrote " << o.stats << "\n";
    }
    return loa::kOk;
}
} // namespace

int main(int argc, char** argv)
{
    return loa::runTool("loa-render", [&] { return run(parse(argc, argv)); });
}
