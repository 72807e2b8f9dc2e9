// The CityJSON 1.0 / 1.1 / 2.0 reader behind osgdb_cityjson (docs/cityjson.md): a parsed
// document in, an osg::Group of feature-carrying object Groups out.
#ifndef OSGLOA_PLUGINS_CITYJSON_CITYJSONREADER_H
#define OSGLOA_PLUGINS_CITYJSON_CITYJSONREADER_H 1

#include <osg/Group>
#include <osgDB/Options>

#include <nlohmann/json.hpp>

#include <stdexcept>
#include <string>

namespace loacityjson
{

/** A problem that makes the file unreadable; the message names it (object id, index). */
class Error : public std::runtime_error
{
public:
    explicit Error(const std::string& what) : std::runtime_error(what) {}
};

/** What the option string asks for ("recenter=0 lod=2.2 theme=summer"). */
struct Settings
{
    bool recenter = true;
    std::string lod;   ///< empty: each object's highest LoD
    std::string theme; ///< empty: the file's default theme, else the first one found
    /** Parses the option string; throws Error for a malformed value. */
    void parse(const std::string& optionString);
};

/** Builds the scene of a parsed CityJSON document. `sourceName` names the file in messages
 *  (the stream reader passes "<stream>"); `textureDirs` are searched, in order, for texture
 *  images before osgDB's data path. Throws Error. */
osg::ref_ptr<osg::Group> buildScene(const nlohmann::ordered_json& doc, const std::string& sourceName,
                                    const Settings& settings, const osgDB::FilePathList& textureDirs,
                                    const osgDB::Options* options);

} // namespace loacityjson

#endif
