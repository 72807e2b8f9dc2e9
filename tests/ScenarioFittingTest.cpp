// ScenarioFitting (issue 18 item 3): scene- and view-relative metrics, regions placed at the
// scene centre, at a feature or along the streets (chain of boxes, or network of centre lines), the focus on
// the tallest landmark, and what a user pins left alone; computed by hand on a small synthetic scene.
#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/ScenarioFitting>
#include <osgLoA/transitions/ScenarioLibrary>

#include <osg/Geode>
#include <osg/MatrixTransform>
#include <osg/ShapeDrawable>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace osgLoA;
typedef SaliencyMetric M;

namespace
{
void addFeature(osg::Group& root, unsigned id, FeatureType type, const osg::Vec3& min, const osg::Vec3& max,
                bool landmark = false)
{
    osg::ref_ptr<osg::Geode> g = new osg::Geode;
    g->addDrawable(new osg::ShapeDrawable(
        new osg::Box((min + max) * 0.5f, max.x() - min.x(), max.y() - min.y(), max.z() - min.z())));
    osg::ref_ptr<Feature> f = new Feature(id, type, "", Feature::MODEL_DATA);
    f->setLandmark(landmark);
    Feature::attach(*g, f.get());
    root.addChild(g);
}

/** 400 x 300 m: an L of three touching streets (0..300 along y = 0, then up x = 300 to
 *  y = 200), one lone street far off, a 20 m house, a 60 m tower, a 40 m landmark. */
osg::ref_ptr<osg::Group> scene()
{
    osg::ref_ptr<osg::Group> root = new osg::Group;
    addFeature(*root, 1, FeatureType::Terrain, {0, 0, -1}, {400, 300, 0});
    addFeature(*root, 2, FeatureType::Street, {0, -5, 0}, {150, 5, 0.2f});
    addFeature(*root, 3, FeatureType::Street, {150, -5, 0}, {305, 5, 0.2f});
    addFeature(*root, 4, FeatureType::Street, {295, 5, 0}, {305, 200, 0.2f});
    addFeature(*root, 5, FeatureType::Street, {20, 250, 0}, {60, 260, 0.2f}); // alone
    addFeature(*root, 6, FeatureType::Building, {50, 50, 0}, {70, 70, 20});
    addFeature(*root, 7, FeatureType::Building, {100, 100, 0}, {120, 120, 60});
    addFeature(*root, 8, FeatureType::Building, {200, 150, 0}, {220, 170, 40}, true);
    FeatureIndex(*root).updateBounds();
    return root;
}

osg::ref_ptr<TransitionConfiguration> config(M* metric)
{
    osg::ref_ptr<TransitionConfiguration> c = new TransitionConfiguration;
    c->setName("c");
    c->setStyle("photorealistic");
    c->setAllFeatureTypes();
    c->addMetric(metric);
    return c;
}
} // namespace

TEST(ScenarioFittingTest, AbsoluteScenariosAreBoundAsTheyAre)
{
    osg::ref_ptr<osg::Group> root = scene();
    FeatureIndex index(*root);
    osg::ref_ptr<UsageScenario> s = new UsageScenario;
    s->addConfiguration(config(new M(M::VIEW_DISTANCE, 10, 20)).get());
    s->addRegion(new RegionOfInterest(RegionOfInterest::CIRCLES, {{5, 5}}, 3));
    s->setFocusFeature(7);
    ScenarioFitting fitting;
    fitting.fit(*s, index);
    EXPECT_EQ(fitting.getScenario(), s.get());
    EXPECT_FALSE(fitting.followsView());
    // S = half the horizontal diagonal of the features' box: (0,-5)..(400,300) -> 0.5*hypot(400,305).
    EXPECT_NEAR(fitting.getSceneSize(), 0.5 * std::hypot(400.0, 305.0), 1e-3);
    EXPECT_NEAR(fitting.getSceneCentre().x(), 200.0, 1e-3);
    EXPECT_NEAR(fitting.getSceneCentre().y(), 147.5, 1e-3);
}

TEST(ScenarioFittingTest, SceneAndViewScalesPlacementsAndTheTallestLandmark)
{
    osg::ref_ptr<osg::Group> root = scene();
    FeatureIndex index(*root);
    const double S = 0.5 * std::hypot(400.0, 305.0);
    const osg::Vec3d C(200.0, 147.5, 29.5); // centre of (0,-5,-1)..(400,300,60)
    osg::ref_ptr<UsageScenario> s = new UsageScenario;
    s->setName("relative");
    osg::ref_ptr<M> region = new M(M::REGION, 0.1, 0.2);
    region->setScale(M::SCENE);
    osg::ref_ptr<M> distance = new M(M::VIEW_DISTANCE, 0.5, 2.0);
    distance->setScale(M::VIEW);
    osg::ref_ptr<M> pinned = new M(M::VIEW_ANGLE, 20, 50);
    osg::ref_ptr<TransitionConfiguration> c = config(region.get());
    c->addMetric(distance.get());
    c->addMetric(pinned.get());
    s->addConfiguration(c.get());
    osg::ref_ptr<RegionOfInterest> centre =
        new RegionOfInterest(RegionOfInterest::CIRCLES, {{0.1, 0.0}}, 0.05);
    centre->setName("centre");
    centre->setPlacement(RegionOfInterest::SCENE_CENTRE);
    centre->setSceneScale(true);
    s->addRegion(centre.get());
    osg::ref_ptr<RegionOfInterest> atTower = new RegionOfInterest(RegionOfInterest::CIRCLES, {{0, 0}}, 30);
    atTower->setName("tower");
    atTower->setPlacement(RegionOfInterest::FEATURE);
    atTower->setPlacementFeature(7);
    s->addRegion(atTower.get());
    osg::ref_ptr<RegionOfInterest> route = new RegionOfInterest(RegionOfInterest::POLYLINE, {}, 0.01);
    route->setName("route");
    route->setPlacement(RegionOfInterest::LONGEST_STREET);
    route->setSceneScale(true);
    s->addRegion(route.get());
    s->setFocusTallestLandmark(true);
    osg::ref_ptr<TransitionConfiguration> focus = config(new M(M::FOCUS, 1, 2));
    focus->setName("focus");
    s->addConfiguration(focus.get());
    ASSERT_TRUE(s->validate().ok()) << s->validate().errors.front();

    ScenarioFitting fitting;
    fitting.fit(*s, index);
    const UsageScenario& f = *fitting.getScenario();
    ASSERT_NE(&f, s.get());
    // The original is untouched.
    EXPECT_EQ(region->getScale(), M::SCENE);
    EXPECT_DOUBLE_EQ(region->getNear(), 0.1);
    EXPECT_EQ(centre->getPlacement(), RegionOfInterest::SCENE_CENTRE);
    // SCENE: times S; the view-angle metric is pinned (absolute) and stays.
    const auto& metrics = f.getConfigurations()[0]->getMetrics();
    EXPECT_NEAR(metrics[0]->getNear(), 0.1 * S, 1e-9);
    EXPECT_NEAR(metrics[0]->getFar(), 0.2 * S, 1e-9);
    EXPECT_EQ(metrics[0]->getScale(), M::ABSOLUTE);
    EXPECT_DOUBLE_EQ(metrics[2]->getNear(), 20.0);
    EXPECT_DOUBLE_EQ(metrics[2]->getFar(), 50.0);
    // VIEW: times the eye's distance to the scene centre, per eye.
    ASSERT_TRUE(fitting.followsView());
    const osg::Vec3d eye = C + osg::Vec3d(300, 0, 400); // 500 m away
    EXPECT_TRUE(fitting.applyEye(eye));
    EXPECT_NEAR(metrics[1]->getNear(), 250.0, 1e-6);
    EXPECT_NEAR(metrics[1]->getFar(), 1000.0, 1e-6);
    EXPECT_FALSE(fitting.applyEye(eye)); // unchanged
    EXPECT_TRUE(fitting.applyEye(C + osg::Vec3d(0, 0, 100)));
    EXPECT_NEAR(metrics[1]->getFar(), 200.0, 1e-6);
    // Regions: centre offset (0.1 S, 0), radius 0.05 S; at the tower's centre (110, 110),
    // radius 30 (not scene-scaled).
    const auto& regions = f.getRegions();
    EXPECT_NEAR(regions[0]->getVertices()[0].x(), 200.0 + 0.1 * S, 1e-6);
    EXPECT_NEAR(regions[0]->getVertices()[0].y(), 147.5, 1e-6);
    EXPECT_NEAR(regions[0]->getRadius(), 0.05 * S, 1e-9);
    EXPECT_NEAR(regions[1]->getVertices()[0].x(), 110.0, 1e-6);
    EXPECT_NEAR(regions[1]->getVertices()[0].y(), 110.0, 1e-6);
    EXPECT_DOUBLE_EQ(regions[1]->getRadius(), 30.0);
    // The longest street chain: 2 -> 3 -> 4 (the lone street 5 is another component), through
    // the centres (75,0), (227.5,0), (300,102.5); the simplification keeps the corner.
    ASSERT_EQ(regions[2]->getShape(), RegionOfInterest::POLYLINE);
    RegionOfInterest::Vertices v = regions[2]->getVertices();
    ASSERT_EQ(v.size(), 3u);
    if (v.front().y() > v.back().y()) std::reverse(v.begin(), v.end()); // either direction
    EXPECT_NEAR(v[0].x(), 75.0, 1e-3);
    EXPECT_NEAR(v[1].x(), 227.5, 1e-3);
    EXPECT_NEAR(v[2].y(), 102.5, 1e-3);
    EXPECT_NEAR(regions[2]->getRadius(), 0.01 * S, 1e-9);
    for (const auto& r : regions)
        EXPECT_TRUE(r->isResolved());
    // The focus: the landmark (feature 8, 40 m), not the taller plain tower (feature 7, 60 m).
    EXPECT_EQ(f.getFocusFeature(), 8u);
    EXPECT_FALSE(fitting.getNotes().empty());
}

TEST(ScenarioFittingTest, MissingFeaturesAndMissingStreetsAreHandled)
{
    osg::ref_ptr<osg::Group> root = scene();
    FeatureIndex index(*root);
    osg::ref_ptr<UsageScenario> s = new UsageScenario;
    s->addConfiguration(config(new M(M::REGION, 0, 10)).get());
    osg::ref_ptr<RegionOfInterest> r = new RegionOfInterest(RegionOfInterest::CIRCLES, {{0, 0}}, 5);
    r->setPlacement(RegionOfInterest::FEATURE);
    r->setPlacementFeature(99);
    s->addRegion(r.get());
    ScenarioFitting fitting;
    try
    {
        fitting.fit(*s, index);
        ADD_FAILURE() << "feature 99 was accepted";
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("feature 99"), std::string::npos) << e.what();
    }
    // No street at all: the route runs along the long axis through the centre, and says so.
    osg::ref_ptr<osg::Group> plain = new osg::Group;
    addFeature(*plain, 1, FeatureType::Terrain, {0, 0, 0}, {100, 40, 1});
    FeatureIndex(*plain).updateBounds();
    osg::ref_ptr<UsageScenario> route = ScenarioLibrary::createBuiltin("route");
    fitting.fit(*route, FeatureIndex(*plain));
    const RegionOfInterest& fitted = *fitting.getScenario()->getRegions()[0];
    ASSERT_EQ(fitted.getVertices().size(), 2u);
    EXPECT_NEAR(fitted.getVertices()[0].x(), 10.0, 1e-6);
    EXPECT_NEAR(fitted.getVertices()[1].x(), 90.0, 1e-6);
    EXPECT_NEAR(fitted.getVertices()[0].y(), 20.0, 1e-6);
    bool said = false;
    for (const std::string& n : fitting.getNotes())
        said = said || n.find("long axis") != std::string::npos;
    EXPECT_TRUE(said);
    // A scale the metric cannot have is a validation error.
    osg::ref_ptr<M> angle = new M(M::VIEW_ANGLE, 10, 20);
    angle->setScale(M::SCENE);
    EXPECT_NE(angle->validate().find("degrees"), std::string::npos);
    osg::ref_ptr<M> region = new M(M::REGION, 0, 1);
    region->setScale(M::VIEW);
    EXPECT_NE(region->validate().find("distance map"), std::string::npos);
}

// The LoA node binds the fitted scenario: the demo city's blueprint focuses on feature 184 (its
// tallest landmark, which the scenario used to name by id).
TEST(ScenarioFittingTest, LoANodeBindsTheFittedScenario)
{
    osg::ref_ptr<osg::Group> root = scene();
    osg::ref_ptr<LoANode> node = new LoANode;
    node->addChild(root.get());
    node->setScenario(ScenarioLibrary::createBuiltin("blueprint").get());
    node->bind();
    EXPECT_EQ(node->getScenario()->getFocusFeature(), 0u);
    EXPECT_EQ(node->getFitting().getScenario()->getFocusFeature(), 8u);
    EXPECT_TRUE(node->getEvaluator()->getView().focus.valid());
}

// Streets with centre lines (as the OSM importer gives them) form a network: the route is its
// longest shortest path through the junctions, along the lines, not through the features'
// centres. Network (metres): a main street A (0,0)-(100,0)-(200,0) as one way, a side street B
// from the junction (100,0) north to (100,80) then east to (160,80) (length 140), a spur C
// (200,0)-(200,-30) (length 30), a way D under a transform (translated by (0,-50)) whose own
// coordinates (0,50)-(-70,50) put it at (0,0)-(-70,0): it joins A's end. The farthest pair is
// (-70,0) .. (160,80): 70 + 100 + 140 = 310 m (via the junction at (100,0)), against
// (-70,0) .. (200,-30): 300 m and (160,80) .. (200,-30): 270 m. A lone way E far off is its own
// network. The route's vertices: (-70,0), (0,0), (100,0), (100,80), (160,80), minus (0,0),
// which is on a straight line.
TEST(ScenarioFittingTest, TheRouteFollowsTheCentreLinesOfAStreetNetwork)
{
    osg::ref_ptr<osg::Group> root = new osg::Group;
    auto way = [&](osg::Group& parent, unsigned id, const Feature::Centreline& line)
    {
        osg::ref_ptr<osg::Geode> g = new osg::Geode;
        osg::BoundingBox b;
        for (const osg::Vec2d& p : line)
            b.expandBy(osg::Vec3(p.x(), p.y(), 0.0f));
        g->addDrawable(new osg::ShapeDrawable(
            new osg::Box(b.center(), b.xMax() - b.xMin() + 4.0f, b.yMax() - b.yMin() + 4.0f, 0.2f)));
        osg::ref_ptr<Feature> f = new Feature(id, FeatureType::Street, "", Feature::MODEL_DATA);
        f->setCentreline(line);
        Feature::attach(*g, f.get());
        parent.addChild(g);
    };
    way(*root, 1, {{0, 0}, {100, 0}, {200, 0}});
    way(*root, 2, {{100, 0}, {100, 80}, {160, 80}});
    way(*root, 3, {{200, 0}, {200, -30}});
    osg::ref_ptr<osg::MatrixTransform> shifted = new osg::MatrixTransform(osg::Matrix::translate(0, -50, 0));
    root->addChild(shifted);
    way(*shifted, 4, {{0, 50}, {-70, 50}});
    way(*root, 5, {{1000, 1000}, {1010, 1000}});
    FeatureIndex index(*root);
    index.updateBounds();
    unsigned features = 0;
    std::vector<osg::Vec2d> v = ScenarioFitting::longestStreetChain(index, 1.0, &features);
    ASSERT_EQ(v.size(), 4u);
    if (v.front().x() > v.back().x()) std::reverse(v.begin(), v.end());
    const std::vector<osg::Vec2d> expected = {{-70, 0}, {100, 0}, {100, 80}, {160, 80}};
    for (std::size_t i = 0; i < expected.size(); ++i)
    {
        EXPECT_NEAR(v[i].x(), expected[i].x(), 1e-9) << i;
        EXPECT_NEAR(v[i].y(), expected[i].y(), 1e-9) << i;
    }
    EXPECT_EQ(features, 3u); // D, A, B

    // A network needs two ways: one way alone falls back to the chain of boxes (its centre).
    osg::ref_ptr<osg::Group> lone = new osg::Group;
    way(*lone, 1, {{0, 0}, {100, 0}});
    FeatureIndex loneIndex(*lone);
    loneIndex.updateBounds();
    v = ScenarioFitting::longestStreetChain(loneIndex, 1.0, &features);
    ASSERT_EQ(v.size(), 1u);
    EXPECT_NEAR(v[0].x(), 50.0, 1e-3);
}
