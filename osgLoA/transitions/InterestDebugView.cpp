// InterestDebugView: Figure 5's black (high detail) to white (low detail) view.
#include <osgLoA/transitions/InterestDebugView>

#include <osgLoA/render/ShaderLibrary>
#include <osgLoA/transitions/TransitionUniforms>

#include <stdexcept>

namespace osgLoA
{

osg::ref_ptr<osg::Group> InterestDebugView::create(LoANode& node, int configuration)
{
    const ScenarioEvaluator* e = node.getEvaluator();
    if (!e || !e->isBound()) throw std::invalid_argument("the LoA node has no bound usage scenario");
    const int n = int(e->getScenario()->getConfigurations().size());
    if (configuration < -1 || configuration >= n)
        throw std::invalid_argument("configuration index " + std::to_string(configuration) +
                                    " is out of range (0.." + std::to_string(n - 1) + ")");
    osg::ref_ptr<osg::Group> group = new osg::Group;
    group->setName("loa.interest-debug");
    // The node's region distance map is computed by pre-render cameras: draw them first.
    if (DistanceField* field = node.getDistanceField()) group->addChild(field);
    for (unsigned i = 0; i < node.getNumChildren(); ++i)
        group->addChild(node.getChild(i));
    osg::StateSet* ss = group->getOrCreateStateSet();
    ss->setAttributeAndModes(
        ShaderLibrary::createProgram(
            "loa_interest_debug",
            {"loa_interest_debug.vert.glsl", "loa_interest_debug.frag.glsl", "loa_transition.frag.glsl"})
            .get(),
        osg::StateAttribute::ON | osg::StateAttribute::OVERRIDE);
    ss->setMode(GL_LIGHTING, osg::StateAttribute::OFF | osg::StateAttribute::OVERRIDE);
    TransitionUniforms::applyScenario(*ss, *e);
    TransitionUniforms::applyEye(*ss, e->getView().eye);
    TransitionUniforms::applyWorldToScene(*ss, osg::Matrixd::identity());
    if (const osg::StateSet* own = node.getStateSet())
    {
        // The node's region map, when it computed one.
        for (const char* name :
             {"loa_hasRegionMap", "loa_regionMap", "loa_regionMapFrame", "loa_regionMapScale"})
            if (const osg::Uniform* u = own->getUniform(name)) ss->addUniform(const_cast<osg::Uniform*>(u));
        if (const osg::StateAttribute* map =
                own->getTextureAttribute(TransitionUniforms::kRegionMapUnit, osg::StateAttribute::TEXTURE))
            ss->setTextureAttributeAndModes(TransitionUniforms::kRegionMapUnit,
                                            const_cast<osg::StateAttribute*>(map), osg::StateAttribute::ON);
    }
    ss->getOrCreateUniform("loa_debugConfiguration", osg::Uniform::INT)->set(configuration);
    ss->getOrCreateUniform("loa_featureMatches", osg::Uniform::INT)->set(0);
    ss->getOrCreateUniform("loa_featureInterest", osg::Uniform::FLOAT)->set(0.0f);

    const auto& entries = node.getFeatureIndex().entries();
    for (const ScenarioEvaluator::FeatureState& f : e->features())
    {
        osg::ref_ptr<osg::Node> featureNode;
        if (!entries[f.entry].node.lock(featureNode)) continue;
        TransitionUniforms::applyFeature(*featureNode->getOrCreateStateSet(), *e, f);
    }
    return group;
}

} // namespace osgLoA
