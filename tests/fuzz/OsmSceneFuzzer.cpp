// libFuzzer target: the OpenStreetMap importer's own code, fed OSM objects decoded straight from
// the input (the file reader, which OsmFuzzer goes through, left out): tag parsing and classification
// (OsmTags), footprints, ribbons, trees, ground and their clamps (OsmScene::buildScene), at thousands of
// inputs a second (issue 22 item 5). The scene is validated (ModelValidation) and its bound must be finite.
//
// Input: text lines. "node", "way" or "area" starts an object of that geometry; in an area,
// "ring" starts a hole and "poly" another polygon; a line with '=' adds the tag key=value (the
// text after the first '=' is the value); any other line is numbers, lon lat pairs (strtod: "nan",
// "inf" and "1e308" included) appended to the current line or ring.
//
// Build and run: scripts/fuzz (FUZZ_TARGETS=OsmSceneFuzzer). Seed corpus: tests/fuzz/corpus/osmscene.
#include <osgLoA/util/ModelValidation>

#include <osg/Notify>

#include "../../plugins/osm/OsmScene.h"
#include "FuzzSupport.h"

#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
const char* const kTarget = "OsmSceneFuzzer";
constexpr std::size_t kMaxObjects = 4096;

std::vector<osmimport::OsmObject> decode(const std::string& text)
{
    using osmimport::OsmObject;
    std::vector<OsmObject> objects;
    std::istringstream lines(text);
    std::string line;
    while (std::getline(lines, line) && objects.size() <= kMaxObjects)
    {
        const std::string word = line.substr(0, line.find(' '));
        if (word == "node" || word == "way" || word == "area")
        {
            OsmObject o;
            o.geometry = word == "node"  ? OsmObject::Point
                         : word == "way" ? OsmObject::Line
                                         : OsmObject::Area;
            o.sourceId = word + "/" + std::to_string(objects.size() + 1);
            if (o.geometry == OsmObject::Area) o.polygons.emplace_back(1);
            objects.push_back(o);
            continue;
        }
        if (objects.empty()) continue;
        OsmObject& o = objects.back();
        if (word == "ring" && o.geometry == OsmObject::Area)
            o.polygons.back().emplace_back();
        else if (word == "poly" && o.geometry == OsmObject::Area)
            o.polygons.emplace_back(1);
        else if (line.find('=') != std::string::npos)
            o.tags.emplace(line.substr(0, line.find('=')), line.substr(line.find('=') + 1));
        else
        {
            osmimport::Ring& ring = o.geometry == OsmObject::Area ? o.polygons.back().back() : o.line;
            const char* p = line.c_str();
            char* end = nullptr;
            for (;;)
            {
                const double lon = std::strtod(p, &end);
                if (end == p) break;
                p = end;
                const double lat = std::strtod(p, &end);
                if (end == p) break;
                p = end;
                ring.emplace_back(lon, lat);
            }
        }
    }
    return objects;
}
} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    osg::setNotifyLevel(osg::FATAL);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    std::vector<osmimport::OsmObject> objects =
        decode(std::string(reinterpret_cast<const char*>(data), size));
    osmimport::ImportOptions options;
    // The ground grid at 100 km cells: its work is by design (at most 512 x 512 cells, about
    // 40 ms under ASan, which fuzzed coordinates spread over the globe always reached); its
    // code still runs on every input, on a few cells.
    options.terrainCell = 100000.0;
    osmimport::ImportReport report;
    osg::ref_ptr<osg::Group> scene;
    try
    {
        scene = osmimport::buildScene(objects, options, report);
    }
    catch (const std::runtime_error& e)
    {
        if (std::string(e.what()).empty()) fuzz::fail(kTarget, "an error without a message");
        return 0;
    }
    if (!scene) fuzz::fail(kTarget, "buildScene returned no scene and no error");
    osgLoA::ModelValidation::validate(*scene, "fuzz.osm");
    fuzz::requireFiniteBound(kTarget, *scene);
    return 0;
}
