// Authoring usage scenarios in the view (issue 20), without a window: the scenario editor's
// undoable edits and what each rebuilds, picking from window points, the feature inspector's
// weights, the home view, and loa-viewer's session driven by pointer events as its window would
// drive it. The window itself (ImGui, scripted osgGA events under Xvfb) is LoaViewerGLTest's.
#include "../apps/loa-viewer/EventScript.h"
#include "../apps/loa-viewer/ViewerSession.h"
#include "support/TestSupport.h"

#include <osgLoA/authoring/FeatureInspector>
#include <osgLoA/authoring/FeaturePicker>
#include <osgLoA/authoring/HomeView>
#include <osgLoA/authoring/ScenarioEditor>
#include <osgLoA/city/CityGenerator>
#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/semantics/FeatureClassifier>
#include <osgLoA/transitions/ScenarioLibrary>
#include <osgLoA/util/AtomicFile>

#include <osg/ComputeBoundsVisitor>
#include <osg/Geode>
#include <osg/ShapeDrawable>
#include <osg/TriangleFunctor>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>
#include <osgGA/EventVisitor>
#include <osgGA/KeySwitchMatrixManipulator>
#include <osgGA/TrackballManipulator>
#include <osgViewer/View>

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>
#include <set>

using namespace osgLoA;

namespace
{
osg::ref_ptr<osg::Group> smallCity()
{
    CityParameters p;
    p.seed = 2;
    p.blocksX = 4;
    p.blocksY = 4;
    return CityGenerator(p).generate();
}

/** A LoA node over model with a library scenario, bound (evaluated once from above). */
osg::ref_ptr<LoANode> boundNode(osg::Node* model, const std::string& scenario)
{
    osg::ref_ptr<LoANode> node = new LoANode;
    node->setScenario(ScenarioLibrary::createBuiltin(scenario).get());
    node->addChild(model);
    node->evaluate(osg::Vec3d(0.0, -600.0, 400.0));
    return node;
}

/** A camera with the tools' perspective (45 degrees) at pose, over viewport. */
osg::ref_ptr<osg::Camera> cameraAt(const CameraPose& pose, const osg::Viewport& vp)
{
    osg::ref_ptr<osg::Camera> c = new osg::Camera;
    c->setViewport(vp.x(), vp.y(), vp.width(), vp.height());
    c->setViewMatrixAsLookAt(pose.eye, pose.center, pose.up);
    c->setProjectionMatrixAsPerspective(pose.fovy, vp.width() / vp.height(), 1.0, 10000.0);
    return c;
}

/** Where a window point's ray meets the horizontal plane z, by hand: the eye plus the ray's
 *  direction from the camera's basis and field of view (not through the inverse matrix the
 *  picker uses). */
osg::Vec3d rayAtHeight(const CameraPose& pose, const osg::Viewport& vp, double x, double y, double z)
{
    osg::Vec3d forward = pose.center - pose.eye;
    forward.normalize();
    osg::Vec3d right = forward ^ pose.up;
    right.normalize();
    const osg::Vec3d up = right ^ forward;
    const double t = std::tan(osg::DegreesToRadians(pose.fovy) * 0.5);
    const double aspect = vp.width() / vp.height();
    const double nx = 2.0 * (x - vp.x()) / vp.width() - 1.0, ny = 2.0 * (y - vp.y()) / vp.height() - 1.0;
    const osg::Vec3d dir = forward + right * (nx * t * aspect) + up * (ny * t);
    return pose.eye + dir * ((z - pose.eye.z()) / dir.z());
}

osg::Vec3d windowOf(const osg::Camera& c, const osg::Vec3d& p)
{
    return p * (c.getViewMatrix() * c.getProjectionMatrix() * c.getViewport()->computeWindowMatrix());
}

/** The centroid of the highest non-vertical triangle under node (world coordinates: the
 *  transforms above node included): a point on the roof of a building, whatever its
 *  footprint's shape (either winding: real models mix them). */
bool roofPoint(osg::Node& node, osg::Vec3d& point)
{
    osg::Matrixd above;
    const osg::NodePathList paths = node.getParentalNodePaths();
    if (!paths.empty() && paths.front().size() > 1)
        above = osg::computeLocalToWorld(osg::NodePath(paths.front().begin(), paths.front().end() - 1));
    struct Roof
    {
        osg::Matrixd m;
        double best = -1e300;
        osg::Vec3d point;
        void operator()(const osg::Vec3& a, const osg::Vec3& b, const osg::Vec3& c)
        {
            const osg::Vec3d wa = osg::Vec3d(a) * m, wb = osg::Vec3d(b) * m, wc = osg::Vec3d(c) * m;
            osg::Vec3d n = (wb - wa) ^ (wc - wa);
            if (n.length() < 1e-6) return;
            n.normalize();
            const osg::Vec3d centroid = (wa + wb + wc) / 3.0;
            // Highest among faces that are not vertical (a steep roof counts).
            if (std::fabs(n.z()) > 0.1 && centroid.z() > best)
            {
                best = centroid.z();
                point = centroid;
            }
        }
    };
    struct Visitor : osg::NodeVisitor
    {
        osg::TriangleFunctor<Roof> roof;
        osg::Matrixd above;
        Visitor() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
        void apply(osg::Drawable& d) override
        {
            roof.m = osg::computeLocalToWorld(getNodePath()) * this->above;
            d.accept(roof);
        }
    } v;
    v.above = above;
    node.accept(v);
    point = v.roof.point;
    return v.roof.best > -1e300;
}

/** loa-viewer's session over the small demo city with a library scenario, seen by the top
 *  camera at width x height, evaluated once from there (what the viewer's first frame does). */
struct SessionInView
{
    osg::ref_ptr<osg::Group> city = smallCity();
    osg::ref_ptr<UsageScenario> start;
    std::unique_ptr<loa::ViewerSession> session;
    osg::ref_ptr<osg::Viewport> viewport;
    CameraPose pose;
    osg::ref_ptr<osg::Camera> camera;
    SessionInView(const std::string& scenario, int width, int height)
        : start(ScenarioLibrary::createBuiltin(scenario)),
          session(new loa::ViewerSession(*city, *start, "built-in")),
          viewport(new osg::Viewport(0, 0, width, height))
    {
        pose = CityCameras::compute("top", *session->getRoot(), double(width) / double(height));
        camera = cameraAt(pose, *viewport);
        session->getNode().evaluate(pose.eye);
    }
};

const Feature* firstOfType(const LoANode& node, FeatureType type)
{
    for (const auto& e : node.getFeatureIndex().entries())
        if (e.feature->getType() == type && e.parent < 0) return e.feature.get();
    return nullptr;
}
} // namespace

TEST(ScenarioEditorTest, UndoAndRedoRestoreEveryValue)
{
    osg::ref_ptr<LoANode> node = boundNode(smallCity().get(), "distance");
    osg::ref_ptr<ScenarioEditor> e = new ScenarioEditor(*node);
    UsageScenario& s = e->getScenario();
    const osg::Vec2f fade0 = s.getConfigurations()[0]->getFadeIn();
    const std::string style1 = s.getConfigurations()[1]->getStyle();
    e->setFadeIn(0, osg::Vec2f(0.1f, 0.3f));
    e->setMetric(0, SaliencyMetric::VIEW_DISTANCE, 0.2, 1.2, 2.0);
    e->setStyle(1, "blueprint");
    EXPECT_EQ(s.getConfigurations()[0]->getFadeIn(), osg::Vec2f(0.1f, 0.3f));
    EXPECT_DOUBLE_EQ(s.getConfigurations()[0]->getMetric(SaliencyMetric::VIEW_DISTANCE)->getFar(), 1.2);
    EXPECT_DOUBLE_EQ(s.getConfigurations()[0]->getMetric(SaliencyMetric::VIEW_DISTANCE)->getWeight(), 2.0);
    EXPECT_EQ(s.getConfigurations()[1]->getStyle(), "blueprint");
    ASSERT_EQ(e->history().size(), 3u);
    EXPECT_TRUE(e->isModified());
    for (int i = 0; i < 3; ++i)
        ASSERT_TRUE(e->undo());
    EXPECT_FALSE(e->undo());
    EXPECT_EQ(s.getConfigurations()[0]->getFadeIn(), fade0);
    EXPECT_DOUBLE_EQ(s.getConfigurations()[0]->getMetric(SaliencyMetric::VIEW_DISTANCE)->getFar(), 1.5);
    EXPECT_EQ(s.getConfigurations()[1]->getStyle(), style1);
    EXPECT_FALSE(e->isModified());
    EXPECT_EQ(e->redoLabel(), "fade-in of '" + s.getConfigurations()[0]->getName() + "'");
    ASSERT_TRUE(e->redo());
    ASSERT_TRUE(e->redo());
    EXPECT_DOUBLE_EQ(s.getConfigurations()[0]->getMetric(SaliencyMetric::VIEW_DISTANCE)->getFar(), 1.2);
    EXPECT_EQ(s.getConfigurations()[1]->getStyle(), style1);
    // A new edit drops what could be redone.
    e->setFadeOut(2, osg::Vec2f(0.9f, 1.0f));
    EXPECT_FALSE(e->canRedo());
    EXPECT_EQ(e->history().size(), 3u);
    // The node kept its scenario object all along.
    EXPECT_EQ(node->getScenario(), &s);
}

TEST(ScenarioEditorTest, RefusesEditsThatBreakTheScenario)
{
    osg::ref_ptr<LoANode> node = boundNode(smallCity().get(), "distance");
    osg::ref_ptr<ScenarioEditor> e = new ScenarioEditor(*node);
    UsageScenario& s = e->getScenario();
    const osg::Vec2f before = s.getConfigurations()[0]->getFadeIn();
    try
    {
        e->setFadeIn(0, osg::Vec2f(0.8f, 0.2f));
        FAIL() << "an inverted fade-in was accepted";
    }
    catch (const EditError& error)
    {
        EXPECT_NE(std::string(error.what()).find(s.getConfigurations()[0]->getName()), std::string::npos)
            << error.what();
    }
    EXPECT_EQ(s.getConfigurations()[0]->getFadeIn(), before);
    EXPECT_EQ(e->history().size(), 0u);
    EXPECT_THROW(e->setStyle(0, "no-such-style"), EditError);
    EXPECT_THROW(e->placeCircle("c", osg::Vec2d(std::nan(""), 0.0), 10.0), EditError);
    EXPECT_THROW(e->placeCircle("c", osg::Vec2d(0.0, 0.0), -1.0), EditError);
    EXPECT_THROW(e->setFadeIn(7, osg::Vec2f(0.0f, 0.1f)), EditError);
    EXPECT_THROW(e->setFocusFeature(999999), EditError);
    EXPECT_THROW(e->setRegionFade(10.0), EditError); // no configuration measures a region
    // Removing configurations down to none: the last removal is refused.
    const std::size_t n = s.getConfigurations().size();
    for (std::size_t i = 1; i < n; ++i)
        e->removeConfiguration(0);
    EXPECT_THROW(e->removeConfiguration(0), EditError);
    EXPECT_EQ(s.getConfigurations().size(), 1u);
    EXPECT_TRUE(e->getValidation().ok());
}

TEST(ScenarioEditorTest, AGestureIsOneStep)
{
    osg::ref_ptr<LoANode> node = boundNode(smallCity().get(), "distance");
    osg::ref_ptr<ScenarioEditor> e = new ScenarioEditor(*node);
    e->beginGesture();
    for (int i = 1; i <= 5; ++i)
        e->placeCircle("c", osg::Vec2d(10.0 * i, 0.0), 20.0 * i);
    e->endGesture();
    ASSERT_EQ(e->history().size(), 1u);
    ASSERT_EQ(e->getScenario().getRegions().size(), 1u);
    EXPECT_DOUBLE_EQ(e->getScenario().getRegions()[0]->getRadius(), 100.0);
    EXPECT_EQ(e->getScenario().getRegions()[0]->getVertices()[0], osg::Vec2d(50.0, 0.0));
    e->undo();
    EXPECT_TRUE(e->getScenario().getRegions().empty());
    e->redo();
    EXPECT_DOUBLE_EQ(e->getScenario().getRegions()[0]->getRadius(), 100.0);
}

TEST(ScenarioEditorTest, AGestureMergesOnlyItsOwnEdits)
{
    // A drag's edits are one step; an edit of another kind arriving while the gesture is open
    // (a key pressed during a drag) is a step of its own.
    osg::ref_ptr<LoANode> node = boundNode(smallCity().get(), "distance");
    osg::ref_ptr<ScenarioEditor> e = new ScenarioEditor(*node);
    e->beginGesture();
    e->placeCircle("c", osg::Vec2d(0.0, 0.0), 10.0);
    e->placeCircle("c", osg::Vec2d(0.0, 0.0), 20.0);
    e->setFadeIn(0, osg::Vec2f(0.1f, 0.9f));
    e->placeCircle("c", osg::Vec2d(0.0, 0.0), 30.0);
    e->endGesture();
    EXPECT_EQ(e->history().size(), 3u);
    e->undo();
    EXPECT_DOUBLE_EQ(e->getScenario().getRegions()[0]->getRadius(), 20.0);
}

TEST(ScenarioEditorTest, ARegionFadeIsInSceneUnitsWhateverTheRampsScale)
{
    // circular-roi measures its region in multiples of the scene's size; a fade dragged in the
    // view is in scene units: the ramp becomes absolute from where the node placed its near end.
    osg::ref_ptr<LoANode> node = boundNode(smallCity().get(), "circular-roi");
    osg::ref_ptr<ScenarioEditor> e = new ScenarioEditor(*node);
    ASSERT_EQ(e->getScenario().getConfigurations()[0]->getMetric(SaliencyMetric::REGION)->getScale(),
              SaliencyMetric::SCENE);
    e->setRegionFade(30.0);
    for (const auto& c : e->getScenario().getConfigurations())
    {
        const SaliencyMetric* m = c->getMetric(SaliencyMetric::REGION);
        EXPECT_EQ(m->getScale(), SaliencyMetric::ABSOLUTE);
        EXPECT_DOUBLE_EQ(m->getNear(), 0.0);
        EXPECT_DOUBLE_EQ(m->getFar(), 30.0);
    }
    node->evaluate(osg::Vec3d(0.0, -600.0, 400.0));
    EXPECT_DOUBLE_EQ(node->getEvaluator()
                         ->getScenario()
                         ->getConfigurations()[0]
                         ->getMetric(SaliencyMetric::REGION)
                         ->getFar(),
                     30.0);
}

TEST(ScenarioEditorTest, ValueEditsRefitStructureEditsRebind)
{
    // Item 5: editing a fade range re-fits the scenario (uniforms) without indexing the features,
    // preparing styles or rebuilding the passes again; a style change rebinds.
    osg::ref_ptr<LoANode> node = boundNode(smallCity().get(), "distance");
    osg::ref_ptr<ScenarioEditor> e = new ScenarioEditor(*node);
    const osg::Vec3d eye(0.0, -600.0, 400.0);
    ASSERT_EQ(node->getBindCount(), 1u);
    e->setFadeIn(0, osg::Vec2f(0.1f, 0.3f));
    node->evaluate(eye);
    EXPECT_EQ(node->getBindCount(), 1u);
    EXPECT_EQ(node->getRefitCount(), 1u);
    // The evaluator sees the new fade: the fitted copy carries it.
    EXPECT_EQ(node->getEvaluator()->getScenario()->getConfigurations()[0]->getFadeIn(),
              osg::Vec2f(0.1f, 0.3f));
    e->setMetric(0, SaliencyMetric::VIEW_DISTANCE, 0.3, 1.4, 1.0);
    e->placeCircle("c", osg::Vec2d(0.0, 0.0), 50.0);
    node->evaluate(eye);
    EXPECT_EQ(node->getBindCount(), 1u);
    EXPECT_EQ(node->getRefitCount(), 2u); // two edits, one evaluation
    e->undo();
    node->evaluate(eye);
    EXPECT_EQ(node->getBindCount(), 1u);
    e->setStyle(1, "blueprint");
    node->evaluate(eye);
    EXPECT_EQ(node->getBindCount(), 2u);
    EXPECT_EQ(e->getCount(ScenarioEditor::VALUES), 4u);
    EXPECT_EQ(e->getCount(ScenarioEditor::STRUCTURE), 1u);
}

TEST(ScenarioEditorTest, AnInterestScopeEditThatChangesMatchesRebinds)
{
    // dirtyValues() is never wrong: a values edit whose matches differ is bound in full.
    osg::ref_ptr<LoANode> node = boundNode(smallCity().get(), "distance");
    osg::ref_ptr<ScenarioEditor> e = new ScenarioEditor(*node);
    e->edit("narrow the scope", ScenarioEditor::VALUES,
            [](UsageScenario& s) { s.getConfigurations()[0]->setInterestRange(osg::Vec2f(0.9f, 1.0f)); });
    node->evaluate(osg::Vec3d(0.0, -600.0, 400.0));
    EXPECT_EQ(node->getBindCount(), 2u);
}

TEST(ScenarioEditorTest, ATypeSetByHandIsAUserRuleForThatFeatureAlone)
{
    osg::ref_ptr<LoANode> node = boundNode(smallCity().get(), "distance");
    osg::ref_ptr<ScenarioEditor> e = new ScenarioEditor(*node);
    const Feature* building = firstOfType(*node, FeatureType::Building);
    ASSERT_TRUE(building);
    const unsigned id = building->getId();
    e->setFeatureType(id, FeatureType::Water);
    EXPECT_EQ(building->getType(), FeatureType::Water);
    EXPECT_EQ(building->getSource(), Feature::USER);
    ASSERT_EQ(e->getUserRules().getRules().size(), 1u);
    node->evaluate(osg::Vec3d(0.0, -600.0, 400.0));
    EXPECT_EQ(node->getBindCount(), 2u); // features re-indexed
    // The rule classifies a fresh copy of the model the same way: that feature, and only it.
    osg::ref_ptr<osg::Group> fresh = smallCity();
    osg::ref_ptr<ClassificationRuleSet> rules =
        new ClassificationRuleSet(e->getUserRules(), osg::CopyOp::DEEP_COPY_ALL);
    FeatureClassifier(rules.get()).classify(*fresh);
    unsigned water = 0, changed = 0;
    const FeatureIndex freshIndex(*fresh);
    for (const auto& entry : freshIndex.entries())
    {
        if (entry.feature->getId() == id)
        {
            EXPECT_EQ(entry.feature->getType(), FeatureType::Water);
        }
        water += entry.feature->getType() == FeatureType::Water ? 1 : 0;
        changed += entry.feature->getSource() == Feature::RULE ? 1 : 0;
    }
    EXPECT_EQ(changed, 1u);
    EXPECT_EQ(water, 2u); // the river and the building
    e->undo();
    EXPECT_EQ(building->getType(), FeatureType::Building);
    EXPECT_TRUE(e->getUserRules().getRules().empty());
    EXPECT_THROW(e->setFeatureType(999999, FeatureType::Green), EditError);
}

TEST(ScenarioEditorGLTest, OnlyARegionEditRecomputesTheDistanceMap)
{
    osg::ref_ptr<osg::Group> city = smallCity();
    osg::ref_ptr<LoANode> node = new LoANode;
    node->setScenario(ScenarioLibrary::createBuiltin("circular-roi").get());
    node->addChild(city.get());
    OffscreenRenderer::Settings settings;
    settings.width = 160;
    settings.height = 90;
    osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(settings);
    r->setSceneData(node.get());
    const CameraPose pose = CityCameras::compute("oblique", *city, 160.0 / 90.0);
    r->setViewMatrixAsLookAt(pose.eye, pose.center, pose.up);
    r->renderImage();
    ASSERT_TRUE(node->getDistanceField());
    const unsigned n0 = node->getDistanceField()->getNumComputations();
    ASSERT_GE(n0, 1u);
    osg::ref_ptr<ScenarioEditor> e = new ScenarioEditor(*node);
    e->setFadeIn(0, osg::Vec2f(0.2f, 1.0f));
    r->renderImage();
    EXPECT_EQ(node->getDistanceField()->getNumComputations(), n0)
        << "a fade edit recomputed the distance map";
    EXPECT_EQ(node->getBindCount(), 1u);
    e->placeCircle("centre", osg::Vec2d(100.0, 50.0), 120.0);
    r->renderImage();
    EXPECT_EQ(node->getDistanceField()->getNumComputations(), n0 + 1);
    e->setFadeOut(2, osg::Vec2f(0.1f, 0.9f));
    r->renderImage();
    EXPECT_EQ(node->getDistanceField()->getNumComputations(), n0 + 1);
    EXPECT_EQ(node->getBindCount(), 1u);
    EXPECT_GE(node->getRefitCount(), 3u);
}

TEST(FeaturePickerTest, FindsTheFeatureUnderAWindowPointAtEverySize)
{
    osg::ref_ptr<osg::Group> city = smallCity();
    osg::ref_ptr<LoANode> node = boundNode(city.get(), "distance");
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(node.get());
    for (const osg::ref_ptr<osg::Viewport>& viewport :
         {osg::ref_ptr<osg::Viewport>(new osg::Viewport(0, 0, 1920, 1080)),
          osg::ref_ptr<osg::Viewport>(new osg::Viewport(0, 0, 641, 359)),
          osg::ref_ptr<osg::Viewport>(new osg::Viewport(100, 50, 641, 359))})
    {
        const osg::Viewport& vp = *viewport;
        const CameraPose pose = CityCameras::compute("oblique", *root, vp.width() / vp.height());
        osg::ref_ptr<osg::Camera> camera = cameraAt(pose, vp);
        unsigned tried = 0, found = 0, behind = 0;
        for (const auto& entry : node->getFeatureIndex().entries())
        {
            if (entry.feature->getType() != FeatureType::Building) continue;
            osg::Vec3d top;
            if (!entry.node.valid() || !roofPoint(*entry.node, top)) continue;
            const osg::Vec3d w = windowOf(*camera, top);
            if (w.x() < vp.x() || w.y() < vp.y() || w.x() > vp.x() + vp.width() ||
                w.y() > vp.y() + vp.height())
                continue;
            ++tried;
            const FeaturePicker::Hit hit = FeaturePicker::pick(*camera, w.x(), w.y(), *root, *node);
            ASSERT_TRUE(hit.surface);
            // The hit lies on the ray: it projects back onto the window point.
            const osg::Vec3d back = windowOf(*camera, hit.world);
            EXPECT_NEAR(back.x(), w.x(), 1e-3);
            EXPECT_NEAR(back.y(), w.y(), 1e-3);
            if (hit.featureId == entry.feature->getId())
                ++found;
            else
            {
                // Another feature in front of the roof: its surface is nearer to the eye.
                EXPECT_LT((hit.world - pose.eye).length(), (top - pose.eye).length());
                EXPECT_NE(hit.featureId, 0u);
                ++behind;
            }
        }
        // Points on roofs seen from the oblique view: the building itself is hit, or one in
        // front of it.
        EXPECT_GE(tried, 10u);
        EXPECT_EQ(found + behind, tried);
        EXPECT_GE(found, tried - 2) << vp.x() << "," << vp.y() << " " << vp.width() << "x" << vp.height();
    }
}

TEST(FeaturePickerTest, PicksEachBuildingOfARealScene)
{
    // The OpenCity block (a scene nobody on the project made): 11 buildings by hand
    // (data/test-scenes/opencity-block.counts.json); each roof picked from the home view.
    const std::string file = std::string(LOA_SOURCE_DIR) + "/data/test-scenes/opencity-block.osgt";
    if (!osgDB::fileExists(std::string(LOA_SOURCE_DIR) + "/data/cache/opencity-data/pine2/pine2.ac"))
        GTEST_SKIP() << "the OpenCity models are absent: run scripts/fetch-test-data";
    osg::ref_ptr<osg::Node> block = osgDB::readRefNodeFile(file);
    ASSERT_TRUE(block.valid());
    FeatureClassifier().classify(*block);
    osg::ref_ptr<LoANode> node = boundNode(block.get(), "distance");
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(node.get());
    osg::ref_ptr<osg::Camera> camera = new osg::Camera;
    camera->setViewport(0, 0, 1921, 1081);
    camera->setProjectionMatrixAsPerspective(45.0, 1921.0 / 1081.0, 1.0, 10000.0);
    const CameraPose pose = HomeView::compute(*root, camera.get());
    camera->setViewMatrixAsLookAt(pose.eye, pose.center, pose.up);
    // A feature of a real model may span several nodes (walls in one geode, the roof in
    // another): its roof point is the highest over all of them.
    std::map<unsigned, osg::Vec3d> roofs;
    for (const auto& entry : node->getFeatureIndex().entries())
    {
        if (entry.feature->getType() != FeatureType::Building || !entry.node.valid()) continue;
        osg::Vec3d top;
        if (!roofPoint(*entry.node, top)) continue;
        auto it = roofs.find(entry.feature->getId());
        if (it == roofs.end() || top.z() > it->second.z()) roofs[entry.feature->getId()] = top;
    }
    std::set<unsigned> ids;
    for (const auto& entry : node->getFeatureIndex().entries())
        if (entry.feature->getType() == FeatureType::Building && entry.parent < 0)
            ids.insert(entry.feature->getId());
    const unsigned buildings = unsigned(ids.size());
    unsigned inView = 0, found = 0, hidden = 0;
    for (unsigned id : ids)
    {
        ASSERT_TRUE(roofs.count(id)) << "building " << id << " has no roof triangle";
        const osg::Vec3d top = roofs[id];
        const osg::Vec3d w = windowOf(*camera, top);
        if (w.x() < 0 || w.y() < 0 || w.x() > 1921 || w.y() > 1081) continue;
        ++inView;
        const FeaturePicker::Hit hit = FeaturePicker::pick(*camera, w.x(), w.y(), *root, *node);
        ASSERT_TRUE(hit.surface);
        if (hit.featureId == id)
            ++found;
        else
        {
            EXPECT_LT((hit.world - pose.eye).length(), (top - pose.eye).length()); // hidden by a nearer one
            ++hidden;
        }
    }
    EXPECT_EQ(buildings, 11u);
    EXPECT_EQ(inView, 11u); // the home view shows the whole block
    // Two roof points lie behind nearer features from the home view (checked above: nearer).
    EXPECT_EQ(found + hidden, 11u);
    EXPECT_GE(found, 9u);
}

TEST(FeaturePickerTest, OffTheModelTheGroundPlaneIsPicked)
{
    // One box feature, 20 m wide, on z = 0..20; the camera 100 m above its centre looking
    // down. A window point beside the box meets the plane of the features' lowest point.
    osg::ref_ptr<osg::Geode> box = new osg::Geode;
    box->addDrawable(new osg::ShapeDrawable(new osg::Box(osg::Vec3(0.0f, 0.0f, 10.0f), 20.0f)));
    Feature::attach(*box, new Feature(7, FeatureType::Building));
    osg::ref_ptr<LoANode> node = new LoANode;
    node->setScenario(ScenarioLibrary::createHomogeneous("photorealistic").get());
    node->addChild(box.get());
    node->evaluate(osg::Vec3d(0.0, 0.0, 100.0));
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(node.get());
    CameraPose pose;
    pose.eye.set(0.0, 0.0, 100.0);
    pose.center.set(0.0, 0.0, 0.0);
    pose.up.set(0.0, 1.0, 0.0);
    osg::ref_ptr<osg::Viewport> viewport = new osg::Viewport(30, 20, 200, 200);
    const osg::Viewport& vp = *viewport;
    osg::ref_ptr<osg::Camera> camera = cameraAt(pose, vp);
    // Pixel (210, 120): nx = 0.8, ny = 0 -> x = 0.8 tan(22.5 deg) 100 = 33.14 m on z = 0.
    const FeaturePicker::Hit off = FeaturePicker::pick(*camera, 210.0, 120.0, *root, *node);
    EXPECT_FALSE(off.surface);
    ASSERT_TRUE(off.ground);
    EXPECT_EQ(off.featureId, 0u);
    EXPECT_NEAR(off.scene.x(), 0.8 * std::tan(osg::DegreesToRadians(22.5)) * 100.0, 1e-6);
    EXPECT_NEAR(off.scene.y(), 0.0, 1e-6);
    EXPECT_NEAR(off.scene.z(), 0.0, 1e-9);
    const osg::Vec3d hand = rayAtHeight(pose, vp, 210.0, 120.0, 0.0);
    EXPECT_NEAR(off.scene.x(), hand.x(), 1e-6);
    // The box's centre pixel: its top face at z = 20.
    const FeaturePicker::Hit on = FeaturePicker::pick(*camera, 130.0, 120.0, *root, *node);
    ASSERT_TRUE(on.surface);
    EXPECT_EQ(on.featureId, 7u);
    EXPECT_NEAR(on.scene.z(), 20.0, 1e-4);
    // Looking up at the sky: no ground in front of the camera.
    pose.center.set(0.0, 0.0, 200.0);
    pose.up.set(0.0, 1.0, 0.0);
    osg::ref_ptr<osg::Camera> up = cameraAt(pose, vp);
    EXPECT_FALSE(FeaturePicker::pick(*up, 130.0, 120.0, *root, *node).ground);
}

TEST(FeatureInspectorTest, WeightsAtAPointAreTheBlendFunctionsOfItsInterest)
{
    // Terrain drawn per fragment: photorealistic fading in and abstract fading out over the
    // region interest 1 - d / 100 around a circle of radius 0 at the origin.
    osg::ref_ptr<osg::Group> city = smallCity();
    osg::ref_ptr<UsageScenario> s = new UsageScenario;
    s->addRegion(new RegionOfInterest(RegionOfInterest::CIRCLES, {osg::Vec2d(0.0, 0.0)}, 0.0));
    ScenarioLibrary::appendTwoLevels(
        *s, *osg::ref_ptr<SaliencyMetric>(new SaliencyMetric(SaliencyMetric::REGION, 0.0, 100.0)),
        "photorealistic", "abstract");
    osg::ref_ptr<LoANode> node = new LoANode;
    node->setScenario(s.get());
    node->addChild(city.get());
    node->evaluate(osg::Vec3d(0.0, -600.0, 400.0));
    const Feature* terrain = firstOfType(*node, FeatureType::Terrain);
    ASSERT_TRUE(terrain);
    auto smoothstep = [](double t) { return t * t * (3.0 - 2.0 * t); };
    for (const osg::Vec3d& p :
         {osg::Vec3d(30.0, 40.0, 0.0), osg::Vec3d(60.0, 0.0, 0.0), osg::Vec3d(0.0, -150.0, 0.0)})
    {
        const FeatureInspector::Report r = FeatureInspector::inspect(*node, terrain->getId(), p);
        ASSERT_TRUE(r.found);
        EXPECT_EQ(r.type, "terrain");
        ASSERT_EQ(r.weights.size(), 2u); // photorealistic-areas, abstract-areas
        const double d = std::hypot(p.x(), p.y());
        const double interest = std::max(0.0, 1.0 - d / 100.0);
        EXPECT_NEAR(r.weights[0].interest, interest, 1e-5);
        EXPECT_NEAR(r.weights[0].weight, smoothstep(interest), 1e-5) << d;
        EXPECT_NEAR(r.weights[1].weight, 1.0 - smoothstep(interest), 1e-5) << d;
        EXPECT_EQ(r.weights[0].interpolation, "fragment");
    }
    EXPECT_FALSE(FeatureInspector::inspect(*node, 999999, osg::Vec3d()).found);
}

TEST(HomeViewTest, FramesTheCityFromTheSouthWest)
{
    osg::ref_ptr<osg::Group> city = smallCity();
    osg::ref_ptr<osg::Camera> camera = new osg::Camera;
    camera->setViewport(0, 0, 1920, 1080);
    camera->setProjectionMatrixAsPerspective(30.0, 1920.0 / 1080.0, 1.0, 10000.0);
    const CameraPose pose = HomeView::compute(*city, camera.get());
    osg::ComputeBoundsVisitor cbv;
    city->accept(cbv);
    const osg::BoundingBox& b = cbv.getBoundingBox();
    EXPECT_LT(pose.eye.x(), b.center().x());
    EXPECT_LT(pose.eye.y(), b.center().y());
    const osg::Vec3d d = pose.center - pose.eye;
    const double pitch = osg::RadiansToDegrees(std::atan2(-d.z(), std::hypot(d.x(), d.y())));
    EXPECT_GT(pitch, 20.0);
    EXPECT_LT(pitch, 50.0);
    EXPECT_DOUBLE_EQ(pose.fovy, 30.0);
    // The features' ground extent is in view with this camera's 30 degrees.
    camera->setViewMatrixAsLookAt(pose.eye, pose.center, pose.up);
    const osg::Matrixd vp = camera->getViewMatrix() * camera->getProjectionMatrix();
    osg::ref_ptr<LoANode> node = boundNode(city.get(), "distance");
    osg::BoundingBoxd features;
    for (const auto& e : node->getFeatureIndex().entries())
        if (e.parent < 0 && e.feature->getType() != FeatureType::Terrain && e.feature->getBound().valid())
            features.expandBy(osg::BoundingBoxd(osg::Vec3d(e.feature->getBound()._min),
                                                osg::Vec3d(e.feature->getBound()._max)));
    for (unsigned i = 0; i < 8; ++i)
    {
        const osg::Vec3d ndc = features.corner(i) * vp;
        EXPECT_LE(std::fabs(ndc.x()), 1.0) << i;
        EXPECT_LE(std::fabs(ndc.y()), 1.0) << i;
    }
}

TEST(HomeViewTest, ALoaSceneSetsTheStockViewersHome)
{
    // What the stock osgviewer does with `demo.loacity.loa`: the first event traversal reaches
    // the LoA node, which gives the view's manipulator its oblique home (not OSG's edge-on one).
    osg::ref_ptr<osgDB::Options> options = new osgDB::Options("seed=2 blocksX=4 blocksY=4");
    osg::ref_ptr<osg::Node> read = osgDB::readRefNodeFile("demo.loacity.loa", options.get());
    osg::ref_ptr<LoANode> node = dynamic_cast<LoANode*>(read.get());
    ASSERT_TRUE(node.valid());
    EXPECT_TRUE(node->getHomeViewPending());
    EXPECT_EQ(node->getNumChildrenRequiringEventTraversal(), 1u);
    osg::ref_ptr<osgViewer::View> view = new osgViewer::View;
    view->getCamera()->setViewport(0, 0, 800, 600);
    view->getCamera()->setProjectionMatrixAsPerspective(30.0, 800.0 / 600.0, 1.0, 10000.0);
    // As osgviewer holds it: a trackball (and others) in a KeySwitchMatrixManipulator.
    osg::ref_ptr<osgGA::TrackballManipulator> trackball = new osgGA::TrackballManipulator;
    osg::ref_ptr<osgGA::TrackballManipulator> second = new osgGA::TrackballManipulator;
    osg::ref_ptr<osgGA::KeySwitchMatrixManipulator> keySwitch = new osgGA::KeySwitchMatrixManipulator;
    keySwitch->addMatrixManipulator('1', "Trackball", trackball.get());
    keySwitch->addMatrixManipulator('2', "Other", second.get());
    view->setCameraManipulator(keySwitch.get(), true); // OSG's edge-on home first
    view->setSceneData(node.get());
    osgGA::EventVisitor ev;
    ev.setActionAdapter(view.get());
    node->accept(ev);
    EXPECT_FALSE(node->getHomeViewPending());
    EXPECT_EQ(node->getNumChildrenRequiringEventTraversal(), 0u);
    osg::Vec3d eye, center, up;
    trackball->getHomePosition(eye, center, up);
    const CameraPose expected = HomeView::compute(*node, view->getCamera());
    EXPECT_LT((eye - expected.eye).length(), 1e-6);
    EXPECT_LT((center - expected.center).length(), 1e-6);
    EXPECT_FALSE(trackball->getAutoComputeHomePosition());
    // The manipulators stand there now: the view's camera is looking from the home.
    osg::Vec3d e2, c2, u2;
    trackball->getTransformation(e2, c2, u2);
    EXPECT_LT((e2 - expected.eye).length(), 1e-6);
    second->getTransformation(e2, c2, u2);
    EXPECT_LT((e2 - expected.eye).length(), 1e-6);
    const osg::Matrixd seen = keySwitch->getInverseMatrix();
    const osg::Matrixd wanted = osg::Matrixd::lookAt(expected.eye, expected.center, expected.up);
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            EXPECT_NEAR(seen(i, j), wanted(i, j), 1e-6 * std::max(1.0, std::fabs(wanted(i, j))));
}

TEST(ViewerSessionTest, TheCircleOfInterestAuthoredWithThePointer)
{
    // What a user does in loa-viewer (region mode): drag a circle on the ground, make the circle
    // scenario (Shift+R), drag its fade with the right button, save; then undo it all.
    SessionInView view("distance", 1920, 1080);
    loa::ViewerSession& session = *view.session;
    const osg::Viewport& vp = *view.viewport;
    const CameraPose& pose = view.pose;
    const osg::ref_ptr<osg::Camera> camera = view.camera;
    session.mode = loa::ViewerSession::REGION;
    const double x0 = 960.5, y0 = 540.5, x1 = 1140.5, x2 = 1260.5;
    ASSERT_TRUE(session.press(*camera, x0, y0, 1));
    for (int i = 1; i <= 8; ++i)
        session.drag(*camera, x0 + (x1 - x0) * i / 8.0, y0);
    ASSERT_TRUE(session.release(*camera, x1, y0));
    UsageScenario& s = session.getEditor().getScenario();
    ASSERT_EQ(s.getRegions().size(), 1u);
    const RegionOfInterest& circle = *s.getRegions()[0];
    // Hand: the rays of the two window points at the heights the picker found there.
    const FeaturePicker::Hit h0 = FeaturePicker::pick(*camera, x0, y0, *session.getRoot(), session.getNode());
    const FeaturePicker::Hit h1 = FeaturePicker::pick(*camera, x1, y0, *session.getRoot(), session.getNode());
    const osg::Vec3d c = rayAtHeight(pose, vp, x0, y0, h0.scene.z());
    const osg::Vec3d r = rayAtHeight(pose, vp, x1, y0, h1.scene.z());
    EXPECT_NEAR(circle.getVertices()[0].x(), c.x(), 1e-3);
    EXPECT_NEAR(circle.getVertices()[0].y(), c.y(), 1e-3);
    const double radius = std::hypot(r.x() - c.x(), r.y() - c.y());
    EXPECT_NEAR(circle.getRadius(), radius, 1e-3);
    EXPECT_GT(radius, 20.0);
    EXPECT_EQ(session.getEditor().history().size(), 1u); // one gesture
    session.useRegionDetail();
    ASSERT_EQ(s.getConfigurations().size(), 4u);
    for (const auto& cfg : s.getConfigurations())
    {
        ASSERT_TRUE(cfg->getMetric(SaliencyMetric::REGION));
        EXPECT_NEAR(cfg->getMetric(SaliencyMetric::REGION)->getFar(), 0.6 * radius, 1e-3);
    }
    session.press(*camera, x0, y0, 3);
    session.drag(*camera, x2, y0);
    session.release(*camera, x2, y0);
    const FeaturePicker::Hit h2 = FeaturePicker::pick(*camera, x2, y0, *session.getRoot(), session.getNode());
    const osg::Vec3d f = rayAtHeight(pose, vp, x2, y0, h2.scene.z());
    const double fade = std::hypot(f.x() - c.x(), f.y() - c.y()) - radius;
    for (const auto& cfg : s.getConfigurations())
        EXPECT_NEAR(cfg->getMetric(SaliencyMetric::REGION)->getFar(), fade, 1e-3);
    // Saved and read back: the same circle and fade.
    const std::string file = loatest::freshDirectory("viewer-session") + "/circle.osgt";
    session.saveScenario(file);
    EXPECT_FALSE(session.getEditor().isModified());
    osg::ref_ptr<UsageScenario> saved = ScenarioLibrary::readFile(file);
    ASSERT_EQ(saved->getRegions().size(), 1u);
    EXPECT_NEAR(saved->getRegions()[0]->getRadius(), radius, 1e-3);
    EXPECT_NEAR(saved->getConfigurations()[3]->getMetric(SaliencyMetric::REGION)->getFar(), fade, 1e-3);
    // Undo all three steps: the distance scenario as it was.
    for (int i = 0; i < 3; ++i)
        EXPECT_TRUE(session.undo());
    EXPECT_TRUE(s.getRegions().empty());
    EXPECT_EQ(s.getConfigurations().size(), view.start->getConfigurations().size());
    EXPECT_TRUE(s.getConfigurations()[0]->getMetric(SaliencyMetric::VIEW_DISTANCE));
}

TEST(ViewerSessionTest, RoutePointsFocusAndInspection)
{
    SessionInView view("distance", 641, 359);
    loa::ViewerSession& session = *view.session;
    const osg::Viewport& vp = *view.viewport;
    const osg::ref_ptr<osg::Camera> camera = view.camera;
    auto click = [&](double x, double y, int button)
    {
        session.press(*camera, x, y, button);
        session.release(*camera, x, y);
    };
    session.mode = loa::ViewerSession::ROUTE;
    click(100.5, 100.5, 1);
    click(300.5, 120.5, 1);
    click(500.5, 200.5, 1);
    UsageScenario& s = session.getEditor().getScenario();
    ASSERT_EQ(s.getRegions().size(), 1u);
    ASSERT_EQ(s.getRegions()[0]->getVertices().size(), 3u);
    EXPECT_EQ(s.getRegions()[0]->getShape(), RegionOfInterest::POLYLINE);
    EXPECT_DOUBLE_EQ(s.getRegions()[0]->getLineWidth(), 6.0);
    // Drag the second point 40 px to the right; right-click the first away.
    session.press(*camera, 300.5, 120.5, 1);
    for (int i = 1; i <= 4; ++i)
        session.drag(*camera, 300.5 + 10.0 * i, 120.5);
    session.release(*camera, 340.5, 120.5);
    const FeaturePicker::Hit moved =
        FeaturePicker::pick(*camera, 340.5, 120.5, *session.getRoot(), session.getNode());
    EXPECT_NEAR(s.getRegions()[0]->getVertices()[1].x(), moved.scene.x(), 1e-6);
    click(100.5, 100.5, 3);
    ASSERT_EQ(s.getRegions()[0]->getVertices().size(), 2u);
    EXPECT_NEAR(s.getRegions()[0]->getVertices()[0].x(), moved.scene.x(), 1e-6);
    EXPECT_EQ(session.getEditor().history().size(), 4u); // the route waits for its second point
    // Focus mode: a click on a building makes it the focus object; inspect mode reports it.
    const Feature* building = nullptr;
    osg::Vec3d w;
    for (const auto& e : session.getNode().getFeatureIndex().entries())
    {
        if (e.feature->getType() != FeatureType::Building) continue;
        const osg::BoundingBoxf& b = e.feature->getBound();
        w = windowOf(*camera, osg::Vec3d(b.center().x(), b.center().y(), b.zMax() - 0.01));
        if (w.x() > 0 && w.y() > 0 && w.x() < vp.width() && w.y() < vp.height())
        {
            building = e.feature.get();
            break;
        }
    }
    ASSERT_TRUE(building);
    session.mode = loa::ViewerSession::FOCUS;
    click(w.x(), w.y(), 1);
    EXPECT_EQ(s.getFocusFeature(), building->getId());
    session.mode = loa::ViewerSession::INSPECT;
    click(w.x(), w.y(), 1);
    ASSERT_TRUE(session.inspected);
    EXPECT_EQ(session.inspection.id, building->getId());
    EXPECT_EQ(session.inspection.type, "building");
    EXPECT_TRUE(session.inspection.focus); // the focus edit was evaluated before the inspection
    // An edit while a feature is inspected refreshes the inspection from the edited scenario:
    // a configuration removed is gone from its weights.
    const std::size_t weightsBefore = session.inspection.weights.size();
    ASSERT_GE(weightsBefore, 1u);
    const unsigned firstMatch = session.inspection.weights[0].configuration;
    ASSERT_TRUE(session.attempt([&] { session.getEditor().removeConfiguration(firstMatch); }));
    EXPECT_EQ(session.inspection.weights.size(), weightsBefore - 1);
    session.undo();
    EXPECT_EQ(session.inspection.weights.size(), weightsBefore);
    // A type set by hand is saved beside the scenario as a rule set the tools read (--rules).
    session.getEditor().setFeatureType(building->getId(), FeatureType::Green, "park");
    const std::string file = loatest::freshDirectory("viewer-rules") + "/s.osgt";
    session.saveScenario(file);
    ASSERT_EQ(loa::ViewerSession::rulesPathFor(file), file.substr(0, file.size() - 5) + ".rules.osgt");
    osg::ref_ptr<ClassificationRuleSet> rules =
        ClassificationRuleSet::read(loa::ViewerSession::rulesPathFor(file));
    ASSERT_EQ(rules->getRules().size(), 1u);
    EXPECT_EQ(rules->getRules()[0]->getType(), FeatureType::Green);
    EXPECT_EQ(rules->getRules()[0]->getSubType(), "park");
    // Navigate mode leaves the pointer to the camera.
    session.mode = loa::ViewerSession::NAVIGATE;
    EXPECT_FALSE(session.press(*camera, 10, 10, 1));
}

TEST(ViewerSessionTest, ALibraryCircleIsMovedWhereTheSceneShowsIt)
{
    // circular-roi's circle is placed at the scene's centre with a radius of 0.14 times the
    // scene's size: dragged in the view, it moves by the drag and keeps the radius it is drawn
    // with (scene units), becoming absolute.
    SessionInView view("circular-roi", 1920, 1080);
    loa::ViewerSession& session = *view.session;
    const osg::ref_ptr<osg::Camera> camera = view.camera;
    const RegionOfInterest& placed = *session.getNode().getEvaluator()->getScenario()->getRegions()[0];
    const osg::Vec2d centre = placed.getVertices()[0];
    const double radius = placed.getRadius();
    ASSERT_GT(radius, 10.0); // scene units, not the written 0.14
    const osg::Vec3d w = windowOf(*camera, osg::Vec3d(centre.x(), centre.y(), 0.0));
    session.mode = loa::ViewerSession::REGION;
    ASSERT_TRUE(session.press(*camera, w.x(), w.y(), 1));
    session.drag(*camera, w.x() + 50.0, w.y());
    session.drag(*camera, w.x() + 100.0, w.y());
    session.release(*camera, w.x() + 100.0, w.y());
    const RegionOfInterest& moved = *session.getEditor().getScenario().getRegions()[0];
    EXPECT_TRUE(moved.isResolved());
    EXPECT_NEAR(moved.getRadius(), radius, 1e-9);
    const FeaturePicker::Hit a =
        FeaturePicker::pick(*camera, w.x(), w.y(), *session.getRoot(), session.getNode());
    const FeaturePicker::Hit b =
        FeaturePicker::pick(*camera, w.x() + 100.0, w.y(), *session.getRoot(), session.getNode());
    EXPECT_NEAR(moved.getVertices()[0].x(), centre.x() + (b.scene.x() - a.scene.x()), 1e-6);
    EXPECT_NEAR(moved.getVertices()[0].y(), centre.y() + (b.scene.y() - a.scene.y()), 1e-6);
    EXPECT_EQ(session.getEditor().history().size(), 1u);
}

TEST(ViewerSessionTest, SavedViewpointsComeBack)
{
    osg::ref_ptr<osg::Group> city = smallCity();
    osg::ref_ptr<UsageScenario> start = ScenarioLibrary::createBuiltin("distance");
    const std::string file = loatest::freshDirectory("viewer-viewpoints") + "/views.txt";
    CameraPose a, b;
    a.eye.set(1.5, -200.25, 80.0);
    a.center.set(0.0, 0.0, 0.0);
    a.up.set(0.0, 0.0, 1.0);
    b.eye.set(-3.0, 4.0, 500.0);
    b.center.set(-3.0, 4.0, 0.0);
    b.up.set(0.0, 1.0, 0.0);
    {
        loa::ViewerSession session(*city, *start, "built-in");
        session.readViewpoints(file); // none yet
        EXPECT_TRUE(session.viewpoints.empty());
        session.viewpointsFile = file;
        session.addViewpoint("gate", a);
        session.addViewpoint("above", b);
    }
    loa::ViewerSession again(*city, *start, "built-in");
    again.readViewpoints(file);
    ASSERT_EQ(again.viewpoints.size(), 2u);
    EXPECT_EQ(again.viewpoints[0].name, "gate");
    EXPECT_EQ(again.viewpoints[0].pose.eye, a.eye);
    EXPECT_EQ(again.viewpoints[1].pose.up, b.up);
    EXPECT_TRUE(again.viewpoints[1].user);
    // A malformed line is named.
    osgLoA::AtomicFile::writeText(file, "ok|1 2 3|0 0 0|0 0 1\nbroken|1 2|0 0 0|0 0 1\n");
    try
    {
        again.readViewpoints(file);
        ADD_FAILURE() << "a malformed viewpoints file was accepted";
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find("views.txt:2"), std::string::npos) << e.what();
    }
}

TEST(EventScriptTest, ParsesCommandsAndNamesTheLineOfAnError)
{
    const loa::EventScript ok =
        loa::EventScript::parse("# a comment\nkey r\nkey s ctrl\ndrag 1 2 3 4 right steps 3\nclick 5 6\nwait "
                                "10\nscreenshot a.png\nquit\n",
                                "demo");
    EXPECT_EQ(ok.size(), 7u);
    for (const std::pair<const char*, const char*>& bad :
         {std::make_pair("key\n", "demo:1: key needs a key"),
          std::make_pair("\nkey nosuchkey\n", "demo:2: unknown key"),
          std::make_pair("click 1\n", "demo:1: 'click' needs more numbers"),
          std::make_pair("drag 1 2 3 x\n", "demo:1: 'x' is not a number"),
          std::make_pair("fly 1\n", "demo:1: unknown command 'fly'"),
          std::make_pair("drag 1 2 3 4 steps 0\n", "demo:1: steps must be 1 to 1000")})
    {
        try
        {
            loa::EventScript::parse(bad.first, "demo");
            ADD_FAILURE() << bad.first;
        }
        catch (const std::runtime_error& e)
        {
            EXPECT_NE(std::string(e.what()).find(bad.second), std::string::npos) << e.what();
        }
    }
}
