// ScenarioEditor: undoable edits of a usage scenario, each marked with what it touches.
#include <osgLoA/authoring/ScenarioEditor>
#include <osgLoA/transitions/ScenarioLibrary>

#include <algorithm>
#include <cmath>
#include <set>

namespace osgLoA
{

namespace
{
// Drawn routes: as the library's route scenario draws its route (RouteLine), pixels.
constexpr double kEditorRouteWidth = 6.0;

bool finite2(const osg::Vec2d& v)
{
    return std::isfinite(v.x()) && std::isfinite(v.y());
}

std::set<std::string> errorSet(const UsageScenario::Validation& v)
{
    return std::set<std::string>(v.errors.begin(), v.errors.end());
}

std::string escapeGlob(const std::string& name)
{
    std::string out;
    for (char c : name)
    {
        if (c == '*' || c == '?' || c == '[' || c == ']' || c == '\\') out += '\\';
        out += c;
    }
    return out;
}
} // namespace

ScenarioEditor::ScenarioEditor(LoANode& node) : _node(&node), _userRules(new ClassificationRuleSet)
{
    if (!node.getScenario()) throw std::invalid_argument("ScenarioEditor: the LoA node has no scenario");
    _userRules->setName("user rules (loa-viewer)");
    _validation = getScenario().validate();
}

unsigned ScenarioEditor::getCount(Change c) const
{
    return c == VALUES ? _counts[0] : c == STRUCTURE ? _counts[1] : c == FEATURES ? _counts[2] : _counts[3];
}

void ScenarioEditor::applied(Change change)
{
    UsageScenario& s = getScenario();
    if (change == VALUES)
    {
        s.dirtyValues();
        ++_counts[0];
    }
    else if (change == STRUCTURE)
    {
        s.dirty();
        ++_counts[1];
    }
    else if (change == FEATURES)
    {
        _node->dirtyFeatures();
        ++_counts[2];
    }
    else
        ++_counts[3];
    _validation = s.validate();
}

void ScenarioEditor::beginGesture()
{
    _gesture = true;
    _gestureStart = _done;
}

void ScenarioEditor::endGesture()
{
    _gesture = false;
}

void ScenarioEditor::recordLive(const std::string& label, const std::function<void(bool redo)>& fn)
{
    Step step;
    step.label = label;
    step.change = LIVE;
    step.featureEdit = fn;
    record(std::move(step));
    applied(LIVE);
}

void ScenarioEditor::record(Step step)
{
    // In a gesture, a scenario edit after the gesture's first one replaces that one's result
    // (keeping its state before).
    if (_gesture && _done == _gestureStart + 1 && _done == _steps.size() && !_steps.back().featureEdit &&
        !step.featureEdit && _steps.back().label == step.label)
    {
        Step& last = _steps.back();
        last.after = step.after;
        last.label = step.label;
        if (step.change == STRUCTURE) last.change = STRUCTURE;
        return;
    }
    _steps.resize(_done);
    if (_savedAt > _done) _savedAt = std::size_t(-1); // the saved state can no longer come back
    _steps.push_back(std::move(step));
    ++_done;
}

void ScenarioEditor::edit(const std::string& label, Change change,
                          const std::function<void(UsageScenario&)>& fn)
{
    UsageScenario& live = getScenario();
    osg::ref_ptr<UsageScenario> before = new UsageScenario(live, osg::CopyOp::DEEP_COPY_ALL);
    osg::ref_ptr<UsageScenario> work = new UsageScenario(live, osg::CopyOp::DEEP_COPY_ALL);
    fn(*work);
    const UsageScenario::Validation v = work->validate();
    const std::set<std::string> had = errorSet(_validation);
    for (const std::string& e : v.errors)
        if (!had.count(e)) throw EditError(label + ": " + e);
    Step step;
    step.label = label;
    step.change = change;
    step.before = before;
    step.after = work;
    live.assign(*work);
    record(std::move(step));
    applied(change);
}

void ScenarioEditor::replace(const UsageScenario& scenario, const std::string& label)
{
    UsageScenario& live = getScenario();
    Step step;
    step.label = label;
    step.change = STRUCTURE;
    step.before = new UsageScenario(live, osg::CopyOp::DEEP_COPY_ALL);
    step.after = new UsageScenario(scenario, osg::CopyOp::DEEP_COPY_ALL);
    live.assign(*step.after);
    record(std::move(step));
    applied(STRUCTURE);
}

std::string ScenarioEditor::undoLabel() const
{
    return canUndo() ? _steps[_done - 1].label : std::string();
}

std::string ScenarioEditor::redoLabel() const
{
    return canRedo() ? _steps[_done].label : std::string();
}

bool ScenarioEditor::undo()
{
    if (!canUndo()) return false;
    const Step& step = _steps[_done - 1];
    if (step.featureEdit)
        step.featureEdit(false);
    else
        getScenario().assign(*step.before);
    --_done;
    applied(step.change);
    return true;
}

bool ScenarioEditor::redo()
{
    if (!canRedo()) return false;
    const Step& step = _steps[_done];
    if (step.featureEdit)
        step.featureEdit(true);
    else
        getScenario().assign(*step.after);
    ++_done;
    applied(step.change);
    return true;
}

std::vector<std::string> ScenarioEditor::history() const
{
    std::vector<std::string> out;
    for (const Step& s : _steps)
        out.push_back(s.label);
    return out;
}

TransitionConfiguration& ScenarioEditor::configuration(UsageScenario& s, unsigned index) const
{
    if (index >= s.getConfigurations().size() || !s.getConfigurations()[index].valid())
        throw EditError("the scenario has no configuration #" + std::to_string(index + 1) + " (it has " +
                        std::to_string(s.getConfigurations().size()) + ")");
    return *s.getConfigurations()[index];
}

RegionOfInterest* ScenarioEditor::findRegion(UsageScenario& s, const std::string& name)
{
    for (const auto& r : s.getRegions())
        if (r.valid() && r->getName() == name) return r.get();
    return nullptr;
}

void ScenarioEditor::setFadeIn(unsigned c, const osg::Vec2f& range)
{
    edit("fade-in of '" + configuration(getScenario(), c).getName() + "'", VALUES,
         [&](UsageScenario& s) { configuration(s, c).setFadeIn(range); });
}

void ScenarioEditor::setFadeOut(unsigned c, const osg::Vec2f& range)
{
    edit("fade-out of '" + configuration(getScenario(), c).getName() + "'", VALUES,
         [&](UsageScenario& s) { configuration(s, c).setFadeOut(range); });
}

void ScenarioEditor::setMetric(unsigned c, SaliencyMetric::Kind kind, double nearValue, double farValue,
                               double weight)
{
    TransitionConfiguration& current = configuration(getScenario(), c);
    const bool present = current.getMetric(kind) != nullptr;
    edit(std::string(SaliencyMetric::toString(kind)) + " metric of '" + current.getName() + "'",
         present ? VALUES : STRUCTURE,
         [&](UsageScenario& s)
         {
             TransitionConfiguration& cfg = configuration(s, c);
             osg::ref_ptr<SaliencyMetric> m =
                 cfg.getMetric(kind) ? osg::clone(cfg.getMetric(kind), osg::CopyOp::DEEP_COPY_ALL)
                                     : new SaliencyMetric(kind, nearValue, farValue, weight);
             m->setNear(nearValue);
             m->setFar(farValue);
             m->setWeight(weight);
             cfg.addMetric(m.get());
         });
}

void ScenarioEditor::removeMetric(unsigned c, SaliencyMetric::Kind kind)
{
    edit(std::string("remove the ") + SaliencyMetric::toString(kind) + " metric of '" +
             configuration(getScenario(), c).getName() + "'",
         STRUCTURE,
         [&](UsageScenario& s)
         {
             auto& metrics = configuration(s, c).getMetrics();
             metrics.erase(std::remove_if(metrics.begin(), metrics.end(),
                                          [&](const osg::ref_ptr<SaliencyMetric>& m)
                                          { return m.valid() && m->getKind() == kind; }),
                           metrics.end());
         });
}

void ScenarioEditor::setCombination(unsigned c, TransitionConfiguration::Combination combination)
{
    edit("combination of '" + configuration(getScenario(), c).getName() + "'", VALUES,
         [&](UsageScenario& s) { configuration(s, c).setCombination(combination); });
}

void ScenarioEditor::setInterpolation(unsigned c, TransitionConfiguration::Interpolation mode)
{
    edit("interpolation of '" + configuration(getScenario(), c).getName() + "'", STRUCTURE,
         [&](UsageScenario& s) { configuration(s, c).setInterpolation(mode); });
}

void ScenarioEditor::setStyle(unsigned c, const std::string& style)
{
    edit("style of '" + configuration(getScenario(), c).getName() + "'", STRUCTURE,
         [&](UsageScenario& s) { configuration(s, c).setStyle(style); });
}

void ScenarioEditor::setFeatureTypes(unsigned c, const TransitionConfiguration::FeatureTypes& types)
{
    edit("feature types of '" + configuration(getScenario(), c).getName() + "'", STRUCTURE,
         [&](UsageScenario& s) { configuration(s, c).setFeatureTypes(types); });
}

void ScenarioEditor::setSubTypes(unsigned c, const TransitionConfiguration::SubTypes& subTypes)
{
    edit("sub-types of '" + configuration(getScenario(), c).getName() + "'", STRUCTURE,
         [&](UsageScenario& s) { configuration(s, c).setSubTypes(subTypes); });
}

void ScenarioEditor::setInterestRange(unsigned c, const osg::Vec2f& range)
{
    edit("interest range of '" + configuration(getScenario(), c).getName() + "'", STRUCTURE,
         [&](UsageScenario& s) { configuration(s, c).setInterestRange(range); });
}

unsigned ScenarioEditor::duplicateConfiguration(unsigned c)
{
    edit("duplicate '" + configuration(getScenario(), c).getName() + "'", STRUCTURE,
         [&](UsageScenario& s)
         {
             osg::ref_ptr<TransitionConfiguration> copy =
                 osg::clone(&configuration(s, c), osg::CopyOp::DEEP_COPY_ALL);
             copy->setName(copy->getName() + " copy");
             s.getConfigurations().insert(s.getConfigurations().begin() + c + 1, copy);
         });
    return c + 1;
}

void ScenarioEditor::removeConfiguration(unsigned c)
{
    edit("remove '" + configuration(getScenario(), c).getName() + "'", STRUCTURE,
         [&](UsageScenario& s)
         {
             configuration(s, c);
             s.getConfigurations().erase(s.getConfigurations().begin() + c);
         });
}

void ScenarioEditor::moveConfiguration(unsigned c, int step)
{
    const long to = long(c) + step;
    if (to < 0 || to >= long(getScenario().getConfigurations().size()))
        throw EditError("configuration #" + std::to_string(c + 1) + " cannot move " +
                        (step < 0 ? "earlier" : "later"));
    edit("move '" + configuration(getScenario(), c).getName() + "'", STRUCTURE,
         [&](UsageScenario& s)
         { std::swap(s.getConfigurations()[c], s.getConfigurations()[std::size_t(to)]); });
}

unsigned ScenarioEditor::placeCircle(const std::string& name, const osg::Vec2d& centre, double radius)
{
    if (!finite2(centre) || !std::isfinite(radius) || radius < 0.0)
        throw EditError("circle '" + name + "': the centre and a radius >= 0 must be finite");
    unsigned index = 0;
    edit("place circle '" + name + "'", VALUES,
         [&](UsageScenario& s)
         {
             RegionOfInterest* r = findRegion(s, name);
             if (!r)
             {
                 r = s.addRegion(new RegionOfInterest(RegionOfInterest::CIRCLES, {}, 0.0));
                 r->setName(name);
             }
             r->setShape(RegionOfInterest::CIRCLES);
             r->setPlacement(RegionOfInterest::ABSOLUTE);
             r->setSceneScale(false);
             r->setVertices({centre});
             r->setRadius(radius);
             for (unsigned i = 0; i < s.getRegions().size(); ++i)
                 if (s.getRegions()[i].get() == r) index = i;
         });
    return index;
}

void ScenarioEditor::addRoutePoint(const std::string& name, const osg::Vec2d& point)
{
    if (!finite2(point)) throw EditError("route '" + name + "': the point must be finite");
    edit("add a point to '" + name + "'", VALUES,
         [&](UsageScenario& s)
         {
             RegionOfInterest* r = findRegion(s, name);
             if (!r)
             {
                 r = s.addRegion(new RegionOfInterest(RegionOfInterest::POLYLINE, {}, 0.0));
                 r->setName(name);
                 r->setLineWidth(kEditorRouteWidth);
             }
             else if (r->getShape() != RegionOfInterest::POLYLINE || !r->isResolved())
                 throw EditError("region '" + name + "' is not a route drawn in scene coordinates");
             r->addVertex(point);
         });
}

void ScenarioEditor::startRoute(const std::string& name, const osg::Vec2d& first, const osg::Vec2d& second)
{
    if (!finite2(first) || !finite2(second))
        throw EditError("route '" + name + "': the points must be finite");
    if (findRegion(getScenario(), name)) throw EditError("the scenario already has a region '" + name + "'");
    edit("start route '" + name + "'", VALUES,
         [&](UsageScenario& s)
         {
             RegionOfInterest* r =
                 s.addRegion(new RegionOfInterest(RegionOfInterest::POLYLINE, {first, second}, 0.0));
             r->setName(name);
             r->setLineWidth(kEditorRouteWidth);
         });
}

void ScenarioEditor::moveRoutePoint(const std::string& name, unsigned vertex, const osg::Vec2d& point)
{
    if (!finite2(point)) throw EditError("route '" + name + "': the point must be finite");
    edit("move a point of '" + name + "'", VALUES,
         [&](UsageScenario& s)
         {
             RegionOfInterest* r = findRegion(s, name);
             if (!r || vertex >= r->getVertices().size())
                 throw EditError("route '" + name + "' has no point #" + std::to_string(vertex + 1));
             r->getVertices()[vertex] = point;
         });
}

void ScenarioEditor::removeRoutePoint(const std::string& name, unsigned vertex)
{
    edit("remove a point of '" + name + "'", VALUES,
         [&](UsageScenario& s)
         {
             RegionOfInterest* r = findRegion(s, name);
             if (!r || vertex >= r->getVertices().size())
                 throw EditError("route '" + name + "' has no point #" + std::to_string(vertex + 1));
             r->getVertices().erase(r->getVertices().begin() + vertex);
         });
}

void ScenarioEditor::removeRegion(const std::string& name)
{
    edit("remove region '" + name + "'", VALUES,
         [&](UsageScenario& s)
         {
             auto& regions = s.getRegions();
             const auto it = std::find_if(regions.begin(), regions.end(),
                                          [&](const osg::ref_ptr<RegionOfInterest>& r)
                                          { return r.valid() && r->getName() == name; });
             if (it == regions.end()) throw EditError("the scenario has no region '" + name + "'");
             regions.erase(it);
         });
}

void ScenarioEditor::setRegionFade(double width)
{
    if (!std::isfinite(width) || width < 0.0) throw EditError("a region fade must be finite and >= 0");
    bool any = false;
    for (const auto& c : getScenario().getConfigurations())
        any = any || (c.valid() && c->getMetric(SaliencyMetric::REGION));
    if (!any) throw EditError("no configuration measures the region metric");
    // A scene- or view-scaled ramp becomes absolute, from where the node fitted its near end:
    // the width is in scene units.
    const UsageScenario* fitted = _node->getEvaluator() && _node->getEvaluator()->isBound()
                                      ? _node->getEvaluator()->getScenario()
                                      : nullptr;
    edit("region fade", VALUES,
         [&](UsageScenario& s)
         {
             for (std::size_t j = 0; j < s.getConfigurations().size(); ++j)
             {
                 const osg::ref_ptr<TransitionConfiguration>& c = s.getConfigurations()[j];
                 if (!c.valid() || !c->getMetric(SaliencyMetric::REGION)) continue;
                 const SaliencyMetric* placed =
                     fitted && j < fitted->getConfigurations().size() &&
                             fitted->getConfigurations()[j].valid()
                         ? fitted->getConfigurations()[j]->getMetric(SaliencyMetric::REGION)
                         : nullptr;
                 for (auto& m : c->getMetrics())
                     if (m.valid() && m->getKind() == SaliencyMetric::REGION)
                     {
                         osg::ref_ptr<SaliencyMetric> copy = osg::clone(m.get(), osg::CopyOp::DEEP_COPY_ALL);
                         if (copy->getScale() != SaliencyMetric::ABSOLUTE)
                         {
                             copy->setNear(placed ? placed->getNear() : 0.0);
                             copy->setScale(SaliencyMetric::ABSOLUTE);
                         }
                         copy->setFar(copy->getNear() + width);
                         m = copy;
                     }
             }
         });
}

void ScenarioEditor::useRegionDetail(const std::string& detailStyle, const std::string& contextStyle,
                                     double fade)
{
    if (!std::isfinite(fade) || fade < 0.0) throw EditError("a region fade must be finite and >= 0");
    edit("detail in the regions (" + detailStyle + " / " + contextStyle + ")", STRUCTURE,
         [&](UsageScenario& s)
         {
             s.getConfigurations().clear();
             osg::ref_ptr<SaliencyMetric> region = new SaliencyMetric(SaliencyMetric::REGION, 0.0, fade);
             ScenarioLibrary::appendTwoLevels(s, *region, detailStyle, contextStyle);
         });
}

void ScenarioEditor::setFocusFeature(unsigned featureId)
{
    if (featureId != 0 && !_node->getFeatureIndex().find(featureId))
        throw EditError("the model has no feature " + std::to_string(featureId));
    edit(featureId ? "focus on feature " + std::to_string(featureId) : std::string("clear the focus"), VALUES,
         [&](UsageScenario& s)
         {
             s.setFocusFeature(featureId);
             if (featureId) s.setFocusTallestLandmark(false);
         });
}

void ScenarioEditor::setLandmark(unsigned featureId, bool landmark)
{
    if (!_node->getFeatureIndex().find(featureId))
        throw EditError("the model has no feature " + std::to_string(featureId));
    edit((landmark ? "make feature " : "clear the interest of feature ") + std::to_string(featureId) +
             (landmark ? " a landmark" : ""),
         STRUCTURE,
         [&](UsageScenario& s)
         {
             if (!s.getInterest()) s.setInterest(new FeatureInterest);
             if (landmark)
                 s.getInterest()->setFeatureInterest(featureId, 1.0f);
             else
                 s.getInterest()->removeFeatureInterest(featureId);
         });
}

void ScenarioEditor::setFeatureType(unsigned featureId, FeatureType type, const std::string& subType)
{
    const FeatureIndex& index = _node->getFeatureIndex();
    const FeatureIndex::Entry* entry = index.find(featureId);
    if (!entry || !entry->node.valid())
        throw EditError("the model has no feature " + std::to_string(featureId));
    const std::string name = entry->node->getName();
    if (name.empty())
        throw EditError("feature " + std::to_string(featureId) +
                        "'s node has no name: no rule could classify it alone");
    for (const FeatureIndex::Entry& e : index.entries())
        if (e.feature != entry->feature && e.node.valid() && e.node->getName() == name)
            throw EditError("feature " + std::to_string(featureId) + "'s node name '" + name +
                            "' is shared with feature " + std::to_string(e.feature->getId()) +
                            ": no rule could classify it alone");
    osg::ref_ptr<Feature> feature = entry->feature;
    const FeatureType oldType = feature->getType();
    const std::string oldSubType = feature->getSubType();
    const Feature::Source oldSource = feature->getSource();
    osg::ref_ptr<ClassificationRule> rule = new ClassificationRule(
        ClassificationRule::NODE_NAME, ClassificationRule::GLOB, escapeGlob(name), type, subType);
    rule->setName("feature " + std::to_string(featureId) + " set by hand");
    rule->setCaseSensitive(true);
    rule->setInheritable(false);
    rule->setOverridesModelData(true);
    osg::ref_ptr<ClassificationRuleSet> rules = _userRules;
    Step step;
    step.label = "type of feature " + std::to_string(featureId) + ": " + toString(type);
    step.change = FEATURES;
    step.featureEdit = [feature, type, subType, oldType, oldSubType, oldSource, rule, rules](bool redo)
    {
        ClassificationRuleSet::Rules list = rules->getRules();
        list.erase(std::remove(list.begin(), list.end(), rule), list.end());
        if (redo)
        {
            feature->setType(type);
            feature->setSubType(subType);
            feature->setSource(Feature::USER);
            list.push_back(rule);
        }
        else
        {
            feature->setType(oldType);
            feature->setSubType(oldSubType);
            feature->setSource(oldSource);
        }
        rules->setRules(list);
    };
    step.featureEdit(true);
    record(std::move(step));
    applied(FEATURES);
}

} // namespace osgLoA
