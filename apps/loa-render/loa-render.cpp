// loa-render: renders a model (or the built-in demo city) headless through EGL to a PNG.
#include "../common/AppSupport.h"
#include "../common/CommandLine.h"

#include <osgLoA/Version>
#include <osgLoA/abstraction/AbstractionNode>
#include <osgLoA/abstraction/AbstractionStyleCatalog>
#include <osgLoA/city/CityCameras>
#include <osgLoA/city/CityGenerator>
#include <osgLoA/compositing/StencilRoutedABuffer>
#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/render/ShaderLibrary>
#include <osgLoA/semantics/FeatureClassifier>
#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/styles/FixedFunctionUniforms>
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/ScenarioLibrary>
#include <osgLoA/util/AtomicFile>
#include <osgLoA/util/ImageFile>
#include <osgLoA/util/JsonString>
#include <osgLoA/util/MachineInfo>
#include <osgLoA/util/SceneStatistics>

#include <osg/Uniform>
#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace
{
const char* kDescription =
    R"(Renders MODEL (any file osgDB reads: .osgb, .osgt, .obj, .cityjson, .gml, .osm, ...) headless
through EGL into a PNG. Several MODELs are drawn as one scene. Without MODEL it renders the
built-in demo city (parameters with -O).
)";
const char* kFooter =
    R"(exit status: 0 done, 1 the model or an output could not be read or written or a shader
failed, 2 bad arguments, 3 no usable EGL/OpenGL context.
)";

struct Options
{
    std::vector<std::string> models; ///< MODEL arguments (several: one scene)
    std::string model, out = "out/render.png", stats, program, scenario, style;
    std::string focus, focusObject, focusWorld, focusRadii, readerOptions;
    bool listStyles = false;
    unsigned samplesABuffer = 4, passesABuffer = 4;
    bool fuseStyles = true;
    osgLoA::OrderIndependentTransparency::Method oit = osgLoA::OrderIndependentTransparency::STENCIL_ROUTED;
    bool oitAuto = false;
    bool oitGiven = false; ///< --oit named a method: stencil-routed is then used even where approximate
    loa::CameraChoice camera;
    loa::RulesChoice rules;
    int width = loa::kDefaultWidth, height = loa::kDefaultHeight, samples = 0;
    unsigned frames = 0;
    bool glInfo = false;
};

Options parse(int argc, char** argv)
{
    Options o;
    loa::CommandLine cl("loa-render", "loa-render [MODEL...] [options]", kDescription);
    CLI::App& app = cl.app();
    loa::addModels(app, o.models, "the models to draw as one scene (default: the demo city)");
    loa::addReaderOptions(app, o.readerOptions);
    loa::addScenario(
        app, o.scenario,
        "draw with LoA transitions: wrap the scene in a LoA node carrying the usage scenario NAME of "
        "the library (loa-scenario list) or FILE (.osgt/.osgb/.osgx); the features are drawn in their "
        "configurations' graphic styles and composed by the stencil-routed A-buffer. The model's own "
        "features keep their types; the rest are classified by the rules, as the loa plugin does. "
        "Styles that need per-texture data are prepared first, once per model (abstract: textures "
        "filtered per mip level into the filter cache, $OSGLOA_FILTER_CACHE or "
        "~/.cache/osgLoA/filters; palette: palettes), with progress lines on stderr");
    loa::addRules(app, o.rules);
    loa::addCamera(app, o.camera);
    loa::addSize(app, o.width, o.height, "the image");
    loa::addOutFile(app, o.out, "the PNG image to write (default out/render.png)");
    app.add_option(
           "--stats", o.stats,
           "write frame times, scene statistics, GL renderer and machine as JSON; with --scenario or a "
           "LoA --style also the classified features per type, counted as loa-classify counts them")
        ->type_name("FILE.json")
        ->group(loa::kGroupOutput);
    app.add_option(
           "--style", o.style,
           "draw in one graphic style: a style of --list-styles, or an abstraction style file "
           "(.osgt/.osgb/.osgx holding an osgLoA::AbstractionStyle). Image-space and hybrid styles "
           "(papers 001, 002) render through an abstraction node; the other styles through a LoA node "
           "whose scenario draws every feature in that style")
        ->type_name("NAME|FILE");
    app.add_flag("--list-styles", o.listStyles,
                 "print every graphic style, one a line: its name and what it draws, and exit");
    app.add_option(
           "--focus", o.focus,
           "focus point of adaptive styles in normalized window coordinates ((0,0) bottom left; default "
           "the style's, usually 0.5,0.5)")
        ->type_name("X,Y");
    app.add_option(
           "--focus-object", o.focusObject,
           "focus object: a feature id (or drawable number in scenes without features); 0 is the object "
           "under the focus point")
        ->type_name("ID");
    app.add_option("--focus-world", o.focusWorld, "focus point in scene coordinates")->type_name("X,Y,Z");
    app.add_option("--focus-radii", o.focusRadii,
                   "focus weight 1 within IN, 0 beyond OUT (fractions of the image diagonal)")
        ->type_name("IN,OUT");
    unsigned samples = 0;
    loa::addCount(
        app, "--samples", samples, 0, 64,
        "multisample anti-aliasing with N samples (default 0; at most GL_MAX_SAMPLES, which is 4 on "
        "llvmpipe)");
    loa::addCount(
        app, "--frames", o.frames, 0, 100000,
        "render N timed frames after one warm-up frame and report the median and minimum frame time (each "
        "frame ends with glFinish)");
    loa::addCount(app, "--abuffer-samples", o.samplesABuffer, 1, 64,
                  "A-buffer samples per pixel (default 4; at most GL_MAX_SAMPLES)");
    loa::addCount(app, "--abuffer-passes", o.passesABuffer, 1, 63,
                  "A-buffer routing passes at most (default 4)");
    app.add_option_function<std::string>(
           "--fuse-styles",
           [&o](const std::string& v)
           {
               if (v != "on" && v != "off")
                   throw loa::UsageError("--fuse-styles takes on or off, not '" + v + "'");
               o.fuseStyles = v == "on";
           },
           "on (default): a feature in transition whose styles are all opaque is drawn once, its styles "
           "blended per fragment; off: every feature in transition goes through the A-buffer")
        ->type_name("on|off");
    app.add_option_function<std::string>(
           "--oit",
           [&o](const std::string& v)
           {
               o.oitAuto = v == "auto";
               if (o.oitAuto) return;
               o.oitGiven = true;
               try
               {
                   o.oit = osgLoA::OrderIndependentTransparency::methodFromName(v);
               }
               catch (const std::invalid_argument& e)
               {
                   throw loa::UsageError(std::string("--oit: ") + e.what() + ", or auto");
               }
           },
           "order-independent transparency of what fused styles cannot draw: stencil-routed (default, the "
           "paper's A-buffer; without this option, on renderers where its routing is approximate at "
           "silhouettes (llvmpipe) the linked lists draw instead), linked-list (per-pixel linked lists, "
           "exact, one pass) or weighted-blended (one pass, approximate), or auto (the exact method whose "
           "routed passes measure cheaper, tried over the first frames that route; use --frames)")
        ->type_name("NAME");
    app.add_option_function<std::string>(
           "--program",
           [&o](const std::string& p)
           {
               if (p != "plain") throw loa::UsageError("unknown --program '" + p + "' (known: plain)");
               o.program = p;
           },
           "plain: draw with the project's loa_plain GLSL program instead of OSG's fixed-function pipeline")
        ->type_name("plain");
    app.add_flag("--gl-info", o.glInfo, "print the GL context's capabilities and exit");
    cl.footer(kFooter);
    cl.parse(argc, argv);
    o.samples = static_cast<int>(samples);
    o.model = loa::modelLabel(o.models);
    loa::checkCameraOptions(o.camera);
    if (!o.scenario.empty() && !o.program.empty())
        throw loa::UsageError(
            "--scenario and --program exclude each other (a scenario's styles bring their programs)");
    if (!o.style.empty() && (!o.scenario.empty() || !o.program.empty()))
        throw loa::UsageError("--style excludes --scenario and --program");
    if ((!o.focus.empty() || !o.focusObject.empty() || !o.focusWorld.empty() || !o.focusRadii.empty()) &&
        o.style.empty())
        throw loa::UsageError("--focus, --focus-object, --focus-world and --focus-radii need --style");
    if (osgDB::getLowerCaseFileExtension(o.out) != "png")
        throw loa::UsageError("--out '" + o.out + "' must name a .png file");
    return o;
}

std::vector<float> parseFloats(const std::string& option, const std::string& text, std::size_t count)
{
    std::vector<float> v;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ','))
    {
        try
        {
            std::size_t used = 0;
            const float f = std::stof(item, &used);
            if (used != item.size() || !std::isfinite(f)) throw std::invalid_argument(item);
            v.push_back(f);
        }
        catch (const std::exception&)
        {
            throw loa::UsageError(option + " '" + text + "': '" + item + "' is not a number");
        }
    }
    if (v.size() != count)
        throw loa::UsageError(option + " '" + text + "' needs " + std::to_string(count) +
                              " comma-separated numbers");
    return v;
}

/** The abstraction style of --style (a catalog name or a file), with the focus options applied;
 *  null when --style names another graphic style. */
osg::ref_ptr<osgLoA::AbstractionStyle> abstractionStyle(const Options& o)
{
    osg::ref_ptr<osgLoA::AbstractionStyle> style;
    const std::string ext = osgDB::getLowerCaseFileExtension(o.style);
    if (osgLoA::AbstractionStyleCatalog::instance().contains(o.style))
        style = osgLoA::AbstractionStyleCatalog::instance().create(o.style);
    else if (ext == "osgt" || ext == "osgb" || ext == "osgx")
    {
        if (!osgDB::fileExists(o.style)) throw std::runtime_error("--style: no file '" + o.style + "'");
        osg::ref_ptr<osg::Object> object = osgDB::readRefObjectFile(o.style);
        style = dynamic_cast<osgLoA::AbstractionStyle*>(object.get());
        if (!style)
            throw std::runtime_error("--style: '" + o.style + "' does not hold an osgLoA::AbstractionStyle");
        try
        {
            style->validate();
        }
        catch (const std::invalid_argument& e)
        {
            throw std::runtime_error("--style '" + o.style + "': " + e.what());
        }
    }
    else if (osgLoA::GraphicStyleCatalog::instance().contains(o.style))
    {
        if (!o.focus.empty() || !o.focusObject.empty() || !o.focusWorld.empty() || !o.focusRadii.empty())
            throw loa::UsageError("the focus options apply to image-space and hybrid styles, not to '" +
                                  o.style + "'");
        return nullptr;
    }
    else
        throw loa::UsageError("unknown --style '" + o.style + "' (loa-render --list-styles lists them)");

    osg::ref_ptr<osgLoA::AbstractionFocus> focus =
        new osgLoA::AbstractionFocus(*style->getFocus(), osg::CopyOp::DEEP_COPY_ALL);
    if (!o.focus.empty())
    {
        const std::vector<float> v = parseFloats("--focus", o.focus, 2);
        focus->setMode(osgLoA::AbstractionFocus::SCREEN_POINT);
        focus->setScreenPoint(osg::Vec2f(v[0], v[1]));
    }
    if (!o.focusWorld.empty())
    {
        const std::vector<float> v = parseFloats("--focus-world", o.focusWorld, 3);
        focus->setMode(osgLoA::AbstractionFocus::WORLD_POINT);
        focus->setWorldPoint(osg::Vec3d(v[0], v[1], v[2]));
    }
    if (!o.focusObject.empty())
    {
        focus->setMode(osgLoA::AbstractionFocus::OBJECT);
        focus->setObjectId(loa::parseCount("--focus-object", o.focusObject, 0xffffffu));
    }
    if (!o.focusRadii.empty())
    {
        const std::vector<float> v = parseFloats("--focus-radii", o.focusRadii, 2);
        focus->setInnerRadius(v[0]);
        focus->setOuterRadius(v[1]);
    }
    try
    {
        focus->validate();
    }
    catch (const std::invalid_argument& e)
    {
        throw loa::UsageError(std::string("focus: ") + e.what());
    }
    style->setFocus(focus.get());
    return style;
}

int run(const Options& o)
{
    if (o.listStyles)
    {
        // One a line: the name, then what it draws (names first, so `cut -d' ' -f1` lists them).
        std::size_t width = 0;
        const auto entries = osgLoA::GraphicStyleCatalog::instance().entries();
        for (const auto& e : entries)
            width = std::max(width, e.name.size());
        for (const auto& e : entries)
            std::cout << e.name << std::string(width + 2 - e.name.size(), ' ')
                      << (e.description.empty() ? std::string("(no description)") : e.description) << "\n";
        return loa::kOk;
    }
    osg::ref_ptr<osgLoA::AbstractionStyle> abstraction;
    if (!o.style.empty()) abstraction = abstractionStyle(o);

    // The scene first: a missing or malformed model is reported as such, with or without GL.
    const bool glInfoOnly = o.glInfo;
    osg::ref_ptr<osg::Node> scene;
    std::string what;
    double loadMs = 0.0;
    if (!glInfoOnly)
    {
        const auto g0 = std::chrono::steady_clock::now();
        scene = loa::loadModelsOrDemoCity(o.models, o.readerOptions, what);
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
        // Which StateSets have a texture (and OSG's defaults above them): loa_plain must not
        // sample unit 0 on untextured drawables (they came out black).
        osgLoA::FixedFunctionUniforms::annotate(*scene);
        osg::ref_ptr<osg::Group> root = new osg::Group;
        root->addChild(scene.get());
        scene = root;
        osg::StateSet* ss = scene->getOrCreateStateSet();
        ss->setAttributeAndModes(
            osgLoA::ShaderLibrary::createProgram("plain", {"loa_plain.vert.glsl", "loa_plain.frag.glsl"})
                .get());
        ss->addUniform(new osg::Uniform("loa_baseTexture", 0));
        osgLoA::FixedFunctionUniforms::setDefaults(*ss);
    }
    osg::ref_ptr<osgLoA::LoANode> loaNode;
    osg::ref_ptr<osgLoA::AbstractionNode> abstractionNode;
    const bool styleScenario = !o.style.empty() && !abstraction.valid();
    if (!o.scenario.empty() || styleScenario)
    {
        std::string origin;
        osg::ref_ptr<osgLoA::UsageScenario> scenario;
        if (styleScenario)
        {
            // One configuration: every feature in the style.
            scenario = osgLoA::ScenarioLibrary::createHomogeneous(o.style);
            scenario->setName("style-" + o.style);
        }
        else
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
        // As the loa plugin does: features the model carries keep their type, the classifier's
        // rules and the appearance fallback type the rest (a model without features would
        // otherwise be drawn unstyled).
        const osgLoA::FeatureClassifier::Report classified =
            osgLoA::FeatureClassifier(o.rules.assemble().get()).classify(*loaNode);
        std::cout << "classifier: " << classified.summary() << "\n";
        osgLoA::TransitionRenderer::Settings rs = loaNode->getRenderer()->getSettings();
        rs.samples = o.samplesABuffer;
        rs.maxPasses = o.passesABuffer;
        rs.fuseStyles = o.fuseStyles;
        rs.oit = o.oit;
        rs.oitAuto = o.oitAuto;
        rs.approximateStencilRouting = o.oitGiven;
        loaNode->getRenderer()->setSettings(rs);
        osgLoA::StylePreparation::Options prep;
        prep.progress = [](const std::string& line) { std::cerr << line << "\n"; };
        loaNode->setStylePreparationOptions(prep);
        try
        {
            // Also prepares the styles that need per-texture data (the abstract style's
            // filtered textures, the palette style's palettes), with progress lines on stderr.
            loaNode->bind();
            const osgLoA::StylePreparation::Report& r = loaNode->getStylePreparationReport();
            for (const std::string& style : r.styles)
                if (style == "palette")
                    std::cout << "palette style: " << r.palettes << " texture palette(s) built\n";
                else if (style == "abstract")
                    std::cout << "abstract style: " << r.abstractTextures << " filtered texture(s), "
                              << r.abstractFromCache << " from the cache\n";
            for (const std::string& m : r.messages)
                std::cerr << "loa-render: warning: " << m << "\n";
        }
        catch (const std::exception& e)
        {
            throw std::runtime_error("scenario '" + (styleScenario ? "style-" + o.style : o.scenario) +
                                     "' cannot be used with this model: " + e.what());
        }
        // Configurations in image-space styles: abstraction nodes around the LoA node.
        scene = osgLoA::AbstractionNode::wrapScenario(loaNode.get());
    }
    if (abstraction.valid())
    {
        abstractionNode = new osgLoA::AbstractionNode;
        abstractionNode->setStyle(abstraction.get());
        abstractionNode->addChild(scene.get());
        scene = abstractionNode;
    }
    renderer->setSceneData(scene.get());
    loa::applyCamera(*renderer, o.camera);

    const osgLoA::SceneStatistics stats = osgLoA::SceneStatistics::collect(*scene);
    osgLoA::FrameTimes times;
    if (o.frames > 0) times = renderer->timeFrames(o.frames);
    osg::ref_ptr<osg::Image> image = renderer->renderImage();
    for (osg::Node* n = scene.get(); n;)
    {
        // Every abstraction stage must have run: a failed stage would show the unabstracted frame.
        osgLoA::AbstractionNode* a = dynamic_cast<osgLoA::AbstractionNode*>(n);
        if (!a) break;
        if (!a->getLastError().empty())
            throw std::runtime_error("abstraction style '" + a->getStyle()->getName() +
                                     "': " + a->getLastError());
        n = a->getNumChildren() ? a->getChild(0) : nullptr;
    }
    osgLoA::ImageFile::write(o.out, *image);

    const osgLoA::MachineInfo machine = osgLoA::MachineInfo::query();
    std::cout << "rendered " << what << ": " << stats.summary() << "\n"
              << "view: " << o.camera.describe() << ", " << o.width << "x" << o.height
              << (o.samples ? ", " + std::to_string(o.samples) + "x MSAA" : std::string())
              << (!o.style.empty()      ? ", style " + o.style
                  : !o.scenario.empty() ? ", scenario " + o.scenario
                  : o.program.empty()   ? ", fixed-function pipeline"
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
                  << " in one style (shared pass), " << st.fusedDraws
                  << " fused (their styles blended in one draw, " << st.fusedPrograms << " combinations), "
                  << st.depthOnlyDraws << " in transition; " << st.aBufferDraws << " A-buffer draws, "
                  << st.pingPongDraws << " ping-pong draws; A-buffer " << (st.aBuffer ? "used" : "not needed")
                  << ", unsharp masking " << (st.unsharp ? "on" : "off") << "\n";
        {
            osgLoA::OrderIndependentTransparency* oit = loaNode->getRenderer()->getABuffer();
            const osgLoA::OITFrameStatistics os = oit->getFrameStatistics();
            std::cout << "order-independent transparency: "
                      << osgLoA::OrderIndependentTransparency::methodName(oit->getMethod())
                      << "; routed region " << os.regionTiles << " of " << os.viewportTiles << " tiles";
            const osgLoA::OITAutoSelection& sel = loaNode->getRenderer()->getOITSelection();
            if (o.oitAuto)
            {
                std::cout << "; auto: " << (sel.hasChosen() ? "chosen" : "still trying (more --frames)");
                for (std::size_t i = 0; i < sel.getMedians().size(); ++i)
                    if (sel.getMedians()[i] >= 0.0)
                        std::cout << " "
                                  << osgLoA::OrderIndependentTransparency::methodName(sel.getCandidates()[i])
                                  << " " << sel.getMedians()[i] << " ms";
            }
            std::cout << "\n";
        }
        if (st.drawnFeatures == 0)
            std::cerr << "loa-render: warning: no feature of the scenario is in view ("
                      << loaNode->getFeatureIndex().size()
                      << " features in the model): the frame shows the model unstyled or nothing\n";
        auto* stencil = dynamic_cast<osgLoA::StencilRoutedABuffer*>(loaNode->getRenderer()->getABuffer());
        const osgLoA::ABufferFrameStatistics ab =
            stencil ? stencil->getLastFrameStatistics() : osgLoA::ABufferFrameStatistics();
        auto mem = osgLoA::TransitionRenderer::memory(
            o.width, o.height, unsigned(std::max(ab.samples, 1)), unsigned(std::max(ab.memory.layers, 1)),
            st.pingPongBuffer, st.unsharp, loaNode->getRenderer()->getUnsharpSigma());
        std::ostringstream aBufferShape;
        if (stencil)
            aBufferShape << " with N=" << std::max(ab.samples, 1) << " x " << std::max(ab.memory.layers, 1)
                         << " layer(s)";
        else
        {
            // The other methods report what they allocated (linked lists: grown to the frame).
            mem.aBufferBytes = double(loaNode->getRenderer()->getABuffer()->getFrameStatistics().bytes);
            aBufferShape << ", "
                         << osgLoA::OrderIndependentTransparency::methodName(
                                loaNode->getRenderer()->getABuffer()->getMethod());
        }
        std::cout << std::setprecision(1) << "GPU memory of the LoA passes: " << mem.totalBytes() / 1048576.0
                  << " MiB (A-buffer " << mem.aBufferBytes / 1048576.0 << aBufferShape.str() << ", G-buffer "
                  << mem.geometryBufferBytes / 1048576.0 << ", ping-pong " << mem.pingPongBytes / 1048576.0
                  << ", unsharp mask " << mem.unsharpBytes / 1048576.0
                  << "); paper 004 formula W H (2N+7)/262144: " << mem.paperBytes / 1048576.0 << " MB\n";
    }
    if (abstractionNode)
    {
        const osgLoA::AbstractionNode::FrameStatistics st = abstractionNode->getLastFrameStatistics();
        std::cout << std::setprecision(1) << "abstraction: " << st.passes << " scene pass(es), "
                  << st.filterRuns << " filter run(s) writing " << st.filterTexels
                  << " texels; focus at pixel (" << st.focusPixel.x() << ", " << st.focusPixel.y() << ")"
                  << (st.focusObject >= 0
                          ? ", focus object id " +
                                std::to_string(abstractionNode->getObjectId(unsigned(st.focusObject)))
                          : std::string())
                  << "; render targets " << abstractionNode->memoryBytes(o.width, o.height) / 1048576.0
                  << " MiB\n";
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
        j << "],\n  \"scene\": " << stats.toJson() << ",\n";
        if (loaNode) j << "  \"features\": " << osgLoA::FeatureIndex(*loaNode).counts().toJson() << ",\n";
        j << "  \"gl\": " << caps.toJson() << ",\n"
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
    Options o;
    return loa::runTool(
        "loa-render", [&] { o = parse(argc, argv); }, [&] { return run(o); });
}
