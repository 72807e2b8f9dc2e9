// loa-viewer's logic: scenario library, authoring modes, inspector, interest view, viewpoints.
#include "ViewerSession.h"

#include <osgLoA/abstraction/AbstractionNode>
#include <osgLoA/transitions/InterestDebugView>
#include <osgLoA/transitions/ScenarioLibrary>
#include <osgLoA/transitions/TransitionUniforms>
#include <osgLoA/util/AtomicFile>

#include <osgDB/FileNameUtils>
#include <osgUtil/CullVisitor>

#include <cmath>
#include <fstream>
#include <sstream>

namespace loa
{

namespace
{
// A press and release closer than this many pixels is a click, not a drag.
constexpr double kClickPixels = 4.0;
// A route point is grabbed within this many pixels of the pointer.
constexpr double kGrabPixels = 12.0;

/** Keeps the interest debug view live: evaluates the scenario from the cull's eye and writes
 *  the per-feature uniforms before the view's features are drawn. */
class LiveInterestView : public osg::NodeCallback
{
public:
    explicit LiveInterestView(osgLoA::LoANode& node) : _node(&node) {}
    void operator()(osg::Node* n, osg::NodeVisitor* nv) override
    {
        if (auto* cv = dynamic_cast<osgUtil::CullVisitor*>(nv))
        {
            const osg::Vec3d eye(cv->getEyeLocal());
            _node->evaluate(eye);
            const osgLoA::ScenarioEvaluator* e = _node->getEvaluator();
            if (e && e->isBound())
            {
                osgLoA::TransitionUniforms::applyEye(*n->getOrCreateStateSet(), eye);
                const auto& entries = _node->getFeatureIndex().entries();
                for (const auto& f : e->features())
                {
                    osg::ref_ptr<osg::Node> featureNode;
                    if (entries[f.entry].node.lock(featureNode))
                        osgLoA::TransitionUniforms::applyFeature(*featureNode->getOrCreateStateSet(), *e, f);
                }
            }
        }
        traverse(n, nv);
    }

private:
    osg::observer_ptr<osgLoA::LoANode> _node;
};

double pixelDistance(const osg::Camera& camera, const osg::Vec3d& scenePoint, double x, double y)
{
    const osg::Matrixd vpw =
        camera.getViewMatrix() * camera.getProjectionMatrix() * camera.getViewport()->computeWindowMatrix();
    const osg::Vec3d w = scenePoint * vpw;
    return std::hypot(w.x() - x, w.y() - y);
}
} // namespace

const char* ViewerSession::modeName(Mode m)
{
    switch (m)
    {
    case NAVIGATE:
        return "navigate";
    case INSPECT:
        return "inspect";
    case REGION:
        return "region";
    case ROUTE:
        return "route";
    case FOCUS:
        return "focus";
    default:
        return "?";
    }
}

ViewerSession::ViewerSession(osg::Node& scene, osgLoA::UsageScenario& scenario, const std::string& from)
    : origin(from), _root(new osg::Switch), _styled(new osg::Group), _node(new osgLoA::LoANode)
{
    _node->setScenario(&scenario);
    _node->addChild(&scene);
    _root->addChild(_styled.get(), true);
    _root->addChild(new osg::Group, false);
    _editor = new osgLoA::ScenarioEditor(*_node);
    savePath = (scenario.getName().empty() ? std::string("scenario") : scenario.getName()) + ".osgt";
    rewrap();
}

void ViewerSession::rewrap()
{
    // Image-space styles (AbstractionNode) wrap the LoA node; which ones depends on the
    // scenario's structure, so they are rebuilt after structural edits only.
    _wrappedRevision = _node->getScenario()->getRevision();
    _styled->removeChildren(0, _styled->getNumChildren());
    try
    {
        _styled->addChild(osgLoA::AbstractionNode::wrapScenario(_node.get()).get());
    }
    catch (const std::exception& e)
    {
        // The node draws its children unstyled and says why once; the status line shows it.
        _styled->addChild(_node.get());
        say(std::string("the scenario cannot be bound: ") + e.what(), true);
    }
}

void ViewerSession::afterEdit()
{
    // The eye of the last evaluation: the node binds or re-fits now and evaluates from there,
    // so that the inspector and the interest view show the edited scenario, not the old one.
    const osgLoA::ScenarioEvaluator* e = _node->getEvaluator();
    const osg::Vec3d eye = e && e->isBound() ? e->getView().eye : _lastEye;
    _lastEye = eye;
    if (_node->getScenario()->getRevision() != _wrappedRevision) rewrap();
    _node->evaluate(eye);
    if (_interestView) setInterestView(true); // its program follows the scenario's structure
    refreshInspection();
    // A file name that came from the scenario's name follows it through undo and redo.
    if (!savePathGiven) savePath = _node->getScenario()->getName() + ".osgt";
}

bool ViewerSession::fittedCircle(const std::string& name, osg::Vec2d& centre, double& radius) const
{
    for (const auto& r : fittedRegions())
        if (r.valid() && r->getName() == name && r->getShape() == osgLoA::RegionOfInterest::CIRCLES &&
            !r->getVertices().empty())
        {
            centre = r->getVertices()[0];
            radius = r->getRadius();
            return true;
        }
    return false;
}

const osgLoA::UsageScenario::Regions& ViewerSession::fittedRegions() const
{
    const osgLoA::ScenarioEvaluator* e = _node->getEvaluator();
    return e && e->isBound() ? e->getScenario()->getRegions() : _node->getScenario()->getRegions();
}

bool ViewerSession::undo()
{
    const std::string label = _editor->undoLabel();
    if (!_editor->undo()) return false;
    afterEdit();
    say("undone: " + label);
    return true;
}

bool ViewerSession::redo()
{
    const std::string label = _editor->redoLabel();
    if (!_editor->redo()) return false;
    afterEdit();
    say("redone: " + label);
    return true;
}

void ViewerSession::say(const std::string& text, bool error)
{
    message = text;
    messageIsError = error;
}

std::vector<std::string> ViewerSession::libraryNames() const
{
    return osgLoA::ScenarioLibrary::availableNames();
}

void ViewerSession::loadScenario(const std::string& nameOrPath)
{
    std::string from;
    osg::ref_ptr<osgLoA::UsageScenario> s = osgLoA::ScenarioLibrary::load(nameOrPath, &from);
    if (s->getName().empty()) s->setName(nameOrPath);
    _editor->replace(*s, "load scenario '" + s->getName() + "'");
    origin = from;
    savePathGiven = false;
    savePath = s->getName() + ".osgt";
    _editor->markSaved();
    afterEdit();
    say("loaded '" + s->getName() + "' (" + from + ")");
}

void ViewerSession::duplicateScenario(const std::string& newName)
{
    if (newName.empty()) throw std::invalid_argument("a scenario needs a name");
    _editor->edit("duplicate as '" + newName + "'", osgLoA::ScenarioEditor::VALUES,
                  [&](osgLoA::UsageScenario& s) { s.setName(newName); });
    savePathGiven = false;
    savePath = newName + ".osgt";
    origin = "(not saved)";
}

void ViewerSession::saveScenario(const std::string& path)
{
    if (path.empty()) throw std::invalid_argument("no file to save to");
    osgLoA::ScenarioLibrary::writeFile(_editor->getScenario(), path);
    _editor->markSaved();
    origin = path;
    std::string rules;
    if (!_editor->getUserRules().getRules().empty())
    {
        // Types set by hand go beside the scenario as a rule set (loa-viewer --rules FILE, and
        // every tool's --rules, classify the model the same way next time).
        rules = rulesPathFor(path);
        _editor->getUserRules().write(rules);
    }
    say("saved '" + _editor->getScenario().getName() + "' to " + path +
        (rules.empty() ? std::string() : " and the types set by hand to " + rules) +
        (_editor->getCount(osgLoA::ScenarioEditor::LIVE) > 0
             ? std::string("; style uniform edits are not part of a scenario file")
             : std::string()));
}

std::string ViewerSession::rulesPathFor(const std::string& scenarioPath)
{
    return osgDB::getNameLessExtension(scenarioPath) + ".rules.osgt";
}

osgLoA::FeaturePicker::Hit ViewerSession::pick(const osg::Camera& camera, double x, double y)
{
    return osgLoA::FeaturePicker::pick(camera, x, y, *_root, *_node);
}

std::string ViewerSession::newCircleName() const
{
    for (unsigned i = 1;; ++i)
    {
        const std::string name = "circle-" + std::to_string(i);
        bool used = false;
        for (const auto& r : _editor->getScenario().getRegions())
            used = used || (r.valid() && r->getName() == name);
        if (!used) return name;
    }
}

bool ViewerSession::press(const osg::Camera& camera, double x, double y, int button)
{
    if (mode == NAVIGATE) return false;
    if (button == 2) return false; // the middle button always pans the camera
    _button = button;
    _moved = false;
    _moving = false;
    _routeVertex = -1;
    _region.clear();
    _pressX = x;
    _pressY = y;
    const osgLoA::FeaturePicker::Hit hit = pick(camera, x, y);
    if (hit.ground) _pressGround.set(hit.scene.x(), hit.scene.y());
    osgLoA::UsageScenario& s = _editor->getScenario();
    if (mode == REGION && hit.ground)
    {
        // The circles where the scene shows them: as the node fitted them (a library circle
        // placed at the scene's centre, in multiples of its size, is in scene units there).
        const osgLoA::UsageScenario::Regions& placed = fittedRegions();
        // Inside a circle: grab it (left) or set the fade from it (right).
        for (const auto& r : placed)
            if (r.valid() && r->getShape() == osgLoA::RegionOfInterest::CIRCLES &&
                r->getVertices().size() == 1 &&
                (r->getVertices()[0] - _pressGround).length() <= r->getRadius())
            {
                _region = r->getName();
                _grabOffset = r->getVertices()[0] - _pressGround;
                _moving = true;
            }
        if (button == 1 && !_moving) _region = newCircleName();
        if (button == 3 && !_moving)
        {
            // The fade of the nearest circle.
            double best = 1e300;
            for (const auto& r : placed)
                if (r.valid() && r->getShape() == osgLoA::RegionOfInterest::CIRCLES &&
                    r->getVertices().size() == 1)
                {
                    const double d = (r->getVertices()[0] - _pressGround).length();
                    if (d < best) best = d, _region = r->getName();
                }
        }
        if (!_region.empty()) _editor->beginGesture();
        return true;
    }
    if (mode == ROUTE)
    {
        // A route point within kGrabPixels of the pointer (at the picked height) is grabbed.
        const osg::NodePathList paths = _node->getParentalNodePaths(_root.get());
        const osg::Matrixd toWorld = paths.empty() ? osg::Matrixd() : osg::computeLocalToWorld(paths.front());
        for (const auto& r : s.getRegions())
            if (r.valid() && r->getName() == "route")
                for (unsigned i = 0; i < r->getVertices().size(); ++i)
                {
                    const osg::Vec2d& v = r->getVertices()[i];
                    const osg::Vec3d p(v.x(), v.y(), hit.ground ? hit.scene.z() : 0.0);
                    if (pixelDistance(camera, p * toWorld, x, y) <= kGrabPixels) _routeVertex = int(i);
                }
        if (_routeVertex >= 0 && button == 1) _editor->beginGesture();
        return true;
    }
    return true;
}

bool ViewerSession::drag(const osg::Camera& camera, double x, double y)
{
    if (mode == NAVIGATE || _button == 0 || _button == 2) return false;
    if (std::hypot(x - _pressX, y - _pressY) > kClickPixels) _moved = true;
    if (!_moved) return true;
    const osgLoA::FeaturePicker::Hit hit = pick(camera, x, y);
    if (!hit.ground) return true;
    const osg::Vec2d p(hit.scene.x(), hit.scene.y());
    if (mode == REGION && !_region.empty())
    {
        if (_button == 1 && _moving)
            attempt(
                [&]
                {
                    osg::Vec2d centre;
                    double radius = 0.0;
                    fittedCircle(_region, centre, radius);
                    _editor->placeCircle(_region, p + _grabOffset, radius);
                });
        else if (_button == 1)
            attempt([&] { _editor->placeCircle(_region, _pressGround, (p - _pressGround).length()); });
        else if (_button == 3)
            attempt(
                [&]
                {
                    osg::Vec2d centre;
                    double radius = 0.0;
                    if (fittedCircle(_region, centre, radius))
                        _editor->setRegionFade(std::max(0.0, (p - centre).length() - radius));
                });
        return true;
    }
    if (mode == ROUTE && _routeVertex >= 0 && _button == 1)
    {
        attempt([&] { _editor->moveRoutePoint("route", unsigned(_routeVertex), p); });
        return true;
    }
    return true;
}

bool ViewerSession::release(const osg::Camera& camera, double x, double y)
{
    // Whatever the mode now (it may have changed during the drag), a gesture ends here.
    if (_editor->inGesture()) _editor->endGesture();
    if (mode == NAVIGATE || _button == 0 || _button == 2)
    {
        _button = 0;
        return false;
    }
    const int button = _button;
    _button = 0;
    if (_moved) return true;
    const osgLoA::FeaturePicker::Hit hit = pick(camera, x, y);
    if (mode == ROUTE)
    {
        const osg::Vec2d p(hit.scene.x(), hit.scene.y());
        bool haveRoute = false;
        for (const auto& r : _editor->getScenario().getRegions())
            haveRoute = haveRoute || (r.valid() && r->getName() == "route");
        if (button == 1 && _routeVertex < 0 && hit.ground && !haveRoute && !_routeStarted)
        {
            // A route needs two points to be valid: the first waits for the second.
            _routeStarted = true;
            _routeStart = p;
            say("route: click the next point");
        }
        else if (button == 1 && _routeVertex < 0 && hit.ground)
            attempt(
                [&]
                {
                    if (haveRoute)
                        _editor->addRoutePoint("route", p);
                    else
                        _editor->startRoute("route", _routeStart, p);
                    _routeStarted = false;
                    for (const auto& r : _editor->getScenario().getRegions())
                        if (r.valid() && r->getName() == "route")
                            say("route: " + std::to_string(r->getVertices().size()) +
                                " points (drag one to move it, right-click one to remove it)");
                });
        else if (button == 3 && _routeVertex >= 0)
            attempt([&] { _editor->removeRoutePoint("route", unsigned(_routeVertex)); });
        return true;
    }
    if (mode == INSPECT && button == 1)
    {
        if (hit.featureId)
            inspect(hit.featureId, hit.scene);
        else
            say("no feature there");
        return true;
    }
    if (mode == FOCUS && button == 1)
    {
        if (hit.featureId)
            attempt([&] { _editor->setFocusFeature(hit.featureId); });
        else
            say("no feature there: the focus is unchanged");
        return true;
    }
    return true;
}

void ViewerSession::useRegionDetail()
{
    double radius = 0.0;
    for (const auto& r : _editor->getScenario().getRegions())
        if (r.valid() && r->getShape() == osgLoA::RegionOfInterest::CIRCLES && r->isResolved())
        {
            radius = r->getRadius();
            break;
        }
    if (radius <= 0.0)
    {
        say("place a circle first (region mode: drag on the ground)", true);
        return;
    }
    attempt([&] { _editor->useRegionDetail("photorealistic", "abstract", 0.6 * radius); });
}

void ViewerSession::inspect(unsigned featureId, const osg::Vec3d& scenePoint)
{
    inspected = true;
    inspectedPoint = scenePoint;
    inspection = osgLoA::FeatureInspector::inspect(*_node, featureId, scenePoint);
}

void ViewerSession::refreshInspection()
{
    if (inspected) inspection = osgLoA::FeatureInspector::inspect(*_node, inspection.id, inspectedPoint);
}

void ViewerSession::setInterestView(bool on)
{
    _interestView = on;
    osg::ref_ptr<osg::Group> view = new osg::Group;
    if (on)
    {
        try
        {
            _node->evaluate(_node->getEvaluator()->getView().eye);
            view = osgLoA::InterestDebugView::create(*_node);
            view->setCullCallback(new LiveInterestView(*_node));
        }
        catch (const std::exception& e)
        {
            say(std::string("no interest view: ") + e.what(), true);
            _interestView = on = false;
        }
    }
    _root->setChild(1, view.get());
    _root->setValue(0, !on);
    _root->setValue(1, on);
}

void ViewerSession::reloadShaders()
{
    _node->getRenderer()->forgetPrograms();
    _node->getScenario()->dirty();
    programsToCheck = true;
    shaderLog.clear();
    afterEdit();
    say("shaders reloaded from OSG_FILE_PATH");
}

void ViewerSession::addViewpoint(const std::string& name, const osgLoA::CameraPose& pose)
{
    Viewpoint v;
    v.name = name;
    v.pose = pose;
    v.user = true;
    viewpoints.push_back(v);
    if (!viewpointsFile.empty()) writeViewpoints(viewpointsFile);
}

void ViewerSession::writeViewpoints(const std::string& path) const
{
    std::ostringstream out;
    out.precision(17);
    out << "# loa-viewer viewpoints: NAME|eye|centre|up\n";
    for (const Viewpoint& v : viewpoints)
        if (v.user)
            out << v.name << "|" << v.pose.eye.x() << " " << v.pose.eye.y() << " " << v.pose.eye.z() << "|"
                << v.pose.center.x() << " " << v.pose.center.y() << " " << v.pose.center.z() << "|"
                << v.pose.up.x() << " " << v.pose.up.y() << " " << v.pose.up.z() << "\n";
    osgLoA::AtomicFile::writeText(path, out.str());
}

void ViewerSession::readViewpoints(const std::string& path)
{
    std::ifstream in(path);
    if (!in) return; // none saved yet
    int lineNo = 0;
    for (std::string line; std::getline(in, line);)
    {
        ++lineNo;
        if (line.empty() || line[0] == '#') continue;
        std::vector<std::string> parts;
        std::istringstream fields(line);
        for (std::string f; std::getline(fields, f, '|');)
            parts.push_back(f);
        osgLoA::CameraPose pose;
        bool ok = parts.size() == 4 && !parts[0].empty();
        for (std::size_t i = 1; ok && i < 4; ++i)
        {
            std::istringstream v(parts[i]);
            osg::Vec3d& target = i == 1 ? pose.eye : i == 2 ? pose.center : pose.up;
            ok = bool(v >> target.x() >> target.y() >> target.z()) && target.valid();
        }
        if (ok) ok = (pose.center - pose.eye).length() > 0.0 && pose.up.length() > 0.0;
        if (!ok)
            throw std::runtime_error("--viewpoints: " + path + ":" + std::to_string(lineNo) +
                                     ": expected NAME|ex ey ez|cx cy cz|ux uy uz with eye != centre");
        Viewpoint vp;
        vp.name = parts[0];
        vp.pose = pose;
        vp.user = true;
        viewpoints.push_back(vp);
    }
}

} // namespace loa
