// osgdb_cityjson: reads CityJSON 1.0, 1.1 and 2.0 (docs/cityjson.md):
//   osgviewer city.city.json
//   osgviewer city.cityjson -O "lod=2.2 theme=summer recenter=0"
// ".json" files are taken only when their top-level "type" is "CityJSON"; any other JSON goes
// back to osgDB as FILE_NOT_HANDLED so that other plugins may try it.
#include "CityJsonReader.h"

#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/Registry>
#include <osgDB/fstream>

#include <sstream>

namespace
{
class ReaderWriterCityJson : public osgDB::ReaderWriter
{
public:
    ReaderWriterCityJson()
    {
        supportsExtension("cityjson", "CityJSON 1.0 / 1.1 / 2.0 city model");
        supportsExtension("json", "CityJSON (.city.json, or any .json whose \"type\" is \"CityJSON\")");
        supportsOption("lod=X",
                       "per object, the geometry of LoD X (e.g. 2.2); default: each object's highest");
        supportsOption("theme=NAME",
                       "appearance theme; default: the file's default theme, else the first found");
        supportsOption("recenter=0",
                       "keep world coordinates (default 1: re-centre on the bounding box centre)");
    }
    const char* className() const override { return "osgLoA CityJSON reader"; }

    ReadResult readObject(const std::string& fileName, const Options* options) const override
    {
        return readNode(fileName, options);
    }
    ReadResult readObject(std::istream& in, const Options* options) const override
    {
        return readNode(in, options);
    }

    ReadResult readNode(const std::string& fileName, const Options* options) const override
    {
        const std::string ext = osgDB::getLowerCaseFileExtension(fileName);
        if (!acceptsExtension(ext)) return ReadResult::FILE_NOT_HANDLED;
        // ".city.json" and ".cityjson" claim to be CityJSON; a plain ".json" may be anything.
        const std::string lowerName = osgDB::convertToLowerCase(fileName);
        const bool claimed =
            ext == "cityjson" ||
            (lowerName.size() >= 10 && lowerName.compare(lowerName.size() - 10, 10, ".city.json") == 0);
        const std::string path = osgDB::findDataFile(fileName, options);
        if (path.empty()) return ReadResult::FILE_NOT_FOUND;
        osgDB::ifstream in(path.c_str(), std::ios::in | std::ios::binary);
        if (!in) return ReadResult("cityjson: " + path + ": cannot open the file");

        nlohmann::ordered_json doc;
        try
        {
            doc = nlohmann::ordered_json::parse(in);
        }
        catch (const nlohmann::json::exception& e)
        {
            if (!claimed && !mentionsCityJson(path)) return ReadResult::FILE_NOT_HANDLED;
            return ReadResult("cityjson: " + path +
                              ": not valid JSON (truncated or malformed?): " + e.what());
        }
        if (!claimed && !(doc.is_object() && doc.contains("type") && doc["type"] == "CityJSON"))
            return ReadResult::FILE_NOT_HANDLED;

        osgDB::FilePathList dirs;
        dirs.push_back(osgDB::getFilePath(path).empty() ? std::string(".") : osgDB::getFilePath(path));
        if (options)
            dirs.insert(dirs.end(), options->getDatabasePathList().begin(),
                        options->getDatabasePathList().end());
        osg::ref_ptr<Options> local =
            options ? static_cast<Options*>(options->clone(osg::CopyOp::SHALLOW_COPY)) : new Options;
        local->getDatabasePathList().push_front(dirs.front());
        return build(doc, path, options, dirs, local.get());
    }

    ReadResult readNode(std::istream& in, const Options* options) const override
    {
        nlohmann::ordered_json doc;
        try
        {
            doc = nlohmann::ordered_json::parse(in);
        }
        catch (const nlohmann::json::exception& e)
        {
            return ReadResult(std::string("cityjson: <stream>: not valid JSON (truncated or malformed?): ") +
                              e.what());
        }
        osgDB::FilePathList dirs;
        if (options)
            dirs.assign(options->getDatabasePathList().begin(), options->getDatabasePathList().end());
        return build(doc, "<stream>", options, dirs, options);
    }

private:
    static ReadResult build(const nlohmann::ordered_json& doc, const std::string& source,
                            const Options* options, const osgDB::FilePathList& dirs,
                            const Options* imageOptions)
    {
        try
        {
            loacityjson::Settings settings;
            if (options) settings.parse(options->getOptionString());
            osg::ref_ptr<osg::Group> root =
                loacityjson::buildScene(doc, source, settings, dirs, imageOptions);
            root->setName(osgDB::getSimpleFileName(source));
            return root.get();
        }
        catch (const std::exception& e)
        {
            return ReadResult(std::string("cityjson: ") + e.what());
        }
    }

    /** Whether a file that failed to parse looks like (truncated) CityJSON. */
    static bool mentionsCityJson(const std::string& path)
    {
        osgDB::ifstream in(path.c_str(), std::ios::in | std::ios::binary);
        std::string head(65536, '\0');
        in.read(&head[0], static_cast<std::streamsize>(head.size()));
        head.resize(static_cast<std::size_t>(in.gcount()));
        return head.find("\"CityJSON\"") != std::string::npos;
    }
};
} // namespace

REGISTER_OSGPLUGIN(cityjson, ReaderWriterCityJson)
