// LoANode without GL: OSG calls apply(osg::Group&) for it (ARCHITECTURE §3: a visitor that
// cares about osgLoA types casts there), and its bind/evaluate path for tools.
#include "support/TestSupport.h"

#include <osgLoA/semantics/Feature>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/ScenarioLibrary>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/MatrixTransform>
#include <osg/NodeVisitor>

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

using namespace osgLoA;

namespace
{
osg::ref_ptr<osg::Geode> box(unsigned id, FeatureType type, const osg::Vec3& minimum,
                             const osg::Vec3& maximum)
{
    osg::ref_ptr<osg::Geode> geode = loatest::boxGeode(minimum, maximum);
    Feature::attach(*geode, new Feature(id, type));
    return geode;
}

/** Finds LoA nodes the way ARCHITECTURE §3 says a visitor should: OSG has no apply() for
 *  osgLoA's types, so it calls apply(osg::Group&), and the visitor casts there. */
class FindLoANodes : public osg::NodeVisitor
{
public:
    FindLoANodes() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
    void apply(osg::Group& group) override
    {
        ++groups;
        if (LoANode* n = dynamic_cast<LoANode*>(&group)) found.push_back(n);
        traverse(group);
    }
    void apply(osg::Node& node) override
    {
        ++otherNodes;
        traverse(node);
    }
    std::vector<LoANode*> found;
    unsigned groups = 0, otherNodes = 0;
};
} // namespace

TEST(LoANodeTest, VisitorsFindItThroughApplyGroup)
{
    osg::ref_ptr<osg::Group> root = new osg::Group;
    osg::ref_ptr<LoANode> outer = new LoANode;
    osg::ref_ptr<osg::MatrixTransform> xf = new osg::MatrixTransform;
    osg::ref_ptr<LoANode> inner = new LoANode;
    root->addChild(outer.get());
    outer->addChild(xf.get());
    xf->addChild(inner.get());
    inner->addChild(box(1, FeatureType::Building, osg::Vec3(), osg::Vec3(1, 1, 1)).get());
    FindLoANodes v;
    root->accept(v);
    EXPECT_EQ(v.found, (std::vector<LoANode*>{outer.get(), inner.get()}));
    // root, outer, the transform, inner and the Geode (all Groups in OSG 3.6) arrive in
    // apply(osg::Group&); LoANode has no apply() of its own that would bypass it. The Geometry
    // is the one node that does not (apply(Drawable&) -> apply(Node&)).
    EXPECT_EQ(v.groups, 5u);
    EXPECT_EQ(v.otherNodes, 1u);
}

TEST(LoANodeTest, BindsLazilyAndEvaluatesForAnEye)
{
    osg::ref_ptr<LoANode> node = new LoANode;
    node->addChild(box(1, FeatureType::Building, osg::Vec3(195, -5, 0), osg::Vec3(205, 5, 10)).get());
    node->setScenario(ScenarioLibrary::createBuiltin("distance").get());
    // distance scenario: view distance 0.25 D .. 1.5 D, D the eye's distance to the centre of
    // the features' box, here the building's centre (200,0,5); eye at (0,0,5): distance 200 =
    // D -> interest 1 - 0.75/1.25 = 0.4 -> abstract only (its fade-in 0.25..0.4 done, the
    // photorealistic fade-in 0.6..0.75 not begun, the cartographic fade-out 0.25..0.4 done).
    node->evaluate(osg::Vec3d(0, 0, 5));
    const ScenarioEvaluator* e = node->getEvaluator();
    ASSERT_TRUE(e->isBound());
    ASSERT_EQ(e->features().size(), 1u);
    const ScenarioEvaluator::Match* m = e->matchesOf(e->features()[0]);
    ASSERT_EQ(e->features()[0].numMatches, 3u);
    EXPECT_NEAR(m[0].interest, 0.4f, 1e-5f);
    EXPECT_EQ(node->getScenario()->getConfigurations()[m[1].configuration]->getStyle(), "abstract");
    EXPECT_EQ(m[0].weight, 0.0f);
    EXPECT_EQ(m[1].weight, 1.0f);
    // The bound (fitted) metric: near 0.25 x 200 = 50 m, far 1.5 x 200 = 300 m.
    const SaliencyMetric* fitted = e->getScenario()->getConfigurations()[0]->getMetrics()[0].get();
    EXPECT_NEAR(fitted->getNear(), 50.0, 1e-9);
    EXPECT_NEAR(fitted->getFar(), 300.0, 1e-9);
    EXPECT_EQ(node->getBindError(), "");
    // A child inserted, replaced or removed is picked up at the next evaluation.
    node->insertChild(0, box(2, FeatureType::Water, osg::Vec3(0, 0, 0), osg::Vec3(10, 10, 1)).get());
    node->evaluate(osg::Vec3d(0, 0, 5));
    EXPECT_EQ(node->getEvaluator()->features().size(), 2u);
    node->removeChildren(0, 1);
    node->evaluate(osg::Vec3d(0, 0, 5));
    EXPECT_EQ(node->getEvaluator()->features().size(), 1u);
    // A new scenario revision re-binds too: an interest override moves the building into a
    // scope it was not in (none here: three levels for every interest).
    node->getScenario()->dirty();
    node->evaluate(osg::Vec3d(0, 0, 5));
    EXPECT_EQ(node->getEvaluator()->getBoundRevision(), node->getScenario()->getRevision());
}

// osg::Group::addChild calls Group::insertChild qualified, not through the virtual, so LoANode
// must override addChild itself for children added the usual way to re-index the features.
TEST(LoANodeTest, AddChildIsPickedUp)
{
    osg::ref_ptr<LoANode> node = new LoANode;
    node->addChild(box(1, FeatureType::Building, osg::Vec3(195, -5, 0), osg::Vec3(205, 5, 10)).get());
    node->setScenario(ScenarioLibrary::createBuiltin("distance").get());
    node->evaluate(osg::Vec3d(0, 0, 5));
    node->addChild(box(2, FeatureType::Water, osg::Vec3(0, 0, 0), osg::Vec3(10, 10, 1)).get());
    node->evaluate(osg::Vec3d(0, 0, 5));
    EXPECT_EQ(node->getEvaluator()->features().size(), 2u);
}

TEST(LoANodeTest, AnInvalidScenarioReportsItsBindError)
{
    osg::ref_ptr<LoANode> node = new LoANode;
    node->addChild(box(1, FeatureType::Building, osg::Vec3(), osg::Vec3(1, 1, 1)).get());
    osg::ref_ptr<UsageScenario> bad = new UsageScenario;
    bad->setName("empty");
    node->setScenario(bad.get());
    EXPECT_THROW(node->bind(), std::invalid_argument);
    EXPECT_EQ(node->getBindError(),
              "usage scenario 'empty' is not valid: the scenario has no transition configuration");
    EXPECT_FALSE(node->getEvaluator()->isBound());
}
