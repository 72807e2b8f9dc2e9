// libFuzzer target: arbitrary bytes as a model file in OSG's native formats (.osgt, .osgb), read
// the way every tool and the .loa plugin read models (issue 22 items 2, 3, 5): by
// BoundedObjectReader (the text's structure checked first), then checked and repaired by
// ModelValidation (a cycle or a graph too deep is refused). Then what the tools do with a model
// before drawing it: the bound (must be finite), classification with the default rules, and
// the image paths of the texture tools: each texture image hashed for the filter cache
// (FilterCache::imageHash, which read past a lying image's buffer once) and its colour table
// built from the scene's texel weights (TextureHistogram::colorTable, likewise). Inline images
// are the input's; image files it names are looked up in an empty folder.
//
// Build and run: scripts/fuzz (FUZZ_TARGETS=ModelFuzzer). Seed corpus: tests/fuzz/corpus/model.
#include <osgLoA/filtering/FilterCache>
#include <osgLoA/palette/TextureHistogram>
#include <osgLoA/semantics/ClassificationRuleSet>
#include <osgLoA/semantics/FeatureClassifier>
#include <osgLoA/util/BoundedObjectReader>
#include <osgLoA/util/ModelValidation>
#include <osgLoA/util/StateSetVisitor>

#include <osg/Notify>
#include <osgDB/Options>
#include <osgDB/Registry>

#include "FuzzSupport.h"

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <sys/stat.h>

namespace
{
const char* const kTarget = "ModelFuzzer";
}

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    osg::setNotifyLevel(osg::FATAL);
    if (!osgDB::Registry::instance()->getReaderWriterForExtension("osgt"))
        fuzz::fail(kTarget, "no osgt reader (osgdb_osg plugin missing)");
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    static const osg::ref_ptr<osgDB::Options> options = []
    {
        const std::string empty = fuzz::scratch("model-images");
        ::mkdir(empty.c_str(), 0700);
        osg::ref_ptr<osgDB::Options> o = new osgDB::Options;
        o->setDatabasePath(empty);
        return o;
    }();
    static const osg::ref_ptr<osgLoA::ClassificationRuleSet> rules =
        osgLoA::ClassificationRuleSet::assemble({}, false, false);

    osg::ref_ptr<osg::Node> node;
    try
    {
        node = osgLoA::BoundedObjectReader::readCheckedNode(
            std::string(reinterpret_cast<const char*>(data), size), options.get());
    }
    catch (const osgLoA::MalformedFileError& e)
    {
        if (std::string(e.what()).empty()) fuzz::fail(kTarget, "an error without a message");
        return 0;
    }
    if (!node) fuzz::fail(kTarget, "readNode returned no node and no error");
    try
    {
        osgLoA::ModelValidation::validate(*node, "fuzz.osgt");
    }
    catch (const osgLoA::ModelStructureError&)
    {
        return 0; // a cycle or a graph too deep: refused, as the tools refuse it
    }
    fuzz::requireFiniteBound(kTarget, *node);

    osgLoA::FeatureClassifier(rules.get()).classify(*node);

    for (osg::Image* image : osgLoA::StateSetVisitor::textureImages(*node))
    {
        if (!image->data()) continue;
        try
        {
            osgLoA::FilterCache::imageHash(*image);
        }
        catch (const std::invalid_argument&)
        {
        }
    }
    std::map<const osg::Image*, std::vector<double>> weights;
    try
    {
        weights =
            osgLoA::TextureHistogram::sceneWeights(*node); // documented: texture coordinates too far apart
    }
    catch (const std::invalid_argument&)
    {
        return 0;
    }
    for (const auto& entry : weights)
    {
        try
        {
            osgLoA::TextureHistogram::colorTable(*entry.first, entry.second);
        }
        catch (const std::invalid_argument&)
        {
        }
    }
    return 0;
}
