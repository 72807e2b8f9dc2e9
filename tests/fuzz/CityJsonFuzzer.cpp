// libFuzzer target: arbitrary bytes as a CityJSON document, in process (issue 22 item 5): parsed
// within the default InputLimits (loacityjson::parseJson) and built into a scene
// (loacityjson::buildScene), as osgdb_cityjson does; the scene is then validated
// (osgLoA::ModelValidation) and its bound must be finite. Every failure must be an exception the
// reader turns into a message; a crash, a hang, a leak, undefined behaviour or an infinite bound
// is a finding. Seed corpus: tests/fuzz/corpus/cityjson (and ../shared/data/cityjson).
//
// Build and run: scripts/fuzz (FUZZ_TARGETS=CityJsonFuzzer).
#include "../../plugins/cityjson/CityJsonReader.h"

#include <osgLoA/util/ModelValidation>

#include <osg/Notify>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    osg::setNotifyLevel(osg::FATAL);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
    loacityjson::Settings settings;
    osg::ref_ptr<osg::Group> scene;
    try
    {
        const loacityjson::Json doc = loacityjson::parseJson(in, "<fuzz>", settings.limits);
        scene = loacityjson::buildScene(doc, "<fuzz>", settings, osgDB::FilePathList(), nullptr);
    }
    catch (const std::exception&)
    {
        return 0; // a reported error: what the reader must do with bad input
    }
    if (!scene.valid()) std::abort();
    osgLoA::ModelValidation::validate(*scene, "<fuzz>");
    const osg::BoundingSphere bs = scene->getBound();
    if (bs.valid() && !(std::isfinite(bs.radius()) && std::isfinite(bs.center().length()))) std::abort();
    return 0;
}
