// ScenarioLibrary: the paper's usage scenarios in code, library directories, scenario files.
#include <osgLoA/transitions/ScenarioLibrary>

#include <osgLoA/transitions/LoANode>
#include <osgLoA/util/AtomicFile>
#include <osgLoA/util/BoundedObjectReader>

#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>
#include <osgDB/Registry>
#include <osgDB/WriteFile>

#include "ScenarioTextParser.h"

#include <osgLoA/util/ModelValidation>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

#include <dlfcn.h>
#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

#ifndef OSGLOA_SCENARIO_SOURCE_DIR
#define OSGLOA_SCENARIO_SOURCE_DIR ""
#endif
#ifndef OSGLOA_SCENARIO_INSTALL_DIR
#define OSGLOA_SCENARIO_INSTALL_DIR ""
#endif
#ifndef OSGLOA_LIBDIR_TO_BINDIR
#define OSGLOA_LIBDIR_TO_BINDIR "../bin"
#endif
#ifndef OSGLOA_BUILD_BINDIR
#define OSGLOA_BUILD_BINDIR ""
#endif

namespace osgLoA
{

namespace
{
const char* const kExtensions[] = {"osgt", "osgb", "osgx"};

// Large features (terrain, streets, water, green spaces) change along their extent, so they
// blend per fragment; buildings blend as whole objects.
const TransitionConfiguration::FeatureTypes kAreaTypes = {FeatureType::Street, FeatureType::Water,
                                                          FeatureType::Green, FeatureType::Terrain};
/** §3.2.2's deformation for map-like scenarios: landmarks morph by the default driver,
 *  non-landmark buildings shrink and sink by their weight of map-like styles. */
osg::ref_ptr<LandmarkDeformation> mapDeformation()
{
    osg::ref_ptr<LandmarkDeformation> d = new LandmarkDeformation;
    d->setSinkingEnabled(true);
    d->setSinkFollowsMapStyles(true);
    return d;
}

// The route drawn on the ground in the route and navigation scenarios (RouteLine), pixels.
constexpr double kRouteLineWidth = 6.0;
const TransitionConfiguration::FeatureTypes kObjectTypes = {FeatureType::Building, FeatureType::Generic};

osg::ref_ptr<TransitionConfiguration> config(const std::string& name, const std::string& style,
                                             const TransitionConfiguration::FeatureTypes& types,
                                             TransitionConfiguration::Interpolation mode,
                                             const BlendFunction& blend)
{
    osg::ref_ptr<TransitionConfiguration> c = new TransitionConfiguration;
    c->setName(name);
    c->setStyle(style);
    c->setFeatureTypes(types);
    c->setInterpolation(mode);
    c->setBlendFunction(blend);
    return c;
}

// Three styles over one interest axis, for both area (fragment) and object features:
// photorealistic for high interest, abstract in the middle, a third style for low interest.
void addThreeLevels(UsageScenario& s, const std::vector<osg::ref_ptr<SaliencyMetric>>& metrics,
                    const std::string& lowStyle, float lowMid0, float lowMid1, float midHigh0, float midHigh1)
{
    struct Level
    {
        const char* style;
        BlendFunction blend;
    };
    const Level levels[] = {{"photorealistic", BlendFunction(midHigh0, midHigh1, 1.0f, 1.0f)},
                            {"abstract", BlendFunction(lowMid0, lowMid1, midHigh0, midHigh1)},
                            {lowStyle.c_str(), BlendFunction(0.0f, 0.0f, lowMid0, lowMid1)}};
    for (const Level& l : levels)
        for (bool area : {false, true})
        {
            auto c =
                config(std::string(l.style) + (area ? "-areas" : "-objects"), l.style,
                       area ? kAreaTypes : kObjectTypes,
                       area ? TransitionConfiguration::FRAGMENT : TransitionConfiguration::OBJECT, l.blend);
            for (const auto& m : metrics)
                c->addMetric(osg::clone(m.get(), osg::CopyOp::DEEP_COPY_ALL));
            s.addConfiguration(c.get());
        }
}

// Two styles with one smooth transition between them, for area and object features.
void addTwoLevels(UsageScenario& s, const std::vector<osg::ref_ptr<SaliencyMetric>>& metrics,
                  const std::string& highStyle, const std::string& lowStyle, float t0, float t1,
                  const osg::Vec2f& interestScope = osg::Vec2f(0.0f, 1.0f))
{
    for (bool high : {true, false})
        for (bool area : {false, true})
        {
            const std::string& style = high ? highStyle : lowStyle;
            auto c = config(style + (area ? "-areas" : "-objects"), style, area ? kAreaTypes : kObjectTypes,
                            area ? TransitionConfiguration::FRAGMENT : TransitionConfiguration::OBJECT,
                            high ? BlendFunction(t0, t1, 1.0f, 1.0f) : BlendFunction(0.0f, 0.0f, t0, t1));
            c->setInterestRange(interestScope);
            for (const auto& m : metrics)
                c->addMetric(osg::clone(m.get(), osg::CopyOp::DEEP_COPY_ALL));
            s.addConfiguration(c.get());
        }
}

// A detailed level (photorealistic) over a map in which each feature type has its cartographic
// device of paper 004 §3.2.3 (relief, waterlining, signatures, streets; cartographic for buildings
// and the rest): the scenarios that read the context as a map.
void addDetailOverMap(
    UsageScenario& s, const std::vector<osg::ref_ptr<SaliencyMetric>>& metrics, const BlendFunction& detailed,
    const BlendFunction& map, const osg::Vec2f& interestScope,
    TransitionConfiguration::Combination combination = TransitionConfiguration::WEIGHTED_MEAN)
{
    struct Part
    {
        const char* name;
        const char* style;
        TransitionConfiguration::FeatureTypes types;
        TransitionConfiguration::Interpolation mode;
        const BlendFunction& blend;
    };
    const Part parts[] = {
        {"photorealistic-objects", "photorealistic", kObjectTypes, TransitionConfiguration::OBJECT, detailed},
        {"photorealistic-areas", "photorealistic", kAreaTypes, TransitionConfiguration::FRAGMENT, detailed},
        {"cartographic-objects", "cartographic", kObjectTypes, TransitionConfiguration::OBJECT, map},
        {"relief-terrain", "relief", {FeatureType::Terrain}, TransitionConfiguration::FRAGMENT, map},
        {"waterlining-water", "waterlining", {FeatureType::Water}, TransitionConfiguration::FRAGMENT, map},
        {"signatures-green", "signatures", {FeatureType::Green}, TransitionConfiguration::FRAGMENT, map},
        {"streets-streets", "streets", {FeatureType::Street}, TransitionConfiguration::FRAGMENT, map}};
    for (const Part& p : parts)
    {
        auto c = config(p.name, p.style, p.types, p.mode, p.blend);
        c->setInterestRange(interestScope);
        c->setCombination(combination);
        for (const auto& m : metrics)
            c->addMetric(osg::clone(m.get(), osg::CopyOp::DEEP_COPY_ALL));
        s.addConfiguration(c.get());
    }
}

// Landmarks (static interest >= 0.8) photorealistic whatever the other configurations do.
void addLandmarksInDetail(UsageScenario& s)
{
    TransitionConfiguration::FeatureTypes allTypes(std::begin(kFeatureTypes), std::end(kFeatureTypes));
    auto landmarks = config("landmarks", "photorealistic", allTypes, TransitionConfiguration::OBJECT,
                            BlendFunction(0.0f, 0.0f, 1.0f, 1.0f));
    landmarks->setInterestRange(osg::Vec2f(0.8f, 1.0f));
    landmarks->addMetric(new SaliencyMetric(SaliencyMetric::FEATURE_INTEREST, 0.0, 0.0));
    s.addConfiguration(landmarks.get());
}

osg::ref_ptr<UsageScenario> makeScenario(const std::string& name, const std::string& description)
{
    osg::ref_ptr<UsageScenario> s = new UsageScenario;
    s->setName(name);
    s->setDescription(description);
    return s;
}
} // namespace

std::vector<std::string> ScenarioLibrary::builtinNames()
{
    return {"manual",       "distance",  "view-angle", "route",
            "circular-roi", "blueprint", "landscape",  "navigation"};
}

void ScenarioLibrary::appendTwoLevels(UsageScenario& scenario, const SaliencyMetric& metric,
                                      const std::string& highStyle, const std::string& lowStyle)
{
    osg::ref_ptr<SaliencyMetric> m = osg::clone(&metric, osg::CopyOp::DEEP_COPY_ALL);
    addTwoLevels(scenario, {m}, highStyle, lowStyle, 0.0f, 1.0f);
}

osg::ref_ptr<UsageScenario> ScenarioLibrary::createHomogeneous(const std::string& style)
{
    osg::ref_ptr<UsageScenario> s = new UsageScenario;
    s->setName("homogeneous-" + style);
    osg::ref_ptr<TransitionConfiguration> c = new TransitionConfiguration;
    c->setName(style);
    c->setStyle(style);
    c->setAllFeatureTypes();
    c->setInterpolation(TransitionConfiguration::OBJECT);
    c->setBlendFunction(BlendFunction(0.0f, 0.0f, 1.0f, 1.0f));
    c->addMetric(new SaliencyMetric(SaliencyMetric::FEATURE_INTEREST, 0.0, 0.0));
    s->addConfiguration(c.get());
    return s;
}

osg::ref_ptr<UsageScenario> ScenarioLibrary::createBuiltin(const std::string& name)
{
    typedef SaliencyMetric M;
    if (name == "manual")
    {
        // Figure 9A: the user picks each feature type's LoA through its interest; hard steps.
        auto s = makeScenario(name, "Manual LoA selection (paper 004 Figure 9A): each feature type's LoA is "
                                    "chosen by hand through its interest value; hard transitions.");
        osg::ref_ptr<FeatureInterest> fi = new FeatureInterest;
        fi->setTypeInterest(FeatureType::Building, 0.5f);
        fi->setTypeInterest(FeatureType::Street, 0.2f);
        fi->setTypeInterest(FeatureType::Water, 0.2f);
        fi->setTypeInterest(FeatureType::Green, 1.0f);
        fi->setTypeInterest(FeatureType::Terrain, 1.0f);
        fi->setTypeInterest(FeatureType::Generic, 0.5f);
        s->setInterest(fi.get());
        addThreeLevels(*s, {new M(M::FEATURE_INTEREST, 0.0, 0.0)}, "cartographic", 0.33f, 0.33f, 0.66f,
                       0.66f);
        return s;
    }
    if (name == "distance")
    {
        // Figure 9B: detail near the camera, abstraction far away.
        auto s =
            makeScenario(name, "View-distance transitions (paper 004 Figure 9B): photorealistic up to 0.56 D "
                               "from the camera, abstract from 0.75 D to 1 D, cartographic beyond 1.19 D, "
                               "smooth in between, where D is the camera's distance to the centre of the "
                               "scene (so the bands fit any scene and follow the camera; on the demo city's "
                               "oblique view D = 590 m: 330 m, 440-590 m, 700 m).");
        osg::ref_ptr<M> distance = new M(M::VIEW_DISTANCE, 0.25, 1.5);
        distance->setScale(M::VIEW);
        addThreeLevels(*s, {distance}, "cartographic", 0.25f, 0.4f, 0.6f, 0.75f);
        return s;
    }
    if (name == "view-angle")
    {
        // §4.1: detailed and map-like views blended by the vertical view angle, weighted with
        // the view distance so that a near bird's-eye view is not drawn in full detail;
        // landmarks (static interest >= 0.8) stay photorealistic.
        auto s = makeScenario(
            name, "Map-like transitions by vertical view angle (paper 004 §4.1): low views "
                  "detailed, bird's-eye views a map (relief, waterlining, green signatures, streets "
                  "with casings and their names): the interest is the lesser of the view angle's "
                  "(25-60 degrees) and the view distance's (0.35-2 times the camera's distance to "
                  "the scene centre), so a street view is detailed near the camera and a map in the "
                  "distance; landmarks keep their detail and, in "
                  "map-like views, grow, turn their best view to the viewer and "
                  "flatten, while the other buildings shrink and sink below the ground where "
                  "they are drawn as a map (§3.2.2, Figure 1).");
        osg::ref_ptr<M> distance = new M(M::VIEW_DISTANCE, 0.35, 2.0, 1.0);
        distance->setScale(M::VIEW);
        // The map: each feature type in its cartographic device (streets with their names).
        // Detailed where the view is low and near (the minimum of the two interests): from the
        // street the foreground is detailed and the distance a map, from above all is a map.
        addDetailOverMap(*s, {new M(M::VIEW_ANGLE, 25.0, 60.0, 1.0), distance},
                         BlendFunction(0.4f, 0.6f, 1.0f, 1.0f), BlendFunction(0.0f, 0.0f, 0.4f, 0.6f),
                         osg::Vec2f(0.0f, 0.8f), TransitionConfiguration::MINIMUM);
        addLandmarksInDetail(*s);
        // §3.2.2: the defaults morph landmarks over the same view angles (25-60 degrees) as
        // the transitions above; non-landmark buildings shrink and sink where the scenario
        // draws them as a map (Figure 1).
        s->setLandmarkDeformation(mapDeformation().get());
        return s;
    }
    if (name == "route")
    {
        // Figure 9C: features along a route in detail, the context cartographic.
        auto s = makeScenario(
            name, "Route highlighting (paper 004 Figure 9C): the route runs along the scene's "
                  "streets (the longest route through their network where they have centre lines, "
                  "as OSM ways do, else their longest chain of touching features); photorealistic within "
                  "0.04 S of its centre "
                  "line, fading smoothly to cartographic 0.15 S away, where S is the scene's "
                  "size (half its horizontal diagonal; 1090 m on the demo city: 44 m, 164 m). The route "
                  "itself is drawn on the ground as a 6 px blue line with a casing.");
        osg::ref_ptr<RegionOfInterest> route = new RegionOfInterest(RegionOfInterest::POLYLINE, {}, 0.01);
        route->setName("route");
        route->setPlacement(RegionOfInterest::LONGEST_STREET);
        route->setSceneScale(true);
        route->setLineWidth(kRouteLineWidth); // the route on the map (RouteLine)
        s->addRegion(route.get());
        osg::ref_ptr<M> region = new M(M::REGION, 0.03, 0.14);
        region->setScale(M::SCENE);
        addTwoLevels(*s, {region}, "photorealistic", "cartographic", 0.0f, 1.0f);
        return s;
    }
    if (name == "circular-roi")
    {
        // Figure 9D-F: a circular region of interest in detail, abstraction around it.
        auto s =
            makeScenario(name, "Circular region of interest (paper 004 Figure 9D-F): photorealistic "
                               "within 0.14 S of the scene's centre, abstract beyond 0.23 S, where S is "
                               "the scene's size (half its horizontal diagonal; 1090 m on the demo city: "
                               "150 m, 250 m).");
        osg::ref_ptr<RegionOfInterest> roi =
            new RegionOfInterest(RegionOfInterest::CIRCLES, {{0.0, 0.0}}, 0.14);
        roi->setName("centre");
        roi->setPlacement(RegionOfInterest::SCENE_CENTRE);
        roi->setSceneScale(true);
        s->addRegion(roi.get());
        osg::ref_ptr<M> region = new M(M::REGION, 0.0, 0.09);
        region->setScale(M::SCENE);
        addTwoLevels(*s, {region}, "photorealistic", "abstract", 0.0f, 1.0f);
        return s;
    }
    if (name == "blueprint")
    {
        // Figure 9E: the focus object drawn as a blueprint, the context in detail.
        auto s = makeScenario(
            name, "Blueprint focus (paper 004 Figure 9E): the focus object (the scene's tallest landmark, "
                  "else its tallest building; the demo city's central tower, feature 184) and what lies "
                  "within 0.03 S of it drawn as a blueprint, fading to the photorealistic context 0.08 S "
                  "away, where S is the scene's size (half its horizontal diagonal; 1090 m on the demo "
                  "city: 33 m, 87 m).");
        s->setFocusTallestLandmark(true);
        osg::ref_ptr<M> focus = new M(M::FOCUS, 0.03, 0.08);
        focus->setScale(M::SCENE);
        addTwoLevels(*s, {focus}, "blueprint", "photorealistic", 0.0f, 1.0f);
        return s;
    }
    if (name == "landscape")
    {
        // Figure 9F: a landscape read as a map, each feature type in its cartographic device
        // (§3.2.3), detail near the camera.
        auto s = makeScenario(
            name,
            "Landscape map (paper 004 Figure 9F): photorealistic near the camera, fading smoothly into a "
            "map between 0.75 D and 1.1 D, where D is the camera's distance to the centre of the scene: "
            "terrain as relief (slope lines, shadowed hachures, form lines), water with waterlines, "
            "green spaces with vegetation signatures, streets as on a road map, buildings in the "
            "brewer-subtypes colours.");
        s->setColorScheme("brewer-subtypes");
        osg::ref_ptr<M> distance = new M(M::VIEW_DISTANCE, 0.75, 1.1);
        distance->setScale(M::VIEW);
        addDetailOverMap(*s, {distance}, BlendFunction(0.0f, 1.0f, 1.0f, 1.0f),
                         BlendFunction(0.0f, 0.0f, 0.0f, 1.0f), osg::Vec2f(0.0f, 1.0f));
        return s;
    }
    if (name == "navigation")
    {
        // §4.1, car navigation: the vertical view angle blends detailed and map-like views (the
        // background of a perspective view is map-like), the route keeps its detail, the map
        // shows each feature type in its cartographic device, and landmarks stay detailed and
        // turn to the viewer.
        auto s = makeScenario(
            name, "Car navigation (paper 004 §4.1): the vertical view angle (detailed below 25 degrees, "
                  "map-like above 60, weight 1), the view distance (detailed within 0.35 D, map-like "
                  "beyond 2 D, weight 2) and the route along the scene's streets (detailed "
                  "within 0.03 S of it, map-like 0.14 S away, weight 2) blend a detailed foreground and "
                  "route into a map-like background: streets as a road map, water "
                  "waterlined, green spaces with signatures, terrain as relief, buildings cartographic, in "
                  "the brewer-subtypes colours; the route is drawn on the ground as a 6 px blue line; "
                  "landmarks (static interest >= 0.8) stay photorealistic "
                  "and turn their best view to the viewer, the other buildings shrink and sink where they "
                  "are drawn as a map (§3.2.2).");
        s->setColorScheme("brewer-subtypes");
        osg::ref_ptr<RegionOfInterest> route = new RegionOfInterest(RegionOfInterest::POLYLINE, {}, 0.01);
        route->setName("route");
        route->setPlacement(RegionOfInterest::LONGEST_STREET);
        route->setSceneScale(true);
        route->setLineWidth(kRouteLineWidth);
        s->addRegion(route.get());
        osg::ref_ptr<M> region = new M(M::REGION, 0.03, 0.14, 1.0);
        region->setScale(M::SCENE);
        region->setWeight(2.0);
        osg::ref_ptr<M> distance = new M(M::VIEW_DISTANCE, 0.35, 2.0, 2.0);
        distance->setScale(M::VIEW);
        const std::vector<osg::ref_ptr<M>> metrics = {new M(M::VIEW_ANGLE, 25.0, 60.0, 1.0), distance,
                                                      region};
        addDetailOverMap(*s, metrics, BlendFunction(0.4f, 0.6f, 1.0f, 1.0f),
                         BlendFunction(0.0f, 0.0f, 0.4f, 0.6f), osg::Vec2f(0.0f, 0.8f));
        addLandmarksInDetail(*s);
        s->setLandmarkDeformation(mapDeformation().get());
        return s;
    }
    throw ScenarioError("unknown built-in scenario '" + name + "'");
}

std::vector<std::string> ScenarioLibrary::searchDirectories()
{
    std::vector<std::string> dirs;
    for (const std::string& d : osgDB::getDataFilePathList())
        dirs.push_back(d + "/scenarios");
    dirs.push_back(OSGLOA_SCENARIO_INSTALL_DIR);
    dirs.push_back(OSGLOA_SCENARIO_SOURCE_DIR);
    std::vector<std::string> existing;
    for (const std::string& d : dirs)
        if (!d.empty() && osgDB::fileType(d) == osgDB::DIRECTORY &&
            std::find(existing.begin(), existing.end(), d) == existing.end())
            existing.push_back(d);
    return existing;
}

std::string ScenarioLibrary::findFile(const std::string& name)
{
    if (name.empty() || name.find('/') != std::string::npos) return std::string();
    for (const std::string& d : searchDirectories())
        for (const char* ext : kExtensions)
        {
            const std::string path = d + "/" + name + "." + ext;
            if (osgDB::fileType(path) == osgDB::REGULAR_FILE) return path;
        }
    return std::string();
}

std::vector<std::string> ScenarioLibrary::availableNames()
{
    std::set<std::string> names;
    for (const std::string& n : builtinNames())
        names.insert(n);
    for (const std::string& d : searchDirectories())
        for (const std::string& f : osgDB::getDirectoryContents(d))
            if (isScenarioFile(f)) names.insert(osgDB::getNameLessExtension(f));
    return std::vector<std::string>(names.begin(), names.end());
}

bool ScenarioLibrary::isScenarioFile(const std::string& path)
{
    const std::string ext = osgDB::getLowerCaseFileExtension(path);
    return std::find(std::begin(kExtensions), std::end(kExtensions), ext) != std::end(kExtensions);
}

osg::ref_ptr<UsageScenario> ScenarioLibrary::load(const std::string& nameOrPath, std::string* origin)
{
    if (nameOrPath.empty()) throw ScenarioError("no scenario name or file given");
    if (osgDB::fileType(nameOrPath) == osgDB::REGULAR_FILE || isScenarioFile(nameOrPath) ||
        nameOrPath.find('/') != std::string::npos)
    {
        if (origin) *origin = nameOrPath;
        return readFile(nameOrPath);
    }
    const std::string file = findFile(nameOrPath);
    if (!file.empty())
    {
        if (origin) *origin = file;
        return readFile(file);
    }
    const std::vector<std::string> builtins = builtinNames();
    if (std::find(builtins.begin(), builtins.end(), nameOrPath) != builtins.end())
    {
        if (origin) *origin = "built-in";
        return createBuiltin(nameOrPath);
    }
    std::string known;
    for (const std::string& n : availableNames())
        known += (known.empty() ? "" : ", ") + n;
    throw ScenarioError("no scenario named '" + nameOrPath + "' (known: " + known + ")");
}

osg::ref_ptr<UsageScenario> ScenarioLibrary::readFile(const std::string& path)
{
    if (!isScenarioFile(path))
        throw ScenarioError("'" + path + "' is not a scenario file (expected .osgt, .osgb or .osgx)");
    if (osgDB::fileType(path) != osgDB::REGULAR_FILE)
        throw ScenarioError("scenario file '" + path + "' not found");
    std::ifstream in(path.c_str(), std::ios::binary);
    std::ostringstream data;
    data << in.rdbuf();
    if (!in) throw ScenarioError("cannot read scenario file '" + path + "'");
    osg::ref_ptr<UsageScenario> s = readData(data.str(), path);
    if (s->getName().empty()) s->setName(osgDB::getNameLessExtension(osgDB::getSimpleFileName(path)));
    return s;
}

std::string ScenarioLibrary::checkAsciiStructure(const std::string& text)
{
    return ModelValidation::checkOsgtText(text);
}

namespace
{
// The scenario an object read from a scenario file holds: itself, or a LoANode's.
osg::ref_ptr<UsageScenario> scenarioOf(osgDB::ReaderWriter::ReadResult& rr, const std::string& label)
{
    if (!rr.success() || !rr.getObject())
        throw ScenarioError("cannot read scenario file '" + label + "'" +
                            (rr.message().empty() ? std::string() : ": " + rr.message()));
    osg::ref_ptr<UsageScenario> s = dynamic_cast<UsageScenario*>(rr.getObject());
    if (LoANode* node = dynamic_cast<LoANode*>(rr.getObject()))
    {
        s = node->getScenario();
        if (!s) throw ScenarioError("'" + label + "' holds an osgLoA::LoANode without a scenario");
    }
    if (!s)
        throw ScenarioError("'" + label + "' holds a " + rr.getObject()->className() +
                            ", not an osgLoA::UsageScenario");
    return s;
}

// osgdb_osg's reader for all three scenario file formats, with our serializer plugin loaded.
osgDB::ReaderWriter& scenarioReaderWriter()
{
    osgDB::ReaderWriter* rw = osgDB::Registry::instance()->getReaderWriterForExtension("osgt");
    if (!rw) throw ScenarioError("no osgDB reader for scenario files (is the osg2 plugin installed?)");
    osgDB::Registry::instance()->getObjectWrapperManager()->findWrapper("osgLoA::UsageScenario");
    return *rw;
}

const char* const kParserName = "loa-scenario-parse";
const char* const kParserVariable = "OSGLOA_SCENARIO_PARSER";
const int kParseSeconds = 5;

bool isExecutableFile(const std::string& path)
{
    struct stat st;
    return stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && access(path.c_str(), X_OK) == 0;
}

// A function of libosgLoA itself (internal linkage, so its address lies in the library).
void libraryAnchor() {}

// The directory of the libosgLoA this code runs in (symbolic links resolved), or "".
std::string libraryDirectory()
{
    Dl_info info;
    if (dladdr(reinterpret_cast<void*>(&libraryAnchor), &info) == 0 || !info.dli_fname) return std::string();
    std::string path = info.dli_fname;
    if (char* real = realpath(info.dli_fname, nullptr))
    {
        path = real;
        std::free(real);
    }
    return osgDB::getFilePath(path);
}

// The helper loa-scenario-parse: $OSGLOA_SCENARIO_PARSER, else next to libosgLoA
// (<libdir>/../bin as in the build tree and a usual install, <libdir>/<relative install bindir>,
// <libdir>), else the build tree's bin/. Throws ScenarioError when there is none.
std::string findParser(const std::string& label)
{
    const std::string prefix = "cannot read text scenario file '" + label + "': helper " + kParserName;
    if (const char* env = std::getenv(kParserVariable))
        if (*env)
        {
            if (!isExecutableFile(env))
                throw ScenarioError(prefix + " not found at '" + env + "' (" + kParserVariable + ")");
            return env;
        }
    std::vector<std::string> candidates;
    const std::string libDir = libraryDirectory();
    if (!libDir.empty())
    {
        candidates.push_back(libDir + "/../bin/" + kParserName);
        const std::string installed = std::string(OSGLOA_LIBDIR_TO_BINDIR);
        if (!installed.empty() && installed != "../bin")
            candidates.push_back(libDir + "/" + installed + "/" + kParserName);
        candidates.push_back(libDir + "/" + kParserName);
    }
    if (*OSGLOA_BUILD_BINDIR) candidates.push_back(std::string(OSGLOA_BUILD_BINDIR) + "/" + kParserName);
    std::string looked;
    for (const std::string& c : candidates)
    {
        if (isExecutableFile(c)) return c;
        looked += (looked.empty() ? "" : ", ") + c;
    }
    throw ScenarioError(prefix + " not found (set " + kParserVariable + "); looked for " + looked);
}

// A file descriptor closed when it goes out of scope.
struct Descriptor
{
    int fd = -1;
    Descriptor() = default;
    Descriptor(const Descriptor&) = delete;
    Descriptor& operator=(const Descriptor&) = delete;
    ~Descriptor() { reset(); }
    void reset()
    {
        if (fd >= 0) close(fd);
        fd = -1;
    }
};

// The helper's environment: ours, with osgDB's library path as this process has it, so that
// the helper loads the same plugins (the serializer plugin above all) even where this process
// set its path in code rather than with OSG_LIBRARY_PATH.
std::vector<std::string> parserEnvironment()
{
    std::vector<std::string> env;
    for (char** e = environ; e && *e; ++e)
        if (std::strncmp(*e, "OSG_LIBRARY_PATH=", 17) != 0) env.push_back(*e);
    std::string path;
    for (const std::string& dir : osgDB::Registry::instance()->getLibraryFilePathList())
        path += (path.empty() ? "" : ":") + dir;
    env.push_back("OSG_LIBRARY_PATH=" + path);
    return env;
}

// OSG 3.6.5's text readers (ASCII and XML) can loop forever on malformed input (at the end of
// the stream, or once a number fails to parse and the stream stays failed), and could crash. So
// a text file is parsed by the helper program loa-scenario-parse (detail::parseTextScenario)
// with a deadline; it sends the scenario back in OSG's binary format (which our own writer
// produced, so it reads safely) or the reader's message. A spawned program, not a fork()ed
// copy of this process: a fork of a multi-threaded process (Mesa's llvmpipe threads, OSG's
// pager threads) can deadlock on a lock another thread held when it forked.
osg::ref_ptr<UsageScenario> readTextOutOfProcess(osgDB::ReaderWriter& rw, const std::string& data,
                                                 const std::string& label)
{
    const std::string parser = findParser(label);
    const std::string cannot = "cannot read scenario file '" + label + "': ";
    // The text goes in through a socket (send() with MSG_NOSIGNAL: a helper that has gone gives
    // EPIPE, not a SIGPIPE for this process), the reply comes out through a pipe. Both are
    // close-on-exec here, so that programs other threads start do not inherit them.
    Descriptor input, childInput, output, childOutput;
    int fds[2];
    if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) != 0)
        throw ScenarioError(cannot + "socketpair() failed: " + std::strerror(errno));
    input.fd = fds[0];
    childInput.fd = fds[1];
    if (pipe2(fds, O_CLOEXEC) != 0) throw ScenarioError(cannot + "pipe() failed: " + std::strerror(errno));
    output.fd = fds[0];
    childOutput.fd = fds[1];

    // stdin and stdout are the channels; the reader's complaints go to /dev/null (they come
    // back in the reply, and a looping reader prints endlessly).
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, childInput.fd, STDIN_FILENO);
    posix_spawn_file_actions_adddup2(&actions, childOutput.fd, STDOUT_FILENO);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t none;
    sigemptyset(&none);
    posix_spawnattr_setsigmask(&attributes, &none);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK);
    const std::vector<std::string> env = parserEnvironment();
    std::vector<char*> envp;
    for (const std::string& e : env)
        envp.push_back(const_cast<char*>(e.c_str()));
    envp.push_back(nullptr);
    const std::string labelOption = "--label";
    char* argv[] = {const_cast<char*>(parser.c_str()), const_cast<char*>(labelOption.c_str()),
                    const_cast<char*>(label.c_str()), nullptr};
    pid_t pid = -1;
    const int spawned = posix_spawn(&pid, parser.c_str(), &actions, &attributes, argv, envp.data());
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
    if (spawned != 0)
        throw ScenarioError(cannot + "cannot start the helper '" + parser + "': " + std::strerror(spawned));
    childInput.reset();
    childOutput.reset();

    // Send the text and read the reply at the same time: the text may not fit the socket's
    // buffer, and a helper that loops may never read all of it.
    std::string reply;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(kParseSeconds);
    const auto msLeft = [&deadline]
    {
        return std::chrono::duration_cast<std::chrono::milliseconds>(deadline -
                                                                     std::chrono::steady_clock::now())
            .count();
    };
    bool timedOut = false;
    std::size_t sent = 0;
    if (data.empty()) input.reset();
    char buffer[65536];
    for (;;)
    {
        const auto left = msLeft();
        if (left <= 0)
        {
            timedOut = true;
            break;
        }
        pollfd p[2] = {{output.fd, POLLIN, 0}, {input.fd, POLLOUT, 0}};
        const int r = poll(p, 2, int(left));
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0)
        {
            timedOut = r == 0;
            break;
        }
        if (input.fd >= 0 && p[1].revents != 0)
        {
            const ssize_t n =
                send(input.fd, data.data() + sent, data.size() - sent, MSG_NOSIGNAL | MSG_DONTWAIT);
            if (n > 0) sent += std::size_t(n);
            if ((n < 0 && errno != EINTR && errno != EAGAIN && errno != EWOULDBLOCK) || sent == data.size())
                input.reset(); // all sent (the helper sees the end of its input), or it stopped reading
        }
        if (p[0].revents != 0)
        {
            const ssize_t n = read(output.fd, buffer, sizeof(buffer));
            if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
            if (n <= 0) break;
            reply.append(buffer, std::size_t(n));
        }
    }
    input.reset();
    output.reset();
    // The helper has sent its reply (or died); it gets until the deadline to exit.
    int status = 0;
    bool exited = false;
    while (!timedOut && !exited && msLeft() > 0)
    {
        const pid_t reaped = waitpid(pid, &status, WNOHANG);
        if (reaped > 0 || (reaped < 0 && errno != EINTR))
            exited = true;
        else if (reaped == 0)
            poll(nullptr, 0, 5);
    }
    if (!exited)
    {
        kill(pid, SIGKILL);
        while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
        {
        }
        if (reply.empty()) timedOut = true; // a complete reply still counts
    }
    if (timedOut)
        throw ScenarioError("malformed scenario file '" + label +
                            "': OpenSceneGraph's text reader did not finish within " +
                            std::to_string(kParseSeconds) + " s");
    if (reply.empty())
    {
        if (WIFEXITED(status))
            throw ScenarioError(cannot + "the helper '" + parser + "' exited with status " +
                                std::to_string(WEXITSTATUS(status)) + " without a reply");
        throw ScenarioError("malformed scenario file '" + label +
                            "': OpenSceneGraph's text reader crashed on it");
    }
    if (reply[0] == 'E') throw ScenarioError(reply.substr(1));
    std::istringstream in(reply.substr(1));
    osgDB::ReaderWriter::ReadResult rr = rw.readObject(in);
    return scenarioOf(rr, label);
}
// OSG's ASCII and binary formats, in this process, read by BoundedObjectReader: OSG's own
// loops on a failed stream (a read past the end, a value that does not parse; they used to need
// a child process with a deadline) and sizes that lie (a 2 GB string in a bit-flipped .osgb)
// end at the end of the data with a message. (XML keeps the helper process.)
osg::ref_ptr<UsageScenario> readBounded(const std::string& data, const std::string& label)
{
    scenarioReaderWriter(); // the reader and our wrappers loaded, or a clear error
    osg::ref_ptr<osg::Object> object;
    try
    {
        object = BoundedObjectReader::readObject(data, nullptr);
    }
    catch (const MalformedFileError& e)
    {
        throw ScenarioError("malformed scenario file '" + label + "': " + e.what());
    }
    osgDB::ReaderWriter::ReadResult rr(object.get());
    return scenarioOf(rr, label);
}
} // namespace

namespace detail
{
std::string parseTextScenario(const std::string& text, const std::string& label)
{
    try
    {
        osgDB::ReaderWriter& rw = scenarioReaderWriter();
        std::istringstream in(text);
        osgDB::ReaderWriter::ReadResult rr = rw.readObject(in);
        osg::ref_ptr<UsageScenario> s = scenarioOf(rr, label);
        std::ostringstream out;
        osg::ref_ptr<osgDB::Options> binary = new osgDB::Options;
        binary->setPluginStringData("fileType", "Binary");
        if (!rw.writeObject(*s, out, binary.get()).success())
            return "Ecannot read scenario file '" + label + "': cannot convert it to the binary format";
        return "S" + out.str();
    }
    catch (const std::exception& e)
    {
        return std::string("E") + e.what();
    }
}
} // namespace detail

osg::ref_ptr<UsageScenario> ScenarioLibrary::readData(const std::string& data, const std::string& label)
{
    // osgdb_osg's three formats: text whose first word is "#Ascii", text whose first line starts
    // with "<?xml", and binary with its magic number.
    const BoundedObjectReader::Format format = BoundedObjectReader::formatOf(data);
    if (format == BoundedObjectReader::Format::Ascii)
    {
        const std::string problem = checkAsciiStructure(data);
        if (!problem.empty()) throw ScenarioError("malformed scenario file '" + label + "': " + problem);
    }
    osgDB::ReaderWriter& rw = scenarioReaderWriter();
    if (format == BoundedObjectReader::Format::Xml) return readTextOutOfProcess(rw, data, label);
    return readBounded(data, label);
}

void ScenarioLibrary::writeFile(const UsageScenario& scenario, const std::string& path)
{
    if (!isScenarioFile(path))
        throw ScenarioError("'" + path + "' is not a scenario file name (use .osgt, .osgb or .osgx)");
    try
    {
        // The scenario travels in an empty LoA node: a node file, which the stock osgconv can
        // convert (OSG 3.6.5's osgconv crashes on files that hold no node).
        osg::ref_ptr<LoANode> node = new LoANode;
        node->setName(scenario.getName());
        node->setScenario(const_cast<UsageScenario*>(&scenario));
        AtomicFile::write(path, [&](const std::string& tmp) { return osgDB::writeNodeFile(*node, tmp); });
    }
    catch (const std::exception& e)
    {
        throw ScenarioError("cannot write scenario file '" + path + "': " + e.what());
    }
}

} // namespace osgLoA
