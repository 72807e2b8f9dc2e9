// LoANode: binds and evaluates a usage scenario during cull.
#include <osgLoA/transitions/LoANode>

#include <osgLoA/transitions/TransitionUniforms>

#include <osg/Notify>
#include <osgUtil/CullVisitor>

namespace osgLoA
{

LoANode::LoANode() : _evaluator(new ScenarioEvaluator) {}

LoANode::LoANode(const LoANode& other, const osg::CopyOp& copyop)
    : osg::Group(other, copyop), _scenario(other._scenario), _evaluator(new ScenarioEvaluator)
{
}

void LoANode::setScenario(UsageScenario* scenario)
{
    std::lock_guard<std::mutex> lock(_mutex);
    _scenario = scenario;
    _boundScenario = nullptr;
}

bool LoANode::insertChild(unsigned int index, osg::Node* child)
{
    _childrenChanged = true;
    return osg::Group::insertChild(index, child);
}

bool LoANode::removeChildren(unsigned int pos, unsigned int numChildrenToRemove)
{
    _childrenChanged = true;
    return osg::Group::removeChildren(pos, numChildrenToRemove);
}

bool LoANode::replaceChild(osg::Node* origChild, osg::Node* newChild)
{
    _childrenChanged = true;
    return osg::Group::replaceChild(origChild, newChild);
}

bool LoANode::setChild(unsigned int i, osg::Node* node)
{
    _childrenChanged = true;
    return osg::Group::setChild(i, node);
}

bool LoANode::needsBind() const
{
    return _scenario.valid() && (_childrenChanged || _boundScenario != _scenario.get() ||
                                 _boundRevision != _scenario->getRevision());
}

void LoANode::bind()
{
    _childrenChanged = false;
    _boundScenario = _scenario.get();
    _boundRevision = _scenario.valid() ? _scenario->getRevision() : ~0u;
    _bindError.clear();
    // The index's root is this node: bounds come out in its local coordinates.
    _index = FeatureIndex();
    _index.build(*this);
    _index.updateBounds();
    _visible.assign(_index.size(), 0);
    if (!_scenario.valid()) return;
    try
    {
        _evaluator->bind(_scenario.get(), _index);
        osg::StateSet* ss = getOrCreateStateSet();
        ss->setDataVariance(osg::Object::DYNAMIC);
        TransitionUniforms::applyScenario(*ss, *_evaluator);
    }
    catch (const std::exception& e)
    {
        _bindError = e.what();
        _evaluator = new ScenarioEvaluator;
        throw;
    }
}

void LoANode::evaluate(const osg::Vec3d& eye)
{
    std::lock_guard<std::mutex> lock(_mutex);
    if (needsBind()) bind();
    if (_evaluator->isBound()) _evaluator->evaluate(eye);
}

void LoANode::traverse(osg::NodeVisitor& nv)
{
    osgUtil::CullVisitor* cv = nv.getVisitorType() == osg::NodeVisitor::CULL_VISITOR
                                   ? dynamic_cast<osgUtil::CullVisitor*>(&nv)
                                   : nullptr;
    if (cv && _scenario.valid())
    {
        std::lock_guard<std::mutex> lock(_mutex);
        if (needsBind())
        {
            try
            {
                bind();
            }
            catch (const std::exception& e)
            {
                OSG_WARN << "osgLoA::LoANode: " << e.what() << "; drawing the model unstyled" << std::endl;
            }
        }
        if (_evaluator->isBound())
        {
            const auto& features = _evaluator->features();
            for (std::size_t i = 0; i < features.size(); ++i)
            {
                const Feature& f = *_index.entries()[features[i].entry].feature;
                _visible[i] = f.getBound().valid() && !cv->isCulled(f.getBound()) ? 1 : 0;
            }
            const osg::Vec3d eye(cv->getEyeLocal());
            _evaluator->evaluate(eye, _visible.data());
            // Fragment-mode uniforms: the eye, and world -> local for the shaders' positions
            // (MV = localToWorld * V, so worldToLocal = V * inverse(MV)).
            osg::StateSet* ss = getOrCreateStateSet();
            TransitionUniforms::applyEye(*ss, eye);
            if (const osg::Camera* camera = cv->getCurrentCamera())
                TransitionUniforms::applyWorldToScene(
                    *ss, camera->getViewMatrix() * osg::Matrixd::inverse(*cv->getModelViewMatrix()));
            ++_evaluations;
            _lastFrame = nv.getFrameStamp() ? nv.getFrameStamp()->getFrameNumber() : 0;
        }
    }
    osg::Group::traverse(nv);
}

} // namespace osgLoA
