// LoANode: binds and evaluates a usage scenario during cull.
#include <osgLoA/authoring/HomeView>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/RouteLine>

#include <osgLoA/transitions/TransitionUniforms>

#include <osg/Notify>

#include <algorithm>
#include <osgGA/EventVisitor>
#include <osgLoA/util/StateSetVisitor>
#include <osgUtil/CullVisitor>
#include <osgUtil/GLObjectsVisitor>
#include <osgViewer/View>
#include <sstream>

namespace osgLoA
{

LoANode::LoANode() : _evaluator(new ScenarioEvaluator)
{
    _renderer = new TransitionRenderer(*this);
}

LoANode::LoANode(const LoANode& other, const osg::CopyOp& copyop)
    : osg::Group(other, copyop), _scenario(other._scenario), _evaluator(new ScenarioEvaluator),
      _renderingEnabled(other._renderingEnabled), _preparationOptions(other._preparationOptions)
{
    _renderer = new TransitionRenderer(*this);
    _renderer->setSettings(other._renderer->getSettings());
}

LoANode::~LoANode()
{
    _renderer->unbind();
}

void LoANode::releaseGLObjects(osg::State* state) const
{
    osg::Group::releaseGLObjects(state);
    _renderer->releaseGLObjects(state);
    if (_distanceField.valid()) _distanceField->releaseGLObjects(state);
}

void LoANode::resizeGLObjectBuffers(unsigned int maxSize)
{
    osg::Group::resizeGLObjectBuffers(maxSize);
    _renderer->resizeGLObjectBuffers(maxSize);
    if (_distanceField.valid()) _distanceField->resizeGLObjectBuffers(maxSize);
}

void LoANode::setScenario(UsageScenario* scenario)
{
    std::lock_guard<std::mutex> lock(_mutex);
    _scenario = scenario;
    _boundScenario = nullptr;
}

bool LoANode::addChild(osg::Node* child)
{
    _childrenChanged = true;
    return osg::Group::addChild(child);
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

bool LoANode::needsRefit() const
{
    return _scenario.valid() && _boundScenario == _scenario.get() &&
           _boundValuesRevision != _scenario->getValuesRevision();
}

void LoANode::bindOrRefit()
{
    try
    {
        if (needsBind())
            bind();
        else if (needsRefit())
            refit();
    }
    catch (const std::exception& e)
    {
        OSG_WARN << "osgLoA::LoANode: " << e.what() << "; drawing the model unstyled" << std::endl;
    }
}

void LoANode::refit()
{
    _boundValuesRevision = _scenario->getValuesRevision();
    if (!_evaluator->isBound())
    {
        bind();
        return;
    }
    // The matches (feature, configuration) the renderer's passes were built for, before and after.
    auto matchList = [this]
    {
        std::vector<unsigned> list;
        list.reserve(_evaluator->matches().size() + _evaluator->features().size());
        for (const auto& f : _evaluator->features())
        {
            list.push_back(f.numMatches);
            for (unsigned k = 0; k < f.numMatches; ++k)
                list.push_back(_evaluator->matchesOf(f)[k].configuration);
        }
        return list;
    };
    const std::vector<unsigned> before = matchList();
    try
    {
        _evaluator->bind(_scenario.get(), _index);
    }
    catch (const std::exception& e)
    {
        _bindError = e.what();
        _evaluator = new ScenarioEvaluator;
        _renderer->unbind();
        throw;
    }
    const std::vector<unsigned> after = matchList();
    if (after != before)
    {
        OSG_INFO << "osgLoA::LoANode: the edit changed which configurations match; binding again"
                 << std::endl;
        bind();
        return;
    }
    ++_refits;
    osg::StateSet* ss = getOrCreateStateSet();
    TransitionUniforms::applyScenario(*ss, *_evaluator);
    if (distanceFieldInputs() != _distanceFieldInputs) setUpDistanceField();
    RouteLine::apply(*ss, RouteLine::collect(_evaluator->getScenario()->getRegions()));
    _renderer->rebindValues(*_evaluator);
}

std::string LoANode::distanceFieldInputs() const
{
    std::ostringstream out;
    out.precision(17);
    if (!_evaluator->isBound()) return std::string();
    for (const auto& c : _evaluator->getScenario()->getConfigurations())
    {
        const SaliencyMetric* m = c->getMetric(SaliencyMetric::REGION);
        if (!m || c->getInterpolation() != TransitionConfiguration::FRAGMENT) continue;
        out << "ramp " << m->getNear() << " " << m->getFar() << "\n";
    }
    for (const auto& r : _evaluator->getScenario()->getRegions())
    {
        if (!r.valid()) continue;
        out << "region " << int(r->getShape()) << " " << r->getRadius();
        for (const osg::Vec2d& v : r->getVertices())
            out << " " << v.x() << "," << v.y();
        out << "\n";
    }
    return out.str();
}

void LoANode::bind()
{
    // bind() visits this node (FeatureIndex::build); its generic-visitor branch must not bind again.
    struct Guard
    {
        bool& flag;
        explicit Guard(bool& f) : flag(f) { flag = true; }
        ~Guard() { flag = false; }
    } guard(_inBind);
    _childrenChanged = false;
    _boundScenario = _scenario.get();
    _boundRevision = _scenario.valid() ? _scenario->getRevision() : ~0u;
    _boundValuesRevision = _scenario.valid() ? _scenario->getValuesRevision() : ~0u;
    _bindError.clear();
    ++_binds;
    // The index's root is this node: bounds come out in its local coordinates.
    _index = FeatureIndex();
    _index.build(*this);
    _index.updateBounds();
    _visible.assign(_index.size(), 0);
    _renderer->unbind();
    if (getStateSet()) RouteLine::apply(*getStateSet(), RouteLine::Segments());
    if (!_scenario.valid()) return;
    try
    {
        _preparation = StylePreparation::Report();
        for (unsigned i = 0; i < getNumChildren(); ++i)
        {
            _preparation.add(StylePreparation::prepare(*getChild(i), *_scenario, _preparationOptions));
        }
        _evaluator->bind(_scenario.get(), _index);
        const UsageScenario* fitted = _evaluator->getScenario();
        for (const std::string& note : _evaluator->getFitting().getNotes())
            OSG_INFO << "osgLoA::LoANode: scenario '" << _scenario->getName() << "': " << note << std::endl;
        osg::StateSet* ss = getOrCreateStateSet();
        ss->setDataVariance(osg::Object::DYNAMIC);
        TransitionUniforms::applyScenario(*ss, *_evaluator);
        setUpDistanceField();
        // The regions as ScenarioFitting placed them (the longest street's route).
        RouteLine::apply(*ss, RouteLine::collect(fitted->getRegions()));
        _renderer->bind(*_evaluator, _index);
        if (fitted->getFocusFeature() != 0 && !_evaluator->getView().focus.valid())
            OSG_WARN << "osgLoA::LoANode: scenario '" << _scenario->getName() << "' focuses on feature "
                     << fitted->getFocusFeature()
                     << ", which this model does not have: the focus metric is 0 everywhere" << std::endl;
    }
    catch (const std::exception& e)
    {
        _bindError = e.what();
        _evaluator = new ScenarioEvaluator;
        _renderer->unbind();
        throw;
    }
}

void LoANode::setUpDistanceField()
{
    _distanceFieldInputs = distanceFieldInputs();
    double texel = 0.0, maxDistance = 0.0;
    for (const auto& c : _evaluator->getScenario()->getConfigurations())
    {
        const SaliencyMetric* m = c->getMetric(SaliencyMetric::REGION);
        if (!m || c->getInterpolation() != TransitionConfiguration::FRAGMENT) continue;
        const double t = std::max(m->getFar() - m->getNear(), 1.0) / 64.0;
        texel = texel > 0.0 ? std::min(texel, t) : t;
        maxDistance = std::max(maxDistance, m->getFar());
    }
    osg::BoundingBoxd area;
    for (const auto& f : _evaluator->features())
        if (f.bound.valid()) area.expandBy(f.bound);
    osg::StateSet* ss = getOrCreateStateSet();
    if (texel <= 0.0 || !area.valid())
    {
        if (_distanceField.valid())
            setNumChildrenRequiringUpdateTraversal(getNumChildrenRequiringUpdateTraversal() - 1);
        _distanceField = nullptr;
        TransitionUniforms::applyRegionMap(*ss, nullptr, osg::Vec2d(), osg::Vec2d(1, 1), 1.0);
        return;
    }
    if (!_distanceField.valid())
    {
        _distanceField = new DistanceField;
        // Its seeds are rasterized in the update traversal, which must therefore reach us.
        setNumChildrenRequiringUpdateTraversal(getNumChildrenRequiringUpdateTraversal() + 1);
    }
    const DistanceField::Grid grid = DistanceField::Grid::cover(area, texel);
    _distanceField->setGrid(grid);
    _distanceField->setUnits(DistanceField::WORLD);
    _distanceField->setMaxDistance(maxDistance + grid.texelSize);
    _distanceField->setRegions(_evaluator->getScenario()->getRegions());
    TransitionUniforms::applyRegionMap(*ss, _distanceField->getDistanceTexture(), grid.origin,
                                       osg::Vec2d(grid.width * grid.texelSize, grid.height * grid.texelSize),
                                       1.0);
}

void LoANode::followEye()
{
    // View-scaled metrics: near/far followed the eye's distance to the scene centre in the
    // evaluation; the shaders read them from uniforms.
    if (_evaluator->isBound() && _evaluator->viewScaleChanged())
        TransitionUniforms::applyRamps(*getOrCreateStateSet(), *_evaluator);
}

void LoANode::evaluate(const osg::Vec3d& eye)
{
    std::lock_guard<std::mutex> lock(_mutex);
    if (needsBind())
        bind();
    else if (needsRefit())
        refit();
    if (_evaluator->isBound())
    {
        _evaluator->evaluate(eye);
        followEye();
    }
}

void LoANode::setHomeViewPending(bool pending)
{
    if (pending == _homeViewPending) return;
    _homeViewPending = pending;
    setNumChildrenRequiringEventTraversal(getNumChildrenRequiringEventTraversal() + (pending ? 1 : -1));
}

void LoANode::traverse(osg::NodeVisitor& nv)
{
    if (_homeViewPending && nv.getVisitorType() == osg::NodeVisitor::EVENT_VISITOR)
    {
        osgGA::EventVisitor* ev = dynamic_cast<osgGA::EventVisitor*>(&nv);
        osgViewer::View* view = ev ? dynamic_cast<osgViewer::View*>(ev->getActionAdapter()) : nullptr;
        if (view && view->getCameraManipulator())
        {
            try
            {
                HomeView::apply(*view->getCameraManipulator(), HomeView::compute(*this, view->getCamera()));
            }
            catch (const std::exception& e)
            {
                OSG_WARN << "osgLoA::LoANode: no home view: " << e.what() << std::endl;
            }
            setHomeViewPending(false);
        }
    }
    osgUtil::CullVisitor* cv = nv.getVisitorType() == osg::NodeVisitor::CULL_VISITOR
                                   ? dynamic_cast<osgUtil::CullVisitor*>(&nv)
                                   : nullptr;
    // Bind in the update traversal (before it reaches the distance field, so that its seeds
    // exist in time) or, for viewers without one, in the first cull.
    const bool update = nv.getVisitorType() == osg::NodeVisitor::UPDATE_VISITOR;
    if ((update || cv) && _scenario.valid())
    {
        std::lock_guard<std::mutex> lock(_mutex);
        bindOrRefit();
        if (cv && _evaluator->isBound())
        {
            const auto& features = _evaluator->features();
            for (std::size_t i = 0; i < features.size(); ++i)
            {
                const Feature& f = *_index.entries()[features[i].entry].feature;
                _visible[i] = f.getBound().valid() && !cv->isCulled(f.getBound()) ? 1 : 0;
            }
            const osg::Vec3d eye(cv->getEyeLocal());
            _evaluator->evaluate(eye, _visible.data());
            followEye();
            // Fragment-mode uniforms: the eye, and world -> local for the shaders' positions
            // (MV = localToWorld * V, so worldToLocal = V * inverse(MV)).
            osg::StateSet* ss = getOrCreateStateSet();
            TransitionUniforms::applyEye(*ss, eye);
            if (const osg::Camera* camera = cv->getCurrentCamera())
                TransitionUniforms::applyWorldToScene(
                    *ss, camera->getViewMatrix() * osg::Matrixd::inverse(*cv->getModelViewMatrix()));
            ++_evaluations;
            _lastFrame = nv.getFrameStamp() ? nv.getFrameStamp()->getFrameNumber() : 0;
            if (_distanceField.valid()) _distanceField->accept(nv);
            if (_renderingEnabled && _renderer->isBound())
            {
                _renderer->cull(*cv, *_evaluator);
                return;
            }
            osg::Group::traverse(nv);
            return;
        }
    }
    if (_distanceField.valid() && (cv || update)) _distanceField->accept(nv);
    // Generic visitors (program checks, GL object compilation before the first frame) bind the
    // scenario and reach the renderer's passes, so that their programs are compiled and checked
    // up front rather than in the middle of the first frame's draw.
    // Only those: other generic visitors (osgconv's optimizer, writers) must find the node as
    // it was read, without the state binding adds.
    const bool compiling =
        nv.getVisitorType() == osg::NodeVisitor::NODE_VISITOR &&
        (dynamic_cast<osgUtil::GLObjectsVisitor*>(&nv) || dynamic_cast<StateSetVisitor*>(&nv));
    if (compiling && _renderingEnabled && _scenario.valid() && !_inBind)
    {
        {
            std::lock_guard<std::mutex> lock(_mutex);
            bindOrRefit();
        }
        if (_renderer->isBound()) _renderer->getInternalNode()->accept(nv);
    }
    osg::Group::traverse(nv);
}

} // namespace osgLoA
