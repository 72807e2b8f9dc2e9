// osgdb_cityjson: reads CityJSON 1.0, 1.1 and 2.0 (docs/cityjson.md):
//   osgviewer city.city.json
//   osgviewer city.cityjson -O "lod=2.2 theme=summer recenter=0"
// ".json" files are taken only when their top-level "type" is "CityJSON"; any other JSON goes
// back to osgDB as FILE_NOT_HANDLED so that other plugins may try it.
#include "CityJsonReader.h"

#include <sys/stat.h>

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
        osgLoA::InputLimits::declareOptions(*this);
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
        loacityjson::Settings settings;
        try
        {
            if (options) settings.parse(options->getOptionString());
        }
        catch (const std::exception& e)
        {
            return ReadResult(std::string("cityjson: ") + path + ": " + e.what());
        }
        const std::string problem = checkRegularFile(path, settings.limits);
        if (!problem.empty()) return ReadResult("cityjson: " + problem);
        osgDB::ifstream in(path.c_str(), std::ios::in | std::ios::binary);
        if (!in) return ReadResult("cityjson: " + path + ": cannot open the file");

        loacityjson::Json doc;
        try
        {
            doc = loacityjson::parseJson(in, path, settings.limits);
        }
        catch (const osgLoA::InputLimitError& e)
        {
            return ReadResult(std::string("cityjson: ") + e.what());
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
        loacityjson::Json doc;
        try
        {
            loacityjson::Settings settings;
            if (options) settings.parse(options->getOptionString());
            doc = loacityjson::parseJson(in, "<stream>", settings.limits);
        }
        catch (const nlohmann::json::exception& e)
        {
            return ReadResult(std::string("cityjson: <stream>: not valid JSON (truncated or malformed?): ") +
                              e.what());
        }
        catch (const std::exception& e)
        {
            return ReadResult(std::string("cityjson: ") + e.what());
        }
        osgDB::FilePathList dirs;
        if (options)
            dirs.assign(options->getDatabasePathList().begin(), options->getDatabasePathList().end());
        return build(doc, "<stream>", options, dirs, options);
    }

private:
    static ReadResult build(const loacityjson::Json& doc, const std::string& source, const Options* options,
                            const osgDB::FilePathList& dirs, const Options* imageOptions)
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

    /** "" when path is a regular file within limits.maxFileBytes, else the problem (a FIFO or a
     *  device such as /dev/zero would be read forever). */
    static std::string checkRegularFile(const std::string& path, const osgLoA::InputLimits& limits)
    {
        struct stat st;
        if (::stat(path.c_str(), &st) != 0) return path + ": cannot open the file";
        if (!S_ISREG(st.st_mode)) return path + ": not a regular file (a device, FIFO or folder)";
        if (static_cast<std::uint64_t>(st.st_size) > limits.maxFileBytes)
            return osgLoA::InputLimits::exceeded(path, std::to_string(st.st_size) + " bytes", "max-file",
                                                 limits.maxFileBytes);
        return std::string();
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
