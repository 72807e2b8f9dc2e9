// osgdb_loacity: a pseudo-loader that generates the demo city, so the stock tools open it:
//   osgviewer demo.loacity
//   osgviewer demo.loacity -O "seed=7 blocksX=6 blocksY=4"
//   osgconv demo.loacity city.osgb
// The file name before ".loacity" is ignored unless it is an existing file, whose text is then
// read as parameters (key=value pairs, '#' starts a comment); the option string overrides.
#include <osgLoA/city/CityGenerator>

#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/Registry>
#include <osgDB/fstream>

#include <sstream>

namespace
{
class ReaderWriterLoaCity : public osgDB::ReaderWriter
{
public:
    ReaderWriterLoaCity()
    {
        supportsExtension("loacity", "osgLoA demo city (procedural; parameters as key=value)");
        supportsOption("seed=N", "random seed");
        supportsOption("blocksX=N / blocksY=N", "city size in blocks");
        supportsOption("blockSize=M", "side of a block in metres");
        supportsOption("minorRoadWidth=M / majorRoadWidth=M / majorRoadEvery=N", "roads");
        supportsOption("terrainResolution=N / terrainMargin=M / reliefAmplitude=M", "terrain");
        supportsOption("river=true|false / riverWidth=M", "the river");
        supportsOption("parkFraction=F / forestFraction=F", "shares of free blocks for parks and forests");
        supportsOption("parkTreesPerHectare=N / forestTreesPerHectare=N", "tree densities");
        supportsOption("landmarks=N / minFloors=N / maxFloors=N", "landmarks and building heights "
                                                                  "(docs/demo-city.md)");
    }
    const char* className() const override { return "osgLoA demo city pseudo-loader"; }

    // osgconv and others ask for an object; the city is a node.
    ReadResult readObject(const std::string& fileName, const Options* options) const override
    {
        return readNode(fileName, options);
    }

    ReadResult readNode(const std::string& fileName, const Options* options) const override
    {
        if (!acceptsExtension(osgDB::getLowerCaseFileExtension(fileName)))
            return ReadResult::FILE_NOT_HANDLED;
        osgLoA::CityParameters params;
        try
        {
            if (osgDB::fileExists(fileName) && osgDB::fileType(fileName) == osgDB::REGULAR_FILE)
            {
                osgDB::ifstream in(fileName.c_str());
                std::ostringstream text;
                for (std::string line; std::getline(in, line);)
                    text << line.substr(0, line.find('#')) << " ";
                params.parse(text.str());
            }
            if (options) params.parse(options->getOptionString());
            params.validate();
            return osgLoA::CityGenerator(params).generate().get();
        }
        catch (const std::exception& e)
        {
            return ReadResult(std::string("loacity: ") + e.what());
        }
    }
};
} // namespace

REGISTER_OSGPLUGIN(loacity, ReaderWriterLoaCity)
