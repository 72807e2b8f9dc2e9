// loa-viewer's logic, apart from any window: the scene, the scenario being authored, the
// authoring modes and what the panels show. Tests and --script drive it through osgGA events;
// it never touches GL itself.
#ifndef OSGLOA_APPS_VIEWERSESSION_H
#define OSGLOA_APPS_VIEWERSESSION_H 1

#include <osgLoA/authoring/FeatureInspector>
#include <osgLoA/authoring/FeaturePicker>
#include <osgLoA/authoring/ScenarioEditor>
#include <osgLoA/city/CityCameras>
#include <osgLoA/transitions/LoANode>

#include <osg/Camera>
#include <osg/Switch>

#include <string>
#include <vector>

namespace loa
{

class ViewerSession
{
public:
    enum Mode
    {
        NAVIGATE = 0, ///< the mouse moves the camera
        INSPECT,      ///< a click shows the feature under it
        REGION,       ///< drag: place or move a circle region; right drag: the region fade
        ROUTE,        ///< click: add a route point; drag a point: move it; right click: remove it
        FOCUS,        ///< a click sets the focus object
        NUM_MODES
    };
    static const char* modeName(Mode m);

    /** scene: the model (classified); scenario: the one to start with (origin: its file or
     *  "built-in", for the library panel). */
    ViewerSession(osg::Node& scene, osgLoA::UsageScenario& scenario, const std::string& origin);

    /** What the viewer shows: the styled scene, or the interest debug view. */
    osg::Group* getRoot() { return _root.get(); }
    osgLoA::LoANode& getNode() { return *_node; }
    osgLoA::ScenarioEditor& getEditor() { return *_editor; }

    // --- scenario library
    std::vector<std::string> libraryNames() const;
    /** Loads a library scenario (by name or file) in place of the current one (undoable). */
    void loadScenario(const std::string& nameOrPath);
    /** The current scenario under a new name (the library panel's "duplicate"). */
    void duplicateScenario(const std::string& newName);
    /** Writes the scenario (.osgt/.osgb/.osgx, atomically) and marks it saved; types set by
     *  hand go beside it as a classification rule set (rulesPathFor). */
    void saveScenario(const std::string& path);
    /** NAME.rules.osgt for NAME.osgt (or .osgb, .osgx). */
    static std::string rulesPathFor(const std::string& scenarioPath);
    std::string savePath;       ///< where Ctrl+S saves
    bool savePathGiven = false; ///< named by the user (--save, the panel): kept through undo
    std::string origin;         ///< where the scenario came from

    // --- modes and pointer input (window coordinates: OSG's, origin bottom left)
    Mode mode = NAVIGATE;
    /** A button went down / the pointer moved with it down / it went up. true: the session used
     *  the event (the manipulator must not). button: 1 left, 2 middle, 3 right. */
    bool press(const osg::Camera& camera, double x, double y, int button);
    bool drag(const osg::Camera& camera, double x, double y);
    bool release(const osg::Camera& camera, double x, double y);

    /** Makes the circles' scenario: detail (photorealistic) inside the regions, abstract
     *  outside, fading over 0.6 times the first circle's radius (Shift+R). */
    void useRegionDetail();

    // --- the inspector
    bool inspected = false;
    osgLoA::FeatureInspector::Report inspection;
    osg::Vec3d inspectedPoint;
    void inspect(unsigned featureId, const osg::Vec3d& scenePoint);
    void refreshInspection();

    // --- the interest debug view (paper 004 Figure 5)
    void setInterestView(bool on);
    bool getInterestView() const { return _interestView; }

    // --- shaders
    /** Builds the style programs from the shader files again (OSG_FILE_PATH overrides);
     *  the compile log comes from checkPrograms() in the next draw. */
    void reloadShaders();
    bool programsToCheck = false;
    std::string shaderLog; ///< empty: the last reload compiled and linked

    // --- viewpoints
    struct Viewpoint
    {
        std::string name;
        osgLoA::CameraPose pose;
        bool user = false;
    };
    std::vector<Viewpoint> viewpoints;
    /** Adds a user viewpoint; with a viewpoints file (--viewpoints), writes every user
     *  viewpoint there (atomically), so they come back next time. */
    void addViewpoint(const std::string& name, const osgLoA::CameraPose& pose);
    std::string viewpointsFile;
    /** Reads user viewpoints: one a line, "NAME|ex ey ez|cx cy cz|ux uy uz" ('#' comments); a
     *  missing file is none yet. Throws std::runtime_error naming the file and line of a
     *  malformed one. */
    void readViewpoints(const std::string& path);
    void writeViewpoints(const std::string& path) const;

    // --- messages for the status line (edits refused, files written)
    std::string message;
    bool messageIsError = false;
    void say(const std::string& text, bool error = false);

    /** After undo/redo or any edit: rebuild what depends on the scenario's structure. */
    void afterEdit();
    bool undo();
    bool redo();

    /** Runs an edit, reporting a refused one (EditError) in the status line. */
    template <typename F> bool attempt(F&& f)
    {
        try
        {
            f();
            afterEdit();
            return true;
        }
        catch (const std::exception& e)
        {
            say(e.what(), true);
            return false;
        }
    }

private:
    void rewrap();
    /** The regions as the node placed them (scene coordinates), else as written. */
    const osgLoA::UsageScenario::Regions& fittedRegions() const;
    /** The circle region of that name as placed (scene coordinates); false when none. */
    bool fittedCircle(const std::string& name, osg::Vec2d& centre, double& radius) const;
    osg::Vec3d _lastEye;
    osgLoA::FeaturePicker::Hit pick(const osg::Camera& camera, double x, double y);
    std::string newCircleName() const;

    osg::ref_ptr<osg::Switch> _root;
    osg::ref_ptr<osg::Group> _styled;
    osg::ref_ptr<osgLoA::LoANode> _node;
    osg::ref_ptr<osgLoA::ScenarioEditor> _editor;
    bool _interestView = false;
    unsigned _wrappedRevision = ~0u;

    // The gesture under way.
    int _button = 0;
    bool _moved = false;
    double _pressX = 0.0, _pressY = 0.0;
    std::string _region;     ///< the circle being placed or moved
    osg::Vec2d _pressGround; ///< where the button went down (scene x, y)
    osg::Vec2d _grabOffset;  ///< circle centre - press point, when moving a circle
    bool _moving = false;
    int _routeVertex = -1;      ///< the route point being dragged
    bool _routeStarted = false; ///< a first route point waits for the second (a route needs two)
    osg::Vec2d _routeStart;
};

} // namespace loa

#endif
