// loa-scenario: authoring tool for usage scenarios (paper 004 §3.1, §3.2.1, §4.1): lists the
// scenario libraries, shows and validates scenarios, creates and edits scenario files, and
// explains what a scenario does to each feature of a model from a camera.
#include "../common/AppSupport.h"
#include "../common/CommandLine.h"
#include "InterestImage.h"

#include <osgLoA/Version>
#include <osgLoA/city/CityCameras>
#include <osgLoA/interest/RegionFile>
#include <osgLoA/semantics/ClassificationRuleSet>
#include <osgLoA/semantics/FeatureClassifier>
#include <osgLoA/styles/ColorScheme>
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/ScenarioLibrary>
#include <osgLoA/util/JsonString>

#include <osg/Polytope>
#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/Registry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <set>
#include <sstream>

namespace
{
using osgLoA::RegionOfInterest;
using osgLoA::SaliencyMetric;
using osgLoA::TransitionConfiguration;
using osgLoA::UsageScenario;

const char* kDescription =
    R"(Authoring tool for usage scenarios: how a city model is drawn for a task (paper 004 §3.1,
§4.1). A SCENARIO argument is a library name (see `list`) or a scenario file (.osgt, .osgb,
.osgx holding an osgLoA::UsageScenario). Full guide with examples: docs/loa-scenario.md.
)";
const char* kFooter =
    R"(exit status: 0 done; 1 the work failed (a scenario or model could not be read or written, a
scenario does not validate, FILE exists without --force); 2 bad arguments (unknown command,
option, key or a bad value); 3 no usable EGL/OpenGL context (only with --image).
)";
const char* kListDescription =
    R"(Every scenario name the libraries and the built-ins offer, with its origin (file or
"built-in") and the first sentence of its description.
)";
const char* kShowDescription =
    R"(Description, interest overrides, regions, focus object, and per configuration its scope,
style, interpolation, combination, metrics, fade-in and fade-out, then the validation result.
)";
const char* kValidateDescription =
    R"(Checks each scenario: one line per error or warning, "FILE: error: ..." or
"FILE: warning: ..."; exit status 1 when any scenario has an error.
)";
const char* kCreateDescription =
    R"(Writes a new scenario file (atomically). --from copies a library, built-in or file scenario.
Without --from the new scenario has one configuration, 'photorealistic': every feature type,
style photorealistic, object interpolation, one feature-interest metric (valid as it is; edit
it with `set`). The scenario's name is FILE's base name. Refuses to overwrite an existing FILE
without --force.
)";
const char* kSetDescription =
    R"(Edits a scenario file in place (atomically), applying the edits in order, then validates:
when the result has errors it prints them, leaves FILE unchanged and exits with status 1,
unless --force. Edits:
  scenario keys
    description=TEXT
    focus=ID | tallest | none       the focus object of focus metrics: a feature id, or
                                    the tallest landmark of the model it is bound to
    colors=SCHEME | none            the cartographic styles' colour scheme:
                                    feature-types (one colour per type) or
                                    brewer-subtypes (per sub-type: building uses,
                                    forest and water kinds, road classes)
    interest.TYPE=V | none          interest override for a feature type (building,
                                    street, water, green, terrain, generic), V in [0,1]
    interest.ID=V | none            interest override for one feature id
    interest.default=V              interest of features without another value
    interest.keep-existing=yes|no   keep the features' own interest where no override
                                    applies (default yes for overrides made here)
    interest.landmark-threshold=V
    interest=none                   (without --configuration) drop every override
  configuration keys (need --configuration NAME)
    name=NEW                        rename it
    style=NAME                      a graphic style (photorealistic, abstract,
                                    cartographic, blueprint, hidden)
    types=T,T... | all              feature types in scope (types= empties the scope)
    subtypes=A,B... | subtypes=     sub-types in scope (empty: any)
    lod=MIN:MAX                     LoD range in scope
    interest=MIN:MAX                static-interest range in scope, e.g. 0.8:1
    interpolation=fragment|object|group
    group-focus=X,Y,Z | none        shared focus point of group interpolation
    combination=weighted-mean|minimum|maximum
    fade-in=BEGIN:END               fade-in interval over interest (BEGIN alone or
    fade-out=BEGIN:END              BEGIN:BEGIN: a hard step; fade-out=1:1: none)
    metric.KIND=NEAR:FAR[:WEIGHT[:SCALE]]
                                    adds or replaces the metric of KIND (view-distance,
                                    view-angle, region, focus, feature-interest);
                                    feature-interest ignores NEAR:FAR (write 0:0 or on);
                                    SCALE: absolute (scene units, the default), scene
                                    (times the model's size S) or view (times the
                                    camera's distance to the model's centre)
    metric.KIND=none                removes it
  structure
    add-configuration NAME          appends a configuration like create's default
                                    (all types, photorealistic, object, feature-interest)
    remove-configuration NAME
    add-region SHAPE "X,Y;X,Y;..." [RADIUS]
                                    SHAPE circles, polyline or polygon; RADIUS >= 0
                                    (default 0); named region-N
    add-regions FILE [RADIUS]       every point (circles), line (polyline) and polygon of
                                    a GeoJSON file (or any vector format GDAL reads),
                                    named by its "name" property; with --model MODEL
                                    of a geo-referenced model (CityJSON, OSM) the
                                    coordinates are longitude/latitude (or the file's
                                    own reference system), else scene x/y
    clear-regions
    region-line NAME|all WIDTH [R,G,B[,A]]
                                    draws the region (or every region) as a line on
                                    the ground, WIDTH pixels wide (0: not drawn, at
                                    most 64), colour components in [0, 1] (default
                                    0.216,0.494,0.722: ColorBrewer Set1 blue)
)";
const char* kExplainDescription =
    R"(Loads MODEL (default: the demo city, demo.loacity; several are one scene), classifies it,
binds the scenario to it in an osgLoA::LoANode and evaluates it at the camera's eye. Prints per
feature in the view frustum, nearest first (distance from the eye to the centre of its box):
id, type, static interest and, per matching configuration, its interest, raw and normalized
blend weight and interpolation mode; then the evaluator's statistics. Fragment-mode values are
those at the centre of the feature's box (the shader evaluates them per fragment); they are
marked with '*'.
)";

// ---------------------------------------------------------------- formatting

std::string num(double v, int precision = 7)
{
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", precision, v == 0.0 ? 0.0 : v);
    return buf;
}

/** A JSON number (null for NaN and infinities). */
std::string jnum(double v, int precision = 7)
{
    return std::isfinite(v) ? num(v, precision) : std::string("null");
}

std::string jstr(const std::string& s)
{
    return "\"" + osgLoA::jsonEscape(s) + "\"";
}

std::string jvec(std::initializer_list<double> values, int precision = 7)
{
    std::string s = "[";
    for (double v : values)
        s += (s.size() > 1 ? ", " : "") + jnum(v, precision);
    return s + "]";
}

std::string range(const osg::Vec2f& v)
{
    return num(v.x()) + ".." + num(v.y());
}

std::string firstSentence(const std::string& text)
{
    for (std::size_t i = 0; i + 2 < text.size(); ++i)
        if (text[i] == '.' && text[i + 1] == ' ' && std::isupper(static_cast<unsigned char>(text[i + 2])))
            return text.substr(0, i + 1);
    return text;
}

std::string joinTypes(const TransitionConfiguration::FeatureTypes& types)
{
    std::string s;
    for (osgLoA::FeatureType t : types)
        s += (s.empty() ? "" : ", ") + std::string(osgLoA::toString(t));
    return s;
}

std::string configLabel(const TransitionConfiguration& c)
{
    return c.getName().empty() ? std::string("(unnamed)") : c.getName();
}

// ---------------------------------------------------------------- value parsing

std::string lower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

std::vector<std::string> split(const std::string& text, char sep)
{
    std::vector<std::string> parts;
    std::string cur;
    for (char c : text)
        if (c == sep)
            parts.push_back(cur), cur.clear();
        else
            cur += c;
    parts.push_back(cur);
    return parts;
}

bool toNumber(const std::string& text, double& v)
{
    if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return false;
    char* end = nullptr;
    v = std::strtod(text.c_str(), &end);
    return end && *end == '\0' && std::isfinite(v);
}

double number(const std::string& what, const std::string& text)
{
    double v = 0.0;
    if (!toNumber(text, v)) throw loa::UsageError(what + ": '" + text + "' is not a finite number");
    return v;
}

double unitNumber(const std::string& what, const std::string& text)
{
    const double v = number(what, text);
    if (v < 0.0 || v > 1.0) throw loa::UsageError(what + ": " + text + " is outside [0,1]");
    return v;
}

/** "A:B", or "A" for A:A. */
osg::Vec2f interval(const std::string& what, const std::string& text)
{
    const std::vector<std::string> p = split(text, ':');
    if (p.size() > 2) throw loa::UsageError(what + ": '" + text + "' is not MIN:MAX");
    const double a = number(what, p[0]);
    const double b = p.size() == 2 ? number(what, p[1]) : a;
    return osg::Vec2f(float(a), float(b));
}

bool yesNo(const std::string& what, const std::string& text)
{
    const std::string t = lower(text);
    if (t == "yes" || t == "true" || t == "on" || t == "1") return true;
    if (t == "no" || t == "false" || t == "off" || t == "0") return false;
    throw loa::UsageError(what + ": '" + text + "' is not yes or no");
}

unsigned featureId(const std::string& what, const std::string& text)
{
    return loa::parseCount(what, text, 4294967295u);
}

bool isId(const std::string& text)
{
    return !text.empty() &&
           std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isdigit(c); });
}

// ---------------------------------------------------------------- scenario helpers

struct Loaded
{
    osg::ref_ptr<UsageScenario> scenario;
    std::string origin; ///< file path or "built-in"
};

Loaded loadScenario(const std::string& nameOrPath)
{
    Loaded l;
    l.scenario = osgLoA::ScenarioLibrary::load(nameOrPath, &l.origin);
    return l;
}

/** The default configuration of `create` and `add-configuration`. */
osg::ref_ptr<TransitionConfiguration> defaultConfiguration(const std::string& name)
{
    osg::ref_ptr<TransitionConfiguration> c = new TransitionConfiguration;
    c->setName(name);
    c->setAllFeatureTypes();
    c->setStyle("photorealistic");
    c->setInterpolation(TransitionConfiguration::OBJECT);
    c->addMetric(new SaliencyMetric(SaliencyMetric::FEATURE_INTEREST, 0.0, 0.0, 1.0));
    return c;
}

std::string regionText(const RegionOfInterest& r)
{
    std::ostringstream o;
    o << (r.getName().empty() ? std::string("(unnamed)") : r.getName()) << ": "
      << RegionOfInterest::toString(r.getShape());
    if (r.getPlacement() != RegionOfInterest::ABSOLUTE)
    {
        o << " placed " << RegionOfInterest::toString(r.getPlacement());
        if (r.getPlacement() == RegionOfInterest::FEATURE)
            o << " "
              << (r.getPlacementFeature() ? std::to_string(r.getPlacementFeature())
                                          : std::string("(tallest)"));
    }
    o << ", radius " << num(r.getRadius(), 12) << (r.getSceneScale() ? " S" : "");
    if (r.getLineWidth() > 0.0)
    {
        const osg::Vec4f& c = r.getLineColor();
        o << ", drawn as a " << num(r.getLineWidth(), 6) << " px line of colour " << num(c.r(), 4) << ","
          << num(c.g(), 4) << "," << num(c.b(), 4) << " (opacity " << num(c.a(), 4) << ")";
    }
    if (r.getPlacement() == RegionOfInterest::LONGEST_STREET)
        return o.str() + " (vertices: a route along the model's streets)";
    o << ", " << r.getVertices().size()
      << (r.getPlacement() != RegionOfInterest::ABSOLUTE ? " vertex offsets" : " vertices")
      << (r.getSceneScale() ? " (times S)" : "") << ":";
    std::string sep = " ";
    for (const osg::Vec2d& v : r.getVertices())
        o << sep << num(v.x(), 12) << "," << num(v.y(), 12), sep = "; ";
    return o.str();
}

std::string metricText(const SaliencyMetric& m)
{
    std::string s = SaliencyMetric::toString(m.getKind());
    if (m.getKind() != SaliencyMetric::FEATURE_INTEREST)
    {
        const std::string unit = m.getScale() == SaliencyMetric::SCENE  ? " S"
                                 : m.getScale() == SaliencyMetric::VIEW ? " D"
                                                                        : "";
        s += " near " + num(m.getNear(), 12) + unit + " far " + num(m.getFar(), 12) + unit;
    }
    return s + " weight " + num(m.getWeight(), 12);
}

std::string fadeText(const osg::Vec2f& v, bool out)
{
    if (out && v.x() >= 1.0f && v.y() <= v.x()) return "none (" + range(v) + ")";
    if (!out && v.x() <= 0.0f && v.y() <= 0.0f) return "none (" + range(v) + ")";
    return range(v) + (v.y() <= v.x() ? " (hard)" : " (smooth)");
}

void printValidation(std::ostream& out, const UsageScenario::Validation& v, const std::string& prefix)
{
    for (const std::string& e : v.errors)
        out << prefix << "error: " << e << "\n";
    for (const std::string& w : v.warnings)
        out << prefix << "warning: " << w << "\n";
}

std::string jsonStrings(const std::vector<std::string>& v)
{
    std::string s = "[";
    for (const std::string& x : v)
        s += (s.size() > 1 ? ", " : "") + jstr(x);
    return s + "]";
}

// ---------------------------------------------------------------- list

int cmdList(bool json)
{
    const std::vector<std::string> names = osgLoA::ScenarioLibrary::availableNames();
    std::size_t width = 4;
    for (const std::string& n : names)
        width = std::max(width, n.size());
    if (json) std::cout << "[";
    bool first = true;
    for (const std::string& n : names)
    {
        std::string origin, description;
        bool readable = true;
        try
        {
            const Loaded l = loadScenario(n);
            origin = l.origin;
            description = firstSentence(l.scenario->getDescription());
        }
        catch (const std::exception& e)
        {
            const std::string file = osgLoA::ScenarioLibrary::findFile(n);
            origin = file.empty() ? "?" : file;
            description = std::string("(unreadable: ") + e.what() + ")";
            readable = false;
        }
        if (json)
            std::cout << (first ? "\n  " : ",\n  ") << "{\"name\": " << jstr(n)
                      << ", \"origin\": " << jstr(origin) << ", \"description\": " << jstr(description)
                      << ", \"readable\": " << (readable ? "true" : "false") << "}";
        else
            std::cout << n << std::string(width + 2 - n.size(), ' ') << origin << "\n"
                      << std::string(width + 2, ' ') << description << "\n";
        first = false;
    }
    if (json) std::cout << (names.empty() ? "]\n" : "\n]\n");
    return loa::kOk;
}

// ---------------------------------------------------------------- show

void showText(const Loaded& l)
{
    const UsageScenario& s = *l.scenario;
    std::cout << "scenario '" << s.getName() << "' (" << l.origin << ")\n";
    std::cout << "description: " << (s.getDescription().empty() ? "(none)" : s.getDescription()) << "\n";
    const osgLoA::FeatureInterest* fi = s.getInterest();
    if (!fi)
        std::cout << "interest overrides: none (the features' own interest values)\n";
    else
    {
        std::cout << "interest overrides:\n";
        std::string types;
        for (const auto& kv : fi->getTypeInterests())
            types +=
                (types.empty() ? "" : ", ") + std::string(osgLoA::toString(kv.first)) + " " + num(kv.second);
        std::cout << "  per type: " << (types.empty() ? "none" : types) << "\n";
        std::string ids;
        for (const auto& kv : fi->getFeatureInterests())
            ids += (ids.empty() ? "" : ", ") + std::to_string(kv.first) + " " + num(kv.second);
        std::cout << "  per feature id: " << (ids.empty() ? "none" : ids) << "\n";
        std::cout << "  keep existing interest: " << (fi->getKeepExistingInterest() ? "yes" : "no")
                  << "; default interest " << num(fi->getDefaultInterest()) << "; landmark threshold "
                  << num(fi->getLandmarkThreshold()) << "\n";
    }
    std::cout << "focus: "
              << (s.getFocusFeature()           ? "feature " + std::to_string(s.getFocusFeature())
                  : s.getFocusTallestLandmark() ? std::string("the tallest landmark (chosen per model)")
                                                : std::string("none"))
              << "\n";
    std::cout << "colour scheme: "
              << (s.getColorScheme().empty() ? std::string("none (one colour per type)") : s.getColorScheme())
              << "\n";
    bool relative = s.getFocusFeature() == 0 && s.getFocusTallestLandmark();
    for (const auto& r : s.getRegions())
        relative = relative || (r.valid() && !r->isResolved());
    for (const auto& c : s.getConfigurations())
        for (const auto& m : c->getMetrics())
            relative = relative || (m.valid() && m->getScale() != SaliencyMetric::ABSOLUTE);
    if (relative)
        std::cout << "fitted to each model: S is the scene's size (half the horizontal diagonal of its "
                     "features' box), D the camera's distance to the scene centre (loa-scenario explain "
                     "prints the values for a model)\n";
    std::cout << "regions: " << s.getRegions().size() << "\n";
    for (const auto& r : s.getRegions())
        if (r.valid()) std::cout << "  " << regionText(*r) << "\n";
    std::cout << "configurations: " << s.getConfigurations().size() << " (drawn in this order)\n";
    unsigned i = 0;
    for (const auto& cp : s.getConfigurations())
    {
        ++i;
        if (!cp.valid())
        {
            std::cout << "  " << i << ". (null)\n";
            continue;
        }
        const TransitionConfiguration& c = *cp;
        std::string subTypes;
        for (const std::string& t : c.getSubTypes())
            subTypes += (subTypes.empty() ? "" : ", ") + t;
        std::cout << "  " << i << ". " << configLabel(c) << "\n"
                  << "     scope: types "
                  << (c.getFeatureTypes().empty() ? "(none)" : joinTypes(c.getFeatureTypes()))
                  << "; sub-types " << (subTypes.empty() ? "any" : subTypes) << "; LoD "
                  << range(c.getLodRange()) << "; interest scope " << range(c.getInterestRange()) << "\n"
                  << "     style: " << (c.getStyle().empty() ? "(none)" : c.getStyle()) << "\n"
                  << "     interpolation: " << TransitionConfiguration::toString(c.getInterpolation());
        if (c.getHasGroupFocus())
        {
            const osg::Vec3d& g = c.getGroupFocus();
            std::cout << " (group focus " << num(g.x(), 12) << "," << num(g.y(), 12) << "," << num(g.z(), 12)
                      << ")";
        }
        std::cout << "\n     combination: " << TransitionConfiguration::toString(c.getCombination()) << "\n"
                  << "     metrics:";
        if (c.getMetrics().empty()) std::cout << " none";
        std::cout << "\n";
        for (const auto& m : c.getMetrics())
            if (m.valid()) std::cout << "       " << metricText(*m) << "\n";
        std::cout << "     fade-in: " << fadeText(c.getFadeIn(), false)
                  << "; fade-out: " << fadeText(c.getFadeOut(), true) << "\n";
    }
    const UsageScenario::Validation v = s.validate();
    std::cout << "validation: "
              << (v.ok() && v.warnings.empty() ? std::string("ok")
                                               : std::to_string(v.errors.size()) + " errors, " +
                                                     std::to_string(v.warnings.size()) + " warnings")
              << "\n";
    printValidation(std::cout, v, "  ");
}

void showJson(const Loaded& l)
{
    const UsageScenario& s = *l.scenario;
    std::ostringstream o;
    o << "{\n  \"name\": " << jstr(s.getName()) << ",\n  \"origin\": " << jstr(l.origin)
      << ",\n  \"description\": " << jstr(s.getDescription()) << ",\n  \"interest\": ";
    if (const osgLoA::FeatureInterest* fi = s.getInterest())
    {
        o << "{\"types\": {";
        bool first = true;
        for (const auto& kv : fi->getTypeInterests())
            o << (first ? "" : ", ") << jstr(osgLoA::toString(kv.first)) << ": " << jnum(kv.second),
                first = false;
        o << "}, \"features\": {";
        first = true;
        for (const auto& kv : fi->getFeatureInterests())
            o << (first ? "" : ", ") << jstr(std::to_string(kv.first)) << ": " << jnum(kv.second),
                first = false;
        o << "}, \"default\": " << jnum(fi->getDefaultInterest())
          << ", \"keep-existing\": " << (fi->getKeepExistingInterest() ? "true" : "false")
          << ", \"landmark-threshold\": " << jnum(fi->getLandmarkThreshold()) << "}";
    }
    else
        o << "null";
    o << ",\n  \"focus\": " << s.getFocusFeature()
      << ", \"focus-tallest-landmark\": " << (s.getFocusTallestLandmark() ? "true" : "false")
      << ", \"color-scheme\": " << jstr(s.getColorScheme()) << ",\n  \"regions\": [";
    bool first = true;
    for (const auto& r : s.getRegions())
    {
        if (!r.valid()) continue;
        o << (first ? "\n    " : ",\n    ") << "{\"name\": " << jstr(r->getName())
          << ", \"shape\": " << jstr(RegionOfInterest::toString(r->getShape()))
          << ", \"placement\": " << jstr(RegionOfInterest::toString(r->getPlacement()))
          << ", \"placement-feature\": " << r->getPlacementFeature()
          << ", \"scene-scale\": " << (r->getSceneScale() ? "true" : "false")
          << ", \"radius\": " << jnum(r->getRadius(), 12)
          << ", \"line-width\": " << jnum(r->getLineWidth(), 6) << ", \"line-color\": "
          << jvec(
                 {r->getLineColor().r(), r->getLineColor().g(), r->getLineColor().b(), r->getLineColor().a()},
                 6)
          << ", \"vertices\": [";
        bool firstVertex = true;
        for (const osg::Vec2d& v : r->getVertices())
            o << (firstVertex ? "" : ", ") << jvec({v.x(), v.y()}, 12), firstVertex = false;
        o << "]}";
        first = false;
    }
    o << (first ? "]" : "\n  ]") << ",\n  \"configurations\": [";
    first = true;
    for (const auto& cp : s.getConfigurations())
    {
        if (!cp.valid()) continue;
        const TransitionConfiguration& c = *cp;
        std::vector<std::string> types;
        for (osgLoA::FeatureType t : c.getFeatureTypes())
            types.push_back(osgLoA::toString(t));
        o << (first ? "\n    " : ",\n    ") << "{\"name\": " << jstr(c.getName())
          << ", \"types\": " << jsonStrings(types) << ", \"subtypes\": " << jsonStrings(c.getSubTypes())
          << ", \"lod\": " << jvec({c.getLodRange().x(), c.getLodRange().y()})
          << ", \"interest\": " << jvec({c.getInterestRange().x(), c.getInterestRange().y()})
          << ", \"style\": " << jstr(c.getStyle())
          << ", \"interpolation\": " << jstr(TransitionConfiguration::toString(c.getInterpolation()))
          << ", \"group-focus\": ";
        if (c.getHasGroupFocus())
            o << jvec({c.getGroupFocus().x(), c.getGroupFocus().y(), c.getGroupFocus().z()}, 12);
        else
            o << "null";
        o << ", \"combination\": " << jstr(TransitionConfiguration::toString(c.getCombination()))
          << ", \"metrics\": [";
        bool firstMetric = true;
        for (const auto& m : c.getMetrics())
        {
            if (!m.valid()) continue;
            o << (firstMetric ? "" : ", ") << "{\"kind\": " << jstr(SaliencyMetric::toString(m->getKind()))
              << ", \"scale\": " << jstr(SaliencyMetric::toString(m->getScale()))
              << ", \"near\": " << jnum(m->getNear(), 12) << ", \"far\": " << jnum(m->getFar(), 12)
              << ", \"weight\": " << jnum(m->getWeight(), 12) << "}";
            firstMetric = false;
        }
        o << "], \"fade-in\": " << jvec({c.getFadeIn().x(), c.getFadeIn().y()})
          << ", \"fade-out\": " << jvec({c.getFadeOut().x(), c.getFadeOut().y()}) << "}";
        first = false;
    }
    const UsageScenario::Validation v = s.validate();
    o << (first ? "]" : "\n  ]") << ",\n  \"validation\": {\"errors\": " << jsonStrings(v.errors)
      << ", \"warnings\": " << jsonStrings(v.warnings) << "}\n}\n";
    std::cout << o.str();
}

int cmdShow(const std::string& name, bool json)
{
    if (name.empty()) throw loa::UsageError("show: no SCENARIO given (see --help)");
    const Loaded l = loadScenario(name);
    if (json)
        showJson(l);
    else
        showText(l);
    return loa::kOk;
}

// ---------------------------------------------------------------- validate

int cmdValidate(const std::vector<std::string>& names)
{
    if (names.empty()) throw loa::UsageError("validate: no SCENARIO given (see --help)");
    bool failed = false;
    for (const std::string& n : names)
    {
        Loaded l;
        try
        {
            l = loadScenario(n);
        }
        catch (const std::exception& e)
        {
            std::cout << n << ": error: " << e.what() << "\n";
            failed = true;
            continue;
        }
        // A file is named as given; a library name with the file it came from.
        const std::string prefix = (l.origin == n ? n : n + " (" + l.origin + ")") + ": ";
        const UsageScenario::Validation v = l.scenario->validate();
        printValidation(std::cout, v, prefix);
        if (v.ok())
            std::cout << prefix << "ok"
                      << (v.warnings.empty() ? std::string()
                                             : " (" + std::to_string(v.warnings.size()) + " warnings)")
                      << "\n";
        failed = failed || !v.ok();
    }
    return failed ? loa::kFailure : loa::kOk;
}

// ---------------------------------------------------------------- create / set

void checkScenarioFileName(const std::string& file)
{
    if (!osgLoA::ScenarioLibrary::isScenarioFile(file))
        throw loa::UsageError("'" + file + "' is not a scenario file name (use .osgt, .osgb or .osgx)");
}

/** Validates; prints the problems; writes unless there are errors and !force. */
int validateAndWrite(const UsageScenario& s, const std::string& file, bool force)
{
    const UsageScenario::Validation v = s.validate();
    printValidation(std::cerr, v, file + ": ");
    if (!v.ok() && !force)
    {
        std::cerr << "loa-scenario: error: the scenario would not validate (" << v.errors.size()
                  << (v.errors.size() == 1 ? " error" : " errors") << "); '" << file
                  << "' left unchanged (--force writes it anyway)\n";
        return loa::kFailure;
    }
    osgLoA::ScenarioLibrary::writeFile(s, file);
    std::cout << "wrote " << file << (v.ok() ? "" : " (with errors, --force)") << "\n";
    return loa::kOk;
}

struct CreateOptions
{
    std::string file, from, description;
    bool haveDescription = false, force = false;
};

int cmdCreate(const CreateOptions& c)
{
    const std::string &file = c.file, &from = c.from, &description = c.description;
    const bool haveDescription = c.haveDescription, force = c.force;
    if (file.empty()) throw loa::UsageError("create: no FILE given (see --help)");
    checkScenarioFileName(file);
    if (osgDB::fileExists(file) && !force)
        throw std::runtime_error("'" + file + "' exists; --force overwrites it");
    osg::ref_ptr<UsageScenario> s;
    if (!from.empty())
        s = loadScenario(from).scenario;
    else
    {
        s = new UsageScenario;
        s->addConfiguration(defaultConfiguration("photorealistic").get());
    }
    s->setName(osgDB::getStrippedName(file));
    if (haveDescription) s->setDescription(description);
    return validateAndWrite(*s, file, force);
}

struct Editor
{
    UsageScenario& scenario;
    std::string configurationName; ///< --configuration
    bool haveConfiguration = false;

    TransitionConfiguration& configuration(const std::string& key)
    {
        if (!haveConfiguration)
            throw loa::UsageError(
                "'" + key + "' is a configuration key: name the configuration with --configuration NAME");
        TransitionConfiguration* c = scenario.findConfiguration(configurationName);
        if (!c)
        {
            std::string known;
            for (const auto& k : scenario.getConfigurations())
                if (k.valid()) known += (known.empty() ? "" : ", ") + k->getName();
            throw loa::UsageError("--configuration '" + configurationName +
                                  "': the scenario has no such configuration (it has: " +
                                  (known.empty() ? "none" : known) + ")");
        }
        return *c;
    }

    osgLoA::FeatureInterest& interest()
    {
        if (!scenario.getInterest())
        {
            osg::ref_ptr<osgLoA::FeatureInterest> fi = new osgLoA::FeatureInterest;
            fi->setKeepExistingInterest(true);
            scenario.setInterest(fi.get());
        }
        return *scenario.getInterest();
    }

    void setInterestKey(const std::string& key, const std::string& sub, const std::string& value)
    {
        const bool none = lower(value) == "none";
        osgLoA::FeatureType type;
        if (sub == "default")
            interest().setDefaultInterest(float(unitNumber(key, value)));
        else if (sub == "keep-existing")
            interest().setKeepExistingInterest(yesNo(key, value));
        else if (sub == "landmark-threshold")
            interest().setLandmarkThreshold(float(unitNumber(key, value)));
        else if (osgLoA::parseFeatureType(sub, type))
        {
            if (none)
                interest().removeTypeInterest(type);
            else
                interest().setTypeInterest(type, float(unitNumber(key, value)));
        }
        else if (isId(sub))
        {
            const unsigned id = featureId(key, sub);
            if (none)
                interest().removeFeatureInterest(id);
            else
                interest().setFeatureInterest(id, float(unitNumber(key, value)));
        }
        else
            throw loa::UsageError("unknown key '" + key +
                                  "' (interest.TYPE, interest.ID, interest.default, interest.keep-existing, "
                                  "interest.landmark-threshold)");
    }

    void setMetric(const std::string& key, const std::string& kindName, const std::string& value)
    {
        SaliencyMetric::Kind kind;
        if (!SaliencyMetric::parseKind(kindName, kind))
            throw loa::UsageError("unknown key '" + key + "': no metric kind '" + kindName +
                                  "' (view-distance, view-angle, region, focus, feature-interest)");
        TransitionConfiguration& c = configuration(key);
        auto& metrics = c.getMetrics();
        if (lower(value) == "none")
        {
            const auto before = metrics.size();
            metrics.erase(std::remove_if(metrics.begin(), metrics.end(),
                                         [&](const osg::ref_ptr<SaliencyMetric>& m)
                                         { return m.valid() && m->getKind() == kind; }),
                          metrics.end());
            if (metrics.size() == before)
                throw loa::UsageError(key + "=none: configuration '" + configLabel(c) + "' has no " +
                                      kindName + " metric");
            return;
        }
        double nearValue = 0.0, farValue = 0.0, weight = 1.0;
        SaliencyMetric::Scale scale = SaliencyMetric::ABSOLUTE;
        const std::vector<std::string> p = split(value, ':');
        const bool on = kind == SaliencyMetric::FEATURE_INTEREST && lower(value) == "on";
        if (!on)
        {
            if (p.size() < 2 || p.size() > 4)
                throw loa::UsageError(key + ": '" + value +
                                      "' is not NEAR:FAR, NEAR:FAR:WEIGHT or NEAR:FAR:WEIGHT:SCALE");
            nearValue = number(key, p[0]);
            farValue = number(key, p[1]);
            if (p.size() >= 3) weight = number(key, p[2]);
            if (p.size() == 4 && !SaliencyMetric::parseScale(p[3], scale))
                throw loa::UsageError(key + ": scale '" + p[3] + "' is not absolute, scene or view");
        }
        osg::ref_ptr<SaliencyMetric> metric = new SaliencyMetric(kind, nearValue, farValue, weight);
        metric->setScale(scale);
        c.addMetric(metric.get());
    }

    void set(const std::string& key, const std::string& value)
    {
        const std::string lowered = lower(value);
        // Scenario keys.
        if (key == "description")
            scenario.setDescription(value);
        else if (key == "focus")
        {
            scenario.setFocusTallestLandmark(lowered == "tallest");
            scenario.setFocusFeature(lowered == "none" || lowered == "tallest" ? 0u : featureId(key, value));
        }
        else if (key == "colors")
        {
            if (lowered != "none" && !osgLoA::ColorScheme::find(lowered))
                throw loa::UsageError("colors=" + value + ": not a colour scheme (" +
                                      osgLoA::ColorScheme::names() + ", or none)");
            scenario.setColorScheme(lowered == "none" ? std::string() : lowered);
        }
        else if (key == "interest" && !haveConfiguration)
        {
            if (lowered != "none")
                throw loa::UsageError(
                    "interest=" + value +
                    ": without --configuration only interest=none (drop every override) is a scenario key");
            scenario.setInterest(nullptr);
        }
        else if (key.compare(0, 9, "interest.") == 0)
            setInterestKey(key, key.substr(9), value);
        else if (key.compare(0, 7, "metric.") == 0)
            setMetric(key, key.substr(7), value);
        // Configuration keys.
        else if (key == "name")
        {
            TransitionConfiguration& c = configuration(key);
            if (value.empty()) throw loa::UsageError("name=: a configuration needs a name");
            if (value != c.getName() && scenario.findConfiguration(value))
                throw loa::UsageError("name=" + value + ": another configuration has that name");
            c.setName(value);
            configurationName = value;
        }
        else if (key == "style")
        {
            TransitionConfiguration& c = configuration(key);
            c.setStyle(value); // an unknown style is reported by validation
        }
        else if (key == "types")
        {
            TransitionConfiguration& c = configuration(key);
            if (lowered == "all")
                c.setAllFeatureTypes();
            else
            {
                TransitionConfiguration::FeatureTypes types;
                if (!value.empty())
                    for (const std::string& n : split(value, ','))
                    {
                        osgLoA::FeatureType t;
                        if (!osgLoA::parseFeatureType(n, t))
                            throw loa::UsageError(
                                "types: unknown feature type '" + n +
                                "' (building, street, water, green, terrain, generic, or all)");
                        types.push_back(t);
                    }
                c.setFeatureTypes(types);
            }
        }
        else if (key == "subtypes")
        {
            TransitionConfiguration& c = configuration(key);
            TransitionConfiguration::SubTypes subTypes;
            if (!value.empty() && lowered != "any")
                for (const std::string& n : split(value, ','))
                {
                    if (n.empty()) throw loa::UsageError("subtypes: '" + value + "' has an empty sub-type");
                    subTypes.push_back(n);
                }
            c.setSubTypes(subTypes);
        }
        else if (key == "lod")
            configuration(key).setLodRange(interval(key, value));
        else if (key == "interest")
            configuration(key).setInterestRange(interval(key, value));
        else if (key == "interpolation")
        {
            TransitionConfiguration& c = configuration(key);
            TransitionConfiguration::Interpolation mode;
            if (!TransitionConfiguration::parseInterpolation(value, mode))
                throw loa::UsageError("interpolation: '" + value + "' is not fragment, object or group");
            c.setInterpolation(mode);
        }
        else if (key == "group-focus")
        {
            TransitionConfiguration& c = configuration(key);
            if (lowered == "none")
                c.setHasGroupFocus(false);
            else
            {
                c.setGroupFocus(loa::parseVec3(key, value));
                c.setHasGroupFocus(true);
            }
        }
        else if (key == "combination")
        {
            TransitionConfiguration& c = configuration(key);
            TransitionConfiguration::Combination comb;
            if (!TransitionConfiguration::parseCombination(value, comb))
                throw loa::UsageError("combination: '" + value +
                                      "' is not weighted-mean, minimum or maximum");
            c.setCombination(comb);
        }
        else if (key == "fade-in")
            configuration(key).setFadeIn(interval(key, value));
        else if (key == "fade-out")
            configuration(key).setFadeOut(interval(key, value));
        else
            throw loa::UsageError("unknown key '" + key + "' (see --help)");
    }

    void addConfiguration(const std::string& name)
    {
        if (name.empty() || name[0] == '-') throw loa::UsageError("add-configuration needs a NAME");
        if (scenario.findConfiguration(name))
            throw loa::UsageError("add-configuration " + name +
                                  ": the scenario already has a configuration of that name");
        scenario.addConfiguration(defaultConfiguration(name).get());
    }

    void removeConfiguration(const std::string& name)
    {
        auto& configs = scenario.getConfigurations();
        const auto it = std::find_if(configs.begin(), configs.end(),
                                     [&](const osg::ref_ptr<TransitionConfiguration>& c)
                                     { return c.valid() && c->getName() == name; });
        if (it == configs.end())
            throw loa::UsageError("remove-configuration " + name +
                                  ": the scenario has no such configuration");
        configs.erase(it);
    }

    void addRegion(const std::string& shapeName, const std::string& points, const std::string& radiusText)
    {
        RegionOfInterest::Shape shape;
        if (!RegionOfInterest::parseShape(shapeName, shape))
            throw loa::UsageError("add-region: unknown shape '" + shapeName +
                                  "' (circles, polyline, polygon)");
        RegionOfInterest::Vertices vertices;
        std::string text = points;
        for (char& c : text)
            if (c == ';') c = ' ';
        std::istringstream in(text);
        for (std::string p; in >> p;)
        {
            const std::vector<std::string> xy = split(p, ',');
            if (xy.size() != 2) throw loa::UsageError("add-region: vertex '" + p + "' is not X,Y");
            vertices.emplace_back(number("add-region vertex", xy[0]), number("add-region vertex", xy[1]));
        }
        if (vertices.empty()) throw loa::UsageError("add-region: no vertex given (\"X,Y;X,Y;...\")");
        const double radius = radiusText.empty() ? 0.0 : number("add-region radius", radiusText);
        if (radius < 0.0) throw loa::UsageError("add-region: radius " + radiusText + " is negative");
        osg::ref_ptr<RegionOfInterest> r = new RegionOfInterest(shape, vertices, radius);
        r->setName("region-" + std::to_string(scenario.getRegions().size() + 1));
        scenario.addRegion(r.get());
    }

    void setRegionLine(const std::string& name, const std::string& widthText, const std::string& colorText)
    {
        const double width = number("region-line width", widthText);
        if (!(width >= 0.0 && width <= RegionOfInterest::kMaxLineWidth))
            throw loa::UsageError("region-line: width " + widthText + " is outside [0, " +
                                  std::to_string(int(RegionOfInterest::kMaxLineWidth)) + "] pixels");
        osg::Vec4f color = RegionOfInterest::defaultLineColor();
        if (!colorText.empty())
        {
            const std::vector<std::string> c = split(colorText, ',');
            if (c.size() != 3 && c.size() != 4)
                throw loa::UsageError("region-line: colour '" + colorText + "' is not R,G,B or R,G,B,A");
            for (std::size_t k = 0; k < c.size(); ++k)
            {
                const double v = number("region-line colour", c[k]);
                if (!(v >= 0.0 && v <= 1.0))
                    throw loa::UsageError("region-line: colour component " + c[k] + " is outside [0, 1]");
                color[int(k)] = float(v);
            }
        }
        unsigned changed = 0;
        for (const auto& r : scenario.getRegions())
            if (r.valid() && (name == "all" || r->getName() == name))
            {
                r->setLineWidth(width);
                if (!colorText.empty()) r->setLineColor(color);
                ++changed;
            }
        if (changed == 0)
            throw loa::UsageError("region-line: the scenario has no region named '" + name + "'" +
                                  (scenario.getRegions().empty() ? " (it has no region)" : ""));
    }
};

struct SetOptions
{
    std::vector<std::string> words; ///< FILE then the edits
    std::string configurationName, model;
    bool force = false, haveConfiguration = false;
};

int cmdSet(const SetOptions& o)
{
    const std::string file = o.words.empty() ? std::string() : o.words.front();
    const std::vector<std::string> words(o.words.empty() ? o.words.begin() : o.words.begin() + 1,
                                         o.words.end());
    const std::string &configurationName = o.configurationName, &model = o.model;
    const bool force = o.force, haveConfiguration = o.haveConfiguration;
    if (file.empty()) throw loa::UsageError("set: no FILE given (see --help)");
    checkScenarioFileName(file);
    if (words.empty())
        throw loa::UsageError("set: no edit given (KEY=VALUE, add-configuration, ...; see --help)");

    // Unknown edit words are usage errors before the file is read.
    osg::ref_ptr<UsageScenario> scenario = osgLoA::ScenarioLibrary::readFile(file);
    Editor ed{*scenario, configurationName, haveConfiguration};
    for (std::size_t i = 0; i < words.size(); ++i)
    {
        const std::string& w = words[i];
        const auto need = [&](const char* what) -> const std::string&
        {
            if (i + 1 >= words.size()) throw loa::UsageError(w + " needs " + what);
            return words[++i];
        };
        const std::size_t eq = w.find('=');
        if (eq != std::string::npos)
        {
            if (eq == 0) throw loa::UsageError("'" + w + "' has no key before '='");
            ed.set(w.substr(0, eq), w.substr(eq + 1));
        }
        else if (w == "add-configuration")
            ed.addConfiguration(need("a NAME"));
        else if (w == "remove-configuration")
            ed.removeConfiguration(need("a NAME"));
        else if (w == "add-regions")
        {
            // A user's routes and regions from a GeoJSON (or other OGR) file, transformed to
            // the model's frame when it is geo-referenced.
            const std::string path = need("a FILE (GeoJSON, ...)");
            double radius = 0.0;
            if (i + 1 < words.size() && toNumber(words[i + 1], radius))
                ++i;
            else
                radius = 0.0;
            osg::ref_ptr<osg::Node> frame = model.empty() ? nullptr : loa::loadModel(model);
            std::vector<osg::ref_ptr<RegionOfInterest>> regions;
            try
            {
                regions = osgLoA::RegionFile::read(path, frame.get(), radius);
            }
            catch (const std::invalid_argument& e)
            {
                throw loa::UsageError(e.what());
            }
            for (const auto& r : regions)
                scenario->addRegion(r.get());
            std::cout << "added " << regions.size() << " region(s) from " << path
                      << (frame.valid() ? " in the frame of " + model : std::string(" in scene coordinates"))
                      << "\n";
        }
        else if (w == "add-region")
        {
            const std::string shape = need("a SHAPE and vertices");
            const std::string points = need("vertices \"X,Y;X,Y;...\"");
            std::string radius;
            double ignored = 0.0;
            if (i + 1 < words.size() && toNumber(words[i + 1], ignored)) radius = words[++i];
            ed.addRegion(shape, points, radius);
        }
        else if (w == "clear-regions")
            scenario->getRegions().clear();
        else if (w == "region-line")
        {
            const std::string name = need("a region NAME (or all), a WIDTH");
            const std::string widthText = need("a WIDTH in pixels");
            std::string colorText;
            if (i + 1 < words.size() && words[i + 1].find(',') != std::string::npos) colorText = words[++i];
            ed.setRegionLine(name, widthText, colorText);
        }
        else
            throw loa::UsageError("unknown edit '" + w +
                                  "' (KEY=VALUE, add-configuration, remove-configuration, "
                                  "add-region, clear-regions, region-line; see --help)");
    }
    scenario->dirty();
    return validateAndWrite(*scenario, file, force);
}

// ---------------------------------------------------------------- explain

struct ExplainOptions
{
    std::vector<std::string> scenarioAndModels; ///< SCENARIO then MODEL...
    std::string scenario, model, readerOptions, image;
    std::vector<std::string> models;
    bool json = false, all = false;
    unsigned features = 25;
    int width = loa::kDefaultWidth, height = loa::kDefaultHeight;
    loa::CameraChoice camera;
    loa::RulesChoice rules;
};

void checkExplain(ExplainOptions& o)
{
    loa::checkCameraOptions(o.camera);
    if (o.scenarioAndModels.empty()) throw loa::UsageError("explain: no SCENARIO given (see --help)");
    o.scenario = o.scenarioAndModels.front();
    o.models.assign(o.scenarioAndModels.begin() + 1, o.scenarioAndModels.end());
    if (o.models.empty()) o.models.push_back("demo.loacity");
    o.model = loa::modelLabel(o.models);
    if (!o.image.empty() && osgDB::getLowerCaseFileExtension(o.image) != "png")
        throw loa::UsageError("--image '" + o.image + "' must name a .png file");
}

int cmdExplain(const ExplainOptions& o)
{
    const Loaded l = loadScenario(o.scenario);
    const UsageScenario::Validation v = l.scenario->validate();
    if (!v.ok())
    {
        std::string msg = "scenario '" + o.scenario + "' does not validate: " + v.errors.front();
        if (v.errors.size() > 1)
            msg += " (and " + std::to_string(v.errors.size() - 1) + " more; see validate)";
        throw std::runtime_error(msg);
    }

    osg::ref_ptr<osg::Node> scene = loa::loadModels(o.models, o.readerOptions);
    const osgLoA::FeatureClassifier::Report report =
        osgLoA::FeatureClassifier(o.rules.assemble().get()).classify(*scene);

    osg::ref_ptr<osgLoA::LoANode> node = new osgLoA::LoANode;
    node->addChild(scene.get());
    node->setScenario(l.scenario.get());
    try
    {
        node->bind();
    }
    catch (const std::invalid_argument& e)
    {
        throw std::runtime_error(e.what()); // a scenario problem, not a usage error
    }
    const double aspect = double(o.width) / o.height;
    const osgLoA::CameraPose pose = loa::cameraPose(o.camera, *scene, aspect);
    const osg::Vec3d eye = pose.eye;

    osgLoA::ScenarioEvaluator& ev = *node->getEvaluator();
    const auto& states = ev.features();
    const auto& entries = node->getFeatureIndex().entries();
    std::vector<unsigned char> visible(states.size(), 1);
    if (!o.all)
    {
        // The view frustum without near and far planes (OSG computes those per frame).
        osg::Matrixd view, projection;
        view.makeLookAt(pose.eye, pose.center, pose.up);
        projection.makePerspective(pose.fovy, aspect, 1.0, 10000.0);
        osg::Polytope frustum;
        frustum.setToUnitFrustum(false, false);
        frustum.transformProvidingInverse(view * projection);
        for (std::size_t i = 0; i < states.size(); ++i)
        {
            const osg::BoundingBoxd& b = states[i].bound;
            visible[i] =
                b.valid() && frustum.contains(osg::BoundingBox(osg::Vec3(b._min), osg::Vec3(b._max))) ? 1 : 0;
        }
    }
    node->evaluate(eye); // fits view-scaled metrics to this eye (ScenarioFitting)
    ev.evaluate(eye, visible.data());
    const UsageScenario& fitted = *node->getFitting().getScenario();
    // Validation cannot know the model: a focus id the model lacks leaves the focus metric
    // without a focus (interest 0 everywhere).
    std::string focusWarning;
    if (fitted.getFocusFeature() != 0 && ev.findFeature(fitted.getFocusFeature()) < 0)
        focusWarning = "focus feature " + std::to_string(fitted.getFocusFeature()) +
                       " is not in the model: focus metrics see no focus object (interest 0)";
    if (!focusWarning.empty()) std::cerr << "loa-scenario: warning: " << focusWarning << "\n";

    struct Row
    {
        std::size_t state;
        double distance;
    };
    std::vector<Row> rows;
    std::set<const osgLoA::Feature*> listedFeatures; // one Feature on several nodes: listed once
    for (std::size_t i = 0; i < states.size(); ++i)
        if (states[i].visible && states[i].bound.valid() &&
            listedFeatures.insert(entries[states[i].entry].feature.get()).second)
            rows.push_back({i, (states[i].bound.center() - eye).length()});
    std::stable_sort(rows.begin(), rows.end(),
                     [](const Row& a, const Row& b) { return a.distance < b.distance; });
    const std::size_t listed = o.features == 0 ? rows.size() : std::min<std::size_t>(rows.size(), o.features);

    const auto& configs = l.scenario->getConfigurations();
    const osgLoA::ScenarioEvaluator::Statistics& st = ev.getStatistics();
    const std::string cameraText =
        o.camera.name.empty() && !o.camera.haveEye ? std::string("framing the model") : o.camera.describe();
    if (o.json)
    {
        std::ostringstream out;
        out << "{\n  \"scenario\": " << jstr(l.scenario->getName()) << ",\n  \"origin\": " << jstr(l.origin)
            << ",\n  \"model\": " << jstr(o.model) << ",\n  \"camera\": " << jstr(cameraText)
            << ",\n  \"eye\": " << jvec({eye.x(), eye.y(), eye.z()}, 12)
            << ",\n  \"center\": " << jvec({pose.center.x(), pose.center.y(), pose.center.z()}, 12)
            << ",\n  \"frustum\": " << (o.all ? "false" : "true")
            << ",\n  \"fitting\": " << jsonStrings(node->getFitting().getNotes())
            << ",\n  \"scene\": {\"centre\": "
            << jvec({node->getFitting().getSceneCentre().x(), node->getFitting().getSceneCentre().y(),
                     node->getFitting().getSceneCentre().z()},
                    12)
            << ", \"size\": " << jnum(node->getFitting().getSceneSize(), 12)
            << ", \"view-distance\": " << jnum((eye - node->getFitting().getSceneCentre()).length(), 12)
            << "}"
            << ",\n  \"warnings\": "
            << jsonStrings(focusWarning.empty() ? std::vector<std::string>()
                                                : std::vector<std::string>{focusWarning})
            << ",\n  \"features\": [";
        for (std::size_t r = 0; r < listed; ++r)
        {
            const auto& s = states[rows[r].state];
            const osgLoA::Feature& f = *entries[s.entry].feature;
            const osg::Vec3d c = s.bound.center();
            out << (r ? ",\n    " : "\n    ") << "{\"id\": " << f.getId()
                << ", \"type\": " << jstr(osgLoA::toString(f.getType()))
                << ", \"subtype\": " << jstr(f.getSubType())
                << ", \"landmark\": " << (f.getLandmark() ? "true" : "false")
                << ", \"static-interest\": " << jnum(s.staticInterest)
                << ", \"distance\": " << jnum(rows[r].distance, 9)
                << ", \"center\": " << jvec({c.x(), c.y(), c.z()}, 9) << ", \"matches\": [";
            const auto* m = ev.matchesOf(s);
            bool drawn = false;
            for (unsigned k = 0; k < s.numMatches; ++k)
            {
                const TransitionConfiguration& tc = *configs[m[k].configuration];
                drawn = drawn || m[k].mayContribute;
                out << (k ? ", " : "") << "{\"configuration\": " << jstr(tc.getName())
                    << ", \"index\": " << m[k].configuration << ", \"style\": " << jstr(tc.getStyle())
                    << ", \"mode\": " << jstr(TransitionConfiguration::toString(tc.getInterpolation()))
                    << ", \"at-box-centre\": " << (m[k].fragment ? "true" : "false")
                    << ", \"point\": " << jvec({m[k].point.x(), m[k].point.y(), m[k].point.z()}, 9)
                    << ", \"interest\": " << jnum(m[k].interest)
                    << ", \"raw-weight\": " << jnum(m[k].rawWeight) << ", \"weight\": " << jnum(m[k].weight)
                    << ", \"may-contribute\": " << (m[k].mayContribute ? "true" : "false") << "}";
            }
            out << "], \"drawn\": " << (drawn ? "true" : "false") << "}";
        }
        out << (listed ? "\n  ]" : "]") << ",\n  \"statistics\": {\"features\": " << states.size()
            << ", \"visible\": " << st.visibleFeatures << ", \"matches\": " << st.matches
            << ", \"contributing\": " << st.contributing << ", \"undrawn\": " << st.undrawnFeatures
            << ", \"listed\": " << listed << "}\n}\n";
        std::cout << out.str();
    }
    else
    {
        std::cout << "scenario '" << l.scenario->getName() << "' (" << l.origin << ") on " << o.model << "\n"
                  << "classifier: " << report.summary() << "\n";
        for (const std::string& note : node->getFitting().getNotes())
            std::cout << "fitted: " << note << "\n";
        std::cout << cameraText << ": eye " << num(eye.x()) << "," << num(eye.y()) << "," << num(eye.z())
                  << "\n"
                  << rows.size() << " of " << states.size() << " features "
                  << (o.all ? "(every feature, --all)" : "in the view frustum") << "; the " << listed
                  << " nearest:\n";
        bool anyFragment = false;
        int column = 0; // width of the "configuration (style)" column
        for (const auto& c : configs)
            column = std::max(
                column, int(std::min<std::size_t>(200, configLabel(*c).size() + c->getStyle().size() + 3)));
        for (std::size_t r = 0; r < listed; ++r)
        {
            const auto& s = states[rows[r].state];
            const osgLoA::Feature& f = *entries[s.entry].feature;
            std::cout << "feature " << f.getId() << " " << osgLoA::toString(f.getType())
                      << (f.getSubType().empty() ? "" : " (" + f.getSubType() + ")")
                      << (f.getLandmark() ? " landmark" : "") << ": distance " << num(rows[r].distance, 5)
                      << ", static interest " << num(s.staticInterest, 3) << "\n";
            if (s.numMatches == 0) std::cout << "    no matching configuration: not drawn\n";
            const auto* m = ev.matchesOf(s);
            bool drawn = false;
            for (unsigned k = 0; k < s.numMatches; ++k)
            {
                const TransitionConfiguration& tc = *configs[m[k].configuration];
                drawn = drawn || m[k].mayContribute;
                anyFragment = anyFragment || m[k].fragment;
                char line[512];
                std::snprintf(line, sizeof line, "    %-9s %-*s  interest %5.3f  raw %5.3f  weight %5.3f%s\n",
                              (std::string(TransitionConfiguration::toString(tc.getInterpolation())) +
                               (m[k].fragment ? "*" : ""))
                                  .c_str(),
                              column, (configLabel(tc) + " (" + tc.getStyle() + ")").substr(0, 200).c_str(),
                              double(m[k].interest), double(m[k].rawWeight), double(m[k].weight),
                              m[k].fragment && m[k].mayContribute && m[k].rawWeight == 0.0f
                                  ? "  (contributes elsewhere on the feature)"
                                  : "");
                std::cout << line;
            }
            if (s.numMatches > 0 && !drawn) std::cout << "    no configuration contributes: not drawn\n";
        }
        if (anyFragment)
            std::cout
                << "* fragment interpolation: evaluated per fragment in the shader; the values shown are "
                   "at the centre of the feature's box\n";
        std::cout << "statistics: " << states.size() << " features, " << st.visibleFeatures << " visible, "
                  << st.matches << " matches, " << st.contributing << " contributing, " << st.undrawnFeatures
                  << " visible but not drawn\n";
    }
    if (!o.image.empty())
    {
        loa::CameraChoice camera = o.camera;
        writeInterestImage(*node, camera, o.width, o.height, o.image);
        if (!o.json) std::cout << "wrote " << o.image << "\n";
    }
    return loa::kOk;
}

int run(int argc, char** argv)
{
    loa::CommandLine cl("loa-scenario", "loa-scenario COMMAND [arguments]", kDescription);
    CLI::App& app = cl.app();
    app.require_subcommand(1, 1);

    bool listJson = false;
    CLI::App* list =
        cl.command("list", "list [--json]", "the scenario names of the libraries", kListDescription);
    list->add_flag("--json", listJson, "one JSON array instead of text");

    std::string showName;
    bool showJsonFlag = false;
    CLI::App* show = cl.command("show", "show SCENARIO [--json]", "a scenario in full", kShowDescription);
    show->add_option("SCENARIO", showName, "a library name or a scenario file");
    show->add_flag("--json", showJsonFlag, "one JSON object instead of text");

    std::vector<std::string> validateNames;
    CLI::App* validate = cl.command("validate", "validate SCENARIO...",
                                    "check scenarios, one line per problem", kValidateDescription);
    validate->add_option("SCENARIO", validateNames, "library names or scenario files");

    CreateOptions create;
    CLI::App* createCommand =
        cl.command("create", "create FILE [--from SCENARIO] [--description TEXT] [--force]",
                   "write a new scenario file", kCreateDescription);
    createCommand->add_option("FILE", create.file, "the scenario file to write (.osgt, .osgb or .osgx)");
    createCommand->add_option("--from", create.from, "copy this scenario (a library name or a file)")
        ->type_name("SCENARIO");
    createCommand
        ->add_option_function<std::string>(
            "--description",
            [&create](const std::string& d) { create.description = d, create.haveDescription = true; },
            "the scenario's description")
        ->type_name("TEXT");
    createCommand->add_flag("--force", create.force, "overwrite an existing FILE");

    SetOptions set;
    CLI::App* setCommand =
        cl.command("set", "set FILE EDIT... [--configuration NAME] [--model MODEL] [--force]",
                   "edit a scenario file", kSetDescription);
    setCommand->add_option("FILE_EDIT", set.words, "the scenario file, then the edits in order");
    setCommand
        ->add_option_function<std::string>(
            "--configuration",
            [&set](const std::string& n) { set.configurationName = n, set.haveConfiguration = true; },
            "the configuration the configuration keys edit")
        ->type_name("NAME");
    setCommand
        ->add_option("--model", set.model,
                     "the model add-regions takes its geo-reference from (a CityJSON or OSM model): the "
                     "file's longitude/latitude are transformed into its frame")
        ->type_name("MODEL");
    setCommand->add_flag("--force", set.force, "write the scenario even when it does not validate");

    ExplainOptions explain;
    CLI::App* explainCommand =
        cl.command("explain", "explain SCENARIO [MODEL...] [options]",
                   "each feature's interest and blend weights at a camera", kExplainDescription);
    explainCommand
        ->add_option("SCENARIO_MODEL", explain.scenarioAndModels,
                     "the scenario (a library name or a file), then the models (default: the demo "
                     "city, demo.loacity; several are one scene)")
        ->group(loa::kGroupModel);
    loa::addReaderOptions(*explainCommand, explain.readerOptions);
    loa::addRules(*explainCommand, explain.rules);
    loa::addCamera(*explainCommand, explain.camera);
    loa::addSize(*explainCommand, explain.width, explain.height, "the camera's viewport and the --image");
    explainCommand
        ->add_option(
            "--image", explain.image,
            "also render the interest debug view (paper 004 Figure 5: black = interest 1, high detail; "
            "white = interest 0, abstraction)")
        ->type_name("FILE.png")
        ->group(loa::kGroupOutput);
    explainCommand
        ->add_option_function<std::string>(
            "--features",
            [&explain](const std::string& t)
            { explain.features = loa::parseCount("--features", t, 100000000u); },
            "list the N nearest features (default 25; 0: all)")
        ->type_name("N");
    explainCommand->add_flag("--all", explain.all,
                             "evaluate every feature, not only those in the view frustum");
    explainCommand->add_flag("--json", explain.json, "one JSON object instead of text");

    cl.footer(kFooter);
    cl.parse(argc, argv);
    if (list->parsed()) return cmdList(listJson);
    if (show->parsed()) return cmdShow(showName, showJsonFlag);
    if (validate->parsed()) return cmdValidate(validateNames);
    if (createCommand->parsed()) return cmdCreate(create);
    if (setCommand->parsed()) return cmdSet(set);
    checkExplain(explain);
    return cmdExplain(explain);
}
} // namespace

int main(int argc, char** argv)
{
    return loa::runTool("loa-scenario", [&] { return run(argc, argv); });
}
