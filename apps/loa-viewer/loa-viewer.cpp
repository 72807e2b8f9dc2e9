// loa-viewer: interactive viewing and authoring of usage scenarios (paper 004 §3.1, §4.4).
#include "../common/AppSupport.h"
#include "../common/CommandLine.h"
#include "AuthoringHandler.h"
#include "EventScript.h"
#include "ImGuiLayer.h"
#include "ViewerPanels.h"
#include "ViewerSession.h"

#include <osgLoA/authoring/HomeView>
#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/render/ShaderLibrary>
#include <osgLoA/semantics/FeatureClassifier>
#include <osgLoA/transitions/ScenarioLibrary>

#include <osg/ApplicationUsage>
#include <osgGA/DriveManipulator>
#include <osgGA/FlightManipulator>
#include <osgGA/OrbitManipulator>
#include <osgGA/TerrainManipulator>
#include <osgGA/TrackballManipulator>
#include <osgViewer/Viewer>
#include <osgViewer/ViewerEventHandlers>

#include <iostream>
#include <memory>

namespace
{
struct Options
{
    std::vector<std::string> models;
    std::string readerOptions;
    std::string scenario;
    loa::RulesChoice rules;
    std::string camera;
    int width = loa::kDefaultWidth, height = loa::kDefaultHeight;
    std::string script;
    std::string save;
    std::string viewpoints;
    bool noPanels = false;
    unsigned frames = 0;
};

Options parse(int argc, char** argv)
{
    Options o;
    loa::CommandLine cl(
        "loa-viewer", "loa-viewer [MODEL...] [options]",
        "Views city models with level-of-abstraction transitions and authors usage scenarios in "
        "the view: ImGui panels (scenario library, configuration and style editors, feature "
        "inspector), circle regions and routes drawn with the mouse, focus picking, the "
        "interest debug view, undo and redo. Without a model it shows the demo city. Press h "
        "in the window for the keys (docs/viewer.md).");
    CLI::App& app = cl.app();
    loa::addModels(app, o.models,
                   "models to view as one scene (any format osgDB reads); none: the demo city");
    loa::addReaderOptions(app, o.readerOptions);
    loa::addScenario(app, o.scenario, "the scenario to start with (library name or file; default: distance)");
    loa::addRules(app, o.rules);
    app.add_option("--camera", o.camera,
                   "start at this viewpoint (street, oblique, top, horizon) instead of home")
        ->group(loa::kGroupCamera)
        ->check(CLI::IsMember(osgLoA::CityCameras::names()));
    loa::addSize(app, o.width, o.height, "the window");
    app.add_option("--script", o.script,
                   "replay these events (keys, clicks, drags, screenshots; docs/viewer.md)")
        ->type_name("FILE")
        ->group(loa::kGroupOptions);
    app.add_option("--save", o.save,
                   "where Ctrl+S saves the scenario (.osgt, .osgb or .osgx; default NAME.osgt)")
        ->type_name("FILE")
        ->group(loa::kGroupOutput);
    app.add_option(
           "--viewpoints", o.viewpoints,
           "read saved viewpoints from FILE and write every one saved with V there (text, atomically)")
        ->type_name("FILE")
        ->group(loa::kGroupCamera);
    app.add_flag("--no-panels", o.noPanels, "start with the panels hidden (Tab shows them)")
        ->group(loa::kGroupOptions);
    loa::addCount(app, "--frames", o.frames, 0, 1000000, "stop after N frames (0: run until closed)");
    cl.footer("Exit status: 0 when the window was closed (or the script or --frames ended), 1 when a model,\n"
              "scenario or script cannot be read or no window opens, 2 for bad arguments.\n");
    cl.parse(argc, argv);
    if (!o.save.empty() && !osgLoA::ScenarioLibrary::isScenarioFile(o.save))
        throw loa::UsageError("--save: '" + o.save + "' is not a .osgt, .osgb or .osgx file");
    return o;
}

int run(const Options& o)
{
    std::unique_ptr<loa::EventScript> script;
    if (!o.script.empty()) script.reset(new loa::EventScript(loa::EventScript::read(o.script)));
    std::string what;
    osg::ref_ptr<osg::Node> scene = loa::loadModelsOrDemoCity(o.models, o.readerOptions, what);
    const osgLoA::FeatureClassifier::Report classified =
        osgLoA::FeatureClassifier(o.rules.assemble().get()).classify(*scene);
    std::cout << "loa-viewer: " << what << "; classifier: " << classified.summary() << std::endl;
    std::string origin;
    osg::ref_ptr<osgLoA::UsageScenario> scenario;
    try
    {
        scenario = osgLoA::ScenarioLibrary::load(
            o.scenario.empty() ? osgLoA::ScenarioLibrary::defaultName() : o.scenario, &origin);
    }
    catch (const std::exception& e)
    {
        throw std::runtime_error(std::string("--scenario: ") + e.what());
    }
    // A .loa model is a LoA node that would set the viewer's home in its first event: the
    // viewer sets its own (and --camera) instead.
    {
        struct NoHome : osg::NodeVisitor
        {
            NoHome() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
            void apply(osg::Group& g) override
            {
                if (auto* loa = dynamic_cast<osgLoA::LoANode*>(&g)) loa->setHomeViewPending(false);
                traverse(g);
            }
        } noHome;
        scene->accept(noHome);
    }
    loa::ViewerSession session(*scene, *scenario, origin);
    if (!o.save.empty())
    {
        session.savePath = o.save;
        session.savePathGiven = true;
    }

    osgViewer::Viewer viewer;
    viewer.setThreadingModel(osgViewer::Viewer::SingleThreaded); // panels edit the scene between frames
    viewer.setUpViewInWindow(0, 0, o.width, o.height);
    viewer.setSceneData(session.getRoot());
    viewer.realize();
    if (!viewer.isRealized()) throw std::runtime_error("no window could be opened (is DISPLAY set?)");
    {
        // As OffscreenRenderer does for the tools: the shaders that read osg_ModelViewMatrix and
        // its kin (the interest debug view, the palette style) get them.
        osgViewer::Viewer::Contexts contexts;
        viewer.getContexts(contexts);
        for (osg::GraphicsContext* gc : contexts)
            gc->getState()->setUseModelViewAndProjectionUniforms(true);
    }

    // The field of view of CityCameras and loa-render (45 degrees; osgViewer's default is 30),
    // so that a viewpoint frames what the tools' camera of the same name frames.
    osgLoA::OffscreenRenderer::setUpSun(viewer);
    viewer.getCamera()->setClearColor(osgLoA::OffscreenRenderer::skyColor());
    viewer.getCamera()->setProjectionMatrixAsPerspective(45.0, double(o.width) / double(o.height), 1.0,
                                                         10000.0);
    osg::ref_ptr<loa::GuardedManipulator> manipulator = new loa::GuardedManipulator;
    manipulator->addMatrixManipulator('1', "Trackball", new osgGA::TrackballManipulator);
    manipulator->addMatrixManipulator('2', "Flight", new osgGA::FlightManipulator);
    manipulator->addMatrixManipulator('3', "Drive", new osgGA::DriveManipulator);
    manipulator->addMatrixManipulator('4', "Terrain", new osgGA::TerrainManipulator);
    manipulator->addMatrixManipulator('5', "Orbit", new osgGA::OrbitManipulator);
    viewer.setCameraManipulator(manipulator.get());
    const osgLoA::CameraPose home = osgLoA::HomeView::compute(*session.getRoot(), viewer.getCamera());
    osgLoA::HomeView::apply(*manipulator, home);
    // Viewpoints: home, the scene's cameras, then the ones the user saves (V).
    session.viewpoints.push_back({"home", home, false});
    const double aspect = double(o.width) / double(o.height);
    for (const std::string& name : osgLoA::CityCameras::names())
        session.viewpoints.push_back(
            {name, osgLoA::CityCameras::compute(name, *session.getRoot(), aspect), false});
    if (!o.viewpoints.empty())
    {
        session.readViewpoints(o.viewpoints);
        session.viewpointsFile = o.viewpoints;
    }
    if (!o.camera.empty())
        for (const auto& v : session.viewpoints)
            if (v.name == o.camera) loa::AuthoringHandler::goTo(viewer, v);

    loa::ViewerPanels panels(session, viewer);
    osg::ref_ptr<loa::ImGuiLayer> imgui = new loa::ImGuiLayer([&] { panels.build(); });
    imgui->visible = !o.noPanels;
    imgui->install(*viewer.getCamera());
    imgui->afterDraw = [&](osg::RenderInfo& info)
    {
        // After a shader reload: compile and link the new style programs here, with the
        // context current, for the log the style panel shows.
        if (!session.programsToCheck || !session.getNode().getRenderer()->isBound()) return;
        session.programsToCheck = false;
        std::string log;
        const std::vector<osg::Program*> programs = session.getNode().getRenderer()->getPrograms();
        if (programs.empty())
        {
            session.say("shaders reloaded: no style program to check", true);
            return;
        }
        for (osg::Program* p : programs)
            for (const osgLoA::ShaderDiagnostic& d : osgLoA::ShaderLibrary::check(*p, *info.getState()))
                log += d.message() + "\n";
        session.shaderLog = log;
        if (!log.empty())
        {
            session.say("a shader failed to compile (the style panel shows the log)", true);
            std::cerr << "loa-viewer: shader log:\n" << log;
        }
        else
            session.say("shaders reloaded from OSG_FILE_PATH: every style program compiled and linked");
    };
    viewer.addEventHandler(imgui.get());
    viewer.addEventHandler(new loa::AuthoringHandler(session, *imgui));
    // The help overlay (h) lists every handler's keys (HelpHandler asks each for its usage).
    osg::ref_ptr<osg::ApplicationUsage> usage = new osg::ApplicationUsage("loa-viewer");
    viewer.addEventHandler(new osgViewer::HelpHandler(usage.get()));
    viewer.addEventHandler(new osgViewer::StatsHandler);
    viewer.addEventHandler(new osgViewer::WindowSizeHandler);
    viewer.addEventHandler(new osgViewer::ScreenCaptureHandler);

    osgViewer::Viewer::Windows windows;
    viewer.getWindows(windows);
    if (windows.empty()) throw std::runtime_error("no window could be opened");
    osgViewer::GraphicsWindow* window = windows.front();
    std::string lastMessage, lastBindError;
    unsigned frames = 0;
    while (!viewer.done())
    {
        if (script && !script->step(*window->getEventQueue(), o.height,
                                    [&](const std::string& f) { imgui->requestScreenshot(f); }))
            break;
        viewer.frame();
        ++frames;
        // A scenario the editor accepted that the model cannot bind (fitting, preparation):
        // the node draws it unstyled; say why.
        if (session.getNode().getBindError() != lastBindError)
        {
            lastBindError = session.getNode().getBindError();
            if (!lastBindError.empty()) session.say("the scenario cannot be bound: " + lastBindError, true);
        }
        if (session.message != lastMessage)
        {
            lastMessage = session.message;
            (session.messageIsError ? std::cerr : std::cout) << "loa-viewer: " << lastMessage << std::endl;
        }
        if (!imgui->screenshotError.empty())
            throw std::runtime_error("screenshot: " + imgui->screenshotError);
        if (o.frames && frames >= o.frames) break;
    }
    // One more frame, so that a screenshot asked for last is drawn and written.
    if (script) viewer.frame();
    std::cout << "loa-viewer: " << frames << " frames; " << session.getEditor().getDone()
              << " edit(s) in effect; "
              << "binds " << session.getNode().getBindCount() << ", re-fits "
              << session.getNode().getRefitCount() << std::endl;
    const std::vector<std::string> history = session.getEditor().history();
    for (std::size_t i = 0; i < session.getEditor().getDone(); ++i)
        std::cout << "loa-viewer: edit " << i + 1 << ": " << history[i] << std::endl;
    return loa::kOk;
}
} // namespace

int main(int argc, char** argv)
{
    Options o;
    return loa::runTool(
        "loa-viewer", [&] { o = parse(argc, argv); }, [&] { return run(o); });
}
