// ViewerPanels: the ImGui panels of loa-viewer.
#include "ViewerPanels.h"

#include "AuthoringHandler.h"

#include <osgLoA/styles/GraphicStyleCatalog>

#include <imgui.h>

#include <osgDB/FileNameUtils>

#include <algorithm>
#include <cstring>
#include <map>
#include <sstream>

namespace loa
{

namespace
{
/** A uniform's value as the style editor edits it. */
struct UniformValue
{
    float f[4] = {0, 0, 0, 0};
    int i = 0;
    bool b = false;
    bool read(const osg::Uniform& u)
    {
        switch (u.getType())
        {
        case osg::Uniform::FLOAT:
            return u.get(f[0]);
        case osg::Uniform::FLOAT_VEC2:
        {
            osg::Vec2f v;
            if (!u.get(v)) return false;
            f[0] = v.x(), f[1] = v.y();
            return true;
        }
        case osg::Uniform::FLOAT_VEC3:
        {
            osg::Vec3f v;
            if (!u.get(v)) return false;
            f[0] = v.x(), f[1] = v.y(), f[2] = v.z();
            return true;
        }
        case osg::Uniform::FLOAT_VEC4:
        {
            osg::Vec4f v;
            if (!u.get(v)) return false;
            f[0] = v.x(), f[1] = v.y(), f[2] = v.z(), f[3] = v.w();
            return true;
        }
        case osg::Uniform::INT:
            return u.get(i);
        case osg::Uniform::BOOL:
            return u.get(b);
        default:
            return false;
        }
    }
    void write(osg::Uniform& u) const
    {
        switch (u.getType())
        {
        case osg::Uniform::FLOAT:
            u.set(f[0]);
            break;
        case osg::Uniform::FLOAT_VEC2:
            u.set(osg::Vec2f(f[0], f[1]));
            break;
        case osg::Uniform::FLOAT_VEC3:
            u.set(osg::Vec3f(f[0], f[1], f[2]));
            break;
        case osg::Uniform::FLOAT_VEC4:
            u.set(osg::Vec4f(f[0], f[1], f[2], f[3]));
            break;
        case osg::Uniform::INT:
            u.set(i);
            break;
        case osg::Uniform::BOOL:
            u.set(b);
            break;
        default:
            break;
        }
    }
};

/** Sets a style's uniform wherever the style is in use: every bound configuration drawn in it
 *  (the next frame shows it) and the catalog's prototype (later re-binds keep it). */
void setStyleUniform(osgLoA::LoANode& node, const std::string& style, const std::string& name,
                     const UniformValue& value)
{
    const auto& configs = node.getScenario()->getConfigurations();
    for (unsigned j = 0; j < configs.size(); ++j)
        if (configs[j].valid() && configs[j]->getStyle() == style)
            if (osg::StateSet* ss = node.getRenderer()->getBoundParameters(j))
                if (osg::Uniform* u = ss->getUniform(name)) value.write(*u);
    osgLoA::GraphicStyleCatalog& catalog = osgLoA::GraphicStyleCatalog::instance();
    if (!catalog.contains(style)) return;
    osg::ref_ptr<osgLoA::GraphicStyle> copy = catalog.create(style);
    if (osg::Uniform* u = copy->getParameter(name))
    {
        value.write(*u);
        catalog.add(*copy);
    }
}

bool combo(const char* label, int& current, const std::vector<std::string>& items)
{
    bool changed = false;
    const char* preview =
        current >= 0 && current < int(items.size()) ? items[std::size_t(current)].c_str() : "";
    if (ImGui::BeginCombo(label, preview))
    {
        for (int i = 0; i < int(items.size()); ++i)
        {
            const bool isSelected = i == current;
            if (ImGui::Selectable(items[std::size_t(i)].c_str(), isSelected))
            {
                current = i;
                changed = true;
            }
            if (isSelected) ImGui::SetItemDefaultFocus();
        }
        ImGui::EndCombo();
    }
    return changed;
}

/** An edit from a widget held over many frames (a slider, a drag field): the gesture opens when
 *  the widget is activated, before its first change is applied, and closes when it is let go,
 *  so that the whole drag is one undoable step. changed: the widget's return value (evaluated,
 *  as an argument, before this runs: the IsItem* calls ask about that widget). */
template <typename F> void edited(ViewerSession& s, bool changed, F&& f)
{
    if (ImGui::IsItemActivated()) s.getEditor().beginGesture();
    if (changed) s.attempt(std::forward<F>(f));
    if (ImGui::IsItemDeactivated()) s.getEditor().endGesture();
}
} // namespace

void ViewerPanels::build()
{
    const ImVec2 size = ImGui::GetIO().DisplaySize;
    const float w = size.x;
    // In a small window the editors on the right start collapsed (a click on a title opens
    // one), so that the scene stays in view.
    const bool compact = size.x < 1400.0f || size.y < 800.0f;
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(330, 230), ImGuiCond_FirstUseEver);
    tools();
    ImGui::SetNextWindowPos(ImVec2(8, 246), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(330, compact ? std::min(300.0f, size.y - 254.0f) : 300.0f),
                             ImGuiCond_FirstUseEver);
    library();
    ImGui::SetNextWindowPos(ImVec2(w - 378, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(370, 420), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowCollapsed(compact, ImGuiCond_FirstUseEver);
    configuration();
    ImGui::SetNextWindowPos(ImVec2(w - 378, compact ? 34.0f : 436.0f), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(370, 260), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowCollapsed(compact, ImGuiCond_FirstUseEver);
    style();
    ImGui::SetNextWindowPos(ImVec2(compact ? w - 378 : 8.0f, compact ? 60.0f : 554.0f),
                            ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(compact ? 370.0f : 520.0f, 190), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowCollapsed(compact, ImGuiCond_FirstUseEver);
    feature();
}

void ViewerPanels::tools()
{
    ViewerSession& s = *_session;
    if (!ImGui::Begin("LoA tools")) return ImGui::End();
    int mode = int(s.mode);
    for (int m = 0; m < ViewerSession::NUM_MODES; ++m)
    {
        if (m) ImGui::SameLine();
        ImGui::RadioButton(ViewerSession::modeName(ViewerSession::Mode(m)), &mode, m);
    }
    s.mode = ViewerSession::Mode(mode);
    bool interest = s.getInterestView();
    if (ImGui::Checkbox("interest view (i)", &interest)) s.setInterestView(interest);
    ImGui::SameLine();
    if (ImGui::Button("detail in circles (R)")) s.useRegionDetail();
    osgLoA::ScenarioEditor& e = s.getEditor();
    ImGui::BeginDisabled(!e.canUndo());
    if (ImGui::Button("undo")) s.undo();
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::BeginDisabled(!e.canRedo());
    if (ImGui::Button("redo")) s.redo();
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::TextDisabled("%s", e.canUndo() ? ("last: " + e.undoLabel()).c_str() : "no edits");
    // Viewpoints: the scene's cameras and saved ones.
    std::vector<std::string> names;
    for (const auto& v : s.viewpoints)
        names.push_back(v.name + (v.user ? " (saved)" : ""));
    static int choice = 0;
    ImGui::SetNextItemWidth(150);
    if (combo("##viewpoint", choice, names) && choice < int(s.viewpoints.size()))
        AuthoringHandler::goTo(*_view, s.viewpoints[std::size_t(choice)]);
    ImGui::SameLine();
    if (ImGui::Button("save viewpoint"))
        s.addViewpoint("view " + std::to_string(s.viewpoints.size() + 1),
                       AuthoringHandler::currentPose(*_view));
    const osgLoA::TransitionRenderer::Statistics& st = s.getNode().getRenderer()->getStatistics();
    ImGui::Text("%u features drawn, %u in transition; binds %u, re-fits %u", st.drawnFeatures,
                st.depthOnlyDraws, s.getNode().getBindCount(), s.getNode().getRefitCount());
    if (!s.message.empty())
        ImGui::TextColored(s.messageIsError ? ImVec4(1.0f, 0.45f, 0.4f, 1.0f)
                                            : ImVec4(0.6f, 0.9f, 0.6f, 1.0f),
                           "%s", s.message.c_str());
    ImGui::TextDisabled("h: keys, Tab: hide panels");
    ImGui::End();
}

void ViewerPanels::library()
{
    ViewerSession& s = *_session;
    if (!ImGui::Begin("Scenario library")) return ImGui::End();
    osgLoA::ScenarioEditor& e = s.getEditor();
    const osgLoA::UsageScenario& sc = e.getScenario();
    ImGui::Text("%s%s", sc.getName().c_str(), e.isModified() ? " (modified)" : "");
    // The file's name and folder only: the panel reads the same on every machine.
    const std::string folder = osgDB::getSimpleFileName(osgDB::getFilePath(s.origin));
    ImGui::TextDisabled("from %s", osgDB::getFilePath(s.origin).empty()
                                       ? s.origin.c_str()
                                       : (folder + "/" + osgDB::getSimpleFileName(s.origin)).c_str());
    const std::vector<std::string> names = s.libraryNames();
    ImGui::SetNextItemWidth(-1);
    if (ImGui::BeginListBox("##library", ImVec2(-1, 90)))
    {
        for (unsigned i = 0; i < names.size(); ++i)
            if (ImGui::Selectable(names[i].c_str(), i == _libraryChoice)) _libraryChoice = i;
        ImGui::EndListBox();
    }
    if (ImGui::Button("load") && _libraryChoice < names.size())
        s.attempt([&] { s.loadScenario(names[_libraryChoice]); });
    ImGui::SameLine();
    ImGui::SetNextItemWidth(120);
    ImGui::InputText("##dup", _duplicateName, sizeof(_duplicateName));
    ImGui::SameLine();
    if (ImGui::Button("duplicate as")) s.attempt([&] { s.duplicateScenario(_duplicateName); });
    if (_saveAs[0] == 0 || ImGui::IsWindowAppearing())
        std::strncpy(_saveAs, s.savePath.c_str(), sizeof(_saveAs) - 1);
    ImGui::SetNextItemWidth(220);
    if (ImGui::InputText("##saveas", _saveAs, sizeof(_saveAs)))
    {
        s.savePath = _saveAs;
        s.savePathGiven = true;
    }
    ImGui::SameLine();
    if (ImGui::Button("save (Ctrl+S)")) s.attempt([&] { s.saveScenario(s.savePath); });
    if (std::strcmp(_saveAs, s.savePath.c_str()) != 0 && !ImGui::IsItemActive())
        std::strncpy(_saveAs, s.savePath.c_str(), sizeof(_saveAs) - 1);
    // Validation, live (what loa-scenario validate says).
    const osgLoA::UsageScenario::Validation& v = e.getValidation();
    if (v.errors.empty() && v.warnings.empty()) ImGui::TextColored(ImVec4(0.6f, 0.9f, 0.6f, 1), "valid");
    for (const std::string& m : v.errors)
        ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "error: %s", m.c_str());
    for (const std::string& m : v.warnings)
        ImGui::TextColored(ImVec4(1, 0.8f, 0.3f, 1), "warning: %s", m.c_str());
    if (ImGui::CollapsingHeader("history"))
    {
        const std::vector<std::string> h = e.history();
        for (std::size_t i = 0; i < h.size(); ++i)
            ImGui::TextColored(i < e.getDone() ? ImVec4(1, 1, 1, 1) : ImVec4(0.5f, 0.5f, 0.5f, 1), "%zu %s",
                               i + 1, h[i].c_str());
    }
    ImGui::End();
}

void ViewerPanels::configuration()
{
    ViewerSession& s = *_session;
    if (!ImGui::Begin("Configuration")) return ImGui::End();
    osgLoA::ScenarioEditor& e = s.getEditor();
    const auto& configs = e.getScenario().getConfigurations();
    if (configs.empty())
    {
        ImGui::Text("the scenario has no configuration");
        return ImGui::End();
    }
    if (selected >= configs.size()) selected = 0;
    std::vector<std::string> names;
    for (const auto& c : configs)
        names.push_back(c.valid() ? c->getName() : "?");
    int sel = int(selected);
    if (combo("configuration", sel, names)) selected = unsigned(sel);
    const unsigned j = selected;
    // Held: an edit below replaces the scenario's configurations (UsageScenario::assign); the
    // rest of this frame's panel reads the one it started with.
    const osg::ref_ptr<const osgLoA::TransitionConfiguration> held = configs[j];
    const osgLoA::TransitionConfiguration& c = *held;
    if (ImGui::Button("duplicate")) s.attempt([&] { selected = e.duplicateConfiguration(j); });
    ImGui::SameLine();
    if (ImGui::Button("remove")) s.attempt([&] { e.removeConfiguration(j); });
    ImGui::SameLine();
    if (ImGui::Button("earlier")) s.attempt([&] { e.moveConfiguration(j, -1); });
    ImGui::SameLine();
    if (ImGui::Button("later")) s.attempt([&] { e.moveConfiguration(j, +1); });

    // Style.
    const std::vector<std::string> styles = osgLoA::GraphicStyleCatalog::instance().names();
    int st = int(std::find(styles.begin(), styles.end(), c.getStyle()) - styles.begin());
    if (combo("style", st, styles)) s.attempt([&] { e.setStyle(j, styles[std::size_t(st)]); });
    // Scope.
    ImGui::Text("types:");
    for (osgLoA::FeatureType t : osgLoA::kFeatureTypes)
    {
        ImGui::SameLine();
        bool on = c.hasFeatureType(t);
        if (ImGui::Checkbox(osgLoA::toString(t), &on))
            s.attempt(
                [&]
                {
                    osgLoA::TransitionConfiguration::FeatureTypes types = c.getFeatureTypes();
                    if (on)
                        types.push_back(t);
                    else
                        types.erase(std::remove(types.begin(), types.end(), t), types.end());
                    e.setFeatureTypes(j, types);
                });
    }
    if (_subTypesFor != j || !ImGui::IsWindowFocused())
    {
        std::string joined;
        for (const std::string& t : c.getSubTypes())
            joined += (joined.empty() ? "" : ",") + t;
        std::strncpy(_subTypes, joined.c_str(), sizeof(_subTypes) - 1);
        _subTypesFor = j;
    }
    if (ImGui::InputText("sub-types", _subTypes, sizeof(_subTypes), ImGuiInputTextFlags_EnterReturnsTrue))
        s.attempt(
            [&]
            {
                osgLoA::TransitionConfiguration::SubTypes list;
                std::istringstream in(_subTypes);
                for (std::string t; std::getline(in, t, ',');)
                    if (!t.empty()) list.push_back(t);
                e.setSubTypes(j, list);
            });
    osg::Vec2f range = c.getInterestRange();
    edited(s, ImGui::DragFloat2("interest scope", range.ptr(), 0.01f, 0.0f, 1.0f),
           [&] { e.setInterestRange(j, range); });
    // Interpolation and combination.
    int mode = int(c.getInterpolation());
    if (combo("interpolation", mode, {"fragment", "object", "group"}))
        s.attempt([&] { e.setInterpolation(j, osgLoA::TransitionConfiguration::Interpolation(mode)); });
    int comb = int(c.getCombination());
    if (combo("combination", comb, {"weighted mean", "minimum", "maximum"}))
        s.attempt([&] { e.setCombination(j, osgLoA::TransitionConfiguration::Combination(comb)); });
    // Validity: fade-in and fade-out over interest.
    osg::Vec2f in = c.getFadeIn(), out = c.getFadeOut();
    edited(s, ImGui::SliderFloat2("fade-in", in.ptr(), 0.0f, 1.0f), [&] { e.setFadeIn(j, in); });
    edited(s, ImGui::SliderFloat2("fade-out", out.ptr(), 0.0f, 1.0f), [&] { e.setFadeOut(j, out); });
    // Metrics.
    ImGui::Separator();
    for (int k = 0; k < osgLoA::SaliencyMetric::kNumKinds; ++k)
    {
        const auto kind = osgLoA::SaliencyMetric::Kind(k);
        const osg::ref_ptr<const osgLoA::SaliencyMetric> m = c.getMetric(kind);
        ImGui::PushID(k);
        bool on = m != nullptr;
        if (ImGui::Checkbox(osgLoA::SaliencyMetric::toString(kind), &on))
            s.attempt(
                [&]
                {
                    if (on)
                        e.setMetric(j, kind, 0.0, kind == osgLoA::SaliencyMetric::VIEW_ANGLE ? 90.0 : 1.0,
                                    1.0);
                    else
                        e.removeMetric(j, kind);
                });
        if (m)
        {
            double v[3] = {m->getNear(), m->getFar(), m->getWeight()};
            const float speed = float(std::max(0.001, std::fabs(m->getFar() - m->getNear()) * 0.005));
            ImGui::SetNextItemWidth(200);
            edited(s, ImGui::DragScalarN("near/far", ImGuiDataType_Double, v, 2, speed),
                   [&] { e.setMetric(j, kind, v[0], v[1], v[2]); });
            ImGui::SameLine();
            ImGui::SetNextItemWidth(60);
            edited(s, ImGui::DragScalar("w", ImGuiDataType_Double, &v[2], 0.01f),
                   [&] { e.setMetric(j, kind, v[0], v[1], std::max(0.0, v[2])); });
            ImGui::TextDisabled("  scale: %s", osgLoA::SaliencyMetric::toString(m->getScale()));
        }
        ImGui::PopID();
    }
    ImGui::End();
}

void ViewerPanels::style()
{
    ViewerSession& s = *_session;
    if (!ImGui::Begin("Style")) return ImGui::End();
    osgLoA::LoANode& node = s.getNode();
    const auto& configs = s.getEditor().getScenario().getConfigurations();
    if (selected < configs.size() && configs[selected].valid())
    {
        const std::string styleName = configs[selected]->getStyle();
        ImGui::Text("style '%s' of configuration '%s'", styleName.c_str(),
                    configs[selected]->getName().c_str());
        if (const osgLoA::GraphicStyle* gs = node.getRenderer()->getBoundStyle(selected))
            ImGui::TextDisabled("fragment stage %s", gs->getFragmentShader().c_str());
        osg::StateSet* ss = node.getRenderer()->getBoundParameters(selected);
        if (!ss)
            ImGui::TextDisabled("(not bound yet)");
        else
            for (const auto& entry : ss->getUniformList())
            {
                osg::Uniform* u = entry.second.first.get();
                UniformValue value;
                if (!u || !value.read(*u))
                {
                    ImGui::TextDisabled("%s (%s)", entry.first.c_str(),
                                        u ? osg::Uniform::getTypename(u->getType()) : "?");
                    continue;
                }
                const UniformValue before = value;
                bool changed = false;
                const char* name = entry.first.c_str();
                switch (u->getType())
                {
                case osg::Uniform::FLOAT:
                    changed = ImGui::DragFloat(name, value.f, 0.01f);
                    break;
                case osg::Uniform::FLOAT_VEC2:
                    changed = ImGui::DragFloat2(name, value.f, 0.01f);
                    break;
                case osg::Uniform::FLOAT_VEC3:
                    changed = entry.first.find("olor") != std::string::npos
                                  ? ImGui::ColorEdit3(name, value.f)
                                  : ImGui::DragFloat3(name, value.f, 0.01f);
                    break;
                case osg::Uniform::FLOAT_VEC4:
                    changed = entry.first.find("olor") != std::string::npos
                                  ? ImGui::ColorEdit4(name, value.f)
                                  : ImGui::DragFloat4(name, value.f, 0.01f);
                    break;
                case osg::Uniform::INT:
                    changed = ImGui::InputInt(name, &value.i);
                    break;
                case osg::Uniform::BOOL:
                    changed = ImGui::Checkbox(name, &value.b);
                    break;
                default:
                    break;
                }
                // Live while the widget is held; one undoable step when it is let go, from the
                // value it had when it was taken.
                static std::map<std::string, UniformValue> heldFrom;
                const std::string uniformName = entry.first;
                const std::string key = styleName + "|" + uniformName;
                if (ImGui::IsItemActivated()) heldFrom[key] = before;
                if (changed) setStyleUniform(node, styleName, uniformName, value);
                if (ImGui::IsItemDeactivatedAfterEdit() || (changed && !ImGui::IsItemActive()))
                {
                    const UniformValue from = heldFrom.count(key) ? heldFrom[key] : before;
                    heldFrom.erase(key);
                    osg::ref_ptr<osgLoA::LoANode> keep = &node;
                    s.getEditor().recordLive(
                        "'" + styleName + "' " + uniformName,
                        [keep, styleName, uniformName, from, value](bool redo)
                        { setStyleUniform(*keep, styleName, uniformName, redo ? value : from); });
                }
                else if (ImGui::IsItemDeactivated())
                    heldFrom.erase(key);
            }
    }
    ImGui::Separator();
    if (ImGui::Button("reload shaders (F5)")) s.reloadShaders();
    ImGui::SameLine();
    ImGui::TextDisabled("from OSG_FILE_PATH");
    if (!s.shaderLog.empty())
    {
        ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "compile log:");
        ImGui::BeginChild("log", ImVec2(0, 90), true, ImGuiWindowFlags_HorizontalScrollbar);
        ImGui::TextUnformatted(s.shaderLog.c_str());
        ImGui::EndChild();
    }
    ImGui::End();
}

void ViewerPanels::feature()
{
    ViewerSession& s = *_session;
    if (!ImGui::Begin("Feature")) return ImGui::End();
    if (!s.inspected)
    {
        ImGui::TextDisabled("inspect mode (e): click a feature");
        return ImGui::End();
    }
    const osgLoA::FeatureInspector::Report& r = s.inspection;
    ImGui::Text("feature %u: %s%s%s (%s)", r.id, r.type.c_str(), r.subType.empty() ? "" : "/",
                r.subType.c_str(), r.source.c_str());
    if (!r.label.empty()) ImGui::Text("'%s'", r.label.c_str());
    if (!r.sourceType.empty()) ImGui::TextDisabled("model class: %s", r.sourceType.c_str());
    ImGui::Text("interest %.3f%s%s", r.staticInterest, r.landmark ? ", landmark" : "",
                r.focus ? ", focus object" : "");
    // Each matching configuration's interest and blend weight at the clicked point.
    if (!r.weights.empty() &&
        ImGui::BeginTable("weights", 5, ImGuiTableFlags_Borders | ImGuiTableFlags_SizingFixedFit))
    {
        for (const char* h : {"configuration", "style", "mode", "interest", "weight"})
            ImGui::TableSetupColumn(h);
        ImGui::TableHeadersRow();
        for (const osgLoA::FeatureInspector::Weight& w : r.weights)
        {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(w.name.c_str());
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(w.style.c_str());
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(w.interpolation.c_str());
            ImGui::TableNextColumn();
            ImGui::Text("%.3f", w.interest);
            ImGui::TableNextColumn();
            ImGui::Text("%.3f", w.weight);
        }
        ImGui::EndTable();
    }
    osgLoA::ScenarioEditor& e = s.getEditor();
    if (ImGui::Button(r.focus ? "clear focus" : "set as focus"))
        s.attempt([&] { e.setFocusFeature(r.focus ? 0 : r.id); });
    ImGui::SameLine();
    if (ImGui::Button(r.landmark ? "clear landmark" : "make landmark"))
        s.attempt([&] { e.setLandmark(r.id, !r.landmark); });
    std::vector<std::string> types;
    for (osgLoA::FeatureType t : osgLoA::kFeatureTypes)
        types.push_back(osgLoA::toString(t));
    ImGui::SetNextItemWidth(110);
    combo("##type", _typeChoice, types);
    ImGui::SameLine();
    if (ImGui::Button("set type (user rule)"))
        s.attempt([&] { e.setFeatureType(r.id, osgLoA::kFeatureTypes[_typeChoice]); });
    ImGui::End();
}

} // namespace loa
